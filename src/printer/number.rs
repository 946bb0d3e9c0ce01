//! Writing exact decimals back as text.

use crate::syntax::{Number, NumberFlags};

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

pub fn write_number(out: &mut String, number: Number, style: Style) {
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
}
