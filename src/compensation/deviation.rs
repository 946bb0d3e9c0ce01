//! How far a point is from a nominal path, and the figures of a set of such distances.
//!
//! The deviation of a predicted point is its distance to the closest point of the nominal
//! path (lines and arcs as programmed), not to the sample it came from: a point that slid
//! along the path is on the part.
//!
//! `compensate` knows which sample each predicted point belongs to, and measures it
//! against the stretch of path around that sample (`LocalPath`): the cutting moves within
//! twice the point's distance from its sample, along the path. A closer point of the path
//! can only be nearer than that along the path, or belong to another pass; another pass
//! is not the surface being cut, and on a program whose passes pile up over the same area
//! it would be found ever closer (a generated 50 MB program crosses every square
//! micrometre of its area several times) and ever more expensive to search. The stretch
//! holds a few moves, so a whole program is measured in time linear in its size.
//!
//! `verify` compares two programs whose moves do not correspond: it follows the original's
//! path along the compensated program (`verify/follow.rs`) and measures against a window of
//! the original's path around each point's own point, falling back to the whole path for
//! points that stray from it.
//!
//! **SSQ** is the thesis' eq. 5.8, the root of the sum of the squares of the errors,
//! `SSQ = [Σ P_i²]^½`, where the thesis' `P_i` is the radial error of the ball bar (for
//! an arc) or the error normal to the path (for a turned or faced surface) at each of its
//! points. Here `P_i` is the distance of the i-th sample from the nominal path, normal to
//! it by construction; like the thesis' figure it grows with the number of points, so
//! figures compare only at the same sampling.

use std::borrow::Cow;

use crate::geometry;
use crate::toolpath::{Motion, Move, Toolpath, Xz};

use super::fit::distance_to_chord;
use crate::error_model::sampling::PathSample;

/// Max, RMS and SSQ of a set of distances, mm.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct Figures {
    pub max_mm: f64,
    pub rms_mm: f64,
    pub ssq_mm: f64,
    pub points: usize,
}

impl Figures {
    /// The figures rounded to 0.1 nm, far below any machine's resolution, for reports
    /// that read the same on every platform.
    pub fn rounded(self) -> Figures {
        Figures { max_mm: nm(self.max_mm), rms_mm: nm(self.rms_mm), ssq_mm: nm(self.ssq_mm), points: self.points }
    }

    pub fn of(distances: impl IntoIterator<Item = f64>) -> Figures {
        let mut tally = Tally::default();
        for d in distances {
            tally.add(d);
        }
        tally.figures()
    }

    /// How much smaller `after` is than `self`, percent of `self` (by RMS), to 0.0001 %;
    /// `None` where `self` deviates by nothing (an RMS under [`NOTHING_MM`]): a share of
    /// nothing is no figure, and a rounding error divided by it is a wild one.
    pub fn improvement_percent(&self, after: &Figures) -> Option<f64> {
        (self.rms_mm >= NOTHING_MM).then(|| (100.0 * (1.0 - after.rms_mm / self.rms_mm) * 1e4).round() / 1e4)
    }
}

/// An RMS improvement as `verify` and `report` say it: the percentage, or that there was
/// nothing to improve.
pub fn improvement_text(percent: Option<f64>) -> String {
    match percent {
        Some(percent) => format!("{percent:.1} %"),
        None => "none to measure: as programmed, the program deviates by nothing on this model".to_string(),
    }
}

/// A deviation this small is none, mm: a nanometre, a thousandth of the finest increment a
/// lathe control writes and far below what any figure is printed to.
pub const NOTHING_MM: f64 = 1e-6;

/// The running sums `Figures` are made of, for distances that come one at a time: added in
/// the same order, they give the same figures as `Figures::of`.
///
/// A distance may stand for more or less than one point (`add_along`): compensation
/// samples a path as sparsely as its model allows, and weighs each sample by the length of
/// path it stands for, in the thesis' 0.254 mm steps, so that its RMS is the RMS along the
/// path and its SSQ the one the thesis' sampling would give, however the path was sampled.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Tally {
    max: f64,
    sum2: f64,
    weight: f64,
    n: usize,
}

impl Tally {
    pub fn add(&mut self, d: f64) {
        self.add_along(d, None, 1.0);
    }

    /// A distance at the end of `weight` points of path whose other end is at `previous`
    /// (`None`: nothing measured there, such as the end of a rapid): the square of the
    /// distance along them is taken by the trapezoid rule, and the maximum is over both
    /// ends (the start is on the path the figures describe, even when it was measured as
    /// the end of the block before).
    pub fn add_along(&mut self, d: f64, previous: Option<f64>, weight: f64) {
        let weight = if weight.is_finite() && weight > 0.0 { weight } else { 0.0 };
        let start = if weight > 0.0 { previous.unwrap_or(d) } else { d };
        self.max = self.max.max(d).max(start);
        self.sum2 += weight * (start * start + d * d) / 2.0;
        self.weight += weight;
        self.n += 1;
    }

