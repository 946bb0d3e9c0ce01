//! Re-expressing a compensated move as G-code segments.
//!
//! Compensation gives, for each nominal move, the points to command along it. A move is
//! written back as lines and arcs that pass within the tolerance of every one of those
//! points (and, for arcs, whose every chord stays within it too), by one of the strategies:
//!
//! * `densify` — straight `G01` moves through the points, at `--step` or as few as the
//!   chord tolerance allows (the thesis' O2012 turn);
//! * `circle` — one least-squares circle per programmed arc (`fit/circle.rs`);
//! * `semicircle` / `quadrant` — the arc split at its X reversals or at every quadrant,
//!   one circle each (the thesis' Table 4–5 modes);
//! * `arcs` — the fewest tangent-continuous arcs within the tolerance (`fit/arcs.rs`);
//! * `auto` — per move, the cheapest of these that meets the tolerance.
//!
//! A line stays one line when its points allow it, whatever the strategy.

use crate::toolpath::Xz;

/// One written segment, from the end of the previous one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Segment {
    Line { end: Xz },
    Arc { end: Xz, centre: Xz, ccw: bool },
}

impl Segment {
    pub fn end(&self) -> Xz {
        match *self {
            Segment::Line { end } | Segment::Arc { end, .. } => end,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Strategy {
    #[default]
    Auto,
    Circle,
    Semicircle,
    Quadrant,
    Arcs,
    Densify,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitOptions {
    pub strategy: Strategy,
    /// Every commanded point must lie this close to the written path, mm.
    pub tolerance_mm: f64,
    /// For `densify`: the length of each `G01`, mm; `None` lets the chord tolerance decide.
    pub step_mm: Option<f64>,
}

/// What the move was before compensation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NominalShape {
    Line,
    Arc { centre: Xz, ccw: bool },
}

/// One compensated move: where it starts (the end of the previous written move) and the
/// points to command along it, the last of which is its end.
#[derive(Debug, Clone, Copy)]
pub struct MovePoints<'a> {
    pub start: Xz,
    pub points: &'a [Xz],
    pub nominal: NominalShape,
}

/// Distance from `p` to the segment `a`–`b`.
pub fn distance_to_chord(p: Xz, a: Xz, b: Xz) -> f64 {
    let (dx, dz) = (b.x - a.x, b.z - a.z);
    let length2 = dx * dx + dz * dz;
    if length2 <= 0.0 {
        return p.distance(a);
    }
    let t = (((p.x - a.x) * dx + (p.z - a.z) * dz) / length2).clamp(0.0, 1.0);
    p.distance(Xz::new(a.x + dx * t, a.z + dz * t))
}

/// `densify`: straight moves through the points. With a step, one line per step of path
/// length (ending on sample points); without, the fewest lines whose every skipped point
/// lies within the tolerance of its chord (greedy, from the start).
pub fn densify(m: &MovePoints<'_>, tolerance_mm: f64, step_mm: Option<f64>) -> Vec<Segment> {
    let points = m.points;
    let Some(&last) = points.last() else { return Vec::new() };
    let mut out = Vec::new();
    match step_mm.filter(|s| s.is_finite() && *s > 0.0) {
        Some(step) => {
            let mut travelled = 0.0;
            let mut previous = m.start;
            for (i, &p) in points.iter().enumerate() {
                travelled += previous.distance(p);
                previous = p;
                if travelled >= step - 1e-9 || i + 1 == points.len() {
                    out.push(Segment::Line { end: p });
                    travelled = 0.0;
                }
            }
        }
        None => {
            let mut from = m.start;
            let mut first = 0;
            while first < points.len() {
                // Extend the chord as far as every skipped point stays within tolerance.
                let mut end = first;
                while end + 1 < points.len()
                    && points[first..=end].iter().all(|&p| distance_to_chord(p, from, points[end + 1]) <= tolerance_mm)
                {
                    end += 1;
                }
                out.push(Segment::Line { end: points[end] });
                from = points[end];
                first = end + 1;
            }
        }
    }
    if out.last().map(Segment::end) != Some(last) {
        out.push(Segment::Line { end: last });
    }
    out
}

#[cfg(test)]
mod tests;
