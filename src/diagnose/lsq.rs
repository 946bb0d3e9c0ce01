//! The least squares of the discrepancy workflow: residuals explained by a few columns
//! (set-up terms, effects already found, one candidate), with the statistics that decide
//! whether a candidate earns its place.
//!
//! The columns that every candidate is fitted beside (the base: set-up terms and the effects
//! found so far) are orthonormalised once (`Base`, modified Gram–Schmidt, run twice for
//! accuracy), so fitting a candidate is projecting its one or two columns off the base and
//! solving a system of that size. A base column that is (nearly) a combination of the
//! others is dropped: a part with no faces gives its Z datum no leverage, and that is not
//! an error.

use nalgebra::{DMatrix, DVector};

/// A column whose norm falls below this fraction of its original norm when projected off
/// the others adds nothing the others cannot do.
pub const DEPENDENT: f64 = 1e-6;

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// An orthonormal basis of the base columns.
#[derive(Debug, Clone, Default)]
pub struct Base {
    q: Vec<Vec<f64>>,
    /// Which of the columns pushed were kept (independent of those before them).
    pub kept: Vec<bool>,
}

impl Base {
    pub fn new(columns: &[Vec<f64>]) -> Base {
        let mut base = Base::default();
        for column in columns {
            base.push(column);
        }
        base
    }

    /// Add a column; returns whether it was independent of the basis (and so kept).
    pub fn push(&mut self, column: &[f64]) -> bool {
        let kept = self.add(column);
        self.kept.push(kept);
        kept
    }

    fn add(&mut self, column: &[f64]) -> bool {
        let original = norm(column);
        if original == 0.0 || !original.is_finite() {
            return false;
        }
        let mut v = column.to_vec();
        self.project_out(&mut v);
        self.project_out(&mut v);
        let left = norm(&v);
        if left <= DEPENDENT * original {
            return false;
        }
        v.iter_mut().for_each(|x| *x /= left);
        self.q.push(v);
        true
    }

    /// The number of independent columns.
    pub fn rank(&self) -> usize {
        self.q.len()
    }

    /// Remove from `v` its projection on the basis.
    pub fn project_out(&self, v: &mut [f64]) {
        for q in &self.q {
            let c = dot(q, v);
            v.iter_mut().zip(q).for_each(|(x, qi)| *x -= c * qi);
        }
    }

    pub fn residual_of(&self, v: &[f64]) -> Vec<f64> {
        let mut out = v.to_vec();
        self.project_out(&mut out);
        out
    }
}

/// Candidate columns fitted to a residual already projected off the base.
#[derive(Debug, Clone)]
pub struct ColumnFit {
    /// The coefficient of each column (in the joint fit with the base).
    pub coefficients: Vec<f64>,
    /// The residual sum of squares after the fit.
    pub rss: f64,
    /// What the candidate explains: its columns, projected off the base, times the
    /// coefficients. Two candidates whose signatures are alike cannot be told apart.
    pub signature: Vec<f64>,
}

/// A candidate column of which the base explains all but this fraction is the base's
/// own signature: what is left is the second-order rest of the readings' nonlinearity
/// (1e-5 of a micrometre probe), not a signature of its own.
pub const ALIASED: f64 = 1e-3;

/// Fit `columns` to `residual` (already taken off the base), jointly with the base.
/// `None` when a column has (almost) nothing left after the base: it is aliased.
pub fn fit_columns(base: &Base, residual_perp: &[f64], columns: &[Vec<f64>]) -> Option<ColumnFit> {
    let projected: Vec<Vec<f64>> = columns.iter().map(|c| base.residual_of(c)).collect();
    for (c, p) in columns.iter().zip(&projected) {
        if norm(p) <= ALIASED * norm(c).max(f64::MIN_POSITIVE) {
            return None;
        }
    }
    let m = projected.len();
    // Scale each column to unit norm so the normal equations stay well conditioned.
    let scales: Vec<f64> = projected.iter().map(|p| norm(p)).collect();
    let mut ata = DMatrix::<f64>::zeros(m, m);
    let mut atb = DVector::<f64>::zeros(m);
    for i in 0..m {
        atb[i] = dot(&projected[i], residual_perp) / scales[i];
        for j in 0..m {
            ata[(i, j)] = dot(&projected[i], &projected[j]) / (scales[i] * scales[j]);
        }
    }
    let solution = ata.clone().cholesky()?.solve(&atb);
    let coefficients: Vec<f64> = (0..m).map(|i| solution[i] / scales[i]).collect();
    let mut signature = vec![0.0; residual_perp.len()];
    for (p, c) in projected.iter().zip(&coefficients) {
        signature.iter_mut().zip(p).for_each(|(s, x)| *s += c * x);
    }
    let rss = residual_perp.iter().zip(&signature).map(|(r, s)| (r - s) * (r - s)).sum();
    Some(ColumnFit { coefficients, rss, signature })
}

/// The covariance of a linear least-squares fit with design `columns`, for a residual
/// variance `sigma2`: `σ² (JᵀJ)⁻¹`, computed on unit-norm columns. `None` when singular.
pub fn covariance(columns: &[Vec<f64>], sigma2: f64) -> Option<DMatrix<f64>> {
    let m = columns.len();
    let scales: Vec<f64> = columns.iter().map(|c| norm(c).max(f64::MIN_POSITIVE)).collect();
    let mut jtj = DMatrix::<f64>::zeros(m, m);
    for i in 0..m {
        for j in 0..m {
            jtj[(i, j)] = dot(&columns[i], &columns[j]) / (scales[i] * scales[j]);
        }
    }
    let inverse = jtj.try_inverse()?;
    Some(DMatrix::from_fn(m, m, |i, j| inverse[(i, j)] * sigma2 / (scales[i] * scales[j])))
}

