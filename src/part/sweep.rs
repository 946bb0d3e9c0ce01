//! Where a line of the half-section crosses the region a tool sweeps, exactly.
//!
//! Every shape the part model cuts with is one of two: a convex polygon grown by a disk
//! (`Rounded`: a round nose alone is a point grown by its radius; a nose on its insert, a
//! grooving insert, a threading V and a drill are polygons grown by the nose radius, and a
//! line move sweeps the hull of the polygon at its two ends), or a disk moved along an arc
//! (`ArcNose`: an annular sector between `R − r` and `R + r` closed by the disks at its
//! ends). A line crosses a convex region in one interval; an arc's sweep in at most three.
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
    /// A disk of `radius` (`r`) moved along the arc from `start` to `end` about `centre`.
    ArcNose { start: Xz, end: Xz, centre: Xz, ccw: bool, radius: f64, sector: Sector },
    /// A rounded polygon (`Rounded`) within the wedge of its chord, less the disk of `radius`
    /// about `centre` (`outside`) or within it: the insert's body swept along a chord of an
    /// arc, held to the arc's side of the circle its nose sweeps, so that its surface there
    /// is the circle's, and to the angles the chord spans, so that its rounded ends do not
    /// reach past the nose's disks at the chord's ends (the true sweep there).
    Clipped { inner: Box<Sweep>, centre: Xz, radius: f64, outside: bool, wedge: Wedge },
}

/// The points about `centre` whose direction lies between two angles less than a half turn
/// apart (the angle of a direction is `a` for `(sin a, cos a)`, as `geometry::angle`): those
/// `p` with `(p − centre)·side ≥ 0` for both sides.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Wedge {
    centre: Xz,
    sides: [Xz; 2],
}

impl Wedge {
    /// The wedge about `centre` from angle `from` to angle `to`, either way round.
    pub fn between(centre: Xz, from: f64, to: f64) -> Wedge {
        let (lo, hi) = (from.min(to), from.max(to));
        // d/da (sin a, cos a) = (cos a, −sin a) points toward growing angles.
        Wedge { centre, sides: [Xz::new(lo.cos(), -lo.sin()), Xz::new(-hi.cos(), hi.sin())] }
    }

    /// The part of `piece` of `line` inside the wedge; a new end's normal faces out of it.
    fn clip(&self, line: Line, piece: (Hit, Hit)) -> Option<(Hit, Hit)> {
        let (mut lo, mut hi) = piece;
        let origin = line.point(0.0);
        let direction = if line.along_z { Xz::new(0.0, 1.0) } else { Xz::new(1.0, 0.0) };
        for side in self.sides {
            // Along the line the side's test is `alpha + beta·t ≥ 0`.
            let alpha = (origin.x - self.centre.x) * side.x + (origin.z - self.centre.z) * side.z;
            let beta = direction.x * side.x + direction.z * side.z;
            let normal = Xz::new(-side.x, -side.z);
            if beta == 0.0 {
                if alpha < 0.0 {
                    return None;
                }
            } else if beta > 0.0 {
                let t = -alpha / beta;
                if t > lo.t {
                    lo = Hit { t, normal };
                }
            } else {
                let t = -alpha / beta;
                if t < hi.t {
                    hi = Hit { t, normal };
                }
            }
        }
        (hi.t > lo.t).then_some((lo, hi))
    }
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

    pub fn arc(start: Xz, end: Xz, centre: Xz, ccw: bool, radius: f64) -> Sweep {
        Sweep::ArcNose { start, end, centre, ccw, radius, sector: Sector::new(start, end, centre, ccw) }
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
            Sweep::ArcNose { start, end, centre, ccw, radius, .. } => {
                let mut lo = Xz::new(start.x.min(end.x), start.z.min(end.z));
                let mut hi = Xz::new(start.x.max(end.x), start.z.max(end.z));
                for p in crate::geometry::arc_extremes(*start, *end, *centre, *ccw) {
                    lo = Xz::new(lo.x.min(p.x), lo.z.min(p.z));
                    hi = Xz::new(hi.x.max(p.x), hi.z.max(p.z));
                }
                (Xz::new(lo.x - radius, lo.z - radius), Xz::new(hi.x + radius, hi.z + radius))
            }
            Sweep::Clipped { inner, .. } => inner.bounds(),
        }
    }

    /// Where `line` is inside the sweep.
    pub fn cross(&self, line: Line) -> Crossing {
        let mut out = Crossing::new();
        match self {
            Sweep::Rounded { points, radius } => {
                if let Some(interval) = rounded_polygon(line, points, *radius) {
                    out.push(interval);
                }
            }
            Sweep::ArcNose { start, end, centre, radius, sector, .. } => {
                let mut pieces: SmallVec<[(Hit, Hit); 6]> = SmallVec::new();
                for disk in [*start, *end] {
                    if let Some(piece) = disk_hits(line, disk, *radius) {
                        pieces.push(piece);
                    }
                }
                annular_sector(line, *centre, start.distance(*centre), *radius, sector, &mut pieces);
                pieces.sort_by(|a, b| a.0.t.total_cmp(&b.0.t));
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
            Sweep::Clipped { inner, centre, radius, outside, wedge } => {
                out = clip(line, inner.cross(line), *centre, *radius, *outside, wedge);
            }
        }
        out
    }
}

