//! Thread passes on a control with no plain thread move (OSP): each pass of a multi-pass
//! thread cycle is written as one single-pass cycle block, `G33 X Z F [I] [K] [M23 L]`
//! (`G32` for a face thread), when its moves are exactly that block's moves: rapid in,
//! thread (with its 45° chamfer), rapid out, rapid back to where the pass began. The check
//! regenerates the block's moves with the cycle's own pass shape
//! (`semantic::cycles::thread_pass`) and compares them, so what is written re-lowers to the
//! same points.
//!
//! What the moves do not hold is read from the call block: a multi-start thread's `Q`
//! becomes the phase `C` of each pass (a cycle cuts one pass per start at each depth, in
//! order); with `F` and `J` the call's words are copied; the call's `S` is copied onto
//! every pass. A cycle whose lead changes (`E`), whose `Q` is not a number, or whose moves
//! are not all such passes and plain moves (tapping, a LAP thread along several elements)
//! stays as it is, with a note. A single-pass cycle block stays as it is: it is one pass
//! already.
//!
//! Chamfering is a mode (`M23`/`M22`): a chamfered pass carries `M23` and its `L`; when the
//! program turns chamfering on anywhere, an unchamfered pass carries `M22`, so the mode in
//! force where the pass is written does not matter.

use crate::dialect::{Address, Code, GFunction, Role};
use crate::printer::{NewBlock, NewWord};
use crate::semantic::Expansion;
use crate::semantic::cycles::thread_pass::{Axes, Pass};
use crate::syntax::{CodeLetter, Command, Program, Statement, WordKind};
use crate::toolpath::{Motion, Move, Xz};

use super::{CycleWriter, THREAD_MOVES};
use crate::back::CycleBlocks;
use crate::back::motion::{WordSink, feed_number};

/// Points closer than this are the same (mm): far below any least increment, far above
/// the arithmetic's rounding.
const SAME_MM: f64 = 1e-6;

