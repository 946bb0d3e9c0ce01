//! Expressions: OSP `X=FLAN+5`, `IF [FIX[VC2/7000] EQ 1]`, Fanuc `X[#504+6.]`, `#1=#2*SIN[30]`.
//!
//! Precedence climbing over three levels (comparisons, then `+ - OR XOR EOR`, then
//! `* / AND MOD`) with unary `- + NOT`. Nesting is bounded by the dialect's `max_depth`, so
//! `[[[[…` 100 000 deep is a diagnostic, not a stack overflow.
//!
//! Outside brackets an OSP value ends at a space (`X=BDIA-1.5 A-150` is two words) and at
//! anything that cannot continue it (`VTOFX[6]VTOFZ[16]=…` is two assignments); inside
//! brackets spaces separate tokens (`[VC1 EQ 20]`).

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::Tables;
use crate::dialect::tables::VariableStyle;
use crate::source::Span;

use super::ast::{BinaryOp, Expr, ExprId, ExprKind, UnaryOp, Variable};
use super::lexer::{Input, lex_digits, lex_name, lex_number, lex_spaces};

pub(super) struct ExprParser<'a, 's> {
    pub source: &'s [u8],
    pub tables: &'static Tables,
    pub exprs: &'a mut Vec<Expr>,
    /// Whether a space at bracket depth 0 ends the expression (OSP word values).
    pub space_ends: bool,
    depth: usize,
    brackets: usize,
}

type ExprResult<'s, T> = Result<(Input<'s>, T), Diagnostic>;

impl<'a, 's> ExprParser<'a, 's> {
    pub fn new(source: &'s [u8], tables: &'static Tables, exprs: &'a mut Vec<Expr>, space_ends: bool) -> Self {
        ExprParser { source, tables, exprs, space_ends, depth: 0, brackets: 0 }
    }

    fn offset(&self, input: Input<'s>) -> u32 {
        (input.as_ptr() as usize - self.source.as_ptr() as usize) as u32
    }

    fn span_between(&self, from: Input<'s>, to: Input<'s>) -> Span {
        Span::new(self.offset(from), self.offset(to))
    }

    fn push(&mut self, span: Span, kind: ExprKind) -> ExprId {
        self.exprs.push(Expr { span, kind });
        (self.exprs.len() - 1) as ExprId
    }

