//! `circle`, `semicircle`, `quadrant`: one fitted circle per piece of a programmed arc.
//!
//! The arc is cut where its nominal angle (about the programmed centre, `geometry::angle`:
//! from +Z toward +X) crosses one of the given angles, at the last point before each
//! crossing; `circle` does not cut at all. Each piece is one circle with the programmed
//! sense of travel, pinned to the piece's first and last points (the first is where the
//! written path stands, so nothing is left to drift) and fitted to the points between by
//! orthogonal least squares (`pinned::through_ends`); a programmed full circle is pinned to
//! its one start-and-end point (`pinned::through_point`).
//!
//! A step in the points is the one thing a circle cannot follow: where the path jumps
//! (a backlash taken up at a reversal, which the inverse writes as a jump of the play), the
//! piece is written as a straight step to its first point and the circle from there.
//!
//! A piece is accepted when every point and every chord (ArcWelder's test, `deviation.rs`)
//! lies within the tolerance; otherwise the whole strategy fails and says how close it came.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use smallvec::SmallVec;

use super::deviation::{self, Between};
use super::pinned;
use super::{MovePoints, NominalShape, Segment, Segments};
use crate::geometry;
use crate::toolpath::Xz;

/// Where `semicircle` cuts: 0° and 180° in `geometry::angle`'s convention, the points level
/// with the centre in X (`x = cx`), at the ends of the circle's Z travel. Z reverses there,
/// so that is where a Z backlash step sits (X moves fastest there and reverses at ±90°).
/// On our reading of the thesis' Table 4 these are its cuts too: the centres fitted to its
/// two halves ("quadrants 1 and 2", "3 and 4") differ mostly in Z.
pub const SEMICIRCLE_CUTS: [f64; 2] = [0.0, PI];

/// Where `quadrant` cuts: every quarter turn, the reversals of both axes.
pub const QUADRANT_CUTS: [f64; 4] = [0.0, FRAC_PI_2, PI, -FRAC_PI_2];

/// The segments `circles_at` writes.
pub struct Circles {
    pub segments: Segments,
    /// When they are one arc: the largest distance of a point from it, which the fit has
    /// measured already and which is all `max_deviation` would measure of a path of one
    /// segment.
    pub deviation: Option<f64>,
}

/// The fitted pieces, ending at the points `ends` (`cut_indices`), or the largest deviation
/// of the best attempt at the piece that failed.
pub fn circles_at(
    m: &MovePoints<'_>,
    centre: Xz,
    ccw: bool,
    ends: &[usize],
    tolerance_mm: f64,
) -> Result<Circles, f64> {
    // The programmed radius, for the bulge between points (see `arcs.rs`).
    let radius = match m.nominal {
        NominalShape::Arc { radius, .. } => radius,
        NominalShape::Line => m.start.distance(centre),
    };
    let context = Piece {
        ccw,
        tolerance: tolerance_mm,
        curvature: if ccw { 1.0 } else { -1.0 } / radius,
        between: Between::Bulge { centre, radius },
    };
    let mut segments = Segments::new();
    let mut deviation = None;
    let mut from = m.start;
    let mut first = 0;
    for &last in ends {
        let points = m.points.get(first..=last).ok_or(f64::INFINITY)?;
        match context.fit(from, points, tolerance_mm)? {
            Fit::Arc(arc) => {
                segments.push(arc.segment);
                deviation = Some(arc.points);
            }
            Fit::Stepped { step, arc } => segments.extend([Segment::Line { end: step }, arc]),
        }
        from = segments.last().map_or(from, Segment::end);
        first = last + 1;
    }
    let deviation = deviation.filter(|_| segments.len() == 1);
    Ok(Circles { segments, deviation })
}

/// The index of the last point of each piece (`cut_indices`): an arc has at most five pieces
/// but where it turns more than a full turn.
pub type Ends = SmallVec<[usize; 5]>;

/// The index of the last point of each piece, the move's last point included.
pub fn cut_indices(m: &MovePoints<'_>, centre: Xz, ccw: bool, cuts: &[f64]) -> Ends {
    if cuts.is_empty() {
        return one_piece(m);
    }
    Travel::new(m, centre, ccw).cut_indices(cuts)
}

