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
//! Where the warm-up ends (the heat source stopped) is found by fitting: the split that
//! leaves the least residual sum of squares of the two curves together, searched on a
//! grid over a thinned log and refined on the whole one. Near equilibrium the log is flat
//! within its noise, so its peak says little about the split; the start of the cool-down's
//! fall says much. A log need not have a cool-down: the two curves are kept only when they
//! beat one warm-up curve over the whole log by the F-test and the BIC (as `diagnose`
//! scores a candidate) and the cool-down is determined — its gain of the sign that takes
//! the log back, at least `DETERMINED_SIGMAS` uncertainties from zero, and its τ inside its
//! search range and at least two uncertainties from zero. Otherwise the log is a warm-up,
//! and the report says why.

use nalgebra::{Matrix3, Vector3};

use super::lsq::{f_test, golden_minimum};
use super::select::{ALPHA, BIC_MARGIN, DETERMINED_SIGMAS, SEARCHED_SIGMAS, short_of};

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
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ThermalFit {
    pub warm: FirstOrderFit,
    /// The cool-down, when the log has one.
    pub cool: Option<FirstOrderFit>,
    /// Where the warm-up ends, minutes from the start of the log (the log's end when it has
    /// no cool-down).
    pub split_min: f64,
    /// How the split was found.
    pub split: Split,
    /// Why the log is taken to have no cool-down, when it is.
    pub no_cool_down: Option<String>,
}

/// How the end of the warm-up was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Split {
    /// `--split-min` gave it.
    Given,
    /// The fit of the two curves found it.
    Fitted,
    /// The log has no cool-down.
    None,
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

/// The range of τ a phase's search covers: from one sample step to a hundred times its
/// span, minutes.
fn tau_range(t: &[f64]) -> Option<(f64, f64)> {
    let span = t[t.len() - 1] - t[0];
    if span.is_nan() || span <= 0.0 {
        return None;
    }
    let step = t.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min).max(span * 1e-6);
    Some((step, 100.0 * span))
}

/// The best τ of a phase (golden section on ln τ over `tau_range`, to `width` in ln τ)
/// and the residual sum of squares it leaves.
fn best_tau(phase: Phase, t: &[f64], y: &[f64], width: f64) -> Option<(f64, f64)> {
    let (low, high) = tau_range(t)?;
    let rss = |log_tau: f64| linear_fit(phase, t, y, log_tau.exp()).2;
    let tau = golden_minimum(rss, low.ln(), high.ln(), 200, width).exp();
    Some((tau, linear_fit(phase, t, y, tau).2))
}

/// Fit one phase to `(t, y)`, t in minutes from the phase's start.
pub fn fit_phase(phase: Phase, t: &[f64], y: &[f64]) -> Result<FirstOrderFit, ThermalFitError> {
    if t.len() < 4 || t.len() != y.len() {
        return Err(ThermalFitError::TooFewSamples(4));
    }
    let (tau, _) = best_tau(phase, t, y, 1e-10).ok_or(ThermalFitError::Flat)?;
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

/// The fewest samples a phase of a split log has.
const PHASE_SAMPLES: usize = 8;
/// The log is thinned to at most this many samples for the grid of splits.
const THINNED: usize = 2000;
/// Splits on the grid.
const SPLIT_GRID: usize = 64;

/// Fit a warm-up and cool-down split where the heat source stopped: `split_min` minutes
/// from the start of the log when it is known, else where the fit of both curves is best
/// (see the module's documentation), or nowhere when the log has no cool-down.
pub fn fit_log_split(t: &[f64], y: &[f64], split_min: Option<f64>) -> Result<ThermalFit, ThermalFitError> {
    if t.len() < 8 || t.len() != y.len() {
        return Err(ThermalFitError::TooFewSamples(8));
    }
    if let Some(k) = t.windows(2).position(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater)) {
        return Err(ThermalFitError::TimesNotIncreasing(k + 2));
    }
    let t0 = t[0];
    let from_start: Vec<f64> = t.iter().map(|&ti| ti - t0).collect();
    if let Some(m) = split_min {
        let split = t.partition_point(|&ti| ti - t0 <= m).saturating_sub(1).max(3);
        let warm = fit_phase(Phase::Warm, &from_start[..=split], &y[..=split])?;
        let cool = (t.len() - split >= PHASE_SAMPLES)
            .then(|| fit_phase(Phase::Cool, &since(&t[split..]), &y[split..]).ok())
            .flatten();
        let no_cool_down = cool.is_none().then(|| format!("fewer than {PHASE_SAMPLES} samples after the split"));
        return Ok(ThermalFit { warm, cool, split_min: t[split] - t0, split: Split::Given, no_cool_down });
    }
    let whole = fit_phase(Phase::Warm, &from_start, y)?;
    let only_warm = |why: String| ThermalFit {
        warm: whole,
        cool: None,
        split_min: from_start[from_start.len() - 1],
        split: Split::None,
        no_cool_down: Some(why),
    };
    let Some(split) = best_split(&from_start, y) else {
        return Ok(only_warm(format!("too short to split into two phases of {PHASE_SAMPLES} samples")));
    };
    let warm = fit_phase(Phase::Warm, &from_start[..=split], &y[..=split])?;
    let Ok(cool) = fit_phase(Phase::Cool, &since(&t[split..]), &y[split..]) else {
        return Ok(only_warm("the samples after the best split are flat".to_string()));
    };
    match cool_down_undetermined(&whole, &warm, &cool, &since(&t[split..])) {
        Some(why) => Ok(only_warm(why)),
        None => Ok(ThermalFit {
            warm,
            cool: Some(cool),
            split_min: from_start[split],
            split: Split::Fitted,
            no_cool_down: None,
        }),
    }
}

