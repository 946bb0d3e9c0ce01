//! First-order thermal curves (eq. 5.1–5.2 of the thesis) fitted to a log of a warm-up
//! followed by a cool-down, as in its Figures 28–30:
//!
//! ```txt
//! warm:  y = gain · (1 − e^(−t/τw)) + offset        t from the start of the log
//! cool:  y = gain · e^(−t'/τc) + offset             t' from the end of the warm-up
//! ```
//!
//! For a fixed τ both are linear in gain and offset, so the fit is a one-dimensional search
//! over τ (golden section on log τ) with a linear least-squares solve inside; the
//! uncertainties are the Gauss–Newton standard errors at the optimum,
//! `σ² (JᵀJ)⁻¹` with `σ² = RSS/(n − 3)`.
//!
//! The warm-up ends where the smoothed log peaks (for a log that falls during warm-up, as a
//! displacement of the opposite sign does, where it bottoms out): the log is split there.

use nalgebra::{Matrix3, Vector3};

use super::lsq::golden_minimum;

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Phase {
    Warm,
    Cool,
}

/// One fitted curve with its standard errors.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FirstOrderFit {
    pub phase: Phase,
    pub gain: f64,
    pub tau_min: f64,
    pub offset: f64,
    pub gain_sigma: f64,
    pub tau_sigma: f64,
    pub offset_sigma: f64,
    /// Root mean square of the residuals.
    pub rms: f64,
    pub samples: usize,
}

impl FirstOrderFit {
    pub fn value(&self, t_min: f64) -> f64 {
        self.gain * basis(self.phase, t_min, self.tau_min) + self.offset
    }
}

/// A whole log's fits.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ThermalFit {
    pub warm: FirstOrderFit,
    /// The cool-down, when the log has one.
    pub cool: Option<FirstOrderFit>,
    /// Where the warm-up ends, minutes from the start of the log.
    pub split_min: f64,
}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ThermalFitError {
    #[error("a thermal log needs at least {0} samples")]
    TooFewSamples(usize),
    #[error("the log's times must increase (row {0})")]
    TimesNotIncreasing(usize),
    #[error("the log is flat: there is no time constant to fit")]
    Flat,
}

fn basis(phase: Phase, t: f64, tau: f64) -> f64 {
    match phase {
        Phase::Warm => 1.0 - (-t / tau).exp(),
        Phase::Cool => (-t / tau).exp(),
    }
}

/// The least-squares gain and offset for a fixed τ, and the residual sum of squares.
fn linear_fit(phase: Phase, t: &[f64], y: &[f64], tau: f64) -> (f64, f64, f64) {
    let n = t.len() as f64;
    let (mut sb, mut sbb, mut sy, mut sby) = (0.0, 0.0, 0.0, 0.0);
    for (&ti, &yi) in t.iter().zip(y) {
        let b = basis(phase, ti, tau);
        sb += b;
        sbb += b * b;
        sy += yi;
        sby += b * yi;
    }
    let det = n * sbb - sb * sb;
    let (gain, offset) =
        if det.abs() > 1e-300 { ((n * sby - sb * sy) / det, (sbb * sy - sb * sby) / det) } else { (0.0, sy / n) };
    let rss = t.iter().zip(y).map(|(&ti, &yi)| (yi - gain * basis(phase, ti, tau) - offset).powi(2)).sum();
    (gain, offset, rss)
}

