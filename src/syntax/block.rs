//! The words of one block.
//!
//! The block's bytes come from the splitter (`syntax.rs`); this module turns them into typed
//! words or, at the first error, into one diagnostic. Words are pushed straight into the
//! program's arena; on error the caller truncates the arena back to the block's start.
//!
//! The dispatch is on the first byte of each word. Everything an address letter may be
//! followed by (a literal, `=expr` on OSP, `[expr]` or `#n` on Fanuc) is read here; what a
//! word *means* in its block is decided afterwards by `classify.rs`.

mod statement;
mod value;

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::tables::{SemicolonRule, SequenceStyle, VariableStyle};
use crate::dialect::{Address, Code, Tables};
use crate::source::Span;

use super::ast::{CommentKind, Expr, Word, WordKind};
use super::expr::ExprParser;
use super::lexer::{Input, is_line_break, lex_name, lex_number, lex_paren_comment};

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
            // Verbatim arguments run to the end of the block, over comments and `$` lines.
            if verbatim_next && c != b'(' {
                rest = self.verbatim(rest);
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
                b'n' if position != Position::Body && self.tables.lower_case => {
                    let next = self.sequence(rest)?;
                    position = Position::Prefix;
                    next
                }
                b'o' if position != Position::Body && self.tables.lower_case => {
                    let next = self.program_name(rest, &rest[1..])?;
                    position = Position::Prefix;
                    next
                }
                // `OG=2` at the start of an OSP block is a word, not a program name.
                b'O' if position != Position::Body && !(self.is_osp() && starts_assignment(rest)) => {
                    let next = self.program_name(rest, &rest[1..])?;
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
                b'a'..=b'z' if self.tables.lower_case => {
                    position = Position::Body;
                    let (next, verbatim) = self.letter(rest)?;
                    verbatim_next = verbatim;
                    next
                }
                b'#' => {
                    position = Position::Body;
                    self.hash(rest)?
                }
                b',' if position == Position::Body && self.tables.has_comma_words => self.comma_word(rest)?,
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

    /// `,C1.`, `,R2.`, `,A30`: a comma word after a move's coordinates.
    fn comma_word(&mut self, input: Input<'s>) -> WordResult<'s> {
        let address = match input.get(1) {
            Some(&letter) if letter.is_ascii_uppercase() => Address::comma(letter),
            _ => return Err(self.invalid_character(input)),
        };
        if self.tables.address(address).is_none() {
            return Err(self.invalid_character(input));
        }
        self.address_value(input, &input[2..], address)
    }

    /// A byte that cannot be where it is, reported by what it is.
    fn invalid_character(&self, at: Input<'s>) -> Diagnostic {
        let c = at.first().copied().unwrap_or(b' ');
        if let Some(text) = self.plain_text(at) {
            return text;
        }
        let kind = match c {
            0 => DiagnosticKind::NulByte,
            0x80..=0xFF => DiagnosticKind::NonAsciiByte { byte: c },
            b'$' if self.tables.lexical.continuation => DiagnosticKind::OrphanContinuation,
            b'a'..=b'z' => return self.lower_case(at),
            b']' => DiagnosticKind::UnmatchedBracket,
            _ => DiagnosticKind::InvalidCharacter { found: c as char },
        };
        self.error(at, 1, kind)
    }

    /// A lower-case letter: a misread digit inside a number (`X4l.`, `l` for `1`; `o` for
    /// `0`), else a letter to write in upper case.
    pub(super) fn lower_case(&self, at: Input<'s>) -> Diagnostic {
        let c = at.first().copied().unwrap_or(b' ');
        let offset = self.offset(at) as usize;
        let before = offset.checked_sub(1).and_then(|i| self.source.get(i)).copied();
        let after = at.get(1).copied();
        let in_number = before.is_some_and(|b| b.is_ascii_digit())
            && after.is_some_and(|a| a.is_ascii_digit() || a == b'.')
            || after.is_some_and(|a| a.is_ascii_digit()) && before == Some(b'.');
        let digit = match c {
            b'l' => Some('1'),
            b'o' => Some('0'),
            _ => None,
        };
        let kind = match digit {
            Some(digit) if in_number => DiagnosticKind::LetterForDigit { found: c as char, digit },
            _ => DiagnosticKind::LowerCaseLetter { found: c as char },
        };
        self.error(at, 1, kind)
    }

    /// Words where a block belongs (`roughing pass`, `[BILLET X40 Z100`): a run of three or
    /// more letters that is no keyword, at the start of the block or after a bracket that
    /// opens nothing. Reported as text, not as damage.
    fn plain_text(&self, at: Input<'s>) -> Option<Diagnostic> {
        let start = self.offset(at) as usize;
        let line_start = self.source[..start].iter().rposition(|&c| is_line_break(c)).map_or(0, |i| i + 1);
        let head = &self.source[line_start..start];
        if !head.iter().all(|&c| c == b' ' || c == b'\t') {
            return None;
        }
        let letters_from = usize::from(at.first() == Some(&b'['));
        let word = at[letters_from..].iter().take_while(|c| c.is_ascii_alphabetic()).count();
        let lower = at.get(letters_from).is_some_and(|c| c.is_ascii_lowercase());
        let plain = word >= 3 && (lower || letters_from == 1);
        if !plain || self.tables.keyword(&at[letters_from..letters_from + word]).is_some() {
            return None;
        }
        let end = at.iter().position(|&c| is_line_break(c) || c == b'(' || c == b';').unwrap_or(at.len());
        let text = String::from_utf8_lossy(&at[..end]).trim_end().to_string();
        Some(self.error(at, text.len(), DiagnosticKind::TextOutsideComment { text }))
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
        // OSP allows block delete right after the sequence name; on Fanuc a slash anywhere but
        // at the head of the block skips the rest of the block.
        let block_delete = position == Position::Start || (position == Position::Prefix && self.is_osp());
        let position = if block_delete { Position::Start } else { Position::Body };
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

    /// `O1234`, `:0100` (Fanuc), `OSTRT` (OSP) at the start of a block; `after_o` is the text
    /// after the `O` or `:`.
    fn program_name(&mut self, input: Input<'s>, after_o: Input<'s>) -> WordResult<'s> {
        let lexical = &self.tables.lexical;
        let max = lexical.program_name_max;
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
            && !self.boundary(c)
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
}

/// Whether the text starts with a name followed by `=` or `[` (`OG=2`, `VTOFX[1]=`).
fn starts_assignment(input: &[u8]) -> bool {
    lex_name(input).is_ok_and(|(after, _)| matches!(after.first(), Some(b'=' | b'[')))
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
