//! Where a line of the half-section crosses the region a tool sweeps, exactly.
//!
//! Every shape the part model cuts with is one of two: a convex polygon grown by a disk
//! (`Rounded`: a round nose alone is a point grown by its radius; a nose on its insert, a
//! grooving insert, a threading V and a drill are polygons grown by the nose radius, and a
//! line move sweeps the hull of the polygon at its two ends), or such a polygon moved along
//! an arc (`BodyAlongArc`: the polygon at the arc's ends, each vertex's disk along the arc
//! (an annular sector between `R − r` and `R + r`) and each offset edge along the arc). A
//! line crosses a convex region in one interval; an arc's sweep in a few.
//! Each end of an interval is computed in f64 from the shape's own equations and carries the
//! sweep's outward normal there, so the surface a cut leaves is known at that point to the
//! rounding of one square root, and which piece of the sweep (a side, a disk, an arc) made
//! it is the direction of that normal.

use smallvec::SmallVec;

use crate::geometry::Sector;
use crate::toolpath::Xz;

/// A ray of the dexel grid: the line `x = at` (a ray along Z, parameter z) or `z = at` (a
/// ray along X, parameter x).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Line {
    pub along_z: bool,
    pub at: f64,
}

impl Line {
    /// The coordinate the line holds fixed, of `p`.
    fn fixed(self, p: Xz) -> f64 {
        if self.along_z { p.x } else { p.z }
    }

    /// The line's parameter at `p` (its z for a ray along Z).
    pub fn param(self, p: Xz) -> f64 {
        if self.along_z { p.z } else { p.x }
    }

    pub fn point(self, t: f64) -> Xz {
        if self.along_z { Xz::new(self.at, t) } else { Xz::new(t, self.at) }
    }

    /// Where the line crosses the circle about `centre` of radius `radius`: the two
    /// parameters, lower first.
    fn circle(self, centre: Xz, radius: f64) -> Option<(f64, f64)> {
        let d = self.at - self.fixed(centre);
        let w2 = radius * radius - d * d;
        if w2 < 0.0 {
            return None;
        }
        let w = w2.sqrt();
        let mid = self.param(centre);
        Some((mid - w, mid + w))
    }

    /// Where the line crosses the segment from `a` to `b` (both ends' parameters when the
    /// segment lies on the line).
    fn segment(self, a: Xz, b: Xz) -> SmallVec<[f64; 2]> {
        let (fa, fb) = (self.fixed(a) - self.at, self.fixed(b) - self.at);
        let mut out = SmallVec::new();
        if (fa > 0.0 && fb > 0.0) || (fa < 0.0 && fb < 0.0) {
            return out;
        }
        if fa == fb {
            out.push(self.param(a));
            out.push(self.param(b));
            return out;
        }
        let s = fa / (fa - fb);
        out.push(self.param(a) + s * (self.param(b) - self.param(a)));
        out
    }
}

/// One end of the interval a line spends inside a sweep: its parameter and the sweep's
/// outward unit normal there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Hit {
    pub t: f64,
    pub normal: Xz,
}

/// The intervals a line spends inside a sweep, in order, disjoint.
pub(crate) type Crossing = SmallVec<[(Hit, Hit); 3]>;

/// A region a tool sweeps (see the module documentation).
#[derive(Debug, Clone)]
pub(crate) enum Sweep {
    /// The convex polygon `points` (in order round it, or one or two points) grown by a
    /// disk of `radius`.
    Rounded { points: SmallVec<[Xz; 8]>, radius: f64 },
    /// A rounded convex polygon moved along an arc: an insert (its nose and the body behind
    /// it) on an arc move (`BodyAlongArc`).
    BodyAlongArc(Box<BodyAlongArc>),
}

/// A rounded convex polygon (`core` about the nose centre, grown by the nose `radius`) whose
/// nose centre moves along the arc from `start` to `end` about `centre`. The polygon only
/// moves (it does not turn), so a point it passes over either lies in the polygon at the
/// end or leaves it on the way through its trailing boundary, where the outward normal is
/// against the direction of travel. The region it sweeps is therefore the union of the
/// polygon at the arc's end, each vertex's disk moved along the arc (its disk at the arc's
/// start and an annular sector about the centre moved by the vertex; the polygon at the end
/// holds its disk there) and each offset edge moved along the arc, of those
/// vertices and edges that trail somewhere on the arc: an edge that leads all the way (on
/// a piece of an arc, about a quarter of an insert's) and a vertex between two such add
/// nothing. A line crosses an edge moved along an arc
/// where the edge at angle `θ` crosses it, at a parameter `t(θ)` that is a sinusoid in `θ`,
/// over the angles where the crossing lies on the edge (`edge_along_arc`): its extremes are
/// at the arc's ends, where the crossing reaches an end of the edge, or where the arc runs
/// parallel to the edge, all in closed form. So the sweep is exact, as a nose's own is.
#[derive(Debug, Clone)]
pub(crate) struct BodyAlongArc {
    /// The nose radius the polygon is grown by.
    radius: f64,
    /// Where the nose centre starts, and the arc's centre.
    start: Xz,
    centre: Xz,
    arc_radius: f64,
    /// The angles the nose centre passes (`geometry::angle`), lower first, and their
    /// directions `u(θ) = (sin θ, cos θ)`.
    angles: (f64, f64),
    angle_directions: (Xz, Xz),
    /// The box of the nose centre's path (its ends and the arc's extremes).
    path: (Xz, Xz),
    /// The box of the polygon about the nose centre.
    core_box: (Xz, Xz),
    /// The range of `u(θ)`'s x and of its z over the arc (the fixed coordinate for the rays
    /// along Z and along X), widened by a rounding: where a ray's `v` lies outside it, no
    /// angle of the arc puts the crossing there (`BodyAlongArc::roots`).
    u_range: [(f64, f64); 2],
    /// The polygon at the arc's end.
    end: SmallVec<[Xz; 8]>,
    /// A convex polygon that holds the whole sweep (grown by the nose radius), on an arc of
    /// at most a quarter turn: the polygon placed at the arc's ends and where its end
    /// tangents meet, since the arc lies in that triangle. A ray whose material lies
    /// outside it is not crossed exactly.
    bound: Option<SmallVec<[Xz; 8]>>,
    /// Each trailing vertex about the nose centre, and its disk's sector (the nose centre's,
    /// moved by the vertex).
    vertices: SmallVec<[(Xz, Sector); 4]>,
    /// The trailing edges.
    edges: SmallVec<[ArcEdge; 4]>,
}