/// `cut_indices` with no cuts: the move's last point ends its one piece, and no angle needs
/// measuring.
pub fn one_piece(m: &MovePoints<'_>) -> Ends {
    m.points.len().checked_sub(1).into_iter().collect()
}

/// The angle each point of a move has travelled about a centre from the move's start,
/// unwrapped along the points: what `cut_indices` cuts, computed once for every set of
/// cuts.
pub struct Travel {
    sense: f64,
    a0: f64,
    /// On the stack for the few points most moves have.
    travel: SmallVec<[f64; 16]>,
}

impl Travel {
    pub fn new(m: &MovePoints<'_>, centre: Xz, ccw: bool) -> Travel {
        let sense = if ccw { 1.0 } else { -1.0 };
        let a0 = geometry::angle(m.start, centre);
        let mut previous = a0;
        let mut travelled = 0.0;
        let travel: SmallVec<[f64; 16]> = m
            .points
            .iter()
            .map(|&p| {
                let a = geometry::angle(p, centre);
                let mut step = (a - previous).rem_euclid(TAU);
                if step > PI {
                    step -= TAU;
                }
                previous = a;
                travelled += sense * step;
                travelled
            })
            .collect();
        Travel { sense, a0, travel }
    }

    /// `cut_indices` of the move.
    pub fn cut_indices(&self, cuts: &[f64]) -> Ends {
        let Travel { sense, a0, ref travel } = *self;
        let total = travel.last().copied().unwrap_or(0.0);
        // A cut within half a sample of either end of the move is no cut: compensation moves
        // the points off the nominal angles by a little, and a move that starts or ends on a cut
        // would otherwise grow a piece of one point.
        let margin = total.abs() / (2.0 * travel.len().max(1) as f64);
        let mut crossings: SmallVec<[f64; 5]> = SmallVec::new();
        for &cut in cuts {
            let mut at = (sense * (cut - a0)).rem_euclid(TAU);
            while at < total - margin {
                if at > margin {
                    crossings.push(at);
                }
                at += TAU;
            }
        }
        crossings.sort_by(f64::total_cmp);
        let mut ends = Ends::new();
        for crossing in crossings {
            // The last point at or before the crossing ends a piece, unless it ends the move.
            let count_before = travel.partition_point(|&t| t <= crossing);
            if let Some(last) = count_before.checked_sub(1)
                && last + 1 < travel.len()
                && ends.last().is_none_or(|&previous| last > previous)
            {
                ends.push(last);
            }
        }
        if let Some(last) = travel.len().checked_sub(1) {
            ends.push(last);
        }
        ends
    }
}

/// A circle fitted to a piece.
#[derive(Clone, Copy)]
struct Arc {
    segment: Segment,
    /// The largest distance of a point from it (`segment_deviation`).
    points: f64,
    /// That, or the chord test's largest gap where that is larger: what the piece is held to.
    worst: f64,
}

/// How a piece is written.
enum Fit {
    Arc(Arc),
    /// A straight step to the piece's first point, and the circle from there.
    Stepped {
        step: Xz,
        arc: Segment,
    },
}

struct Piece {
    ccw: bool,
    /// The tolerance the free circle must meet to be preferred over the pinned one.
    tolerance: f64,
    /// The nominal curvature, for a piece with no point between its ends.
    curvature: f64,
    between: Between,
}

