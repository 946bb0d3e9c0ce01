//! The material as dexels: rays along Z at evenly spaced radii and rays along X at evenly
//! spaced Z, each holding the intervals of material on it, in order.
//!
//! Every end of an interval is a point of the surface, exact in f64: the stock's own faces,
//! or where the ray left the sweep of the move that cut it ([`Edge`] records which move,
//! and the outward normal of the material there). The spacing of the rays decides which
//! features are seen (a groove narrower than the spacing can fall between two rays), not
//! how exactly a seen surface is placed.

use smallvec::SmallVec;

use super::sweep::{Crossing, Line, Sweep};
use crate::toolpath::Xz;

/// Who made an edge of the material: a move of the toolpath, or the stock.
pub const STOCK: u32 = u32::MAX;

/// One end of an interval of material: where it is along its ray, the outward normal of
/// the material there (x, z), and the move that cut it ([`STOCK`] for the bar's faces).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Edge {
    pub at: f64,
    pub normal: [f32; 2],
    pub by: u32,
}

impl Edge {
    pub fn normal(&self) -> Xz {
        Xz::new(f64::from(self.normal[0]), f64::from(self.normal[1]))
    }
}

/// An interval of material on a ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span {
    pub lo: Edge,
    pub hi: Edge,
}

/// The material on one ray, in order along it, disjoint.
pub type Spans = SmallVec<[Span; 2]>;

/// Intervals shorter than this (mm) are no material: a film left by rounding where two
/// sweeps meet.
const FILM: f64 = 1e-7;

/// What a sweep found or took on the rays it crossed.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Taken {
    /// The longest length of material inside the sweep on one ray along Z, and on one ray
    /// along X, mm.
    pub along_z: f64,
    pub along_x: f64,
    /// The material inside the sweep summed over every ray crossed, mm (times the spacing, an
    /// area).
    pub total: f64,
    /// How many rays were visited.
    pub rays: u64,
}

/// The two families of rays over the stock's box.
#[derive(Debug, Clone)]
pub struct Dexels {
    /// The spacing of both families, mm.
    pub spacing: f64,
    /// The lowest x and z of the box: ray `i` along Z lies at `x_lo + (i + ½)·spacing`.
    pub x_lo: f64,
    pub z_lo: f64,
    pub along_z: Vec<Spans>,
    pub along_x: Vec<Spans>,
    /// For each run of [`BLOCK`] rays of a family, the lowest and highest end of the
    /// material on them: a sweep passes over a run whose material it cannot reach without
    /// visiting its rays (most moves of a long program run through air).
    reach_z: Vec<(f64, f64)>,
    reach_x: Vec<(f64, f64)>,
}

/// How many rays a reach of [`Dexels`] covers.
const BLOCK: usize = 32;

/// The lowest and highest end of the material on `rays`.
fn reach_of(rays: &[Spans]) -> (f64, f64) {
    rays.iter()
        .filter(|s| !s.is_empty())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| (lo.min(s[0].lo.at), hi.max(s[s.len() - 1].hi.at)))
}

impl Dexels {
    /// The box from `lo` to `hi` filled with rays `spacing` apart, each holding what
    /// `fill` gives for its line.
    pub fn new(lo: Xz, hi: Xz, spacing: f64, mut fill: impl FnMut(Line) -> Spans) -> Dexels {
        let count = |extent: f64| ((extent / spacing).ceil() as usize).max(1);
        let (nx, nz) = (count(hi.x - lo.x), count(hi.z - lo.z));
        let mut dexels = Dexels {
            spacing,
            x_lo: lo.x,
            z_lo: lo.z,
            along_z: Vec::new(),
            along_x: Vec::new(),
            reach_z: Vec::new(),
            reach_x: Vec::new(),
        };
        dexels.along_z = (0..nx).map(|i| fill(dexels.line(true, i))).collect();
        dexels.along_x = (0..nz).map(|j| fill(dexels.line(false, j))).collect();
        dexels.reach_z = dexels.along_z.chunks(BLOCK).map(reach_of).collect();
        dexels.reach_x = dexels.along_x.chunks(BLOCK).map(reach_of).collect();
        dexels
    }

    /// Ray `index` of a family.
    pub fn line(&self, along_z: bool, index: usize) -> Line {
        let origin = if along_z { self.x_lo } else { self.z_lo };
        Line { along_z, at: origin + (index as f64 + 0.5) * self.spacing }
    }

