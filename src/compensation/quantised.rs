//! The path the control will really command: each move's written segments rounded onto
//! the grid, as the control reads the rounded words, and for each sample the reference
//! point it commands there. The report and `plot` predict the machine along this path, so
//! their residuals include the re-expression and the rounding, not only the inverse.

use std::ops::Range;

use crate::back::grid::{ArcWords, Grid};
use crate::geometry;
use crate::semantic::nose_radius::ToolTable;
use crate::toolpath::{Move, Xz};

use super::fit::Segment;
use super::plan::{MovePlan, PlanInput};
use super::squares::root_less;
use super::written;
use crate::error_model::sampling::PathSample;

/// A move's segments rounded onto `grid`, from its rounded start, as the control runs the
/// words `rewrite` writes for them: each end rounded from its exact value, each arc about
/// the centre the control finds from its words (`Grid::arc_words`, in the form
/// `prefer_radius` asks for where it holds the arc; the plan's own `words` where it chose
/// them), an arc no words can give a line. Into `out`, which is cleared first; the rounded
/// start (`grid.round(start)`) is returned.
pub fn quantise(
    grid: &Grid,
    start: Xz,
    segments: &[Segment],
    words: &[ArcWords],
    prefer_radius: bool,
    out: &mut Vec<Segment>,
) -> Xz {
    let mut from_exact = start;
    let mut from = grid.point(start);
    let rounded_start = grid.to_mm(from);
    out.clear();
    for (index, segment) in segments.iter().enumerate() {
        let end = grid.point(segment.end());
        let rounded = match *segment {
            Segment::Line { .. } => Segment::Line { end: grid.to_mm(end) },
            Segment::Arc { end: exact_end, centre, ccw } => {
                let words = match words.get(index) {
                    Some(&chosen) => chosen,
                    None => grid.arc_words(from_exact, exact_end, centre, ccw, prefer_radius),
                };
                match grid.arc_centre(from, end, words, ccw) {
                    Some(centre) => Segment::Arc { end: grid.to_mm(end), centre, ccw },
                    None => Segment::Line { end: grid.to_mm(end) },
                }
            }
        };
        out.push(rounded);
        from = end;
        from_exact = segment.end();
    }
    rounded_start
}

/// A segment's constants, computed once for the many samples measured against it.
#[derive(Debug, Clone, Copy)]
enum Gauge {
    Line { start: Xz, dx: f64, dz: f64, length2: f64 },
    Arc { radius: f64, sector: geometry::Sector },
}

impl Gauge {
    fn new(start: Xz, segment: &Segment) -> Gauge {
        match *segment {
            Segment::Line { end } => {
                let (dx, dz) = (end.x - start.x, end.z - start.z);
                Gauge::Line { start, dx, dz, length2: dx * dx + dz * dz }
            }
            Segment::Arc { end, centre, ccw } => Gauge::Arc {
                radius: start.distance(centre),
                sector: geometry::Sector::unmeasured(start, end, centre, ccw),
            },
        }
    }

    /// The closest point to `p`; an arc's is where the ray from its centre through `p`
    /// meets it, or the nearer end when the ray misses the arc.
    fn closest(&self, p: Xz) -> Xz {
        match *self {
            Gauge::Line { start, dx, dz, length2 } => {
                if length2 <= 0.0 {
                    return start;
                }
                let t = (((p.x - start.x) * dx + (p.z - start.z) * dz) / length2).clamp(0.0, 1.0);
                Xz::new(start.x + dx * t, start.z + dz * t)
            }
            Gauge::Arc { radius, sector } => {
                let (start, end, centre) = (sector.start(), sector.end(), sector.centre());
                let offset = Xz::new(p.x - centre.x, p.z - centre.z);
                let length = p.distance(centre);
                if length > 0.0 && sector.contains(p) {
                    let scale = radius / length;
                    Xz::new(centre.x + offset.x * scale, centre.z + offset.z * scale)
                } else if p.distance(start) <= p.distance(end) {
                    start
                } else {
                    end
                }
            }
        }
    }
}

