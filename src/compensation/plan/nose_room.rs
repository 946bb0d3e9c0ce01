//! Room for the nose under nose-radius compensation: no written element that the control
//! would use up at a concave corner.
//!
//! Under `G41`/`G42` the control offsets every written element by the nose radius and, at
//! a corner that turns toward the tool, cuts the two offset elements back to where they
//! cross (`semantic::nose_radius::path`). An element shorter than those cut-backs runs
//! backwards once offset, and the control stops with an alarm although nothing would be
//! gouged (Fanuc 30i, B-63944EN-1/02, 5 "When interference is assumed although actual
//! interference does not occur": a depression or a step smaller than the nose radius).
//! Compensation writes such elements of its own: the play taken up at a reversal as a
//! short move of its own (`plan.rs`), or the last chords of a densified arc next to the
//! corner it runs into. A control reads several blocks ahead to make these corners, so the
//! element and its neighbours are seen together here, the previous move's last element
//! among them.
//!
//! The nose never touches such an element: it lies wholly inside the cut-backs, in the
//! corner the nose rounds. So it is left out, and its neighbours are carried on to where
//! they meet, which is the path a control with interference avoidance makes of it (the
//! interfering block's offset vectors dropped and the neighbours' offsets joined:
//! Mitsubishi M700V, 12.4 "Operation during interference avoidance"; Beckhoff's bottleneck
//! detection "segments may be left out"), written so that every control runs it. Only
//! lines between lines are joined (their meeting point is one point, near the corner);
//! a step between two arcs (the play taken up where an arc reverses an axis) becomes the
//! line tangent to the arc the tool runs outside of, which leaves the nose one convex
//! corner to roll round. Whatever is joined or bridged is measured on the part by the check
//! before writing, which refuses the program where the take-up so moved leaves the part
//! off by more than the bound.

use crate::geometry;
use crate::semantic::nose_radius::path::{self, Curve, Problem};
use crate::toolpath::{Compensation, Motion, Xz};

use super::{MovePlan, PlanInput, Segment};

/// A written element: which plan holds it (0: the previous written move's, 1: this
/// move's) and its index there.
type Owner = (usize, usize);

/// The previous written move's plan, and whether its move switches compensation on: the
/// control makes that block the start-up, which ends perpendicular to the next element,
/// so no corner of the contour is cut there.
pub(super) struct Before<'a> {
    pub plan: &'a mut MovePlan,
    pub starts: bool,
}

/// At most this many elements are left out at one move (each pass leaves out one).
const MAX_JOINS: usize = 16;

/// `make_room` for move `index` and its plan, given the plans of the moves from `first`
/// before it (`earlier`): the previous written move's plan is the last of them with
/// segments (a corner the control makes, or a dwell, writes none), when it belongs to the
/// same compensated run and may be rewritten. The plans between keep starting where it
/// ends. Returns whether an arc of `plan` moved (its words are to be chosen again). A plan
/// in an earlier piece of the stream (`program/stream.rs`) has gone on to be rounded: a
/// corner between two pieces is left as it is, and the read-back refuses what the control
/// would.
pub(super) fn make_room_at(
    input: &PlanInput<'_>,
    index: usize,
    earlier: &mut [MovePlan],
    first: usize,
    plan: &mut MovePlan,
    jogs: &[Xz],
) -> bool {
    let moves = &input.toolpath.moves;
    let Some(m) = moves.get(index) else { return false };
    let writable = |k: usize| input.writable.get(k).copied().unwrap_or(false);
    let cuts =
        |k: usize| moves.get(k).is_some_and(|c| c.motion != Motion::Rapid && c.motion != Motion::Dwell && !c.threading);
    if m.compensation == Compensation::Off || !cuts(index) || !writable(index) {
        return false;
    }
    let (radius, _) = input.tools.lookup(m.tool, m.offset);
    let side = if m.compensation == Compensation::Left { 1.0 } else { -1.0 };
    let previous = earlier.iter().rposition(|p| !p.segments.is_empty()).filter(|&j| {
        let k = first + j;
        let p = &moves[k];
        p.compensation == m.compensation
            && (p.tool, p.offset) == (m.tool, m.offset)
            && cuts(k)
            && writable(k)
            && !earlier[j].lead_in
    });
    match previous {
        Some(j) => {
            let k = first + j;
            let starts = k == 0 || moves[k - 1].compensation != moves[k].compensation;
            let (head, between) = earlier.split_at_mut(j + 1);
            let before = head.last_mut().map(|b| Before { plan: b, starts });
            let arcs_moved = make_room(before, plan, radius, side, jogs);
            for p in between {
                p.start = plan.start;
            }
            arcs_moved
        }
        None => make_room(None, plan, radius, side, jogs),
    }
}

