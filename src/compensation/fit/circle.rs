//! The least-squares circle through a set of points.
//!
//! Two stages, as metrology software does it (research notes, metrology.md §5.1):
//!
//! 1. **Taubin's algebraic fit**, in the form N. Chernov published ("Circular and Linear
//!    Regression", 2010): centre the data, form the moments of x, z and w = x² + z², find
//!    the root of a cubic next to zero by Newton's method, and read the centre off a 2×2
//!    solve. It needs no starting guess, works on full circles and on short arcs alike, and
//!    is nearly unbiased, which makes it a good start for
//! 2. **the geometric fit**: Levenberg–Marquardt on Σ(‖pᵢ − c‖ − R)², the orthogonal
//!    distances themselves (`lm.rs`). This is the fit a CMM reports, and the one the
//!    tolerance is measured against.
//!
//! Points on one line (or fewer than three distinct points) have no circle: `None`.

use nalgebra::{SVector, Vector3};

use super::lm::{self, LeastSquares, NormalEquations};
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    pub centre: Xz,
    pub radius: f64,
}

impl Circle {
    /// The signed distance of `p` from the circle (positive outside).
    pub fn residual(&self, p: Xz) -> f64 {
        p.distance(self.centre) - self.radius
    }
}

/// Σ(‖pᵢ − c‖ − R)²: what the geometric fit minimises.
pub fn geometric_cost(points: &[Xz], circle: &Circle) -> f64 {
    points.iter().map(|&p| circle.residual(p).powi(2)).sum()
}

/// Taubin's fit, then the geometric refinement; `None` for collinear or too few points.
pub fn fit(points: &[Xz]) -> Option<Circle> {
    let start = taubin(points)?;
    Some(refine(points, start).unwrap_or(start))
}

/// The mean of the points and their second and third moments about it, in (x, z) with
/// w = x² + z², as Chernov names them.
struct Moments {
    mean: Xz,
    xx: f64,
    zz: f64,
    xz: f64,
    xw: f64,
    zw: f64,
    ww: f64,
}

impl Moments {
    fn of(points: &[Xz]) -> Option<Moments> {
        let n = points.len() as f64;
        let (sx, sz) = points.iter().fold((0.0, 0.0), |(sx, sz), p| (sx + p.x, sz + p.z));
        let mean = Xz::new(sx / n, sz / n);
        let mut m = Moments { mean, xx: 0.0, zz: 0.0, xz: 0.0, xw: 0.0, zw: 0.0, ww: 0.0 };
        for p in points {
            let (x, z) = (p.x - mean.x, p.z - mean.z);
            let w = x * x + z * z;
            m.xx += x * x;
            m.zz += z * z;
            m.xz += x * z;
            m.xw += x * w;
            m.zw += z * w;
            m.ww += w * w;
        }
        for value in [&mut m.xx, &mut m.zz, &mut m.xz, &mut m.xw, &mut m.zw, &mut m.ww] {
            *value /= n;
        }
        Some(m).filter(|m| m.ww.is_finite())
    }

    /// Whether the points spread in two directions: the smaller eigenvalue of their
    /// covariance against the larger. Rounding alone leaves about 1e-16 of the larger on
    /// exactly collinear points; 1e-14 is a band of a ten-millionth of their length.
    fn spread_in_two_directions(&self) -> bool {
        let trace = self.xx + self.zz;
        let det = self.xx * self.zz - self.xz * self.xz;
        let gap = (trace * trace / 4.0 - det).max(0.0).sqrt();
        let largest = trace / 2.0 + gap;
        let smallest = det / largest.max(f64::MIN_POSITIVE);
        largest > 0.0 && smallest > 1e-14 * largest
    }
}

