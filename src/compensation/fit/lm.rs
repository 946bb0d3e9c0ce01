//! Levenberg–Marquardt on the normal equations of a small least-squares problem.
//!
//! The circle fits here have one, two or three parameters, so the normal equations are a
//! 1×1 to 3×3 system that nalgebra solves on the stack. The loop is written here rather
//! than taken from the `levenberg-marquardt` crate: its latest release (0.15) requires
//! nalgebra 0.34 where turnpass uses 0.35, so it would bring a second copy of nalgebra into
//! the build for a loop of forty lines.
//!
//! The damping is Marquardt's: `(JᵀJ + λ·diag(JᵀJ)) δ = −Jᵀr`; a step that lowers the cost
//! is taken and λ shrinks tenfold, one that does not is refused and λ grows tenfold.

use nalgebra::{SMatrix, SVector};

/// A sum of squared residuals in `N` parameters.
pub(crate) trait LeastSquares<const N: usize> {
    /// Σ r² at `params`; `None` where the parameters leave the problem's domain.
    fn cost(&self, params: &SVector<f64, N>) -> Option<f64>;

    /// `JᵀJ`, `Jᵀr` and Σ r² at `params`, accumulated in one pass over the residuals.
    fn normal_equations(&self, params: &SVector<f64, N>) -> Option<NormalEquations<N>>;
}

pub(crate) struct NormalEquations<const N: usize> {
    pub jtj: SMatrix<f64, N, N>,
    pub jtr: SVector<f64, N>,
    pub cost: f64,
}

impl<const N: usize> NormalEquations<N> {
    pub fn zero() -> NormalEquations<N> {
        NormalEquations { jtj: SMatrix::zeros(), jtr: SVector::zeros(), cost: 0.0 }
    }

    /// Adds one residual `r` with gradient `j`.
    pub fn add(&mut self, r: f64, j: &SVector<f64, N>) {
        self.jtj += j * j.transpose();
        self.jtr += j * r;
        self.cost += r * r;
    }
}

const MAX_ITERATIONS: usize = 100;

/// The parameters that minimise the problem's cost from `start`, and that cost; `None`
/// when the problem is not defined at `start`.
pub(crate) fn minimise<const N: usize>(
    problem: &impl LeastSquares<N>,
    start: SVector<f64, N>,
) -> Option<(SVector<f64, N>, f64)> {
    let mut params = start;
    let mut equations = problem.normal_equations(&params)?;
    let mut lambda = 1e-3;
    for _ in 0..MAX_ITERATIONS {
        // Stationary already: the gradient vanishes to rounding.
        if equations.jtr.norm() <= 1e-15 * (1.0 + equations.cost.sqrt()) {
            break;
        }
        let mut damped = equations.jtj;
        for i in 0..N {
            damped[(i, i)] += lambda * equations.jtj[(i, i)].max(1e-300);
        }
        let Some(step) = damped.cholesky().map(|c| c.solve(&-equations.jtr)) else {
            lambda *= 10.0;
            if lambda > 1e16 {
                break;
            }
            continue;
        };
        let candidate = params + step;
        match problem.cost(&candidate) {
            Some(cost) if cost < equations.cost => {
                let gain = equations.cost - cost;
                params = candidate;
                let small_step = step.norm() <= 1e-14 * (1.0 + params.norm());
                if gain <= 1e-15 * equations.cost || small_step {
                    equations.cost = cost;
                    break;
                }
                equations = problem.normal_equations(&params)?;
                lambda = (lambda / 10.0).max(1e-15);
            }
            // A step this small that does not lower the cost is rounding noise: the
            // minimum is found, and raising the damping up to its limit would only shorten
            // the step further (that tail was most of the iterations on near-exact circles).
            _ if step.norm() <= 1e-12 * (1.0 + params.norm()) => break,
            _ => {
                lambda *= 10.0;
                if lambda > 1e16 {
                    break;
                }
            }
        }
    }
    Some((params, equations.cost))
}