/// Fit one phase to `(t, y)`, t in minutes from the phase's start.
pub fn fit_phase(phase: Phase, t: &[f64], y: &[f64]) -> Result<FirstOrderFit, ThermalFitError> {
    if t.len() < 4 || t.len() != y.len() {
        return Err(ThermalFitError::TooFewSamples(4));
    }
    let span = t[t.len() - 1] - t[0];
    let step = t.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min).max(span * 1e-6);
    if span.is_nan() || span <= 0.0 {
        return Err(ThermalFitError::Flat);
    }
    // Golden-section search on ln τ between one sample step and a hundred times the span.
    let rss = |log_tau: f64| linear_fit(phase, t, y, log_tau.exp()).2;
    let tau = golden_minimum(rss, step.ln(), (100.0 * span).ln(), 200, 1e-10).exp();
    let (gain, offset, rss) = linear_fit(phase, t, y, tau);
    if gain.abs() < 1e-300 {
        return Err(ThermalFitError::Flat);
    }
    // Gauss–Newton covariance at the optimum.
    let mut jtj = Matrix3::zeros();
    for &ti in t {
        let e = (-ti / tau).exp();
        let d_tau = match phase {
            Phase::Warm => -gain * e * ti / (tau * tau),
            Phase::Cool => gain * e * ti / (tau * tau),
        };
        let row = Vector3::new(basis(phase, ti, tau), d_tau, 1.0);
        jtj += row * row.transpose();
    }
    let n = t.len();
    let sigma2 = rss / (n.saturating_sub(3).max(1)) as f64;
    let cov = jtj.try_inverse().map(|m| m * sigma2);
    let sd = |k: usize| cov.map_or(f64::NAN, |c| c[(k, k)].max(0.0).sqrt());
    Ok(FirstOrderFit {
        phase,
        gain,
        tau_min: tau,
        offset,
        gain_sigma: sd(0),
        tau_sigma: sd(1),
        offset_sigma: sd(2),
        rms: (rss / n as f64).sqrt(),
        samples: n,
    })
}

/// Fit a warm-up (and the cool-down after it, when the log has one).
pub fn fit_log(t: &[f64], y: &[f64]) -> Result<ThermalFit, ThermalFitError> {
    fit_log_split(t, y, None)
}

/// Fit a warm-up and cool-down split where the heat source stopped, `split_min` minutes
/// from the start of the log, when it is known. Near equilibrium the log is flat within
/// its noise, so the extreme it would otherwise be split at can lie minutes early, and a
/// cool-down fitted from there starts with a plateau that lengthens its τ.
pub fn fit_log_split(t: &[f64], y: &[f64], split_min: Option<f64>) -> Result<ThermalFit, ThermalFitError> {
    if t.len() < 8 || t.len() != y.len() {
        return Err(ThermalFitError::TooFewSamples(8));
    }
    if let Some(k) = t.windows(2).position(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater)) {
        return Err(ThermalFitError::TimesNotIncreasing(k + 2));
    }
    let split = match split_min {
        Some(m) => t.partition_point(|&ti| ti - t[0] <= m).saturating_sub(1).max(3),
        None => split_index(y),
    };
    let t0 = t[0];
    let warm_t: Vec<f64> = t[..=split].iter().map(|&ti| ti - t0).collect();
    let warm = fit_phase(Phase::Warm, &warm_t, &y[..=split])?;
    let cool = if t.len() - split >= 8 {
        let ts = t[split];
        let cool_t: Vec<f64> = t[split..].iter().map(|&ti| ti - ts).collect();
        fit_phase(Phase::Cool, &cool_t, &y[split..]).ok()
    } else {
        None
    };
    Ok(ThermalFit { warm, cool, split_min: t[split] - t0 })
}

/// Where the warm-up ends: the extreme of the log smoothed over 2 % of its samples, on the
/// side the log moved to from its start.
fn split_index(y: &[f64]) -> usize {
    let n = y.len();
    let half = (n / 100).max(1);
    let smooth: Vec<f64> = (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(half), (i + half + 1).min(n));
            y[a..b].iter().sum::<f64>() / (b - a) as f64
        })
        .collect();
    let rising = smooth[n / 2] >= smooth[0]
        || smooth.iter().copied().fold(f64::NEG_INFINITY, f64::max) - smooth[0]
            > smooth[0] - smooth.iter().copied().fold(f64::INFINITY, f64::min);
    let pick = |a: &(usize, &f64), b: &(usize, &f64)| if rising { a.1.total_cmp(b.1) } else { b.1.total_cmp(a.1) };
    smooth.iter().enumerate().max_by(pick).map_or(n - 1, |(i, _)| i)
}

#[cfg(test)]
mod tests;
