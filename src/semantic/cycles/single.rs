//! Fanuc single cycles: `G90` turning, `G92` threading and `G94` facing (system A numbers;
//! `G77`/`G78`/`G79` on B, `G20`/`G21`/`G24` on C), and their modal repetition: later blocks
//! that give only a new X (or Z) run the cycle again with the other values kept.
//!
//! ```txt
//!  G90 / G92 (turning, threading)         G94 (facing)
//!   A ◀─────4(R)───── .                    A ─1(R)─▶ .
//!   │1(R)             ▲3                   ▲4(R)     │2(F)
//!   ▼                 │                    │         ▼
//!   . ───2(F)───────▶ end                  . ◀─3(F)─ end
//! ```
//! Move 2 runs along Z (X for facing) and may taper by `R` (the radius difference between
//! the start and the end of the cut). `G90` and `G94` return with a feed move 3; `G92` cuts
//! move 2 as a thread (lead `F`) and retracts at rapid.

use crate::diagnostic::DiagnosticKind;
use crate::dialect::{Address, GFunction, Role};
use crate::syntax::{Command, Word};
use crate::toolpath::Xz;

use super::super::interpreter::{Flow, Interpreter};
use super::super::modal::MotionMode;

/// The last single cycle, for its modal repetitions (toolpath frame, mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingleCycleMemory {
    pub function: GFunction,
    pub end: Xz,
    pub taper: f64,
    /// The start angle the last thread run wrote (`Q`, 0.001°), which a repeat does not keep.
    pub start_angle: Option<f64>,
}

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command, function: GFunction) -> Flow {
    if interp.form_name(command) == "select" {
        // The code alone selects the cycle, as any motion code does; it moves nothing, and
        // the next block with only X/Z runs the cycle from where the tool then is.
        let block = interp.program.block(index);
        let code = interp.program.word(command.code_word).kind;
        if let crate::syntax::WordKind::Code { code, .. } = code {
            interp
                .warning(crate::diagnostic::DiagnosticKind::CycleSelectedAlone { code: code.display('G') }, block.span);
        }
        interp.cycle_memory.single = None;
        interp.modal.motion = motion_mode(function);
        return Flow::Next;
    }
    let words: Vec<Word> = command.params.iter().map(|p| *interp.program.word(p.word)).collect();
    let axes = interp.axis_target(&words);
    let taper = interp.param(command, Role::Taper).map(|r| interp.modal.frame.mm(r)).unwrap_or(0.0);
    let start = interp.emitter.at;
    let end = axes.target.unwrap_or(start);
    if let Some(lead) = interp.param(command, Role::Lead) {
        interp.modal.feed = lead;
    }
    let start_angle = interp.param(command, Role::ShiftAngle);
    interp.cycle_memory.single = Some(SingleCycleMemory { function, end, taper, start_angle });
    interp.modal.motion = motion_mode(function);
    cut(interp, index, (function, start_angle), start, end, taper);
    Flow::Next
}

fn motion_mode(function: GFunction) -> MotionMode {
    match function {
        GFunction::TurningCycle => MotionMode::TurningCycle,
        GFunction::ThreadCycle => MotionMode::ThreadCycle,
        _ => MotionMode::FacingCycle,
    }
}

/// A block repeating the modal single cycle with new end values; after a code that only
/// selected the cycle, the first such block runs it from where the tool is.
pub(in crate::semantic) fn single_cycle_again(interp: &mut Interpreter<'_, '_>, index: usize, words: &[Word]) -> Flow {
    let function = match interp.modal.motion {
        MotionMode::TurningCycle => GFunction::TurningCycle,
        MotionMode::ThreadCycle => GFunction::ThreadCycle,
        _ => GFunction::FacingCycle,
    };
    let at = interp.emitter.at;
    let memory =
        interp.cycle_memory.single.unwrap_or(SingleCycleMemory { function, end: at, taper: 0.0, start_angle: None });
    let block = *interp.program.block(index);
    interp.emitter.context = super::super::emitter::Context { source: block.span, cycle: block.span };
    let first_move = interp.emitter.moves.len();
    let axes = interp.axis_target(words);
    let frame = interp.modal.frame;
    let taper = interp.address_value(words, Address::R).map(|r| frame.mm(r)).unwrap_or(memory.taper);
    if let Some(feed) = interp.address_value(words, Address::F) {
        interp.modal.feed = feed;
    }
    let start = interp.emitter.at;
    let end = Xz::new(
        if axes.x_given { axes.target.map_or(memory.end.x, |t| t.x) } else { memory.end.x },
        if axes.z_given { axes.target.map_or(memory.end.z, |t| t.z) } else { memory.end.z },
    );
    // A thread's start angle is the block's own, as on the call: it is not kept. A repeat
    // that leaves out the one the run before it wrote cuts another start: said, as the
    // programmer may have meant the same one.
    let start_angle = match memory.function {
        GFunction::ThreadCycle => interp.address_value(words, Address::Q),
        _ => None,
    };
    if let (None, Some(before)) = (start_angle, memory.start_angle.filter(|q| q.rem_euclid(360_000.0) != 0.0)) {
        interp.warning(DiagnosticKind::ThreadStartAngleNotKept { degrees: before / 1000.0 }, block.span);
    }
    interp.cycle_memory.single = Some(SingleCycleMemory { end, taper, start_angle, ..memory });
    cut(interp, index, (memory.function, start_angle), start, end, taper);
    interp.expansions.push(super::super::Expansion {
        block: index,
        frame: interp.modal.frame,
        consumed: Vec::new(),
        setup: None,
        traced: Vec::new(),
        traced_end: first_move,
        root: Vec::new(),
        moves: first_move..interp.emitter.moves.len(),
        before: interp.modal_before_block,
        after: crate::semantic::ModalAfter::of(&interp.modal),
        kept: None,
        note: None,
        feed_read_after: true,
        motion_read_after: true,
    });
    Flow::Next
}

/// The cycle's four moves; a thread's (`G92`) starts `start_angle` (0.001°) past the
/// spindle's index.
fn cut(
    interp: &mut Interpreter<'_, '_>,
    index: usize,
    (function, start_angle): (GFunction, Option<f64>),
    start: Xz,
    end: Xz,
    taper: f64,
) {
    let span = interp.program.block(index).span;
    if interp.known_position(span).is_none() {
        return;
    }
    if function == GFunction::ThreadCycle {
        super::thread_pass::warn_if_no_length(interp, (end.z - start.z).abs(), span);
    }
    let modal = interp.modal.clone();
    let e = &mut interp.emitter;
    match function {
        GFunction::FacingCycle => {
            e.rapid(&modal, Xz::new(start.x, end.z + taper));
            e.line(&modal, end, true);
            e.line(&modal, Xz::new(end.x, start.z), true);
            e.rapid(&modal, start);
        }
        GFunction::ThreadCycle => {
            let lead = modal.frame.feed_mm(modal.feed);
            e.rapid(&modal, Xz::new(end.x + taper, start.z));
            e.thread_phase = start_angle.map_or(0.0, super::thread_pass::start_angle_turns);
            e.thread(&modal, end, lead);
            e.thread_phase = 0.0;
            e.rapid(&modal, Xz::new(start.x, end.z));
            e.rapid(&modal, start);
        }
        _ => {
            e.rapid(&modal, Xz::new(end.x + taper, start.z));
            e.line(&modal, end, true);
            e.line(&modal, Xz::new(start.x, end.z), true);
            e.rapid(&modal, start);
        }
    }
    interp.report_zero_feed(span);
}
