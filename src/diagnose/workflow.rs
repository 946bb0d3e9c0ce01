//! The iteration: simulate, remove the set-up terms and the outliers, rank the candidates
//! (the catalogue's kinds the model lacks, and the model's own effects refitted as stale
//! values), add or update the winner with its fitted parameters, refit the model's found
//! effects jointly, re-test the earlier ones, simulate again — until the residual is at the
//! noise floor or no candidate is significant (or the best ones cannot be told apart).
//! What is left above the noise then is said plainly, with the measured table that would
//! hold it (`unexplained.rs`).
//!
//! The noise floor is estimated from the data themselves: the high-frequency part of the
//! residual, from the differences of neighbouring points along the path
//! (`σ = 1.4826 · median |Δr| / √2`, the median so that the few steps of a backlash or a
//! corner do not count). A smooth systematic error hardly changes from one point to the
//! next, so it hardly enters.
//!
//! **Outliers** (ball bar and CMM points), by a robust rule: a point whose residual departs
//! from the median of its four nearest neighbours along the path (or of three of them: one
//! may be a glitch too) by more than `OUTLIER_SIGMAS` standard deviations of such a
//! departure (`√1.5 σ`, σ the noise floor above: a median of absolute differences, which a
//! few glitches do not move), while those neighbours agree with each other within half
//! that departure — a glitch of one or two readings, not a step, a corner or a decaying
//! spike, which neighbours share. Points within `REVERSAL_ZONE_MM`
//! after an axis reversal are not screened (a reversal spike can show at one point). It is
//! judged on the residual of the current model at every iteration, excluded from the fits
//! (a column of its own in the base) and listed with its line in the file. A table's values
//! are means of runs at a few targets, which no neighbour can judge: they are not screened.

use nalgebra::DMatrix;
use serde::Serialize;

use super::advice::separate_by;
use super::breakdown::REVERSAL_ZONE_MM;
use super::candidates::{Extents, Reach, SHAPES, Shape};
use super::forward::{Forward, ForwardError, Nominal, Simulation};
use super::lsq::{self, Base};
use super::measured::{Kind, Measured};
use super::select::{self, Candidate, Context, FoundFit, Stale, Status};
use super::unexplained::{self, Unexplained, peak_kept, rms_kept};
use crate::error_model::{Effect, ErrorModel};

/// A residual RMS within this factor of the noise floor is at the floor.
pub const NOISE_MARGIN: f64 = 1.05;
/// A point departing from its neighbours by more than this many standard deviations of
/// such a departure is an outlier: with a thousand points of normal noise, one in two
/// thousand such measurements would flag a sound point.
pub const OUTLIER_SIGMAS: f64 = 5.0;
/// How many of the best candidates have the found effects' searched parameters searched
/// again beside them.
const REFINED: usize = 6;

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
/// the machine settings (or, for a stale effect, kept from the model); `previous` is the
/// model's value of a stale effect's parameter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Param {
    pub name: String,
    pub value: f64,
    pub sigma: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub previous: Option<f64>,
}

/// One candidate's line in a ranking.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Ranked {
    pub effect: &'static str,
    /// An effect of the working model refitted (its value stale), not a kind it lacks.
    pub stale: bool,
    /// `significant`, `not significant`, `not determined: …`, `no signature`, `aliased` or
    /// `out of bounds: …`.
    pub status: String,
    /// The share of the residual sum of squares it explains, %.
    pub explained_percent: f64,
    pub delta_bic: f64,
    pub p_value: f64,
    pub params: Vec<Param>,
}

impl Ranked {
    /// The kind, with ` (stale)` for an effect of the model refitted.
    pub fn label(&self) -> String {
        if self.stale { format!("{} (stale)", self.effect) } else { self.effect.to_string() }
    }
}

/// A found effect whose searched parameter moved when a later one was added beside it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Refitted {
    pub effect: &'static str,
    pub param: &'static str,
    pub before: f64,
    pub after: f64,
}

/// An effect found earlier that a later addition left insignificant, and so removed (a
/// stale update reverted to the model's value).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Dropped {
    pub effect: &'static str,
    pub stale: bool,
    pub p_value: f64,
    pub delta_bic: f64,
    pub reason: String,
}

