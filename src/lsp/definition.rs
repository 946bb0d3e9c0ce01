//! Go to definition: from a word that names a block to that block.
//!
//! - `P20`/`Q30` of a cycle (its profile's first and last block): every block with that
//!   sequence number (more than one is an error the semantic pass reports);
//! - `N0207` of a LAP call: the `G81`/`G82`/`G83` block of that name, searched as the
//!   control searches (the first after the call, else the first from the top);
//! - `GOTO NAT00`, `IF […] NAT00`, Fanuc `GOTO 100`, `M99 P100`: the block the jump lands on
//!   (the first after the jump, else the first from the top);
//! - `CALL OSUB`, `MODIN OSUB`, `M98 P1000`: the block that names the program, in this file
//!   or, when it holds none, in a program file of the same folder (the server looks there).
//!
//! A block with a typo is still found by its name (`names.rs`).

use crate::dialect::{Address, Tables};
use crate::semantic::labels;
use crate::source::Span;
use crate::syntax::{CodeLetter, Statement, WordKind};

use super::document::{BlockRef, Document};
use super::names;

/// Where a word's definition is.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Definition {
    /// Blocks of this document (none when the word names nothing).
    Here(Vec<Span>),
    /// A program this document does not hold, by its key (`labels::program_key`).
    Program(String),
}

/// The definition of the word at byte `offset`.
pub fn definition(document: &Document, offset: usize) -> Definition {
    if let Some(name) = names::at(document, offset) {
        let all = names::all(document);
        return Definition::Here(names::definitions(&all, &name).into_iter().map(|n| n.block).collect());
    }
    let Some(block) = document.block_at(offset) else { return Definition::Here(Vec::new()) };
    let Some((_, word)) = block.word_at(offset) else { return Definition::Here(Vec::new()) };
    let dialect = document.config().dialect;
    let key = match word.kind {
        WordKind::Number { address: Address::P, number } if calls_subprogram(&block, document.config().tables()) => {
            names::whole_key(number.to_f64())
        }
        WordKind::ProgramRef => labels::program_key(dialect, block.text(word.span)),
        _ => return Definition::Here(Vec::new()),
    };
    match program(document, &key) {
        Some(span) => Definition::Here(vec![span]),
        None => Definition::Program(key),
    }
}

/// The block that names program `key` (`O1000`, `OSUB`), the first if several do.
pub fn program(document: &Document, key: &str) -> Option<Span> {
    let dialect = document.config().dialect;
    document.blocks().filter(|b| b.block().statement == Statement::ProgramName).find_map(|block| {
        block
            .words()
            .iter()
            .filter(|w| matches!(w.kind, WordKind::ProgramName))
            .any(|w| labels::program_key(dialect, block.text(w.span)) == key)
            .then(|| block.absolute(block.block().span))
    })
}

/// Whether the block calls a subprogram with an M code (`M98 P1000`), so that its `P` names it.
fn calls_subprogram(block: &BlockRef<'_>, tables: &Tables) -> bool {
    block.words().iter().any(|w| match w.kind {
        WordKind::Code { letter: CodeLetter::M, code } => tables.m_functions.subprogram_call.contains(&code.major()),
        _ => false,
    })
}