/// The blocks of a cycle whose `moves` (from `start`) include thread moves, on a control with
/// no thread move.
pub(super) fn write(
    program: &Program<'_>,
    expansion: &Expansion,
    moves: &[Move],
    start: Xz,
    cycle: &mut CycleWriter,
) -> CycleBlocks {
    let tables = program.config().tables();
    let Some(command) = call_command(program, expansion.block) else { return CycleBlocks::NotExpandable(THREAD_MOVES) };
    let function = match program.word(command.code_word).kind {
        WordKind::Code { code, .. } => tables.g(code).and_then(|g| g.function),
        _ => None,
    };
    if matches!(
        function,
        Some(
            GFunction::ThreadSingle
                | GFunction::ThreadSingleAlias
                | GFunction::ThreadSingleFace
                | GFunction::ThreadSingleLeadIncreasing
                | GFunction::ThreadSingleLeadDecreasing
        )
    ) {
        return CycleBlocks::Keep;
    }
    let codes = cycle.writer.codes;
    let (Some(longitudinal_code), Some(face_code)) = (codes.thread_single, codes.thread_single_face) else {
        return CycleBlocks::NotExpandable(THREAD_MOVES);
    };
    if command.param(Role::LeadChange).is_some() {
        return CycleBlocks::NotExpandable(THREAD_MOVES);
    }
    let starts = match command.param(Role::Starts).map(|id| program.word(id).kind) {
        None => 1,
        Some(WordKind::Number { number, .. }) => number.to_f64().round().max(1.0) as usize,
        Some(_) => return CycleBlocks::NotExpandable(THREAD_MOVES),
    };
    // With `F` and `J` both written, the lead is copied as the call writes it (`F/J` need not
    // have a short decimal form); otherwise it is written as the F the moves record.
    let lead_words = match (command.param(Role::Lead), command.param(Role::ThreadsPerInch)) {
        (Some(f), Some(j)) => Some([NewWord::Copy(f), NewWord::Copy(j)]),
        _ => None,
    };
    let speed_word = command.param(Role::Speed).map(NewWord::Copy);
    let (chamfer_on, chamfer_off) = (codes.chamfer_on, codes.chamfer_off);
    let chamfering_used = cycle.style.thread_chamfering;
    let grid = cycle.grid;

    let mut blocks = Vec::new();
    // The words of each pass, and where its block goes among `blocks`.
    let mut passes: Vec<Vec<NewWord>> = Vec::new();
    let mut slots = Vec::new();
    let mut at = start;
    let mut i = 0;
    while i < moves.len() {
        let m = &moves[i];
        let begins_pass = m.motion == Motion::Rapid && moves.get(i + 1).is_some_and(|n| n.threading);
        if !m.threading && !begins_pass {
            blocks.push(cycle.block(at, m, None));
            at = m.contour;
            i += 1;
            continue;
        }
        let Some((count, pass)) = match_pass(at, &moves[i..]) else { return CycleBlocks::NotExpandable(THREAD_MOVES) };
        let face = pass.axes.face;
        let (Some(&first), Some(&end)) = (pass.points.first(), pass.points.last()) else {
            return CycleBlocks::NotExpandable(THREAD_MOVES);
        };
        let writer = &mut cycle.writer;
        writer.out.code(CodeLetter::G, if face { face_code } else { longitudinal_code });
        writer.point(&grid, end);
        let (taper_address, shift_address) = if face { (Address::K, Address::I) } else { (Address::I, Address::K) };
        let taper = pass.axes.depth(first) - pass.axes.depth(end);
        let shift = pass.axes.along(first) - pass.axes.along(at);
        for (address, value) in [(taper_address, taper), (shift_address, shift)] {
            let count = grid.length(value);
            if count != 0 {
                writer.coordinate(&grid, address, count);
            }
        }
        match &lead_words {
            Some(copies) => copies.iter().for_each(|word| writer.out.word(word)),
            None => writer.out.number(Address::F, feed_number(moves.get(i + 1).map_or(0.0, |m| m.f_word))),
        }
        if let Some(speed) = &speed_word {
            writer.out.word(speed);
        }
        match (pass.chamfer, chamfer_on, chamfer_off) {
            (Some(length), Some(on), _) => {
                writer.out.code(CodeLetter::M, Code::whole(on));
                writer.length(&grid, Address::L, length);
            }
            (Some(_), None, _) => return CycleBlocks::NotExpandable(THREAD_MOVES),
            (None, _, Some(off)) if chamfering_used => writer.out.code(CodeLetter::M, Code::whole(off)),
            (None, _, _) => {}
        }
        passes.push(writer.take_words());
        slots.push(blocks.len());
        blocks.push(NewBlock::default());
        at = moves.get(i + count - 1).map_or(at, |m| m.contour);
        i += count;
    }
    // Each depth is cut once per start, in order: a group of `starts` equal passes, the
    // k-th at the phase 360·k/starts.
    if starts > 1 {
        if !passes.len().is_multiple_of(starts)
            || passes.chunks(starts).any(|group| group.iter().any(|p| *p != group[0]))
        {
            return CycleBlocks::NotExpandable(THREAD_MOVES);
        }
        for (index, words) in passes.iter_mut().enumerate() {
            let phase = 360.0 * (index % starts) as f64 / starts as f64;
            words.push(NewWord::Number(Address::C, grid.number(grid.count(phase))));
        }
    }
    for (slot, words) in slots.into_iter().zip(passes) {
        if let Some(block) = blocks.get_mut(slot) {
            block.words = words;
        }
    }
    CycleBlocks::Blocks(blocks, None)
}

/// The command of the cycle call block.
fn call_command<'p>(program: &'p Program<'_>, block: usize) -> Option<&'p Command> {
    match program.block(block).statement {
        Statement::Cycle(id) | Statement::LapCall(id) => Some(program.command(id)),
        _ => None,
    }
}

/// The pass beginning at `moves[0]` (tool at `from`), and how many moves it takes, if the
/// moves are exactly one single-pass cycle's, longitudinal or face.
fn match_pass(from: Xz, moves: &[Move]) -> Option<(usize, Pass)> {
    let entry = moves.first()?.contour;
    let threads = moves.iter().skip(1).take_while(|m| m.threading).count();
    if !(1..=2).contains(&threads) {
        return None;
    }
    for face in [false, true] {
        let axes = Axes { face };
        let first_end = moves[1].contour;
        let (end, chamfer) = if threads == 1 {
            (first_end, None)
        } else {
            // The chamfer starts on the thread line; the block's end is where that line meets
            // the chamfer's end along the axis.
            let pull_end = moves[2].contour;
            let run = axes.along(first_end) - axes.along(entry);
            if run.abs() < SAME_MM {
                continue;
            }
            let t = (axes.along(pull_end) - axes.along(entry)) / run;
            let end = Xz::new(entry.x + (first_end.x - entry.x) * t, entry.z + (first_end.z - entry.z) * t);
            (end, Some((axes.along(pull_end) - axes.along(first_end)).abs()))
        };
        let pass = Pass { axes, from, points: vec![entry, end], chamfer };
        let expected = pass.moves();
        let fits = expected.len() <= moves.len()
            && expected.iter().zip(moves).all(|(e, m)| {
                e.threading == m.threading
                    && (m.threading || m.motion == Motion::Rapid)
                    && e.to.distance(m.contour) < SAME_MM
            });
        if fits {
            return Some((expected.len(), pass));
        }
    }
    None
}