/// One iteration: the effect added (or the stale value updated) and the gap before and
/// after.
#[derive(Debug, Clone, PartialEq)]
pub struct Iteration {
    pub effect: Effect,
    /// The model's own effect when this iteration updated its stale value.
    pub stale: Option<Effect>,
    pub params: Vec<Param>,
    pub rms_before_mm: f64,
    pub rms_after_mm: f64,
    pub peak_before_mm: f64,
    pub peak_after_mm: f64,
    pub f: f64,
    pub p_value: f64,
    pub delta_bic: f64,
    pub ranking: Vec<Ranked>,
    pub refitted: Vec<Refitted>,
    pub dropped: Vec<Dropped>,
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
    /// No candidate is significant and determined.
    NothingSignificant,
    /// The best candidates cannot be told apart.
    Confounded,
    IterationLimit,
}

/// A point excluded as an outlier.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Outlier {
    /// Its index among the measured points.
    pub point: usize,
    /// Its line in the measurement file.
    pub line: usize,
    /// Its residual (set-up removed) on the final model, mm.
    pub residual_mm: f64,
    /// How far it departs from its neighbours, in noise standard deviations.
    pub sigmas: f64,
}

/// An effect found, with its final parameters and their uncertainties.
#[derive(Debug, Clone, PartialEq)]
pub struct Added {
    pub effect: Effect,
    pub params: Vec<Param>,
}

/// A stale value of the working model and what the data give for it.
#[derive(Debug, Clone, PartialEq)]
pub struct Update {
    /// Its index in the working model's effects.
    pub index: usize,
    pub old: Effect,
    pub new: Effect,
    pub params: Vec<Param>,
}

/// The outcome of the workflow.
#[derive(Debug, Clone)]
pub struct Diagnosis {
    pub forward: Forward,
    /// The rows of the measurement's file (`Measured::rows`).
    pub rows: usize,
    pub noise_floor_mm: f64,
    /// The residual (measured − simulated, set-up removed) before anything was added, and
    /// after the last addition; an outlier's value is its own residual, and it counts in no
    /// figure.
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
    /// The effects found, in the order they were added, with their final (jointly
    /// refitted) parameters.
    pub added: Vec<Added>,
    /// The working model's effects whose stale values were updated.
    pub updated: Vec<Update>,
    /// The points excluded as outliers, in file order.
    pub outliers: Vec<Outlier>,
    /// Whether each point counts (not an outlier).
    pub kept: Vec<bool>,
    /// A significant residual no catalogued effect explains.
    pub unexplained: Option<Unexplained>,
    /// The working model with the effects found and the stale values updated.
    pub model: ErrorModel,
}

impl Diagnosis {
    pub fn rms_before_mm(&self) -> f64 {
        rms_kept(&self.residual_before, &self.kept)
    }

    pub fn rms_after_mm(&self) -> f64 {
        rms_kept(&self.residual_after, &self.kept)
    }

    pub fn peak_before_mm(&self) -> f64 {
        peak_kept(&self.residual_before, &self.kept)
    }

    pub fn peak_after_mm(&self) -> f64 {
        peak_kept(&self.residual_after, &self.kept)
    }
}

/// An effect found (or a stale one updated): its shape and fitted values.
#[derive(Debug, Clone)]
struct Found {
    shape: &'static Shape,
    linear: Vec<f64>,
    searched: f64,
    /// The searched parameter was not fitted (given by the settings or kept from the model).
    searched_fixed: bool,
    /// The working model's effect it updates (a stale value), by index.
    replaces: Option<usize>,
    /// The working model's value of that effect, and its linear parameters in the fit's
    /// terms.
    old: Option<(Effect, Vec<f64>)>,
}

impl Found {
    fn effect(&self) -> Effect {
        self.shape.build(&self.linear, self.searched)
    }

    /// The parameters it spends (its searched one when fitted).
    fn parameters(&self) -> usize {
        self.linear.len() + usize::from(!self.searched_fixed && self.searched.is_finite())
    }

    fn has_free_search(&self) -> bool {
        !self.searched_fixed && self.searched.is_finite()
    }
}

/// The working model with the found effects: stale values replaced in place, new effects
/// appended.
fn with_found(model: &ErrorModel, found: &[Found]) -> ErrorModel {
    let mut out = model.clone();
    for f in found {
        match f.replaces {
            Some(index) => out.effects[index] = f.effect(),
            None => out.effects.push(f.effect()),
        }
    }
    out
}

fn shape_of(effect: &Effect) -> &'static Shape {
    let kind = effect.kind();
    SHAPES.iter().find(|s| s.kind == kind).unwrap_or(&SHAPES[0])
}

