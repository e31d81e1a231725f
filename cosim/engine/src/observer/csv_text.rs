//! The text of CSV cells, appended to a reused line buffer without allocating: Reals exactly as
//! Rust's `{:?}` writes them, text fields quoted by the rules of the `csv` crate.

/// Appends `value` as `format!("{value:?}")` writes it: the shortest decimal that reads back to
/// the same bits, in plain notation for `1e-4 <= |value| < 1e16` (at least one decimal, `1.0`,
/// `0.0001`, `-0.0`) and in e-notation outside it (`1e-7`, `1.5e-5`, `1e16`, `5e-324`); `NaN`,
/// `inf`, `-inf` for the non-finite values.
///
/// `zmij` (twice as fast as `ryu`) writes `1e+16` where `{:?}` writes `1e16`, and
/// `1e-5 <= |value| < 1e-4` as `0.0000ddd` where `{:?}` writes `d.dde-5`; both are rewritten.
/// One difference is left: when the value lies exactly halfway between the two shortest
/// decimals (a value with few binary fraction digits whose exact decimal is one digit longer,
/// e.g. `1 + 2^-17 = 1.00000762939453125`), `zmij` takes the even last digit
/// (`1.0000076293945312`) where `{:?}` rounds up (`1.0000076293945313`); both read back to the
/// same bits.
pub(super) fn push_real(line: &mut Vec<u8>, buffer: &mut zmij::Buffer, value: f64) {
    let text = buffer.format(value).as_bytes();
    if value.abs() >= 1e16 && value.is_finite() {
        line.extend(text.iter().filter(|&&byte| byte != b'+'));
        return;
    }
    let (sign, magnitude) = match text.split_first() {
        Some((b'-', rest)) => (&text[..1], rest),
        _ => (&text[..0], text),
    };
    match magnitude.strip_prefix(b"0.0000") {
        Some(digits) => {
            line.extend_from_slice(sign);
            line.push(digits[0]);
            if digits.len() > 1 {
                line.push(b'.');
                line.extend_from_slice(&digits[1..]);
            }
            line.extend_from_slice(b"e-5");
        }
        None => line.extend_from_slice(text),
    }
}

/// The text of one column's last Real, so that a value equal (bit for bit) to the previous row's
/// is copied instead of formatted again: set-points, parameters and still-water ship motion stay
/// constant over a run, and formatting a Real costs about ten times the copy.
#[derive(Debug, Clone, Copy)]
pub(super) struct RealText {
    bits: u64,
    len: u8,
    /// The longest text `push_real` writes is 24 bytes (`-2.2250738585072014e-308`).
    text: [u8; 32],
}

impl Default for RealText {
    /// Holds no text yet (`len` 0), so the first value is always formatted.
    fn default() -> Self {
        RealText { bits: 0, len: 0, text: [0; 32] }
    }
}

impl RealText {
    /// Appends `value` as [`push_real`] does, from the memo when it holds `value`'s bits.
    pub(super) fn push(&mut self, line: &mut Vec<u8>, buffer: &mut zmij::Buffer, value: f64) {
        let bits = value.to_bits();
        if self.len > 0 && bits == self.bits {
            // The whole fixed-size array and a truncation: two vector moves, where a copy of
            // `len` bytes would call memcpy.
            let end = line.len() + usize::from(self.len);
            line.extend_from_slice(&self.text);
            line.truncate(end);
            return;
        }
        let start = line.len();
        push_real(line, buffer, value);
        let text = &line[start..];
        // Always true (see `text`); a longer text would just not be remembered.
        if let (Some(slot), Ok(len)) = (self.text.get_mut(..text.len()), u8::try_from(text.len())) {
            slot.copy_from_slice(text);
            self.bits = bits;
            self.len = len;
        }
    }
}

/// Appends `value` in decimal.
pub(super) fn push_integer(line: &mut Vec<u8>, value: i32) {
    use std::io::Write;
    // Writing to a Vec cannot fail.
    let _ = write!(line, "{value}");
}

