//! Fitting every candidate of the catalogue to the residual and choosing among them
//! (metrology notes §3.1).
//!
//! Each candidate is fitted jointly with the base: the set-up terms, the points excluded as
//! outliers, and the effects found in earlier iterations, whose linear parameters are
//! refitted beside it (and, for the best candidates, their searched parameters too:
//! `refine`). Its own searched parameter (τ, decay, pitch) is chosen on a grid and refined
//! by golden section. A candidate is scored by the drop in the residual sum of squares it
//! buys: the nested F-test for its parameters (searched ones counted) and the change in
//! BIC. It is significant when both agree (p < `ALPHA`, ΔBIC < −`BIC_MARGIN`), its fitted
//! values lie within the catalogue's physical bounds, and its parameters are
//! **determined** (`determine`): each linear parameter (a cyclic error's amplitude) at
//! least `DETERMINED_SIGMAS` standard uncertainties from zero, and a searched one inside its
//! search range, not at an end of it, and at least `SEARCHED_SIGMAS` uncertainties from
//! zero.
//!
//! An effect the model already has is a candidate too (`stale`): refitted from nothing with
//! the rest of the model as it is (its searched parameter keeps the model's value: a
//! screw's lead or a time constant is the machine's), scored against the model with its
//! value as written, and determined when its value moved by at least `DETERMINED_SIGMAS`
//! (the Mahalanobis distance of the change, for a pair of parameters).
//!
//! Two candidates are **confounded** when they explain the same part of the residual
//! (their fitted signatures correlate above `ALIKE`) about as well (their BIC within
//! `BIC_MARGIN`): the data cannot say which it is, and the workflow says so instead of
//! picking one.

use nalgebra::DMatrix;

use super::candidates::{Extents, Reach, SHAPES, Search, Shape};
use super::forward::{Forward, Simulation};
use super::lsq::{self, Base, ColumnFit};
use crate::error_model::{Effect, ErrorModel};
use crate::machine::ScrewPitch;

/// Significance level of the nested F-test.
pub const ALPHA: f64 = 1e-3;
/// A BIC difference of 10 is "very strong" evidence (Kass and Raftery).
pub const BIC_MARGIN: f64 = 10.0;
/// Signatures correlated above this are the same shape.
pub const ALIKE: f64 = 0.9;
/// A linear parameter (or the change of a stale one) closer to zero than this many
/// standard uncertainties is not determined by the data. For a single parameter the F-test
/// at `ALPHA` already asks 3.3; five asks that the value be known to 20 %.
pub const DETERMINED_SIGMAS: f64 = 5.0;
/// A searched parameter (τ, decay, pitch) must be at least this many standard
/// uncertainties from zero: known to within a half of itself.
pub const SEARCHED_SIGMAS: f64 = 2.0;
/// A probe that moves no reading by more than this (mm) shows no signature.
const NO_SIGNATURE_MM: f64 = 1e-9;

/// What one candidate's fit gave.
#[derive(Debug, Clone, PartialEq)]
pub enum Status {
    /// Fitted, within bounds.
    Fitted,
    /// The effect does not move this measurement's readings at all.
    NoSignature,
    /// Its signature is one the set-up terms or the effects found already make.
    Aliased,
    /// The best fit lies outside the physical bounds.
    OutOfBounds(String),
    /// The fit is significant but a parameter is not determined by the data.
    Undetermined(String),
}

/// A stale candidate: an effect of the model refitted.
#[derive(Debug, Clone, PartialEq)]
pub struct Stale {
    /// Its index in the working model's effects.
    pub index: usize,
    /// The effect as the model has it.
    pub old: Effect,
    /// Its linear parameters as the model has them (in the fit's terms).
    pub old_linear: Vec<f64>,
}

/// A found effect refitted beside a candidate: its searched parameter searched again.
#[derive(Debug, Clone, PartialEq)]
pub struct Refit {
    /// Its index among the effects found.
    pub found: usize,
    pub linear: Vec<f64>,
    pub searched: f64,
}

