//! OSP single-pass thread cycles: `G33` (and `G31`, "programmed in the same manner")
//! longitudinal, `G32` on a face, `G34`/`G35` with a lead that grows or shrinks by `E` each
//! revolution. One block, one pass (the motion is drawn in `thread_pass.rs`):
//!
//! `G33 X Z F [I | A] [K] [L] [J] [C] [E]` ([M-P97], dialects.md §1.6): from the tool's
//! position S, rapid to the pass diameter `X` (plus the taper) at S's Z shifted by `K`,
//! thread to `Z` at the lead `F` (`F/J` with `J`), chamfer the end over `L` when
//! chamfering is on (`M23`; one lead when `L` is not given), rapid out to S's X and back to
//! S. `G32` is the same with the axes swapped: the thread runs along X to `X` at the depth
//! `Z`, `K` gives the taper and `I` shifts the start.
//!
//! Readings of the manual where it is silent or its OCR garbled:
//!
//! - `I` is the radius at the start minus the radius at the end (Fanuc's `R` sense); `A`
//!   is the taper angle to the axis, positive when the thread starts on the larger side,
//!   so `I = tan(A) · length`. With both, `I` is used.
//! - `K` shifts the thread's start along its axis (signed, program units); the end stays
//!   at `Z`. This is how a program shifts passes for flank infeed by hand.
//! - The chamfer pulls out at 45°: as far away from the work as it runs along the axis.
//! - `C` (the phase of one start of a multi-start thread, degrees) turns the spindle, not
//!   the path: it changes no move, only where the pass's grooves fall (`Move::phase`).
//! - `E` on `G34` makes the lead grow by |E| per revolution, on `G35` shrink by |E|; on
//!   `G33` it is taken as written. Such a pass is one move per spindle turn, each at its
//!   turn's lead (`Emitter::varying_thread`).
//! - `F` and `S` belong to the cycle; after it, the feed and speed in force are the ones
//!   before it.

use crate::dialect::{GFunction, Role};
use crate::syntax::Command;

use super::super::interpreter::{Flow, Interpreter};
use super::Call;
use super::thread_pass::{self, Axes, Pass};

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command, function: GFunction) -> Flow {
    let Some(Call { span, start: from }) = interp.cycle_call(index) else { return Flow::Next };
    let frame = interp.modal.frame;
    let axes = Axes { face: function == GFunction::ThreadSingleFace };
    let end = interp.cycle_end(command, from);
    let shift = interp.param(command, Role::StartShift).map_or(0.0, |k| frame.mm(k));
    let start_along = axes.along(from) + shift;
    let length = (axes.along(end) - start_along).abs();
    thread_pass::warn_if_no_length(interp, length, span);
    let taper = thread_pass::taper(interp, command, length);
    let (modal, lead_mm) = thread_pass::thread_modal(interp, command);
    let change = thread_pass::lead_change(interp, command);
    let change = match function {
        GFunction::ThreadSingleLeadIncreasing => change.abs(),
        GFunction::ThreadSingleLeadDecreasing => -change.abs(),
        _ => change,
    };
    let chamfer = thread_pass::chamfer(interp, command, lead_mm);
    let pass = Pass { axes, from, points: vec![axes.point(start_along, axes.depth(end) + taper), end], chamfer };
    // `C`, degrees, turns the spindle past its index before the pass starts.
    interp.emitter.thread_phase = interp.param(command, Role::Phase).map_or(0.0, |c| (c / 360.0).rem_euclid(1.0));
    let lasts = pass.emit(interp, &modal, (lead_mm, change));
    interp.emitter.thread_phase = 0.0;
    thread_pass::report_lead_to_nothing(interp, lasts, span);
    interp.report_zero_feed(span);
    Flow::Next
}
