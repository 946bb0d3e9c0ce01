//! Circles pinned to points the written path must pass through.
//!
//! A written arc must start where the path stands and, for the last one of a move, end on
//! the move's end point; an arc that continues the previous one smoothly must also leave
//! in its direction. Each of these leaves a one- or two-parameter family of circles, fitted
//! here to the points in between:
//!
//! * [`through_ends`]: through two points. The family is parametrised by the angle α
//!   between the chord and the tangent at the start (curvature `2 sin α / chord`), not by
//!   the centre's place on the perpendicular bisector: α passes smoothly through a straight
//!   line (α = 0) where the centre runs off to infinity. The start is the algebraic fit,
//!   which in α is the smallest eigenvector of a 2×2 matrix; Levenberg–Marquardt then
//!   minimises the orthogonal distances.
//! * [`with_tangent`] / [`with_tangent_to`]: through one point with a given direction,
//!   parametrised by the signed curvature κ (again a line at κ = 0): the arcs strategy's
//!   tangent-continuous pieces.
//! * [`through_point`]: through one point (a full circle that starts and ends there).
//!
//! The orthogonal distance of a point q from the circle through p with unit tangent t and
//! curvature κ is, with d = q − p, A = d·d, B = d·n (n the left normal):
//!
//! ```txt
//! δ = (κA − 2B) / (1 + √(1 − 2κB + κ²A))
//! ```
//!
//! which is ρ − R for κ > 0 (ρ the distance from the centre), R − ρ for κ < 0 and −B for
//! a line: positive to the right of travel in every case, and exact, with no large numbers
//! to cancel however flat the arc.

use nalgebra::{SVector, Vector1, Vector2};

use super::Segment;
use super::circle;
use super::lm::{self, LeastSquares, NormalEquations};
use crate::geometry;
use crate::toolpath::Xz;

/// Arcs flatter than this are written as lines: a control's radius word has room for five
/// integer digits in millimetres.
pub const MAX_RADIUS_MM: f64 = 99_999.0;

/// A circle (a line when the curvature is zero) through `start`, travelled in `tangent`'s
/// direction there; positive curvature turns left (counter-clockwise, `G03`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bend {
    pub start: Xz,
    /// A unit vector.
    pub tangent: Xz,
    pub curvature: f64,
}

fn dot(a: Xz, b: Xz) -> f64 {
    a.x * b.x + a.z * b.z
}

fn sub(a: Xz, b: Xz) -> Xz {
    Xz::new(a.x - b.x, a.z - b.z)
}

fn add_scaled(a: Xz, b: Xz, s: f64) -> Xz {
    Xz::new(a.x + b.x * s, a.z + b.z * s)
}

/// The left normal of a direction in the (Z, X) view, as `geometry::left_normal`.
fn left(t: Xz) -> Xz {
    Xz::new(t.z, -t.x)
}

/// δ and its partial derivatives in κ and in B, for one point.
struct Offset {
    value: f64,
    by_curvature: f64,
    by_normal_component: f64,
}

fn offset(a: f64, b: f64, kappa: f64) -> Offset {
    let s = (1.0 - 2.0 * kappa * b + kappa * kappa * a).max(0.0).sqrt();
    let n = kappa * a - 2.0 * b;
    let denominator = 1.0 + s;
    let value = n / denominator;
    // At the centre itself (s = 0) the distance does not depend smoothly on the circle;
    // the point then steers the fit through its value alone.
    let (ds_dk, ds_db) = if s > 1e-12 { ((kappa * a - b) / s, -kappa / s) } else { (0.0, 0.0) };
    let square = denominator * denominator;
    Offset {
        value,
        by_curvature: (a * denominator - n * ds_dk) / square,
        by_normal_component: (-2.0 * denominator - n * ds_db) / square,
    }
}

impl Bend {
    fn normal(&self) -> Xz {
        left(self.tangent)
    }

    /// The signed orthogonal distance of `q` (positive to the right of travel).
    pub fn offset(&self, q: Xz) -> f64 {
        let d = sub(q, self.start);
        offset(dot(d, d), dot(d, self.normal()), self.curvature).value
    }

    pub fn radius(&self) -> f64 {
        1.0 / self.curvature.abs()
    }

    pub fn centre(&self) -> Option<Xz> {
        (self.curvature != 0.0).then(|| add_scaled(self.start, self.normal(), 1.0 / self.curvature))
    }

    /// The nearest point of the circle (or line) to `q`.
    pub fn project(&self, q: Xz) -> Xz {
        match self.centre() {
            Some(centre) => {
                let r = q.distance(centre);
                if r <= 0.0 {
                    return self.start;
                }
                add_scaled(centre, sub(q, centre), self.radius() / r)
            }
            None => add_scaled(self.start, self.tangent, dot(sub(q, self.start), self.tangent)),
        }
    }

