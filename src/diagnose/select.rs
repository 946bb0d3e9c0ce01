//! Fitting every candidate of the catalogue to the residual and choosing among them
//! (metrology notes §3.1).
//!
//! Each candidate is fitted jointly with the base: the set-up terms and the effects found
//! in earlier iterations, whose linear parameters are refitted beside it. Its searched
//! parameter (τ, decay, pitch) is chosen on a grid and refined by golden section. A
//! candidate is scored by the drop in the residual sum of squares it buys: the nested
//! F-test for its parameters (searched ones counted) and the change in BIC. It is
//! significant when both agree (p < `ALPHA`, ΔBIC < −`BIC_MARGIN`) and its fitted values
//! lie within the catalogue's physical bounds.
//!
//! Two candidates are **confounded** when they explain the same part of the residual
//! (their fitted signatures correlate above `ALIKE`) about as well (their BIC within
//! `BIC_MARGIN`): the data cannot say which it is, and the workflow says so instead of
//! picking one.

use nalgebra::DMatrix;

use super::candidates::{Extents, SHAPES, Search, Shape};
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
}

/// A candidate's best fit and its scores.
#[derive(Debug, Clone)]
pub struct Candidate {
    pub shape: &'static Shape,
    pub status: Status,
    pub linear: Vec<f64>,
    /// The searched parameter (NaN when the shape has none).
    pub searched: f64,
    /// The searched parameter was given (a pitch from the machine settings), not fitted.
    pub searched_fixed: bool,
    pub columns: Vec<Vec<f64>>,
    pub rss: f64,
    /// The parameters the fit spent (searched ones included).
    pub parameters: usize,
    pub delta_rss: f64,
    pub f: f64,
    pub p_value: f64,
    pub delta_bic: f64,
    pub signature: Vec<f64>,
}

impl Candidate {
    pub fn effect(&self) -> Effect {
        self.shape.build(&self.linear, self.searched)
    }

    pub fn significant(&self) -> bool {
        self.status == Status::Fitted && self.p_value < ALPHA && self.delta_bic < -BIC_MARGIN
    }
}

/// Everything a candidate is fitted against in one iteration.
pub struct Context<'a> {
    pub forward: &'a Forward,
    /// The current model (the working model and the effects found so far).
    pub model: &'a ErrorModel,
    pub simulation: &'a Simulation,
    pub extents: Extents,
    /// The span of x and of z the measured points cover, mm.
    pub span: (f64, f64),
    pub pitch: ScrewPitch,
    pub base: Base,
    pub residual_perp: Vec<f64>,
    pub rss0: f64,
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

    /// Fit one candidate.
    pub fn fit(&self, shape: &'static Shape) -> Candidate {
        let given = self.given(shape);
        let mut candidate = Candidate {
            shape,
            status: Status::NoSignature,
            linear: vec![0.0; shape.linear.len()],
            searched: f64::NAN,
            searched_fixed: given.is_some(),
            columns: Vec::new(),
            rss: self.rss0,
            parameters: shape.linear.len(),
            delta_rss: 0.0,
            f: 0.0,
            p_value: 1.0,
            delta_bic: 0.0,
            signature: vec![0.0; self.n()],
        };
        // Where the signature is looked for: the searched parameter's grid (or its given
        // value), or nowhere for a shape without one.
        let searched = match (shape.search, given) {
            (Search::None, _) => f64::NAN,
            (_, Some(value)) => value,
            _ => match self.search(shape) {
                Some(value) => {
                    candidate.parameters += 1;
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
        candidate.rss = fit.rss;
        candidate.delta_rss = self.rss0 - fit.rss;
        let dof = self.n().saturating_sub(self.base.rank() + candidate.parameters);
        let (f, p) = lsq::f_test(self.rss0, fit.rss, candidate.parameters, dof);
        candidate.f = f;
        candidate.p_value = p;
        candidate.delta_bic = self.n() as f64 * (fit.rss.max(f64::MIN_POSITIVE) / self.rss0).ln()
            + candidate.parameters as f64 * (self.n() as f64).ln();
        candidate.signature = fit.signature;
        candidate.status = match candidate.effect().out_of_bounds(&self.extents) {
            Some(why) => Status::OutOfBounds(why),
            None => Status::Fitted,
        };
        candidate
    }

    /// The best value of the searched parameter: the grid, then golden section between
    /// the best point's neighbours (on log τ or decay; on frequency for a pitch).
    fn search(&self, shape: &Shape) -> Option<f64> {
        let (low, high, points) = shape.search_range(self.span.0, self.span.1)?;
        let pitch = matches!(shape.search, Search::PitchX | Search::PitchZ);
        // The search variable u and the parameter at u.
        let (u_low, u_high) = if pitch { (1.0 / high, 1.0 / low) } else { (low.ln(), high.ln()) };
        let value = |u: f64| if pitch { 1.0 / u } else { u.exp() };
        let rss = |u: f64| self.fit_at(shape, value(u)).map_or(f64::INFINITY, |(fit, _)| fit.rss);
        let step = (u_high - u_low) / (points - 1) as f64;
        let grid: Vec<f64> = (0..points).map(|k| u_low + step * k as f64).collect();
        let scores: Vec<f64> = grid.iter().map(|&u| rss(u)).collect();
        let best = scores.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1)).map(|(k, _)| k)?;
        if !scores[best].is_finite() {
            return None;
        }
        let (a, b) = ((grid[best] - step).max(u_low), (grid[best] + step).min(u_high));
        // 25 steps narrow the bracket to 1e-5 of a grid step.
        let refined = lsq::golden_minimum(rss, a, b, 25, 1e-6 * step.abs().max(1e-12));
        Some(value(if rss(refined) <= scores[best] { refined } else { grid[best] }))
    }

    /// The change of the fitted readings with the searched parameter (for its
    /// uncertainty), by central differences on its scale.
    pub fn searched_derivative(&self, candidate: &Candidate) -> Option<Vec<f64>> {
        if candidate.searched_fixed || !candidate.searched.is_finite() {
            return None;
        }
        let h = 1e-3 * candidate.searched;
        let at = |value: f64| -> Vec<f64> {
            let (columns, _) = self.columns(candidate.shape, value);
            let mut out = vec![0.0; self.n()];
            for (column, b) in columns.iter().zip(&candidate.linear) {
                out.iter_mut().zip(column).for_each(|(o, c)| *o += b * c);
            }
            out
        };
        let (plus, minus) = (at(candidate.searched + h), at(candidate.searched - h));
        Some(plus.iter().zip(&minus).map(|(p, m)| (p - m) / (2.0 * h)).collect())
    }
}

