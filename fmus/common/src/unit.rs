//! Uniform numbers in the unit interval from one 64-bit random word (of a ChaCha stream, in this
//! project), with 53 random bits: the top 53 bits of the word, k = word >> 11, scaled by 2⁻⁵³,
//! which is exact in an `f64`. The three variants differ in which end they may reach; every draw
//! of the FMUs, the sweep plans and the fuzzer depends on them bit for bit.

/// 2⁻⁵³, the spacing of the draws.
const UNIT_53: f64 = 1.0 / (1u64 << 53) as f64;

/// The 53 random bits of `word`.
fn bits(word: u64) -> f64 {
    (word >> 11) as f64
}

/// Uniform in [0, 1): k · 2⁻⁵³.
pub fn closed_open(word: u64) -> f64 {
    bits(word) * UNIT_53
}

/// Uniform in (0, 1]: (k + 1) · 2⁻⁵³, never 0 (a logarithm of it is finite).
pub fn open_closed(word: u64) -> f64 {
    (bits(word) + 1.0) * UNIT_53
}

/// Uniform in (0, 1): (k + ½) · 2⁻⁵³, never 0 (where a normal's inverse CDF is infinite).
///
/// Not quite open at the top: for the one largest k (probability 2⁻⁵³) k + ½ needs 54 bits and
/// rounds to 2⁵³, giving exactly 1. Kept so, because the sweep plans' draws depend on it bit for
/// bit; a caller that cannot take 1 must clamp.
pub fn open(word: u64) -> f64 {
    (bits(word) + 0.5) * UNIT_53
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ends_are_reached_or_not_as_named() {
        assert_eq!(closed_open(0), 0.0);
        assert_eq!(closed_open(u64::MAX), 1.0 - UNIT_53);
        assert_eq!(open_closed(0), UNIT_53);
        assert_eq!(open_closed(u64::MAX), 1.0);
        assert_eq!(open(0), 0.5 * UNIT_53);
        // The one word whose draw rounds up to 1 (see `open`); the next lower k stays below.
        assert_eq!(open(u64::MAX), 1.0);
        assert!(open(u64::MAX - (1 << 11)) < 1.0);
    }

    #[test]
    fn only_the_top_53_bits_count() {
        assert_eq!(closed_open(0x7ff), 0.0);
        assert_eq!(closed_open(1 << 63), 0.5);
    }
}
