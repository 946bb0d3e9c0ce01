//! The inverse of the error model: the point to command for each nominal sample.
//!
//! The iteration is the thesis' eq. 2.14–2.16, solved sample by sample along the path:
//!
//! ```txt
//! U_c(1) = U_d
//! U_a(I) = U_c(I) + Δ(U_c(I))
//! U_c(I+1) = U_c(I) + γ (U_d − U_a(I))
//! ```
//!
//! With γ = 1 the first step is the thesis' mirror, `2 U_d − U_a`, and the residual then
//! shrinks by the slope of the error map per step (about 1e-4 for geometric errors), so a
//! second step usually ends it. The samples are solved in path order with one `Tracker`,
//! so each axis' direction, the travel since a reversal and the cut length are those of
//! the compensated path itself: compensation can move a reversal, and the state follows.
//! After the first sample, `U_c(1)` is `U_d` moved by the previous sample's correction,
//! which is nearer the answer and keeps the commanded path continuous inside the play.
//!
//! Backlash is the one term the plain iteration cannot invert: inside the play the slide
//! does not move whatever the command does, so the residual would only leak out by the
//! step it gains per iteration. The play part is therefore inverted exactly — to move the
//! slide up to `s`, command `s + play/2`; down, `s − play/2`; to keep it, keep the command —
//! and the iteration runs on the rest of the error. That is how a compensated path takes up
//! the backlash at a reversal: by a jump of the play in the new direction.
//!
//! A reversal costs a jump of the whole play, so it is made only for a move against the
//! slide's last direction of more than the tolerance (and never less than half the least
//! increment, which no written program can hold to: `InverseOptions::dead_band_mm`): a slide that would have to come back
//! by a few nanometres (a squareness term drifting as the other axis moves) stays where it
//! is, within the tolerance, instead of jumping across its play.

use crate::error_model::sampling::{inputs_of, t_min};
use crate::error_model::{ErrorModel, SampleInputs, Step, Tracker, without_play};
use crate::toolpath::Xz;

use super::squares::root_at_most;
use crate::error_model::sampling::PathSample;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InverseOptions {
    /// Stop when every predicted point is this close to its nominal one, mm (each sample
    /// is solved to a thousandth of it; the tolerance proper is for the re-expression).
    pub tolerance_mm: f64,
    /// A slide is reversed (its whole play taken up) only for a move against its last
    /// direction of more than this, mm: the larger of the tolerance and half the least
    /// increment, since a correction smaller than half an increment rounds away when it is
    /// written, and a reversal costs a take-up move of the whole play.
    pub dead_band_mm: f64,
    /// The gain γ of the correction.
    pub gain: f64,
    pub max_iterations: u32,
}

impl Default for InverseOptions {
    fn default() -> InverseOptions {
        InverseOptions { tolerance_mm: 0.0005, dead_band_mm: 0.0005, gain: 1.0, max_iterations: 20 }
    }
}

/// The compensated samples.
#[derive(Debug, Clone, PartialEq)]
pub struct Compensated {
    /// The point to command for each sample, mm, X as a radius.
    pub commanded: Vec<Xz>,
    /// Per sample, the backlash taken up on the way to it (`Tracker::take_up`): the
    /// command's travel inside the play where an axis reverses, zero elsewhere.
    pub take_ups: Vec<Xz>,
    /// Where the model predicts the tool goes for it, after the last pass.
    pub predicted: Vec<Xz>,
    /// Where the tool goes when the nominal path is commanded (the uncompensated error).
    pub uncompensated: Vec<Xz>,
    /// The most steps one sample took.
    pub iterations: u32,
    /// The largest |nominal − predicted|, mm.
    pub max_residual_mm: f64,
}