/// A tool's cutting shape as the sweeps take it: a convex polygon about the nose centre
/// (counter-clockwise) grown by the nose radius, with its box and each offset edge's facts
/// for a sweep along an arc, made once per tool (each arc move's sweep reads them).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Insert {
    core: SmallVec<[Xz; 8]>,
    radius: f64,
    core_box: (Xz, Xz),
    /// Edge `i` runs from vertex `i` to the next.
    edges: SmallVec<[ArcEdge; 4]>,
}

impl Insert {
    /// The hull of `core` grown by `radius`.
    pub fn new(core: impl IntoIterator<Item = Xz>, radius: f64) -> Insert {
        let core = convex_hull(core.into_iter().collect());
        let (mut core_lo, mut core_hi) = (Xz::new(0.0, 0.0), Xz::new(0.0, 0.0));
        for p in &core {
            core_lo = Xz::new(core_lo.x.min(p.x), core_lo.z.min(p.z));
            core_hi = Xz::new(core_hi.x.max(p.x), core_hi.z.max(p.z));
        }
        let n = core.len();
        let mut edges = SmallVec::new();
        for i in 0..if n >= 2 { n } else { 0 } {
            let (a, b) = (core[i], core[(i + 1) % n]);
            let d = unit(Xz::new(b.x - a.x, b.z - a.z));
            let normal = Xz::new(d.z, -d.x);
            let offset = |p: Xz| Xz::new(p.x + normal.x * radius, p.z + normal.z * radius);
            let edge = Xz::new(b.x - a.x, b.z - a.z);
            let turns = [true, false].map(|along_z| {
                let (fixed, along) = axes(along_z);
                let (df, dg) = (dot(edge, fixed), dot(edge, along));
                // t(θ) = t0 + R u(θ)·w turns where u is along w.
                (df != 0.0).then(|| {
                    let w = Xz::new(along.x - fixed.x * dg / df, along.z - fixed.z * dg / df);
                    (w.x.atan2(w.z), unit(w))
                })
            });
            edges.push(ArcEdge { a: offset(a), b: offset(b), normal, turns });
        }
        Insert { core, radius, core_box: (core_lo, core_hi), edges }
    }
}

/// An offset edge of a [`BodyAlongArc`]'s polygon, about the nose centre.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ArcEdge {
    a: Xz,
    b: Xz,
    /// Its outward normal.
    normal: Xz,
    /// For the rays along Z and along X: the angle `θ` where `t(θ)` turns (mod π) and its
    /// direction `u(θ)`; none where the edge runs along the rays.
    turns: [Option<(f64, Xz)>; 2],
}

/// The unit vectors of a family's rays: the coordinate a ray holds fixed, and its parameter.
fn axes(along_z: bool) -> (Xz, Xz) {
    if along_z { (Xz::new(1.0, 0.0), Xz::new(0.0, 1.0)) } else { (Xz::new(0.0, 1.0), Xz::new(1.0, 0.0)) }
}

fn dot(p: Xz, q: Xz) -> f64 {
    p.x * q.x + p.z * q.z
}

fn unit(v: Xz) -> Xz {
    let n = (v.x * v.x + v.z * v.z).sqrt();
    if n > 0.0 { Xz::new(v.x / n, v.z / n) } else { Xz::new(0.0, 0.0) }
}

impl Sweep {
    /// The hull of `points` grown by `radius`: the sweep of a rounded convex shape along a
    /// line is the hull of the shape at both ends.
    pub fn rounded(points: impl IntoIterator<Item = Xz>, radius: f64) -> Sweep {
        Sweep::Rounded { points: convex_hull(points.into_iter().collect()), radius }
    }

    /// A disk of `radius` moved along the arc from `start` to `end` about `centre`.
    #[cfg(test)]
    pub fn arc(start: Xz, end: Xz, centre: Xz, ccw: bool, radius: f64) -> Sweep {
        let insert = Insert::new([Xz::new(0.0, 0.0)], radius);
        Sweep::body_along_arc(&insert, (start, end, centre), ccw, crate::geometry::turn(start, end, centre, ccw))
    }

    /// `insert` (a rounded convex polygon about the nose centre), its nose centre moved
    /// along the arc from `start` to `end` about `centre` ([`BodyAlongArc`]); `turn` is the
    /// arc's start angle and the angle it turns through (`geometry::angle`,
    /// `geometry::turn`), which the caller has measured for its own box.
    pub fn body_along_arc(
        insert: &Insert,
        (start, end, centre): (Xz, Xz, Xz),
        ccw: bool,
        (a0, total): (f64, f64),
    ) -> Sweep {
        let (core, radius) = (&insert.core, insert.radius);
        let a1 = if ccw { a0 + total } else { a0 - total };
        let moved = |p: Xz, v: Xz| Xz::new(p.x + v.x, p.z + v.z);
        // Whether the boundary with outward normal `n` leads all the way: the direction of
        // travel at angle θ is ±(cos θ, −sin θ) (θ grows counter-clockwise), so `n·v` is a
        // sinusoid in θ, positive over at most half a turn; on an arc shorter than that it
        // is positive throughout where it is at both ends.
        let travel = if ccw { 1.0 } else { -1.0 };
        let (c0, s0, c1, s1) = (a0.cos(), a0.sin(), a1.cos(), a1.sin());
        let short = total < std::f64::consts::PI - 1e-9;
        let leads = |n: Xz| short && travel * (n.x * c0 - n.z * s0) > 1e-12 && travel * (n.x * c1 - n.z * s1) > 1e-12;
        let n = core.len();
        let leading: SmallVec<[bool; 8]> = insert.edges.iter().map(|edge| leads(edge.normal)).collect();
        let vertices = (0..n)
            // A vertex's disk spans the normals between its two edges'.
            .filter(|&i| n < 2 || !(leading[(i + n - 1) % n] && leading[i]))
            .map(|i| {
                let v = core[i];
                (v, Sector::with_angles(moved(start, v), moved(end, v), moved(centre, v), ccw, a0, total))
            })
            .collect();
        let mut lo = Xz::new(start.x.min(end.x), start.z.min(end.z));
        let mut hi = Xz::new(start.x.max(end.x), start.z.max(end.z));
        for p in crate::geometry::arc_extremes_from(centre, start.distance(centre), a0, total, ccw) {
            lo = Xz::new(lo.x.min(p.x), lo.z.min(p.z));
            hi = Xz::new(hi.x.max(p.x), hi.z.max(p.z));
        }
        let edges = insert.edges.iter().zip(&leading).filter(|(_, leads)| !**leads).map(|(edge, _)| *edge).collect();
        let (low, high) = (a0.min(a1), a0.max(a1));
        // The range of sin θ (x) and cos θ (z) over the arc: their values at its ends, and
        // ±1 where it passes the angle of that extreme.
        let passes = |at: f64| {
            let tau = std::f64::consts::TAU;
            crate::geometry::ceil((low - at) / tau) <= crate::geometry::floor((high - at) / tau)
        };
        let half_pi = std::f64::consts::FRAC_PI_2;
        let range = |a: f64, b: f64, top: f64, bottom: f64| {
            let (mut lo, mut hi) = (a.min(b), a.max(b));
            if passes(top) {
                hi = 1.0;
            }
            if passes(bottom) {
                lo = -1.0;
            }
            (lo - 1e-9, hi + 1e-9)
        };
        let u_range =
            [range(low.sin(), high.sin(), half_pi, -half_pi), range(low.cos(), high.cos(), 0.0, std::f64::consts::PI)];
        let bound = (total <= std::f64::consts::FRAC_PI_2).then(|| {
            let middle = if ccw { a0 + total / 2.0 } else { a0 - total / 2.0 };
            let apex = crate::geometry::on_circle(centre, start.distance(centre) / (total / 2.0).cos(), middle);
            let mut points: SmallVec<[Xz; 8]> = SmallVec::new();
            for at in [start, end, apex] {
                points.extend(core.iter().map(|&v| moved(at, v)));
            }
            convex_hull(points)
        });
        Sweep::BodyAlongArc(Box::new(BodyAlongArc {
            radius,
            start,
            centre,
            arc_radius: start.distance(centre),
            angles: (low, high),
            angle_directions: (Xz::new(low.sin(), low.cos()), Xz::new(high.sin(), high.cos())),
            path: (lo, hi),
            core_box: insert.core_box,
            u_range,
            bound,
            end: core.iter().map(|&v| moved(end, v)).collect(),
            vertices,
            edges,
        }))
    }