/// `commanded_path` for the moves from `first` planned by `plans`, into `out` (one point
/// per sample of `input.samples`; the samples of other moves are left alone).
pub fn commanded_moves(
    input: &PlanInput<'_>,
    first: usize,
    plans: &[MovePlan],
    grid_of: impl Fn(usize) -> Grid,
    out: &mut [Xz],
) {
    let (toolpath, samples, tools) = (input.toolpath, input.samples, input.tools);
    let moves = toolpath.moves.get(first..).unwrap_or_default();
    // Buffers for every move's rounded segments and their gauges.
    let (mut rounded, mut gauges) = (Vec::new(), Vec::new());
    for (index, (m, plan)) in moves.iter().zip(plans).enumerate() {
        let index = first + index;
        let Some(range) = input.ranges.get(index).filter(|r| !r.is_empty()) else { continue };
        let contour_start = written::contour_start(toolpath, index);
        let grid = grid_of(index);
        if plan.segments.is_empty() {
            // A corner the control makes: around the written corner.
            let corner = grid.round(plan.start);
            for j in range.clone() {
                out[j] = written::reference_point(m, contour_start, &samples[j], corner, tools);
            }
            continue;
        }
        let prefer_radius = input.radius.get(index).copied().unwrap_or(false);
        let start = quantise(&grid, plan.start, &plan.segments, &plan.words, prefer_radius, &mut rounded);
        let walk = Walk { m, contour_start, start, segments: &rounded, tools };
        walk.follow(samples, input.commanded, range.clone(), &mut gauges, out);
    }
}

/// One move's rounded segments, from their rounded start.
struct Walk<'a> {
    m: &'a Move,
    contour_start: Xz,
    start: Xz,
    segments: &'a [Segment],
    tools: &'a ToolTable,
}

impl Walk<'_> {
    /// Walk the samples of the move along the segments, each to its closest point.
    fn follow(
        &self,
        samples: &[PathSample],
        ideal: &[Xz],
        range: Range<usize>,
        gauges: &mut Vec<Gauge>,
        out: &mut [Xz],
    ) {
        // Samples and segments both run along the move: search a window ahead of the last
        // segment used, wide enough to pass the segments between two samples (densified
        // lines along an arc may be twenty or more to a sample interval).
        let window = 16 + 2 * self.segments.len().div_ceil(range.len().max(1));
        // A move of one segment (most are) keeps its gauge here: a gauge is large, and each
        // was copied into `gauges`.
        let one: [Gauge; 1];
        let gauges: &[Gauge] = match self.segments {
            [segment] => {
                one = [Gauge::new(self.start, segment)];
                &one
            }
            _ => {
                gauges.clear();
                let mut from = self.start;
                for segment in self.segments {
                    gauges.push(Gauge::new(from, segment));
                    from = segment.end();
                }
                gauges
            }
        };
        let mut cursor = 0usize;
        for j in range {
            // The sample's contour point, for the point written and back (`written`).
            let contour = written::contour_at(self.m, self.contour_start, &samples[j], self.tools);
            let target = written::written_from(contour, &samples[j], ideal[j]);
            // The nearest point, the first of equally near ones, by distances compared as
            // their squares (`root_less`).
            let (mut best, mut best_k, mut best_d) = (self.start, cursor, f64::INFINITY);
            let first = cursor.saturating_sub(1);
            for (k, gauge) in gauges.iter().enumerate().skip(first).take(window + 1) {
                let q = gauge.closest(target);
                let d = q.distance_squared(target);
                if root_less(d, best_d) {
                    (best, best_k, best_d) = (q, k, d);
                }
            }
            cursor = best_k;
            out[j] = written::reference_from(contour, &samples[j], best);
        }
    }
}

#[cfg(test)]
mod tests;
