//! [`codes!`](macro@crate::codes): the integer codes of an enumeration, both directions from one list.
//!
//! An FMU shows a setting that is an enumeration (a mode, a feedback source) as an Integer
//! parameter. Written by hand, each needs a `code` and a `from_code` that must agree, and a
//! declared range that must be exactly the codes; the macro writes both directions from one
//! list of `value => code` arms and derives the range from the codes, so none can drift apart.

/// Defines a unit struct that converts the values of an enumeration (or `bool`) to integer codes
/// and back:
///
/// ```
/// #[derive(Clone, Copy, Debug, PartialEq)]
/// enum Mode { Hold, Run(Speed) }
/// #[derive(Clone, Copy, Debug, PartialEq)]
/// enum Speed { Slow, Fast }
///
/// fmu_model::codes! {
///     /// `mode`: 0 hold, 1 slow, 2 fast.
///     ModeCodes: Mode { Mode::Hold => 0, Mode::Run(Speed::Slow) => 1, Mode::Run(Speed::Fast) => 2 }
/// }
///
/// const START: i32 = ModeCodes::code(Mode::Run(Speed::Slow)); // `const`: usable as a start
/// assert_eq!(START, 1);
/// assert_eq!(ModeCodes::decode(2), Some(Mode::Run(Speed::Fast)));
/// assert_eq!(ModeCodes::decode(3), None);
/// assert_eq!((ModeCodes::MIN, ModeCodes::MAX), (0, 2));
/// ```
///
/// A value is a path (`Mode::Hold`, `true`) with at most one path inside parentheses
/// (`Mode::Run(Speed::Fast)`). The codes must be distinct and fill `MIN..=MAX` without a gap,
/// which the build checks: a table row declares `.range(ModeCodes::MIN, ModeCodes::MAX)`, so
/// that the export layer refuses any other code (with its error status and a message naming the
/// variable and its range) before the setter sees it, and every code the setter can meet decodes.
/// The setter is `.set(|m, v| ModeCodes::set(&mut m.mode, v))`; [`coded!`](macro@crate::coded) writes
/// such a row whole.
///
/// Codes with a gap do not build:
///
/// ```compile_fail
/// fmu_model::codes! { Flag: bool { false => 0, true => 2 } }
/// const MAX: i32 = Flag::MAX;
/// ```
#[macro_export]
macro_rules! codes {
    (
        $(#[$attr:meta])*
        $vis:vis $name:ident: $ty:ty {
            $($($seg:ident)::+ $(($($arg:ident)::+))? => $code:literal),+ $(,)?
        }
    ) => {
        $(#[$attr])*
        $vis struct $name;

        impl $name {
            const CODES: &'static [i32] = &[$($code),+];
            /// The smallest code: the row's declared minimum.
            pub const MIN: i32 = $crate::codes::range(Self::CODES).0;
            /// The largest code: the row's declared maximum.
            pub const MAX: i32 = $crate::codes::range(Self::CODES).1;

            /// The code of `value`.
            pub const fn code(value: $ty) -> i32 {
                match value {
                    $($($seg)::+ $(($($arg)::+))? => $code,)+
                }
            }

            /// The value of `code`, `None` for a code that is none of them.
            pub const fn decode(code: i32) -> Option<$ty> {
                match code {
                    $($code => Some($($seg)::+ $(($($arg)::+))?),)+
                    _ => None,
                }
            }

            /// Writes the value of `code` to `target`. The row's range is `MIN..=MAX`, which the
            /// export layer enforces before any setter runs and which the codes fill, so every
            /// code that gets here decodes; were one not to, `target` would keep its value
            /// rather than the instance panic across the C interface.
            pub fn set(target: &mut $ty, code: i32) {
                if let Some(value) = Self::decode(code) {
                    *target = value;
                }
            }
        }
    };
}

/// An Integer row of an enumeration with the codes of a [`codes!`](macro@crate::codes) struct: its start
/// is the code of `start`, its range the codes, and it reads and writes the field that `value`
/// names.
///
/// ```text
/// coded!(Integer::tunable(0, "mode"), ModeCodes, start: CONFIG.mode, doc: "0 hold, …",
///     value: |m| m.config.mode)
/// ```
#[macro_export]
macro_rules! coded {
    (
        $($kind:ident)::+ ($vr:expr, $name:expr), $codes:ident,
        start: $start:expr,
        doc: $doc:expr,
        value: |$m:ident| $($field:tt)+
    ) => {
        $($kind)::+($vr, $name)
            .start($codes::code($start))
            .range($codes::MIN, $codes::MAX)
            .doc($doc)
            .get(|$m| $codes::code($($field)+))
            .set(|$m, v| $codes::set(&mut $($field)+, v))
    };
}

/// The smallest and largest of `codes`, which must be distinct and fill the range between them
/// without a gap (a `const` evaluation that fails the build otherwise).
pub const fn range(codes: &[i32]) -> (i32, i32) {
    assert!(!codes.is_empty(), "an enumeration without codes");
    let (mut min, mut max) = (codes[0], codes[0]);
    let mut i = 0;
    while i < codes.len() {
        let mut j = i + 1;
        while j < codes.len() {
            assert!(codes[i] != codes[j], "two values share a code");
            j += 1;
        }
        if codes[i] < min {
            min = codes[i];
        }
        if codes[i] > max {
            max = codes[i];
        }
        i += 1;
    }
    // Distinct codes fill [min, max] exactly when there are as many as the range is wide.
    assert!(max as i64 - min as i64 + 1 == codes.len() as i64, "the codes leave a gap in their range");
    (min, max)
}
