//! The nose-centre path of a chain of contour elements: pure plane geometry, no moves.
//!
//! Each contour element is offset by the nose radius to the tool's side (a line stays a
//! parallel line, an arc stays concentric with radius `R ± r`). At each corner the
//! direction of travel decides how the offset elements are joined:
//!
//! - **tangent** (the offset elements meet exactly): they share the meeting point;
//! - **concave** (the path turns toward the tool): the offset elements are cut back to
//!   where they cross;
//! - **convex** (the path turns away from the tool, or reverses): the nose rolls round the
//!   corner on an arc of radius `r` about the contour corner, turning the way the path turns.
//!
//! An element the nose cannot follow (a concave arc smaller than the nose, an element that
//! the cuts at its two corners use up, offset elements of a concave corner that never
//! cross) is reported as a [`Problem`]; the path is still made, so that lowering goes on.

use std::f64::consts::{PI, TAU};

use crate::geometry;
use crate::toolpath::Xz;

/// A line or an arc in the toolpath frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Curve {
    Line {
        start: Xz,
        end: Xz,
    },
    /// `ccw` in the `G03` sense of [`crate::geometry`].
    Arc {
        start: Xz,
        end: Xz,
        centre: Xz,
        ccw: bool,
    },
}

/// Offset points closer than this (mm) are one point: the corner is tangent. A tangent join
/// computed in floating point misses by far less; a corner that really turns leaves a
/// larger gap and gets its arc or its cut-back, however small.
pub const TANGENT_GAP: f64 = 1e-7;

/// Shorter elements (mm) have no direction; the nose stands still on them.
const NULL_LENGTH: f64 = 1e-9;

impl Curve {
    pub fn start(&self) -> Xz {
        match *self {
            Curve::Line { start, .. } | Curve::Arc { start, .. } => start,
        }
    }

    pub fn end(&self) -> Xz {
        match *self {
            Curve::Line { end, .. } | Curve::Arc { end, .. } => end,
        }
    }

    fn set_start(&mut self, p: Xz) {
        match self {
            Curve::Line { start, .. } | Curve::Arc { start, .. } => *start = p,
        }
    }

    fn set_end(&mut self, p: Xz) {
        match self {
            Curve::Line { end, .. } | Curve::Arc { end, .. } => *end = p,
        }
    }

    /// The radius of an arc (the distance of its start from the centre); 0 for a line.
    pub fn radius(&self) -> f64 {
        match *self {
            Curve::Line { .. } => 0.0,
            Curve::Arc { start, centre, .. } => start.distance(centre),
        }
    }

    pub fn length(&self) -> f64 {
        match *self {
            Curve::Line { start, end } => start.distance(end),
            Curve::Arc { start, end, centre, ccw } => geometry::arc_length(start, end, centre, ccw),
        }
    }

    /// Too short to have a direction: a line shorter than a nanometre, an arc about its own
    /// start. (An arc whose end meets its start is a full circle, not a null element.)
    pub fn is_null(&self) -> bool {
        match *self {
            Curve::Line { start, end } => start.distance(end) < NULL_LENGTH,
            Curve::Arc { .. } => self.radius() < NULL_LENGTH,
        }
    }

    /// The unit direction of travel at the start.
    pub fn start_tangent(&self) -> Xz {
        match *self {
            Curve::Line { start, end } => geometry::direction(start, end),
            Curve::Arc { start, centre, ccw, .. } => arc_tangent(start, centre, ccw),
        }
    }

    /// The unit direction of travel at the end.
    pub fn end_tangent(&self) -> Xz {
        match *self {
            Curve::Line { start, end } => geometry::direction(start, end),
            Curve::Arc { end, centre, ccw, .. } => arc_tangent(end, centre, ccw),
        }
    }
}

/// The direction of travel at `point` on an arc about `centre`: the radial direction turned
/// a quarter turn the way the arc goes.
fn arc_tangent(point: Xz, centre: Xz, ccw: bool) -> Xz {
    let radial = geometry::direction(centre, point);
    // With the angle atan2(x, z), d/dφ of (sin φ, cos φ) is (cos φ, −sin φ).
    let forward = Xz::new(radial.z, -radial.x);
    if ccw { forward } else { Xz::new(-forward.x, -forward.z) }
}

/// The unit normal on the tool's side of the direction `tangent`: `side` is +1 for `G41`
/// (left of the path, seen with Z to the right and X up) and −1 for `G42`.
pub fn tool_normal(tangent: Xz, side: f64) -> Xz {
    Xz::new(tangent.z * side, -tangent.x * side)
}

/// How the path turns at a corner, as the tool sees it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CornerKind {
    /// The offset elements meet: no turn worth a nanometre at the nose centre.
    Tangent,
    /// The path turns toward the tool: the offset elements cross.
    Concave,
    /// The path turns away from the tool, or reverses: the nose rolls round the corner.
    Convex,
}