    /// The direction of travel at `on`, a point of the circle.
    pub fn tangent_at(&self, on: Xz) -> Xz {
        match self.centre() {
            Some(centre) => {
                let radial = geometry::direction(centre, on);
                // Counter-clockwise travel runs along the left normal of the radius.
                if self.curvature > 0.0 { left(radial) } else { Xz::new(-radial.z, radial.x) }
            }
            None => self.tangent,
        }
    }

    /// The segment from `start` along the circle to `end` (a point on it). An arc whose
    /// sagitta over its chord is under a nanometre is written as the line it is.
    pub fn segment_to(&self, end: Xz) -> Segment {
        let chord = self.start.distance(end);
        match self.centre() {
            Some(centre) if self.curvature.abs() * chord * chord / 8.0 >= 1e-9 => {
                Segment::Arc { end, centre, ccw: self.curvature > 0.0 }
            }
            _ => Segment::Line { end },
        }
    }

    /// Whether the radius is one a control can be given.
    pub fn writable(&self) -> bool {
        self.curvature.is_finite() && (self.curvature == 0.0 || self.radius() <= MAX_RADIUS_MM)
    }
}

/// The circle through `from` and `to` that fits `interior` best: algebraically when
/// `refine` is false, to the orthogonal distances when true. `ccw` asks for one sense of
/// travel (a circle of the other sense is refused unless it is flat enough to be a line);
/// without it, the arc from `from` to `to` is the minor one. `hint` is the curvature to
/// take when there are no interior points (else a line). `None` when `from` and `to`
/// coincide (see [`through_point`]).
pub fn through_ends(
    from: Xz,
    to: Xz,
    interior: &[Xz],
    ccw: Option<bool>,
    hint: Option<f64>,
    refine: bool,
) -> Option<Bend> {
    let chord_vector = sub(to, from);
    let chord = from.distance(to);
    if chord.is_nan() || chord <= 1e-9 || chord.is_infinite() {
        return None;
    }
    let family = EndFamily { from, chord, along: Xz::new(chord_vector.x / chord, chord_vector.z / chord), interior };
    let alpha = match family.algebraic(ccw) {
        Some(alpha) => alpha,
        None => {
            // No interior point: the hinted curvature, on the side the sense asks for.
            let sine = (hint.unwrap_or(0.0) * chord / 2.0).clamp(-1.0, 1.0);
            let sine = match ccw {
                Some(true) => sine.abs(),
                Some(false) => -sine.abs(),
                None => sine,
            };
            sine.asin()
        }
    };
    let alpha = if refine && !interior.is_empty() {
        lm::minimise(&family, Vector1::new(alpha)).map_or(alpha, |(best, _)| best.x)
    } else {
        alpha
    };
    let bend = family.bend(alpha);
    let wrong_sense = match ccw {
        Some(ccw) => (bend.curvature > 0.0) != ccw && bend.segment_to(to) != (Segment::Line { end: to }),
        None => false,
    };
    (!wrong_sense && bend.curvature.is_finite()).then_some(bend)
}

struct EndFamily<'a> {
    from: Xz,
    chord: f64,
    /// The unit chord direction, t₀; n₀ is its left normal.
    along: Xz,
    interior: &'a [Xz],
}

impl EndFamily<'_> {
    /// The circle whose tangent at `from` is the chord turned by −α: it turns left by 2α
    /// over the chord, so its curvature is 2 sin α / chord.
    fn bend(&self, alpha: f64) -> Bend {
        let (sin, cos) = alpha.sin_cos();
        let n0 = left(self.along);
        let tangent = Xz::new(cos * self.along.x - sin * n0.x, cos * self.along.z - sin * n0.z);
        Bend { start: self.from, tangent, curvature: 2.0 * sin / self.chord }
    }

    /// The algebraic residual κA − 2B is 2(sin α·u − cos α·v) with u = A/chord − d·t₀ and
    /// v = d·n₀; the (sin α, cos α) minimising its sum of squares is the eigenvector of the
    /// smaller eigenvalue of [[Σu², −Σuv], [−Σuv, Σv²]].
    fn algebraic(&self, ccw: Option<bool>) -> Option<f64> {
        if self.interior.is_empty() {
            return None;
        }
        let n0 = left(self.along);
        let (mut uu, mut uv, mut vv) = (0.0, 0.0, 0.0);
        for &q in self.interior {
            let d = sub(q, self.from);
            let u = dot(d, d) / self.chord - dot(d, self.along);
            let v = dot(d, n0);
            uu += u * u;
            uv += u * v;
            vv += v * v;
        }
        let (a, b, d) = (uu, -uv, vv);
        let half_gap = (((a - d) / 2.0).powi(2) + b * b).sqrt();
        let smallest = (a + d) / 2.0 - half_gap;
        // Of the two forms of the eigenvector, the one computed from the larger entries.
        let (s, c) = if (a - smallest).abs() >= (d - smallest).abs() { (-b, a - smallest) } else { (d - smallest, -b) };
        let (s, c) = if s == 0.0 && c == 0.0 { (0.0, 1.0) } else { (s, c) };
        let flip = match ccw {
            Some(true) => s < 0.0 || (s == 0.0 && c < 0.0),
            Some(false) => s > 0.0 || (s == 0.0 && c < 0.0),
            None => c < 0.0,
        };
        let (s, c) = if flip { (-s, -c) } else { (s, c) };
        let alpha = s.atan2(c);
        alpha.is_finite().then_some(alpha)
    }
}

