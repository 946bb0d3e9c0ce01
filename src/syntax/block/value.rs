//! Word values: what follows an address letter.
//!
//! `fast_literal` reads the common word (`X12.345`, `G01`) in one pass; everything else
//! (`X=FLAN+5` on OSP, `X[#1]` or `X-#1` on Fanuc, damage such as `F. }0`, a missing value)
//! goes through `address_value`, which also reports the problems.

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::{Address, Code};
use crate::source::Span;
use crate::syntax::ast::{CodeLetter, ExprKind, Number, NumberFlags, Word, WordKind};
use crate::syntax::lexer::{Input, RawNumber, is_line_break, is_word_boundary, lex_name, lex_number, lex_spaces};

use super::{BlockParser, WordResult, osp_name, parse_u32};

impl<'s> BlockParser<'_, 's> {
    /// A word that starts with a letter: an address with a value, a code, a keyword, an OSP
    /// extended address, name or assignment. Returns whether a verbatim argument follows.
    pub(super) fn letter(&mut self, input: Input<'s>) -> Result<(Input<'s>, bool), Diagnostic> {
        // A control that reads lower case takes `x10.` as `X10.` (the text keeps its case).
        let letter = if self.tables.lower_case { input[0].to_ascii_uppercase() } else { input[0] };
        let next = input.get(1).copied();
        let osp = self.is_osp();
        if letter == b'N' {
            return Ok((self.label(input)?, false));
        }
        // A run of letters: a keyword, and on OSP an extended address, a name or a variable.
        if next.is_some_and(|c| c.is_ascii_uppercase())
            || (osp && letter == b'V' && next.is_some_and(|c| c.is_ascii_digit()))
        {
            if let Some(result) = self.keyword(input)? {
                return Ok(result);
            }
            if osp {
                return Ok((self.osp_name_word(input)?, false));
            }
            if let Ok((after, name)) = lex_name(input)
                && after.first() == Some(&b'=')
            {
                return Err(self.foreign_assignment(input, name));
            }
            if letter == b'O' || next == Some(b'O') {
                return Err(self.letter_o_for_zero(input, if letter == b'O' { 0 } else { 1 }));
            }
            // Two letters in a row on Fanuc: the first has no value (`XZ10`).
            return Err(self.error(
                input,
                1,
                DiagnosticKind::MissingValue { address: (letter as char).to_string(), suggestion: None },
            ));
        }
        if letter == b'O' {
            if input.get(1).is_some_and(|c| c.is_ascii_digit() || *c == b'.') {
                return Err(self.letter_o_for_zero(input, 0));
            }
            return Err(self.error(
                input,
                1,
                DiagnosticKind::InvalidProgramName { max: self.tables.lexical.program_name_max },
            ));
        }
        let address = Address::letter(letter);
        if let Some(rest) = self.fast_literal(input, address) {
            return Ok((rest, false));
        }
        if self.tables.address(address).is_none() {
            return Err(self.error(
                input,
                1,
                DiagnosticKind::MissingValue { address: (letter as char).to_string(), suggestion: None },
            ));
        }
        Ok((self.address_value(input, &input[1..], address)?, false))
    }

    /// The common word, `X12.345` or `G01`: a literal right after the letter, ending at a word
    /// boundary, within the address's digit limit. Lexes, converts and checks in one pass.
    /// Returns `None` for anything else, and the general path (which also reports errors)
    /// takes over from the start of the word.
    #[inline]
    pub(super) fn fast_literal(&mut self, word: Input<'s>, address: Address) -> Option<Input<'s>> {
        let bytes = word;
        let n = bytes.len();
        let mut i = 1;
        let negative = match bytes.get(1) {
            Some(b'-') => {
                i = 2;
                true
            }
            Some(b'0'..=b'9' | b'.') => false,
            _ => return None,
        };
        // Up to 18 digits cannot overflow an i64; longer numbers take the general path.
        let mut mantissa: i64 = 0;
        let integer_start = i;
        while i < n && bytes[i].is_ascii_digit() {
            mantissa = mantissa.wrapping_mul(10).wrapping_add((bytes[i] - b'0') as i64);
            i += 1;
        }
        let integer_len = i - integer_start;
        let point = i < n && bytes[i] == b'.';
        let mut scale = 0usize;
        if point {
            i += 1;
            while i < n && bytes[i].is_ascii_digit() {
                mantissa = mantissa.wrapping_mul(10).wrapping_add((bytes[i] - b'0') as i64);
                i += 1;
                scale += 1;
            }
        }
        let digits = integer_len + scale;
        if digits > 18 || digits == 0 {
            return None;
        }
        if i < n {
            let c = bytes[i];
            if c == b'O' || !(self.boundary(c) || (c == b',' && self.tables.has_comma_words)) {
                return None;
            }
        }
        let leading_zero = integer_len > 0 && bytes[integer_start] == b'0';
        let leading_zeros = if leading_zero {
            bytes[integer_start..integer_start + integer_len].iter().take_while(|&&d| d == b'0').count()
        } else {
            0
        };
        let significant = digits - leading_zeros;
        let kind = if address == Address::G || address == Address::M {
            if negative || scale > 1 || (point && scale == 0) || integer_len == 0 || significant - scale > 3 {
                return None;
            }
            let letter = if address == Address::G { CodeLetter::G } else { CodeLetter::M };
            let tenths = if scale == 0 { mantissa * 10 } else { mantissa };
            WordKind::Code { letter, code: Code(tenths as u16) }
        } else {
            if significant > self.tables.max_digits(address)? {
                return None;
            }
            let mut flags = NumberFlags::default();
            if point {
                flags.insert(NumberFlags::POINT);
            }
            if negative {
                mantissa = -mantissa;
                flags.insert(NumberFlags::MINUS);
            }
            if integer_len == 0 {
                flags.insert(NumberFlags::NO_INTEGER_DIGITS);
            } else if integer_len > 1 && leading_zero {
                flags.insert(NumberFlags::LEADING_ZEROS);
            }
            WordKind::Number { address, number: Number { mantissa, scale: scale as u8, flags } }
        };
        let start = self.offset(word);
        self.words.push(Word { span: Span::new(start, start + i as u32), kind });
        Some(&bytes[i..])
    }

    /// The value after an address: `X10.`, `X=FLAN+5`, `X[#1]`, `X#1`, `X-#1`, `TG=01`.
    pub(super) fn address_value(&mut self, word: Input<'s>, after: Input<'s>, address: Address) -> WordResult<'s> {
        let mut value = after;
        if self.tables.lexical.space_before_value {
            value = lex_spaces(value).map_or(value, |(r, _)| r);
        }
        let is_code = address == Address::G || address == Address::M;
        match value.first().copied() {
            Some(b'=') if self.is_osp() => {
                let expr_start = &value[1..];
                let (rest, expr) = self.exprs(true).expression(expr_start)?;
                self.expect_boundary(rest)?;
                // A literal after `=` (`TG=01`) is a literal word; only expressions stay expressions.
                let kind = match self.exprs[expr as usize].kind {
                    ExprKind::Number(number) if !is_code => {
                        self.check_digits(word, rest, address, number.significant_digits())?;
                        self.exprs.truncate(expr as usize);
                        WordKind::Number { address, number }
                    }
                    _ => WordKind::Expr { address, expr },
                };
                self.push(word, rest, kind);
                Ok(rest)
            }
            Some(b'[' | b'#') | Some(b'-' | b'+')
                if !self.is_osp()
                    && (value.first() == Some(&b'[')
                        || value.first() == Some(&b'#')
                        || matches!(value.get(1), Some(b'[' | b'#'))) =>
            {
                let mut parser = self.exprs(false);
                let (rest, expr) = parser.operand(value)?;
                self.expect_boundary(rest)?;
                self.push(word, rest, WordKind::Expr { address, expr });
                Ok(rest)
            }
            Some(b'O') if value.get(1).is_some_and(|c| c.is_ascii_digit() || *c == b'.') || value.len() == 1 => {
                Err(self.letter_o_for_zero(word, word.len() - value.len()))
            }
            _ => {
                let Ok((rest, raw)) = lex_number(value) else {
                    if value.first() == Some(&b'=') {
                        return Err(self.foreign_assignment(word, &word[..word.len() - value.len()]));
                    }
                    return Err(self.missing_value(word, value, &address.name()));
                };
                if !raw.has_digits() {
                    return Err(self.no_digits(word, value, rest, &address.name()));
                }
                match rest.first() {
                    Some(b'O') => return Err(self.letter_o_for_zero(word, word.len() - rest.len())),
                    // `V1=2` on Fanuc: an OSP variable.
                    Some(b'=') if !self.is_osp() => {
                        return Err(self.foreign_assignment(word, &word[..word.len() - rest.len()]));
                    }
                    _ => {}
                }
                self.expect_boundary(rest)?;
                let kind = if is_code {
                    self.code(word, rest, address, raw)?
                } else {
                    self.literal(word, rest, address, raw)?
                };
                self.push(word, rest, kind);
                Ok(rest)
            }
        }
    }

    pub(super) fn literal(
        &self,
        word: Input<'s>,
        rest: Input<'s>,
        address: Address,
        raw: RawNumber<'s>,
    ) -> Result<WordKind, Diagnostic> {
        let digits = raw.significant_digits();
        self.check_digits(word, rest, address, digits)?;
        match raw.to_number() {
            Some(number) => Ok(WordKind::Number { address, number }),
            // More than an i64 mantissa holds: out of range whatever the address allows.
            None => {
                let kind = DiagnosticKind::NumberOutOfRange { address: address.name(), digits, max_digits: 18 };
                Err(self.error(word, word.len() - rest.len(), kind))
            }
        }
    }

    /// The address's digit limit (`[address] max_digits` in `grammar/`).
    fn check_digits(
        &self,
        word: Input<'s>,
        rest: Input<'s>,
        address: Address,
        digits: usize,
    ) -> Result<(), Diagnostic> {
        let max_digits = self.tables.address(address).map_or(8, |spec| spec.max_digits);
        if digits > max_digits {
            let kind = DiagnosticKind::NumberOutOfRange { address: address.name(), digits, max_digits };
            return Err(self.error(word, word.len() - rest.len(), kind));
        }
        Ok(())
    }

    pub(super) fn code(
        &self,
        word: Input<'s>,
        rest: Input<'s>,
        address: Address,
        raw: RawNumber<'s>,
    ) -> Result<WordKind, Diagnostic> {
        let letter = if address == Address::G { CodeLetter::G } else { CodeLetter::M };
        let len = word.len() - rest.len();
        if raw.sign.is_some()
            || raw.fraction.len() > 1
            || (raw.point && raw.fraction.is_empty())
            || raw.integer.is_empty()
        {
            return Err(self.error(word, len, DiagnosticKind::MalformedCode { address: letter.as_char() }));
        }
        let integer_digits = raw.integer.iter().skip_while(|&&d| d == b'0').count();
        // A code holds at most three integer digits and a tenth (`Code` is `u16` tenths).
        let max_digits = self.tables.address(address).map_or(3, |spec| spec.max_digits).min(3);
        let major = if integer_digits > max_digits { None } else { parse_u32(raw.integer) };
        let Some(major) = major else {
            return Err(self.error(
                word,
                len,
                DiagnosticKind::NumberOutOfRange { address: address.name(), digits: integer_digits, max_digits },
            ));
        };
        let minor = raw.fraction.first().map_or(0, |d| (d - b'0') as u32);
        Ok(WordKind::Code { letter, code: Code((major * 10 + minor) as u16) })
    }

    /// Whether `c` starts the next word or ends the block's words: a word boundary, or on a
    /// control that reads lower case (`[control.*] lower_case`) a lower-case letter too.
    pub(super) fn boundary(&self, c: u8) -> bool {
        is_word_boundary(c) || (self.tables.lower_case && c.is_ascii_lowercase())
    }

    /// After a value: the next word, a blank, a comment, or the end. Anything else is
    /// damage (`X1.0}2`) or a stray character.
    pub(super) fn expect_boundary(&self, rest: Input<'s>) -> Result<(), Diagnostic> {
        match rest.first() {
            None => Ok(()),
            Some(&c) if self.boundary(c) => Ok(()),
            Some(b',') if self.tables.has_comma_words => Ok(()),
            Some(&c) if c.is_ascii_lowercase() => Err(self.lower_case(rest)),
            Some(0) => Err(self.error(rest, 1, DiagnosticKind::NulByte)),
            Some(&c) if c >= 0x80 => Err(self.error(rest, 1, DiagnosticKind::NonAsciiByte { byte: c })),
            Some(b']') => Err(self.error(rest, 1, DiagnosticKind::UnmatchedBracket)),
            Some(_) => Err(self.invalid_character(rest)),
        }
    }

    /// An address with nothing usable after it. `X SDIA-3` on OSP is a missing `=`.
    pub(super) fn missing_value(&self, word: Input<'s>, value: Input<'s>, address: &str) -> Diagnostic {
        let after_spaces = lex_spaces(value).map_or(value, |(r, _)| r);
        if let Some(&c) = after_spaces.first()
            && !is_word_boundary(c)
            && !c.is_ascii_alphanumeric()
            && !matches!(c, b'[' | b'=' | b']')
        {
            return self.invalid_character(after_spaces);
        }
        let suggestion = if self.is_osp() && after_spaces.len() < value.len() {
            // `X SDIA-3`: a name with spaces before it and no `=`.
            lex_name(after_spaces).ok().map(|(rest, _)| {
                let end = rest.iter().position(|&c| c == b' ' || c == b'(' || is_line_break(c)).unwrap_or(rest.len());
                let expr = &after_spaces[..after_spaces.len() - rest.len() + end];
                format!("{address}={}", String::from_utf8_lossy(expr))
            })
        } else {
            None
        };
        let len = word.len() - value.len();
        self.error(word, len.max(1), DiagnosticKind::MissingValue { address: address.to_string(), suggestion })
    }

    /// A sign or point with no digits: a plain omission (`X.`), or damage (`F. }0`).
    pub(super) fn no_digits(&self, word: Input<'s>, value: Input<'s>, rest: Input<'s>, address: &str) -> Diagnostic {
        let after_spaces = lex_spaces(rest).map_or(rest, |(r, _)| r);
        let damaged = after_spaces.first().is_some_and(|&c| {
            !c.is_ascii_alphanumeric()
                && !matches!(c, b'(' | b';' | b'/' | b'%' | b'#' | b'[' | b'\r' | b'\n')
                && c != b'$'
        });
        if damaged {
            let run = after_spaces
                .iter()
                .position(|&c| c == b' ' || c == b'\t' || c == b'(' || c.is_ascii_uppercase() || is_line_break(c))
                .unwrap_or(after_spaces.len());
            let end = &after_spaces[run..];
            let start = self.offset(value);
            let span = Span::new(start, self.offset(end));
            let text = String::from_utf8_lossy(&word[..word.len() - end.len()]).into_owned();
            return Diagnostic::error(DiagnosticKind::DamagedNumber { text }, span);
        }
        let len = word.len() - rest.len();
        self.error(word, len, DiagnosticKind::MissingDigits { address: address.to_string() })
    }

    /// `N` after the start of a block: an OSP label operand (`G85 N0207`, `GOTO NDTM`), or a
    /// misplaced Fanuc sequence number.
    pub(super) fn label(&mut self, input: Input<'s>) -> WordResult<'s> {
        if !self.is_osp() {
            return Err(self.error(input, 1, DiagnosticKind::MisplacedSequence));
        }
        let after_n = &input[1..];
        let (len, number) = osp_name(after_n);
        if len == 0 {
            return Err(self.error(input, 1, DiagnosticKind::MissingSequenceName));
        }
        if len > self.tables.lexical.sequence_max {
            return Err(self.error(
                input,
                1 + len,
                DiagnosticKind::SequenceTooLong { max: self.tables.lexical.sequence_max },
            ));
        }
        let rest = &after_n[len..];
        self.expect_boundary(rest)?;
        self.push(input, rest, WordKind::Label { number });
        Ok(rest)
    }
}
