//! OSP tapping: `G77` right-hand, `G78` left-hand, `G77 X Z K F [E]` (dialects.md §1.6,
//! [GE] §6.2). From the tool's position S: rapid to `X`, rapid `K` toward `Z` (the
//! approach), tap to `Z` with the feed tied to the spindle (the lead `F` per revolution),
//! dwell `E` if given, the spindle reverses and the tap backs out the same way to where it
//! began cutting, then rapids back to S's Z and to S.
//!
//! Right- and left-hand tapping differ in the spindle's direction only, which the toolpath
//! does not hold, so both make the same moves. Under feed per minute (`G94`) `F` is the
//! feed, and the lead is `F` divided by the spindle speed at `X`. The tap's moves are
//! thread moves (feed synchronised with the spindle), so `expand` keeps the cycle.

use crate::dialect::Role;
use crate::syntax::Command;
use crate::toolpath::Xz;

use super::super::interpreter::{Flow, Interpreter};
use super::Call;

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command) -> Flow {
    let Some(Call { span, start: from }) = interp.cycle_call(index) else { return Flow::Next };
    let frame = interp.modal.frame;
    let end = interp.cycle_end(command, from);
    let approach = interp.param(command, Role::StartShift).map_or(0.0, |k| frame.mm(k).abs());
    let dwell = interp.param(command, Role::DwellSeconds).filter(|e| *e > 0.0);
    let mut modal = interp.modal.clone();
    if let Some(feed) = interp.param(command, Role::Lead) {
        modal.feed = feed;
    }
    let feed_mm = frame.feed_mm(modal.feed);
    let lead_mm = if modal.feed_per_rev {
        feed_mm
    } else {
        let rpm = modal.rpm_at(end.x);
        if rpm > 0.0 { feed_mm / rpm } else { 0.0 }
    };
    let direction = (end.z - from.z).signum();
    let cut_start = Xz::new(end.x, from.z + direction * approach.min((end.z - from.z).abs()));
    let e = &mut interp.emitter;
    e.rapid(&modal, Xz::new(end.x, from.z));
    e.rapid(&modal, cut_start);
    e.thread(&modal, end, lead_mm);
    if let Some(seconds) = dwell {
        e.dwell(&modal, seconds);
    }
    e.thread(&modal, cut_start, lead_mm);
    e.rapid(&modal, Xz::new(end.x, from.z));
    e.rapid(&modal, from);
    interp.report_zero_feed(span);
    Flow::Next
}
