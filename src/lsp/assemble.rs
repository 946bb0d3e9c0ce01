//! Splicing chunks back into one [`Program`]: every span moves by the chunk's start, every
//! word, expression and command index by the number of its kind in the chunks before
//! (`syntax::relocate`).

use crate::dialect::DialectConfig;
use crate::source::Span;
use crate::syntax::relocate::{self, Bases};
use crate::syntax::{Block, Program, Statement, Word};

use super::chunk::Chunk;

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
        later_words: Vec::new(),
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
        program.blocks.extend(part.blocks.iter().map(|b| relocate::block(b, bases)));
        program.words.extend(
            part.words
                .iter()
                .map(|w| Word { span: relocate::span(w.span, bases), kind: relocate::word(w.kind, bases) }),
        );
        program.exprs.extend(part.exprs.iter().map(|e| relocate::expr(e, bases)));
        program.commands.extend(part.commands.iter().map(|c| relocate::command(c, bases)));
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