    /// The box that holds the sweep: lowest x and z, highest x and z.
    pub fn bounds(&self) -> (Xz, Xz) {
        match self {
            Sweep::Rounded { points, radius } => {
                let (mut lo, mut hi) =
                    (Xz::new(f64::INFINITY, f64::INFINITY), Xz::new(f64::NEG_INFINITY, f64::NEG_INFINITY));
                for p in points {
                    lo = Xz::new(lo.x.min(p.x), lo.z.min(p.z));
                    hi = Xz::new(hi.x.max(p.x), hi.z.max(p.z));
                }
                (Xz::new(lo.x - radius, lo.z - radius), Xz::new(hi.x + radius, hi.z + radius))
            }
            Sweep::BodyAlongArc(body) => {
                let (core_lo, core_hi) = body.core_box;
                let (r, (lo, hi)) = (body.radius, body.path);
                (
                    Xz::new(lo.x + core_lo.x - r, lo.z + core_lo.z - r),
                    Xz::new(hi.x + core_hi.x + r, hi.z + core_hi.z + r),
                )
            }
        }
    }

    /// Where `line` is inside the sweep, each piece crossed in turn: the plain reference the
    /// tests hold [`Sweep::prepare`]'s chains to.
    #[cfg(test)]
    pub fn cross(&self, line: Line) -> Crossing {
        let mut out = Crossing::new();
        match self {
            Sweep::Rounded { points, radius } => {
                if let Some(interval) = rounded_polygon(line, points, *radius) {
                    out.push(interval);
                }
            }
            Sweep::BodyAlongArc(body) => out = body.cross(line),
        }
        out
    }
}

impl BodyAlongArc {
    /// Whether `line` may meet what a piece spanning `from..=to` about the nose centre
    /// (across the line) sweeps.
    fn reaches(&self, line: Line, from: f64, to: f64) -> bool {
        let (lo, hi) = self.path;
        let (path_lo, path_hi) = if line.along_z { (lo.x, hi.x) } else { (lo.z, hi.z) };
        line.at >= path_lo + from && line.at <= path_hi + to
    }

    /// Where `line` is inside the sweep (see [`BodyAlongArc`]), its end polygons crossed
    /// piece by piece (the tests' reference).
    #[cfg(test)]
    fn cross(&self, line: Line) -> Crossing {
        let mut out = Crossing::new();
        self.cross_with_end(line, rounded_polygon(line, &self.end, self.radius), &mut out);
        out
    }

    /// [`BodyAlongArc::cross`] with where `line` crosses the polygon at the end given.
    fn cross_with_end(&self, line: Line, end: Option<(Hit, Hit)>, out: &mut Crossing) {
        let r = self.radius;
        let fixed = |p: Xz| if line.along_z { p.x } else { p.z };
        let mut pieces: SmallVec<[(Hit, Hit); 12]> = SmallVec::new();
        pieces.extend(end);
        if r > 0.0 {
            for (v, sector) in &self.vertices {
                if self.reaches(line, fixed(*v) - r, fixed(*v) + r) {
                    pieces.extend(disk_hits(line, Xz::new(self.start.x + v.x, self.start.z + v.z), r));
                    let centre = Xz::new(self.centre.x + v.x, self.centre.z + v.z);
                    let mut ring: SmallVec<[(Hit, Hit); 6]> = SmallVec::new();
                    annular_sector(line, centre, self.arc_radius, r, sector, &mut ring);
                    pieces.extend(ring);
                }
            }
        }
        for edge in &self.edges {
            let (fa, fb) = (fixed(edge.a), fixed(edge.b));
            if self.reaches(line, fa.min(fb), fa.max(fb)) {
                self.edge_along_arc(line, edge, &mut pieces);
            }
        }
        pieces.sort_by(|a, b| a.0.t.total_cmp(&b.0.t));
        out.clear();
        for piece in pieces {
            match out.last_mut() {
                Some(last) if piece.0.t <= last.1.t + MERGE => {
                    if piece.1.t > last.1.t {
                        last.1 = piece.1;
                    }
                }
                _ => out.push(piece),
            }
        }
    }

    /// [`roots`] over the arc's angles, none without solving where `v` is out of the range
    /// the arc gives `u`'s fixed coordinate (most rays of a short arc).
    fn roots(&self, along_z: bool, v: f64) -> SmallVec<[(f64, Xz); 4]> {
        let (lo, hi) = self.u_range[usize::from(!along_z)];
        if v < lo || v > hi {
            return SmallVec::new();
        }
        roots(along_z, v, self.angles.0, self.angles.1)
    }

