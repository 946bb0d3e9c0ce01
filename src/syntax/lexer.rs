//! Token-level nom parsers shared by the block and expression parsers.
//!
//! Naming contract (after Gleam's parser): `lex_x` recognises an `x` and fails without
//! consuming when there is none; callers turn a failure into a diagnostic that fits the
//! context. All parsers work on byte slices of the whole source, so a slice's position is
//! its offset from the source start.

use nom::bytes::complete::{take_while, take_while1};
use nom::combinator::recognize;
use nom::{IResult, Parser};

use super::ast::{Number, NumberFlags};

pub type Input<'s> = &'s [u8];

/// The parts of a numeric literal as written: `-12.50` is sign `-`, integer `12`, point,
/// fraction `50`.
#[derive(Debug, Clone, Copy)]
pub struct RawNumber<'s> {
    pub text: &'s [u8],
    pub sign: Option<u8>,
    pub integer: &'s [u8],
    pub point: bool,
    pub fraction: &'s [u8],
}

impl RawNumber<'_> {
    pub fn has_digits(&self) -> bool {
        !self.integer.is_empty() || !self.fraction.is_empty()
    }

    /// Significant digits: the integer part without leading zeros, plus every fraction digit.
    pub fn significant_digits(&self) -> usize {
        let integer = self.integer.iter().skip_while(|&&d| d == b'0').count();
        integer + self.fraction.len()
    }

    /// The exact value, or `None` when it does not fit an `i64` mantissa with a scale of at
    /// most 18 (a 400-digit number).
    pub fn to_number(self) -> Option<Number> {
        if self.fraction.len() > 18 {
            return None;
        }
        let mut mantissa: i64 = 0;
        for &d in self.integer.iter().chain(self.fraction) {
            mantissa = mantissa.checked_mul(10)?.checked_add((d - b'0') as i64)?;
        }
        let mut flags = NumberFlags::default();
        if self.point {
            flags.insert(NumberFlags::POINT);
        }
        match self.sign {
            Some(b'-') => {
                mantissa = -mantissa;
                flags.insert(NumberFlags::MINUS);
            }
            Some(_) => flags.insert(NumberFlags::PLUS),
            None => {}
        }
        if self.integer.is_empty() {
            flags.insert(NumberFlags::NO_INTEGER_DIGITS);
        } else if self.integer.len() > 1 && self.integer[0] == b'0' {
            flags.insert(NumberFlags::LEADING_ZEROS);
        }
        Some(Number { mantissa, scale: self.fraction.len() as u8, flags })
    }
}

/// `[+-]? digits* ('.' digits*)?` — succeeds on a lone sign or point too, so the caller can
/// report "no digits" at the right place instead of a generic failure.
///
/// Written by hand rather than composed from nom's `digit0`/`one_of`: it runs for nearly
/// every word of every program and dominates parse time.
pub fn lex_number(input: Input<'_>) -> IResult<Input<'_>, RawNumber<'_>> {
    let mut i = 0;
    let sign = match input.first() {
        Some(&c @ (b'+' | b'-')) => {
            i = 1;
            Some(c)
        }
        _ => None,
    };
    let integer_start = i;
    while i < input.len() && input[i].is_ascii_digit() {
        i += 1;
    }
    let integer = &input[integer_start..i];
    let mut point = false;
    let mut fraction = &input[i..i];
    if input.get(i) == Some(&b'.') {
        point = true;
        i += 1;
        let fraction_start = i;
        while i < input.len() && input[i].is_ascii_digit() {
            i += 1;
        }
        fraction = &input[fraction_start..i];
    }
    if i == 0 {
        return Err(nom::Err::Error(nom::error::Error::new(input, nom::error::ErrorKind::Digit)));
    }
    Ok((&input[i..], RawNumber { text: &input[..i], sign, integer, point, fraction }))
}

/// An upper-case name: a letter, then letters and digits (`FLAN`, `VTOFX`, `DIA1`, `CALL`).
pub fn lex_name(input: Input<'_>) -> IResult<Input<'_>, Input<'_>> {
    recognize((
        take_while1(|c: u8| c.is_ascii_uppercase()),
        take_while(|c: u8| c.is_ascii_alphanumeric() && !c.is_ascii_lowercase()),
    ))
    .parse(input)
}

/// Only the letters of a name (`DO` of `DO1`, `END` of `END1`).
pub fn lex_letters(input: Input<'_>) -> IResult<Input<'_>, Input<'_>> {
    take_while1(|c: u8| c.is_ascii_uppercase()).parse(input)
}

/// Spaces and tabs.
pub fn lex_spaces(input: Input<'_>) -> IResult<Input<'_>, Input<'_>> {
    take_while(|c: u8| c == b' ' || c == b'\t').parse(input)
}

/// Decimal digits.
pub fn lex_digits(input: Input<'_>) -> IResult<Input<'_>, Input<'_>> {
    take_while1(|c: u8| c.is_ascii_digit()).parse(input)
}

/// The body of a `( … )` comment up to its `)`; fails when the line ends first.
pub fn lex_paren_comment(input: Input<'_>) -> IResult<Input<'_>, Input<'_>> {
    recognize((
        nom::character::complete::char('('),
        take_while(|c: u8| c != b')' && c != b'\n' && c != b'\r'),
        nom::character::complete::char(')'),
    ))
    .parse(input)
}

pub fn is_line_break(c: u8) -> bool {
    c == b'\n' || c == b'\r'
}

/// Whether `c` can end a word's value: the start of another word, a comment, the end.
pub fn is_word_boundary(c: u8) -> bool {
    c.is_ascii_uppercase() || matches!(c, b' ' | b'\t' | b'(' | b';' | b'/' | b'\n' | b'\r' | b'#' | b'%')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_their_spelling() {
        let (rest, raw) = lex_number(b"-.075X").unwrap();
        assert_eq!(rest, b"X");
        let n = raw.to_number().unwrap();
        assert_eq!((n.mantissa, n.scale), (-75, 3));
        assert!(n.flags.contains(NumberFlags::NO_INTEGER_DIGITS));
        let (_, raw) = lex_number(b"0600").unwrap();
        let n = raw.to_number().unwrap();
        assert_eq!((n.mantissa, n.scale), (600, 0));
        assert!(n.flags.contains(NumberFlags::LEADING_ZEROS));
        assert_eq!(raw.significant_digits(), 3);
    }

    #[test]
    fn a_lone_point_is_a_number_without_digits() {
        let (rest, raw) = lex_number(b". }0").unwrap();
        assert_eq!(rest, b" }0");
        assert!(!raw.has_digits());
    }

    #[test]
    fn four_hundred_digits_do_not_fit() {
        let digits = "9".repeat(400);
        let (_, raw) = lex_number(digits.as_bytes()).unwrap();
        assert!(raw.to_number().is_none());
        assert_eq!(raw.significant_digits(), 400);
    }

    #[test]
    fn comments_stop_at_the_line_end() {
        assert!(lex_paren_comment(b"(abc)X").is_ok());
        assert!(lex_paren_comment(b"(abc\n)").is_err());
    }
}
