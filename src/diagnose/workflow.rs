//! The iteration: simulate, remove the set-up terms, rank the candidates, add the winner
//! with its fitted parameters, simulate again, until the residual is at the noise floor
//! or no candidate is significant (or the best ones cannot be told apart).
//!
//! The noise floor is estimated from the data themselves: the high-frequency part of the
//! residual, from the differences of neighbouring points along the path
//! (`σ = 1.4826 · median |Δr| / √2`, the median so that the few steps of a backlash or a
//! corner do not count). A smooth systematic error hardly changes from one point to the
//! next, so it hardly enters.

use serde::Serialize;

use super::advice::separate_by;
use super::candidates::{Extents, Shape};
use super::forward::{Forward, ForwardError, Nominal, Simulation};
use super::lsq::Base;
use super::measured::Measured;
use super::select::{self, Candidate, Context, Status};
use crate::error_model::{Effect, ErrorModel};

/// A residual RMS within this factor of the noise floor is at the floor.
pub const NOISE_MARGIN: f64 = 1.05;

/// How far the workflow may go.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    pub max_iterations: usize,
}

impl Default for Options {
    fn default() -> Options {
        Options { max_iterations: 6 }
    }
}

/// A fitted parameter; `sigma` is its standard uncertainty, `None` for a value taken from
/// the machine settings.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Param {
    pub name: String,
    pub value: f64,
    pub sigma: Option<f64>,
}

/// One candidate's line in a ranking.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Ranked {
    pub effect: &'static str,
    /// `fitted`, `significant`, `no signature`, `aliased` or `out of bounds: …`.
    pub status: String,
    /// The share of the residual sum of squares it explains, %.
    pub explained_percent: f64,
    pub delta_bic: f64,
    pub p_value: f64,
    pub params: Vec<Param>,
}

/// One iteration: the effect added and the gap before and after.
#[derive(Debug, Clone, PartialEq)]
pub struct Iteration {
    pub effect: Effect,
    pub params: Vec<Param>,
    pub rms_before_mm: f64,
    pub rms_after_mm: f64,
    pub peak_before_mm: f64,
    pub peak_after_mm: f64,
    pub f: f64,
    pub p_value: f64,
    pub delta_bic: f64,
    pub ranking: Vec<Ranked>,
}

impl Iteration {
    /// How much of the RMS gap the iteration closed, %.
    pub fn shrink_percent(&self) -> f64 {
        shrink(self.rms_before_mm, self.rms_after_mm)
    }
}

pub fn shrink(before: f64, after: f64) -> f64 {
    if before > 0.0 { 100.0 * (before - after) / before } else { 0.0 }
}

/// Candidates the data cannot tell apart, and what would.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Confounded {
    pub effects: Vec<String>,
    pub separate_by: String,
}

/// Why the iteration stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Stop {
    /// The residual is at the noise floor.
    NoiseFloor,
    /// No candidate is significant.
    NothingSignificant,
    /// The best candidates cannot be told apart.
    Confounded,
    IterationLimit,
}

/// The outcome of the workflow.
#[derive(Debug, Clone)]
pub struct Diagnosis {
    pub forward: Forward,
    pub noise_floor_mm: f64,
    /// The residual (measured − simulated, set-up removed) before anything was added, and
    /// after the last addition.
    pub residual_before: Vec<f64>,
    pub residual_after: Vec<f64>,
    /// The simulated readings of the working model and of the final one.
    pub simulated_before: Simulation,
    pub simulated_after: Simulation,
    pub iterations: Vec<Iteration>,
    pub confounded: Vec<Confounded>,
    pub stop: Stop,
    /// The ranking of the last iteration, the one that added nothing.
    pub last_ranking: Vec<Ranked>,
    /// The effects found, with their final (jointly refitted) parameters.
    pub added: Vec<Effect>,
    /// The working model with the effects found.
    pub model: ErrorModel,
}

impl Diagnosis {
    pub fn rms_before_mm(&self) -> f64 {
        rms(&self.residual_before)
    }

    pub fn rms_after_mm(&self) -> f64 {
        rms(&self.residual_after)
    }

    pub fn peak_before_mm(&self) -> f64 {
        peak(&self.residual_before)
    }

    pub fn peak_after_mm(&self) -> f64 {
        peak(&self.residual_after)
    }
}

pub fn rms(values: &[f64]) -> f64 {
    if values.is_empty() { 0.0 } else { (values.iter().map(|v| v * v).sum::<f64>() / values.len() as f64).sqrt() }
}

pub fn peak(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m: f64, v| m.max(v.abs()))
}

/// An effect found: its shape and fitted values.
#[derive(Debug, Clone)]
struct Found {
    shape: &'static Shape,
    linear: Vec<f64>,
    searched: f64,
}

impl Found {
    fn effect(&self) -> Effect {
        self.shape.build(&self.linear, self.searched)
    }
}

