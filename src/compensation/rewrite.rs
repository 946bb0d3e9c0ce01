//! The compensated program as edits to the parsed one: only the blocks whose motion
//! changes are touched.
//!
//! Input: the parsed program, the lowered toolpath (with nose-radius compensation:
//! `Move.end` is the tool reference point, `Move.contour` the programmed point), and each
//! move's plan (`plan.rs`: the segments to write in the contour frame). Every other block
//! prints byte-identical.
//!
//! * **Motion blocks** (`G00`–`G03`, a thread move) are written back in their own form
//!   (`rewrite/block.rs`). A block that runs more than once (a subprogram called twice, a
//!   loop) is edited only if every run asks for the same words; a block that makes several
//!   moves (an OSP automatic corner) cannot carry several corrections. Both refuse with a
//!   diagnostic when their motion must change.
//! * **Under `G41`/`G42`** the program describes the contour, and so does the rewritten
//!   block: its points are the contour points moved by the correction of their reference
//!   points, `contour + (commanded − nominal)` (`written.rs`), never the reference points,
//!   so the control's nose-radius offset still applies on top.
//! * **Cycles** whose motion changes are expanded into their compensated moves
//!   (`rewrite/cycles.rs`); the others stay calls.
//! * Moves of other blocks (`G28`, `G53` returns) stay as programmed: they go to fixed
//!   machine positions, not to points of the part.

mod block;
pub mod cycles;

use std::collections::{HashMap, HashSet};
use std::ops::Range;

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::printer::{Edits, NewBlock};
use crate::semantic::Lowered;
use crate::semantic::nose_radius::ToolTable;
use crate::syntax::{Program, Statement};

use super::grid::Grid;
use super::plan::MovePlan;
use super::written;

/// The edits, their problems, and what was edited.
#[derive(Debug, Clone, Default)]
pub struct Rewrite {
    pub edits: Edits,
    /// Refusals (errors: nothing may be written) and notes.
    pub diagnostics: Vec<Diagnostic>,
    /// Each edited block (a motion block, or a cycle call that was expanded) and the moves
    /// it writes (for a block that runs several times, its first run).
    pub edited: Vec<EditedBlock>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct EditedBlock {
    pub block: usize,
    pub moves: Range<usize>,
    pub cycle: bool,
}

/// Which moves can be written back: moves of motion blocks, and of cycles that can be
/// expanded.
pub fn writable_moves(program: &Program<'_>, lowered: &Lowered) -> Vec<bool> {
    let moves = &lowered.toolpath.moves;
    let mut writable = vec![false; moves.len()];
    let mut in_cycle = vec![false; moves.len()];
    for expansion in &lowered.expansions {
        let expandable = cycles::expandable(program, lowered, expansion);
        for k in expansion.moves.clone() {
            if let (Some(w), Some(c)) = (writable.get_mut(k), in_cycle.get_mut(k)) {
                *w = expandable;
                *c = true;
            }
        }
    }
    let blocks = BlockLookup::new(program);
    for (k, m) in moves.iter().enumerate() {
        if in_cycle[k] {
            continue;
        }
        writable[k] = blocks
            .index(m.source.start)
            .is_some_and(|b| matches!(program.block(b).statement, Statement::Motion | Statement::ThreadMove));
    }
    writable
}

/// Block indices by the start of their span.
struct BlockLookup {
    starts: Vec<u32>,
}

impl BlockLookup {
    fn new(program: &Program<'_>) -> BlockLookup {
        BlockLookup { starts: program.blocks().iter().map(|b| b.span.start).collect() }
    }

