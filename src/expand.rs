//! `turnpass expand`: every cycle replaced by the explicit `G00`/`G01`/`G02`/`G03` blocks it
//! performs, in the program's own dialect and style, all other blocks untouched.
//!
//! The moves come from lowering without nose-radius compensation, so they are the
//! programmed contour, and the printed blocks stay under the program's own `G41`/`G42`.
//! This module decides which calls are replaced and which blocks go with them; the back end
//! writes the blocks (`back::cycle_blocks`: coordinates back through the program's frame on
//! its least increment, motion codes and F where they change, arcs in the program's form).

use crate::back::{CycleBlocks, cycle_blocks};
use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::printer::{Edits, ProgramStyle};
use crate::semantic::Lowered;
use crate::syntax::{Program, Statement};
use crate::toolpath::{Compensation, Validated};

/// Edits that replace each cycle call with its moves (and delete the blocks it consumed).
/// On a control with no thread move (OSP) a thread pass is written as a single-pass cycle
/// block (`back/cycle/thread_pass.rs`); a cycle whose thread moves are not such passes stays as
/// it is, with a note.
pub fn expansion_edits(program: &Program<'_>, lowered: &Validated<Lowered>) -> (Edits, Vec<Diagnostic>) {
    let mut edits = Edits::new();
    let mut notes = Vec::new();
    let calls: std::collections::HashSet<usize> = lowered.expansions.iter().map(|e| e.block).collect();
    // Read from every block once: the blocks of every cycle are written in it, and the
    // printer writes them in it.
    let style = ProgramStyle::infer(program);
    edits.write_in(style.clone());
    for expansion in &lowered.expansions {
        let moves = &lowered.toolpath.moves[expansion.moves.clone()];
        let start = lowered.toolpath.start_of(expansion.moves.start);
        // The compensation in effect when the cycle starts: the written blocks switch it
        // where the cycle's moves do (a G70 profile's own G41/G42/G40).
        let compensation_before = expansion
            .moves
            .start
            .checked_sub(1)
            .and_then(|k| lowered.toolpath.moves.get(k))
            .map_or(Compensation::Off, |m| m.compensation);
        let shift = lowered.coordinates_at(expansion.moves.start).shift;
        match cycle_blocks(program, expansion, moves, start, compensation_before, shift, &style) {
            CycleBlocks::Keep => {}
            CycleBlocks::Blocks(blocks) => {
                edits.replace(expansion.block, blocks);
                delete_consumed(&mut edits, program, expansion, &calls);
                if let Some(note) = &expansion.note {
                    notes.push(Diagnostic::note(note.clone(), program.block(expansion.block).span));
                }
            }
            CycleBlocks::NotExpandable(reason) => {
                let span = program.block(expansion.block).span;
                notes.push(Diagnostic::note(DiagnosticKind::NotExpandable { reason }, span));
            }
        }
    }
    (edits, notes)
}

/// Delete the blocks a cycle consumed; a block that is itself a cycle call keeps its own
/// expansion.
pub(crate) fn delete_consumed(
    edits: &mut Edits,
    program: &Program<'_>,
    expansion: &crate::semantic::Expansion,
    calls: &std::collections::HashSet<usize>,
) {
    for &consumed in &expansion.consumed {
        if !calls.contains(&consumed) && program.block(consumed).statement != Statement::Invalid {
            edits.delete(consumed);
        }
    }
}