fn with_found(model: &ErrorModel, found: &[Found]) -> ErrorModel {
    let mut out = model.clone();
    out.effects.extend(found.iter().map(Found::effect));
    out
}

/// Run the workflow on `measured` taken on the program `nominal`, starting from `model`.
pub fn diagnose(
    nominal: &Nominal,
    measured: &Measured,
    model: &ErrorModel,
    options: &Options,
) -> Result<Diagnosis, ForwardError> {
    let forward = Forward::new(nominal, measured)?;
    let measured_values = forward.measured();
    let setup = forward.setup_columns();
    let setup_base = Base::new(&setup);
    let order = path_order(&forward);
    let residual_of = |simulation: &Simulation| -> Vec<f64> {
        let r: Vec<f64> = measured_values.iter().zip(&simulation.readings).map(|(m, s)| m - s).collect();
        setup_base.residual_of(&r)
    };

    let known: Vec<&'static str> = model.effects.iter().map(Effect::name).collect();
    let mut found: Vec<Found> = Vec::new();
    let mut current = model.clone();
    let simulated_before = forward.simulate(&current);
    let mut simulation = simulated_before.clone();
    let residual_before = residual_of(&simulation);
    let mut residual = residual_before.clone();
    let mut iterations = Vec::new();
    let mut confounded = Vec::new();
    let mut last_ranking = Vec::new();
    let mut stop = Stop::IterationLimit;

    for _ in 0..options.max_iterations {
        let noise = noise_floor(&residual, &order);
        let (rms_before, peak_before) = (rms(&residual), peak(&residual));
        let extents = Extents::of(&simulation.states);
        // The base: the set-up terms, then the columns of every effect found, refitted
        // beside each candidate.
        let mut base_columns = setup.clone();
        let mut owners = Vec::new();
        let probe_context = context(&forward, &current, &simulation, extents, nominal, Base::default(), &residual);
        for (k, f) in found.iter().enumerate() {
            let (columns, _) = probe_context.columns(f.shape, f.searched);
            for (i, column) in columns.into_iter().enumerate() {
                owners.push((k, i));
                base_columns.push(column);
            }
        }
        let base = Base::new(&base_columns);
        let full_residual: Vec<f64> = measured_values.iter().zip(&simulation.readings).map(|(m, s)| m - s).collect();
        let ctx = context(&forward, &current, &simulation, extents, nominal, base, &full_residual);

        let mut exclude = known.clone();
        exclude.extend(found.iter().map(|f| f.shape.name()));
        let ranked = select::rank(&ctx, &exclude);
        let contenders = select::contenders(&ranked);
        let ranking: Vec<Ranked> = ranked.iter().map(|c| ranked_line(c, ctx.rss0)).collect();
        // At the noise floor there is nothing left to explain, whatever a test says.
        if rms_before <= NOISE_MARGIN * noise {
            stop = Stop::NoiseFloor;
            last_ranking = ranking;
            break;
        }
        if contenders.is_empty() {
            stop = Stop::NothingSignificant;
            last_ranking = ranking;
            break;
        }
        if contenders.len() > 1 {
            let effects: Vec<&str> = contenders.iter().map(|c| c.shape.name()).collect();
            confounded.push(Confounded {
                effects: effects.iter().map(|s| s.to_string()).collect(),
                separate_by: separate_by(&effects, forward.kind),
            });
            stop = Stop::Confounded;
            last_ranking = ranking;
            break;
        }
        let winner = contenders[0];
        let searched_column = ctx.searched_derivative(winner);
        let joint = select::joint(&base_columns, &ctx.base, winner, searched_column, &full_residual);
        let covariance = joint.as_ref().map(|j| j.covariance.clone());
        if let Some(joint) = &joint {
            for (slot, &(k, i)) in owners.iter().enumerate() {
                found[k].linear[i] += joint.base_coefficients[setup.len() + slot];
            }
        }
        let params = describe(winner, covariance.as_ref());
        found.push(Found { shape: winner.shape, linear: winner.linear.clone(), searched: winner.searched });
        current = with_found(model, &found);
        simulation = forward.simulate(&current);
        residual = residual_of(&simulation);
        iterations.push(Iteration {
            effect: winner.effect(),
            params,
            rms_before_mm: rms_before,
            rms_after_mm: rms(&residual),
            peak_before_mm: peak_before,
            peak_after_mm: peak(&residual),
            f: winner.f,
            p_value: winner.p_value,
            delta_bic: winner.delta_bic,
            ranking,
        });
    }
    let noise_floor_mm = noise_floor(&residual, &order);
    Ok(Diagnosis {
        noise_floor_mm,
        residual_before,
        residual_after: residual,
        simulated_before,
        simulated_after: simulation,
        iterations,
        confounded,
        stop,
        last_ranking,
        added: found.iter().map(Found::effect).collect(),
        model: current,
        forward,
    })
}

