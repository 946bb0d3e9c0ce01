//! Quantising a move's segments to the machine's grid.
//!
//! Every end point is rounded on its own, from its exact position, never from the previous
//! rounded point plus a rounded increment: the rounded path is then within half an
//! increment of the exact one at every end point however long it runs, and an incremental
//! program (`U`/`W`) written as differences of these rounded absolutes sums back to them
//! exactly. (Rounding each increment instead lets the errors add up: a random walk of
//! half-increments, a full increment off after a few dozen moves.)
//!
//! An arc's two rounded ends are generally no longer on one circle about its centre, so the
//! centre is recomputed:
//!
//! * in the radius form (`R`, OSP `L`), the control finds the centre from the rounded ends
//!   and the rounded radius; the radius is rounded to the length increment (raised to the
//!   smallest one that reaches across the chord, if rounding left it short) and the centre
//!   put on the side the arc's sweep needs (beyond 180° a negative `R`);
//! * in the centre form (`I K`), the centre offset from the rounded start is rounded to its
//!   own grid; the control then checks that the two ends are equally far from that centre
//!   (Fanuc and OSP raise an alarm beyond a set tolerance), so when they are not, the grid
//!   centres within two increments are tried and the nearest one to the exact centre that
//!   passes is taken.
//!
//! An arc that cannot be written is reported and written as a line to its rounded end (a
//! move the control will run); the deviation from the compensated points is measured again
//! after rounding, so the caller sees what rounding cost.

use std::f64::consts::PI;

use super::Segment;
use super::deviation;
use crate::geometry;
use crate::toolpath::Xz;

/// The least increment along each axis, mm, in the toolpath's frame: X as a radius, so on a
/// diameter-programmed machine `x_mm` is half the diameter increment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    pub x_mm: f64,
    pub z_mm: f64,
}

/// `value` to the nearest multiple of `step` (unchanged when `step` is not a positive number).
pub fn round_to(value: f64, step: f64) -> f64 {
    if step.is_finite() && step > 0.0 { (value / step).round() * step } else { value }
}

impl Grid {
    pub fn round(&self, p: Xz) -> Xz {
        Xz::new(round_to(p.x, self.x_mm), round_to(p.z, self.z_mm))
    }
}

/// How the program writes arcs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ArcForm {
    /// `R` (Fanuc) or `L` (OSP): the radius, on a grid of `increment_mm`.
    Radius { increment_mm: f64 },
    /// `I K`: the centre's offset from the start, on `grid`; the control accepts an arc whose
    /// two end radii differ by up to `tolerance_mm` (take one least increment).
    Centre { grid: Grid, tolerance_mm: f64 },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ArcProblem {
    /// Its rounded ends coincide though it was not a full circle (a control would run a
    /// full circle): written as a line.
    Vanished,
    /// A full circle has no radius form: written as a line (no motion).
    FullCircleByRadius,
    /// No centre on the grid near the exact one puts both ends within the control's
    /// tolerance of one radius; the smallest difference of the end radii found, mm.
    RadiusMismatch { mm: f64 },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcFailure {
    /// Which of the segments.
    pub index: usize,
    pub problem: ArcProblem,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Quantized {
    /// The rounded start.
    pub start: Xz,
    pub segments: Vec<Segment>,
    /// The largest distance of a compensated point from the rounded path, mm.
    pub max_deviation_mm: f64,
    pub failures: Vec<ArcFailure>,
}

/// Round the segments that run from `start` to `grid`, and measure the rounded path
/// against the compensated `points`.
pub fn quantize(start: Xz, segments: &[Segment], points: &[Xz], grid: Grid, form: ArcForm) -> Quantized {
    let rounded_start = grid.round(start);
    let mut out = Vec::with_capacity(segments.len());
    let mut failures = Vec::new();
    let mut exact_from = start;
    let mut from = rounded_start;
    for (index, segment) in segments.iter().enumerate() {
        let end = grid.round(segment.end());
        let written = match *segment {
            Segment::Line { .. } => Segment::Line { end },
            Segment::Arc { end: exact_end, centre, ccw } => {
                let arc = Arc { exact_from, exact_end, centre, ccw, from, end };
                arc.round(form).unwrap_or_else(|problem| {
                    failures.push(ArcFailure { index, problem });
                    Segment::Line { end }
                })
            }
        };
        out.push(written);
        exact_from = segment.end();
        from = end;
    }
    let max_deviation_mm = deviation::max_deviation(rounded_start, &out, points);
    Quantized { start: rounded_start, segments: out, max_deviation_mm, failures }
}

/// An arc, exact and with its ends rounded.
struct Arc {
    exact_from: Xz,
    exact_end: Xz,
    centre: Xz,
    ccw: bool,
    from: Xz,
    end: Xz,
}

impl Arc {
    fn round(&self, form: ArcForm) -> Result<Segment, ArcProblem> {
        let full = self.exact_from.distance(self.exact_end) <= 1e-9;
        if !full && self.from == self.end {
            return Err(ArcProblem::Vanished);
        }
        let centre = match form {
            ArcForm::Radius { increment_mm } => self.by_radius(full, increment_mm)?,
            ArcForm::Centre { grid, tolerance_mm } => self.by_centre(grid, tolerance_mm)?,
        };
        Ok(Segment::Arc { end: self.end, centre, ccw: self.ccw })
    }

    fn by_radius(&self, full: bool, increment: f64) -> Result<Xz, ArcProblem> {
        if full {
            return Err(ArcProblem::FullCircleByRadius);
        }
        let major = geometry::sweep(self.exact_from, self.exact_end, self.centre, self.ccw) > PI;
        let half_chord = self.from.distance(self.end) / 2.0;
        let mut radius = round_to(self.exact_from.distance(self.centre), increment);
        if radius < half_chord {
            radius = if increment.is_finite() && increment > 0.0 {
                (half_chord / increment).ceil() * increment
            } else {
                half_chord
            };
        }
        let signed = if major { -radius } else { radius };
        geometry::centre_from_radius(self.from, self.end, signed, self.ccw, 1e-12)
            .ok_or(ArcProblem::RadiusMismatch { mm: half_chord - radius })
    }

    fn by_centre(&self, grid: Grid, tolerance: f64) -> Result<Xz, ArcProblem> {
        let offset = grid.round(Xz::new(self.centre.x - self.from.x, self.centre.z - self.from.z));
        let base = Xz::new(self.from.x + offset.x, self.from.z + offset.z);
        let mut best: Option<(f64, Xz)> = None;
        let mut least_mismatch = f64::INFINITY;
        for i in -2..=2 {
            for k in -2..=2 {
                let candidate = Xz::new(base.x + f64::from(i) * grid.x_mm, base.z + f64::from(k) * grid.z_mm);
                let mismatch = (self.from.distance(candidate) - self.end.distance(candidate)).abs();
                least_mismatch = least_mismatch.min(mismatch);
                let away = candidate.distance(self.centre);
                if mismatch <= tolerance && best.is_none_or(|(d, _)| away < d) {
                    best = Some((away, candidate));
                }
            }
        }
        best.map(|(_, centre)| centre).ok_or(ArcProblem::RadiusMismatch { mm: least_mismatch })
    }
}

#[cfg(test)]
mod tests;