    /// The indices of the rays of a family whose line lies between `lo` and `hi`.
    fn range(&self, along_z: bool, lo: f64, hi: f64) -> std::ops::Range<usize> {
        let (origin, count) = if along_z { (self.x_lo, self.along_z.len()) } else { (self.z_lo, self.along_x.len()) };
        let first = crate::geometry::ceil((lo - origin) / self.spacing - 0.5);
        let last = crate::geometry::floor((hi - origin) / self.spacing - 0.5);
        if !(first.is_finite() && last.is_finite()) || last < 0.0 || first >= count as f64 || last < first {
            return 0..0;
        }
        (first.max(0.0) as usize)..((last as usize + 1).min(count))
    }

    /// Whether the box from `lo` to `hi` may hold material: false when every run of rays
    /// across it holds its material wholly outside it (the test [`Dexels::sweep_families`]
    /// passes over a run with).
    pub fn may_meet(&self, lo: Xz, hi: Xz) -> bool {
        [(true, lo.x, hi.x, lo.z, hi.z), (false, lo.z, hi.z, lo.x, hi.x)].into_iter().any(
            |(along_z, from, to, reach_lo, reach_hi)| {
                let range = self.range(along_z, from, to);
                let reach = if along_z { &self.reach_z } else { &self.reach_x };
                !range.is_empty()
                    && reach[range.start / BLOCK..=(range.end - 1) / BLOCK]
                        .iter()
                        .any(|&(lo, hi)| reach_hi > lo && reach_lo < hi)
            },
        )
    }

    /// The rays `sweep` crosses, and how many.
    pub fn rays_crossed(&self, sweep: &Sweep) -> u64 {
        let (lo, hi) = sweep.bounds();
        (self.range(true, lo.x, hi.x).len() + self.range(false, lo.z, hi.z).len()) as u64
    }

    /// Remove what `sweep` covers, the new edges made by move `by`; or with `remove`
    /// false only measure what it would.
    #[cfg(test)]
    pub fn sweep(&mut self, sweep: &Sweep, by: u32, remove: bool) -> Taken {
        self.sweep_families(sweep, by, remove, [true, false], None)
    }

    /// [`Dexels::sweep`] on the families listed (`true` for the rays along Z). Rays whose
    /// line lies outside `window` (for the family it names) count toward the total but not
    /// toward the longest: a cut's depth is measured where it is under way, not where its
    /// nose runs into a shoulder ahead of it.
    pub fn sweep_families(
        &mut self,
        sweep: &Sweep,
        by: u32,
        remove: bool,
        families: impl IntoIterator<Item = bool>,
        window: Option<(bool, f64, f64)>,
    ) -> Taken {
        let (lo, hi) = sweep.bounds();
        let mut taken = Taken::default();
        let mut crossing = Crossing::new();
        for along_z in families {
            // Made when a ray first needs it: a sweep through air crosses no ray.
            let mut prepared = None;
            let range = if along_z { self.range(true, lo.x, hi.x) } else { self.range(false, lo.z, hi.z) };
            let (reach_lo, reach_hi) = if along_z { (lo.z, hi.z) } else { (lo.x, hi.x) };
            let mut index = range.start;
            while index < range.end {
                let block = index / BLOCK;
                let block_end = ((block + 1) * BLOCK).min(range.end);
                let reach = if along_z { self.reach_z[block] } else { self.reach_x[block] };
                if reach_hi <= reach.0 || reach_lo >= reach.1 {
                    taken.rays += 1;
                    index = block_end;
                    continue;
                }
                let mut changed = false;
                for index in index..block_end {
                    taken.rays += 1;
                    let line = self.line(along_z, index);
                    let spans = if along_z { &mut self.along_z[index] } else { &mut self.along_x[index] };
                    if spans.is_empty() {
                        continue;
                    }
                    let (first, last) = (spans[0].lo.at, spans[spans.len() - 1].hi.at);
                    if reach_hi <= first || reach_lo >= last {
                        continue;
                    }
                    let prepared = prepared.get_or_insert_with(|| sweep.prepare(along_z));
                    if prepared.misses(line, |lo, hi| spans.iter().any(|s| s.hi.at > lo && s.lo.at < hi)) {
                        continue;
                    }
                    prepared.cross_into(line, &mut crossing);
                    if crossing.is_empty() {
                        continue;
                    }
                    let inside = if remove { subtract(spans, &crossing, by) } else { overlap(spans, &crossing) };
                    changed |= remove && inside.0 > 0.0;
                    taken.total += inside.0;
                    if window.is_some_and(|(family, lo, hi)| family == along_z && !(lo..=hi).contains(&line.at)) {
                        continue;
                    }
                    if along_z {
                        taken.along_z = taken.along_z.max(inside.1);
                    } else {
                        taken.along_x = taken.along_x.max(inside.1);
                    }
                }
                if changed {
                    let rays = if along_z { &self.along_z } else { &self.along_x };
                    let reach = reach_of(&rays[block * BLOCK..((block + 1) * BLOCK).min(rays.len())]);
                    if along_z { self.reach_z[block] = reach } else { self.reach_x[block] = reach }
                }
                index = block_end;
            }
        }
        taken
    }

