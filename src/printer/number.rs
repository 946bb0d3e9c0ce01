//! Writing exact decimals back as text.

use crate::syntax::{Number, NumberFlags};

use super::text::Text;

/// The plain decimal spelling of a number: sign, integer digits, point and fraction digits as
/// the number's flags say (`.075`, `-0.`, `0600`-style leading zeros are not reproduced).
pub fn plain(number: Number) -> String {
    let mut out = String::new();
    write_number(&mut out, number, Style::AS_WRITTEN);
    out
}

/// How to spell a number.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Style {
    /// Write `0.5` rather than `.5`.
    pub leading_zero: bool,
    /// Write a decimal point even on whole numbers (`X50.`).
    pub force_point: bool,
    /// Keep the number's own choice of point and leading zero (used for `plain`).
    pub as_written: bool,
    /// Drop trailing zeros of the fraction (`1.500` → `1.5`).
    pub trim_zeros: bool,
}

impl Style {
    pub const AS_WRITTEN: Style = Style { leading_zero: true, force_point: false, as_written: true, trim_zeros: false };
}

pub fn write_number(out: &mut impl Text, number: Number, style: Style) {
    if usize::from(number.scale) > MANTISSA_DIGITS {
        return write_long_fraction(out, number, style);
    }
    // A fraction longer than the mantissa starts with the zeros the digits are padded with.
    let (digits, start) = digits(number.mantissa.unsigned_abs());
    // The fraction's digits written are `fraction_start..fraction_end`.
    let fraction_start = MANTISSA_DIGITS - usize::from(number.scale);
    let mut fraction_end = MANTISSA_DIGITS;
    if style.trim_zeros {
        // Trailing zeros of the fraction go, and with a fraction of zeros only, every one.
        while fraction_end > fraction_start && digits.get(fraction_end - 1) == Some(&b'0') {
            fraction_end -= 1;
        }
    }
    let fraction_empty = fraction_end == fraction_start;
    let point = if style.as_written { number.has_point() } else { style.force_point || !fraction_empty };
    let leading =
        if style.as_written { !number.flags.contains(NumberFlags::NO_INTEGER_DIGITS) } else { style.leading_zero };
    // The spelling is put together on the stack and handed over at once (sign, at most one
    // more digit than the mantissa has, point).
    let mut spelling = Spelling { bytes: [0; MANTISSA_DIGITS + 3], length: 0 };
    if number.mantissa < 0 || number.flags.contains(NumberFlags::MINUS) {
        spelling.push(b"-");
    } else if style.as_written && number.flags.contains(NumberFlags::PLUS) {
        spelling.push(b"+");
    }
    // The integer part: the digits above the fraction (the first of them is not a zero).
    if start < fraction_start {
        spelling.push(digits.get(start..fraction_start).unwrap_or_default());
    } else if leading || !point || fraction_empty {
        spelling.push(b"0");
    }
    if point {
        spelling.push(b".");
        spelling.push(digits.get(fraction_start..fraction_end).unwrap_or_default());
    }
    out.push_ascii(spelling.bytes.get(..spelling.length).unwrap_or_default());
}

/// Write `value`'s decimal digits (`0` for zero): codes and other whole numbers.
pub(crate) fn write_whole(out: &mut impl Text, value: u64) {
    let (digits, start) = digits(value);
    out.push_ascii(digits.get(start..).filter(|d| !d.is_empty()).unwrap_or(b"0"));
}

/// The crate's one digit writer: `value`'s decimal digits right-aligned in a buffer padded
/// with `0`, and where the first of them is (the buffer's end for zero). On the stack: a
/// printed program has millions of numbers and codes, and `format!` costs an allocation
/// each.
fn digits(value: u64) -> ([u8; MANTISSA_DIGITS], usize) {
    let mut digits = [b'0'; MANTISSA_DIGITS];
    if value == 0 {
        return (digits, MANTISSA_DIGITS);
    }
    let mut buffer = itoa::Buffer::new();
    let text = buffer.format(value).as_bytes();
    let start = MANTISSA_DIGITS - text.len();
    if let Some(slot) = digits.get_mut(start..) {
        slot.copy_from_slice(text);
    }
    (digits, start)
}

/// The most decimal digits a mantissa has (`u64::MAX` has 20).
const MANTISSA_DIGITS: usize = 20;

/// A number's spelling as it is put together.
struct Spelling {
    bytes: [u8; MANTISSA_DIGITS + 3],
    length: usize,
}

impl Spelling {
    fn push(&mut self, text: &[u8]) {
        let end = self.length + text.len();
        if let Some(slot) = self.bytes.get_mut(self.length..end) {
            slot.copy_from_slice(text);
            self.length = end;
        }
    }
}

