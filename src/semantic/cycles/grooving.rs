//! OSP `G73` grooving / cutting off in X and `G74` end-face cutting / peck drilling in Z,
//! one block each (dialects.md §1.6, [GE] §6.1):
//!
//! `G74 X Z [I] [K] D [L] [DA=] [E] F [T]` and `G73 X Z [I] [K] D [L] [DA=] [E] F`.
//!
//! `G74` plunges along Z from the tool's position S to `Z`, at one X after the other from
//! S's X to `X`, stepping by `I` (a diameter); `D` is the peck, `DA=` the retract after a
//! peck, `L` the depth after which the tool leaves the hole to clear the chips, `E` the
//! dwell at the bottom, `F` the feed. `G73` is the same with the axes swapped: plunges
//! along X to `X`, at one Z after the other from S's Z to `Z`, stepping by `K`; its `D`,
//! `L` and `DA=` run along X and are diameters, as every OSP X-direction word.
//!
//! ```txt
//!   S ●──rapid──▶●──rapid──▶●         (G74: steps in X by I)
//!     │ ▲        │ ▲        │ ▲
//!     ▼ │rapid   ▼ │        ▼ │       each plunge: feed D, rapid back DA=, feed D + DA=, …
//!     ▼ │        ▼ │        ▼ │       (after L, back out to S's Z and in again), dwell E at
//!     ● ┘        ● ┘        ● ┘       the bottom, rapid out; at the end, back to S
//! ```
//!
//! Readings of the sources, and what this module does:
//!
//! - The real `G73 X47 Z534.15 K2.79 D4 L12.4 F0.1 E0.14` (OSP7000L) is read like `G74`:
//!   `K` the Z step between plunges (2.79 = 0.9 × the 3.1 mm tool width the program's second
//!   offset describes), `D` the peck, `L` the clearing depth (12.4, more than the 5 mm
//!   groove: no clearing), `E` the dwell (0.14 s and 0.167 s in its two grooves, in the
//!   ratio of their diameters: about two revolutions at the bottom). The address list of
//!   the manual gives the same meanings to these letters in its other cycles.
//! - Steps are exact from the start, the last plunge at the end (`X`/`Z`) even when it is
//!   closer than a step. An end off the start line with no step word is an error.
//! - Without `D` the tool plunges in one go; without `DA=` it retracts 0.1 mm (the control
//!   takes it from a parameter; 0.1 mm is the LAP relief parameter's default).
//! - The tool comes back to S at the end.
//! - `T` (offset for the end point), `OG=` and `TG=` choose tool offsets, which the
//!   toolpath (the programmed path) does not apply.

use crate::diagnostic::DiagnosticKind;
use crate::dialect::{GFunction, Role};
use crate::syntax::Command;
use crate::toolpath::Xz;

use super::super::interpreter::{Flow, Interpreter};
use super::Call;
use super::thread_infeed::MAX_PASSES;

/// The retract after a peck when `DA=` is not given, mm.
const DEFAULT_PECK_RETRACT_MM: f64 = 0.1;

