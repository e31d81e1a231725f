//! How numbers read in messages: times without the round-off of their arithmetic, counts with
//! the noun in the right number.

use std::fmt;

/// A time (s) or another decimal quantity printed as the shortest decimal within
/// [`DISPLAY_TOLERANCE`] of it: the grid's `t0 + k·h` carries round-off in its last bits
/// (`2.4000000000000004` for 12 · 0.2), which tells a reader nothing. Values a message must give
/// exactly (an FMI call's arguments) keep `{:?}`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Decimal(pub f64);

/// Relative difference below which two decimals print the same.
pub const DISPLAY_TOLERANCE: f64 = 1e-12;

impl fmt::Display for Decimal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let value = self.0;
        if !value.is_finite() {
            return write!(f, "{value}");
        }
        let close =
            |text: &str| text.parse::<f64>().is_ok_and(|v| (v - value).abs() <= DISPLAY_TOLERANCE * value.abs());
        // From 1e16 on, `{:.0}` spells out every digit (301 for 1e300): the exponent form instead,
        // within the same tolerance.
        let text = if value.abs() >= 1e16 {
            (0..=17).map(|digits| format!("{value:.digits$e}")).find(|text| close(text))
        } else {
            (0..=17).map(|digits| format!("{value:.digits$}")).find(|text| close(text))
        };
        match text {
            Some(text) => f.write_str(&text),
            None => write!(f, "{value:?}"),
        }
    }
}

/// `value` as the number [`Decimal`] prints, for output that carries numbers rather than text
/// (JSON): `10.07` for `10.37 - 0.3`, not `10.069999999999999`.
pub fn rounded(value: f64) -> f64 {
    // From 1e16 on a value has no decimals to round off; it stays exactly as it was.
    if value.abs() >= 1e16 {
        return value;
    }
    Decimal(value).to_string().parse().unwrap_or(value)
}

/// `n` and the noun, plural unless `n` is 1: "1 row", "0 rows", "2 threads". The plural adds
/// an "s", which every noun these messages count takes.
pub fn counted(n: impl Into<u64>, noun: &str) -> String {
    let n = n.into();
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimals_without_round_off() {
        let shown = |v: f64| Decimal(v).to_string();
        assert_eq!(shown(12.0 * 0.2), "2.4");
        assert_eq!(shown(0.1 + 0.2), "0.3");
        assert_eq!(shown(11982.0 * 0.01), "119.82");
        assert_eq!(shown(120.0), "120");
        assert_eq!(shown(0.0), "0");
        assert_eq!(shown(-0.5), "-0.5");
        assert_eq!(shown(1e-3), "0.001");
        // Beyond 17 decimals, or not a number: as Rust prints it.
        assert_eq!(shown(1.5e-20), "1.5e-20");
        // Very large: the exponent form, not hundreds of digits.
        assert_eq!(shown(1e300), "1e300");
        assert_eq!(shown(-2.5e20), "-2.5e20");
        assert_eq!(shown(5e-324), "5e-324");
        assert_eq!(shown(1e15), "1000000000000000");
        assert_eq!(shown(f64::INFINITY), "inf");
        // A difference the tolerance keeps.
        assert_eq!(shown(2.4 + 1e-9), "2.400000001");
    }

    #[test]
    fn rounded_numbers_lose_the_round_off() {
        assert_eq!(rounded(10.37 - 0.3), 10.07);
        assert_eq!(rounded(11982.0 * 0.01).to_string(), "119.82");
        assert_eq!(rounded(1.5e-20), 1.5e-20);
        assert_eq!(rounded(1.0000000000000002e20), 1.0000000000000002e20);
        assert!(rounded(f64::NAN).is_nan());
    }

    #[test]
    fn nouns_in_the_right_number() {
        assert_eq!(counted(1u64, "row"), "1 row");
        assert_eq!(counted(0u64, "row"), "0 rows");
        assert_eq!(counted(2usize as u64, "thread"), "2 threads");
    }
}