/// A candidate's best fit and its scores.
#[derive(Debug, Clone)]
pub struct Candidate {
    pub shape: &'static Shape,
    pub status: Status,
    pub linear: Vec<f64>,
    /// The searched parameter (NaN when the shape has none).
    pub searched: f64,
    /// The searched parameter was given (a pitch from the machine settings, or a stale
    /// effect's own), not fitted.
    pub searched_fixed: bool,
    /// The searched parameter's best value lies at an end of its search range.
    pub searched_at_end: bool,
    pub columns: Vec<Vec<f64>>,
    pub rss: f64,
    /// The parameters the fit spent (searched ones included).
    pub parameters: usize,
    pub delta_rss: f64,
    pub f: f64,
    pub p_value: f64,
    pub delta_bic: f64,
    pub signature: Vec<f64>,
    /// The covariance of its parameters (linear, then the searched one when fitted), once
    /// the fit was found significant.
    pub covariance: Option<DMatrix<f64>>,
    /// The model's own effect this candidate refits.
    pub stale: Option<Stale>,
    /// Found effects whose searched parameter moved beside this candidate.
    pub refits: Vec<Refit>,
}

impl Candidate {
    pub fn effect(&self) -> Effect {
        self.shape.build(&self.linear, self.searched)
    }

    /// Significant by both tests and within bounds (its parameters may still be
    /// undetermined).
    pub fn passes_tests(&self) -> bool {
        self.p_value < ALPHA && self.delta_bic < -BIC_MARGIN
    }

    pub fn significant(&self) -> bool {
        self.status == Status::Fitted && self.passes_tests()
    }

    /// The kind's name, and ` (stale)` for an effect of the model refitted.
    pub fn label(&self) -> String {
        match self.stale {
            Some(_) => format!("{} (stale)", self.shape.name()),
            None => self.shape.name().to_string(),
        }
    }
}

/// Everything a candidate is fitted against in one iteration.
pub struct Context<'a> {
    pub forward: &'a Forward,
    /// The current model (the working model and the effects found so far).
    pub model: &'a ErrorModel,
    pub simulation: &'a Simulation,
    pub extents: Extents,
    /// The reach of the measured points: spans of x, z and time.
    pub reach: Reach,
    pub pitch: ScrewPitch,
    pub base: Base,
    /// Measured − simulated, before the base is taken off.
    pub residual: Vec<f64>,
    pub residual_perp: Vec<f64>,
    pub rss0: f64,
    /// The residual sum of squares a candidate must improve on: `rss0`, or for a stale
    /// candidate (fitted on the model without the effect) the current model's.
    pub rss_reference: f64,
    /// The points that count (the outliers excluded): for the BIC's n.
    pub kept: usize,
}

