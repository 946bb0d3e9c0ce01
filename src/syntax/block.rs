//! The words of one block.
//!
//! The block's bytes come from the splitter (`syntax.rs`); this module turns them into typed
//! words or, at the first error, into one diagnostic. Words are pushed straight into the
//! program's arena; on error the caller truncates the arena back to the block's start.
//!
//! The dispatch is on the first byte of each word. Everything an address letter may be
//! followed by (a literal, `=expr` on OSP, `[expr]` or `#n` on Fanuc) is read here; what a
//! word *means* in its block is decided afterwards by `classify.rs`.

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::tables::{KeywordArgs, KeywordKind, SemicolonRule, SequenceStyle, VariableStyle};
use crate::dialect::{Address, Code, Tables};
use crate::source::Span;

use super::ast::{CodeLetter, CommentKind, Expr, ExprKind, Number, NumberFlags, Word, WordKind};
use super::expr::ExprParser;
use super::lexer::{
    Input, RawNumber, is_line_break, is_word_boundary, lex_name, lex_number, lex_paren_comment, lex_spaces,
};

pub(super) struct BlockParser<'a, 's> {
    pub source: &'s [u8],
    pub tables: &'static Tables,
    pub words: &'a mut Vec<Word>,
    pub exprs: &'a mut Vec<Expr>,
    pub warnings: &'a mut Vec<Diagnostic>,
}

type WordResult<'s> = Result<Input<'s>, Diagnostic>;

/// Where the parser is in the block: what may still come first.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Position {
    /// Nothing but blanks so far.
    Start,
    /// After a block delete, tape mark, program name or sequence name: a sequence name, a
    /// block delete (after an OSP sequence name) or the first word may follow.
    Prefix,
    /// After the first ordinary word.
    Body,
}

impl<'a, 's> BlockParser<'a, 's> {
    fn offset(&self, input: Input<'s>) -> u32 {
        (input.as_ptr() as usize - self.source.as_ptr() as usize) as u32
    }

    fn span(&self, from: Input<'s>, to: Input<'s>) -> Span {
        Span::new(self.offset(from), self.offset(to))
    }

    fn push(&mut self, from: Input<'s>, to: Input<'s>, kind: WordKind) {
        let span = self.span(from, to);
        self.words.push(Word { span, kind });
    }

    fn error(&self, from: Input<'s>, len: usize, kind: DiagnosticKind) -> Diagnostic {
        let start = self.offset(from);
        let len = len.min(from.len()) as u32;
        Diagnostic::error(kind, Span::new(start, start + len))
    }

    fn exprs(&mut self, space_ends: bool) -> ExprParser<'_, 's> {
        ExprParser::new(self.source, self.tables, self.exprs, space_ends)
    }

    fn is_osp(&self) -> bool {
        self.tables.lexical.variables == VariableStyle::Osp
    }

