//! Moving a run of lines parsed on its own to its place in a larger program: every span by
//! the run's start in the text, every word, expression and command index by the number of
//! its kind in the runs before. The language server splices its chunks back into one
//! program this way (`crate::lsp::assemble`), and `parse` joins the two halves of a large
//! program it parsed on two threads.
//!
//! The matches below name every variant on purpose: a new AST node that holds an index
//! must be relocated here, and the compiler says so.

use crate::source::Span;

use super::ast::{Block, Command, Expr, ExprKind, Param, Statement, Variable, WordKind};

/// How far a run's nodes move.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Bases {
    /// Bytes, for spans.
    pub offset: u32,
    pub word: u32,
    pub expr: u32,
    pub command: u32,
}

pub(crate) fn span(span: Span, bases: Bases) -> Span {
    Span::new(span.start + bases.offset, span.end + bases.offset)
}

pub(crate) fn block(block: &Block, bases: Bases) -> Block {
    let command = |id: u32| id + bases.command;
    let statement = match block.statement {
        Statement::Cycle(id) => Statement::Cycle(command(id)),
        Statement::LapCall(id) => Statement::LapCall(command(id)),
        Statement::LapMarker(id) => Statement::LapMarker(command(id)),
        Statement::Dwell(id) => Statement::Dwell(command(id)),
        Statement::OneShot(id) => Statement::OneShot(command(id)),
        other @ (Statement::Empty
        | Statement::TapeMark
        | Statement::Header
        | Statement::ProgramName
        | Statement::Motion
        | Statement::ThreadMove
        | Statement::ToolCall
        | Statement::Spindle
        | Statement::Control
        | Statement::Assignment
        | Statement::Graphics
        | Statement::Pattern
        | Statement::Settings
        | Statement::Invalid
        | Statement::Trailing
        | Statement::Leader) => other,
    };
    Block {
        span: span(block.span, bases),
        statement,
        first_word: block.first_word + bases.word,
        word_count: block.word_count,
    }
}

/// A word's kind: only the expression indexes it holds move (its span is the caller's).
pub(crate) fn word(kind: WordKind, bases: Bases) -> WordKind {
    let expr = |id: u32| id + bases.expr;
    match kind {
        WordKind::Expr { address, expr: id } => WordKind::Expr { address, expr: expr(id) },
        WordKind::Operand { expr: id } => WordKind::Operand { expr: expr(id) },
        WordKind::Assign { target, value } => WordKind::Assign { target: expr(target), value: expr(value) },
        other @ (WordKind::Sequence { .. }
        | WordKind::BlockDelete { .. }
        | WordKind::OptionalSkip { .. }
        | WordKind::TapeMark
        | WordKind::Header
        | WordKind::ProgramName
        | WordKind::Comment(_)
        | WordKind::Code { .. }
        | WordKind::Number { .. }
        | WordKind::Label { .. }
        | WordKind::ProgramRef
        | WordKind::Keyword { .. }
        | WordKind::Verbatim) => other,
    }
}

pub(crate) fn expr(node: &Expr, bases: Bases) -> Expr {
    let id = |id: u32| id + bases.expr;
    let kind = match node.kind {
        ExprKind::Unary { op, operand } => ExprKind::Unary { op, operand: id(operand) },
        ExprKind::Binary { op, lhs, rhs } => ExprKind::Binary { op, lhs: id(lhs), rhs: id(rhs) },
        ExprKind::Call { function, mut args, arg_count } => {
            // Unused argument slots hold 0 as the parser leaves them, not an index.
            for arg in args.iter_mut().take(arg_count as usize) {
                *arg = id(*arg);
            }
            ExprKind::Call { function, args, arg_count }
        }
        ExprKind::Group(inner) => ExprKind::Group(id(inner)),
        ExprKind::Variable(Variable::Indexed { name, index }) => {
            ExprKind::Variable(Variable::Indexed { name: span(name, bases), index: id(index) })
        }
        ExprKind::Variable(Variable::Hash { index }) => ExprKind::Variable(Variable::Hash { index: id(index) }),
        other @ (ExprKind::Number(_) | ExprKind::Variable(Variable::Common(_) | Variable::Named)) => other,
    };
    Expr { span: span(node.span, bases), kind }
}

pub(crate) fn command(command: &Command, bases: Bases) -> Command {
    Command {
        code_word: command.code_word + bases.word,
        schema: command.schema,
        form: command.form,
        params: command.params.iter().map(|p| Param { role: p.role, word: p.word + bases.word }).collect(),
    }
}