    /// A distance with its side (`LocalPath::side`) at the end of `weight` points of path
    /// whose other end is at `previous`, the path between followed as a straight
    /// interpolation of the two: the square is integrated exactly along it, so a stretch
    /// where the path crosses the contour counts for what it deviates, not for the larger
    /// of its ends (the trapezoid rule of `add_along` would).
    pub fn add_signed_along(&mut self, signed: f64, previous: Option<f64>, weight: f64) {
        let weight = if weight.is_finite() && weight > 0.0 { weight } else { 0.0 };
        let start = if weight > 0.0 { previous.unwrap_or(signed) } else { signed };
        self.max = self.max.max(signed.abs()).max(start.abs());
        self.sum2 += weight * (start * start + start * signed + signed * signed) / 3.0;
        self.weight += weight;
        self.n += 1;
    }

    /// Both tallies, `other`'s distances counted after `self`'s (the sum of squares is then
    /// added as one term, so the figures may differ from one tally of all the distances in
    /// the last place).
    pub fn merged(self, other: Tally) -> Tally {
        Tally {
            max: self.max.max(other.max),
            sum2: self.sum2 + other.sum2,
            weight: self.weight + other.weight,
            n: self.n + other.n,
        }
    }

    pub fn figures(&self) -> Figures {
        Figures {
            max_mm: self.max,
            rms_mm: if self.weight > 0.0 { (self.sum2 / self.weight).sqrt() } else { 0.0 },
            ssq_mm: self.sum2.sqrt(),
            // The length measured in the thesis' steps, which the sum of squares is over:
            // the same however closely the path was sampled.
            points: self.weight.round() as usize,
        }
    }
}

/// `mm` rounded to 0.1 nm.
pub fn nm(mm: f64) -> f64 {
    (mm * 1e7).round() / 1e7
}

/// Distance from `p` to the move `m` that starts at `start` (reference points: `m.end`).
pub fn distance_to_move(p: Xz, start: Xz, m: &Move) -> f64 {
    match m.motion {
        Motion::Cw | Motion::Ccw => {
            let ccw = m.motion == Motion::Ccw;
            let radius = start.distance(m.centre);
            if geometry::angle_within(p, start, m.end, m.centre, ccw) {
                (p.distance(m.centre) - radius).abs()
            } else {
                p.distance(start).min(p.distance(m.end))
            }
        }
        Motion::Dwell => p.distance(m.end),
        _ => distance_to_chord(p, start, m.end),
    }
}

/// The nominal path as stretches around samples (see the module documentation).
pub struct LocalPath<'a> {
    toolpath: &'a Toolpath,
    /// The length of the path up to the end of each move, mm.
    ends: Vec<f64>,
    /// Per move, where its arc's constants are in `arcs` (`NO_ARC` for other moves): most
    /// moves are lines, and a table of options for every move cost a hundred megabytes on
    /// a 50 MB program.
    arc_of: Vec<u32>,
    /// Each arc's constants, computed once for its many samples.
    arcs: Vec<ArcConstants>,
    /// The farthest the path goes from the origin in each axis (`LocalPath::reach`).
    reach: Xz,
}

/// `LocalPath::arc_of` for a move that is no arc, or whose constants are not kept (past
/// four thousand million arcs; they are then computed when asked for).
const NO_ARC: u32 = u32::MAX;

/// What `distance_to_move` computes of an arc before it looks at the point.
#[derive(Debug, Clone, Copy)]
struct ArcConstants {
    radius: f64,
    sector: geometry::Sector,
}

impl ArcConstants {
    fn of(start: Xz, m: &Move) -> ArcConstants {
        ArcConstants {
            radius: start.distance(m.centre),
            sector: geometry::Sector::new(start, m.end, m.centre, m.motion == Motion::Ccw),
        }
    }
}