    /// Where `line` crosses `edge` moved along the arc, pushed onto `out`. With the nose
    /// centre at `centre + R·u(θ)`, `u(θ) = (sin θ, cos θ)`, the edge crosses the line at a
    /// fraction `s(θ)` along it and at a parameter `t(θ)` along the line, both affine in
    /// `u(θ)`; the crossing is on the edge where `0 ≤ s ≤ 1`. Between the angles where `s`
    /// reaches 0 or 1 or `t` turns (`u ∥ w`, every half turn), the crossing is wholly on
    /// the edge or off it and `t` is monotonic, so each stretch on the edge covers the
    /// interval between its marks' least and greatest `t`. The marks are at most half a turn
    /// apart, so the direction midway between two is their directions' sum, normalised.
    fn edge_along_arc(&self, line: Line, edge: &ArcEdge, out: &mut SmallVec<[(Hit, Hit); 12]>) {
        let (fixed, along) = axes(line.along_z);
        let r = self.arc_radius;
        let (lo, hi) = self.angles;
        let normal = edge.normal;
        // The edge's start when the nose centre is at the arc's centre.
        let base = Xz::new(self.centre.x + edge.a.x, self.centre.z + edge.a.z);
        let vector = Xz::new(edge.b.x - edge.a.x, edge.b.z - edge.a.z);
        let (df, dg) = (dot(vector, fixed), dot(vector, along));
        // An end where the crossing reaches an end of the edge: a vertex's path, whose disk
        // has the edge's normal there; a corner of a polygon without a nose traces an arc,
        // whose normal there is radial.
        let end_normal = |u: Xz, low: bool| {
            if self.radius > 0.0 {
                return normal;
            }
            if (dot(u, along) > 0.0) == low { Xz::new(-u.x, -u.z) } else { u }
        };
        let Some((turn, turn_direction)) = edge.turns[usize::from(!line.along_z)] else {
            // The edge runs along the line: it lies on it where its fixed coordinate does.
            let v = (line.at - dot(base, fixed)) / r;
            for (_, u) in self.roots(line.along_z, v) {
                let p = Xz::new(base.x + r * u.x, base.z + r * u.z);
                let (t0, t1) = (dot(p, along), dot(p, along) + dg);
                if t0 != t1 {
                    let (t0, t1) = (t0.min(t1), t0.max(t1));
                    out.push((Hit { t: t0, normal: end_normal(u, true) }, Hit { t: t1, normal: end_normal(u, false) }));
                }
            }
            return;
        };
        // s(θ) = s0 − R u(θ)·fixed / df;  t(θ) = t0 + R u(θ)·w.
        let s0 = (line.at - dot(base, fixed)) / df;
        let t0 = dot(base, along) + s0 * dg;
        let w = Xz::new(along.x - fixed.x * dg / df, along.z - fixed.z * dg / df);
        let s = |u: Xz| s0 - r * dot(u, fixed) / df;
        let t = |u: Xz| t0 + r * dot(u, w);
        // The marks: angle, direction, and whether the crossing is at an end of the edge.
        let mut marks: SmallVec<[(f64, Xz, bool); 12]> = SmallVec::new();
        marks.push((lo, self.angle_directions.0, false));
        marks.push((hi, self.angle_directions.1, false));
        for k in [0.0, 1.0] {
            let v = (line.at - dot(base, fixed) - k * df) / r;
            marks.extend(self.roots(line.along_z, v).into_iter().map(|(theta, u)| (theta, u, true)));
        }
        let half = std::f64::consts::PI;
        let (first, last) = (crate::geometry::ceil((lo - turn) / half), crate::geometry::floor((hi - turn) / half));
        if first.is_finite() && last.is_finite() && last >= first && last - first < 4.0 {
            for k in first as i64..=last as i64 {
                let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
                marks.push((turn + k as f64 * half, Xz::new(sign * turn_direction.x, sign * turn_direction.z), false));
            }
        }
        marks.sort_by(|p, q| p.0.total_cmp(&q.0));
        let midway = |(a, ua): (f64, Xz), (b, ub): (f64, Xz)| {
            let sum = Xz::new(ua.x + ub.x, ua.z + ub.z);
            let length = (sum.x * sum.x + sum.z * sum.z).sqrt();
            if length > 1e-3 {
                Xz::new(sum.x / length, sum.z / length)
            } else {
                let m = 0.5 * (a + b);
                Xz::new(m.sin(), m.cos())
            }
        };
        // An end is the sweep's only where the edge faces out along the line there (else
        // the polygon reaches past it); a segment (no nose) is both its edges.
        let (facing_low, facing_high) = if dot(normal, along) <= 0.0 {
            (normal, Xz::new(-normal.x, -normal.z))
        } else {
            (Xz::new(-normal.x, -normal.z), normal)
        };
        let take = |(u, at_end): (Xz, bool), stretch: &mut Option<(Hit, Hit)>| {
            let value = t(u);
            let (low, high) =
                if at_end { (end_normal(u, true), end_normal(u, false)) } else { (facing_low, facing_high) };
            match stretch {
                None => *stretch = Some((Hit { t: value, normal: low }, Hit { t: value, normal: high })),
                Some((first, last)) => {
                    if value < first.t {
                        *first = Hit { t: value, normal: low };
                    }
                    if value > last.t {
                        *last = Hit { t: value, normal: high };
                    }
                }
            }
        };
        let mut stretch: Option<(Hit, Hit)> = None;
        for pair in marks.windows(2) {
            let ((from, from_u, from_end), (to, to_u, to_end)) = (pair[0], pair[1]);
            if to <= from || !(0.0..=1.0).contains(&s(midway((from, from_u), (to, to_u)))) {
                if let Some(done) = stretch.take().filter(|d| d.1.t > d.0.t) {
                    out.push(done);
                }
                continue;
            }
            take((from_u, from_end), &mut stretch);
            take((to_u, to_end), &mut stretch);
        }
        if let Some(done) = stretch.take().filter(|d| d.1.t > d.0.t) {
            out.push(done);
        }
    }
}

