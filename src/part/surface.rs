//! The finished part: the material the last move leaves, read as a surface.
//!
//! Every end of an interval of material on a ray is a point of the surface with the
//! material's outward normal and the move that cut it (or the stock's face it still is).
//! What inspection needs of it is read from these points: a CMM probes along a normal, a
//! thread's flanks are the points the thread passes' stamps left, a plot draws the stock's
//! outline and the part's.
//!
//! **Part-off.** Where a move leaves no material at all at some Z between material in front
//! and behind (a part-off tool run to the axis), the part is cut from the bar: the finished
//! part is the piece in front (toward +Z, the end the program machined), and the piece
//! behind is the bar left in the chuck ([`Part::separated_at`]).

use super::dexel::{Dexels, STOCK, Span};
use super::stock::Stock;
use crate::toolpath::Xz;

/// The finished part of a program.
#[derive(Debug, Clone)]
pub struct Part {
    dexels: Dexels,
    pub stock: Stock,
    /// The Z of the cut that parted it off the bar, if one did (the part's back face as the
    /// rays along Z see it): the part lies in front.
    pub separated_at: Option<f64>,
}

/// A point of the finished surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    pub at: Xz,
    /// The material's outward unit normal.
    pub normal: Xz,
    /// The index of the move that cut it, or none for a face of the stock still there.
    pub cut_by: Option<usize>,
}

impl Part {
    pub(crate) fn new(dexels: Dexels, stock: Stock) -> Part {
        let has = |j: usize| !dexels.along_x[j].is_empty();
        let rays = dexels.along_x.len();
        // The frontmost empty ray with material both in front of it and behind it.
        let mut separated_at = None;
        if let Some(front) = (0..rays).rev().find(|&j| has(j)) {
            let back = (0..rays).find(|&j| has(j)).unwrap_or(front);
            if let Some(gap) = (back..front).rev().find(|&j| !has(j)) {
                // The part's back face: the cut's own edge on the rays along Z, exactly.
                let gap = dexels.line(false, gap).at;
                let face =
                    dexels.along_z.iter().flatten().map(|s| s.lo.at).filter(|&z| z > gap).fold(f64::INFINITY, f64::min);
                let next = dexels.line(false, (front + 1).min(rays)).at;
                separated_at = Some(if face.is_finite() && face < next { face } else { gap });
            }
        }
        Part { dexels, stock, separated_at }
    }

    /// The spacing of the rays the part was cut on, mm: features narrower than it may fall
    /// between two rays.
    pub fn spacing(&self) -> f64 {
        self.dexels.spacing
    }

    /// Whether `p` lies in the part (in front of a part-off cut), as the ray along Z nearest
    /// it says: exact for a point on a ray, and between rays the nearer ray's word, which may
    /// be half the spacing away across a surface. [`Part::rays`] gives the exact material.
    pub fn contains(&self, p: Xz) -> bool {
        self.separated_at.is_none_or(|z| p.z >= z) && self.dexels.contains(p)
    }

    /// The rays of one family (`along_z`: the lines `x = at`, else `z = at`) whose line lies
    /// between `lo` and `hi`, each with the part's material on it, exactly.
    pub fn rays(&self, along_z: bool, lo: f64, hi: f64) -> impl Iterator<Item = Ray<'_>> + '_ {
        let rays = if along_z { &self.dexels.along_z } else { &self.dexels.along_x };
        let origin = if along_z { self.dexels.x_lo } else { self.dexels.z_lo };
        let first = ((lo - origin) / self.dexels.spacing - 0.5).ceil().max(0.0);
        let first = if first.is_finite() { (first as usize).min(rays.len()) } else { rays.len() };
        rays[first..]
            .iter()
            .enumerate()
            .map(move |(k, spans)| Ray {
                line: self.dexels.line(along_z, first + k),
                spans,
                separated_at: self.separated_at,
            })
            .take_while(move |ray| ray.at() <= hi)
    }