    /// Whether `p` lies in the material, as the ray nearest it says (exact on a ray; between
    /// rays, the nearer ray's word).
    pub fn contains(&self, p: Xz) -> bool {
        let index = ((p.x - self.x_lo) / self.spacing - 0.5).round();
        if index < 0.0 || index >= self.along_z.len() as f64 {
            return false;
        }
        self.along_z[index as usize].iter().any(|s| s.lo.at <= p.z && p.z <= s.hi.at)
    }
}

/// The material of `spans` inside `crossing`: the total and the longest on one piece.
fn overlap(spans: &Spans, crossing: &Crossing) -> (f64, f64) {
    let (mut total, mut longest) = (0.0f64, 0.0f64);
    for (lo, hi) in crossing {
        let mut inside = 0.0;
        for span in spans {
            let length = span.hi.at.min(hi.t) - span.lo.at.max(lo.t);
            if length > 0.0 {
                inside += length;
            }
        }
        total += inside;
        longest = longest.max(inside);
    }
    (total, longest)
}

/// Take `crossing` out of `spans`; the material removed, total and longest on one piece.
fn subtract(spans: &mut Spans, crossing: &Crossing, by: u32) -> (f64, f64) {
    let (mut total, mut longest) = (0.0f64, 0.0f64);
    for (lo, hi) in crossing {
        if !spans.iter().any(|span| span.hi.at > lo.t && span.lo.at < hi.t) {
            continue;
        }
        let mut removed = 0.0;
        let mut out = Spans::new();
        for span in spans.iter() {
            if span.hi.at <= lo.t || span.lo.at >= hi.t {
                out.push(*span);
                continue;
            }
            removed += span.hi.at.min(hi.t) - span.lo.at.max(lo.t);
            // The material's outward normal at a new edge points into the sweep.
            let edge = |t: f64, n: Xz| Edge { at: t, normal: [-n.x as f32, -n.z as f32], by };
            if span.lo.at < lo.t - FILM {
                out.push(Span { lo: span.lo, hi: edge(lo.t, lo.normal) });
            }
            if span.hi.at > hi.t + FILM {
                out.push(Span { lo: edge(hi.t, hi.normal), hi: span.hi });
            }
        }
        *spans = out;
        total += removed;
        longest = longest.max(removed);
    }
    (total, longest)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bar() -> Dexels {
        // A bar of radius 10 from z = -20 to z = 0, rays 0.1 mm apart.
        Dexels::new(Xz::new(0.0, -20.0), Xz::new(10.0, 0.0), 0.1, |line| {
            let (lo, hi) = if line.along_z { (-20.0, 0.0) } else { (0.0, 10.0) };
            let stock = |at: f64, n: [f32; 2]| Edge { at, normal: n, by: STOCK };
            let (n_lo, n_hi) = if line.along_z { ([0.0, -1.0], [0.0, 1.0]) } else { ([-1.0, 0.0], [1.0, 0.0]) };
            SmallVec::from_slice(&[Span { lo: stock(lo, n_lo), hi: stock(hi, n_hi) }])
        })
    }

    #[test]
    fn a_turning_pass_leaves_its_radius_with_the_move_and_normal_on_every_ray() {
        let mut dexels = bar();
        // A nose of 0.5 at x = 8.5 from z = 1 to z = -10: the surface is x = 8 to z = -10.
        let sweep =
            Sweep::rounded([Xz::new(8.5, 1.0), Xz::new(8.5, -10.0), Xz::new(20.0, 1.0), Xz::new(20.0, -10.0)], 0.5);
        let taken = dexels.sweep(&sweep, 7, true);
        assert!((taken.along_x - 2.0).abs() < 1e-12, "{taken:?}");
        let ray = &dexels.along_x[150]; // z = -4.95
        assert_eq!(ray.len(), 1);
        assert!((ray[0].hi.at - 8.0).abs() < 1e-12 && ray[0].hi.by == 7);
        assert_eq!(ray[0].hi.normal, [1.0, 0.0]);
        assert!(dexels.contains(Xz::new(7.9, -5.0)) && !dexels.contains(Xz::new(8.1, -5.0)));
        // Measuring again finds nothing left.
        assert_eq!(dexels.sweep(&sweep, 8, false).total, 0.0);
    }
}