/// Taubin's algebraic circle fit (Chernov's formulation); `None` for fewer than three
/// points or points on one line.
pub fn taubin(points: &[Xz]) -> Option<Circle> {
    if points.len() < 3 || points.iter().any(|p| !p.is_finite()) {
        return None;
    }
    let m = Moments::of(points)?;
    if !m.spread_in_two_directions() {
        return None;
    }
    // The characteristic polynomial of Taubin's generalised eigenproblem, in Chernov's
    // reduced form: A3·η³ + A2·η² + A1·η + A0 with η the eigenvalue sought.
    let mean_w = m.xx + m.zz;
    let cov_xz = m.xx * m.zz - m.xz * m.xz;
    let var_w = m.ww - mean_w * mean_w;
    let a3 = 4.0 * mean_w;
    let a2 = -3.0 * mean_w * mean_w - m.ww;
    let a1 = var_w * mean_w + 4.0 * cov_xz * mean_w - m.xw * m.xw - m.zw * m.zw;
    let a0 = m.xw * (m.xw * m.zz - m.zw * m.xz) + m.zw * (m.zw * m.xx - m.xw * m.xz) - var_w * cov_xz;
    let polynomial = |eta: f64| a0 + eta * (a1 + eta * (a2 + eta * a3));
    // Newton from zero descends to the smallest positive root, the one that is Taubin's fit;
    // it stops when the step no longer lowers |P| (the root to rounding).
    let mut eta = 0.0;
    let mut value = a0;
    for _ in 0..100 {
        let slope = a1 + eta * (2.0 * a2 + 3.0 * a3 * eta);
        let next = eta - value / slope;
        if !next.is_finite() || next == eta {
            break;
        }
        let next_value = polynomial(next);
        if next_value.abs() >= value.abs() {
            break;
        }
        eta = next;
        value = next_value;
    }
    let det = eta * eta - eta * mean_w + cov_xz;
    let cx = (m.xw * (m.zz - eta) - m.zw * m.xz) / (2.0 * det);
    let cz = (m.zw * (m.xx - eta) - m.xw * m.xz) / (2.0 * det);
    let radius = (cx * cx + cz * cz + mean_w).sqrt();
    let circle = Circle { centre: Xz::new(cx + m.mean.x, cz + m.mean.z), radius };
    (circle.centre.is_finite() && radius.is_finite() && radius > 0.0).then_some(circle)
}

/// The geometric problem in (cx, cz, R), about the points' mean so that the normal
/// equations are as well conditioned as the data allow.
struct Orthogonal<'a> {
    points: &'a [Xz],
    origin: Xz,
}

impl Orthogonal<'_> {
    fn relative(&self, p: Xz) -> (f64, f64) {
        (p.x - self.origin.x, p.z - self.origin.z)
    }
}

impl LeastSquares<3> for Orthogonal<'_> {
    fn cost(&self, params: &Vector3<f64>) -> Option<f64> {
        let mut cost = 0.0;
        for &p in self.points {
            let (x, z) = self.relative(p);
            let r = ((x - params.x).powi(2) + (z - params.y).powi(2)).sqrt() - params.z;
            cost += r * r;
        }
        cost.is_finite().then_some(cost)
    }

    fn normal_equations(&self, params: &Vector3<f64>) -> Option<NormalEquations<3>> {
        let mut equations = NormalEquations::zero();
        for &p in self.points {
            let (x, z) = self.relative(p);
            let (dx, dz) = (x - params.x, z - params.y);
            let distance = (dx * dx + dz * dz).sqrt();
            // A point on the centre has no direction; its residual still counts, through R.
            let (ux, uz) = if distance > 0.0 { (dx / distance, dz / distance) } else { (0.0, 0.0) };
            equations.add(distance - params.z, &SVector::from([-ux, -uz, -1.0]));
        }
        equations.cost.is_finite().then_some(equations)
    }
}

/// The geometric least-squares circle, from `start`.
pub fn refine(points: &[Xz], start: Circle) -> Option<Circle> {
    if points.len() < 3 {
        return None;
    }
    let n = points.len() as f64;
    let origin = points.iter().fold(Xz::new(0.0, 0.0), |s, p| Xz::new(s.x + p.x / n, s.z + p.z / n));
    let problem = Orthogonal { points, origin };
    let initial = Vector3::new(start.centre.x - origin.x, start.centre.z - origin.z, start.radius);
    let (best, _) = lm::minimise(&problem, initial)?;
    let circle = Circle { centre: Xz::new(best.x + origin.x, best.y + origin.z), radius: best.z.abs() };
    (circle.centre.is_finite() && circle.radius.is_finite() && circle.radius > 0.0).then_some(circle)
}

#[cfg(test)]
pub(crate) mod tests;