    fn skip_spaces(&self, input: Input<'s>) -> Input<'s> {
        if self.brackets == 0 && self.space_ends {
            return input;
        }
        match lex_spaces(input) {
            Ok((rest, _)) => rest,
            Err(_) => input,
        }
    }

    fn error_at(&self, input: Input<'s>, kind: DiagnosticKind) -> Diagnostic {
        let start = self.offset(input);
        let end = if input.is_empty() { start } else { start + 1 };
        Diagnostic::error(kind, Span::new(start, end))
    }

    /// A whole expression.
    pub fn expression(&mut self, input: Input<'s>) -> ExprResult<'s, ExprId> {
        self.binary(input, 1)
    }

    /// One operand with an optional sign: the value of a Fanuc word (`X[#1+2]`, `X#1`, `X-#1`).
    pub fn operand(&mut self, input: Input<'s>) -> ExprResult<'s, ExprId> {
        self.unary(input)
    }

    /// A bracketed expression starting at `[`, returned as a `Group` node.
    pub fn bracketed(&mut self, input: Input<'s>) -> ExprResult<'s, ExprId> {
        self.primary(input)
    }

    fn binary(&mut self, input: Input<'s>, min_precedence: u8) -> ExprResult<'s, ExprId> {
        let (mut rest, mut lhs) = self.unary(input)?;
        loop {
            let after_space = self.skip_spaces(rest);
            let Some((after_op, op)) = self.operator(after_space) else { break };
            if op.precedence() < min_precedence {
                break;
            }
            let after_op = self.skip_spaces(after_op);
            let (after_rhs, rhs) = self.binary(after_op, op.precedence() + 1)?;
            let span = self.exprs[lhs as usize].span.merge(self.exprs[rhs as usize].span);
            lhs = self.push(span, ExprKind::Binary { op, lhs, rhs });
            rest = after_rhs;
        }
        Ok((rest, lhs))
    }

    fn operator(&self, input: Input<'s>) -> Option<(Input<'s>, BinaryOp)> {
        let (&c, tail) = input.split_first()?;
        let symbol = match c {
            b'+' => Some(BinaryOp::Add),
            b'-' => Some(BinaryOp::Sub),
            b'*' => Some(BinaryOp::Mul),
            b'/' => Some(BinaryOp::Div),
            _ => None,
        };
        if let Some(op) = symbol {
            return Some((tail, op));
        }
        // Word operators need brackets around them (or a Fanuc statement), never a bare OSP value.
        if self.brackets == 0 && self.space_ends {
            return None;
        }
        let (rest, name) = super::lexer::lex_letters(input).ok()?;
        let rules = &self.tables.expression;
        let is = |list: &Vec<String>| list.iter().any(|w| w.as_bytes() == name);
        let op = match name {
            b"EQ" => BinaryOp::Eq,
            b"NE" => BinaryOp::Ne,
            b"GT" => BinaryOp::Gt,
            b"GE" => BinaryOp::Ge,
            b"LT" => BinaryOp::Lt,
            b"LE" => BinaryOp::Le,
            b"AND" if is(&rules.logic) => BinaryOp::And,
            b"OR" if is(&rules.logic) => BinaryOp::Or,
            b"XOR" | b"EOR" if is(&rules.logic) => BinaryOp::Xor,
            b"MOD" if is(&rules.arithmetic_words) => BinaryOp::Mod,
            _ => return None,
        };
        if !is(&rules.comparisons) && op.precedence() == 1 {
            return None;
        }
        Some((rest, op))
    }

    fn enter(&mut self, at: Input<'s>) -> Result<(), Diagnostic> {
        self.depth += 1;
        let max = self.tables.expression.max_depth;
        if self.depth > max {
            return Err(self.error_at(at, DiagnosticKind::ExpressionTooDeep { max }));
        }
        Ok(())
    }

    fn unary(&mut self, input: Input<'s>) -> ExprResult<'s, ExprId> {
        let op = match input.first() {
            Some(b'-') => Some((UnaryOp::Minus, 1)),
            Some(b'+') => Some((UnaryOp::Plus, 1)),
            Some(b'N')
                if input.starts_with(b"NOT")
                    && !input.get(3).is_some_and(u8::is_ascii_alphanumeric)
                    && !(self.brackets == 0 && self.space_ends)
                    && self.tables.expression.logic.iter().any(|w| w == "NOT") =>
            {
                Some((UnaryOp::Not, 3))
            }
            _ => None,
        };
        let Some((op, len)) = op else { return self.primary(input) };
        // A signed literal is one number node, as written (`-1.5`), not a negation.
        if op != UnaryOp::Not
            && let Ok((rest, raw)) = lex_number(input)
            && raw.has_digits()
        {
            return self.literal(input, rest, raw);
        }
        self.enter(input)?;
        let operand_start = self.skip_spaces(&input[len..]);
        let (rest, operand) = self.unary(operand_start)?;
        self.depth -= 1;
        let span = Span::new(self.offset(input), self.exprs[operand as usize].span.end);
        Ok((rest, self.push(span, ExprKind::Unary { op, operand })))
    }

    fn literal(
        &mut self,
        start: Input<'s>,
        rest: Input<'s>,
        raw: super::lexer::RawNumber<'s>,
    ) -> ExprResult<'s, ExprId> {
        let span = self.span_between(start, rest);
        let Some(number) = raw.to_number() else {
            return Err(Diagnostic::error(
                DiagnosticKind::NumberOutOfRange {
                    address: "value".into(),
                    digits: raw.significant_digits(),
                    max_digits: 18,
                },
                span,
            ));
        };
        Ok((rest, self.push(span, ExprKind::Number(number))))
    }

    fn primary(&mut self, input: Input<'s>) -> ExprResult<'s, ExprId> {
        let Some(&c) = input.first() else {
            return Err(self.error_at(input, DiagnosticKind::MalformedExpression { expected: "a value" }));
        };
        match c {
            b'[' => {
                self.enter(input)?;
                self.brackets += 1;
                let inner_start = lex_spaces(&input[1..]).map_or(&input[1..], |(r, _)| r);
                let (after, inner) = self.expression(inner_start)?;
                let after = lex_spaces(after).map_or(after, |(r, _)| r);
                self.brackets -= 1;
                self.depth -= 1;
                match after.first() {
                    Some(b']') => {
                        let rest = &after[1..];
                        let span = self.span_between(input, rest);
                        Ok((rest, self.push(span, ExprKind::Group(inner))))
                    }
                    Some(_) => {
                        Err(self
                            .error_at(after, DiagnosticKind::MalformedExpression { expected: "`]` or an operator" }))
                    }
                    None => Err(self.error_at(input, DiagnosticKind::UnclosedBracket)),
                }
            }
            b'0'..=b'9' | b'.' => match lex_number(input) {
                Ok((rest, raw)) if raw.has_digits() => self.literal(input, rest, raw),
                _ => Err(self.error_at(input, DiagnosticKind::MalformedExpression { expected: "digits" })),
            },
            b'#' if self.tables.lexical.variables == VariableStyle::Hash => self.hash_variable(input),
            b'A'..=b'Z' => self.name(input),
            b']' => Err(self.error_at(input, DiagnosticKind::MalformedExpression { expected: "a value before `]`" })),
            _ => Err(self.error_at(input, DiagnosticKind::MalformedExpression { expected: "a value" })),
        }
    }

    /// Fanuc `#501`, `#[#1+2]`.
    pub fn hash_variable(&mut self, input: Input<'s>) -> ExprResult<'s, ExprId> {
        let after_hash = &input[1..];
        let (rest, index) = match after_hash.first() {
            Some(b'[') => self.primary(after_hash)?,
            Some(b'0'..=b'9') => {
                let (rest, digits) = lex_digits(after_hash).map_err(|_| {
                    self.error_at(after_hash, DiagnosticKind::MalformedExpression { expected: "a variable number" })
                })?;
                let (_, raw) = lex_number(digits).map_err(|_| {
                    self.error_at(after_hash, DiagnosticKind::MalformedExpression { expected: "a variable number" })
                })?;
                self.literal(digits, rest, raw)?
            }
            _ => {
                return Err(self.error_at(
                    after_hash,
                    DiagnosticKind::MalformedExpression { expected: "a variable number after `#`" },
                ));
            }
        };
        let span = self.span_between(input, rest);
        Ok((rest, self.push(span, ExprKind::Variable(Variable::Hash { index }))))
    }

    fn name(&mut self, input: Input<'s>) -> ExprResult<'s, ExprId> {
        let Ok((rest, name)) = lex_name(input) else {
            return Err(self.error_at(input, DiagnosticKind::MalformedExpression { expected: "a value" }));
        };
        if let Some(function) = self.tables.function_index(name)
            && rest.first() == Some(&b'[')
        {
            return self.call(input, rest, function as u8);
        }
        if self.tables.lexical.variables == VariableStyle::Hash {
            return Err(self.error_at(
                input,
                DiagnosticKind::MalformedExpression { expected: "a value (`#n`, a number or a function)" },
            ));
        }
        self.osp_variable(input, rest, name)
    }

    /// An OSP variable read in an expression, or the target of an assignment.
    pub fn osp_variable(&mut self, start: Input<'s>, rest: Input<'s>, name: &[u8]) -> ExprResult<'s, ExprId> {
        let name_span = self.span_between(start, rest);
        if name.len() > 1 && name[0] == b'V' && name[1..].iter().all(u8::is_ascii_digit) {
            let number = std::str::from_utf8(&name[1..]).ok().and_then(|s| s.parse::<u32>().ok());
            if let Some(number) = number {
                return Ok((rest, self.push(name_span, ExprKind::Variable(Variable::Common(number)))));
            }
        }
        if rest.first() == Some(&b'[') {
            self.enter(rest)?;
            self.brackets += 1;
            let inner_start = lex_spaces(&rest[1..]).map_or(&rest[1..], |(r, _)| r);
            let (after, index) = self.expression(inner_start)?;
            let after = lex_spaces(after).map_or(after, |(r, _)| r);
            self.brackets -= 1;
            self.depth -= 1;
            return match after.first() {
                Some(b']') => {
                    let end = &after[1..];
                    let span = self.span_between(start, end);
                    Ok((end, self.push(span, ExprKind::Variable(Variable::Indexed { name: name_span, index }))))
                }
                _ => Err(self.error_at(rest, DiagnosticKind::UnclosedBracket)),
            };
        }
        Ok((rest, self.push(name_span, ExprKind::Variable(Variable::Named))))
    }

    fn call(&mut self, start: Input<'s>, open: Input<'s>, function: u8) -> ExprResult<'s, ExprId> {
        self.enter(open)?;
        self.brackets += 1;
        let mut args = [0 as ExprId; 2];
        let mut arg_count = 0u8;
        let mut cursor = lex_spaces(&open[1..]).map_or(&open[1..], |(r, _)| r);
        loop {
            let (after, arg) = self.expression(cursor)?;
            if (arg_count as usize) < args.len() {
                args[arg_count as usize] = arg;
                arg_count += 1;
            } else {
                return Err(
                    self.error_at(cursor, DiagnosticKind::MalformedExpression { expected: "at most two arguments" })
                );
            }
            let after = lex_spaces(after).map_or(after, |(r, _)| r);
            match after.first() {
                Some(b',') => cursor = lex_spaces(&after[1..]).map_or(&after[1..], |(r, _)| r),
                Some(b']') => {
                    let end = &after[1..];
                    self.brackets -= 1;
                    self.depth -= 1;
                    let span = self.span_between(start, end);
                    return Ok((end, self.push(span, ExprKind::Call { function, args, arg_count })));
                }
                Some(_) => {
                    return Err(self.error_at(after, DiagnosticKind::MalformedExpression { expected: "`,` or `]`" }));
                }
                None => return Err(self.error_at(open, DiagnosticKind::UnclosedBracket)),
            }
        }
    }
}