impl<'a> LocalPath<'a> {
    pub fn new(toolpath: &'a Toolpath) -> LocalPath<'a> {
        let mut total = 0.0;
        let mut ends = Vec::with_capacity(toolpath.moves.len());
        let mut arc_of = Vec::with_capacity(toolpath.moves.len());
        let mut arcs = Vec::new();
        let mut reach = Xz::new(toolpath.start.x.abs(), toolpath.start.z.abs());
        for (k, m) in toolpath.moves.iter().enumerate() {
            let start = toolpath.start_of(k);
            let index = match m.is_arc().then(|| ArcConstants::of(start, m)) {
                Some(arc) => {
                    let radius = arc.radius;
                    reach = crate::toolpath::reach_past(reach, m.end, Some((m.centre, radius)));
                    // `move_length`, with the sweep the constants hold.
                    total += arc.radius * arc.sector.total();
                    let index = u32::try_from(arcs.len()).unwrap_or(NO_ARC);
                    if index != NO_ARC {
                        arcs.push(arc);
                    }
                    index
                }
                None => {
                    reach = crate::toolpath::reach_past(reach, m.end, None);
                    total += move_length(start, m);
                    NO_ARC
                }
            };
            ends.push(total);
            arc_of.push(index);
        }
        LocalPath { toolpath, ends, arc_of, arcs, reach }
    }

    /// The farthest the path goes from the origin in each axis, mm (X as a radius): an
    /// arc's whole circle counts, which bounds it without finding its extremes. Measured in
    /// `new`'s pass over the moves, which has each arc's radius, so that `compensate` need
    /// not read a long program's moves once more for its sampling (`program::sampling`).
    pub fn reach(&self) -> Xz {
        self.reach
    }

    /// The constants of move `k` when it is an arc: borrowed from `arcs` (they are read for
    /// every sample measured against the arc, and a copy of them cost more than reading them).
    fn arc(&self, k: usize, m: &Move) -> Option<Cow<'_, ArcConstants>> {
        if !m.is_arc() {
            return None;
        }
        match self.arc_of.get(k).and_then(|&index| self.arcs.get(index as usize)) {
            Some(arc) => Some(Cow::Borrowed(arc)),
            None => Some(Cow::Owned(ArcConstants::of(self.toolpath.start_of(k), m))),
        }
    }

    /// The distance from `p`, predicted for `sample`, to the closest cutting move within
    /// twice its distance from the sample along the path; `None` for a sample that does not
    /// cut.
    pub fn distance(&self, sample: &PathSample, p: Xz) -> Option<f64> {
        if !sample.cutting {
            return None;
        }
        self.distance_around(sample.move_index, sample.param, sample.nominal, p)
    }

    /// The distance from `p` to the closest cutting move within twice its distance from
    /// `anchor` along the path, where `anchor` is the point at `param` of move `k`; `None`
    /// when move `k` does not cut.
    pub fn distance_around(&self, k: usize, param: f64, anchor: Xz, p: Xz) -> Option<f64> {
        let m = self.toolpath.moves.get(k)?;
        if !m.cutting || m.motion == Motion::Dwell {
            return None;
        }
        let end = self.ends.get(k).copied().unwrap_or(0.0);
        let start = if k == 0 { 0.0 } else { self.ends.get(k - 1).copied().unwrap_or(0.0) };
        let at = start + (end - start) * param.clamp(0.0, 1.0);
        let reach = 2.0 * p.distance(anchor);
        let mut best = self.distance_to(p, k);
        for before in (0..k).rev() {
            if at - self.ends[before] > reach {
                break;
            }
            best = best.min(self.distance_to(p, before));
        }
        for after in k + 1..self.toolpath.moves.len() {
            if self.ends[after - 1] - at > reach {
                break;
            }
            best = best.min(self.distance_to(p, after));
        }
        best.is_finite().then_some(best)
    }

    /// The start angle about its centre and the sweep of move `k` when it is an arc
    /// (`geometry::angle`, `geometry::sweep`), as measured once for its constants.
    pub fn arc_angles(&self, k: usize) -> Option<(f64, f64)> {
        let m = self.toolpath.moves.get(k)?;
        self.arc(k, m).map(|arc| (arc.sector.start_angle(), arc.sector.total()))
    }

    /// The distance to move `k` when it cuts (infinity otherwise): `distance_to_move`, with
    /// an arc's constants taken from `arcs`.
    pub fn distance_to(&self, p: Xz, k: usize) -> f64 {
        let Some(m) = self.toolpath.moves.get(k).filter(|m| m.cutting && m.motion != Motion::Dwell) else {
            return f64::INFINITY;
        };
        let start = self.toolpath.start_of(k);
        match self.arc(k, m).as_deref() {
            Some(ArcConstants { radius, sector, .. }) => {
                if sector.contains(p) {
                    (p.distance(m.centre) - radius).abs()
                } else {
                    p.distance(start).min(p.distance(m.end))
                }
            }
            None => distance_to_move(p, start, m),
        }
    }
}

/// The length of move `m` from `start`, mm (the arc length of an arc).
fn move_length(start: Xz, m: &Move) -> f64 {
    match m.motion {
        Motion::Dwell => 0.0,
        Motion::Cw | Motion::Ccw => geometry::arc_length(start, m.end, m.centre, m.motion == Motion::Ccw),
        _ => start.distance(m.end),
    }
}

#[cfg(test)]
mod tests;