/// The angles `θ` from `lo` to `hi`, with their directions `u(θ) = (sin θ, cos θ)`, where
/// the fixed coordinate of `u` (its x for the rays along Z, its z for those along X) is `v`.
fn roots(along_z: bool, v: f64, lo: f64, hi: f64) -> SmallVec<[(f64, Xz); 4]> {
    let mut out = SmallVec::new();
    if !(-1.0..=1.0).contains(&v) {
        return out;
    }
    let other = (1.0 - v * v).max(0.0).sqrt();
    let pair = if along_z {
        // sin θ = v: θ = asin v (cos ≥ 0) or π − asin v (cos ≤ 0).
        let a = v.asin();
        [(a, Xz::new(v, other)), (std::f64::consts::PI - a, Xz::new(v, -other))]
    } else {
        // cos θ = v: θ = acos v (sin ≥ 0) or −acos v (sin ≤ 0).
        let a = v.acos();
        [(a, Xz::new(other, v)), (-a, Xz::new(-other, v))]
    };
    let tau = std::f64::consts::TAU;
    for (root, u) in pair {
        let (first, last) = (crate::geometry::ceil((lo - root) / tau), crate::geometry::floor((hi - root) / tau));
        if !(first.is_finite() && last.is_finite()) || last < first || last - first > 2.0 {
            continue;
        }
        for k in first as i64..=last as i64 {
            out.push((root + k as f64 * tau, u));
        }
    }
    out
}

/// A sweep made ready for the parallel rays of one family: a rounded polygon's boundary cut
/// into its lower and upper chains along the rays (each piece an offset edge or a quarter of
/// a vertex's disk, with the range of lines it spans), so that each ray finds its two ends
/// by a short scan and one square root, not by crossing every piece.
// The chains live on the stack: a sweep is prepared once per family of each move.
#[allow(clippy::large_enum_variant)]
pub(crate) enum Prepared<'s> {
    Chains(Chains),
    /// An insert along an arc, the polygon at its end and its bound prepared (every ray
    /// that meets the sweep asks them).
    Arc {
        body: &'s BodyAlongArc,
        end: Chains,
        bound: Option<Chains>,
    },
}

/// A rounded convex polygon's boundary as its lower and upper chains along the rays of one
/// family.
pub(crate) struct Chains {
    along_z: bool,
    lower: SmallVec<[Piece; 12]>,
    upper: SmallVec<[Piece; 12]>,
}

/// One piece of a chain: the lines `from..=to` cross it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Piece {
    from: f64,
    to: f64,
    shape: PieceShape,
}

#[derive(Debug, Clone, Copy)]
enum PieceShape {
    /// An offset edge: the parameter at `from` and its rate along the lines, and its normal.
    Edge { at: f64, rate: f64, normal: Xz },
    /// A vertex's disk: its centre (fixed coordinate, parameter), radius, and whether the
    /// piece is the disk's low side along the lines.
    Disk { fixed: f64, param: f64, radius: f64, low: bool },
}

impl Piece {
    fn hit(&self, along_z: bool, at: f64) -> Hit {
        match self.shape {
            PieceShape::Edge { at: start, rate, normal } => Hit { t: start + (at - self.from) * rate, normal },
            PieceShape::Disk { fixed, param, radius, low } => {
                let d = at - fixed;
                let w = (radius * radius - d * d).max(0.0).sqrt();
                let (t, along) = if low { (param - w, -w) } else { (param + w, w) };
                let (nf, ng) = (d / radius, along / radius);
                Hit { t, normal: if along_z { Xz::new(nf, ng) } else { Xz::new(ng, nf) } }
            }
        }
    }
}

impl Sweep {
    /// This sweep ready for the rays of one family.
    pub fn prepare(&self, along_z: bool) -> Prepared<'_> {
        match self {
            Sweep::Rounded { points, radius } => Prepared::Chains(Chains::new(points, *radius, along_z)),
            Sweep::BodyAlongArc(body) => Prepared::Arc {
                body,
                end: Chains::new(&body.end, body.radius, along_z),
                bound: body.bound.as_ref().map(|points| Chains::new(points, body.radius + 1e-9, along_z)),
            },
        }
    }
}

impl Chains {
    /// The lower and upper chains of the convex polygon `points` grown by `radius`, for the
    /// rays of one family.
    fn new(points: &[Xz], radius: f64, along_z: bool) -> Chains {
        let (r, n) = (radius, points.len());
        // (fixed, param) of a point, and of a vector.
        let fg = |p: Xz| if along_z { (p.x, p.z) } else { (p.z, p.x) };
        let mut lower = SmallVec::new();
        let mut upper = SmallVec::new();
        let mut normals: SmallVec<[Xz; 8]> = SmallVec::new();
        let edges = if n >= 2 { n } else { 0 };
        for i in 0..edges {
            let (a, b) = (points[i], points[(i + 1) % n]);
            let d = unit(Xz::new(b.x - a.x, b.z - a.z));
            let normal = Xz::new(d.z, -d.x);
            normals.push(normal);
            let (fa, ga) = fg(Xz::new(a.x + normal.x * r, a.z + normal.z * r));
            let (fb, gb) = fg(Xz::new(b.x + normal.x * r, b.z + normal.z * r));
            let (_, ng) = fg(normal);
            if (fb - fa).abs() < 1e-15 || ng.abs() < 1e-15 {
                continue;
            }
            let (from, to, at) = if fa < fb { (fa, fb, ga) } else { (fb, fa, gb) };
            let piece = Piece { from, to, shape: PieceShape::Edge { at, rate: (gb - ga) / (fb - fa), normal } };
            if ng < 0.0 { lower.push(piece) } else { upper.push(piece) }
        }
        if r > 0.0 {
            let cross = |a: Xz, b: Xz| a.x * b.z - a.z * b.x;
            for i in 0..n {
                // The normals this vertex's disk spans: from the edge into it to the edge out.
                let (into, out) = if n >= 2 {
                    (normals[(i + n - 1) % n], normals[i])
                } else {
                    (Xz::new(0.0, 0.0), Xz::new(0.0, 0.0))
                };
                let within = |u: Xz| {
                    if n < 2 {
                        true
                    } else if n == 2 {
                        cross(into, u) >= -1e-15
                    } else {
                        cross(into, u) >= -1e-15 && cross(u, out) >= -1e-15
                    }
                };
                let (fv, gv) = fg(points[i]);
                for low in [true, false] {
                    let sign = if low { -1.0 } else { 1.0 };
                    // The ends of the part of the disk's arc on this side: directions within
                    // the vertex's span and on the side, those of least and greatest reach.
                    let mut ends: SmallVec<[Xz; 4]> = SmallVec::new();
                    let mut consider = |u: Xz| {
                        let (_, ug) = fg(u);
                        if ug * sign >= -1e-15 && within(u) {
                            ends.push(u);
                        }
                    };
                    if n >= 2 {
                        consider(into);
                        consider(out);
                    }
                    for uf in [-1.0, 1.0] {
                        consider(if along_z { Xz::new(uf, 0.0) } else { Xz::new(0.0, uf) });
                    }
                    let reach = |u: &Xz| fg(*u).0;
                    let (Some(first), Some(last)) = (
                        ends.iter().copied().min_by(|a, b| reach(a).total_cmp(&reach(b))),
                        ends.iter().copied().max_by(|a, b| reach(a).total_cmp(&reach(b))),
                    ) else {
                        continue;
                    };
                    // An arc that only touches the side at its ends has no part on it.
                    let sum = Xz::new(first.x + last.x, first.z + last.z);
                    let pole = if along_z { Xz::new(0.0, sign) } else { Xz::new(sign, 0.0) };
                    let middle = if sum.x.hypot(sum.z) < 1e-9 { pole } else { unit(sum) };
                    if !(within(middle) && fg(middle).1 * sign > 1e-12) {
                        continue;
                    }
                    let (from, to) = (fv + r * reach(&first), fv + r * reach(&last));
                    if to > from {
                        let piece =
                            Piece { from, to, shape: PieceShape::Disk { fixed: fv, param: gv, radius: r, low } };
                        if low { lower.push(piece) } else { upper.push(piece) }
                    }
                }
            }
        }
        Chains { along_z, lower, upper }
    }