impl Piece {
    /// One circle from `from` over `points`, or a step to the first point and the circle
    /// from there; `Err` with the smaller deviation of the two when neither passes.
    fn fit(&self, from: Xz, points: &[Xz], tolerance: f64) -> Result<Fit, f64> {
        let direct = self.arc(from, points);
        if let Some(arc) = direct.filter(|arc| arc.worst <= tolerance) {
            return Ok(Fit::Arc(arc));
        }
        let stepped = match points {
            [step, rest @ ..] if !rest.is_empty() => self.arc(*step, rest).map(|arc| (*step, arc.segment, arc.worst)),
            _ => None,
        };
        // The step is held to the path it replaces: along a nominal arc that is the arc's
        // bulge to the first point, which a straight step cuts inside by its sagitta.
        let stepped = stepped.map(|(step, segment, deviation)| {
            let bulge = deviation::line_bulge_deviation(from, &Segment::Line { end: step }, &[step], self.between);
            (step, segment, deviation.max(bulge))
        });
        if let Some((step, segment, deviation)) = stepped
            && deviation <= tolerance
        {
            return Ok(Fit::Stepped { step, arc: segment });
        }
        let best =
            [direct.map(|arc| arc.worst), stepped.map(|s| s.2)].into_iter().flatten().fold(f64::INFINITY, f64::min);
        Err(best)
    }

    /// The circle from `from` to the last of `points`, and its deviation (points and chords):
    /// the free least-squares circle (Taubin, then geometric Levenberg–Marquardt), its
    /// centre moved onto the perpendicular bisector of the exact ends, when that stays within
    /// the tolerance; else the circle pinned to both ends by a least-squares fit of the
    /// points between.
    fn arc(&self, from: Xz, points: &[Xz]) -> Option<Arc> {
        let Some(free) = self.free_arc(from, points) else { return self.pinned_arc(from, points) };
        // A free circle within the tolerance is taken whatever the pinned one gives, so the
        // pinned one is fitted only when it could be taken.
        if free.worst <= self.tolerance {
            return Some(free);
        }
        match self.pinned_arc(from, points) {
            Some(p) if p.worst < free.worst => Some(p),
            _ => Some(free),
        }
    }

    fn free_arc(&self, from: Xz, points: &[Xz]) -> Option<Arc> {
        let (&end, _) = points.split_last()?;
        if from.distance(end) <= 1e-9 || points.len() < 2 {
            return None;
        }
        // Most pieces have a few points: room for them without a heap allocation.
        let mut all: SmallVec<[Xz; 16]> = SmallVec::with_capacity(points.len() + 1);
        all.push(from);
        all.extend_from_slice(points);
        let circle = super::circle::fit(&all)?;
        // Both ends on one circle (the `R`/`L` form has no other): the free centre moved onto
        // the perpendicular bisector of the ends, the least it can move.
        let mid = Xz::new((from.x + end.x) / 2.0, (from.z + end.z) / 2.0);
        let chord = Xz::new(end.x - from.x, end.z - from.z);
        let length2 = chord.x * chord.x + chord.z * chord.z;
        let along = ((circle.centre.x - mid.x) * chord.x + (circle.centre.z - mid.z) * chord.z) / length2;
        let centre = Xz::new(circle.centre.x - along * chord.x, circle.centre.z - along * chord.z);
        let segment = Segment::Arc { end, centre, ccw: self.ccw };
        // The same sense as programmed, and a sweep the nominal arc could have.
        let deviation = deviation::segment_deviation(from, &segment, points);
        let worst =
            deviation.max(deviation::chord_deviation(from, points, centre, from.distance(centre), self.between));
        worst.is_finite().then_some(Arc { segment, points: deviation, worst })
    }

    fn pinned_arc(&self, from: Xz, points: &[Xz]) -> Option<Arc> {
        let (&end, interior) = points.split_last()?;
        let segment = if from.distance(end) <= 1e-9 {
            if interior.is_empty() {
                Segment::Line { end }
            } else {
                let circle = pinned::through_point(end, interior)?;
                Segment::Arc { end, centre: circle.centre, ccw: self.ccw }
            }
        } else {
            let bend = pinned::through_ends(from, end, interior, Some(self.ccw), Some(self.curvature), true)?;
            if !bend.writable() {
                return None;
            }
            bend.segment_to(end)
        };
        let deviation = deviation::segment_deviation(from, &segment, points);
        let mut worst = deviation;
        if let Segment::Arc { centre, .. } = segment {
            let chords = deviation::chord_deviation(from, points, centre, from.distance(centre), self.between);
            worst = worst.max(chords);
        }
        Some(Arc { segment, points: deviation, worst })
    }
}