/// Leave out every line of `plan` (and the last line of `before`, the previous written
/// move's plan of the same compensated run, when it may be rewritten) that the control
/// would use up at a concave corner between two lines, joining its neighbours where they
/// meet, and make a step of `plan` between two of its arcs that the control would use up
/// the line tangent to one of them (`bridged`). `side` is +1 for `G41`, −1 for `G42`;
/// `jogs` are the steps `plan` writes as moves of their own (a backlash take-up), so that a
/// step done away with is not counted. Returns whether an arc of `plan` moved.
pub(super) fn make_room(before: Option<Before<'_>>, plan: &mut MovePlan, radius: f64, side: f64, jogs: &[Xz]) -> bool {
    if radius <= 0.0 || plan.lead_in {
        return false;
    }
    let starts = before.as_ref().is_some_and(|b| b.starts);
    let mut before = before.map(|b| b.plan);
    let mut arcs_moved = false;
    for _ in 0..MAX_JOINS {
        let (curves, owners) = chain(before.as_deref(), plan);
        // The elements the control offsets: after a start-up, not the start-up itself.
        let skip = if starts { owners.iter().take_while(|(owner, _)| *owner == 0).count() } else { 0 };
        let mut offsets = vec![None; skip];
        offsets.extend(path::offset_chain(&curves[skip..], radius, side).into_iter().map(|o| o.problem));
        let Some((i, fix)) = (1..curves.len().saturating_sub(1)).find_map(|i| {
            if offsets[i] != Some(Problem::UsedUp) {
                return None;
            }
            // `before` gives up only its last element, and keeps one.
            let (owner, index) = owners[i];
            if owner == 0 && before.as_ref().is_none_or(|b| index + 1 != b.segments.len() || index == 0) {
                return None;
            }
            if owner == 1 && plan.segments.len() < 2 {
                return None;
            }
            joined(curves[i - 1], curves[i], curves[i + 1], radius).map(|meet| (i, Fix::Join(meet))).or_else(|| {
                let inside = owners[i - 1].0 == 1 && owner == 1 && owners[i + 1].0 == 1;
                inside.then(|| bridged(curves[i - 1], curves[i], curves[i + 1], side)).flatten().map(|fix| (i, fix))
            })
        }) else {
            return arcs_moved;
        };
        let meet = match fix {
            Fix::Join(meet) => meet,
            Fix::Bridge { arc_before_ends, line_ends } => {
                // The step between two arcs becomes the line tangent to one of them: the arc
                // before ends earlier on its circle, or the arc after starts later on its.
                let (before_index, after_index) = (owners[i - 1].1, owners[i].1);
                let moved = arc_before_ends
                    .map(|q| q.distance(curves[i - 1].end()))
                    .or(line_ends.map(|q| q.distance(curves[i].end())));
                if moved.is_none_or(|d| d <= 1e-12) {
                    return arcs_moved;
                }
                if let Some(end) = arc_before_ends
                    && let Some(Segment::Arc { end: e, .. }) = plan.segments.get_mut(before_index)
                {
                    *e = end;
                }
                if let Some(end) = line_ends
                    && let Some(Segment::Line { end: e }) = plan.segments.get_mut(after_index)
                {
                    *e = end;
                }
                plan.changed = true;
                arcs_moved = true;
                let step = Xz::new(curves[i].end().x - curves[i].start().x, curves[i].end().z - curves[i].start().z);
                if plan.jumps > 0 && is_jog(jogs, step) {
                    plan.jumps -= 1;
                }
                continue;
            }
        };
        let (owner, index) = owners[i];
        let removed = curves[i];
        // The neighbour before now ends, and the one after starts, where they meet.
        match owners[i - 1] {
            (0, k) => {
                if let Some(b) = before.as_deref_mut() {
                    set_end(b, k, meet);
                }
            }
            (_, k) => set_end(plan, k, meet),
        }
        if owner == 0 {
            if let Some(b) = before.as_deref_mut() {
                remove(b, index);
            }
        } else {
            remove(plan, index);
            let step = Xz::new(removed.end().x - removed.start().x, removed.end().z - removed.start().z);
            if plan.jumps > 0 && is_jog(jogs, step) {
                plan.jumps -= 1;
            }
        }
        if owners[i - 1].0 == 0 {
            plan.start = meet;
        }
    }
    arcs_moved
}