/// The signed turn from `incoming` to `outgoing` (unit directions), radians in `[−π, π]`,
/// positive to the left (counter-clockwise with Z to the right and X up).
pub fn turn_angle(incoming: Xz, outgoing: Xz) -> f64 {
    let cross = incoming.z * outgoing.x - incoming.x * outgoing.z;
    let dot = incoming.z * outgoing.z + incoming.x * outgoing.x;
    cross.atan2(dot)
}

/// Classify a corner from the directions of travel into and out of it. The tangent test is
/// on the gap it leaves between the offset points (`2r sin(θ/2)`), so it is a distance.
pub fn classify(incoming: Xz, outgoing: Xz, r: f64, side: f64) -> CornerKind {
    let turn = turn_angle(incoming, outgoing);
    if 2.0 * r * (turn / 2.0).sin().abs() <= TANGENT_GAP {
        return CornerKind::Tangent;
    }
    // A reversal goes round the end whichever way rounding tips the sign of the turn.
    if turn.abs() >= PI - 1e-12 || turn * side < 0.0 { CornerKind::Convex } else { CornerKind::Concave }
}

/// The arc the nose centre rolls round a convex corner: radius `r` about the contour corner,
/// from the offset point of the incoming element to that of the outgoing one, turning the
/// way the path turns (clockwise when the tool is on the left).
pub fn corner_arc(corner: Xz, incoming: Xz, outgoing: Xz, r: f64, side: f64) -> Curve {
    let from = tool_normal(incoming, side);
    let to = tool_normal(outgoing, side);
    Curve::Arc {
        start: Xz::new(corner.x + r * from.x, corner.z + r * from.z),
        end: Xz::new(corner.x + r * to.x, corner.z + r * to.z),
        centre: corner,
        ccw: side < 0.0,
    }
}

/// The element the nose centre follows for a contour element, and whether the nose fits
/// (a concave arc needs a radius of at least `r`).
pub fn offset(contour: Curve, r: f64, side: f64) -> (Curve, bool) {
    match contour {
        Curve::Line { start, end } => {
            let n = tool_normal(geometry::direction(start, end), side);
            let shift = |p: Xz| Xz::new(p.x + r * n.x, p.z + r * n.z);
            (Curve::Line { start: shift(start), end: shift(end) }, true)
        }
        Curve::Arc { start, end, centre, ccw } => {
            let radius = contour.radius();
            // The tool's side of a counter-clockwise arc is its inside when the tool is on
            // the left, and the other way round.
            let inward = if ccw { side } else { -side };
            let wanted = radius - inward * r;
            let fits = wanted >= -NULL_LENGTH;
            let new_radius = wanted.max(0.0);
            let at = |p: Xz| geometry::on_circle(centre, new_radius, geometry::angle(p, centre));
            (Curve::Arc { start: at(start), end: at(end), centre, ccw }, fits)
        }
    }
}

/// Why the nose cannot follow an element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Problem {
    /// A concave arc with a smaller radius than the nose.
    ArcTooTight,
    /// The cuts at its corners use the element up: the neighbours come closer than the
    /// nose allows (a groove narrower than the nose, a step shorter than the cut-back).
    UsedUp,
    /// The offset elements of a concave corner never cross; a straight link joins them.
    NoMeeting,
}

impl Problem {
    /// The reason, as the diagnostic words it.
    pub fn reason(self) -> &'static str {
        match self {
            Problem::ArcTooTight => "the concave arc is tighter than the nose",
            Problem::UsedUp => "the elements on either side leave no room for the nose",
            Problem::NoMeeting => "the offset paths of the corner before it never meet",
        }
    }
}

/// The nose-centre path of one contour element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Offset {
    /// What joins the previous element's path to this one's at the corner before it: the
    /// corner arc of a convex corner, or a straight link where concave offsets never cross.
    pub lead_in: Option<Curve>,
    /// The element's own path (for a null element, a point where the nose stands).
    pub path: Curve,
    pub problem: Option<Problem>,
}