impl Context<'_> {
    fn n(&self) -> usize {
        self.residual_perp.len()
    }

    /// The columns of `shape` at the searched value, and the largest reading change of
    /// its probes.
    pub fn columns(&self, shape: &Shape, searched: f64) -> (Vec<Vec<f64>>, f64) {
        let probes = shape.probes(&self.extents);
        let mut largest: f64 = 0.0;
        let columns = probes
            .iter()
            .enumerate()
            .map(|(i, &probe)| {
                let effect = shape.unit(i, probe, searched);
                let response = self.forward.response(self.model, self.simulation, &effect);
                largest = response.iter().fold(largest, |m, r| m.max(r.abs()));
                response.iter().map(|r| r / probe).collect()
            })
            .collect();
        (columns, largest)
    }

    fn fit_at(&self, shape: &Shape, searched: f64) -> Option<(ColumnFit, Vec<Vec<f64>>)> {
        let (columns, _) = self.columns(shape, searched);
        lsq::fit_columns(&self.base, &self.residual_perp, &columns).map(|fit| (fit, columns))
    }

    /// The given value of the searched parameter, if the settings give it.
    fn given(&self, shape: &Shape) -> Option<f64> {
        match shape.search {
            Search::PitchX => self.pitch.x,
            Search::PitchZ => self.pitch.z,
            Search::None | Search::Tau | Search::Decay => None,
        }
    }

    /// Fit one candidate of the catalogue.
    pub fn fit(&self, shape: &'static Shape) -> Candidate {
        self.fit_with(shape, self.given(shape), None)
    }

    /// Refit the model's own effect `stale` (the context's model lacks it): its searched
    /// parameter keeps the model's value.
    pub fn fit_stale(&self, shape: &'static Shape, searched: f64, stale: Stale) -> Candidate {
        let fixed = if shape.search == Search::None { None } else { Some(searched) };
        self.fit_with(shape, fixed, Some(stale))
    }

    fn fit_with(&self, shape: &'static Shape, given: Option<f64>, stale: Option<Stale>) -> Candidate {
        let mut candidate = Candidate {
            shape,
            status: Status::NoSignature,
            linear: vec![0.0; shape.linear.len()],
            searched: f64::NAN,
            searched_fixed: given.is_some(),
            searched_at_end: false,
            columns: Vec::new(),
            rss: self.rss_reference,
            parameters: shape.linear.len(),
            delta_rss: 0.0,
            f: 0.0,
            p_value: 1.0,
            delta_bic: 0.0,
            signature: vec![0.0; self.n()],
            covariance: None,
            stale,
            refits: Vec::new(),
        };
        // Where the signature is looked for: the searched parameter's grid (or its given
        // value), or nowhere for a shape without one.
        let searched = match (shape.search, given) {
            (Search::None, _) => f64::NAN,
            (_, Some(value)) => value,
            _ => match self.search(shape) {
                Some((value, at_end)) => {
                    candidate.parameters += 1;
                    candidate.searched_at_end = at_end;
                    value
                }
                None => return candidate,
            },
        };
        candidate.searched = searched;
        let (mut columns, largest) = self.columns(shape, searched);
        if largest < NO_SIGNATURE_MM {
            return candidate;
        }
        let Some(mut fit) = lsq::fit_columns(&self.base, &self.residual_perp, &columns) else {
            candidate.status = Status::Aliased;
            return candidate;
        };
        if shape.secant {
            // The play holds the slide across a reversal, so the readings are not quite
            // linear in it: take the column again at the fitted value.
            for _ in 0..3 {
                let value = fit.coefficients[0];
                if value.abs() < 1e-5 || shape.build(&[value], searched).out_of_bounds(&self.extents).is_some() {
                    break;
                }
                let response = self.forward.response(self.model, self.simulation, &shape.build(&[value], searched));
                let secant = vec![response.iter().map(|r| r / value).collect::<Vec<f64>>()];
                let Some(next) = lsq::fit_columns(&self.base, &self.residual_perp, &secant) else { break };
                let settled = (next.coefficients[0] - value).abs() < 1e-3 * value.abs();
                fit = next;
                columns = secant;
                if settled {
                    break;
                }
            }
        }
        candidate.linear = fit.coefficients.clone();
        candidate.columns = columns;
        candidate.signature = fit.signature;
        self.score(&mut candidate, fit.rss);
        candidate.status = match candidate.effect().out_of_bounds(&self.extents) {
            Some(why) => Status::OutOfBounds(why),
            None => Status::Fitted,
        };
        self.determine(&mut candidate);
        candidate
    }

    /// The F-test and ΔBIC of a fit that leaves `rss`, against the reference.
    fn score(&self, candidate: &mut Candidate, rss: f64) {
        candidate.rss = rss;
        candidate.delta_rss = self.rss_reference - rss;
        let dof = self.n().saturating_sub(self.base.rank() + candidate.parameters);
        let (f, p) = lsq::f_test(self.rss_reference, rss, candidate.parameters, dof);
        candidate.f = f;
        candidate.p_value = p;
        candidate.delta_bic = self.kept as f64 * (rss.max(f64::MIN_POSITIVE) / self.rss_reference).ln()
            + candidate.parameters as f64 * (self.kept as f64).ln();
    }

    /// Whether a candidate that passes the tests has its parameters determined (see the
    /// module's documentation); its covariance is kept for the report.
    fn determine(&self, candidate: &mut Candidate) {
        if candidate.status != Status::Fitted || !candidate.passes_tests() {
            return;
        }
        let mut columns = candidate.columns.clone();
        if let Some(derivative) = self.searched_derivative(candidate) {
            columns.push(derivative);
        }
        let projected: Vec<Vec<f64>> = columns.iter().map(|c| self.base.residual_of(c)).collect();
        let dof = self.n().saturating_sub(self.base.rank() + projected.len());
        let sigma2 = candidate.rss / dof.max(1) as f64;
        candidate.covariance = lsq::covariance(&projected, sigma2);
        if let Some(why) = undetermined(candidate) {
            candidate.status = Status::Undetermined(why);
        }
    }

    /// The best value of the searched parameter, and whether it lies at an end of the
    /// search range: the grid, then golden section between the best point's neighbours (on
    /// log τ or decay; on frequency for a pitch).
    fn search(&self, shape: &Shape) -> Option<(f64, bool)> {
        let (low, high, points) = shape.search_range(&self.reach)?;
        let (u_low, u_high, step) = search_variable(shape.search, low, high, points);
        let rss = |u: f64| self.fit_at(shape, value_of(shape.search, u)).map_or(f64::INFINITY, |(fit, _)| fit.rss);
        let grid: Vec<f64> = (0..points).map(|k| u_low + step * k as f64).collect();
        let scores: Vec<f64> = grid.iter().map(|&u| rss(u)).collect();
        let best = scores.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1)).map(|(k, _)| k)?;
        if !scores[best].is_finite() {
            return None;
        }
        let (a, b) = ((grid[best] - step).max(u_low), (grid[best] + step).min(u_high));
        // 25 steps narrow the bracket to 1e-5 of a grid step.
        let refined = lsq::golden_minimum(rss, a, b, 25, 1e-6 * step.abs().max(1e-12));
        let u = if rss(refined) <= scores[best] { refined } else { grid[best] };
        let at_end = (u - u_low).abs() < step / 2.0 || (u_high - u).abs() < step / 2.0;
        Some((value_of(shape.search, u), at_end))
    }

    /// The change of the fitted readings with the searched parameter (for its
    /// uncertainty), by central differences on its scale.
    pub fn searched_derivative(&self, candidate: &Candidate) -> Option<Vec<f64>> {
        if candidate.searched_fixed || !candidate.searched.is_finite() {
            return None;
        }
        Some(self.signature_derivative(candidate.shape, &candidate.linear, candidate.searched))
    }

    /// The change of `Σ linear[k]·column_k` with the searched parameter at `searched`.
    pub fn signature_derivative(&self, shape: &Shape, linear: &[f64], searched: f64) -> Vec<f64> {
        let h = 1e-3 * searched;
        let at = |value: f64| -> Vec<f64> {
            let (columns, _) = self.columns(shape, value);
            let mut out = vec![0.0; self.n()];
            for (column, b) in columns.iter().zip(linear) {
                out.iter_mut().zip(column).for_each(|(o, c)| *o += b * c);
            }
            out
        };
        let (plus, minus) = (at(searched + h), at(searched - h));
        plus.iter().zip(&minus).map(|(p, m)| (p - m) / (2.0 * h)).collect()
    }

    /// Search again the searched parameter of a found effect beside `candidate`: the found
    /// effect is taken out of the residual (`contribution`, its current part of the
    /// readings), its columns are fitted jointly with the candidate's at each trial value
    /// on `base_without` (the base less its columns), and the value that leaves the least
    /// is kept when it improves on the candidate's fit.
    pub fn refine(&self, candidate: &mut Candidate, found: &FoundFit<'_>, base_without: &Base) {
        if candidate.columns.is_empty() {
            return;
        }
        let Some((low, high, points)) = found.shape.search_range(&self.reach) else { return };
        let (u_low, u_high, step) = search_variable(found.shape.search, low, high, points);
        let residual: Vec<f64> = self.residual.iter().zip(found.contribution).map(|(r, c)| r + c).collect();
        let residual_perp = base_without.residual_of(&residual);
        let fit = |u: f64| -> Option<ColumnFit> {
            let (own, _) = self.columns(found.shape, value_of(found.shape.search, u));
            let mut columns = candidate.columns.clone();
            columns.extend(own);
            lsq::fit_columns(base_without, &residual_perp, &columns)
        };
        let u_now = variable_of(found.shape.search, found.searched);
        let (a, b) = ((u_now - step).max(u_low), (u_now + step).min(u_high));
        let u = lsq::golden_minimum(|u| fit(u).map_or(f64::INFINITY, |f| f.rss), a, b, 25, 1e-6 * step.abs());
        let Some(best) = fit(u) else { return };
        if best.rss.partial_cmp(&candidate.rss) != Some(std::cmp::Ordering::Less) {
            return;
        }
        let own = candidate.linear.len();
        candidate.linear = best.coefficients[..own].to_vec();
        candidate.refits.retain(|r| r.found != found.index);
        candidate.refits.push(Refit {
            found: found.index,
            linear: best.coefficients[own..].to_vec(),
            searched: value_of(found.shape.search, u),
        });
        // What the candidate itself explains, for telling it from others.
        let projected: Vec<Vec<f64>> = candidate.columns.iter().map(|c| base_without.residual_of(c)).collect();
        let mut signature = vec![0.0; self.n()];
        for (p, c) in projected.iter().zip(&candidate.linear) {
            signature.iter_mut().zip(p).for_each(|(s, x)| *s += c * x);
        }
        candidate.signature = signature;
        self.score(candidate, best.rss);
        candidate.status = match candidate.effect().out_of_bounds(&self.extents) {
            Some(why) => Status::OutOfBounds(why),
            None => Status::Fitted,
        };
        candidate.covariance = None;
        self.determine(candidate);
    }
}

