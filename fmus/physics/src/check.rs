//! Checks of configuration values: finite, and positive or non-negative, each named in the
//! message of its failure.

/// Err unless `value` is finite and > 0, the message naming it `what` with its `unit`.
pub(crate) fn check_positive(what: &str, value: f64, unit: &str) -> Result<(), String> {
    if value > 0.0 && value.is_finite() {
        Ok(())
    } else {
        Err(format!("{what} must be a finite value > 0 {unit}, got {value}"))
    }
}

/// Checks that each named value is finite and ≥ 0 (or > 0 where `strict`).
pub(crate) fn check_values(owner: &str, values: &[(&str, f64, bool)]) -> Result<(), String> {
    for &(name, value, strict) in values {
        let ok = value.is_finite() && if strict { value > 0.0 } else { value >= 0.0 };
        if !ok {
            let bound = if strict { "> 0" } else { "≥ 0" };
            return Err(format!("{owner} {name} must be a finite value {bound}, got {value}"));
        }
    }
    Ok(())
}

/// [`check_values`] of fields of `$owner`, each under its own name, in the order given:
/// `check_fields!("cylinder", self; bore > 0, viscous >= 0)` checks that `self.bore` is finite
/// and > 0 and `self.viscous` finite and ≥ 0.
macro_rules! check_fields {
    ($what:expr, $owner:expr; $($field:ident $bound:tt 0),+ $(,)?) => {
        $crate::check::check_values(
            $what,
            &[$((stringify!($field), $owner.$field, $crate::check::check_fields!(@strict $bound))),+],
        )
    };
    (@strict >) => {
        true
    };
    (@strict >=) => {
        false
    };
}
pub(crate) use check_fields;
