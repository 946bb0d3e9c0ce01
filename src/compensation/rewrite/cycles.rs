//! Canned cycles whose motion changes: expanded into their compensated moves.
//!
//! A cycle call cannot carry a correction: the control computes its passes from the
//! call's words. A cycle none of whose moves changes stays as it is; any other is replaced
//! by explicit blocks, written by the back end from the compensated segments as `expand`
//! writes a cycle (`back::cycle_blocks`), and the blocks it consumed (its profile, the
//! first block of a two-block cycle) are deleted. Cycles that share consumed blocks are
//! expanded together: a finishing cycle
//! left as a call would need the profile the roughing cycle's expansion deletes, and a
//! profile left in place after an expanded call would run as plain moves.
//!
//! The call block's own words that are not the cycle's (its sequence name, comments, M
//! codes) go on the first written block, and a block-delete slash on every written block.
//! A consumed block with a comment leaves the comment behind.

use std::collections::{BTreeMap, HashMap, HashSet};

use crate::back::motion::Codes;
use crate::back::{CycleBlocks, carried_words, carry_traced, cycle_blocks};
use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::expand;
use crate::printer::{Edits, NewBlock, NewWord, ProgramStyle};
use crate::semantic::{Expansion, Lowered};
use crate::syntax::{CodeLetter, Program, WordKind};
use crate::toolpath::{Compensation, Motion, Move, Xz};

use super::super::fit::Segment;
use super::super::plan::{KeptPlans, MovePlan};

/// Whether the moves of `expansion` can be written back: on a control with no thread move
/// (OSP) a cycle's thread passes are written only as the cycle's own single-pass blocks,
/// which compensated passes are not.
pub fn expandable(program: &Program<'_>, lowered: &Lowered, expansion: &Expansion) -> bool {
    Codes::of(program).has_thread_move()
        || !lowered.toolpath.moves.get(expansion.moves.clone()).is_some_and(|moves| moves.iter().any(|m| m.threading))
}

/// The cycles to expand: those whose moves changed (every one with `all`), and those that
/// share blocks with one of them (a call block, or a consumed block). Indices into
/// `lowered.expansions`. A cycle to expand that shares blocks with one that cannot be
/// expanded is refused with an error in `diagnostics` (and not expanded).
pub(super) fn chosen(
    program: &Program<'_>,
    lowered: &Lowered,
    plans: &KeptPlans,
    all: bool,
    diagnostics: &mut Vec<Diagnostic>,
) -> Vec<bool> {
    let expansions = &lowered.expansions;
    let expandable: Vec<bool> = expansions.iter().map(|e| expandable(program, lowered, e)).collect();
    let mut chosen: Vec<bool> = expansions
        .iter()
        .zip(&expandable)
        .map(|(e, &ok)| ok && (all || plans.get(e.moves.clone()).is_some_and(|p| p.iter().any(|p| p.changed))))
        .collect();
    // Cycles that share a block form a group (a roughing cycle, the finishing cycle on the
    // same profile): a group is expanded whole or not at all.
    let mut group: Vec<usize> = (0..expansions.len()).collect();
    let mut first_with: HashMap<usize, usize> = HashMap::new();
    for (k, e) in expansions.iter().enumerate() {
        for &block in std::iter::once(&e.block).chain(&e.consumed) {
            match first_with.get(&block) {
                Some(&other) => {
                    let (a, b) = (root(&mut group, k), root(&mut group, other));
                    group[a] = b;
                }
                None => {
                    first_with.insert(block, k);
                }
            }
        }
    }
    let roots: Vec<usize> = (0..expansions.len()).map(|k| root(&mut group, k)).collect();
    let mut wanted: HashMap<usize, bool> = HashMap::new();
    let mut possible: HashMap<usize, bool> = HashMap::new();
    for k in 0..expansions.len() {
        *wanted.entry(roots[k]).or_default() |= chosen[k];
        *possible.entry(roots[k]).or_insert(true) &= expandable[k];
    }
    for k in 0..expansions.len() {
        let r = roots[k];
        let (want, can) = (wanted.get(&r).copied().unwrap_or(false), possible.get(&r).copied().unwrap_or(false));
        if want && !can && chosen[k] {
            diagnostics.push(Diagnostic::error(
                DiagnosticKind::CannotRewriteBlock {
                    reason: "its blocks are shared with a cycle whose passes cannot be written out",
                },
                program.block(expansions[k].block).span,
            ));
        }
        chosen[k] = want && can;
    }
    chosen
}

