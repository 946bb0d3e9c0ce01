//! The canonical frame of the roughing-cycle property tests (`lap.rs`, `stock_removal.rs`):
//! `u` across the cut, pointing to the start point, `v` along it, the profile running toward
//! smaller `v`. The generated shapes are lines and quarter arcs in that frame.

/// A point of the canonical frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Uv {
    pub u: f64,
    pub v: f64,
}

impl Uv {
    pub fn shifted(self, du: f64, dv: f64) -> Uv {
        Uv { u: self.u + du, v: self.v + dv }
    }

    pub fn distance(self, other: Uv) -> f64 {
        (self.u - other.u).hypot(self.v - other.v)
    }
}

/// One element of a generated shape; arcs are quarter circles, `upper` when the arc lies on
/// the side of its centre toward larger `u`.
#[derive(Debug, Clone, Copy)]
pub struct Element {
    pub start: Uv,
    pub end: Uv,
    pub arc: Option<(Uv, bool)>,
}

impl Element {
    pub fn line(start: Uv, end: Uv) -> Element {
        Element { start, end, arc: None }
    }

    pub fn shifted(&self, du: f64, dv: f64) -> Element {
        Element {
            start: self.start.shifted(du, dv),
            end: self.end.shifted(du, dv),
            arc: self.arc.map(|(c, upper)| (c.shifted(du, dv), upper)),
        }
    }

    /// The shape's `u` at `v` on this element (the top of a wall), if `v` is in its span.
    pub fn u_at(&self, v: f64) -> Option<f64> {
        let (lo, hi) = (self.start.v.min(self.end.v), self.start.v.max(self.end.v));
        if v < lo - 1e-12 || v > hi + 1e-12 {
            return None;
        }
        match self.arc {
            None if (hi - lo) < 1e-12 => Some(self.start.u.max(self.end.u)),
            None => Some(self.start.u + (self.end.u - self.start.u) * (v - self.start.v) / (self.end.v - self.start.v)),
            Some((c, upper)) => {
                let r = self.start.distance(c);
                let d = (r * r - (v - c.v).powi(2)).max(0.0).sqrt();
                Some(if upper { c.u + d } else { c.u - d })
            }
        }
    }

    /// How far `p` lies from the element.
    pub fn distance(&self, p: Uv) -> f64 {
        match self.arc {
            None => {
                let (du, dv) = (self.end.u - self.start.u, self.end.v - self.start.v);
                let t = (((p.u - self.start.u) * du + (p.v - self.start.v) * dv) / (du * du + dv * dv)).clamp(0.0, 1.0);
                p.distance(Uv { u: self.start.u + du * t, v: self.start.v + dv * t })
            }
            // A quarter arc: the point's direction from the centre lies between the directions
            // of its ends (on the same side of each as the other end, and toward the arc).
            Some((c, _)) => {
                let (s, e, q) = (
                    (self.start.u - c.u, self.start.v - c.v),
                    (self.end.u - c.u, self.end.v - c.v),
                    (p.u - c.u, p.v - c.v),
                );
                let cross = |a: (f64, f64), b: (f64, f64)| a.0 * b.1 - a.1 * b.0;
                let within = cross(s, q) * cross(s, e) >= 0.0
                    && cross(q, e) * cross(s, e) >= 0.0
                    && (q.0 * (s.0 + e.0) + q.1 * (s.1 + e.1)) > 0.0;
                if within {
                    (p.distance(c) - self.start.distance(c)).abs()
                } else {
                    p.distance(self.start).min(p.distance(self.end))
                }
            }
        }
    }
}