/// How a used-up element is done away with.
enum Fix {
    /// Left out, its neighbours (lines) joined at this point.
    Join(Xz),
    /// A step between two arcs made the line from one tangent to the other: the arc before
    /// now ends at `arc_before_ends`, or the line at `line_ends` (where the arc after starts).
    Bridge { arc_before_ends: Option<Xz>, line_ends: Option<Xz> },
}

/// Whether `step` is one of the steps written as moves of their own.
fn is_jog(jogs: &[Xz], step: Xz) -> bool {
    jogs.iter().any(|j| (j.x - step.x).abs() <= 1e-12 && (j.z - step.z).abs() <= 1e-12)
}

/// A short line `middle` between two arcs (the play taken up where an arc reverses an
/// axis, at the top of a bump or the bottom of a groove: the arc cut there and written on
/// either side of the step) made the line tangent to one of them, so that no corner is
/// left for the control to cut back: from the step's start, tangent to the arc after's
/// circle where that start lies outside it (the arc after then starts at the tangent
/// point), else from the arc before's circle, tangent to it, to the step's end (the arc
/// before then ends at the tangent point). The tangent point must lie on the arc, running
/// the way the line runs. Where the nose rolls round the one corner left, at the step's
/// far end, the corner turns by the angle the line spans, `√(2·step/R)`. Only an arc the
/// tool runs outside of (convex, as the tool sees it) is touched: a tangent lies outside
/// its circle, on the tool's side, so the line never reaches into the part beyond it.
fn bridged(previous: Curve, middle: Curve, next: Curve, side: f64) -> Option<Fix> {
    let (Curve::Arc { start: s1, centre: c1, ccw: ccw1, .. }, Curve::Line { start: t, end: u }) = (previous, middle)
    else {
        return None;
    };
    let Curve::Arc { end: e2, centre: c2, ccw: ccw2, .. } = next else { return None };
    let dot = |a: Xz, b: Xz| a.x * b.x + a.z * b.z;
    // The points where lines from `from` touch the circle about `centre` of `radius`.
    let touching = |from: Xz, centre: Xz, radius: f64| {
        let d = from.distance(centre);
        if !(d > radius && radius > 0.0) {
            return Vec::new();
        }
        let spread = (radius / d).acos();
        let towards = geometry::angle(from, centre);
        vec![
            geometry::on_circle(centre, radius, towards + spread),
            geometry::on_circle(centre, radius, towards - spread),
        ]
    };
    let (r1, r2) = (t.distance(c1), u.distance(c2));
    // The tool runs inside a counter-clockwise arc with G41 (`path::offset`).
    let outside = |ccw: bool| (if ccw { side } else { -side }) < 0.0;
    // From `t` onto the arc after: the line runs the way the arc does at the tangent point,
    // which lies between the arc's start and its end.
    let onto = touching(t, c2, r2).into_iter().filter(|_| outside(ccw2)).find(|&q| {
        let along = Curve::Arc { start: q, end: e2, centre: c2, ccw: ccw2 }.start_tangent();
        dot(along, geometry::direction(t, q)) > 0.0
            && geometry::sweep(u, q, c2, ccw2) < geometry::sweep(u, e2, c2, ccw2)
            && q.distance(e2) > 0.0
    });
    if let Some(q) = onto {
        return Some(Fix::Bridge { arc_before_ends: None, line_ends: Some(q) });
    }
    // From the arc before onto `u`.
    let off = touching(u, c1, r1).into_iter().filter(|_| outside(ccw1)).find(|&q| {
        let along = Curve::Arc { start: s1, end: q, centre: c1, ccw: ccw1 }.end_tangent();
        dot(along, geometry::direction(q, u)) > 0.0
            && geometry::sweep(s1, q, c1, ccw1) < geometry::sweep(s1, t, c1, ccw1)
            && q.distance(s1) > 0.0
    });
    off.map(|q| Fix::Bridge { arc_before_ends: Some(q), line_ends: None })
}