/// Pecks of all plunges beyond this are an error (bounded work).
const MAX_PECKS: f64 = 100_000.0;

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command, function: GFunction) -> Flow {
    let Some(Call { span, start: from }) = interp.cycle_call(index) else { return Flow::Next };
    let frame = interp.modal.frame;
    // `plunge_x`: G73 plunges along X and steps along Z; G74 the other way round.
    let plunge_x = function == GFunction::OspGrooving;
    let along_plunge = |interp: &mut Interpreter<'_, '_>, role: Role| {
        interp.param(command, role).map(|v| if plunge_x { frame.x_mm(v).abs() } else { frame.mm(v).abs() })
    };
    let peck = along_plunge(interp, Role::PeckDepth).filter(|d| *d > 0.0);
    let clearing = along_plunge(interp, Role::Relief).filter(|l| *l > 0.0);
    let retract = along_plunge(interp, Role::PeckRetract).unwrap_or(DEFAULT_PECK_RETRACT_MM);
    let (step_role, step_letter, step_axis) =
        if plunge_x { (Role::ShiftZ, 'K', 'Z') } else { (Role::ShiftX, 'I', 'X') };
    let step = interp
        .param(command, step_role)
        .map(|v| if plunge_x { frame.mm(v).abs() } else { frame.x_mm(v).abs() })
        .filter(|s| *s > 0.0);
    let dwell = interp.param(command, Role::DwellSeconds).filter(|e| *e > 0.0);
    let end = interp.cycle_end(command, from);

    // (step axis, plunge axis) coordinates.
    let split = |p: Xz| if plunge_x { (p.z, p.x) } else { (p.x, p.z) };
    let join =
        |step_at: f64, plunge_at: f64| if plunge_x { Xz::new(plunge_at, step_at) } else { Xz::new(step_at, plunge_at) };
    let (step_from, plunge_from) = split(from);
    let (step_to, plunge_to) = split(end);
    let travel = (step_to - step_from).abs();
    let positions = if travel < 1e-9 {
        vec![step_from]
    } else {
        let Some(step) = step else {
            let at = interp.param_span(command, if plunge_x { Role::EndZ } else { Role::EndX }, span);
            interp.error(DiagnosticKind::CycleNeedsShift { shift: step_letter, axis: step_axis }, at);
            return Flow::Next;
        };
        let count = (travel / step).ceil() + 1.0;
        if count > MAX_PASSES as f64 {
            let at = interp.param_span(command, step_role, span);
            interp.error(DiagnosticKind::TooManyPasses { passes: count as usize, max: MAX_PASSES }, at);
            return Flow::Next;
        }
        let direction = (step_to - step_from).signum();
        let mut positions: Vec<f64> = (0..count as usize)
            .map(|n| step_from + direction * step * n as f64)
            .take_while(|p| (p - step_from).abs() < travel - 1e-9)
            .collect();
        positions.push(step_to);
        positions
    };
    let depth = (plunge_to - plunge_from).abs();
    let pecks = peck.map_or(1.0, |d| (depth / d).ceil().max(1.0));
    if pecks * positions.len() as f64 > MAX_PECKS {
        let at = interp.param_span(command, Role::PeckDepth, span);
        let passes = (pecks * positions.len() as f64).min(usize::MAX as f64) as usize;
        interp.error(DiagnosticKind::TooManyPasses { passes, max: MAX_PECKS as usize }, at);
        return Flow::Next;
    }

    let mut modal = interp.modal.clone();
    if let Some(feed) = interp.param(command, Role::Feed) {
        modal.feed = feed;
    }
    let direction = (plunge_to - plunge_from).signum();
    let at_depth = |reached: f64| plunge_from + direction * reached;
    let e = &mut interp.emitter;
    for position in positions {
        e.rapid(&modal, join(position, plunge_from));
        let mut reached = 0.0;
        let mut since_clearing = 0.0;
        while depth - reached > 1e-9 {
            let next = peck.map_or(depth, |d| (reached + d).min(depth));
            e.line(&modal, join(position, at_depth(next)), true);
            since_clearing += next - reached;
            reached = next;
            if depth - reached <= 1e-9 {
                break;
            }
            if clearing.is_some_and(|l| since_clearing >= l - 1e-9) {
                // Out of the cut to clear the chips, and back in to just short of the bottom.
                e.rapid(&modal, join(position, plunge_from));
                since_clearing = 0.0;
            }
            e.rapid(&modal, join(position, at_depth((reached - retract).max(0.0))));
        }
        if let Some(seconds) = dwell {
            e.dwell(&modal, seconds);
        }
        e.rapid(&modal, join(position, plunge_from));
    }
    e.rapid(&modal, from);
    interp.report_zero_feed(span);
    Flow::Next
}