/// The nose-centre path of a chain of contour elements, each starting where the previous
/// one ends. The first element has no corner before it and the last none after it: they
/// start and end perpendicular to themselves (C-type start-up and cancel).
pub fn offset_chain(contours: &[Curve], r: f64, side: f64) -> Vec<Offset> {
    // Each element's whole offset, before the corners cut or extend it (None: null element).
    let whole: Vec<Option<(Curve, bool)>> =
        contours.iter().map(|&c| (!c.is_null()).then(|| offset(c, r, side))).collect();
    let mut out: Vec<Offset> = contours
        .iter()
        .zip(&whole)
        .map(|(&contour, w)| match *w {
            Some((path, fits)) => Offset { lead_in: None, path, problem: (!fits).then_some(Problem::ArcTooTight) },
            None => Offset { lead_in: None, path: contour, problem: None },
        })
        .collect();
    // Join each real element to the real element before it.
    let real: Vec<usize> = (0..contours.len()).filter(|&i| whole[i].is_some()).collect();
    for pair in real.windows(2) {
        let (p, n) = (pair[0], pair[1]);
        let (incoming, outgoing) = (contours[p], contours[n]);
        let corner = incoming.end();
        let (into, out_of) = (incoming.end_tangent(), outgoing.start_tangent());
        let (mut before, mut after) = (out[p].path, out[n].path);
        match classify(into, out_of, r, side) {
            CornerKind::Tangent => {
                // An arc keeps its start on its circle; a line may take the arc's end.
                let meet = if matches!(after, Curve::Arc { .. }) { after.start() } else { before.end() };
                before.set_end(meet);
                after.set_start(meet);
            }
            CornerKind::Convex => {
                let arc = corner_arc(corner, into, out_of, r, side);
                before.set_end(arc.start());
                after.set_start(arc.end());
                out[n].lead_in = Some(arc);
            }
            CornerKind::Concave => match crossing(before, after, corner) {
                Some(meet) => {
                    before.set_end(meet);
                    after.set_start(meet);
                }
                None => {
                    out[n].lead_in = Some(Curve::Line { start: before.end(), end: after.start() });
                    out[n].problem = out[n].problem.or(Some(Problem::NoMeeting));
                }
            },
        }
        out[p].path = before;
        out[n].path = after;
    }
    for &i in &real {
        if let Some((w, _)) = whole[i]
            && out[i].problem.is_none()
            && !runs_forward(w, out[i].path)
        {
            out[i].problem = Some(Problem::UsedUp);
        }
    }
    // A null element stands where the nose is: at the end of the real element before it,
    // or, before the first real element, at that element's start.
    let mut at = real.first().map(|&i| out[i].lead_in.map_or(out[i].path.start(), |c| c.start()));
    for i in 0..out.len() {
        if whole[i].is_some() {
            at = Some(out[i].path.end());
        } else if let Some(p) = at {
            out[i].path = Curve::Line { start: p, end: p };
        }
    }
    out
}

/// Where the offset elements of a concave corner cross: the crossing nearest the corner.
fn crossing(a: Curve, b: Curve, corner: Xz) -> Option<Xz> {
    let on_line =
        |start: Xz, end: Xz, t: f64| Xz::new(start.x + (end.x - start.x) * t, start.z + (end.z - start.z) * t);
    let candidates: Vec<Xz> = match (a, b) {
        (Curve::Line { start: a0, end: a1 }, Curve::Line { start: b0, end: b1 }) => {
            geometry::line_line(a0, a1, b0, b1).into_iter().collect()
        }
        (Curve::Line { start, end }, arc @ Curve::Arc { centre, .. })
        | (arc @ Curve::Arc { centre, .. }, Curve::Line { start, end }) => {
            geometry::line_circle(start, end, centre, arc.radius())
                .into_iter()
                .map(|t| on_line(start, end, t))
                .collect()
        }
        (first @ Curve::Arc { centre: c1, .. }, second @ Curve::Arc { centre: c2, .. }) => {
            geometry::circle_circle(c1, first.radius(), c2, second.radius())
        }
    };
    candidates.into_iter().filter(|p| p.is_finite()).min_by(|p, q| p.distance(corner).total_cmp(&q.distance(corner)))
}

/// Whether a cut-back element still runs the way its whole offset runs, from no earlier
/// than its start to no later than its end.
fn runs_forward(whole: Curve, cut: Curve) -> bool {
    const SLACK: f64 = 1e-9;
    match (whole, cut) {
        (Curve::Line { start: w0, end: w1 }, Curve::Line { start: c0, end: c1 }) => {
            let d = geometry::direction(w0, w1);
            let along = |p: Xz| (p.x - w0.x) * d.x + (p.z - w0.z) * d.z;
            let length = w0.distance(w1);
            let (s, e) = (along(c0), along(c1));
            s >= -TANGENT_GAP && e <= length + TANGENT_GAP && e - s >= -SLACK
        }
        (Curve::Arc { start: w0, end: w1, centre, ccw }, Curve::Arc { start: c0, end: c1, .. }) => {
            let radius = whole.radius();
            if radius < NULL_LENGTH {
                return true;
            }
            let total = geometry::sweep(w0, w1, centre, ccw);
            // Angles from the whole arc's start (for the cut start) and back from its end
            // (for the cut end), each as a small negative when rounding moved it outward.
            let slack = TANGENT_GAP / radius;
            let advance = |from: Xz, to: Xz, forward: bool| {
                let (a, b) = (geometry::angle(from, centre), geometry::angle(to, centre));
                let raw = if forward == ccw { b - a } else { a - b };
                let s = raw.rem_euclid(TAU);
                if s > TAU - slack { s - TAU } else { s }
            };
            let cut_start = advance(w0, c0, true);
            let cut_end = advance(w1, c1, false);
            cut_start >= -slack && cut_end >= -slack && cut_start + cut_end <= total + slack
        }
        _ => true,
    }
}