/// A found effect with a searched parameter, as `Context::refine` takes it.
pub struct FoundFit<'a> {
    pub index: usize,
    pub shape: &'static Shape,
    pub searched: f64,
    /// Its part of the current simulated readings.
    pub contribution: &'a [f64],
}

/// The search variable's range and grid step: frequency for a pitch, the logarithm for τ
/// and decay.
fn search_variable(search: Search, low: f64, high: f64, points: usize) -> (f64, f64, f64) {
    let (u_low, u_high) = (variable_of(search, high).min(variable_of(search, low)), {
        variable_of(search, high).max(variable_of(search, low))
    });
    (u_low, u_high, (u_high - u_low) / (points.max(2) - 1) as f64)
}

fn is_pitch(search: Search) -> bool {
    matches!(search, Search::PitchX | Search::PitchZ)
}

fn variable_of(search: Search, value: f64) -> f64 {
    if is_pitch(search) { 1.0 / value } else { value.ln() }
}

fn value_of(search: Search, u: f64) -> f64 {
    if is_pitch(search) { 1.0 / u } else { u.exp() }
}

/// Why a candidate's parameters are not determined, if they are not.
fn undetermined(candidate: &Candidate) -> Option<String> {
    undetermined_values(
        candidate.shape,
        &candidate.linear,
        candidate.searched,
        candidate.searched_fixed,
        candidate.searched_at_end,
        candidate.covariance.as_ref()?,
        candidate.stale.as_ref().map(|s| s.old_linear.as_slice()),
    )
}

