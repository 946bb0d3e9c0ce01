//! One OSP thread pass, the motion of a `G33` (`G32` on a face) single-pass cycle, which
//! the multi-pass cycles (`G71`, `G72`, `G88`) repeat at growing depth:
//!
//! ```txt
//!   from ●◀──────────4 rapid──────────● ▲
//!        │1 rapid                       │3 rapid (back to from's depth)
//!        ▼                              │
//!        ●━━━━━━━━━2 thread━━━━━━━━━━━━╱●  ← with chamfering (M23) the last L along the
//!      start                       end      axis pulls out at 45° while still threading
//! ```
//!
//! `along` is the thread's axis (Z for a longitudinal thread, X for a face thread) and
//! `depth` the infeed axis. The shape is a pure function of the pass, so that `expand` can
//! check that a cycle's moves are exactly such passes before it writes them as `G33` blocks.

use crate::diagnostic::DiagnosticKind;
use crate::dialect::Role;
use crate::source::Span;
use crate::syntax::Command;
use crate::toolpath::Xz;

use super::super::interpreter::Interpreter;
use super::super::modal::Modal;

/// The axes of a thread: longitudinal (thread along Z, infeed in X) or face (along X, infeed in Z).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Axes {
    pub face: bool,
}

impl Axes {
    pub fn along(self, p: Xz) -> f64 {
        if self.face { p.x } else { p.z }
    }

    pub fn depth(self, p: Xz) -> f64 {
        if self.face { p.z } else { p.x }
    }

    pub fn point(self, along: f64, depth: f64) -> Xz {
        if self.face { Xz::new(along, depth) } else { Xz::new(depth, along) }
    }
}

/// A pass: the thread from `points[0]` through the other points (one more for a straight
/// or taper thread, several for a LAP contour), entered from and left back to `from`.
#[derive(Debug, Clone, PartialEq)]
pub struct Pass {
    pub axes: Axes,
    pub from: Xz,
    pub points: Vec<Xz>,
    /// Thread-end chamfer length along the thread's axis (chamfering on), mm.
    pub chamfer: Option<f64>,
}

/// One move of a pass: where it ends and whether it threads (else it is a rapid).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassMove {
    pub to: Xz,
    pub threading: bool,
}

struct Moves {
    at: Xz,
    moves: Vec<PassMove>,
}

impl Moves {
    fn push(&mut self, to: Xz, threading: bool) {
        if self.at.distance(to) > NO_MOVE_MM {
            self.moves.push(PassMove { to, threading });
            self.at = to;
        }
    }
}

/// Lengths below this are no move (the emitter drops such rapids too), mm.
const NO_MOVE_MM: f64 = 1e-9;

impl Pass {
    /// The moves of the pass, without the ones that go nowhere.
    pub fn moves(&self) -> Vec<PassMove> {
        let axes = self.axes;
        let mut out = Moves { at: self.from, moves: Vec::with_capacity(self.points.len() + 4) };
        let Some((&first, rest)) = self.points.split_first() else { return out.moves };
        out.push(first, false);
        let Some((&end, middle)) = rest.split_last() else { return out.moves };
        for &p in middle {
            out.push(p, true);
        }
        let before_end = middle.last().copied().unwrap_or(first);
        match self.chamfer.filter(|l| *l > NO_MOVE_MM) {
            Some(length) => {
                // The pull-out starts `length` before the end along the axis, on the last
                // element, and rises by the same amount away from the work (toward `from`).
                let run = (axes.along(end) - axes.along(before_end)).abs();
                let t = if run > NO_MOVE_MM { (1.0 - length / run).max(0.0) } else { 0.0 };
                let pull_start =
                    Xz::new(before_end.x + (end.x - before_end.x) * t, before_end.z + (end.z - before_end.z) * t);
                let out_sign = outward(axes, self.from, end);
                let pull_end = axes.point(axes.along(end), axes.depth(pull_start) + out_sign * length);
                out.push(pull_start, true);
                out.push(pull_end, true);
            }
            None => out.push(end, true),
        }
        let thread_end = out.at;
        out.push(axes.point(axes.along(thread_end), axes.depth(self.from)), false);
        out.push(self.from, false);
        out.moves
    }

    /// Run the pass: rapids at the rapid rate, thread moves at `lead_mm` per revolution,
    /// growing by `change_mm` every revolution from the pass's first thread move
    /// (`G34`/`G35`: a chamfer goes on at the lead the thread reached). `modal` carries the F
    /// (the lead, program units) and S the moves record. False where the lead shrinks to
    /// nothing before the pass's end.
    pub(in crate::semantic) fn emit(
        &self,
        interp: &mut Interpreter<'_, '_>,
        modal: &Modal,
        (lead_mm, change_mm): (f64, f64),
    ) -> bool {
        let mut turns = 0.0;
        let mut lasts = true;
        for m in self.moves() {
            if !m.threading {
                interp.emitter.rapid(modal, m.to);
            } else if change_mm == 0.0 {
                interp.emitter.thread(modal, m.to, lead_mm);
            } else {
                lasts &= interp.emitter.varying_thread(modal, m.to, (lead_mm, change_mm), &mut turns).is_some();
            }
        }
        lasts
    }
}

