//! A cycle's moves written as the explicit blocks that make them.
//!
//! Coordinates go back through the cycle's frame (units, diameter X) onto its grid; motion
//! codes, F and S are written where they change; arcs take the program's own form (`R`/`L`
//! radius or `I K` centre) where it holds them after rounding. On a control with no thread
//! move (OSP) a thread pass is written as a single-pass cycle block (`cycle/thread_pass.rs`).

mod thread_pass;

use crate::dialect::Address;
use crate::printer::{NewBlock, NewWord, ProgramStyle};
use crate::semantic::Expansion;
use crate::syntax::{CodeLetter, Number, Program, WordKind};
use crate::toolpath::{Compensation, Move, Xz};

use super::grid::Grid;
use super::motion::{Codes, GivenNext, Modal, MotionWriter, Restore};
use super::thread_lead::WrittenLead;

/// What a cycle call becomes.
pub(crate) enum CycleBlocks {
    /// A single-pass thread cycle: it is one pass already; leave it.
    Keep,
    /// The blocks that replace the call; where the last only puts back modal words the
    /// blocks after the call run under, what it puts back (`MotionWriter::restore`).
    Blocks(Vec<NewBlock>, Option<Restore>),
    /// It has no plain-block form (why); leave it.
    NotExpandable(&'static str),
}

/// Which axes the blocks written for a cycle's moves name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Axes {
    /// Both, on every block: a cycle written out move by move.
    Every,
    /// Only those a straight move travels, as a profile is written by hand (a profile copy
    /// for a finishing cycle).
    Travelled,
}

/// Why a cycle whose thread moves are no single pass stays as it is.
pub(crate) const THREAD_MOVES: &str = "its thread moves have no plain-block form in this dialect";

/// The blocks that replace `expansion`'s call block when the cycle makes `moves` from
/// `start` (programmed contour points: `Move.contour`, arcs about `Move.centre`), with
/// `compensation_before` in force before it and the program's coordinates shifted by
/// `shift` (`G50 X Z`), in the program's `style` (`ProgramStyle::infer`, read once per
/// program: it reads every block). `expand` passes the cycle's own moves, the compensation
/// pass its compensated ones. The block written for `moves[k]` is the `k`-th, so that
/// [`carry_traced`] can put a profile block's words on the block of its move. `leads`, where
/// it has an entry for a thread move of `moves` (same index), is the lead that move is
/// written with (compensation's, for the slide to cut the programmed lead); otherwise a
/// thread move's lead is its F.
pub(crate) fn cycle_blocks(
    program: &Program<'_>,
    expansion: &Expansion,
    (moves, leads): (&[Move], &[Option<WrittenLead>]),
    (start, axes): (Xz, Axes),
    compensation_before: Compensation,
    shift: Xz,
    style: &ProgramStyle,
) -> CycleBlocks {
    if let Some(reason) = expansion.kept {
        return CycleBlocks::NotExpandable(reason);
    }
    let codes = Codes::of(program);
    // S in force before the cycle's block: the written blocks give S where it changes
    // (the cycle block's own S included, since the block is replaced).
    let modal = Modal::new(compensation_before, expansion.before.s_word);
    let grid = Grid::of(expansion.frame, shift);
    let modal = match axes {
        Axes::Every => modal,
        Axes::Travelled => modal.writing_travelled_axes(grid.point(start)),
    };
    let mut cycle = CycleWriter { writer: MotionWriter::new(codes, Vec::new()), modal, grid, style };
    if !codes.has_thread_move() && moves.iter().any(|m| m.threading) {
        // No thread move in this dialect: passes become single-pass cycle blocks, which copy
        // the call's lead or write the moves' F; a lead given for them is not written, so
        // the cycle is left as it is rather than cut at a lead other than the one asked.
        if leads.iter().any(Option::is_some) {
            return CycleBlocks::NotExpandable(THREAD_MOVES);
        }
        return thread_pass::write(program, expansion, moves, start, &mut cycle);
    }
    // A pass that starts past the spindle's index needs the thread move's start-angle word.
    if codes.start_angle.is_none() && moves.iter().any(|m| m.threading && m.phase != 0.0) {
        return CycleBlocks::NotExpandable(THREAD_MOVES);
    }
    let mut start = start;
    let mut blocks: Vec<NewBlock> = moves
        .iter()
        .enumerate()
        .map(|(k, m)| {
            let lead = leads.get(k).and_then(Option::as_ref).map(|lead| &lead.words[..]);
            let block = cycle.block(start, m, lead);
            start = m.contour;
            block
        })
        .collect();
    // The control goes on after the blocks the cycle consumed (its profile after the call).
    let next = GivenNext::after(program, &codes, expansion.block, |b| expansion.consumed.contains(&b));
    // A motion code or an F no later move reads is not put back.
    let next = GivenNext {
        motion: next.motion || !expansion.motion_read_after,
        feed: next.feed || !expansion.feed_read_after,
        ..next
    };
    let restore = cycle.writer.restore(&mut cycle.modal, &expansion.after, next);
    if restore.is_none() {
        return CycleBlocks::Blocks(blocks, None);
    }
    blocks.push(NewBlock::new(cycle.writer.take_words()));
    CycleBlocks::Blocks(blocks, Some(restore))
}

/// Put the words of each profile block a cycle runs (`traced`: the block, and the index in
/// the cycle's `moves` of the first move it makes, `Expansion::traced`) on the block written
/// for that move ([`cycle_blocks`] writes the `k`-th block for `moves[k]`), where the control
/// runs them; a block whose elements make no move of their own (an approach of no length at
/// the end) leaves them on the last move's block.
pub(crate) fn carry_traced(
    program: &Program<'_>,
    blocks: &mut [NewBlock],
    moves: usize,
    traced: impl IntoIterator<Item = (usize, usize)>,
) {
    for (at, block) in traced {
        if let Some(written) = blocks.get_mut(at.min(moves.saturating_sub(1))) {
            written.words.extend(carried_words(program, block));
        }
    }
}

/// The words of block `block` that run where the block runs and that no written move block
/// gives: its M codes, T words and comments, as copies, in their order. A cycle's first block
/// (`Expansion::setup`) leaves them where it was; a profile block the cycle runs
/// (`Expansion::traced`) puts them on the block written for its move.
pub(crate) fn carried_words(program: &Program<'_>, block: usize) -> Vec<NewWord> {
    let block = program.block(block);
    program
        .words_of(block)
        .iter()
        .enumerate()
        .filter(|(_, word)| match word.kind {
            WordKind::Code { letter: CodeLetter::M, .. } | WordKind::Comment(_) => true,
            WordKind::Number { address, .. } | WordKind::Expr { address, .. } => address == Address::T,
            _ => false,
        })
        .map(|(k, _)| NewWord::Copy(block.first_word + k as u32))
        .collect()
}

/// The writer of one cycle's blocks, and what they leave in force.
pub(super) struct CycleWriter<'s> {
    pub writer: MotionWriter<Vec<NewWord>>,
    pub modal: Modal,
    /// The grid of the cycle's coordinates.
    pub grid: Grid,
    pub style: &'s ProgramStyle,
}

impl CycleWriter<'_> {
    /// The block of move `m` from `start`, a thread move's lead written with `lead` where
    /// given.
    pub(super) fn block(&mut self, start: Xz, m: &Move, lead: Option<&[(Address, Number)]>) -> NewBlock {
        self.writer.move_block(&mut self.modal, &self.grid, self.style.radius_arcs, (start, m), lead);
        NewBlock::new(self.writer.take_words())
    }
}