/// Why fitted values are not determined by the data, if they are not (the module's
/// documentation): `covariance` is that of the linear parameters, then the searched one
/// when fitted; `old_linear` the model's values of a stale effect.
pub fn undetermined_values(
    shape: &Shape,
    linear: &[f64],
    searched: f64,
    searched_fixed: bool,
    searched_at_end: bool,
    covariance: &DMatrix<f64>,
    old_linear: Option<&[f64]>,
) -> Option<String> {
    let m = linear.len();
    if covariance.nrows() < m {
        return None;
    }
    if let Some(old) = old_linear {
        // The change from the model's value, against the uncertainty of the new one.
        let delta: Vec<f64> = linear.iter().zip(old).map(|(a, b)| a - b).collect();
        let block = covariance.view((0, 0), (m, m)).into_owned();
        let distance = mahalanobis(&delta, &block)?;
        return (distance < DETERMINED_SIGMAS)
            .then(|| format!("the change is {distance:.1} standard uncertainties, below {DETERMINED_SIGMAS}"));
    }
    if m == 2 {
        // A cyclic error: its amplitude, from the sine and cosine parts.
        let (a, b) = (linear[0], linear[1]);
        let amp = a.hypot(b);
        let variance = (a * a * covariance[(0, 0)] + b * b * covariance[(1, 1)] + 2.0 * a * b * covariance[(0, 1)])
            / (amp * amp).max(f64::MIN_POSITIVE);
        let sigma = variance.max(0.0).sqrt();
        if short_of(amp, DETERMINED_SIGMAS * sigma) {
            return Some(format!("amp {amp:.2e} ± {sigma:.1e} is within {DETERMINED_SIGMAS} σ of zero"));
        }
    } else {
        for (i, value) in linear.iter().enumerate() {
            let sigma = covariance[(i, i)].max(0.0).sqrt();
            if short_of(value.abs(), DETERMINED_SIGMAS * sigma) {
                return Some(format!(
                    "{} {value:.2e} ± {sigma:.1e} is within {DETERMINED_SIGMAS} σ of zero",
                    shape.linear.get(i).copied().unwrap_or("?")
                ));
            }
        }
    }
    if !searched_fixed && searched.is_finite() {
        let name = shape.search.parameter().unwrap_or("?");
        if searched_at_end {
            return Some(format!("{name} {searched:.4} lies at an end of what the data can show"));
        }
        let sigma = covariance.get((m, m)).map_or(f64::NAN, |v| v.max(0.0).sqrt());
        if short_of(searched.abs(), SEARCHED_SIGMAS * sigma) {
            return Some(format!("{name} {searched:.4} ± {sigma:.2} is within {SEARCHED_SIGMAS} σ of zero"));
        }
    }
    None
}

