//! Go to definition: from a word that names a block to that block.
//!
//! - `P20`/`Q30` of a cycle (its profile's first and last block): every block with that
//!   sequence number (more than one is an error the semantic pass reports);
//! - `N0207` of a LAP call: the `G81`/`G82`/`G83` block of that name, searched as the
//!   control searches (the first after the call, else the first from the top);
//! - `GOTO NAT00`, `IF […] NAT00`, Fanuc `GOTO 100`: the block the jump lands on (the first
//!   after the jump, else the first from the top);
//! - `CALL OSUB`, `MODIN OSUB`, `M98 P1000`: the block that names the program.
//!
//! Names compare as the semantic pass compares them (`semantic::labels`): by value on Fanuc
//! (`N01` is `N1`), as text on OSP (`N0207` is not `N207`).

use crate::dialect::{Address, GFunction, KeywordKind, Role, Tables};
use crate::semantic::labels;
use crate::source::Span;
use crate::syntax::{CodeLetter, ExprKind, Statement, WordKind};

use super::document::{BlockRef, Document};

/// What a word refers to.
enum Target {
    /// Every block with this sequence key.
    Sequence(String),
    /// The block a jump from `from` lands on.
    Jump {
        key: String,
        from: u32,
    },
    /// The contour a LAP call at `from` names.
    Contour {
        key: String,
        from: u32,
    },
    Program(String),
}

/// The spans of the blocks the word at byte `offset` refers to (none when it refers to
/// nothing, or to no block of this file).
pub fn definition(document: &Document, offset: usize) -> Vec<Span> {
    let Some(block) = document.block_at(offset) else { return Vec::new() };
    let Some((id, word)) = block.word_at(offset) else { return Vec::new() };
    let dialect = document.config().dialect;
    let tables = document.config().tables();
    let from = block.absolute(block.block().span).start;
    let parameter = block.command().and_then(|c| c.params.iter().find(|p| p.word == id)).map(|p| p.role);
    let target = match word.kind {
        WordKind::Number { number, .. } if matches!(parameter, Some(Role::ProfileStart | Role::ProfileEnd)) => {
            Target::Sequence(whole_key(number.to_f64()))
        }
        WordKind::Number { address, number } if address == Address::P && calls_subprogram(&block, tables) => {
            Target::Program(whole_key(number.to_f64()))
        }
        WordKind::Label { number } => {
            let key = labels::key(dialect, block.text(word.span), number);
            if matches!(block.block().statement, Statement::LapCall(_)) {
                Target::Contour { key, from }
            } else {
                Target::Jump { key, from }
            }
        }
        WordKind::Operand { expr } if is_jump(&block, tables) => match block.expr(expr).map(|e| e.kind) {
            Some(ExprKind::Number(number)) => Target::Jump { key: whole_key(number.to_f64()), from },
            _ => return Vec::new(),
        },
        WordKind::ProgramRef => Target::Program(labels::program_key(dialect, block.text(word.span))),
        _ => return Vec::new(),
    };
    find(document, &target)
}

/// The key of a sequence or program number given as a value (`P20`, `GOTO 100`), as the
/// semantic pass forms it.
fn whole_key(value: f64) -> String {
    (value.round() as i64).to_string()
}

/// Whether the block calls a subprogram with an M code (`M98 P1000`), so that its `P` names it.
fn calls_subprogram(block: &BlockRef<'_>, tables: &Tables) -> bool {
    block.words().iter().any(|w| match w.kind {
        WordKind::Code { letter: CodeLetter::M, code } => tables.m_functions.subprogram_call.contains(&code.major()),
        _ => false,
    })
}

/// Whether the block jumps (`GOTO`, `IF … GOTO`), so that its number operand is a target.
fn is_jump(block: &BlockRef<'_>, tables: &Tables) -> bool {
    block.words().iter().any(|w| match w.kind {
        WordKind::Keyword { index } => tables.keyword_info(index as usize).kind == KeywordKind::Goto,
        _ => false,
    })
}

/// Whether the block starts a LAP contour (or blank): `G81`, `G82`, `G83`.
pub(super) fn starts_contour(block: &BlockRef<'_>, tables: &Tables) -> bool {
    matches!(block.block().statement, Statement::LapMarker(_))
        && block.words().iter().any(|w| match w.kind {
            WordKind::Code { letter: CodeLetter::G, code } => matches!(
                tables.g(code).and_then(|g| g.function),
                Some(GFunction::LapContourLongitudinal | GFunction::LapContourTransverse | GFunction::LapBlank)
            ),
            _ => false,
        })
}

fn find(document: &Document, target: &Target) -> Vec<Span> {
    let dialect = document.config().dialect;
    let tables = document.config().tables();
    // The span of every block the key names, and whether it starts a contour.
    let mut named: Vec<(Span, bool)> = Vec::new();
    for block in document.blocks() {
        if block.block().statement == Statement::Invalid {
            continue;
        }
        for word in block.words() {
            let matches = match (&word.kind, target) {
                (
                    WordKind::Sequence { number },
                    Target::Sequence(key) | Target::Jump { key, .. } | Target::Contour { key, .. },
                ) => labels::key(dialect, block.text(word.span), *number) == *key,
                (WordKind::ProgramName, Target::Program(key)) => {
                    labels::program_key(dialect, block.text(word.span)) == *key
                }
                _ => false,
            };
            if matches {
                named.push((block.absolute(block.block().span), starts_contour(&block, tables)));
            }
        }
    }
    let after_or_first = |candidates: Vec<Span>, from: u32| -> Vec<Span> {
        candidates
            .iter()
            .copied()
            .find(|s| s.start > from)
            .or_else(|| candidates.first().copied())
            .into_iter()
            .collect()
    };
    match target {
        Target::Sequence(_) => named.into_iter().map(|(span, _)| span).collect(),
        Target::Jump { from, .. } => after_or_first(named.into_iter().map(|(span, _)| span).collect(), *from),
        Target::Contour { from, .. } => {
            let contours: Vec<Span> = named.iter().filter(|(_, c)| *c).map(|(s, _)| *s).collect();
            if contours.is_empty() {
                // No contour block has the name: show what has it; the diagnostic says the rest.
                named.into_iter().map(|(span, _)| span).collect()
            } else {
                after_or_first(contours, *from)
            }
        }
        Target::Program(_) => named.into_iter().map(|(span, _)| span).take(1).collect(),
    }
}