/// `write_number` for a fraction longer than any mantissa's digits (more than twenty
/// places), digit by digit.
fn write_long_fraction(out: &mut impl Text, number: Number, style: Style) {
    let (digits, start) = digits(number.mantissa.unsigned_abs());
    let count = MANTISSA_DIGITS - start;
    // Digit `k` of the mantissa (0 the last); a fraction longer than the mantissa starts
    // with zeros.
    let digit = |k: usize| MANTISSA_DIGITS.checked_sub(k + 1).and_then(|at| digits.get(at)).copied().unwrap_or(b'0');
    let scale = usize::from(number.scale);
    // The fraction's digits written are those from `last_place` up.
    let mut last_place = 0;
    if style.trim_zeros {
        // Trailing zeros of the fraction go, and with a fraction of zeros only, every one.
        while last_place < scale && digit(last_place) == b'0' {
            last_place += 1;
        }
    }
    let fraction_empty = last_place == scale;
    let point = if style.as_written { number.has_point() } else { style.force_point || !fraction_empty };
    let leading =
        if style.as_written { !number.flags.contains(NumberFlags::NO_INTEGER_DIGITS) } else { style.leading_zero };
    let negative = number.mantissa < 0 || number.flags.contains(NumberFlags::MINUS);
    if negative {
        out.push_byte(b'-');
    } else if style.as_written && number.flags.contains(NumberFlags::PLUS) {
        out.push_byte(b'+');
    }
    // The integer part: the digits above the fraction (the first of them is not a zero).
    if count > scale {
        for k in (scale..count).rev() {
            out.push_byte(digit(k));
        }
    } else if leading || !point || fraction_empty {
        out.push_byte(b'0');
    }
    if point {
        out.push_byte(b'.');
        for k in (last_place..scale).rev() {
            out.push_byte(digit(k));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn number(mantissa: i64, scale: u8, point: bool) -> Number {
        Number::new(mantissa, scale, point)
    }

    #[test]
    fn plain_spelling_follows_the_flags() {
        assert_eq!(plain(number(1250, 3, true)), "1.250");
        assert_eq!(plain(number(-125, 2, true)), "-1.25");
        assert_eq!(plain(number(50, 0, false)), "50");
        assert_eq!(plain(number(50, 0, true)), "50.");
    }

    #[test]
    fn canonical_spelling() {
        let style = Style { leading_zero: true, force_point: true, as_written: false, trim_zeros: true };
        let mut out = String::new();
        write_number(&mut out, number(75, 3, true), style);
        assert_eq!(out, "0.075");
        out.clear();
        write_number(&mut out, number(3000, 3, true), style);
        assert_eq!(out, "3.");
        out.clear();
        write_number(&mut out, number(0, 0, false), style);
        assert_eq!(out, "0.");
    }

    /// The spelling as it was first written, with strings: the reference the stack-buffer
    /// version must agree with.
    fn by_strings(out: &mut String, number: Number, style: Style) {
        let negative = number.mantissa < 0 || number.flags.contains(NumberFlags::MINUS);
        if negative {
            out.push('-');
        } else if style.as_written && number.flags.contains(NumberFlags::PLUS) {
            out.push('+');
        }
        let digits = number.mantissa.unsigned_abs().to_string();
        let scale = number.scale as usize;
        let (integer, fraction) = if digits.len() > scale {
            (digits[..digits.len() - scale].to_string(), digits[digits.len() - scale..].to_string())
        } else {
            (String::new(), format!("{}{}", "0".repeat(scale - digits.len()), digits))
        };
        let mut fraction = fraction;
        if style.trim_zeros {
            while fraction.ends_with('0') {
                fraction.pop();
            }
        }
        let integer = integer.trim_start_matches('0');
        let point = if style.as_written { number.has_point() } else { style.force_point || !fraction.is_empty() };
        let leading =
            if style.as_written { !number.flags.contains(NumberFlags::NO_INTEGER_DIGITS) } else { style.leading_zero };
        if integer.is_empty() {
            if leading || !point || fraction.is_empty() {
                out.push('0');
            }
        } else {
            out.push_str(integer);
        }
        if point {
            out.push('.');
            out.push_str(&fraction);
        }
    }

    proptest::proptest! {
        #[test]
        fn whole_numbers_are_written_as_rust_writes_them(
            value in proptest::prop_oneof![proptest::num::u64::ANY, 0u64..1000, proptest::strategy::Just(u64::MAX)],
        ) {
            let mut out = String::new();
            write_whole(&mut out, value);
            proptest::prop_assert_eq!(out, value.to_string());
        }

        #[test]
        fn the_stack_spelling_is_the_string_spelling(
            mantissa in proptest::prop_oneof![proptest::num::i64::ANY, -100_000i64..100_000, proptest::strategy::Just(0i64)],
            scale in 0u8..=40,
            flags in 0u8..32,
            style in 0u8..16,
        ) {
            let mut n = Number::new(mantissa, scale, flags & 1 != 0);
            for (bit, flag) in [(2, NumberFlags::PLUS), (4, NumberFlags::MINUS), (8, NumberFlags::NO_INTEGER_DIGITS), (16, NumberFlags::LEADING_ZEROS)] {
                if flags & bit != 0 {
                    n.flags.insert(flag);
                }
            }
            let style = Style {
                leading_zero: style & 1 != 0,
                force_point: style & 2 != 0,
                as_written: style & 4 != 0,
                trim_zeros: style & 8 != 0,
            };
            let (mut fast, mut reference) = (String::new(), String::new());
            write_number(&mut fast, n, style);
            by_strings(&mut reference, n, style);
            proptest::prop_assert_eq!(fast, reference);
        }
    }
}