/// The written elements of `before` then `plan`, as contour curves, with their owners.
fn chain(before: Option<&MovePlan>, plan: &MovePlan) -> (Vec<Curve>, Vec<Owner>) {
    let mut curves = Vec::new();
    let mut owners = Vec::new();
    for (owner, p) in before.into_iter().map(|b| (0, b)).chain([(1, plan)]) {
        let mut from = p.start;
        for (index, segment) in p.segments.iter().enumerate() {
            curves.push(match *segment {
                Segment::Line { end } => Curve::Line { start: from, end },
                Segment::Arc { end, centre, ccw } => Curve::Arc { start: from, end, centre, ccw },
            });
            owners.push((owner, index));
            from = segment.end();
        }
    }
    (curves, owners)
}

/// Where the lines on either side of a used-up line `middle` meet, when they do near it and
/// each still runs the way it ran: the line before from its start forward to the meeting
/// point, the line after from there forward to its end.
fn joined(previous: Curve, middle: Curve, next: Curve, radius: f64) -> Option<Xz> {
    let (Curve::Line { start: a0, end: a1 }, Curve::Line { start: b0, end: b1 }) = (previous, next) else {
        return None;
    };
    if !matches!(middle, Curve::Line { .. }) {
        return None;
    }
    let meet = geometry::line_line(a0, a1, b0, b1)?;
    if !meet.is_finite() {
        return None;
    }
    let dot = |a: Xz, b: Xz| a.x * b.x + a.z * b.z;
    let step = |from: Xz, to: Xz| Xz::new(to.x - from.x, to.z - from.z);
    // The meeting point lies on the line before past its start, and on the line after
    // before its end (each keeps its direction), and inside the corner the nose rounds.
    let keeps_before = dot(step(a0, meet), step(a0, a1)) > 0.0;
    let keeps_after = dot(step(meet, b1), step(b0, b1)) > 0.0;
    let near = meet.distance(middle.start()).min(meet.distance(middle.end())) <= 2.0 * radius + middle.length();
    (keeps_before && keeps_after && near).then_some(meet)
}

fn set_end(plan: &mut MovePlan, index: usize, end: Xz) {
    if let Some(Segment::Line { end: e }) = plan.segments.get_mut(index) {
        *e = end;
        plan.changed = true;
    }
}

fn remove(plan: &mut MovePlan, index: usize) {
    if index < plan.segments.len() {
        plan.segments.remove(index);
        if index < plan.words.len() {
            plan.words.remove(index);
        }
        plan.changed = true;
    }
}