/// Measured − simulated.
fn difference(measured: &[f64], simulation: &Simulation) -> Vec<f64> {
    measured.iter().zip(&simulation.readings).map(|(m, s)| m - s).collect()
}

/// A column that is one at point `i` and zero elsewhere: the point taken out of the fits.
fn indicator(n: usize, i: usize) -> Vec<f64> {
    let mut column = vec![0.0; n];
    column[i] = 1.0;
    column
}

/// The columns of `columns` that are independent of those before them.
fn independent(columns: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let base = Base::new(columns);
    columns.iter().zip(&base.kept).filter(|(_, k)| **k).map(|(c, _)| c.clone()).collect()
}

/// What each iteration fits against: the measurement's forward model and readings.
struct Setting<'a> {
    forward: &'a Forward,
    nominal: &'a Nominal,
    measured: Vec<f64>,
    setup: Vec<Vec<f64>>,
    order: Vec<Vec<usize>>,
    screen_outliers: bool,
}

impl Setting<'_> {
    fn context<'m>(
        &'m self,
        model: &'m ErrorModel,
        simulation: &'m Simulation,
        base: Base,
        kept: &[bool],
        rss_reference: Option<f64>,
    ) -> Context<'m> {
        let residual = difference(&self.measured, simulation);
        let residual_perp = base.residual_of(&residual);
        let rss0 = residual_perp.iter().map(|r| r * r).sum();
        Context {
            forward: self.forward,
            model,
            simulation,
            extents: Extents::of(&simulation.states),
            reach: Reach::of(&simulation.states, kept),
            pitch: self.nominal.screw_pitch,
            base,
            residual,
            residual_perp,
            rss0,
            rss_reference: rss_reference.unwrap_or(rss0),
            kept: kept.iter().filter(|k| **k).count(),
        }
    }

    /// The set-up columns and an indicator for each outlier.
    fn fixed_columns(&self, outliers: &[usize]) -> Vec<Vec<f64>> {
        let n = self.measured.len();
        let mut columns = self.setup.clone();
        columns.extend(outliers.iter().map(|&i| indicator(n, i)));
        columns
    }

    /// The outliers of the model whose simulation is `simulation`, and the noise floor.
    fn screen(&self, simulation: &Simulation) -> (Vec<usize>, f64) {
        let residual = Base::new(&self.setup).residual_of(&difference(&self.measured, simulation));
        let noise = noise_floor(&residual, &self.order);
        let mut outliers = if self.screen_outliers { find_outliers(&residual, &self.order, noise) } else { Vec::new() };
        // A reversal spike may show at one point only, right after the reversal: a
        // systematic error, not a glitch.
        outliers.retain(|&i| {
            simulation
                .states
                .get(i)
                .is_none_or(|s| s.since_reversal.x >= REVERSAL_ZONE_MM && s.since_reversal.z >= REVERSAL_ZONE_MM)
        });
        (outliers, noise)
    }
}

fn kept_mask(n: usize, outliers: &[usize]) -> Vec<bool> {
    let mut kept = vec![true; n];
    for &i in outliers {
        kept[i] = false;
    }
    kept
}

/// The found effects refitted jointly (their linear parameters, one Gauss–Newton step on
/// the residual off the fixed columns), and the covariance of each one's parameters
/// (linear, then its searched one when fitted).
struct Joint {
    model: ErrorModel,
    simulation: Simulation,
    covariances: Vec<Option<DMatrix<f64>>>,
    /// The residual sum of squares off the fixed columns and every found effect's.
    rss: f64,
    rank: usize,
}

