//! The writing style of a program, inferred from its own blocks, so that blocks an edit adds
//! look like the blocks around them: packed or spaced words, `.075` or `0.075`, `G1` or
//! `G01`, `X3.` or `X3.0`, fixed decimal places, CR LF or LF, arcs by radius or by centre,
//! and whether the program switches thread chamfering. It is the one style every new block
//! is written in, by the printer and by the back end (`crate::back`), counted in one pass
//! over the program's words (`StyleTally`).

use crate::dialect::{Address, AddressKind, Dialect, Tables};
use crate::syntax::{Block, CodeLetter, Number, NumberFlags, Program, Statement, WordKind};

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
    /// Arcs are written with a radius (`R`, OSP `L`) rather than `I K`: the program's motion
    /// blocks write more radius words than centre words.
    pub radius_arcs: bool,
    /// Some block turns thread chamfering on (OSP `M23`): an unchamfered thread pass the back
    /// end writes then turns it off (`back/cycle/thread_pass.rs`).
    pub thread_chamfering: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WholeNumbers {
    PointOnly,
    PointZero,
    NoPoint,
}

/// The arc words of one block, as `StyleTally::add_block` read them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BlockArcWords {
    /// Not a motion block: its words were not read for arcs.
    NotRead,
    /// Neither a radius nor a centre word.
    Neither,
    /// A radius word (`R`, OSP `L`), with or without centre words.
    Radius,
    /// Centre words (`I`, `K`) and no radius word.
    Centre,
}

/// The counts the style is decided by, gathered block by block: `ProgramStyle::infer` reads
/// every block for them, and a caller that reads every block anyway (the compensation's
/// rewrite, `compensation::rewrite::MotionBlocks::new`) gathers them in its own pass, so
/// that the long arrays of a big program's blocks and words are read from memory once
/// rather than twice.
pub struct StyleTally {
    /// The program's dialect and its tables, looked up once rather than per block.
    dialect: Dialect,
    tables: &'static Tables,
    /// The address of an arc's radius in the dialect (`R`, OSP `L`).
    radius_address: Address,
    /// The M code that turns thread chamfering on, where the dialect has one.
    chamfer_on: Option<u16>,
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
    /// Radius and centre words of motion blocks.
    by_radius: u32,
    by_centre: u32,
    /// A block writes `chamfer_on`.
    chamfering: bool,
}

impl StyleTally {
    /// No block counted yet, for `program`.
    pub fn new(program: &Program<'_>) -> StyleTally {
        let (dialect, tables) = (program.config().dialect, program.config().tables());
        StyleTally {
            dialect,
            tables,
            radius_address: if dialect == Dialect::Osp { Address::L } else { Address::R },
            chamfer_on: tables.m_functions.thread_chamfer_on.first().copied(),
            packed: 0,
            spaced: 0,
            small_without_zero: 0,
            small_with_zero: 0,
            one_digit_codes: 0,
            two_digit_codes: 0,
            point_only: 0,
            point_zero: 0,
            no_point: 0,
            scales: [0; 10],
            with_trailing_zero: 0,
            lengths: 0,
            crlf: 0,
            lf: 0,
            cr: 0,
            by_radius: 0,
            by_centre: 0,
            chamfering: false,
        }
    }

