//! `turnpass expand`: every cycle replaced by the explicit `G00`/`G01`/`G02`/`G03` blocks it
//! performs, in the program's own dialect and style, all other blocks untouched.
//!
//! The moves come from lowering without nose-radius compensation, so they are the
//! programmed contour, and the printed blocks stay under the program's own `G41`/`G42`.
//! This module decides which calls are replaced and which blocks go with them; the back end
//! writes the blocks (`back::cycle_blocks`: coordinates back through the program's frame on
//! its least increment, motion codes and F where they change, arcs in the program's form).

use crate::back::{Axes, CycleBlocks, carried_words, carry_traced, cycle_blocks};
use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::printer::{Edits, NewBlock, ProgramStyle};
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
        match cycle_blocks(program, expansion, (moves, &[]), (start, Axes::Every), compensation_before, shift, &style) {
            CycleBlocks::Keep => {}
            CycleBlocks::Blocks(mut blocks, _) => {
                let first = expansion.moves.start;
                carry_traced(program, &mut blocks, moves.len(), expansion.traced.iter().map(|&(m, b)| (m - first, b)));
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
/// expansion. The cycle's first block ran where it is (`Expansion::setup`): its M codes, T
/// words and comments stay there. A profile block's words go with the cycle that runs it
/// (`carry_traced`); a cycle that only reads its profile (`G71`) never runs them.
pub(crate) fn delete_consumed(
    edits: &mut Edits,
    program: &Program<'_>,
    expansion: &crate::semantic::Expansion,
    calls: &std::collections::HashSet<usize>,
) {
    for &consumed in &expansion.consumed {
        if calls.contains(&consumed) || program.block(consumed).statement == Statement::Invalid {
            continue;
        }
        let kept = if expansion.setup == Some(consumed) { carried_words(program, consumed) } else { Vec::new() };
        if kept.is_empty() {
            edits.delete(consumed);
        } else {
            edits.replace(consumed, vec![NewBlock::new(kept)]);
        }
    }
}

/// Why `expand` does not write the program it printed ([`check_written`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Unwritable {
    /// The printed program, read back, has errors (over its own text).
    Errors(Vec<Diagnostic>),
    /// It runs cleanly but cuts another number of moves than the original.
    OtherCuts { original: usize, written: usize },
    /// Its `index`-th cutting move (from 1) ends `by_mm` from the original's, or threads
    /// where the original's does not (or the other way round), or starts its thread at
    /// another angle past the spindle's index.
    OtherCut { index: usize, by_mm: f64 },
}

/// How far a cutting move of the expansion may end from the original's: the rounding of a
/// cycle's computed points onto the program's grid, an inch program's least increment
/// (0.0001 in) at most, with room for the diameter's halving.
const CUT_END_TOLERANCE_MM: f64 = 0.003;

/// What `expand` checks before it writes, as `compensate` checks what it writes
/// (`compensation::verify::check_written`): `written`, a printing of `original`, read back
/// with `reading` (the original's settings, its dialect and G-code system fixed:
/// `printer::read_back_options`), lowered and validated, must run without an error and cut
/// the original's moves: as many, each ending where the original's does (to the grid), each
/// thread pass starting at the original's angle. A coordinate past the digits the control
/// reads, a block that ran nowhere in the original and runs in the expansion, or a start of a
/// multi-start thread written without its angle, is found here, not on the control.
pub fn check_written(
    original: &Validated<Lowered>,
    written: &[u8],
    reading: &crate::pipeline::Settings,
) -> Result<(), Unwritable> {
    match crate::pipeline::analyse(written, reading).ready() {
        Ok(read) => {
            let (original, written) = (&original.toolpath.moves, &read.lowered.toolpath.moves);
            let cutting = |moves: &[crate::toolpath::Move]| moves.iter().filter(|m| m.cutting).count();
            let (count, written_count) = (cutting(original), cutting(written));
            if count != written_count {
                return Err(Unwritable::OtherCuts { original: count, written: written_count });
            }
            let pairs = original.iter().filter(|m| m.cutting).zip(written.iter().filter(|m| m.cutting));
            for (k, (a, b)) in pairs.enumerate() {
                let by_mm = a.contour.distance(b.contour);
                let turns_apart = (a.phase - b.phase).rem_euclid(1.0).min((b.phase - a.phase).rem_euclid(1.0));
                if by_mm > CUT_END_TOLERANCE_MM || a.threading != b.threading || a.threading && turns_apart > 1e-6 {
                    return Err(Unwritable::OtherCut { index: k + 1, by_mm });
                }
            }
            Ok(())
        }
        Err(analysed) => {
            Err(Unwritable::Errors(analysed.diagnostics.into_iter().filter(Diagnostic::is_error).collect()))
        }
    }
}
