//! `arcs`: the fewest arcs and lines, tangent-continuous where the points are smooth.
//!
//! **Construction.** Pieces are laid greedily from the move's start, each covering as long
//! a run of points as passes ArcWelder's acceptance test (every point, and the path between
//! consecutive points, within the tolerance: `deviation.rs`), the run found by doubling and
//! bisection (`grow.rs`). Each piece is one of two kinds:
//!
//! * a **smooth** piece leaves in the direction the previous piece arrived in: the circle
//!   through the current position with that tangent (one parameter, the curvature, which is
//!   zero for a line) fitted to the run (`pinned::with_tangent`). It ends where the run's last
//!   point projects onto the circle, so its end tangent is the fitted circle's own, not one
//!   forced by an end point; that keeps the tangent from see-sawing from piece to piece as
//!   it does when arcs are chained end point to end point. The move's last piece instead ends
//!   on the last point exactly (`pinned::with_tangent_to`);
//! * a **corner** piece starts at the current position in any direction: along a programmed
//!   arc, the circle of the programmed curvature through it and the run's last point where
//!   that holds the points (the programmer's radius stays where it is as good as any);
//!   else the circle through both fitted to the points between (`pinned::through_ends`), or
//!   a line to the next point, which always passes and guarantees progress.
//!
//! The smooth piece is taken unless the corner piece covers a third again as many points
//! (the path has a corner or a step there, such as a backlash take-up, which a tangent
//! piece cannot turn). The first piece of a move is a corner piece: the previous move's
//! direction is not known here, and programmed moves meet at corners anyway.
//!
//! This is not a biarc fit: biarcs need a tangent estimated from the points at every knot
//! and cost two arcs per span, where a circle fitted through a run costs one. Arcs never
//! sweep more than half a turn (so an `R` word can write each of them) nor have a radius a
//! control cannot take (`pinned::MAX_RADIUS_MM`; flatter pieces are lines).

use std::f64::consts::PI;

use super::deviation::{self, Between};
use super::pinned::{self, Bend};
use super::{MovePoints, NominalShape, Segment, grow};
use crate::geometry;
use crate::toolpath::Xz;

/// The segments and the largest distance of a point from the piece written for it.
#[derive(Debug, Clone, PartialEq)]
pub struct Pieces {
    pub segments: Vec<Segment>,
    pub max_deviation_mm: f64,
}

struct Piece {
    segment: Segment,
    /// The direction of travel at its end (`None`: it has no length).
    tangent: Option<Xz>,
    deviation: f64,
}

struct Run<'a> {
    points: &'a [Xz],
    tolerance: f64,
    between: Between,
    /// The nominal arc's signed curvature (positive counter-clockwise), for a piece with no
    /// point between its ends; `None` along a nominal line.
    curvature: Option<f64>,
}

/// Fit the move's points with arcs and lines (see the module comment).
pub fn fit(m: &MovePoints<'_>, tolerance_mm: f64) -> Pieces {
    let between = match m.nominal {
        NominalShape::Line => Between::Chords,
        // The programmed radius: the compensated start lies off the programmed circle by its
        // correction, and a bulge taken with its distance from the centre would be off by
        // that correction times 1 − cos of half the angle between points.
        NominalShape::Arc { centre, radius, .. } => Between::Bulge { centre, radius },
    };
    let curvature = match m.nominal {
        NominalShape::Line => None,
        NominalShape::Arc { ccw, radius, .. } => Some(if ccw { 1.0 } else { -1.0 } / radius),
    };
    let run = Run { points: m.points, tolerance: tolerance_mm, between, curvature };
    let count = m.points.len();
    let mut segments = Vec::new();
    let mut worst: f64 = 0.0;
    let mut at = m.start;
    let mut tangent: Option<Xz> = None;
    let mut first = 0;
    while first < count {
        let smooth = tangent.and_then(|t| grow::longest(first, count, |last| run.smooth(at, t, first, last)));
        let chosen = match smooth {
            Some((last, piece)) if last + 1 == count => Some((last, piece)),
            smooth => {
                let corner = grow::longest(first, count, |last| run.corner(at, first, last));
                match (smooth, corner) {
                    (Some(s), Some(c)) => Some(if 3 * (c.0 - first + 1) > 4 * (s.0 - first + 1) { c } else { s }),
                    (s, c) => s.or(c),
                }
            }
        };
        // A line to the next point always passes; this is only the guard for points that
        // are not numbers at all.
        let (last, piece) = chosen.unwrap_or_else(|| {
            let end = m.points.get(first).copied().unwrap_or(at);
            (first, Piece { segment: Segment::Line { end }, tangent: None, deviation: f64::INFINITY })
        });
        worst = worst.max(piece.deviation);
        at = piece.segment.end();
        tangent = piece.tangent.or(tangent);
        segments.push(piece.segment);
        first = last + 1;
    }
    Pieces { segments, max_deviation_mm: worst }
}