    /// Skip spaces, tabs and (OSP) a line break followed by the `$` of a continuation line.
    fn skip_blank(&self, mut input: Input<'s>) -> Input<'s> {
        if !matches!(input.first(), Some(b' ' | b'\t' | b'\r' | b'\n')) {
            return input;
        }
        loop {
            let blanks = input.iter().position(|&c| c != b' ' && c != b'\t').unwrap_or(input.len());
            input = &input[blanks..];
            match input {
                [b'\r', b'\n', b'$', rest @ ..] | [b'\n', b'$', rest @ ..] | [b'\r', b'$', rest @ ..]
                    if self.tables.lexical.continuation =>
                {
                    input = rest;
                }
                _ => return input,
            }
        }
    }

    /// Parse the words of a block. `text` is the block's bytes (a slice of the source).
    pub fn parse(&mut self, text: Input<'s>) -> Result<(), Diagnostic> {
        let mut rest = text;
        let mut position = Position::Start;
        // A verbatim keyword makes the rest of the block (up to a comment) one Verbatim word.
        let mut verbatim_next = false;
        loop {
            rest = self.skip_blank(rest);
            let Some(&c) = rest.first() else { return Ok(()) };
            if verbatim_next && c != b'(' {
                rest = self.verbatim(rest);
                verbatim_next = false;
                continue;
            }
            rest = match c {
                b'(' => self.paren_comment(rest)?,
                b';' => self.semicolon(rest),
                b'/' => {
                    let (next, new_position) = self.slash(rest, position)?;
                    position = new_position;
                    next
                }
                b'%' if position == Position::Start => {
                    let next = &rest[1..];
                    self.push(rest, next, WordKind::TapeMark);
                    position = Position::Prefix;
                    next
                }
                b'N' if position != Position::Body => {
                    let next = self.sequence(rest)?;
                    position = Position::Prefix;
                    next
                }
                b'O' if position != Position::Body => {
                    let next = self.program_name(rest, rest)?;
                    position = Position::Prefix;
                    next
                }
                b':' if position != Position::Body && !self.is_osp() => {
                    let next = self.program_name(rest, &rest[1..])?;
                    position = Position::Prefix;
                    next
                }
                b'A'..=b'Z' => {
                    position = Position::Body;
                    let (next, verbatim) = self.letter(rest)?;
                    verbatim_next = verbatim;
                    next
                }
                b'#' => {
                    position = Position::Body;
                    self.hash(rest)?
                }
                b'0'..=b'9' | b'-' | b'+' | b'.' => return Err(self.number_without_address(rest)),
                b'$' if !self.is_osp() => {
                    return Err(self.error(
                        rest,
                        1,
                        DiagnosticKind::ForeignWord {
                            what: "`$`".into(),
                            dialect: self.tables.config.dialect.name(),
                            belongs_to: "Okuma OSP",
                        },
                    ));
                }
                _ => return Err(self.invalid_character(rest)),
            };
        }
    }

    /// A byte that cannot be where it is, reported by what it is.
    fn invalid_character(&self, at: Input<'s>) -> Diagnostic {
        let c = at.first().copied().unwrap_or(b' ');
        let kind = match c {
            0 => DiagnosticKind::NulByte,
            0x80..=0xFF => DiagnosticKind::NonAsciiByte { byte: c },
            b'$' if self.tables.lexical.continuation => DiagnosticKind::OrphanContinuation,
            b'a'..=b'z' => DiagnosticKind::LowerCaseLetter { found: c as char },
            b']' => DiagnosticKind::UnmatchedBracket,
            _ => DiagnosticKind::InvalidCharacter { found: c as char },
        };
        self.error(at, 1, kind)
    }

    fn paren_comment(&mut self, input: Input<'s>) -> WordResult<'s> {
        match lex_paren_comment(input) {
            Ok((rest, _)) => {
                self.push(input, rest, WordKind::Comment(CommentKind::Paren));
                Ok(rest)
            }
            Err(_) => Err(self.error(input, 1, DiagnosticKind::UnclosedComment)),
        }
    }

    /// Fanuc: `;` ends the block and the rest of the line is a comment. OSP: the same reading,
    /// with a warning, because `;` is not an OSP comment.
    fn semicolon(&mut self, input: Input<'s>) -> Input<'s> {
        let end = input.iter().position(|&c| is_line_break(c)).unwrap_or(input.len());
        let rest = &input[end..];
        self.push(input, rest, WordKind::Comment(CommentKind::Semicolon));
        if self.tables.lexical.semicolon == SemicolonRule::NotAComment {
            let span = self.span(input, &input[1..]);
            self.warnings.push(Diagnostic::warning(DiagnosticKind::SemicolonInOsp, span));
        }
        rest
    }

    fn slash(&mut self, input: Input<'s>, position: Position) -> Result<(Input<'s>, Position), Diagnostic> {
        let mut end = 1;
        let mut level = 1u8;
        if self.tables.lexical.block_delete_levels
            && let Some(&d) = input.get(1)
            && (b'1'..=b'9').contains(&d)
        {
            level = d - b'0';
            end = 2;
        }
        let rest = &input[end..];
        match position {
            Position::Start | Position::Prefix => {
                self.push(input, rest, WordKind::BlockDelete { level });
                Ok((rest, Position::Prefix))
            }
            Position::Body if self.tables.lexical.mid_block_skip => {
                self.push(input, rest, WordKind::OptionalSkip { level });
                Ok((rest, Position::Body))
            }
            Position::Body => Err(self.error(input, 1, DiagnosticKind::MisplacedBlockDelete)),
        }
    }

    /// `N` at the start of a block: the sequence name.
    fn sequence(&mut self, input: Input<'s>) -> WordResult<'s> {
        let lexical = &self.tables.lexical;
        let after_n = &input[1..];
        match lexical.sequence {
            SequenceStyle::Numeric => {
                let digits = after_n.iter().take_while(|c| c.is_ascii_digit()).count();
                if digits == 0 {
                    if after_n.first() == Some(&b'O') {
                        return Err(self.letter_o_for_zero(input, 1));
                    }
                    return Err(self.error(input, 1, DiagnosticKind::MissingSequenceName));
                }
                if digits > lexical.sequence_max {
                    return Err(self.error(
                        input,
                        1 + digits,
                        DiagnosticKind::SequenceTooLong { max: lexical.sequence_max },
                    ));
                }
                let rest = &after_n[digits..];
                let number = parse_u32(&after_n[..digits]);
                self.push(input, rest, WordKind::Sequence { number });
                Ok(rest)
            }
            SequenceStyle::Osp => {
                let (name_len, number) = osp_name(after_n);
                if name_len == 0 {
                    return Err(self.error(input, 1, DiagnosticKind::MissingSequenceName));
                }
                let rest = &after_n[name_len..];
                if name_len > lexical.sequence_max {
                    return Err(self.error(
                        input,
                        1 + name_len,
                        DiagnosticKind::SequenceTooLong { max: lexical.sequence_max },
                    ));
                }
                // OSP needs a blank, a comment or the end after the name (`N100G00` is an alarm).
                match rest.first() {
                    None | Some(b' ' | b'\t' | b'(' | b'\r' | b'\n' | b';') => {}
                    Some(_) => {
                        let name = String::from_utf8_lossy(&input[..1 + name_len]).into_owned();
                        return Err(self.error(rest, 1, DiagnosticKind::MissingSpaceAfterSequence { name }));
                    }
                }
                self.push(input, rest, WordKind::Sequence { number });
                Ok(rest)
            }
        }
    }

    /// `O1234`, `:0100` (Fanuc), `OSTRT` (OSP) at the start of a block.
    fn program_name(&mut self, input: Input<'s>, after_prefix: Input<'s>) -> WordResult<'s> {
        let lexical = &self.tables.lexical;
        let (after_o, max) = if input[0] == b':' {
            (after_prefix, lexical.program_name_max)
        } else {
            (&input[1..], lexical.program_name_max)
        };
        let len = match lexical.program_name {
            SequenceStyle::Numeric => after_o.iter().take_while(|c| c.is_ascii_digit()).count(),
            SequenceStyle::Osp => osp_name(after_o).0,
        };
        if len == 0 || len > max {
            let bad = after_o.iter().take_while(|c| c.is_ascii_alphanumeric()).count();
            return Err(self.error(input, 1 + bad, DiagnosticKind::InvalidProgramName { max }));
        }
        let rest = &after_o[len..];
        if let Some(&c) = rest.first()
            && !is_word_boundary(c)
        {
            return Err(self.error(input, 1 + len + 1, DiagnosticKind::InvalidProgramName { max }));
        }
        self.push(input, rest, WordKind::ProgramName);
        Ok(rest)
    }

    fn letter_o_for_zero(&self, word_start: Input<'s>, o_at: usize) -> Diagnostic {
        let word_len = word_start
            .iter()
            .enumerate()
            .skip(1)
            .find(|&(i, c)| i > o_at && !(c.is_ascii_digit() || *c == b'.' || *c == b'O' || *c == b'-'))
            .map_or(word_start.len(), |(i, _)| i);
        let text = &word_start[..word_len];
        let mut suggestion = Vec::with_capacity(text.len());
        suggestion.push(text[0]);
        suggestion.extend(text[1..].iter().map(|&c| if c == b'O' { b'0' } else { c }));
        let suggestion = String::from_utf8_lossy(&suggestion).into_owned();
        self.error(&word_start[o_at..], 1, DiagnosticKind::LetterOForZero { suggestion })
    }

    fn number_without_address(&self, input: Input<'s>) -> Diagnostic {
        let (len, suggestion) = match lex_number(input) {
            Ok((rest, raw)) if raw.has_digits() => {
                let len = input.len() - rest.len();
                let code = raw.to_number().and_then(|n| n.as_whole()).filter(|n| *n <= 999);
                let suggestion = code
                    .filter(|&n| self.tables.g(Code::whole(n as u16)).is_some())
                    .map(|_| format!("G{}", String::from_utf8_lossy(raw.text)));
                (len, suggestion)
            }
            _ => (1, None),
        };
        self.error(input, len, DiagnosticKind::NumberWithoutAddress { suggestion })
    }

    /// A word that starts with a letter: an address with a value, a code, a keyword, an OSP
    /// extended address, name or assignment. Returns whether a verbatim argument follows.
    fn letter(&mut self, input: Input<'s>) -> Result<(Input<'s>, bool), Diagnostic> {
        let letter = input[0];
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
    fn fast_literal(&mut self, word: Input<'s>, address: Address) -> Option<Input<'s>> {
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
            if c == b'O' || !is_word_boundary(c) {
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
    fn address_value(&mut self, word: Input<'s>, after: Input<'s>, address: Address) -> WordResult<'s> {
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

    fn literal(
        &self,
        word: Input<'s>,
        rest: Input<'s>,
        address: Address,
        raw: RawNumber<'s>,
    ) -> Result<WordKind, Diagnostic> {
        let max_digits = self.tables.address(address).map_or(8, |spec| spec.max_digits);
        let digits = raw.significant_digits();
        let number = raw.to_number().filter(|_| digits <= max_digits);
        match number {
            Some(number) => Ok(WordKind::Number { address, number }),
            None => Err(self.error(
                word,
                word.len() - rest.len(),
                DiagnosticKind::NumberOutOfRange { address: address.name(), digits, max_digits },
            )),
        }
    }

    fn code(
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

    /// After a value: the next word, a blank, a comment, or the end. Anything else is
    /// damage (`X1.0}2`) or a stray character.
    fn expect_boundary(&self, rest: Input<'s>) -> Result<(), Diagnostic> {
        match rest.first() {
            None => Ok(()),
            Some(&c) if is_word_boundary(c) => Ok(()),
            Some(&c) if c.is_ascii_lowercase() => {
                Err(self.error(rest, 1, DiagnosticKind::LowerCaseLetter { found: c as char }))
            }
            Some(0) => Err(self.error(rest, 1, DiagnosticKind::NulByte)),
            Some(&c) if c >= 0x80 => Err(self.error(rest, 1, DiagnosticKind::NonAsciiByte { byte: c })),
            Some(b']') => Err(self.error(rest, 1, DiagnosticKind::UnmatchedBracket)),
            Some(_) => Err(self.invalid_character(rest)),
        }
    }

    /// An address with nothing usable after it. `X SDIA-3` on OSP is a missing `=`.
    fn missing_value(&self, word: Input<'s>, value: Input<'s>, address: &str) -> Diagnostic {
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
    fn no_digits(&self, word: Input<'s>, value: Input<'s>, rest: Input<'s>, address: &str) -> Diagnostic {
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
    fn label(&mut self, input: Input<'s>) -> WordResult<'s> {
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

    /// A keyword at this position. Returns `None` when the letters are not a keyword.
    fn keyword(&mut self, input: Input<'s>) -> Result<Option<(Input<'s>, bool)>, Diagnostic> {
        let Ok((after_letters, letters)) = super::lexer::lex_letters(input) else { return Ok(None) };
        // OSP keywords are whole names (`IF` but not `IFX`); Fanuc's `DO1`/`END1`/`GOTO100`
        // carry their operand right after the letters.
        let (name, after) = if self.is_osp() {
            match lex_name(input) {
                Ok((after, name)) => (name, after),
                Err(_) => return Ok(None),
            }
        } else {
            (letters, after_letters)
        };
        let Some((index, info)) = self.tables.keyword(name) else {
            if !self.is_osp()
                && let Some(diagnostic) = self.foreign_keyword(input, name)
            {
                return Err(diagnostic);
            }
            return Ok(None);
        };
        let info = info.clone();
        self.push(input, after, WordKind::Keyword { index: index as u16 });
        let verbatim = info.args == KeywordArgs::Verbatim;
        let rest = match info.kind {
            KeywordKind::If | KeywordKind::While => self.condition(after)?,
            KeywordKind::Goto => self.jump_target(after)?,
            KeywordKind::Do | KeywordKind::EndLoop if !self.is_osp() => self.loop_number(after)?,
            KeywordKind::Call | KeywordKind::ModalCall => self.call_target(after)?,
            _ => after,
        };
        Ok(Some((rest, verbatim)))
    }

    /// `NAME=value` or `V1=value` in a Fanuc program: an OSP variable or extended address.
    fn foreign_assignment(&self, input: Input<'s>, name: &[u8]) -> Diagnostic {
        self.error(
            input,
            name.len() + 1,
            DiagnosticKind::ForeignWord {
                what: format!("`{}=`", String::from_utf8_lossy(name)),
                dialect: "Fanuc",
                belongs_to: "Okuma OSP",
            },
        )
    }

    /// OSP keywords in a Fanuc program are reported as foreign words.
    fn foreign_keyword(&self, input: Input<'s>, name: &[u8]) -> Option<Diagnostic> {
        const OSP_ONLY: [&[u8]; 5] = [b"CALL", b"RTS", b"MODIN", b"MODOUT", b"VC"];
        OSP_ONLY.contains(&name).then(|| {
            self.error(
                input,
                name.len(),
                DiagnosticKind::ForeignWord {
                    what: format!("`{}`", String::from_utf8_lossy(name)),
                    dialect: "Fanuc",
                    belongs_to: "Okuma OSP",
                },
            )
        })
    }

    /// The `[ … ]` after `IF` or `WHILE`.
    fn condition(&mut self, input: Input<'s>) -> WordResult<'s> {
        let start = lex_spaces(input).map_or(input, |(r, _)| r);
        if start.first() != Some(&b'[') {
            return Err(self.error(start, 1, DiagnosticKind::MalformedExpression { expected: "`[` and a condition" }));
        }
        let (rest, expr) = self.exprs(false).bracketed(start)?;
        self.push(start, rest, WordKind::Operand { expr });
        Ok(rest)
    }

    /// The target of `GOTO`: an OSP `N` name, or a Fanuc number or expression.
    fn jump_target(&mut self, input: Input<'s>) -> WordResult<'s> {
        let start = lex_spaces(input).map_or(input, |(r, _)| r);
        if self.is_osp() {
            if start.first() != Some(&b'N') {
                return Err(self.error(start, 1, DiagnosticKind::MissingSequenceName));
            }
            return self.label(start);
        }
        let (rest, expr) = self.exprs(false).operand(start)?;
        self.push(start, rest, WordKind::Operand { expr });
        Ok(rest)
    }

    /// Fanuc `DO1`, `END1`: the loop number.
    fn loop_number(&mut self, input: Input<'s>) -> WordResult<'s> {
        let start = lex_spaces(input).map_or(input, |(r, _)| r);
        let (rest, expr) = self.exprs(false).operand(start)?;
        self.push(start, rest, WordKind::Operand { expr });
        Ok(rest)
    }

    /// OSP `CALL OSUB`, `MODIN OINT1`: the program name.
    fn call_target(&mut self, input: Input<'s>) -> WordResult<'s> {
        let start = lex_spaces(input).map_or(input, |(r, _)| r);
        match start.first() {
            Some(b'O') => {
                let (len, _) = osp_name(&start[1..]);
                let max = self.tables.lexical.program_name_max;
                if len == 0 || len > max {
                    return Err(self.error(start, 1 + len, DiagnosticKind::InvalidProgramName { max }));
                }
                let rest = &start[1 + len..];
                self.expect_boundary(rest)?;
                self.push(start, rest, WordKind::ProgramRef);
                Ok(rest)
            }
            Some(b'0') => {
                let len = start.iter().take_while(|c| c.is_ascii_alphanumeric()).count();
                let suggestion = format!("O{}", String::from_utf8_lossy(&start[1..len]));
                Err(self.error(start, 1, DiagnosticKind::ZeroForLetterO { suggestion }))
            }
            _ => Err(self.error(
                start,
                1,
                DiagnosticKind::InvalidProgramName { max: self.tables.lexical.program_name_max },
            )),
        }
    }

    /// The rest of the block up to a comment, as text.
    fn verbatim(&mut self, input: Input<'s>) -> Input<'s> {
        let end = input.iter().position(|&c| c == b'(' || is_line_break(c)).unwrap_or(input.len());
        let mut text_end = end;
        while text_end > 0 && matches!(input[text_end - 1], b' ' | b'\t') {
            text_end -= 1;
        }
        if text_end > 0 {
            self.push(input, &input[text_end..], WordKind::Verbatim);
        }
        &input[end..]
    }

    /// OSP: a name at word position: an extended address (`XA=60`), a variable assignment
    /// (`FLAN=318`, `V1=2`, `VTOFX[16]=…`), or an error.
    fn osp_name_word(&mut self, input: Input<'s>) -> WordResult<'s> {
        let (after, name) = lex_name(input)
            .map_err(|_| self.error(input, 1, DiagnosticKind::UnknownStatement { name: String::new() }))?;
        if let Some(address) = self.tables.extended_address(name) {
            if after.first() != Some(&b'=') {
                return Err(self.error(
                    input,
                    name.len(),
                    DiagnosticKind::ExtendedAddressNeedsEquals { name: address.name() },
                ));
            }
            return self.address_value(input, after, address);
        }
        let (after_target, target) = self.exprs(true).osp_variable(input, after, name)?;
        if after_target.first() != Some(&b'=') {
            let name = String::from_utf8_lossy(name).into_owned();
            return Err(self.error(
                input,
                after_target.len().min(input.len() - after_target.len()).max(name.len()),
                DiagnosticKind::UnknownStatement { name },
            ));
        }
        let value_start = &after_target[1..];
        let (rest, value) = self.exprs(true).expression(value_start)?;
        self.expect_boundary(rest)?;
        self.push(input, rest, WordKind::Assign { target, value });
        Ok(rest)
    }

    /// `#` at word position: a Fanuc assignment `#1=…`, `#[#2]=…`; foreign on OSP.
    fn hash(&mut self, input: Input<'s>) -> WordResult<'s> {
        if self.is_osp() {
            return Err(self.error(
                input,
                1,
                DiagnosticKind::ForeignWord { what: "`#` variable".into(), dialect: "Okuma OSP", belongs_to: "Fanuc" },
            ));
        }
        let (after_target, target) = self.exprs(false).hash_variable(input)?;
        let after_target = lex_spaces(after_target).map_or(after_target, |(r, _)| r);
        if after_target.first() != Some(&b'=') {
            return Err(self.error(
                after_target,
                1,
                DiagnosticKind::MalformedExpression { expected: "`=` after the variable" },
            ));
        }
        let value_start = lex_spaces(&after_target[1..]).map_or(&after_target[1..], |(r, _)| r);
        let (rest, value) = self.exprs(false).expression(value_start)?;
        self.expect_boundary(rest)?;
        self.push(input, rest, WordKind::Assign { target, value });
        Ok(rest)
    }
}

/// An OSP name after `N` or `O`: 1+ digits, or a letter followed by letters and digits.
/// Returns its length and, when it is all digits, its value.
fn osp_name(input: &[u8]) -> (usize, Option<u32>) {
    match input.first() {
        Some(c) if c.is_ascii_digit() => {
            let len = input.iter().take_while(|c| c.is_ascii_digit()).count();
            (len, parse_u32(&input[..len]))
        }
        Some(c) if c.is_ascii_uppercase() => {
            let len = input.iter().take_while(|c| c.is_ascii_uppercase() || c.is_ascii_digit()).count();
            (len, None)
        }
        _ => (0, None),
    }
}

fn parse_u32(digits: &[u8]) -> Option<u32> {
    let mut value: u32 = 0;
    for &d in digits {
        value = value.checked_mul(10)?.checked_add((d - b'0') as u32)?;
    }
    Some(value)
}