    /// Where `line` (of the family prepared for) is inside the polygon.
    fn cross(&self, line: Line) -> Option<(Hit, Hit)> {
        let find = |chain: &[Piece]| chain.iter().find(|p| p.from <= line.at && line.at <= p.to).copied();
        let (lo, hi) = (find(&self.lower)?, find(&self.upper)?);
        let (lo, hi) = (lo.hit(self.along_z, line.at), hi.hit(self.along_z, line.at));
        (hi.t > lo.t).then_some((lo, hi))
    }
}

impl Prepared<'_> {
    /// Where `line` (of the family prepared for) is inside the sweep.
    #[cfg(test)]
    pub fn cross(&self, line: Line) -> Crossing {
        let mut out = Crossing::new();
        self.cross_into(line, &mut out);
        out
    }

    /// Whether `line` crosses the sweep nowhere `within` says there is material: a test
    /// that passes over rays an arc's sweep cannot reach without crossing it exactly (the
    /// bound holds the sweep; it is grown by a rounding, across the rays and along them).
    pub fn misses(&self, line: Line, within: impl Fn(f64, f64) -> bool) -> bool {
        let Prepared::Arc { bound: Some(bound), .. } = self else { return false };
        bound.cross(line).is_none_or(|(lo, hi)| !within(lo.t - 1e-9, hi.t + 1e-9))
    }

    /// [`Prepared::cross`] into `out`, which a caller asking ray after ray keeps.
    pub fn cross_into(&self, line: Line, out: &mut Crossing) {
        match self {
            Prepared::Chains(chains) => {
                out.clear();
                out.extend(chains.cross(line));
            }
            Prepared::Arc { body, end, .. } => body.cross_with_end(line, end.cross(line), out),
        }
    }
}

/// Intervals whose ends lie closer than this (mm) are one: the pieces of one sweep meet
/// exactly on paper, and rounding must not leave a film between them.
const MERGE: f64 = 1e-9;

/// Where `line` is inside the disk about `centre`.
fn disk_hits(line: Line, centre: Xz, radius: f64) -> Option<(Hit, Hit)> {
    if radius <= 0.0 {
        return None;
    }
    let (t0, t1) = line.circle(centre, radius)?;
    let normal = |t: f64| {
        let p = line.point(t);
        unit(Xz::new(p.x - centre.x, p.z - centre.z))
    };
    Some((Hit { t: t0, normal: normal(t0) }, Hit { t: t1, normal: normal(t1) }))
}

/// Where `line` is inside the convex polygon `points` grown by `radius` (one interval: the
/// region is convex, so it is the hull of every crossing of its boundary pieces).
#[cfg(test)]
fn rounded_polygon(line: Line, points: &[Xz], radius: f64) -> Option<(Hit, Hit)> {
    let mut lo: Option<Hit> = None;
    let mut hi: Option<Hit> = None;
    let mut take = |hit: Hit| {
        if lo.is_none_or(|l| hit.t < l.t) {
            lo = Some(hit);
        }
        if hi.is_none_or(|h| hit.t > h.t) {
            hi = Some(hit);
        }
    };
    if radius > 0.0 {
        for &p in points {
            if let Some((a, b)) = disk_hits(line, p, radius) {
                take(a);
                take(b);
            }
        }
    }
    let n = points.len();
    if n >= 2 {
        for i in 0..n {
            let (a, b) = (points[i], points[(i + 1) % n]);
            if n == 2 && i == 1 && radius <= 0.0 {
                break;
            }
            let d = unit(Xz::new(b.x - a.x, b.z - a.z));
            // Outward for a polygon counter-clockwise in (x, z) (`convex_hull`); a segment's
            // two edges face both ways.
            let normal = Xz::new(d.z, -d.x);
            let (a, b) = (
                Xz::new(a.x + normal.x * radius, a.z + normal.z * radius),
                Xz::new(b.x + normal.x * radius, b.z + normal.z * radius),
            );
            for t in line.segment(a, b) {
                take(Hit { t, normal });
            }
        }
    }
    match (lo, hi) {
        (Some(lo), Some(hi)) if hi.t > lo.t => Some((lo, hi)),
        _ => None,
    }
}