    /// Count block `index` of the program (`block` is `program.block(index)`), and say which
    /// arc words it has.
    pub fn add_block(&mut self, program: &Program<'_>, index: usize, block: &Block) -> BlockArcWords {
        match program.terminator(index) {
            b"\r\n" => self.crlf += 1,
            b"\n" => self.lf += 1,
            b"\r" => self.cr += 1,
            _ => {}
        }
        // Only a motion block's `R`/`L` and `I K` place an arc's centre.
        let motion = block.statement == Statement::Motion;
        let (by_radius, by_centre) = (self.by_radius, self.by_centre);
        // The end of the word before, when it is not a comment: two such words next to each
        // other are packed when nothing lies between them.
        let mut significant_end = None;
        for word in program.words_of(block) {
            let significant = !matches!(word.kind, WordKind::Comment(_));
            if let (true, Some(end)) = (significant, significant_end) {
                if end == word.span.start {
                    self.packed += 1;
                } else {
                    self.spaced += 1;
                }
            }
            significant_end = significant.then_some(word.span.end);
            match word.kind {
                WordKind::Code { letter, code } if letter == CodeLetter::G && code.major() < 10 => {
                    let text = program.text(word.span);
                    if text.len() >= 3 && text[1] == b'0' {
                        self.two_digit_codes += 1;
                    } else {
                        self.one_digit_codes += 1;
                    }
                }
                WordKind::Code { letter: CodeLetter::M, code } => {
                    self.chamfering |= self.chamfer_on == Some(code.major());
                }
                WordKind::Number { address, number } => {
                    let kind = self.tables.address(address).map(|s| s.kind);
                    if matches!(kind, Some(AddressKind::Length | AddressKind::Feed)) {
                        self.add_number(number, kind == Some(AddressKind::Length));
                    }
                    if motion {
                        self.add_arc_word(address);
                    }
                }
                WordKind::Expr { address, .. } if motion => self.add_arc_word(address),
                _ => {}
            }
        }
        if !motion {
            BlockArcWords::NotRead
        } else if self.by_radius > by_radius {
            BlockArcWords::Radius
        } else if self.by_centre > by_centre {
            BlockArcWords::Centre
        } else {
            BlockArcWords::Neither
        }
    }

    /// Count a motion block's word at `address` if it is a radius or a centre word.
    fn add_arc_word(&mut self, address: Address) {
        if address == self.radius_address {
            self.by_radius += 1;
        } else if address == Address::I || address == Address::K {
            self.by_centre += 1;
        }
    }

    /// Count a length or feed number.
    fn add_number(&mut self, number: Number, is_length: bool) {
        if number.has_point()
            && Number::power_of_ten(number.scale).is_none_or(|p| number.mantissa.unsigned_abs() < p)
            && number.mantissa != 0
        {
            if number.flags.contains(NumberFlags::NO_INTEGER_DIGITS) {
                self.small_without_zero += 1;
            } else {
                self.small_with_zero += 1;
            }
        }
        if !is_length {
            return;
        }
        self.lengths += 1;
        if number.has_point() {
            self.scales[(number.scale as usize).min(9)] += 1;
            if number.scale > 0 && number.mantissa % 10 == 0 {
                self.with_trailing_zero += 1;
            }
        }
        if number.is_whole() {
            match (number.has_point(), number.scale) {
                (false, _) => self.no_point += 1,
                (true, 0) => self.point_only += 1,
                (true, _) => self.point_zero += 1,
            }
        }
    }

    /// The style the counts of every block of the program decide.
    pub fn style(&self) -> ProgramStyle {
        let dialect = self.dialect;
        let line_ending = if self.crlf >= self.lf && self.crlf >= self.cr && self.crlf > 0 {
            "\r\n"
        } else if self.cr > self.lf {
            "\r"
        } else {
            "\n"
        };
        let whole_numbers = if self.point_zero > self.point_only && self.point_zero >= self.no_point {
            WholeNumbers::PointZero
        } else if self.no_point > self.point_only && dialect == Dialect::Osp {
            // Only OSP reads `X50` as 50 mm on every machine; on Fanuc it may be 50 increments.
            WholeNumbers::NoPoint
        } else {
            WholeNumbers::PointOnly
        };
        let (top_scale, top_count) =
            self.scales.iter().enumerate().max_by_key(|(_, c)| **c).map_or((0, 0), |(s, c)| (s, *c));
        let fixed_decimals = (top_count > 0
            && top_scale > 0
            && top_count * 10 >= self.lengths * 8
            && self.with_trailing_zero * 10 >= top_count)
            .then_some(top_scale as u8);
        ProgramStyle {
            dialect,
            packed: dialect == Dialect::Fanuc && self.packed > self.spaced,
            suppress_leading_zero: self.small_without_zero > self.small_with_zero,
            two_digit_codes: self.two_digit_codes >= self.one_digit_codes,
            whole_numbers,
            fixed_decimals,
            line_ending,
            radius_arcs: self.by_radius > self.by_centre,
            thread_chamfering: self.chamfering,
        }
    }
}

impl ProgramStyle {
    pub fn infer(program: &Program<'_>) -> ProgramStyle {
        let mut tally = StyleTally::new(program);
        for (index, block) in program.blocks().iter().enumerate() {
            tally.add_block(program, index, block);
        }
        tally.style()
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
            radius_arcs: false,
            thread_chamfering: false,
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

#[cfg(test)]
mod tests;