/// The least-squares coefficients of `columns` for `y`, with their covariance for the
/// residual variance of the fit. `None` when the columns are dependent.
pub fn solve(columns: &[Vec<f64>], y: &[f64]) -> Option<(Vec<f64>, DMatrix<f64>, f64)> {
    let m = columns.len();
    let n = y.len();
    let unscaled = covariance(columns, 1.0)?;
    let aty: Vec<f64> = columns.iter().map(|c| dot(c, y)).collect();
    let coefficients: Vec<f64> = (0..m).map(|i| (0..m).map(|j| unscaled[(i, j)] * aty[j]).sum()).collect();
    let rss: f64 = (0..n)
        .map(|k| {
            let fitted: f64 = columns.iter().zip(&coefficients).map(|(c, b)| c[k] * b).sum();
            (y[k] - fitted).powi(2)
        })
        .sum();
    let sigma2 = rss / n.saturating_sub(m).max(1) as f64;
    Some((coefficients, unscaled * sigma2, rss))
}

/// The minimiser of a unimodal `f` on `[lo, hi]` by golden-section search: the middle of
/// the bracket after at most `steps` steps, or once it is narrower than `width`.
pub fn golden_minimum(f: impl Fn(f64) -> f64, lo: f64, hi: f64, steps: usize, width: f64) -> f64 {
    let golden = (5f64.sqrt() - 1.0) / 2.0;
    let (mut lo, mut hi) = (lo, hi);
    let (mut a, mut b) = (hi - golden * (hi - lo), lo + golden * (hi - lo));
    let (mut fa, mut fb) = (f(a), f(b));
    for _ in 0..steps {
        if hi - lo < width {
            break;
        }
        if fa < fb {
            hi = b;
            b = a;
            fb = fa;
            a = hi - golden * (hi - lo);
            fa = f(a);
        } else {
            lo = a;
            a = b;
            fa = fb;
            b = lo + golden * (hi - lo);
            fb = f(b);
        }
    }
    (lo + hi) / 2.0
}

/// The nested F statistic for `added` parameters that take the residual sum of squares
/// from `rss_without` to `rss_with`, with `dof` degrees of freedom left, and its p-value.
pub fn f_test(rss_without: f64, rss_with: f64, added: usize, dof: usize) -> (f64, f64) {
    if added == 0 || dof == 0 || rss_with <= 0.0 {
        return (f64::INFINITY, 0.0);
    }
    let f = ((rss_without - rss_with) / added as f64) / (rss_with / dof as f64);
    (f, f_survival(f, added as f64, dof as f64))
}

/// `P(F > f)` for Fisher's F with `d1`, `d2` degrees of freedom.
pub fn f_survival(f: f64, d1: f64, d2: f64) -> f64 {
    if f.is_nan() {
        return f64::NAN;
    }
    if f <= 0.0 {
        return 1.0;
    }
    if f.is_infinite() {
        return 0.0;
    }
    incomplete_beta(d2 / (d2 + d1 * f), d2 / 2.0, d1 / 2.0)
}

/// `ln Γ(x)` for `x > 0`: the recurrence up to `x ≥ 10`, then Stirling's series, whose
/// first omitted term is below 1e-13 there.
pub fn ln_gamma(x: f64) -> f64 {
    let mut shift = 0.0;
    let mut x = x;
    while x < 10.0 {
        shift -= x.ln();
        x += 1.0;
    }
    let inv = 1.0 / x;
    let inv2 = inv * inv;
    let series = inv * (1.0 / 12.0 - inv2 * (1.0 / 360.0 - inv2 * (1.0 / 1260.0 - inv2 / 1680.0)));
    shift + (x - 0.5) * x.ln() - x + 0.5 * std::f64::consts::TAU.ln() + series
}

/// The regularised incomplete beta function `I_x(a, b)`, by its continued fraction
/// (DLMF 8.17.22) evaluated with the modified Lentz method, on the side of `x` where it
/// converges fast.
pub fn incomplete_beta(x: f64, a: f64, b: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    if x >= 1.0 {
        return 1.0;
    }
    if x > (a + 1.0) / (a + b + 2.0) {
        return 1.0 - incomplete_beta(1.0 - x, b, a);
    }
    let log_front = a * x.ln() + b * (1.0 - x).ln() - (ln_gamma(a) + ln_gamma(b) - ln_gamma(a + b)) - a.ln();
    const TINY: f64 = 1e-300;
    let mut c = 1.0;
    let mut d = 1.0 - (a + b) * x / (a + 1.0);
    d = if d.abs() < TINY { TINY } else { d };
    d = 1.0 / d;
    let mut fraction = d;
    for m in 1..500 {
        let m = f64::from(m);
        for numerator in [
            m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m)),
            -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0)),
        ] {
            d = 1.0 + numerator * d;
            d = if d.abs() < TINY { TINY } else { d };
            c = 1.0 + numerator / c;
            c = if c.abs() < TINY { TINY } else { c };
            d = 1.0 / d;
            fraction *= d * c;
        }
        if (d * c - 1.0).abs() < 1e-15 {
            break;
        }
    }
    (log_front.exp() * fraction).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests;