impl LeastSquares<1> for EndFamily<'_> {
    fn cost(&self, params: &Vector1<f64>) -> Option<f64> {
        let bend = self.bend(params.x);
        let cost: f64 = self.interior.iter().map(|&q| bend.offset(q).powi(2)).sum();
        cost.is_finite().then_some(cost)
    }

    fn normal_equations(&self, params: &Vector1<f64>) -> Option<NormalEquations<1>> {
        let alpha = params.x;
        let (sin, cos) = alpha.sin_cos();
        let bend = self.bend(alpha);
        let n0 = left(self.along);
        let normal = bend.normal();
        let dk = 2.0 * cos / self.chord;
        let mut equations = NormalEquations::zero();
        for &q in self.interior {
            let d = sub(q, self.from);
            let o = offset(dot(d, d), dot(d, normal), bend.curvature);
            // B = cos α·d·n₀ + sin α·d·t₀.
            let db = -sin * dot(d, n0) + cos * dot(d, self.along);
            equations.add(o.value, &Vector1::new(o.by_curvature * dk + o.by_normal_component * db));
        }
        equations.cost.is_finite().then_some(equations)
    }
}

/// The circle through `start` leaving in `tangent`'s direction that fits `points` best
/// (algebraically: to first order in δ/R the same as the orthogonal fit, since the
/// algebraic residual is δ·(1 + √…) with the root within δ/R of 1 near the circle).
pub fn with_tangent(start: Xz, tangent: Xz, points: &[Xz]) -> Bend {
    let normal = left(tangent);
    let (mut ab, mut aa) = (0.0, 0.0);
    for &q in points {
        let d = sub(q, start);
        let a = dot(d, d);
        ab += a * dot(d, normal);
        aa += a * a;
    }
    let curvature = if aa > 0.0 { 2.0 * ab / aa } else { 0.0 };
    Bend { start, tangent, curvature: if curvature.is_finite() { curvature } else { 0.0 } }
}

/// The circle through `start` leaving in `tangent`'s direction that passes through `end`.
pub fn with_tangent_to(start: Xz, tangent: Xz, end: Xz) -> Bend {
    let d = sub(end, start);
    let a = dot(d, d);
    let curvature = if a > 0.0 { 2.0 * dot(d, left(tangent)) / a } else { 0.0 };
    Bend { start, tangent, curvature }
}

/// The full circle through `point` that fits `others` best (orthogonal distances), with
/// the centre started from Taubin's fit of all of them.
pub fn through_point(point: Xz, others: &[Xz]) -> Option<circle::Circle> {
    let mut all = Vec::with_capacity(others.len() + 1);
    all.push(point);
    all.extend_from_slice(others);
    let start = circle::taubin(&all)?;
    let problem = PointFamily { point, others };
    let (centre, _) = lm::minimise(&problem, Vector2::new(start.centre.x, start.centre.z))?;
    let centre = Xz::new(centre.x, centre.y);
    let radius = point.distance(centre);
    (centre.is_finite() && radius > 0.0).then_some(circle::Circle { centre, radius })
}

struct PointFamily<'a> {
    point: Xz,
    others: &'a [Xz],
}

impl LeastSquares<2> for PointFamily<'_> {
    fn cost(&self, params: &Vector2<f64>) -> Option<f64> {
        let centre = Xz::new(params.x, params.y);
        let radius = self.point.distance(centre);
        let cost: f64 = self.others.iter().map(|&q| (q.distance(centre) - radius).powi(2)).sum();
        cost.is_finite().then_some(cost)
    }

    fn normal_equations(&self, params: &Vector2<f64>) -> Option<NormalEquations<2>> {
        let centre = Xz::new(params.x, params.y);
        let radius = self.point.distance(centre);
        if radius <= 0.0 {
            return None;
        }
        let pinned = sub(self.point, centre);
        let mut equations = NormalEquations::zero();
        for &q in self.others {
            let d = sub(q, centre);
            let distance = d.distance(Xz::new(0.0, 0.0));
            let unit = if distance > 0.0 { Xz::new(d.x / distance, d.z / distance) } else { Xz::new(0.0, 0.0) };
            // r = ‖q − c‖ − ‖p − c‖, so ∂r/∂c = −(q − c)/‖q − c‖ + (p − c)/‖p − c‖.
            let gradient = SVector::from([pinned.x / radius - unit.x, pinned.z / radius - unit.z]);
            equations.add(distance - radius, &gradient);
        }
        equations.cost.is_finite().then_some(equations)
    }
}

#[cfg(test)]
mod tests;