    /// Every point of the finished surface the rays see: along each ray along Z, then each
    /// ray along X, in order. The axis (the low end of a solid part's rays along X) is no
    /// surface and is left out.
    pub fn surface(&self) -> impl Iterator<Item = SurfacePoint> + '_ {
        let in_part = move |p: Xz| self.separated_at.is_none_or(|z| p.z >= z);
        let point = |line: super::sweep::Line, edge: &super::dexel::Edge| SurfacePoint {
            at: line.point(edge.at),
            normal: edge.normal(),
            cut_by: (edge.by != STOCK).then_some(edge.by as usize),
        };
        let along_z = self.dexels.along_z.iter().enumerate().flat_map(move |(i, spans)| {
            let line = self.dexels.line(true, i);
            spans.iter().flat_map(move |s| [point(line, &s.lo), point(line, &s.hi)])
        });
        let along_x = self.dexels.along_x.iter().enumerate().flat_map(move |(j, spans)| {
            let line = self.dexels.line(false, j);
            spans.iter().flat_map(move |s| {
                let axis = s.lo.by == STOCK && s.lo.at <= 1e-12;
                (!axis).then(|| point(line, &s.lo)).into_iter().chain([point(line, &s.hi)])
            })
        });
        along_z.chain(along_x).filter(move |p| in_part(p.at))
    }

    /// Whether `p` lies on the finished surface as far as the rays can tell: a point of the
    /// surface (an end of the material on a ray) lies within one cell of the rays' grid of
    /// it (the spacing times √2), as one does of every point of a surface, which crosses a
    /// side of each cell it passes through. A point in the air farther than that from any
    /// material, or deep in the material, is not on it.
    pub fn is_on_surface(&self, p: Xz) -> bool {
        let reach = self.dexels.spacing * std::f64::consts::SQRT_2;
        let close = |ray: &Ray<'_>, t: f64| ray.point(t).distance(p) <= reach;
        // The axis end of a solid part's ray along X is no surface.
        let on = |ray: &Ray<'_>| {
            ray.material().any(|(lo, hi)| ((ray.along_z() || lo > 1e-12) && close(ray, lo)) || close(ray, hi))
        };
        self.rays(true, p.x - reach, p.x + reach).any(|ray| on(&ray))
            || self.rays(false, p.z - reach, p.z + reach).any(|ray| on(&ray))
    }

    /// The half-section's outline for a drawing: for each run of rays along X that hold
    /// material, a closed polygon of (z, x) points — the outermost material of each ray from
    /// the back to the front, then the innermost from the front to the back (the axis, or a
    /// bore). A recess inside the material (an undercut seen from no ray's end) is filled in.
    pub fn outline(&self) -> Vec<Vec<(f64, f64)>> {
        let mut polygons = Vec::new();
        let mut outer: Vec<(f64, f64)> = Vec::new();
        let mut inner: Vec<(f64, f64)> = Vec::new();
        let mut close = |outer: &mut Vec<(f64, f64)>, inner: &mut Vec<(f64, f64)>| {
            if outer.len() > 1 {
                let mut polygon = std::mem::take(outer);
                polygon.extend(inner.drain(..).rev());
                polygons.push(polygon);
            }
            outer.clear();
            inner.clear();
        };
        for ray in self.rays(false, f64::NEG_INFINITY, f64::INFINITY) {
            let mut material = ray.material();
            let Some((lo, mut hi)) = material.next() else {
                close(&mut outer, &mut inner);
                continue;
            };
            hi = material.last().map_or(hi, |(_, h)| h);
            outer.push((ray.at(), hi));
            inner.push((ray.at(), lo));
        }
        close(&mut outer, &mut inner);
        polygons
    }

    /// The part's outer radius at `z` as the ray along X nearest it sees (none where there is
    /// no material), for plots and thread measures.
    pub fn outer_radius_at(&self, z: f64) -> Option<f64> {
        let index = ((z - self.dexels.z_lo) / self.dexels.spacing - 0.5).round();
        if index < 0.0 || !self.separated_at.is_none_or(|at| z >= at) {
            return None;
        }
        self.dexels.along_x.get(index as usize)?.last().map(|s| s.hi.at)
    }
}

/// One ray of a part's dexels and the part's material on it.
#[derive(Debug, Clone, Copy)]
pub struct Ray<'p> {
    line: super::sweep::Line,
    spans: &'p [Span],
    separated_at: Option<f64>,
}

impl Ray<'_> {
    /// Whether the ray runs along Z (the line `x = at`), else along X (`z = at`).
    pub fn along_z(&self) -> bool {
        self.line.along_z
    }

    /// The coordinate the ray holds fixed, mm.
    pub fn at(&self) -> f64 {
        self.line.at
    }

    /// The point of the ray at parameter `t` (its z for a ray along Z, else its x).
    pub fn point(&self, t: f64) -> Xz {
        self.line.point(t)
    }

    /// The intervals of the part's material on the ray, in order along it (in front of a
    /// part-off cut).
    pub fn material(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        let from = match self.separated_at {
            Some(z) if self.line.along_z => z,
            Some(z) if self.line.at < z => f64::INFINITY,
            _ => f64::NEG_INFINITY,
        };
        self.spans.iter().filter(move |s| s.hi.at > from).map(move |s| (s.lo.at.max(from), s.hi.at))
    }
}