/// Appends `text` as one CSV field, quoted as the `csv` crate quotes by default: only when it
/// contains a comma, a double quote, CR or LF, with every double quote doubled.
pub(super) fn push_field(line: &mut Vec<u8>, text: &str) {
    let bytes = text.as_bytes();
    if !bytes.iter().any(|b| matches!(b, b',' | b'"' | b'\r' | b'\n')) {
        line.extend_from_slice(bytes);
        return;
    }
    line.push(b'"');
    for &byte in bytes {
        if byte == b'"' {
            line.push(b'"');
        }
        line.push(byte);
    }
    line.push(b'"');
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The memo writes exactly what `push_real` writes, for repeated values, for values that
    /// differ only in the sign of zero or in a NaN payload, and after a change.
    #[test]
    fn a_remembered_real_is_written_as_push_real_writes_it() {
        let mut memo = RealText::default();
        let mut buffer = zmij::Buffer::new();
        let values =
            [0.0, 0.0, -0.0, -0.0, 0.1, 0.1, f64::NAN, -f64::NAN, 1e-5, 1e300, 1e300, -2.2250738585072014e-308];
        for value in values {
            let mut memo_line = b"x,".to_vec();
            memo.push(&mut memo_line, &mut buffer, value);
            assert_eq!(String::from_utf8(memo_line).expect("ASCII"), format!("x,{}", real(value)), "{value:?}");
        }
    }

    fn real(value: f64) -> String {
        let mut line = Vec::new();
        push_real(&mut line, &mut zmij::Buffer::new(), value);
        String::from_utf8(line).expect("ASCII")
    }

    /// A deterministic stream of f64 bit patterns (SplitMix64), covering every exponent.
    fn bit_patterns(count: usize) -> impl Iterator<Item = u64> {
        let mut state = 0x9E37_79B9_7F4A_7C15_u64;
        std::iter::repeat_with(move || {
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        })
        .take(count)
    }

    #[test]
    fn reals_are_written_as_debug_formatting_writes_them() {
        let special = [
            0.0,
            -0.0,
            0.1,
            1.0,
            -2.5,
            1e-4,
            9.999999999999999e-5,
            1e-5,
            -1.5e-5,
            1.2345e-5,
            1e-7,
            1e15,
            1e16,
            123456789012345680.0,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for value in special {
            assert_eq!(real(value), format!("{value:?}"));
        }
        let tie = 1.0 + 2f64.powi(-17);
        assert_eq!((real(tie).as_str(), format!("{tie:?}").as_str()), ("1.0000076293945312", "1.0000076293945313"));
        let mut ties = 0;
        for bits in bit_patterns(200_000) {
            // Any value, and one in 1e-5..1e-4, where zmij's own notation differs.
            let small = f64::from_bits(bits % (1e-4_f64.to_bits() - 1e-5_f64.to_bits()) + 1e-5_f64.to_bits());
            for value in [f64::from_bits(bits), small] {
                let (ours, debug) = (real(value), format!("{value:?}"));
                assert!(value.is_nan() || ours.parse::<f64>() == Ok(value), "{ours} for {value:?}");
                if ours != debug {
                    assert_halfway_tie(&ours, &debug, value);
                    ties += 1;
                }
            }
        }
        assert!(ties < 100, "{ties} ties in 400000 values");
    }

    /// `ours` and `debug` are the two shortest decimals `value` lies exactly halfway between:
    /// they differ by one in the last digit, ours ends in an even digit, both read back to `value`.
    fn assert_halfway_tie(ours: &str, debug: &str, value: f64) {
        let last = |text: &str| text.bytes().rfind(u8::is_ascii_digit).map(|d| d - b'0');
        let (a, b) = (last(ours).unwrap_or(0), last(debug).unwrap_or(0));
        assert!(
            ours.len() == debug.len()
                && ours[..ours.len() - 1] == debug[..debug.len() - 1]
                && a % 2 == 0
                && a.abs_diff(b) == 1
                && debug.parse::<f64>() == Ok(value),
            "{ours} (ours) vs {debug} ({{:?}}) for {value:?}"
        );
    }

    #[test]
    fn fields_are_quoted_like_the_csv_crate() {
        for text in ["plain", "pendulum.theta_x", "", "a,b", "say \"hi\"", "two\nlines", "cr\r", "'single'", " spaced "]
        {
            let mut ours = Vec::new();
            push_field(&mut ours, text);
            ours.extend_from_slice(b",x\n");
            let mut writer = csv::Writer::from_writer(Vec::new());
            writer.write_record([text, "x"]).expect("write");
            assert_eq!(ours, writer.into_inner().expect("flush"), "{text:?}");
        }
    }

    #[test]
    fn integers_are_decimal() {
        let mut line = Vec::new();
        for value in [0, -1, i32::MAX, i32::MIN] {
            line.clear();
            push_integer(&mut line, value);
            assert_eq!(line, value.to_string().as_bytes());
        }
    }
}
