//! Splicing chunks back into one [`Program`]: every span moves by the chunk's start, every
//! word, expression and command index by the number of its kind in the chunks before.
//!
//! The matches below name every variant on purpose: a new AST node that holds an index
//! must be relocated here, and the compiler says so.

use crate::dialect::DialectConfig;
use crate::source::Span;
use crate::syntax::{Block, Command, Expr, ExprKind, Param, Program, Statement, Variable, Word, WordKind};

use super::chunk::{Chunk, shifted};

/// How far a chunk's nodes move.
#[derive(Clone, Copy)]
struct Bases {
    offset: u32,
    word: u32,
    expr: u32,
    command: u32,
}

pub(crate) fn program<'a, 'c>(
    text: &'a [u8],
    config: DialectConfig,
    chunks: impl Iterator<Item = (&'c Chunk, u32)> + Clone,
) -> Program<'a> {
    let total = |count: fn(&Chunk) -> usize| chunks.clone().map(|(c, _)| count(c)).sum::<usize>();
    let mut program = Program {
        source: text,
        config,
        blocks: Vec::with_capacity(total(|c| c.part.blocks.len()) + 1),
        words: Vec::with_capacity(total(|c| c.part.words.len())),
        exprs: Vec::with_capacity(total(|c| c.part.exprs.len())),
        commands: Vec::with_capacity(total(|c| c.part.commands.len())),
    };
    let mut trailing = None;
    for (chunk, offset) in chunks {
        let part = &chunk.part;
        let bases = Bases {
            offset,
            word: program.words.len() as u32,
            expr: program.exprs.len() as u32,
            command: program.commands.len() as u32,
        };
        program.blocks.extend(part.blocks.iter().map(|b| block(b, bases)));
        program
            .words
            .extend(part.words.iter().map(|w| Word { span: shifted(w.span, offset), kind: word(w.kind, bases) }));
        program.exprs.extend(part.exprs.iter().map(|e| expr(e, bases)));
        program.commands.extend(part.commands.iter().map(|c| command(c, bases)));
        if let Some(from) = part.trailing_from {
            trailing = Some(offset + from as u32);
        }
    }
    // The text after the closing `%` is one block to the end, whatever chunks it spans.
    if let Some(from) = trailing
        && (from as usize) < text.len()
    {
        let span = Span::new(from, text.len() as u32);
        program.blocks.push(Block { span, statement: Statement::Trailing, first_word: 0, word_count: 0 });
    }
    program
}

fn block(block: &Block, bases: Bases) -> Block {
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
        | Statement::Trailing) => other,
    };
    Block {
        span: shifted(block.span, bases.offset),
        statement,
        first_word: block.first_word + bases.word,
        word_count: block.word_count,
    }
}

fn word(kind: WordKind, bases: Bases) -> WordKind {
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

fn expr(node: &Expr, bases: Bases) -> Expr {
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
            ExprKind::Variable(Variable::Indexed { name: shifted(name, bases.offset), index: id(index) })
        }
        ExprKind::Variable(Variable::Hash { index }) => ExprKind::Variable(Variable::Hash { index: id(index) }),
        other @ (ExprKind::Number(_) | ExprKind::Variable(Variable::Common(_) | Variable::Named)) => other,
    };
    Expr { span: shifted(node.span, bases.offset), kind }
}

fn command(command: &Command, bases: Bases) -> Command {
    Command {
        code_word: command.code_word + bases.word,
        schema: command.schema,
        form: command.form,
        params: command.params.iter().map(|p| Param { role: p.role, word: p.word + bases.word }).collect(),
    }
}