    fn index(&self, start: u32) -> Option<usize> {
        self.starts.binary_search(&start).ok()
    }
}

/// The edits for `plans` (one per move of `lowered.toolpath`).
pub fn rewrite(
    program: &Program<'_>,
    lowered: &Lowered,
    plans: &[MovePlan],
    tools: &ToolTable,
    expand_cycles: bool,
) -> Rewrite {
    let mut out = Rewrite::default();
    let chosen = cycles::chosen(program, lowered, plans, expand_cycles, &mut out.diagnostics);
    let expanded = cycles::write(program, lowered, plans, &chosen, &mut out.edits, &mut out.diagnostics);
    // The first expansion of each call block (a call that runs several times has several).
    let mut first_expansion: HashMap<usize, usize> = HashMap::new();
    for (k, e) in lowered.expansions.iter().enumerate() {
        first_expansion.entry(e.block).or_insert(k);
    }
    for block in expanded {
        if let Some(e) = first_expansion.get(&block).and_then(|&k| lowered.expansions.get(k)) {
            out.edited.push(EditedBlock { block, moves: e.moves.clone(), cycle: true });
        }
    }
    motion_blocks(program, lowered, plans, tools, &mut out);
    out.edited.sort_by_key(|e| e.block);
    out.diagnostics.sort_by_key(|d| d.span.start);
    out
}

/// One run of a block: its moves, and the new blocks (`None`: as written).
struct Run {
    moves: Range<usize>,
    blocks: Option<Vec<NewBlock>>,
}

fn motion_blocks(program: &Program<'_>, lowered: &Lowered, plans: &[MovePlan], tools: &ToolTable, out: &mut Rewrite) {
    let moves = &lowered.toolpath.moves;
    let mut in_cycle = vec![false; moves.len()];
    for e in &lowered.expansions {
        for k in e.moves.clone() {
            if let Some(c) = in_cycle.get_mut(k) {
                *c = true;
            }
        }
    }
    let lookup = BlockLookup::new(program);
    let radius_arcs = crate::expand::uses_radius_arcs(program);
    let mut runs: HashMap<usize, Vec<Run>> = HashMap::new();
    let mut refused: HashSet<usize> = HashSet::new();
    let mut k = 0;
    while k < moves.len() {
        let source = moves[k].source;
        let first = k;
        while k < moves.len() && moves[k].source == source && !in_cycle[k] {
            k += 1;
        }
        if k == first {
            k += 1;
            continue;
        }
        let Some(block) = lookup.index(source.start) else { continue };
        if !matches!(program.block(block).statement, Statement::Motion | Statement::ThreadMove) {
            continue;
        }
        // The moves the block writes (not dwells or corners the control makes).
        let written: Vec<usize> =
            (first..k).filter(|&i| plans.get(i).is_some_and(|p| !p.segments.is_empty())).collect();
        let any_change = written.iter().any(|&i| plans[i].changed);
        let blocks = match written.as_slice() {
            [] => None,
            [single] => {
                let mark = lowered.coordinates_at(*single);
                let context = block::BlockContext { program, block, mark, grid: Grid::new(&mark), radius_arcs, tools };
                let contour_start = written::contour_start(&lowered.toolpath, *single);
                context.rewrite(&moves[*single], contour_start, &plans[*single])
            }
            _ if any_change => {
                if refused.insert(block) {
                    out.diagnostics.push(Diagnostic::error(
                        DiagnosticKind::CannotRewriteBlock {
                            reason: "it makes several moves (an automatic corner), which cannot each carry a correction",
                        },
                        source,
                    ));
                }
                None
            }
            _ => None,
        };
        runs.entry(block).or_default().push(Run { moves: first..k, blocks });
    }
    let mut blocks: Vec<usize> = runs.keys().copied().collect();
    blocks.sort_unstable();
    for block in blocks {
        let Some(block_runs) = runs.get(&block) else { continue };
        let Some(first) = block_runs.first() else { continue };
        if block_runs.iter().all(|r| r.blocks.is_none()) {
            continue;
        }
        if block_runs.iter().any(|r| r.blocks != first.blocks) {
            if refused.insert(block) {
                out.diagnostics.push(Diagnostic::error(
                    DiagnosticKind::CannotRewriteBlock {
                        reason: "it runs more than once, and its runs need different corrections",
                    },
                    program.block(block).span,
                ));
            }
            continue;
        }
        if let Some(new) = &first.blocks {
            out.edits.replace(block, new.clone());
            out.edited.push(EditedBlock { block, moves: first.moves.clone(), cycle: false });
        }
    }
}
