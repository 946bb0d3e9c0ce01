//! A canonical frame for the roughing cycles: levels step down in `u`, passes cut toward
//! decreasing `v`. `G71` maps X to `u` and Z to `v`; `G72` swaps them; an inside profile
//! mirrors `u`, a profile running toward +Z mirrors `v`. Lines stay lines; an arc's sense
//! flips once per swap or mirror.

use crate::geometry;
use crate::toolpath::Xz;

use super::super::profile::{Profile, Shape};

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Canon {
    /// `u` is Z and `v` is X (facing) instead of `u` X and `v` Z (turning).
    pub swap: bool,
    pub mirror_u: bool,
    pub mirror_v: bool,
}

/// A point in the canonical frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Uv {
    pub u: f64,
    pub v: f64,
}

impl Canon {
    pub fn to(&self, p: Xz) -> Uv {
        let (u, v) = if self.swap { (p.z, p.x) } else { (p.x, p.z) };
        Uv { u: if self.mirror_u { -u } else { u }, v: if self.mirror_v { -v } else { v } }
    }

    pub fn from(&self, q: Uv) -> Xz {
        let u = if self.mirror_u { -q.u } else { q.u };
        let v = if self.mirror_v { -q.v } else { q.v };
        if self.swap { Xz::new(v, u) } else { Xz::new(u, v) }
    }

    /// Whether arcs change sense between the frames.
    pub fn flips(&self) -> bool {
        self.swap ^ self.mirror_u ^ self.mirror_v
    }
}

/// A profile element in the canonical frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Element {
    pub start: Uv,
    pub end: Uv,
    /// For arcs: centre and sense in the canonical frame (counter-clockwise in (v, u)... the
    /// sense is only carried through, never interpreted here).
    pub arc: Option<(Uv, bool)>,
    /// The block the element comes from, where a problem of the shape is reported.
    pub source: crate::source::Span,
}

impl Uv {
    pub fn distance(self, other: Uv) -> f64 {
        (self.u - other.u).hypot(self.v - other.v)
    }
}

impl Element {
    pub fn radius(&self) -> f64 {
        self.arc.map_or(0.0, |(c, _)| (self.start.u - c.u).hypot(self.start.v - c.v))
    }

    /// Whether `p`, a point on an arc's circle, lies within the arc's sweep (its ends
    /// included, to rounding). The canonical frame is a rigid map, so the angular test of the
    /// toolpath frame works on (u, v) read as (x, z).
    fn sweeps(&self, p: Uv) -> bool {
        let Some((c, ccw)) = self.arc else { return false };
        let as_xz = |q: Uv| Xz::new(q.u, q.v);
        p.distance(self.start) < 1e-9
            || p.distance(self.end) < 1e-9
            || geometry::angle_within(as_xz(p), as_xz(self.start), as_xz(self.end), as_xz(c), ccw)
    }

    /// Whether `p` lies on the element (to a micrometre's thousandth).
    pub fn contains(&self, p: Uv) -> bool {
        const ON: f64 = 1e-7;
        match self.arc {
            None => {
                let (d_u, d_v) = (self.end.u - self.start.u, self.end.v - self.start.v);
                let length2 = d_u * d_u + d_v * d_v;
                if length2 < 1e-24 {
                    return p.distance(self.start) < ON;
                }
                let t = (((p.u - self.start.u) * d_u + (p.v - self.start.v) * d_v) / length2).clamp(0.0, 1.0);
                p.distance(Uv { u: self.start.u + d_u * t, v: self.start.v + d_v * t }) < ON
            }
            Some((c, _)) => (p.distance(c) - self.radius()).abs() < ON && self.sweeps(p),
        }
    }
}

/// The profile, shifted by `offset` (toolpath frame), as canonical elements.
pub fn elements(canon: &Canon, profile: &Profile, offset: Xz, skip_first: bool) -> Vec<Element> {
    let shift = |p: Xz| Xz::new(p.x + offset.x, p.z + offset.z);
    let mut out = Vec::new();
    let mut at = shift(profile.start);
    for (i, segment) in profile.segments.iter().enumerate() {
        let end = shift(segment.end);
        if !(skip_first && i == 0) && at.distance(end) > 1e-12 {
            let arc = match segment.shape {
                Shape::Arc { centre, ccw } => Some((canon.to(shift(centre)), ccw ^ canon.flips())),
                Shape::Line => None,
            };
            out.push(Element { start: canon.to(at), end: canon.to(end), arc, source: segment.source });
        }
        at = end;
    }
    out
}