fn context<'a>(
    forward: &'a Forward,
    model: &'a ErrorModel,
    simulation: &'a Simulation,
    extents: Extents,
    nominal: &Nominal,
    base: Base,
    residual: &[f64],
) -> Context<'a> {
    let span = |f: &dyn Fn(&crate::error_model::Sample) -> f64| {
        let (lo, hi) = simulation
            .states
            .iter()
            .map(f)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
        if hi >= lo { hi - lo } else { 0.0 }
    };
    let residual_perp = base.residual_of(residual);
    let rss0 = residual_perp.iter().map(|r| r * r).sum();
    Context {
        forward,
        model,
        simulation,
        extents,
        span: (span(&|s| s.at.x), span(&|s| s.at.z)),
        pitch: nominal.screw_pitch,
        base,
        residual_perp,
        rss0,
    }
}

/// The points of each set-up group in path order (run, then sample), for differences of
/// neighbours: one sequence per group, since a table's positioning and straightness
/// readings share their places on the path.
fn path_order(forward: &Forward) -> Vec<Vec<usize>> {
    let mut order: Vec<usize> = (0..forward.len()).collect();
    let p = &forward.points;
    order.sort_by_key(|&i| (p[i].group, p[i].run, p[i].sample));
    order.chunk_by(|&a, &b| p[a].group == p[b].group).map(<[usize]>::to_vec).collect()
}

/// The noise floor: the robust spread of the differences of neighbouring residuals.
pub fn noise_floor(residual: &[f64], order: &[Vec<usize>]) -> f64 {
    let mut differences: Vec<f64> = order
        .iter()
        .flat_map(|sequence| sequence.windows(2))
        .filter_map(|w| Some((residual.get(w[1])? - residual.get(w[0])?).abs()))
        .collect();
    if differences.is_empty() {
        return 0.0;
    }
    differences.sort_by(f64::total_cmp);
    let median = differences[differences.len() / 2];
    1.4826 * median / std::f64::consts::SQRT_2
}

fn status_text(candidate: &Candidate) -> String {
    match &candidate.status {
        Status::Fitted if candidate.significant() => "significant".to_string(),
        Status::Fitted => "not significant".to_string(),
        Status::NoSignature => "no signature in this measurement".to_string(),
        Status::Aliased => "aliased with the set-up or the effects found".to_string(),
        Status::OutOfBounds(why) => format!("out of bounds: {why}"),
    }
}

fn ranked_line(candidate: &Candidate, rss0: f64) -> Ranked {
    Ranked {
        effect: candidate.shape.name(),
        status: status_text(candidate),
        explained_percent: if rss0 > 0.0 { 100.0 * candidate.delta_rss / rss0 } else { 0.0 },
        delta_bic: candidate.delta_bic,
        p_value: candidate.p_value,
        params: if candidate.status == Status::Fitted || matches!(candidate.status, Status::OutOfBounds(_)) {
            describe(candidate, None)
        } else {
            Vec::new()
        },
    }
}

/// The effect's parameters as the model file names them, with uncertainties from the
/// covariance of the linear parameters (then the searched one). A cyclic error's
/// amplitude and phase come from its sine and cosine parts by the usual propagation.
fn describe(candidate: &Candidate, covariance: Option<&nalgebra::DMatrix<f64>>) -> Vec<Param> {
    let var = |i: usize| covariance.and_then(|c| c.get((i, i)).copied()).map(|v| v.max(0.0).sqrt());
    let shape = candidate.shape;
    let linear = &candidate.linear;
    let searched_sigma = if candidate.searched_fixed { None } else { var(linear.len()) };
    let mut out = Vec::new();
    if shape.linear.len() == 2 {
        let (a, b) = (linear[0], linear[1]);
        let amp = a.hypot(b);
        let phase = b.atan2(a);
        let (saa, sbb, sab) = match covariance {
            Some(c) if c.nrows() >= 2 => (c[(0, 0)], c[(1, 1)], c[(0, 1)]),
            _ => (f64::NAN, f64::NAN, f64::NAN),
        };
        let amp_sigma = ((a * a * saa + b * b * sbb + 2.0 * a * b * sab) / (amp * amp)).max(0.0).sqrt();
        let phase_sigma = ((b * b * saa + a * a * sbb - 2.0 * a * b * sab) / amp.powi(4)).max(0.0).sqrt();
        let sigma = |s: f64| covariance.map(|_| s);
        out.push(Param { name: "amp".into(), value: amp, sigma: sigma(amp_sigma) });
        out.push(Param {
            name: "pitch".into(),
            value: candidate.searched,
            sigma: searched_sigma.filter(|_| covariance.is_some()),
        });
        out.push(Param { name: "phase".into(), value: phase, sigma: sigma(phase_sigma) });
        return out;
    }
    for (i, name) in shape.linear.iter().enumerate() {
        out.push(Param { name: name.to_string(), value: linear[i], sigma: var(i) });
    }
    if let Some(searched_name) = shape.search.parameter()
        && candidate.searched.is_finite()
    {
        out.push(Param { name: searched_name.into(), value: candidate.searched, sigma: searched_sigma });
    }
    out
}
