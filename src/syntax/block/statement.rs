//! Statements that begin with a keyword (`IF`, `GOTO`, `CALL`, `WHILE`, graphics
//! statements …) and assignments (`FLAN=318`, `VTOFX[16]=…`, `#1=…`).

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::tables::{KeywordArgs, KeywordKind};
use crate::syntax::ast::WordKind;
use crate::syntax::lexer::{Input, is_line_break, lex_name, lex_spaces};

use super::{BlockParser, WordResult, osp_name};

impl<'s> BlockParser<'_, 's> {
    /// A keyword at this position. Returns `None` when the letters are not a keyword.
    pub(super) fn keyword(&mut self, input: Input<'s>) -> Result<Option<(Input<'s>, bool)>, Diagnostic> {
        let Ok((after_letters, letters)) = crate::syntax::lexer::lex_letters(input) else { return Ok(None) };
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
    pub(super) fn foreign_assignment(&self, input: Input<'s>, name: &[u8]) -> Diagnostic {
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
    pub(super) fn foreign_keyword(&self, input: Input<'s>, name: &[u8]) -> Option<Diagnostic> {
        const OSP_ONLY: [&[u8]; 4] = [b"CALL", b"RTS", b"MODIN", b"MODOUT"];
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
    pub(super) fn condition(&mut self, input: Input<'s>) -> WordResult<'s> {
        let start = lex_spaces(input).map_or(input, |(r, _)| r);
        if start.first() != Some(&b'[') {
            return Err(self.error(start, 1, DiagnosticKind::MalformedExpression { expected: "`[` and a condition" }));
        }
        let (rest, expr) = self.exprs(false).bracketed(start)?;
        self.push(start, rest, WordKind::Operand { expr });
        Ok(rest)
    }

    /// The target of `GOTO`: an OSP `N` name, or a Fanuc number or expression.
    pub(super) fn jump_target(&mut self, input: Input<'s>) -> WordResult<'s> {
        let start = lex_spaces(input).map_or(input, |(r, _)| r);
        if self.is_osp() {
            if start.first() != Some(&b'N') {
                return Err(self.error(start, 1, DiagnosticKind::MissingSequenceName));
            }
            return self.label(start);
        }
        self.loop_number(start)
    }

    /// Fanuc `DO1`, `END1`: the loop number (and the operand of a Fanuc `GOTO`).
    pub(super) fn loop_number(&mut self, input: Input<'s>) -> WordResult<'s> {
        let start = lex_spaces(input).map_or(input, |(r, _)| r);
        let (rest, expr) = self.exprs(false).operand(start)?;
        self.push(start, rest, WordKind::Operand { expr });
        Ok(rest)
    }

    /// OSP `CALL OSUB`, `MODIN OINT1`: the program name.
    pub(super) fn call_target(&mut self, input: Input<'s>) -> WordResult<'s> {
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
    pub(super) fn verbatim(&mut self, input: Input<'s>) -> Input<'s> {
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
    pub(super) fn osp_name_word(&mut self, input: Input<'s>) -> WordResult<'s> {
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
    pub(super) fn hash(&mut self, input: Input<'s>) -> WordResult<'s> {
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