/// The representative of `k`'s group (with path halving).
fn root(group: &mut [usize], mut k: usize) -> usize {
    while group[k] != k {
        group[k] = group[group[k]];
        k = group[k];
    }
    k
}

/// The compensated moves of a cycle, as the back end's cycle writer takes them: one move per
/// segment, in the contour frame, and the index of the first of each move's. A take-up of
/// the play before a move that switches compensation is a rapid under the compensation in
/// force before it.
fn compensated_moves(moves: &[Move], plans: &[MovePlan], compensation_before: Compensation) -> (Vec<Move>, Vec<usize>) {
    let mut out = Vec::with_capacity(moves.len());
    let mut firsts = Vec::with_capacity(moves.len());
    let mut compensation = compensation_before;
    for (m, plan) in moves.iter().zip(plans) {
        firsts.push(out.len());
        if m.motion == Motion::Dwell {
            out.push(*m);
            continue;
        }
        for (k, segment) in plan.segments.iter().enumerate() {
            let (motion, centre) = match *segment {
                Segment::Line { .. } if m.motion == Motion::Rapid || (plan.lead_in && k == 0) => {
                    (Motion::Rapid, Xz::new(f64::NAN, f64::NAN))
                }
                Segment::Line { .. } => (Motion::Feed, Xz::new(f64::NAN, f64::NAN)),
                Segment::Arc { centre, ccw, .. } => (if ccw { Motion::Ccw } else { Motion::Cw }, centre),
            };
            let compensation = if plan.lead_in && k == 0 { compensation } else { m.compensation };
            out.push(Move { motion, centre, compensation, contour: segment.end(), end: segment.end(), ..*m });
        }
        compensation = m.compensation;
    }
    (out, firsts)
}

/// Write the chosen cycles into `edits`; problems go to `diagnostics`.
pub(super) fn write(
    program: &Program<'_>,
    lowered: &Lowered,
    plans: &KeptPlans,
    chosen: &[bool],
    style: &ProgramStyle,
    edits: &mut Edits,
    diagnostics: &mut Vec<Diagnostic>,
) -> Vec<usize> {
    let calls: HashSet<usize> = lowered.expansions.iter().map(|e| e.block).collect();
    // The profile blocks whose words a written cycle carries (`back::carry_traced`).
    let traced: HashSet<usize> = lowered
        .expansions
        .iter()
        .zip(chosen)
        .filter(|(_, chosen)| **chosen)
        .flat_map(|(e, _)| e.traced.iter().map(|&(_, block)| block))
        .collect();
    // A call block that runs more than once (a cycle in a subprogram) must come out the
    // same every time.
    let mut by_block: BTreeMap<usize, Vec<NewBlock>> = BTreeMap::new();
    let mut refused = HashSet::new();
    let mut written = Vec::new();
    for (expansion, _) in lowered.expansions.iter().zip(chosen).filter(|(_, chosen)| **chosen) {
        let range = expansion.moves.clone();
        let (Some(moves), Some(cycle_plans)) = (lowered.toolpath.moves.get(range.clone()), plans.get(range.clone()))
        else {
            continue;
        };
        let start = cycle_plans.first().map_or(lowered.toolpath.start, |p| p.start);
        let compensation_before = range
            .start
            .checked_sub(1)
            .and_then(|k| lowered.toolpath.moves.get(k))
            .map_or(Compensation::Off, |m| m.compensation);
        let shift = lowered.coordinates_at(range.start).shift;
        let (compensated, firsts) = compensated_moves(moves, cycle_plans, compensation_before);
        let blocks = match cycle_blocks(program, expansion, &compensated, start, compensation_before, shift, style) {
            CycleBlocks::Blocks(mut blocks) => {
                let at = |m: usize| firsts.get(m - range.start).copied().unwrap_or(compensated.len());
                carry_traced(
                    program,
                    &mut blocks,
                    compensated.len(),
                    expansion.traced.iter().map(|&(m, b)| (at(m), b)),
                );
                with_call_words(program, expansion.block, blocks)
            }
            CycleBlocks::Keep | CycleBlocks::NotExpandable(_) => {
                let span = program.block(expansion.block).span;
                diagnostics.push(Diagnostic::warning(DiagnosticKind::CycleNotCompensated, span));
                continue;
            }
        };
        match by_block.get(&expansion.block) {
            Some(previous) if *previous != blocks => {
                if refused.insert(expansion.block) {
                    let span = program.block(expansion.block).span;
                    diagnostics.push(Diagnostic::error(
                        DiagnosticKind::CannotRewriteBlock {
                            reason: "the cycle runs more than once with different corrections",
                        },
                        span,
                    ));
                }
            }
            Some(_) => {}
            None => {
                by_block.insert(expansion.block, blocks);
                written.push(expansion.block);
                delete_consumed(program, expansion, (&calls, &traced), edits, diagnostics);
            }
        }
    }
    for (block, blocks) in by_block {
        edits.replace(block, blocks);
    }
    written
}