/// Compensate `samples` from the machine's position `start`.
pub fn compensate_samples(
    samples: &[PathSample],
    start: Xz,
    model: &ErrorModel,
    options: &InverseOptions,
) -> Compensated {
    let nominal: Vec<Xz> = samples.iter().map(|s| s.nominal).collect();
    let uncompensated = predict(samples, &nominal, start, model);
    let mut inverse = Inverse::new(start, model, options);
    let mut commanded = Vec::with_capacity(samples.len());
    let mut take_ups = Vec::with_capacity(samples.len());
    let mut predicted = Vec::with_capacity(samples.len());
    let mut terms = Vec::new();
    time_terms(samples, model, &mut terms);
    inverse.solve(samples, &terms, (&mut commanded, &mut take_ups), Some(&mut predicted));
    Compensated {
        commanded,
        take_ups,
        predicted,
        uncompensated,
        iterations: inverse.iterations,
        max_residual_mm: inverse.max_residual_mm(),
    }
}

/// The inverse solved in path order over successive runs of samples: a path solved in
/// pieces gives the same points as solved whole (`compensate_samples`).
#[derive(Debug, Clone)]
pub struct Inverse<'m> {
    model: &'m ErrorModel,
    options: InverseOptions,
    tracker: Tracker,
    /// The model's terms of time per sample (`ErrorModel::time_term_count`).
    time_count: usize,
    /// The previous sample's correction: the first guess of the next (see `solve`).
    correction: Xz,
    /// The most steps one sample took so far.
    pub iterations: u32,
    /// The square of the largest |nominal − predicted| so far, mm² (`max_residual_mm`).
    max_residual_squared: f64,
}

impl<'m> Inverse<'m> {
    /// The largest |nominal − predicted| so far, mm. The square root is taken of the largest
    /// square rather than of each sample's: a rounded square root never decreases as its
    /// argument grows, so the answer is the same.
    pub fn max_residual_mm(&self) -> f64 {
        self.max_residual_squared.sqrt()
    }