fn joint_refit(setting: &Setting<'_>, model: &ErrorModel, found: &mut [Found], fixed: &[Vec<f64>]) -> Joint {
    let fixed_base = Base::new(fixed);
    let kept = vec![true; setting.measured.len()];
    let mut current = with_found(model, found);
    let mut simulation = setting.forward.simulate(&current);
    if !found.is_empty() {
        let ctx = setting.context(&current, &simulation, Base::default(), &kept, None);
        let columns: Vec<Vec<f64>> = found.iter().flat_map(|f| ctx.columns(f.shape, f.searched).0).collect();
        let projected: Vec<Vec<f64>> = columns.iter().map(|c| fixed_base.residual_of(c)).collect();
        let residual = fixed_base.residual_of(&ctx.residual);
        if let Some((deltas, _, _)) = lsq::solve(&projected, &residual) {
            let mut slot = 0;
            for f in found.iter_mut() {
                for value in &mut f.linear {
                    *value += deltas[slot];
                    slot += 1;
                }
            }
            current = with_found(model, found);
            simulation = setting.forward.simulate(&current);
        }
    }
    // The covariance at the refitted values.
    let ctx = setting.context(&current, &simulation, Base::default(), &kept, None);
    let mut columns: Vec<Vec<f64>> = Vec::new();
    let mut owners: Vec<(usize, usize)> = Vec::new();
    for (k, f) in found.iter().enumerate() {
        for column in ctx.columns(f.shape, f.searched).0 {
            owners.push((k, columns.len()));
            columns.push(column);
        }
    }
    let mut all = fixed.to_vec();
    all.extend(columns.iter().cloned());
    let base = Base::new(&all);
    let residual = base.residual_of(&ctx.residual);
    let rss: f64 = residual.iter().map(|r| r * r).sum();
    for (k, f) in found.iter().enumerate() {
        if f.has_free_search() {
            owners.push((k, columns.len()));
            columns.push(ctx.signature_derivative(f.shape, &f.linear, f.searched));
        }
    }
    let projected: Vec<Vec<f64>> = columns.iter().map(|c| fixed_base.residual_of(c)).collect();
    let dof = setting.measured.len().saturating_sub(base.rank() + usize::from(!projected.is_empty()));
    let sigma2 = rss / dof.max(1) as f64;
    let whole = lsq::covariance(&projected, sigma2);
    let covariances = (0..found.len())
        .map(|k| {
            let whole = whole.as_ref()?;
            let mine: Vec<usize> = owners.iter().filter(|(owner, _)| *owner == k).map(|(_, i)| *i).collect();
            Some(DMatrix::from_fn(mine.len(), mine.len(), |a, b| whole[(mine[a], mine[b])]))
        })
        .collect();
    Joint { model: current, simulation, covariances, rss, rank: base.rank() }
}

