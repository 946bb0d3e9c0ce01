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
//! - The final pass (depth `H`) runs on the contour itself: its moves are recorded with the
//!   contour's blocks (`Expansion::root`), which `compensate` edits in place to correct the
//!   finished thread while the call stays.

use crate::diagnostic::DiagnosticKind;
use crate::syntax::Command;

use super::super::interpreter::{Flow, Interpreter};
use super::super::profile::{Segment, Shape};
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
    for (n, pass) in infeed.plan.passes.iter().enumerate() {
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
        for start in 0..infeed.starts {
            interp.emitter.thread_phase = f64::from(start) / f64::from(infeed.starts);
            let first = interp.emitter.moves.len();
            thread.emit(interp, &modal, (lead_mm, 0.0));
            if n + 1 == infeed.plan.passes.len() {
                interp.cycle_root = root_blocks(interp, &profile.segments[..approach], elements, &thread, first);
            }
        }
    }
    interp.emitter.thread_phase = 0.0;
    interp.report_zero_feed(span);
    contour.consume(interp);
    flow
}

/// The contour blocks that place the final pass `thread`, whose moves start at move `first`
/// (`Expansion::root`): the last approach block with the rapid to the thread's start, each
/// element's block with its thread move. Empty where the moves made are not one rapid and
/// then one thread move per element (a pass that starts where the tool stands).
fn root_blocks(
    interp: &Interpreter<'_, '_>,
    approach: &[Segment],
    elements: &[Segment],
    thread: &Pass,
    first: usize,
) -> Vec<(usize, usize)> {
    let moves = thread.moves();
    let made = interp.emitter.moves.len() - first;
    let threads = moves.iter().skip(1).take_while(|m| m.threading).count();
    let (Some(last_approach), Some(entry)) = (approach.last(), moves.first()) else { return Vec::new() };
    if made != moves.len() || entry.threading || threads != elements.len() {
        return Vec::new();
    }
    let blocks = interp.program.blocks();
    let block_of = |segment: &Segment| blocks.partition_point(|b| b.span.start <= segment.source.start).checked_sub(1);
    std::iter::once(last_approach)
        .chain(elements)
        .enumerate()
        .map(|(k, segment)| block_of(segment).map(|block| (first + k, block)))
        .collect::<Option<Vec<_>>>()
        // One block, one move: a block that makes several elements cannot carry each its own.
        .filter(|root| root.windows(2).all(|w| w[0].1 < w[1].1))
        .unwrap_or_default()
}
