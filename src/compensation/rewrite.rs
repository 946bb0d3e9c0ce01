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
    let in_cycle = in_cycle(lowered);
    for expansion in &lowered.expansions {
        let expandable = cycles::expandable(program, lowered, expansion);
        for w in writable.get_mut(expansion.moves.clone()).unwrap_or_default() {
            *w = expandable;
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

/// For each move, whether the arcs written for it prefer the radius form (`R`/`L`) to the
/// centre form (`I K`): a motion block's own form (`block::writes_radius`), a cycle's the
/// program's (`expand` writes its blocks so). `grid::Grid::arc_words` still writes an arc
/// by its centre where its radius would not hold it.
pub fn radius_preference(program: &Program<'_>, lowered: &Lowered) -> Vec<bool> {
    let program_radius_arcs = crate::expand::uses_radius_arcs(program);
    let moves = &lowered.toolpath.moves;
    let mut out = vec![program_radius_arcs; moves.len()];
    let in_cycle = in_cycle(lowered);
    let blocks = BlockLookup::new(program);
    for (k, m) in moves.iter().enumerate() {
        if in_cycle[k] {
            continue;
        }
        if let Some(b) = blocks.index(m.source.start) {
            out[k] = block::writes_radius(program, b, m.is_arc(), program_radius_arcs);
        }
    }
    out
}

/// Whether each move is one of a cycle's.
fn in_cycle(lowered: &Lowered) -> Vec<bool> {
    let mut out = vec![false; lowered.toolpath.moves.len()];
    for expansion in &lowered.expansions {
        for c in out.get_mut(expansion.moves.clone()).unwrap_or_default() {
            *c = true;
        }
    }
    out
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
    let mut motion = MotionBlocks::new(program, lowered, tools);
    for run in move_runs(lowered) {
        motion.add(&run, plans.get(run.moves.clone()).unwrap_or_default());
    }
    finish(program, lowered, plans, expand_cycles, motion)
}

/// The edits, once every move is planned and every run of a motion block was given to
/// `motion`: the cycles, then the motion blocks.
pub fn finish(
    program: &Program<'_>,
    lowered: &Lowered,
    plans: &[MovePlan],
    expand_cycles: bool,
    motion: MotionBlocks<'_, '_>,
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
    motion.finish(&mut out);
    out.edited.sort_by_key(|e| e.block);
    out.diagnostics.sort_by_key(|d| d.span.start);
    out
}

/// One run of a block: its moves, and the new blocks (`None`: as written).
struct Run {
    moves: Range<usize>,
    blocks: Option<Vec<NewBlock>>,
}

/// A stretch of moves one edited block can write: the moves of one cycle call, or a run
/// of consecutive moves of one block outside cycles (one run of a block that runs several
/// times).
#[derive(Debug, Clone, PartialEq)]
pub struct MoveRun {
    pub moves: Range<usize>,
    pub cycle: bool,
}

/// Every move's run, in path order: each `EditedBlock` writes the moves of one of them.
pub fn move_runs(lowered: &Lowered) -> Vec<MoveRun> {
    let moves = &lowered.toolpath.moves;
    // The cycle each move belongs to (the first that lists it).
    let mut cycle_of: Vec<Option<usize>> = vec![None; moves.len()];
    for (index, e) in lowered.expansions.iter().enumerate() {
        for k in e.moves.clone() {
            if let Some(c) = cycle_of.get_mut(k) {
                c.get_or_insert(index);
            }
        }
    }
    let mut runs = Vec::new();
    let mut k = 0;
    while k < moves.len() {
        let (source, cycle) = (moves[k].source, cycle_of[k]);
        let first = k;
        while k < moves.len() && cycle_of[k] == cycle && (cycle.is_some() || moves[k].source == source) {
            k += 1;
        }
        runs.push(MoveRun { moves: first..k, cycle: cycle.is_some() });
    }
    runs
}

/// The motion blocks rewritten run by run, in path order (`add`), then settled (`finish`):
/// a block that runs several times is edited only if every run asks for the same words.
pub struct MotionBlocks<'a, 'src> {
    program: &'a Program<'src>,
    lowered: &'a Lowered,
    tools: &'a ToolTable,
    lookup: BlockLookup,
    radius_arcs: bool,
    /// Each run of a motion block, in path order.
    runs: Vec<(usize, Run)>,
    refused: HashSet<usize>,
    diagnostics: Vec<Diagnostic>,
}

impl<'a, 'src> MotionBlocks<'a, 'src> {
    pub fn new(program: &'a Program<'src>, lowered: &'a Lowered, tools: &'a ToolTable) -> MotionBlocks<'a, 'src> {
        MotionBlocks {
            program,
            lowered,
            tools,
            lookup: BlockLookup::new(program),
            radius_arcs: crate::expand::uses_radius_arcs(program),
            runs: Vec::new(),
            refused: HashSet::new(),
            diagnostics: Vec::new(),
        }
    }

    /// The next run (after those given before it), with the plans of its moves; a cycle's
    /// run is the cycles' business (`finish`).
    pub fn add(&mut self, run: &MoveRun, plans: &[MovePlan]) {
        let (program, lowered, tools) = (self.program, self.lowered, self.tools);
        let moves = &lowered.toolpath.moves;
        let first = run.moves.start;
        let Some(source) = moves.get(first).map(|m| m.source) else { return };
        if run.cycle {
            return;
        }
        let Some(block) = self.lookup.index(source.start) else { return };
        if !matches!(program.block(block).statement, Statement::Motion | Statement::ThreadMove) {
            return;
        }
        // The moves the block writes (not dwells or corners the control makes).
        let written: Vec<usize> =
            run.moves.clone().filter(|&i| plans.get(i - first).is_some_and(|p| !p.segments.is_empty())).collect();
        let any_change = written.iter().any(|&i| plans.get(i - first).is_some_and(|p| p.changed));
        let blocks = match written.as_slice() {
            [] => None,
            [single] => {
                let mark = lowered.coordinates_at(*single);
                let context = block::BlockContext {
                    program,
                    block,
                    mark,
                    grid: Grid::new(&mark),
                    radius_arcs: self.radius_arcs,
                    tools,
                };
                let contour_start = written::contour_start(&lowered.toolpath, *single);
                match (moves.get(*single), plans.get(*single - first)) {
                    (Some(m), Some(plan)) => context.rewrite(m, contour_start, plan),
                    _ => None,
                }
            }
            _ if any_change => {
                if self.refused.insert(block) {
                    self.diagnostics.push(Diagnostic::error(
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
        self.runs.push((block, Run { moves: run.moves.clone(), blocks }));
    }

    /// The edits of the motion blocks, after the cycles' in `out`.
    fn finish(mut self, out: &mut Rewrite) {
        let program = self.program;
        out.diagnostics.append(&mut self.diagnostics);
        // By block, each block's runs in path order (a stable sort; the runs mostly come in
        // block order already).
        self.runs.sort_by_key(|(block, _)| *block);
        let mut replacements = Vec::with_capacity(self.runs.len());
        for block_runs in self.runs.chunk_by_mut(|a, b| a.0 == b.0) {
            let Some((block, first)) = block_runs.first() else { continue };
            let block = *block;
            if block_runs.iter().all(|(_, r)| r.blocks.is_none()) {
                continue;
            }
            if block_runs.iter().skip(1).any(|(_, r)| r.blocks != first.blocks) {
                if self.refused.insert(block) {
                    out.diagnostics.push(Diagnostic::error(
                        DiagnosticKind::CannotRewriteBlock {
                            reason: "it runs more than once, and its runs need different corrections",
                        },
                        program.block(block).span,
                    ));
                }
                continue;
            }
            if let Some((_, first)) = block_runs.first_mut()
                && let Some(new) = first.blocks.take()
            {
                replacements.push((block, new));
                out.edited.push(EditedBlock { block, moves: first.moves.clone(), cycle: false });
            }
        }
        out.edits.replace_all(replacements);
    }
}