/// Run the workflow on `measured` taken on the program `nominal`, starting from `model`.
pub fn diagnose(
    nominal: &Nominal,
    measured: &Measured,
    model: &ErrorModel,
    options: &Options,
) -> Result<Diagnosis, ForwardError> {
    let forward = Forward::new(nominal, measured)?;
    let setting = Setting {
        forward: &forward,
        nominal,
        measured: forward.measured(),
        setup: forward.setup_columns(),
        order: path_order(&forward),
        screen_outliers: matches!(forward.kind, Kind::BallBar | Kind::Profile),
    };
    let n = setting.measured.len();

    let mut found: Vec<Found> = Vec::new();
    // Kinds dropped by a re-test are not offered again; nor is a stale value once reverted.
    let mut dropped_kinds: Vec<&'static str> = Vec::new();
    let mut reverted: Vec<usize> = Vec::new();
    let mut current = model.clone();
    let simulated_before = forward.simulate(&current);
    let mut simulation = simulated_before.clone();
    let mut iterations = Vec::new();
    let mut confounded = Vec::new();
    let mut last_ranking = Vec::new();
    let mut stop = Stop::IterationLimit;

    for _ in 0..options.max_iterations {
        let (outliers, noise) = setting.screen(&simulation);
        let kept = kept_mask(n, &outliers);
        let fixed = independent(&setting.fixed_columns(&outliers));
        let fixed_residual = Base::new(&fixed).residual_of(&difference(&setting.measured, &simulation));
        let (rms_before, peak_before) = (rms_kept(&fixed_residual, &kept), peak_kept(&fixed_residual, &kept));

        // The base: the fixed columns, then the columns of every effect found, refitted
        // beside each candidate.
        let probe = setting.context(&current, &simulation, Base::default(), &kept, None);
        let found_columns: Vec<Vec<Vec<f64>>> = found.iter().map(|f| probe.columns(f.shape, f.searched).0).collect();
        let base_with = |skip: Option<usize>| {
            let mut columns = fixed.clone();
            for (k, own) in found_columns.iter().enumerate() {
                if Some(k) != skip {
                    columns.extend(own.iter().cloned());
                }
            }
            Base::new(&columns)
        };
        let ctx = setting.context(&current, &simulation, base_with(None), &kept, None);
        let rss_now = ctx.rss0;

        // The found effects whose searched parameter is searched again beside the best
        // candidates: each one's part of the readings, and the base without it.
        let contributions: Vec<Vec<f64>> = found
            .iter()
            .zip(&found_columns)
            .map(|(f, columns)| {
                let mut out = vec![0.0; n];
                for (column, b) in columns.iter().zip(&f.linear) {
                    out.iter_mut().zip(column).for_each(|(o, c)| *o += b * c);
                }
                out
            })
            .collect();
        let refinable: Vec<(usize, Base)> = found
            .iter()
            .enumerate()
            .filter(|(_, f)| f.has_free_search())
            .map(|(k, _)| (k, base_with(Some(k))))
            .collect();
        let refine = |ctx: &Context<'_>, candidate: &mut Candidate| {
            for (k, base_without) in &refinable {
                let fit = FoundFit {
                    index: *k,
                    shape: found[*k].shape,
                    searched: found[*k].searched,
                    contribution: &contributions[*k],
                };
                ctx.refine(candidate, &fit, base_without);
            }
        };

        let mut exclude: Vec<&str> = current.effects.iter().map(Effect::name).collect();
        exclude.extend(dropped_kinds.iter().copied());
        let mut ranked = select::rank(&ctx, &exclude);
        if !refinable.is_empty() {
            for candidate in ranked.iter_mut().filter(|c| refinable_status(c)).take(REFINED) {
                refine(&ctx, candidate);
            }
        }
        // The working model's own effects, refitted as stale values.
        for (index, effect) in model.effects.iter().enumerate() {
            if found.iter().any(|f| f.replaces == Some(index)) || reverted.contains(&index) {
                continue;
            }
            let shape = shape_of(effect);
            let Some((old_linear, searched)) = shape.values_of(effect) else { continue };
            let mut without = current.clone();
            without.effects.remove(index);
            let simulated = forward.simulate(&without);
            let stale_ctx = setting.context(&without, &simulated, ctx.base.clone(), &kept, Some(rss_now));
            let mut candidate = stale_ctx.fit_stale(shape, searched, Stale { index, old: effect.clone(), old_linear });
            if !refinable.is_empty() && refinable_status(&candidate) {
                refine(&stale_ctx, &mut candidate);
            }
            ranked.push(candidate);
        }
        select::sort(&mut ranked);
        let contenders = select::contenders(&ranked);
        let ranking: Vec<Ranked> = ranked.iter().map(|c| ranked_line(c, rss_now)).collect();
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
                effects: contenders.iter().map(|c| c.label()).collect(),
                separate_by: separate_by(&effects, forward.kind),
            });
            stop = Stop::Confounded;
            last_ranking = ranking;
            break;
        }
        let winner = contenders[0].clone();
        let mut refitted = Vec::new();
        for r in &winner.refits {
            let f = &mut found[r.found];
            refitted.push(Refitted {
                effect: f.shape.name(),
                param: f.shape.search.parameter().unwrap_or("?"),
                before: f.searched,
                after: r.searched,
            });
            f.linear = r.linear.clone();
            f.searched = r.searched;
        }
        found.push(Found {
            shape: winner.shape,
            linear: winner.linear.clone(),
            searched: winner.searched,
            searched_fixed: winner.searched_fixed,
            replaces: winner.stale.as_ref().map(|s| s.index),
            old: winner.stale.as_ref().map(|s| (s.old.clone(), s.old_linear.clone())),
        });
        let mut joint = joint_refit(&setting, model, &mut found, &fixed);
        // Re-test the earlier ones: each must still earn its place beside the others.
        let mut dropped = Vec::new();
        while let Some((k, record)) = weakest(&setting, model, &found, &fixed, &joint, &kept) {
            if let Some(index) = found[k].replaces {
                reverted.push(index);
            } else {
                dropped_kinds.push(found[k].shape.name());
            }
            found.remove(k);
            dropped.push(record);
            joint = joint_refit(&setting, model, &mut found, &fixed);
        }
        let last = found.len() - 1;
        let params = describe_found(&found[last], joint.covariances[last].as_ref());
        current = joint.model;
        simulation = joint.simulation;
        let after = Base::new(&fixed).residual_of(&difference(&setting.measured, &simulation));
        iterations.push(Iteration {
            effect: found[last].effect(),
            stale: winner.stale.as_ref().map(|s| s.old.clone()),
            params,
            rms_before_mm: rms_before,
            rms_after_mm: rms_kept(&after, &kept),
            peak_before_mm: peak_before,
            peak_after_mm: peak_kept(&after, &kept),
            f: winner.f,
            p_value: winner.p_value,
            delta_bic: winner.delta_bic,
            ranking,
            refitted,
            dropped,
        });
    }

    let (outlier_points, noise_floor_mm) = setting.screen(&simulation);
    let kept = kept_mask(n, &outlier_points);
    let fixed = independent(&setting.fixed_columns(&outlier_points));
    // The found effects' final values and uncertainties: jointly refitted beside the final
    // set-up and outlier columns.
    let joint = joint_refit(&setting, model, &mut found, &fixed);
    let current = joint.model;
    let simulation = joint.simulation;
    let params: Vec<Vec<Param>> =
        found.iter().zip(&joint.covariances).map(|(f, covariance)| describe_found(f, covariance.as_ref())).collect();
    let fixed_base = Base::new(&fixed);
    let setup_base = Base::new(&setting.setup);
    let with_outliers = |simulation: &Simulation| {
        let difference = difference(&setting.measured, simulation);
        let mut residual = fixed_base.residual_of(&difference);
        let own = setup_base.residual_of(&difference);
        for &i in &outlier_points {
            residual[i] = own[i];
        }
        residual
    };
    let residual_before = with_outliers(&simulated_before);
    let residual_after = with_outliers(&simulation);
    let setup_residual = setup_base.residual_of(&difference(&setting.measured, &simulation));
    let outliers = outlier_points
        .iter()
        .map(|&i| Outlier {
            point: i,
            line: measured.line(i),
            residual_mm: residual_after[i],
            sigmas: departure_sigmas(&setup_residual, &setting.order, i, noise_floor_mm),
        })
        .collect();
    let updated = found
        .iter()
        .zip(&params)
        .filter_map(|(f, params)| {
            let index = f.replaces?;
            Some(Update { index, old: model.effects[index].clone(), new: f.effect(), params: params.clone() })
        })
        .collect();
    let added = found
        .iter()
        .zip(&params)
        .filter(|(f, _)| f.replaces.is_none())
        .map(|(f, params)| Added { effect: f.effect(), params: params.clone() })
        .collect();
    let unexplained = if matches!(stop, Stop::NothingSignificant | Stop::IterationLimit)
        && rms_kept(&residual_after, &kept) > unexplained::ABOVE_NOISE * noise_floor_mm
    {
        let found_columns: Vec<Vec<f64>> = {
            let probe = setting.context(&current, &simulation, Base::default(), &kept, None);
            found.iter().flat_map(|f| probe.columns(f.shape, f.searched).0).collect()
        };
        let mut base_columns = fixed.clone();
        base_columns.extend(found_columns);
        Some(unexplained::analyse(&unexplained::Inputs {
            forward: &forward,
            model: &current,
            simulation: &simulation,
            measured: &setting.measured,
            base: Base::new(&base_columns),
            residual: &residual_after,
            kept: &kept,
            noise_floor_mm,
        }))
    } else {
        None
    };
    Ok(Diagnosis {
        rows: measured.rows(),
        noise_floor_mm,
        residual_before,
        residual_after,
        simulated_before,
        simulated_after: simulation,
        iterations,
        confounded,
        stop,
        last_ranking,
        added,
        updated,
        outliers,
        kept,
        unexplained,
        model: current,
        forward,
    })
}