/// Times from the first of `t`.
fn since(t: &[f64]) -> Vec<f64> {
    t.iter().map(|&ti| ti - t[0]).collect()
}

/// The residual sum of squares of both curves fitted with the warm-up ending at sample `k`
/// (shared by both: the cool-down's time starts there). Near its best τ a phase's sum of
/// squares is flat, so τ to 1e-6 of itself is enough to compare splits.
fn split_rss(t: &[f64], y: &[f64], k: usize) -> f64 {
    let warm = best_tau(Phase::Warm, &t[..=k], &y[..=k], 1e-6).map_or(f64::INFINITY, |(_, rss)| rss);
    let cool = best_tau(Phase::Cool, &since(&t[k..]), &y[k..], 1e-6).map_or(f64::INFINITY, |(_, rss)| rss);
    warm + cool
}

/// The sample in `low..=high` that leaves the least of `rss`, by a search that narrows the
/// interval by a third a step (the sum of squares falls to the split and rises after it).
fn narrowest(rss: impl Fn(usize) -> f64, low: usize, high: usize) -> usize {
    let (mut a, mut b) = (low, high.max(low));
    while b - a > 3 {
        let third = (b - a) / 3;
        let (m1, m2) = (a + third, b - third);
        if rss(m1) <= rss(m2) { b = m2 } else { a = m1 }
    }
    (a..=b).map(|k| (k, rss(k))).min_by(|p, q| p.1.total_cmp(&q.1)).map_or(a, |(k, _)| k)
}

/// The sample at which the warm-up ends, by least squares: a grid of splits over the log
/// thinned to `THINNED` samples, narrowed on the thinned log between the best one's grid
/// neighbours, then on the whole log between the best one's thinned neighbours. `None` when
/// the log is too short for two phases.
fn best_split(t: &[f64], y: &[f64]) -> Option<usize> {
    let n = t.len();
    let (first, last) = (PHASE_SAMPLES - 1, n.checked_sub(PHASE_SAMPLES)?);
    if first >= last {
        return None;
    }
    let stride = n.div_ceil(THINNED).max(1);
    let thin: Vec<usize> = (0..n).step_by(stride).collect();
    let (tt, yt): (Vec<f64>, Vec<f64>) = thin.iter().map(|&i| (t[i], y[i])).unzip();
    let full = |k: usize| split_rss(t, y, k);
    let (thin_first, thin_last) = (first.div_ceil(stride), thin.len().saturating_sub(PHASE_SAMPLES));
    if thin_first >= thin_last {
        return Some(narrowest(full, first, last));
    }
    let thinned = |j: usize| split_rss(&tt, &yt, j);
    let count = SPLIT_GRID.min(thin_last - thin_first + 1);
    let grid: Vec<usize> = (0..count).map(|g| thin_first + (thin_last - thin_first) * g / (count - 1).max(1)).collect();
    let best = (0..count).map(|g| (g, thinned(grid[g]))).min_by(|p, q| p.1.total_cmp(&q.1)).map(|(g, _)| g)?;
    let j = narrowest(thinned, grid[best.saturating_sub(1)], grid[(best + 1).min(count - 1)]);
    let (low, high) = (thin[j.saturating_sub(1)].max(first), thin[(j + 1).min(thin.len() - 1)].min(last));
    Some(narrowest(full, low, high))
}

/// Why a fitted cool-down is not one the log shows, if it is not (the module's
/// documentation): the two curves against one warm-up curve over the whole log (`whole`),
/// and the cool-down's own parameters. `cool_t` are its times from the split.
fn cool_down_undetermined(
    whole: &FirstOrderFit,
    warm: &FirstOrderFit,
    cool: &FirstOrderFit,
    cool_t: &[f64],
) -> Option<String> {
    let rss = |f: &FirstOrderFit| f.rms * f.rms * f.samples as f64;
    let n = whole.samples;
    // The split's curves spend four more parameters: a gain, a τ, an offset and the split.
    let added = 4;
    let (rss_whole, rss_split) = (rss(whole), rss(warm) + rss(cool));
    let (_, p) = f_test(rss_whole, rss_split, added, n.saturating_sub(3 + added));
    let delta_bic = n as f64 * (rss_split.max(f64::MIN_POSITIVE) / rss_whole.max(f64::MIN_POSITIVE)).ln()
        + added as f64 * (n as f64).ln();
    if !(p < ALPHA && delta_bic < -BIC_MARGIN) {
        return Some(format!(
            "a cool-down curve does not improve on one warm-up curve over the whole log (p = {p:.1e}, ΔBIC = {delta_bic:.1})"
        ));
    }
    if cool.gain * warm.gain <= 0.0 {
        return Some("after the best split the log moves on the way it warmed, not back".to_string());
    }
    if short_of(cool.gain.abs(), DETERMINED_SIGMAS * cool.gain_sigma) {
        return Some(format!(
            "the cool-down's gain {:.3e} ± {:.1e} is within {DETERMINED_SIGMAS} σ of zero",
            cool.gain, cool.gain_sigma
        ));
    }
    let (low, high) = tau_range(cool_t)?;
    if cool.tau_min <= low * 1.01 || cool.tau_min >= high / 1.01 {
        return Some(format!(
            "the cool-down's τ {:.3} min lies at an end of what its {:.1} min can show",
            cool.tau_min,
            cool_t[cool_t.len() - 1]
        ));
    }
    if short_of(cool.tau_min, SEARCHED_SIGMAS * cool.tau_sigma) {
        return Some(format!(
            "the cool-down's τ {:.3} ± {:.2} min is within {SEARCHED_SIGMAS} σ of zero",
            cool.tau_min, cool.tau_sigma
        ));
    }
    None
}

#[cfg(test)]
mod tests;