/// The modal state a thread cycle's moves run under, and its lead in mm: the cycle's own
/// `S` for its moves, and its lead as the F they record: `F`, or `F/J` when `J` threads
/// share the length `F` ([M-P97] "F/J if a J word is provided"); without `F`, the F in force.
pub(in crate::semantic) fn thread_modal(interp: &mut Interpreter<'_, '_>, command: &Command) -> (Modal, f64) {
    let mut modal = interp.modal.clone();
    let lead = interp.param(command, Role::Lead).unwrap_or(modal.feed);
    let threads = interp.param(command, Role::ThreadsPerInch).filter(|j| *j > 0.0).unwrap_or(1.0);
    modal.feed = lead / threads;
    if let Some(speed) = interp.param(command, Role::Speed) {
        modal.speed = speed;
    }
    let lead_mm = modal.frame.feed_mm(modal.feed);
    (modal, lead_mm)
}

/// A warning where a thread cycle's thread is `length` mm long along its axis and that is
/// no length: the passes still plunge and back out (the moves the cycle makes), but a
/// forgotten `Z`/`W` is the likelier reading than a thread meant to cut nothing.
pub(in crate::semantic) fn warn_if_no_length(interp: &mut Interpreter<'_, '_>, length: f64, span: Span) {
    if length <= NO_MOVE_MM {
        interp.warning(DiagnosticKind::ThreadOfNoLength, span);
    }
}

/// The taper of a thread `length` mm long, mm across it: `I` as written, else from the taper
/// angle `A` (degrees), else none.
pub(in crate::semantic) fn taper(interp: &mut Interpreter<'_, '_>, command: &Command, length: f64) -> f64 {
    match (interp.param(command, Role::Taper), interp.param(command, Role::TaperAngle)) {
        (Some(i), _) => interp.modal.frame.mm(i),
        (None, Some(angle)) => angle.to_radians().tan() * length,
        (None, None) => 0.0,
    }
}

/// The lead change per revolution (`E` of `G34`/`G35`), mm.
pub(in crate::semantic) fn lead_change(interp: &mut Interpreter<'_, '_>, command: &Command) -> f64 {
    interp.param(command, Role::LeadChange).map_or(0.0, |e| interp.modal.frame.feed_mm(e))
}

/// The spindle's turns past its index at which a thread starts, from a start-angle word's
/// value (`value`): a count of 0.001° (Fanuc-compatible `G92`/`G32`/Haas `G76` `Q`).
pub(in crate::semantic) fn start_angle_turns(value: f64) -> f64 {
    (value / 360_000.0).rem_euclid(1.0)
}

/// An error where a pass's lead shrank to nothing before the thread's end: the control
/// stops with an alarm there.
pub(in crate::semantic) fn report_lead_to_nothing(interp: &mut Interpreter<'_, '_>, lasts: bool, span: Span) {
    if !lasts {
        interp.error(DiagnosticKind::LeadShrinksToNothing, span);
    }
}

/// The chamfer at the thread's end while chamfering is on (`M23`): the call's `L`, else one
/// lead; none when it is off.
pub(in crate::semantic) fn chamfer(interp: &mut Interpreter<'_, '_>, command: &Command, lead_mm: f64) -> Option<f64> {
    let frame = interp.modal.frame;
    interp.cycle_memory.thread_chamfer.then(|| interp.param(command, Role::Chamfer).map_or(lead_mm, |l| frame.mm(l)))
}

/// +1 when `from` lies on the increasing side of `end` along the infeed axis (an outside
/// thread for a longitudinal pass), −1 on the other side.
pub fn outward(axes: Axes, from: Xz, end: Xz) -> f64 {
    if axes.depth(from) >= axes.depth(end) { 1.0 } else { -1.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pass(chamfer: Option<f64>) -> Pass {
        Pass {
            axes: Axes { face: false },
            from: Xz::new(20.0, 5.0),
            points: vec![Xz::new(14.0, 5.0), Xz::new(14.0, -20.0)],
            chamfer,
        }
    }

    #[test]
    fn a_pass_goes_in_threads_retracts_and_returns() {
        let moves = pass(None).moves();
        let points: Vec<(f64, f64, bool)> = moves.iter().map(|m| (m.to.x, m.to.z, m.threading)).collect();
        assert_eq!(points, [(14.0, 5.0, false), (14.0, -20.0, true), (20.0, -20.0, false), (20.0, 5.0, false)]);
    }

    #[test]
    fn a_chamfer_pulls_out_at_45_degrees_over_its_length() {
        let moves = pass(Some(1.5)).moves();
        let points: Vec<(f64, f64, bool)> = moves.iter().map(|m| (m.to.x, m.to.z, m.threading)).collect();
        assert_eq!(
            points,
            [(14.0, 5.0, false), (14.0, -18.5, true), (15.5, -20.0, true), (20.0, -20.0, false), (20.0, 5.0, false)]
        );
    }
}
