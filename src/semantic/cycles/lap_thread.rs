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
//! - The contour is found, read and owned as the LAP roughing cycles' contours are
//!   (`lap_contour.rs`): before or after the call, its name compared as text; right after
//!   the call it belongs to the call (the flow continues after its `G80`, and `expand`
//!   deletes it with the call), anywhere else it stays for other calls.

use crate::diagnostic::DiagnosticKind;
use crate::syntax::Command;

use super::super::interpreter::{Flow, Interpreter};
use super::super::profile::Shape;
use super::Call;
use super::compound_thread::infeed_of;
use super::lap_contour::{self, Direction};
use super::thread_pass::{self, Axes, Pass};

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command) -> Flow {
    let Some((Call { span, start: from }, contour)) = lap_contour::call(interp, index, command) else {
        return Flow::Next;
    };
    let flow = contour.flow_after();
    let (modal, lead_mm) = thread_pass::thread_modal(interp, command);
    let profile = &contour.profile;
    // The approach (leading rapids), then straight thread elements only.
    let approach = profile.segments.iter().take_while(|s| s.rapid).count();
    let thread_start = profile.segments[..approach].last().map_or(profile.start, |s| s.end);
    let elements = &profile.segments[approach..];
    if let Some(bad) = elements.iter().find(|s| s.rapid || !matches!(s.shape, Shape::Line)) {
        interp.error(DiagnosticKind::ThreadContourNotStraight, bad.source);
        return flow;
    }
    if elements.is_empty() {
        interp.error(DiagnosticKind::ThreadContourNotStraight, contour.span);
        return flow;
    }
    let Some(infeed) = infeed_of(interp, command, span) else { return flow };
    let face = contour.direction == Direction::Transverse;
    if !face {
        super::compound_thread::height_read_as_diameter(interp, command, &infeed, lead_mm);
    }
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
    contour.consume(interp);
    flow
}