    /// The inverse from the machine's position `start`.
    pub fn new(start: Xz, model: &'m ErrorModel, options: &InverseOptions) -> Inverse<'m> {
        Inverse {
            model,
            options: *options,
            tracker: Tracker::new(start, model.play()).counting_cut(model.wears()),
            time_count: model.time_term_count(),
            correction: Xz::new(0.0, 0.0),
            iterations: 0,
            max_residual_squared: 0.0,
        }
    }

    /// Solve the next `samples`, appending the point to command for each to `commanded`,
    /// the backlash taken up on the way to it to `take_ups` (`Tracker::take_up`), and where
    /// the model predicts it goes to `predicted` (when it is asked for);
    /// `time_terms` holds the model's terms of time at the samples (`time_terms`; empty to
    /// evaluate them at each command tried).
    pub fn solve(
        &mut self,
        samples: &[PathSample],
        time_terms: &[Xz],
        (commanded, take_ups): (&mut Vec<Xz>, &mut Vec<Xz>),
        mut predicted: Option<&mut Vec<Xz>>,
    ) {
        let model = self.model;
        for (index, s) in samples.iter().enumerate() {
            let inputs = inputs_of(s, model);
            let terms = terms_of(time_terms, self.time_count, index);
            let guess = Xz::new(s.nominal.x + self.correction.x, s.nominal.z + self.correction.z);
            let (step, a, steps) = solve(&self.tracker, s, guess, &inputs, terms, model, &self.options);
            let c = step.to();
            self.correction = Xz::new(c.x - s.nominal.x, c.z - s.nominal.z);
            take_ups.push(self.tracker.take_up(&step));
            self.tracker.take(&step, s.tool, s.cutting);
            self.iterations = self.iterations.max(steps);
            self.max_residual_squared = self.max_residual_squared.max(s.nominal.distance_squared(a));
            commanded.push(c);
            if let Some(predicted) = predicted.as_deref_mut() {
                predicted.push(a);
            }
        }
    }
}

/// The point to command for one sample from the tracker's state (as the tracker's step to
/// it, for the tracker to take), where the model predicts it goes, and the steps it took. The iteration starts from `guess`, the nominal point
/// moved by the previous sample's correction: the errors change little from one sample to
/// the next, and inside an axis' play every command leaves the slide where it is, so of all
/// the commands that solve the sample the one nearest the previous correction is taken,
/// and the commanded path does not jump back and forth across the play for nothing.
fn solve(
    tracker: &Tracker,
    s: &PathSample,
    guess: Xz,
    inputs: &SampleInputs,
    time_terms: &[Xz],
    model: &ErrorModel,
    options: &InverseOptions,
) -> (Step, Xz, u32) {
    let play = tracker.play();
    let slide = tracker.slide();
    let before = tracker.position();
    let direction = tracker.direction();
    let dead_band = options.dead_band_mm;
    let mut c = guess;
    let mut steps = 0;
    loop {
        let step = tracker.step(c);
        let state = tracker.sample_after(&step, s.tool, s.cutting, inputs);
        // One evaluation of the model gives both the actual point and the rest of the error
        // (`ErrorModel::actual` and `displacement_without_play` of the same state).
        let displacement = model.displacement_timed(&state, time_terms);
        let actual = Xz::new(state.at.x + displacement.x, state.at.z + displacement.z);
        // The residual |nominal − actual|, compared as its square (see `root_at_most`).
        let residual = s.nominal.distance_squared(actual);
        if root_at_most(residual, options.tolerance_mm * 1e-3)
            || steps >= options.max_iterations
            || !residual.is_finite()
        {
            return (step, actual, steps);
        }
        steps += 1;
        // The rest of the error at this command, and where the slide must go for it.
        let rest = without_play(&state, displacement);
        let target = Xz::new(s.nominal.x - rest.x, s.nominal.z - rest.z);
        let next = Xz::new(
            command_for(
                Axis { target: target.x, slide: slide.x, before: before.x, play: play.x, direction: direction.x },
                c.x,
                options.gain,
                dead_band,
            ),
            command_for(
                Axis { target: target.z, slide: slide.z, before: before.z, play: play.z, direction: direction.z },
                c.z,
                options.gain,
                dead_band,
            ),
        );
        if root_at_most(next.distance_squared(c), 1e-12) {
            return (step, actual, steps);
        }
        c = next;
    }
}

/// One axis of the solve: where its slide must go, where it is, the command it was
/// reached with, its play and the direction it was last pushed in.
struct Axis {
    target: f64,
    slide: f64,
    before: f64,
    play: f64,
    direction: i8,
}

/// The command that puts a slide at `target` through the play (a reversal only for more
/// than `dead_band`); without play, the eq. 2.16 step from the current guess.
fn command_for(axis: Axis, guess: f64, gain: f64, dead_band: f64) -> f64 {
    let Axis { target, slide, before, play, direction } = axis;
    if play <= 0.0 {
        // The slide is the command: U_c += γ (U_d − U_a) is U_c += γ (target − U_c).
        return guess + gain * (target - guess);
    }
    let half = play / 2.0;
    // Keep the command where it was, inside the play: the slide stays.
    let keep = before.clamp(slide - half, slide + half);
    if target > slide + 1e-12 {
        if direction < 0 && target - slide <= dead_band { keep } else { target + half }
    } else if target < slide - 1e-12 {
        if direction > 0 && slide - target <= dead_band { keep } else { target - half }
    } else {
        keep
    }
}

/// The model's terms of time (`ErrorModel::time_terms`) at each of `samples`, appended to
/// `out`: each sample's are evaluated once here, for every command `Inverse::solve` tries
/// at it and for each prediction of it (`Predictor`).
pub fn time_terms(samples: &[PathSample], model: &ErrorModel, out: &mut Vec<Xz>) {
    if model.time_term_count() == 0 {
        return;
    }
    for s in samples {
        model.time_terms(t_min(s, model), out);
    }
}

/// The terms of time of the `index`-th sample in `terms` (`time_terms`, `count` per sample);
/// none when they were not given, and the model evaluates them.
fn terms_of(terms: &[Xz], count: usize, index: usize) -> &[Xz] {
    let start = index.saturating_mul(count);
    terms.get(start..start.saturating_add(count)).unwrap_or_default()
}

/// Where the tool goes when `commanded` (one point per sample) is commanded in order: the
/// model at each of `states`, evaluated as the tracker walks (the states are not kept).
pub fn predict(samples: &[PathSample], commanded: &[Xz], start: Xz, model: &ErrorModel) -> Vec<Xz> {
    let mut out = Vec::with_capacity(samples.len());
    Predictor::new(start, model).predict(samples, &[], commanded, &mut out);
    out
}

/// `predict` over successive runs of samples, in path order.
#[derive(Debug, Clone)]
pub struct Predictor<'m> {
    model: &'m ErrorModel,
    tracker: Tracker,
    /// The model's terms of time per sample (`ErrorModel::time_term_count`).
    time_count: usize,
}

