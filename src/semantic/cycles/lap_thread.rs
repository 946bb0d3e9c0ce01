//! OSP LAP continuous thread cutting: `G88 N<name> D H [B] [U | W] F [J] [Q] M3x M7x`
//! ([M-P175], dialects.md §1.7). The contour named by `N` (its `G81`/`G82` block, up to
//! `G80`, before or after the call) is the thread's root line; the thread follows it
//! element after element without stopping, so a straight thread can run into a taper.
//!
//! The passes are those of `G71` (`thread_infeed.rs` with the same words and M codes, so
//! the same checks): a pass at depth `d` follows the contour `(H − d)/2` outside it (in Z
//! for a `G82` face contour), its start shifted along the thread's axis for flank infeed,
//! then rapids out to the start point's depth and back to the start point.
//!
//! Readings of the sources, and what this module does:
//!
//! - The contour is the root, as a LAP contour is the finished shape; rapids before the
//!   first thread element are its approach and set where the thread starts.
//! - Thread elements are straight (`G01`); an arc needs the arc-threading option
//!   (`G112`/`G113`), which is not simulated, and is an error, as is a rapid between
//!   thread elements (the thread must be continuous).
//! - The lead is the call's `F` (`F/J`), else the F in force; F words inside the contour
//!   are finishing feeds for `G87` and are not leads. `U` and `W` are both read as the
//!   allowance, in the unit of `H`. No chamfer (the call takes no `M22`/`M23`).
//! - The contour stays in the program after `expand`: another call may use it.
//!
//! The contour is found by the name of its `G81`/`G82` block with a small lookup of this
//! module's own, until the LAP roughing cycles share theirs.

use crate::diagnostic::DiagnosticKind;
use crate::dialect::{GFunction, Role};
use crate::syntax::{Command, Statement, WordKind};

use super::super::interpreter::{Flow, Interpreter};
use super::super::labels;
use super::super::profile::Shape;
use super::compound_thread::infeed_of;
use super::thread_pass::{self, Axes, Pass};

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command) -> Flow {
    let span = interp.program.block(index).span;
    let from = interp.emitter.at;
    if !from.is_finite() {
        interp.unknown_position(span);
        return Flow::Next;
    }
    let Some((marker, face)) = contour_block(interp, command) else { return Flow::Next };
    let Some(last) = interp.lap_end(marker) else {
        let at = interp.program.block(marker).span;
        interp.error(DiagnosticKind::LapContourNotClosed, at);
        return Flow::Next;
    };
    // The contour's elements are read as moves; they are threads at the lead, so they are
    // read under it (a thread contour needs no feed of its own).
    let (modal, lead_mm) = thread_pass::thread_modal(interp, command);
    let feed_in_force = std::mem::replace(&mut interp.modal.feed, modal.feed);
    let profile = interp.profile(marker..=last, from);
    interp.modal.feed = feed_in_force;
    let profile = match profile {
        Ok(profile) => profile,
        Err(diagnostic) => {
            interp.diagnostics.push(diagnostic);
            return Flow::Next;
        }
    };
    // The approach (leading rapids), then straight thread elements only.
    let approach = profile.segments.iter().take_while(|s| s.rapid).count();
    let thread_start = profile.segments[..approach].last().map_or(profile.start, |s| s.end);
    let elements = &profile.segments[approach..];
    if let Some(bad) = elements.iter().find(|s| s.rapid || !matches!(s.shape, Shape::Line)) {
        interp.error(DiagnosticKind::ThreadContourNotStraight, bad.source);
        return Flow::Next;
    }
    if elements.is_empty() {
        interp.error(DiagnosticKind::ThreadContourNotStraight, interp.program.block(marker).span);
        return Flow::Next;
    }
    let Some(infeed) = infeed_of(interp, command, span) else { return Flow::Next };
    let axes = Axes { face };
    let frame = interp.modal.frame;
    let to_mm = |d: f64| if face { frame.mm(d) } else { frame.x_mm(d) };
    let root: Vec<_> = std::iter::once(thread_start).chain(elements.iter().map(|s| s.end)).collect();
    let thread_end = root.last().copied().unwrap_or(thread_start);
    let out = thread_pass::outward(axes, from, thread_start);
    let toward_start = if axes.along(thread_start) >= axes.along(thread_end) { 1.0 } else { -1.0 };
    let height = to_mm(infeed.height);
    for pass in &infeed.plan.passes {
        let above_root = height - to_mm(pass.depth);
        let shift = pass.flank * above_root * infeed.flank_slope * toward_start;
        let points = root
            .iter()
            .enumerate()
            .map(|(i, &p)| {
                let along = axes.along(p) + if i == 0 { shift } else { 0.0 };
                axes.point(along, axes.depth(p) + out * above_root)
            })
            .collect();
        let thread = Pass { axes, from, points, chamfer: None };
        for _ in 0..infeed.starts {
            thread.emit(interp, &modal, lead_mm);
        }
    }
    interp.report_zero_feed(span);
    Flow::Next
}

/// The `G81`/`G82` block the call's `N` names, and whether it is a face (`G82`) contour.
fn contour_block(interp: &mut Interpreter<'_, '_>, command: &Command) -> Option<(usize, bool)> {
    let id = command.param(Role::ContourName)?;
    let word = *interp.program.word(id);
    let WordKind::Label { number } = word.kind else { return None };
    let key = labels::key(interp.dialect, interp.program.text(word.span), number);
    let found = interp.labels.blocks(&key).iter().copied().find_map(|i| {
        let block = interp.program.block(i);
        if !matches!(block.statement, Statement::LapMarker(_)) {
            return None;
        }
        interp.g_infos(interp.program.words_of(block)).iter().find_map(|(_, g)| match g.function {
            Some(GFunction::LapContourLongitudinal) => Some((i, false)),
            Some(GFunction::LapContourTransverse) => Some((i, true)),
            _ => None,
        })
    });
    if found.is_none() {
        interp.error(DiagnosticKind::ThreadContourNotFound { name: format!("N{key}") }, word.span);
    }
    found
}