/// The pieces of `line` inside the ring between `big − r` and `big + r` about `centre`,
/// within the sector, pushed onto `out`.
fn annular_sector(line: Line, centre: Xz, big: f64, r: f64, sector: &Sector, out: &mut SmallVec<[(Hit, Hit); 6]>) {
    let Some((o0, o1)) = line.circle(centre, big + r) else { return };
    let outer = |t: f64| {
        let p = line.point(t);
        Hit { t, normal: unit(Xz::new(p.x - centre.x, p.z - centre.z)) }
    };
    let inner = |t: f64| {
        let p = line.point(t);
        Hit { t, normal: unit(Xz::new(centre.x - p.x, centre.z - p.z)) }
    };
    let mut ring: SmallVec<[(Hit, Hit); 2]> = SmallVec::new();
    match (big - r > 0.0).then(|| line.circle(centre, big - r)).flatten() {
        Some((i0, i1)) => {
            ring.push((outer(o0), inner(i0)));
            ring.push((inner(i1), outer(o1)));
        }
        None => ring.push((outer(o0), outer(o1))),
    }
    // Where the line crosses the sector's two end rays, out to the ring's outer circle: the
    // pieces between are wholly in or wholly out. Those ends lie on the end disks'
    // diameters, inside the disks, so the union with the disks absorbs them.
    let reach = (big + r) * 2.0 + 1.0;
    let mut cuts: SmallVec<[f64; 4]> = SmallVec::new();
    for end in [sector.start(), sector.end()] {
        let dir = unit(Xz::new(end.x - centre.x, end.z - centre.z));
        let far = Xz::new(centre.x + dir.x * reach, centre.z + dir.z * reach);
        cuts.extend(line.segment(centre, far));
    }
    cuts.sort_by(f64::total_cmp);
    for (lo, hi) in ring {
        if hi.t <= lo.t {
            continue;
        }
        let mut from = lo;
        let mut points: SmallVec<[f64; 6]> = cuts.iter().copied().filter(|&t| t > lo.t && t < hi.t).collect();
        points.push(hi.t);
        for t in points {
            let to = if t == hi.t { hi } else { Hit { t, normal: Xz::new(0.0, 0.0) } };
            let mid = line.point(0.5 * (from.t + to.t));
            if to.t > from.t && sector.contains(mid) {
                out.push((from, to));
            }
            from = Hit { t, normal: Xz::new(0.0, 0.0) };
        }
    }
}