/// Where the level `u` crosses the elements: the `v` of each crossing.
pub fn crossings(elements: &[Element], u: f64) -> Vec<f64> {
    let mut out = Vec::new();
    for e in elements {
        match e.arc {
            None => {
                let (u0, u1) = (e.start.u, e.end.u);
                if (u0 - u1).abs() < 1e-12 {
                    // A level on a flat (to rounding: levels are A's level less whole depths)
                    // meets it at both ends; without them, a level a hair above a flat would
                    // seem to run along it, and the stretch before it would not be cut.
                    if (u - u0).abs() <= 1e-9 {
                        out.extend([e.start.v, e.end.v]);
                    }
                    continue;
                }
                if u >= u0.min(u1) - 1e-9 && u <= u0.max(u1) + 1e-9 {
                    let t = ((u - u0) / (u1 - u0)).clamp(0.0, 1.0);
                    out.push(e.start.v + (e.end.v - e.start.v) * t);
                }
            }
            Some((c, _)) => {
                let r = e.radius();
                let du = u - c.u;
                // A level that touches the arc (to rounding) meets it there.
                if du.abs() > r + 1e-9 {
                    continue;
                }
                let dv = (r * r - du * du).max(0.0).sqrt();
                for v in [c.v + dv, c.v - dv] {
                    if e.sweeps(Uv { u, v }) {
                        out.push(v);
                    }
                }
            }
        }
    }
    out.sort_by(|a, b| b.total_cmp(a));
    out.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    out
}

/// The profile's `u` at `v` (the profile is a function of `v` for the roughing cycles);
/// beyond its ends, the nearest end's `u`.
pub fn u_at(elements: &[Element], v: f64) -> f64 {
    let (Some(first), Some(last)) = (elements.first(), elements.last()) else { return f64::NEG_INFINITY };
    let (v_hi, v_lo) = (first.start.v.max(last.end.v), first.start.v.min(last.end.v));
    if v >= v_hi {
        return if first.start.v >= last.end.v { first.start.u } else { last.end.u };
    }
    if v <= v_lo {
        return if first.start.v <= last.end.v { first.start.u } else { last.end.u };
    }
    let mut best = f64::NEG_INFINITY;
    for e in elements {
        let (a, b) = (e.start.v.min(e.end.v), e.start.v.max(e.end.v));
        match e.arc {
            None if v >= a - 1e-12 && v <= b + 1e-12 => {
                let u = if (b - a).abs() < 1e-12 {
                    e.start.u.max(e.end.u)
                } else {
                    e.start.u + (e.end.u - e.start.u) * (v - e.start.v) / (e.end.v - e.start.v)
                };
                best = best.max(u);
            }
            Some((c, _)) => {
                let r = e.radius();
                let dv = v - c.v;
                if dv.abs() > r + 1e-9 {
                    continue;
                }
                let du = (r * r - dv * dv).max(0.0).sqrt();
                for u in [c.u + du, c.u - du] {
                    if e.sweeps(Uv { u, v }) {
                        best = best.max(u);
                    }
                }
            }
            _ => {}
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_round_trip_and_flip_arcs() {
        for swap in [false, true] {
            for mirror_u in [false, true] {
                for mirror_v in [false, true] {
                    let canon = Canon { swap, mirror_u, mirror_v };
                    let p = Xz::new(3.0, -7.0);
                    assert_eq!(canon.from(canon.to(p)), p);
                    assert_eq!(canon.flips(), swap ^ mirror_u ^ mirror_v);
                }
            }
        }
    }

    #[test]
    fn a_level_crosses_a_line_and_an_arc() {
        let line = Element {
            start: Uv { u: 0.0, v: 0.0 },
            end: Uv { u: 10.0, v: -10.0 },
            arc: None,
            source: crate::source::Span::SYNTHETIC,
        };
        assert_eq!(crossings(&[line], 4.0), vec![-4.0]);
        assert!((u_at(&[line], -4.0) - 4.0).abs() < 1e-12);
        // A quarter circle about (0, -10) from (0, 0) to (10, -10), counter-clockwise in the
        // (u, v) read as (x, z) sense used by the geometry module.
        let arc = Element {
            start: Uv { u: 0.0, v: 0.0 },
            end: Uv { u: 10.0, v: -10.0 },
            arc: Some((Uv { u: 0.0, v: -10.0 }, true)),
            source: crate::source::Span::SYNTHETIC,
        };
        let v = crossings(&[arc], 6.0);
        assert_eq!(v.len(), 1);
        assert!((v[0] - (-10.0 + 8.0)).abs() < 1e-9);
    }
}