/// Fit every kind of the catalogue not in `exclude`, best (lowest ΔBIC) first.
pub fn rank(context: &Context<'_>, exclude: &[&str]) -> Vec<Candidate> {
    let mut out: Vec<Candidate> =
        SHAPES.iter().filter(|s| !exclude.contains(&s.name())).map(|s| context.fit(s)).collect();
    out.sort_by(|a, b| {
        let key = |c: &Candidate| if c.status == Status::Fitted { c.delta_bic } else { f64::INFINITY };
        key(a).total_cmp(&key(b)).then(b.delta_rss.total_cmp(&a.delta_rss))
    });
    out
}

/// The correlation of two signatures.
pub fn alike(a: &[f64], b: &[f64]) -> f64 {
    let dot: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    let na: f64 = a.iter().map(|x| x * x).sum::<f64>().sqrt();
    let nb: f64 = b.iter().map(|x| x * x).sum::<f64>().sqrt();
    if na == 0.0 || nb == 0.0 { 0.0 } else { dot / (na * nb) }
}

/// The candidates that cannot be told apart from the best one (the best first); just the
/// best when it stands alone. Empty when nothing is significant.
pub fn contenders(ranked: &[Candidate]) -> Vec<&Candidate> {
    let Some(best) = ranked.iter().find(|c| c.significant()) else { return Vec::new() };
    let mut out = vec![best];
    for other in ranked {
        if std::ptr::eq(other, best) || other.status != Status::Fitted {
            continue;
        }
        if other.delta_bic - best.delta_bic < BIC_MARGIN && alike(&best.signature, &other.signature).abs() > ALIKE {
            out.push(other);
        }
    }
    out
}

/// The joint fit of the winner with the set-up terms and the effects found before:
/// the base columns' coefficients (zero for a dependent one), and the covariance of the
/// winner's parameters (its linear ones, then its searched one when fitted).
pub struct Joint {
    pub base_coefficients: Vec<f64>,
    pub covariance: DMatrix<f64>,
}

pub fn joint(
    base_columns: &[Vec<f64>],
    base: &Base,
    candidate: &Candidate,
    searched_column: Option<Vec<f64>>,
    residual: &[f64],
) -> Option<Joint> {
    let kept: Vec<usize> = (0..base_columns.len()).filter(|&i| base.kept.get(i).copied().unwrap_or(false)).collect();
    let mut columns: Vec<Vec<f64>> = kept.iter().map(|&i| base_columns[i].clone()).collect();
    columns.extend(candidate.columns.iter().cloned());
    let own = candidate.columns.len() + usize::from(searched_column.is_some());
    columns.extend(searched_column);
    let (coefficients, covariance, _) = lsq::solve(&columns, residual)?;
    let mut base_coefficients = vec![0.0; base_columns.len()];
    for (slot, &i) in kept.iter().enumerate() {
        base_coefficients[i] = coefficients[slot];
    }
    let first = kept.len();
    let covariance = covariance.view((first, first), (own, own)).into_owned();
    Some(Joint { base_coefficients, covariance })
}