impl<'m> Predictor<'m> {
    pub fn new(start: Xz, model: &'m ErrorModel) -> Predictor<'m> {
        Predictor {
            model,
            tracker: Tracker::new(start, model.play()).counting_cut(model.wears()),
            time_count: model.time_term_count(),
        }
    }

    /// Where the tool goes for the next `samples` commanded at `commanded`, appended to `out`;
    /// `time_terms` as for `Inverse::solve`.
    pub fn predict(&mut self, samples: &[PathSample], time_terms: &[Xz], commanded: &[Xz], out: &mut Vec<Xz>) {
        let (model, count) = (self.model, self.time_count);
        out.extend(samples.iter().zip(commanded).enumerate().map(|(index, (s, &c))| {
            let step = self.tracker.step(c);
            let state = self.tracker.sample_after(&step, s.tool, s.cutting, &inputs_of(s, model));
            let actual = model.actual_timed(&state, terms_of(time_terms, count, index));
            self.tracker.take(&step, s.tool, s.cutting);
            actual
        }));
    }

    /// Where the slides lag the command now, on the axes with play (`Sample::backlash`): the
    /// part of the last point's displacement the play operator gives.
    pub fn backlash(&self) -> Xz {
        let (slide, at, play) = (self.tracker.slide(), self.tracker.position(), self.tracker.play());
        let lag = |play: f64, slide: f64, at: f64| if play > 0.0 { slide - at } else { 0.0 };
        Xz::new(lag(play.x, slide.x, at.x), lag(play.z, slide.z, at.z))
    }

    /// The backlash the tracker would take up on the way to `to` (`Tracker::take_up`), and
    /// where each slide is now.
    pub fn take_up(&self, to: Xz) -> (Xz, Xz) {
        (self.tracker.take_up(&self.tracker.step(to)), self.tracker.slide())
    }

    /// `predict` of the samples' nominal points (the program as written).
    pub fn predict_nominal(&mut self, samples: &[PathSample], time_terms: &[Xz], out: &mut Vec<Xz>) {
        let count = self.time_count;
        out.extend(
            samples.iter().enumerate().map(|(index, s)| self.predict_one(s, terms_of(time_terms, count, index))),
        );
    }

    /// `predict_nominal` of one sample, its terms of time `time_terms` (empty: the model
    /// evaluates them).
    pub fn predict_one(&mut self, s: &PathSample, time_terms: &[Xz]) -> Xz {
        let model = self.model;
        let step = self.tracker.step(s.nominal);
        let state = self.tracker.sample_after(&step, s.tool, s.cutting, &inputs_of(s, model));
        let actual = model.actual_timed(&state, time_terms);
        self.tracker.take(&step, s.tool, s.cutting);
        actual
    }
}

#[cfg(test)]
mod tests;