/// Whether a candidate is worth searching the found effects again beside: one that is
/// fitted and explains something.
fn refinable_status(candidate: &Candidate) -> bool {
    matches!(candidate.status, Status::Fitted | Status::Undetermined(_)) && candidate.delta_bic < 0.0
}

/// The found effect (the one added last excepted) that no longer earns its place beside
/// the others, the least significant first: the residual without it against the residual
/// with it, by the F-test and ΔBIC, and its parameters' determination.
fn weakest(
    setting: &Setting<'_>,
    model: &ErrorModel,
    found: &[Found],
    fixed: &[Vec<f64>],
    joint: &Joint,
    kept: &[bool],
) -> Option<(usize, Dropped)> {
    let count = kept.iter().filter(|k| **k).count();
    let mut worst: Option<(usize, Dropped)> = None;
    for k in 0..found.len().saturating_sub(1) {
        let f = &found[k];
        let others: Vec<Found> = found.iter().enumerate().filter(|(j, _)| *j != k).map(|(_, f)| f.clone()).collect();
        let without = with_found(model, &others);
        let simulation = setting.forward.simulate(&without);
        let ctx = setting.context(&without, &simulation, Base::default(), kept, None);
        let mut columns = fixed.to_vec();
        for other in &others {
            columns.extend(ctx.columns(other.shape, other.searched).0);
        }
        let residual = Base::new(&columns).residual_of(&ctx.residual);
        let rss_without: f64 = residual.iter().map(|r| r * r).sum();
        let parameters = f.parameters();
        let dof = setting.measured.len().saturating_sub(joint.rank + usize::from(f.has_free_search()));
        let (_, p_value) = lsq::f_test(rss_without, joint.rss, parameters, dof);
        let delta_bic = count as f64 * (joint.rss.max(f64::MIN_POSITIVE) / rss_without.max(f64::MIN_POSITIVE)).ln()
            + parameters as f64 * (count as f64).ln();
        let reason = if p_value >= select::ALPHA || delta_bic >= -select::BIC_MARGIN {
            Some(format!("p = {p_value:.1e}, ΔBIC = {delta_bic:.1} beside the others"))
        } else {
            joint.covariances[k].as_ref().and_then(|c| {
                select::undetermined_values(
                    f.shape,
                    &f.linear,
                    f.searched,
                    f.searched_fixed,
                    false,
                    c,
                    f.old.as_ref().map(|(_, old)| old.as_slice()),
                )
            })
        };
        let Some(reason) = reason else { continue };
        if worst.as_ref().is_none_or(|(_, w)| p_value > w.p_value) {
            worst =
                Some((k, Dropped { effect: f.shape.name(), stale: f.replaces.is_some(), p_value, delta_bic, reason }));
        }
    }
    worst
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

/// How the point at position `j` of `sequence` departs from its neighbours along the path,
/// and the standard deviation of that departure in units of the noise: its residual less
/// the median of its four nearest neighbours in the sequence (two each side, or the four
/// on one side at an end), or of three of them (one may be a glitch too), when those
/// neighbours agree with each other — their range under half the departure. `√1.5`
/// between neighbours, `√2` at an end. `None` when no such set of neighbours agrees (a
/// step, a corner, or a spike that decays over several points) or the sequence is shorter
/// than five points.
fn departure(residual: &[f64], sequence: &[usize], j: usize) -> Option<(f64, f64)> {
    if sequence.len() < 5 {
        return None;
    }
    let start = j.saturating_sub(2).min(sequence.len() - 5);
    let neighbours: Vec<f64> = (start..start + 5).filter(|&k| k != j).map(|k| residual[sequence[k]]).collect();
    let x = residual[sequence[j]];
    let scale = if start + 2 == j { 1.5f64.sqrt() } else { std::f64::consts::SQRT_2 };
    // All four, then each three; the first that agrees.
    let sets = std::iter::once(neighbours.clone())
        .chain((0..4).map(|skip| neighbours.iter().enumerate().filter(|(k, _)| *k != skip).map(|(_, v)| *v).collect()));
    sets.filter_map(|mut set: Vec<f64>| {
        set.sort_by(f64::total_cmp);
        let m = set.len();
        let median = if m % 2 == 1 { set[m / 2] } else { (set[m / 2 - 1] + set[m / 2]) / 2.0 };
        let e = x - median;
        (set[m - 1] - set[0] < e.abs() / 2.0).then_some((e, scale))
    })
    .next()
}

/// The outliers of `residual` (see the module's documentation), in point order.
pub fn find_outliers(residual: &[f64], order: &[Vec<usize>], noise: f64) -> Vec<usize> {
    if noise <= 0.0 {
        return Vec::new();
    }
    let mut out: Vec<usize> = order
        .iter()
        .flat_map(|sequence| {
            (0..sequence.len()).filter_map(move |j| {
                departure(residual, sequence, j)
                    .is_some_and(|(e, scale)| e.abs() > OUTLIER_SIGMAS * scale * noise)
                    .then_some(sequence[j])
            })
        })
        .collect();
    out.sort_unstable();
    out
}

/// How far point `i` departs from its neighbours, in noise standard deviations.
fn departure_sigmas(residual: &[f64], order: &[Vec<usize>], i: usize, noise: f64) -> f64 {
    order
        .iter()
        .find_map(|sequence| sequence.iter().position(|&p| p == i).map(|j| (sequence, j)))
        .and_then(|(sequence, j)| departure(residual, sequence, j))
        .map_or(f64::NAN, |(e, scale)| e.abs() / (scale * noise).max(f64::MIN_POSITIVE))
}

fn status_text(candidate: &Candidate) -> String {
    match &candidate.status {
        Status::Fitted if candidate.significant() => "significant".to_string(),
        Status::Fitted => "not significant".to_string(),
        Status::NoSignature => "no signature in this measurement".to_string(),
        Status::Aliased => "aliased with the set-up or the effects found".to_string(),
        Status::OutOfBounds(why) => format!("out of bounds: {why}"),
        Status::Undetermined(why) => format!("not determined: {why}"),
    }
}

fn ranked_line(candidate: &Candidate, rss0: f64) -> Ranked {
    Ranked {
        effect: candidate.shape.name(),
        stale: candidate.stale.is_some(),
        status: status_text(candidate),
        explained_percent: if rss0 > 0.0 { 100.0 * candidate.delta_rss / rss0 } else { 0.0 },
        delta_bic: candidate.delta_bic,
        p_value: candidate.p_value,
        params: if matches!(candidate.status, Status::Fitted | Status::OutOfBounds(_) | Status::Undetermined(_)) {
            describe(
                candidate.shape,
                &candidate.linear,
                candidate.searched,
                candidate.searched_fixed,
                candidate.covariance.as_ref(),
                candidate.stale.as_ref().map(|s| &s.old),
            )
        } else {
            Vec::new()
        },
    }
}

fn describe_found(f: &Found, covariance: Option<&DMatrix<f64>>) -> Vec<Param> {
    describe(f.shape, &f.linear, f.searched, f.searched_fixed, covariance, f.old.as_ref().map(|(old, _)| old))
}

/// The effect's parameters as the model file names them, with uncertainties from the
/// covariance of the linear parameters (then the searched one), and for a stale effect
/// the model's values. A cyclic error's amplitude and phase come from its sine and cosine
/// parts by the usual propagation.
fn describe(
    shape: &Shape,
    linear: &[f64],
    searched: f64,
    searched_fixed: bool,
    covariance: Option<&DMatrix<f64>>,
    old: Option<&Effect>,
) -> Vec<Param> {
    let var = |i: usize| covariance.and_then(|c| c.get((i, i)).copied()).map(|v| v.max(0.0).sqrt());
    let searched_sigma = if searched_fixed { None } else { var(linear.len()) };
    let previous = |name: &str| -> Option<f64> {
        let fields = serde_json::to_value(old?).ok()?;
        match name.strip_suffix("[0]") {
            Some(array) => fields.get(array)?.get(0)?.as_f64(),
            None => fields.get(name)?.as_f64(),
        }
    };
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
        out.push(Param { name: "amp".into(), value: amp, sigma: sigma(amp_sigma), previous: previous("amp") });
        out.push(Param {
            name: "pitch".into(),
            value: searched,
            sigma: searched_sigma.filter(|_| covariance.is_some()),
            previous: previous("pitch"),
        });
        out.push(Param { name: "phase".into(), value: phase, sigma: sigma(phase_sigma), previous: previous("phase") });
        return out;
    }
    for (i, name) in shape.linear.iter().enumerate() {
        out.push(Param { name: name.to_string(), value: linear[i], sigma: var(i), previous: previous(name) });
    }
    if let Some(searched_name) = shape.search.parameter()
        && searched.is_finite()
    {
        out.push(Param {
            name: searched_name.into(),
            value: searched,
            sigma: searched_sigma,
            previous: previous(searched_name),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glitches_are_outliers_and_a_step_or_a_decaying_spike_is_not() {
        let noise = 0.001;
        let quiet = |k: usize| 0.0002 * ((k * 7919 % 13) as f64 / 13.0 - 0.5);
        let mut residual: Vec<f64> = (0..80).map(quiet).collect();
        residual[10] += 0.03; // a glitch
        residual[20] -= 0.03; // two glitches in a row
        residual[21] += 0.025;
        for (k, value) in residual.iter_mut().enumerate().skip(30) {
            *value += 0.02; // a step at 30
            if k >= 45 {
                *value += 0.03 * (-((k - 45) as f64) / 4.0).exp(); // a spike decaying from 45
            }
        }
        residual[79] -= 0.03; // a glitch at the end
        let order = vec![(0..80).collect::<Vec<usize>>()];
        assert_eq!(find_outliers(&residual, &order, noise), vec![10, 20, 21, 79]);
    }
}