/// A sweep made ready for the parallel rays of one family: a rounded polygon's boundary cut
/// into its lower and upper chains along the rays (each piece an offset edge or a quarter of
/// a vertex's disk, with the range of lines it spans), so that each ray finds its two ends
/// by a short scan and one square root, not by crossing every piece.
// The chains live on the stack: a sweep is prepared once per family of each move.
#[allow(clippy::large_enum_variant)]
pub(crate) enum Prepared<'s> {
    Chains {
        along_z: bool,
        lower: SmallVec<[Piece; 12]>,
        upper: SmallVec<[Piece; 12]>,
    },
    /// A prepared rounded polygon within a wedge, less or within a disk (`Sweep::Clipped`).
    Clipped {
        inner: Box<Prepared<'s>>,
        centre: Xz,
        radius: f64,
        outside: bool,
        wedge: Wedge,
    },
    General(&'s Sweep),
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
        if let Sweep::Clipped { inner, centre, radius, outside, wedge } = self {
            let inner = Box::new(inner.prepare(along_z));
            return Prepared::Clipped { inner, centre: *centre, radius: *radius, outside: *outside, wedge: *wedge };
        }
        let Sweep::Rounded { points, radius } = self else { return Prepared::General(self) };
        let (r, n) = (*radius, points.len());
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
        Prepared::Chains { along_z, lower, upper }
    }
}

impl Prepared<'_> {
    /// Where `line` (of the family prepared for) is inside the sweep.
    pub fn cross(&self, line: Line) -> Crossing {
        match self {
            Prepared::General(sweep) => sweep.cross(line),
            Prepared::Clipped { inner, centre, radius, outside, wedge } => {
                clip(line, inner.cross(line), *centre, *radius, *outside, wedge)
            }
            Prepared::Chains { along_z, lower, upper } => {
                let mut out = Crossing::new();
                let find = |chain: &[Piece]| chain.iter().find(|p| p.from <= line.at && line.at <= p.to).copied();
                if let (Some(lo), Some(hi)) = (find(lower), find(upper)) {
                    let (lo, hi) = (lo.hit(*along_z, line.at), hi.hit(*along_z, line.at));
                    if hi.t > lo.t {
                        out.push((lo, hi));
                    }
                }
                out
            }
        }
    }
}

/// `pieces` of `line` within `wedge`, less the disk of `radius` about `centre` (`outside`),
/// or within it; a disk of no radius is none.
fn clip(line: Line, pieces: Crossing, centre: Xz, radius: f64, outside: bool, wedge: &Wedge) -> Crossing {
    let mut out = Crossing::new();
    let disk = (radius > 0.0).then(|| line.circle(centre, radius)).flatten();
    let at = |t: f64| {
        let p = line.point(t);
        // The sweep's outward normal on the circle: toward the centre when the disk is left
        // out, away from it when the sweep keeps within it.
        let n = unit(Xz::new(p.x - centre.x, p.z - centre.z));
        Hit { t, normal: if outside { Xz::new(-n.x, -n.z) } else { n } }
    };
    for (lo, hi) in pieces.into_iter().filter_map(|piece| wedge.clip(line, piece)) {
        match (disk, outside) {
            (None, true) => out.push((lo, hi)),
            (None, false) => {}
            (Some((d0, d1)), true) => {
                if d0 > lo.t {
                    out.push((lo, if d0 < hi.t { at(d0) } else { hi }));
                }
                if d1 < hi.t {
                    out.push((if d1 > lo.t { at(d1) } else { lo }, hi));
                }
            }
            (Some((d0, d1)), false) => {
                let from = if d0 > lo.t { at(d0) } else { lo };
                let to = if d1 < hi.t { at(d1) } else { hi };
                out.push((from, to));
            }
        }
    }
    out.retain(|(lo, hi)| hi.t > lo.t);
    out
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
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Xz>> =
            if pass == 0 { Box::new(points.iter()) } else { Box::new(points.iter().rev()) };
        for &p in iter {
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
