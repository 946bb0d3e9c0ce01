//! The writing style of a program, inferred from its own blocks, so that blocks an edit adds
//! look like the blocks around them: packed or spaced words, `.075` or `0.075`, `G1` or
//! `G01`, `X3.` or `X3.0`, fixed decimal places, CR LF or LF.

use crate::dialect::{Address, AddressKind, Dialect};
use crate::syntax::{CodeLetter, NumberFlags, Program, WordKind};

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ProgramStyle {
    pub dialect: Dialect,
    /// Words written without spaces (`G01X10.Z2.`), Fanuc only.
    pub packed: bool,
    /// `.075` rather than `0.075`.
    pub suppress_leading_zero: bool,
    /// `G01` rather than `G1`.
    pub two_digit_codes: bool,
    /// How a whole length is written: `3.`, `3.0` or `3`.
    pub whole_numbers: WholeNumbers,
    /// When most lengths carry the same number of decimals, trailing zeros included
    /// (`60.000`), new lengths get that many.
    pub fixed_decimals: Option<u8>,
    pub line_ending: &'static str,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WholeNumbers {
    PointOnly,
    PointZero,
    NoPoint,
}

#[derive(Default)]
struct Tally {
    packed: u32,
    spaced: u32,
    small_without_zero: u32,
    small_with_zero: u32,
    one_digit_codes: u32,
    two_digit_codes: u32,
    point_only: u32,
    point_zero: u32,
    no_point: u32,
    scales: [u32; 10],
    with_trailing_zero: u32,
    lengths: u32,
    crlf: u32,
    lf: u32,
    cr: u32,
}

impl ProgramStyle {
    pub fn infer(program: &Program<'_>) -> ProgramStyle {
        let tables = program.config().tables();
        let source = program.source();
        let mut tally = Tally::default();
        for (index, block) in program.blocks().iter().enumerate() {
            match program.terminator(index) {
                b"\r\n" => tally.crlf += 1,
                b"\n" => tally.lf += 1,
                b"\r" => tally.cr += 1,
                _ => {}
            }
            let words = program.words_of(block);
            for pair in words.windows(2) {
                let between = &source[pair[0].span.end as usize..pair[1].span.start as usize];
                let significant = |k: &WordKind| !matches!(k, WordKind::Comment(_));
                if significant(&pair[0].kind) && significant(&pair[1].kind) {
                    if between.is_empty() {
                        tally.packed += 1;
                    } else {
                        tally.spaced += 1;
                    }
                }
            }
            for word in words {
                match word.kind {
                    WordKind::Code { letter, code } if letter == CodeLetter::G && code.major() < 10 => {
                        let text = program.text(word.span);
                        if text.len() >= 3 && text[1] == b'0' {
                            tally.two_digit_codes += 1;
                        } else {
                            tally.one_digit_codes += 1;
                        }
                    }
                    WordKind::Number { address, number } => {
                        let kind = tables.address(address).map(|s| s.kind);
                        if !matches!(kind, Some(AddressKind::Length | AddressKind::Feed)) {
                            continue;
                        }
                        if number.has_point()
                            && number.mantissa.unsigned_abs() < 10u64.pow(number.scale as u32)
                            && number.mantissa != 0
                        {
                            if number.flags.contains(NumberFlags::NO_INTEGER_DIGITS) {
                                tally.small_without_zero += 1;
                            } else {
                                tally.small_with_zero += 1;
                            }
                        }
                        if kind == Some(AddressKind::Length) {
                            tally.lengths += 1;
                            if number.has_point() {
                                tally.scales[(number.scale as usize).min(9)] += 1;
                                if number.scale > 0 && number.mantissa % 10 == 0 {
                                    tally.with_trailing_zero += 1;
                                }
                            }
                            let whole = number.is_whole();
                            if whole {
                                match (number.has_point(), number.scale) {
                                    (false, _) => tally.no_point += 1,
                                    (true, 0) => tally.point_only += 1,
                                    (true, _) => tally.point_zero += 1,
                                }
                            }
                        }
                    }
                    _ => {}
                }
            }
        }
        let dialect = program.config().dialect;
        let line_ending = if tally.crlf >= tally.lf && tally.crlf >= tally.cr && tally.crlf > 0 {
            "\r\n"
        } else if tally.cr > tally.lf {
            "\r"
        } else {
            "\n"
        };
        let whole_numbers = if tally.point_zero > tally.point_only && tally.point_zero >= tally.no_point {
            WholeNumbers::PointZero
        } else if tally.no_point > tally.point_only && dialect == Dialect::Osp {
            // Only OSP reads `X50` as 50 mm on every machine; on Fanuc it may be 50 increments.
            WholeNumbers::NoPoint
        } else {
            WholeNumbers::PointOnly
        };
        let (top_scale, top_count) =
            tally.scales.iter().enumerate().max_by_key(|(_, c)| **c).map_or((0, 0), |(s, c)| (s, *c));
        let fixed_decimals = (top_count > 0
            && top_scale > 0
            && top_count * 10 >= tally.lengths * 8
            && tally.with_trailing_zero * 10 >= top_count)
            .then_some(top_scale as u8);
        ProgramStyle {
            dialect,
            packed: dialect == Dialect::Fanuc && tally.packed > tally.spaced,
            suppress_leading_zero: tally.small_without_zero > tally.small_with_zero,
            two_digit_codes: tally.two_digit_codes >= tally.one_digit_codes,
            whole_numbers,
            fixed_decimals,
            line_ending,
        }
    }

    /// The style of a new program with nothing to learn from.
    pub fn default_for(dialect: Dialect) -> ProgramStyle {
        ProgramStyle {
            dialect,
            packed: false,
            suppress_leading_zero: false,
            two_digit_codes: true,
            whole_numbers: WholeNumbers::PointOnly,
            fixed_decimals: None,
            line_ending: "\n",
        }
    }

    pub fn word_separator(&self) -> &'static str {
        if self.packed { "" } else { " " }
    }

    pub fn is_length(&self, program: &Program<'_>, address: Address) -> bool {
        matches!(
            program.config().tables().address(address).map(|s| s.kind),
            Some(AddressKind::Length | AddressKind::Angle)
        )
    }
}