/// `value < bound`, and true when either is NaN: a value not known to clear the bound.
pub fn short_of(value: f64, bound: f64) -> bool {
    value.partial_cmp(&bound).is_none_or(std::cmp::Ordering::is_lt)
}

/// `sqrt(δᵀ C⁻¹ δ)`; `None` for a singular `C`.
pub fn mahalanobis(delta: &[f64], covariance: &DMatrix<f64>) -> Option<f64> {
    let inverse = covariance.clone().try_inverse()?;
    let d = nalgebra::DVector::from_column_slice(delta);
    Some((d.transpose() * inverse * &d)[(0, 0)].max(0.0).sqrt())
}

/// Fit every kind of the catalogue not in `exclude`, best (lowest ΔBIC) first.
pub fn rank(context: &Context<'_>, exclude: &[&str]) -> Vec<Candidate> {
    let mut out: Vec<Candidate> =
        SHAPES.iter().filter(|s| !exclude.contains(&s.name())).map(|s| context.fit(s)).collect();
    sort(&mut out);
    out
}

/// Best (lowest ΔBIC) first, those whose parameters the data do not determine among them
/// (their status says so); those not fitted last.
pub fn sort(candidates: &mut [Candidate]) {
    candidates.sort_by(|a, b| {
        let key = |c: &Candidate| match c.status {
            Status::Fitted | Status::Undetermined(_) => c.delta_bic,
            _ => f64::INFINITY,
        };
        key(a).total_cmp(&key(b)).then(b.delta_rss.total_cmp(&a.delta_rss))
    });
}

/// The correlation of two signatures.
pub fn alike(a: &[f64], b: &[f64]) -> f64 {
    let dot: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    let na: f64 = a.iter().map(|x| x * x).sum::<f64>().sqrt();
    let nb: f64 = b.iter().map(|x| x * x).sum::<f64>().sqrt();
    if na == 0.0 || nb == 0.0 { 0.0 } else { dot / (na * nb) }
}

/// The candidates that cannot be told apart from the best one (the best first); just the
/// best when it stands alone. Empty when nothing is significant. A rival whose parameters
/// the data do not determine still counts: it fits the residual alike (a cyclic error read
/// at a spacing near its pitch trades its amplitude for its pitch), so choosing the best
/// would be a guess.
pub fn contenders(ranked: &[Candidate]) -> Vec<&Candidate> {
    let Some(best) = ranked.iter().find(|c| c.significant()) else { return Vec::new() };
    let mut out = vec![best];
    for other in ranked {
        let rival = match other.status {
            Status::Fitted => true,
            Status::Undetermined(_) => other.passes_tests(),
            _ => false,
        };
        if std::ptr::eq(other, best) || !rival {
            continue;
        }
        if other.delta_bic - best.delta_bic < BIC_MARGIN && alike(&best.signature, &other.signature).abs() > ALIKE {
            out.push(other);
        }
    }
    out
}