/// The call block's sequence name, comments and M codes on the first written block, and
/// its block-delete slash on every one.
fn with_call_words(program: &Program<'_>, call: usize, mut blocks: Vec<NewBlock>) -> Vec<NewBlock> {
    let block = program.block(call);
    let mut leading = Vec::new();
    let mut trailing = Vec::new();
    let mut slash = None;
    for (k, word) in program.words_of(block).iter().enumerate() {
        let id = block.first_word + k as u32;
        match word.kind {
            WordKind::BlockDelete { .. } => slash = Some(id),
            WordKind::Sequence { .. } => leading.push(NewWord::Copy(id)),
            WordKind::Comment(_) | WordKind::Code { letter: CodeLetter::M, .. } => trailing.push(NewWord::Copy(id)),
            _ => {}
        }
    }
    if let Some(first) = blocks.first_mut() {
        leading.append(&mut first.words);
        leading.append(&mut trailing);
        first.words = leading;
    }
    if let Some(slash) = slash {
        for b in &mut blocks {
            b.words.insert(0, NewWord::Copy(slash));
        }
    }
    blocks
}

/// Delete the blocks a cycle consumed (not another cycle's call, `calls`), keeping every
/// word of theirs that runs: the cycle's first block ran where it is (`Expansion::setup`),
/// so its M codes, T words and comments stay there; a profile block's words go with the
/// written cycle that runs it (`traced`, `back::carry_traced`). A profile block no written
/// cycle runs keeps its comments where it was; its M codes and T words, which only a
/// finishing cycle runs, have no block to go on: the cycle is refused (an error in
/// `diagnostics` on the block), as `verify` would find them lost.
fn delete_consumed(
    program: &Program<'_>,
    expansion: &Expansion,
    (calls, traced): (&HashSet<usize>, &HashSet<usize>),
    edits: &mut Edits,
    diagnostics: &mut Vec<Diagnostic>,
) {
    let mut plain = Edits::new();
    expand::delete_consumed(&mut plain, program, expansion, calls);
    for &consumed in &expansion.consumed {
        if !plain.touches(consumed) {
            continue;
        }
        let mut words = carried_words(program, consumed);
        let kept = if expansion.setup == Some(consumed) {
            words
        } else if traced.contains(&consumed) {
            Vec::new()
        } else {
            let comment = |word: &NewWord| matches!(word, NewWord::Copy(id) if matches!(program.word(*id).kind, WordKind::Comment(_)));
            if let Some(&NewWord::Copy(id)) = words.iter().find(|word| !comment(word)) {
                let span = program.word(id).span;
                let word = String::from_utf8_lossy(program.text(span)).into_owned();
                diagnostics.push(Diagnostic::error(DiagnosticKind::ProfileWordNotRun { word }, span));
            }
            words.retain(comment);
            words
        };
        if kept.is_empty() {
            edits.delete(consumed);
        } else {
            edits.replace(consumed, vec![NewBlock::new(kept)]);
        }
    }
}