impl Run<'_> {
    /// The tangent-continuous piece from `at` over `first..=last`.
    fn smooth(&self, at: Xz, tangent: Xz, first: usize, last: usize) -> Option<Piece> {
        let points = self.points.get(first..=last)?;
        let &target = points.last()?;
        let closing = last + 1 == self.points.len();
        let bend = if closing {
            pinned::with_tangent_to(at, tangent, target)
        } else {
            pinned::with_tangent(at, tangent, points)
        };
        let bend = if bend.writable() { bend } else { Bend { curvature: 0.0, ..bend } };
        let end = if closing { target } else { bend.project(target) };
        // Straight on must go forward, and the move's end must be on the circle itself.
        let forward = (end.x - at.x) * tangent.x + (end.z - at.z) * tangent.z;
        if forward <= 0.0 || (closing && bend.offset(end).abs() > 1e-9) {
            return None;
        }
        self.accept(at, &bend, end, points)
    }

    /// The piece from `at` over `first..=last` in whatever direction fits.
    fn corner(&self, at: Xz, first: usize, last: usize) -> Option<Piece> {
        let points = self.points.get(first..=last)?;
        let (&end, interior) = points.split_last()?;
        if interior.is_empty() {
            // Along a nominal arc the path to the next point is the arc's bulge: the circle
            // of the nominal curvature through both ends follows it where a line would cut
            // inside by its sagitta.
            let nominal = self.curvature.and_then(|c| pinned::through_ends(at, end, &[], None, Some(c), false));
            if let Some(piece) = nominal.filter(Bend::writable).and_then(|bend| self.accept(at, &bend, end, points)) {
                return Some(piece);
            }
            // A line to the next point always passes its points (it is measured as what it
            // is, the bulge included).
            let tangent = (at.distance(end) > 0.0).then(|| geometry::direction(at, end));
            let segment = Segment::Line { end };
            let deviation = deviation::line_bulge_deviation(at, &segment, points, self.between);
            return Some(Piece { segment, tangent, deviation });
        }
        // The programmed arc's own curvature where it holds the points: over a run whose
        // points lie within the tolerance of many circles (a chord of a few increments), a
        // free fit takes whichever the rounding of the points favours (`G03 R0.010` for a
        // `G02 R0.8`), where the programmer's radius is as good and stays theirs.
        let nominal = self.curvature.and_then(|c| pinned::through_ends(at, end, &[], None, Some(c), false));
        if let Some(piece) = nominal.filter(Bend::writable).and_then(|bend| self.accept(at, &bend, end, points)) {
            return Some(piece);
        }
        let bend = pinned::through_ends(at, end, interior, None, None, false)?;
        let bend =
            if bend.writable() { bend } else { Bend { tangent: geometry::direction(at, end), curvature: 0.0, ..bend } };
        self.accept(at, &bend, end, points)
    }

    /// ArcWelder's test of the piece along `bend` from `at` to `end` over `points`.
    fn accept(&self, at: Xz, bend: &Bend, end: Xz, points: &[Xz]) -> Option<Piece> {
        let segment = bend.segment_to(end);
        let mut deviation = deviation::segment_deviation(at, &segment, points);
        match segment {
            Segment::Arc { centre, ccw, .. } => {
                if geometry::sweep(at, end, centre, ccw) > PI + 1e-12 {
                    return None;
                }
                let radius = at.distance(centre);
                deviation = deviation.max(deviation::chord_deviation(at, points, centre, radius, self.between));
            }
            Segment::Line { .. } => {
                deviation = deviation.max(deviation::line_bulge_deviation(at, &segment, points, self.between))
            }
        }
        if deviation.is_nan() || deviation > self.tolerance {
            return None;
        }
        let tangent = match segment {
            Segment::Arc { .. } => Some(bend.tangent_at(end)),
            Segment::Line { .. } => (at.distance(end) > 0.0).then(|| geometry::direction(at, end)),
        };
        Some(Piece { segment, tangent, deviation })
    }
}

#[cfg(test)]
mod tests;
