//! OSP LAP `G86 N<name> D F [U] [W] [M85]`: copy turning (AP mode II), the pattern-repeat
//! roughing for cast or forged stock that already has the part's shape.
//!
//! Every pass follows the whole contour, shifted so that its start point lies on the infeed
//! line of `lap_frame.rs`: pass N starts at `(Xp, Zp)` with `Xp = Xs − N·D` and `Zp` from
//! M-P195, and the contour is offset from the finished one by `(U + XOFF, W + ZOFF)` with
//! `XOFF = Xp − (Xa + U)`, `ZOFF = Zp − (Za + W)`, exactly M-P195's offsets. Passes repeat
//! while the infeed point stays above Xa + U; then (XOFF, ZOFF) = (0, 0) and the last pass
//! runs along the contour offset by (U, W) (M-P195 step 8). With the usual first contour
//! block `G00 X…` (Za = Zs) the Z offset of pass N from the finished contour is W times the
//! share of the stock already cut: the passes close in on the finished contour without ever
//! crossing it, but near a shoulder they run up to W inside the Z allowance.
//!
//! ```txt
//!   A ●                                        each pass: approach the shifted start
//!      ╲●━━━━━━━━━━━━━━━━━━━━━━━╮                (as the contour's first block moves),
//!        ╲●━━━━━━━━━━━━━━━━━━╮  ┃                 follow the shifted contour at F,
//!          ╲●━━━━━━━━━━━━━━╮ ┃  ┃                 rapid straight up above its highest
//!        C0 ●━━━━━━━━━━━━╮ ┃ ┃  ┃                 point, back along the cut, and down
//! ```
//!
//! Between passes the tool leaves the end of the pass straight away from the axis (for
//! outside turning) to 0.1 mm above the pass's highest point, returns along the cut above
//! everything cut so far, and comes down at the next start. When A lies further back along
//! the cut than C0 the last stretch of that descent crosses stock and is fed (see
//! `lap_frame.rs`). After the last pass the tool returns to the AP start point
//! (`lap_contour.rs`) unless the call holds M85.
//!
//! `G84` condition changes belong to `G85` bar turning (M-P177); a `G86` that carries them
//! is warned about and cut without them. The contour feed `E` is for bar turning; copy
//! passes run at the call's F (else the feed in force). The contour must run one way along
//! the cut, as for `G85`: an undercut cannot be followed by the passes nor left by the
//! return.

use crate::diagnostic::DiagnosticKind;
use crate::dialect::Role;
use crate::geometry;
use crate::syntax::Command;
use crate::toolpath::Xz;

use super::super::interpreter::{Flow, Interpreter};
use super::Call;
use super::canonical::{self, Uv};
use super::lap_contour;
use super::lap_frame::{self, RELIEF_MM, RoughFrame};
use super::lap_rough::CallWords;

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command) -> Flow {
    let Some((Call { span, start }, contour)) = lap_contour::call(interp, index, command) else { return Flow::Next };
    let flow = contour.flow_after();
    let Some(words) = CallWords::read(interp, command, &contour) else { return flow };
    warn_conditions(interp, command);
    if !contour.roughable(interp, span) {
        return flow;
    }
    let frame = RoughFrame::new(&contour, start, words.x_allowance, words.z_allowance);
    if frame.stock_depth() < -1e-9 {
        interp.error(DiagnosticKind::LapStartInsideContour, span);
        return flow;
    }
    if words.too_many_passes(interp, frame.stock_depth(), words.depth, span) {
        return flow;
    }
    let saved = interp.modal.clone();
    interp.modal.feed = words.feed;
    let shares = shares(frame.stock_depth(), words.depth);
    let rapid_approach = contour.approach_rapid() && !frame.plunge_cuts();
    let top = top(&frame);
    let mut at = frame.start;
    let mut previous = 1.0;
    for (n, &share) in shares.iter().enumerate() {
        let offset = offset(&frame, share);
        let first = Uv { u: frame.contour_start.u + offset.u, v: frame.contour_start.v + offset.v };
        frame.go(interp, Uv { u: at.u, v: first.v }, true);
        if !rapid_approach {
            // Rapid down to just above what the previous pass left, then feed.
            let before = self::offset(&frame, previous);
            let left = canonical::u_at(&frame.elements, first.v - before.v) + before.u;
            frame.go(interp, Uv { u: (left + RELIEF_MM).min(at.u).max(first.u), v: first.v }, true);
        }
        frame.go(interp, first, rapid_approach);
        let shift = frame.canon.from(offset);
        let along = Xz::new(frame.allowance.x + shift.x, frame.allowance.z + shift.z);
        lap_frame::cut_along(interp, &contour, along, |_| words.feed);
        if n + 1 < shares.len() {
            let end = frame.canon.to(interp.emitter.at);
            at = Uv { u: top + offset.u + RELIEF_MM, v: end.v };
            frame.go(interp, at, true);
        }
        previous = share;
    }
    interp.modal = saved;
    words.end_call(interp, &contour, start);
    flow
}

/// The share of the stock each pass leaves (1 at A, 0 on the contour plus allowance): passes
/// step `depth` from A while they stay above the contour start, then the last pass at 0.
pub(super) fn shares(stock: f64, depth: f64) -> Vec<f64> {
    let mut out = Vec::new();
    if stock > 1e-9 && depth > 0.0 {
        let mut cut = depth;
        while cut < stock - 1e-9 {
            out.push((stock - cut) / stock);
            cut += depth;
        }
    }
    out.push(0.0);
    out
}

/// The canonical offset of the pass that leaves `share` of the stock: `share · (A − C0)`.
fn offset(frame: &RoughFrame, share: f64) -> Uv {
    Uv { u: share * (frame.start.u - frame.contour_start.u), v: share * (frame.start.v - frame.contour_start.v) }
}

/// The highest `u` of the allowance-shifted contour, arcs included.
fn top(frame: &RoughFrame) -> f64 {
    let mut top = frame.contour_start.u;
    for e in &frame.elements {
        top = top.max(e.start.u).max(e.end.u);
        if let Some((c, ccw)) = e.arc {
            let peak = Uv { u: c.u + e.radius(), v: c.v };
            let as_xz = |q: Uv| Xz::new(q.u, q.v);
            if geometry::angle_within(as_xz(peak), as_xz(e.start), as_xz(e.end), as_xz(c), ccw) {
                top = top.max(peak.u);
            }
        }
    }
    top
}

/// `G84` condition changes in a `G86` call: warned about, not applied.
fn warn_conditions(interp: &mut Interpreter<'_, '_>, command: &Command) {
    let roles = [
        Role::ConditionXA,
        Role::ConditionXB,
        Role::ConditionZA,
        Role::ConditionZB,
        Role::ConditionDepthA,
        Role::ConditionDepthB,
        Role::ConditionFeedA,
        Role::ConditionFeedB,
    ];
    if let Some(id) = roles.iter().find_map(|&r| command.param(r)) {
        let word = *interp.program.word(id);
        let text = String::from_utf8_lossy(interp.program.text(word.span)).into_owned();
        let name = text.split('=').next().unwrap_or("").to_string() + "=";
        let reason = "condition changes (G84) apply to G85 bar turning; this G86 cuts without them";
        interp.warning(DiagnosticKind::LapConditionMisplaced { word: name, reason }, word.span);
    }
}