/// The convex hull of `points`, counter-clockwise in (x, z), without repeated or collinear
/// points (Andrew's monotone chain): one point, two, or a polygon.
pub(crate) fn convex_hull(mut points: SmallVec<[Xz; 8]>) -> SmallVec<[Xz; 8]> {
    points.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.z.total_cmp(&b.z)));
    points.dedup_by(|a, b| (a.x - b.x).abs() < 1e-12 && (a.z - b.z).abs() < 1e-12);
    if points.len() < 3 {
        return points;
    }
    let cross = |o: Xz, a: Xz, b: Xz| (a.x - o.x) * (b.z - o.z) - (a.z - o.z) * (b.x - o.x);
    let mut hull: SmallVec<[Xz; 8]> = SmallVec::new();
    let n = points.len();
    for pass in 0..2 {
        let start = hull.len();
        for k in 0..n {
            let p = points[if pass == 0 { k } else { n - 1 - k }];
            while hull.len() >= start + 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 1e-15 {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-12
    }

    #[test]
    fn a_capsule_is_crossed_by_its_sides_and_its_end_disks() {
        // A nose of 1 mm moved from z = 0 to z = -10 at x = 5.
        let sweep = Sweep::rounded([Xz::new(5.0, 0.0), Xz::new(5.0, -10.0)], 1.0);
        let along_x = sweep.cross(Line { along_z: false, at: -4.0 });
        assert_eq!(along_x.len(), 1);
        let (lo, hi) = along_x[0];
        assert!(close(lo.t, 4.0) && close(hi.t, 6.0), "{lo:?} {hi:?}");
        assert!(close(lo.normal.x, -1.0) && close(hi.normal.x, 1.0));
        // Through the end disk: z = 0.6 lies 0.6 beyond the end, so x = 5 ± 0.8.
        let (lo, hi) = sweep.cross(Line { along_z: false, at: 0.6 })[0];
        assert!(close(lo.t, 4.2) && close(hi.t, 5.8), "{lo:?} {hi:?}");
        let (lo, hi) = sweep.cross(Line { along_z: true, at: 5.5 })[0];
        assert!(close(hi.t, 0.75f64.sqrt()) && close(lo.t, -10.0 - 0.75f64.sqrt()));
        assert!(sweep.cross(Line { along_z: true, at: 6.5 }).is_empty());
    }

    #[test]
    fn an_arc_sweep_is_two_pieces_where_the_line_crosses_its_ring_twice() {
        // A quarter arc of radius 10 about the origin from (0, 10) to (10, 0), nose 1.
        let sweep = Sweep::arc(Xz::new(0.0, 10.0), Xz::new(10.0, 0.0), Xz::new(0.0, 0.0), true, 1.0);
        let crossing = sweep.cross(Line { along_z: true, at: 5.0 });
        assert_eq!(crossing.len(), 1, "{crossing:?}");
        let (lo, hi) = crossing[0];
        assert!(close(lo.t, (81.0f64 - 25.0).sqrt()) && close(hi.t, (121.0f64 - 25.0).sqrt()), "{lo:?} {hi:?}");
        // Below the arc's lowest point's ring: a line at x = 0.5 meets the start disk.
        let crossing = sweep.cross(Line { along_z: true, at: 0.5 });
        assert_eq!(crossing.len(), 1);
        // A half circle from (0, 10) over the top to (0, -10): the line x = 5 crosses its ring twice.
        let half = Sweep::arc(Xz::new(0.0, 10.0), Xz::new(0.0, -10.0), Xz::new(0.0, 0.0), true, 1.0);
        let crossing = half.cross(Line { along_z: true, at: 5.0 });
        assert_eq!(crossing.len(), 2, "{crossing:?}");
        assert!(close(crossing[0].1.t, -(56.0f64).sqrt()) && close(crossing[1].0.t, 56.0f64.sqrt()));
    }

    #[test]
    fn prepared_chains_cross_as_the_pieces_do() {
        let shapes = [
            Sweep::rounded([Xz::new(5.0, 0.0), Xz::new(5.0, -10.0)], 1.0),
            Sweep::rounded([Xz::new(5.0, 0.0)], 0.8),
            Sweep::rounded(
                [
                    Xz::new(5.0, 0.0),
                    Xz::new(11.0, 0.0),
                    Xz::new(11.0, 6.0),
                    Xz::new(5.0, 6.0),
                    Xz::new(3.0, -7.0),
                    Xz::new(9.0, -7.0),
                    Xz::new(9.0, -1.0),
                    Xz::new(3.0, -1.0),
                ],
                0.4,
            ),
            Sweep::rounded([Xz::new(5.0, 0.0), Xz::new(8.0, -3.0), Xz::new(8.0, 3.0)], 0.0),
        ];
        for sweep in &shapes {
            for along_z in [true, false] {
                let prepared = sweep.prepare(along_z);
                for k in 0..400 {
                    let line = Line { along_z, at: -12.0 + k as f64 * 0.0617 };
                    let (a, b) = (sweep.cross(line), prepared.cross(line));
                    assert_eq!(a.len(), b.len(), "{sweep:?} {line:?}");
                    for ((a0, a1), (b0, b1)) in a.iter().zip(&b) {
                        assert!((a0.t - b0.t).abs() < 1e-9 && (a1.t - b1.t).abs() < 1e-9, "{line:?} {a:?} {b:?}");
                        for (x, y) in [(a0.normal, b0.normal), (a1.normal, b1.normal)] {
                            assert!((x.x - y.x).abs() < 1e-6 && (x.z - y.z).abs() < 1e-6, "{line:?} {a:?} {b:?}");
                        }
                    }
                }
            }
        }
    }

    /// The distance from `p` to the convex polygon `points` (counter-clockwise) grown by
    /// `radius`: 0 inside.
    fn distance_to_rounded(p: Xz, points: &[Xz], radius: f64) -> f64 {
        let n = points.len();
        let segment = |a: Xz, b: Xz| {
            let (dx, dz) = (b.x - a.x, b.z - a.z);
            let length2 = dx * dx + dz * dz;
            let s = if length2 > 0.0 { (((p.x - a.x) * dx + (p.z - a.z) * dz) / length2).clamp(0.0, 1.0) } else { 0.0 };
            p.distance(Xz::new(a.x + dx * s, a.z + dz * s))
        };
        let inside = n >= 3
            && (0..n).all(|i| {
                let (a, b) = (points[i], points[(i + 1) % n]);
                (b.x - a.x) * (p.z - a.z) - (b.z - a.z) * (p.x - a.x) >= 0.0
            });
        let edge = (0..n).map(|i| segment(points[i], points[(i + 1) % n])).fold(f64::INFINITY, f64::min);
        if inside { 0.0 } else { (edge - radius).max(0.0) }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig { cases: 128, ..Default::default() })]

        /// The exact sweep of an insert along an arc against the insert placed at thousands
        /// of points of the arc: every placement lies inside the sweep, and every point of
        /// the sweep lies within a placement, or as near one as the placements are apart.
        #[test]
        fn a_body_along_an_arc_is_the_union_of_its_placements(
            corner in 0usize..5,
            nose in proptest::sample::select(vec![0.0, 0.4, 0.8]),
            arc_radius in 0.5f64..8.0,
            start_angle in -3.2f64..3.2,
            total in 0.01f64..std::f64::consts::TAU,
            ccw in proptest::bool::ANY,
            along_z in proptest::bool::ANY,
            across in 0.0f64..1.0,
        ) {
            let body = 6.0;
            let core: SmallVec<[Xz; 8]> = match corner {
                4 => SmallVec::from_slice(&[Xz::new(0.0, 0.0), Xz::new(body, 0.0)]),
                k => {
                    let (ax, az) = (if k % 2 == 0 { 1.0 } else { -1.0 }, if k / 2 == 0 { 1.0 } else { -1.0 });
                    SmallVec::from_slice(&[
                        Xz::new(0.0, 0.0),
                        Xz::new(body * ax, 0.0),
                        Xz::new(body * ax, body * az),
                        Xz::new(0.0, body * az),
                    ])
                }
            };
            let centre = Xz::new(3.0, -2.0);
            let sign = if ccw { 1.0 } else { -1.0 };
            let on = |a: f64| crate::geometry::on_circle(centre, arc_radius, a);
            let (start, end) = (on(start_angle), on(start_angle + sign * total));
            let insert = Insert::new(core.iter().copied(), nose);
            let sweep = Sweep::body_along_arc(&insert, (start, end, centre), ccw, crate::geometry::turn(start, end, centre, ccw));
            let hull = convex_hull(core.clone());
            let count = 2000;
            let placements: Vec<SmallVec<[Xz; 8]>> = (0..=count)
                .map(|k| {
                    let c = on(start_angle + sign * total * k as f64 / count as f64);
                    hull.iter().map(|v| Xz::new(c.x + v.x, c.z + v.z)).collect()
                })
                .collect();
            // How far a point of the sweep may be from the nearest placement.
            let apart = arc_radius * total / count as f64 / 2.0 + 1e-9;
            let (lo, hi) = sweep.bounds();
            let (from, to) = if along_z { (lo.x, hi.x) } else { (lo.z, hi.z) };
            let line = Line { along_z, at: from + (to - from) * across };
            let crossing = sweep.cross(line);
            for piece in &crossing {
                proptest::prop_assert!(piece.1.t > piece.0.t, "{crossing:?}");
            }
            let (t_lo, t_hi) = if along_z { (lo.z, hi.z) } else { (lo.x, hi.x) };
            for k in 0..=250 {
                let t = t_lo - 0.5 + (t_hi - t_lo + 1.0) * k as f64 / 250.0;
                let p = line.point(t);
                let nearest = placements.iter().map(|q| distance_to_rounded(p, q, nose)).fold(f64::INFINITY, f64::min);
                let inside = crossing.iter().any(|(a, b)| a.t - 1e-9 <= t && t <= b.t + 1e-9);
                if nearest == 0.0 {
                    proptest::prop_assert!(inside, "{p:?} is under a placement, outside the sweep {crossing:?}");
                }
                if inside {
                    proptest::prop_assert!(nearest <= apart, "{p:?} is {nearest} from every placement");
                }
            }
            // Each end is on the sweep's boundary: its normal faces out along the line.
            for (a, b) in &crossing {
                let direction = if along_z { a.normal.z } else { a.normal.x };
                let direction_b = if along_z { b.normal.z } else { b.normal.x };
                proptest::prop_assert!(direction <= 1e-9 && direction_b >= -1e-9, "{crossing:?}");
            }
        }
    }

    #[test]
    fn a_hull_is_counter_clockwise_and_its_normals_face_out() {
        let hull = convex_hull(SmallVec::from_slice(&[
            Xz::new(0.0, 0.0),
            Xz::new(1.0, 1.0),
            Xz::new(1.0, 0.0),
            Xz::new(0.0, 1.0),
            Xz::new(0.5, 0.5),
        ]));
        assert_eq!(hull.len(), 4);
        let sweep = Sweep::Rounded { points: hull, radius: 0.0 };
        let (lo, hi) = sweep.cross(Line { along_z: true, at: 0.5 })[0];
        assert!(close(lo.t, 0.0) && close(hi.t, 1.0));
        assert!(close(lo.normal.z, -1.0) && close(hi.normal.z, 1.0), "{lo:?} {hi:?}");
    }
}
