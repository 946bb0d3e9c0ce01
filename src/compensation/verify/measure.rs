//! One program's measure: its samples predicted through the model as written, in path
//! order, each cutting point measured against the original's nominal path (`follow.rs`) and
//! tallied along the path (`Tally::add_signed_along`).
//!
//! Between two samples the model is followed within the sampling's allowance, but two
//! things bend the deviation faster than any model's term. Where a slide reverses it stands
//! still while the command crosses its play and moves on from the knee where the command
//! reaches the far side: each such knee on a cutting move is measured too (`knee.rs`), with
//! the standing slide's velocity. And round a corner the distance from the path moves from
//! the one element to the next within a few micrometres of the corner, so a cutting move
//! longer than two of the thesis' steps is also measured one step after its start and one
//! before its end: the distance along the rest of it is then its own element's.
//!
//! A `Walk` takes the samples one by one (`Walk::sample`), so the samples a caller has made
//! already are measured as they are: `measure` makes them for a program held compact
//! (`toolpath::compact`), move by move.

use smallvec::SmallVec;

use crate::error_model::ErrorModel;
use crate::error_model::sampling::{MoveView, PathSample, Sampling, sample_view, sample_view_at};
use crate::toolpath::compact::CompactPath;
use crate::toolpath::{Motion, Xz};

use super::super::deviation::Tally;
use super::super::inverse::Predictor;
use super::super::program::SAMPLE_STEP_MM;
use super::follow::{Follower, Original};
use super::knee::{self, Axis};
use super::{Measured, Side, Worst};

/// Moves sampled and measured at a time: memory follows them, not the program.
const CHUNK_MOVES: usize = 4096;

/// Sample `program` as `sampling` allows, predict it through `model` as written, and tally
/// the distance of each predicted cutting point from `original`, with its side, integrated
/// along the path between samples; every point measured is also given to `each`.
pub fn measure(
    program: &CompactPath,
    original: &Original<'_>,
    model: &ErrorModel,
    sampling: &Sampling,
    side: Side,
    each: &mut dyn FnMut(Side, Measured),
) -> (Tally, Option<Worst>) {
    let mut walk = Walk::new(program, original, model, side);
    let mut samples = Vec::new();
    let count = program.len();
    for first in (0..count).step_by(CHUNK_MOVES) {
        samples.clear();
        for index in first..(first + CHUNK_MOVES).min(count) {
            if let Some(view) = MoveView::of_compact(program, index) {
                let angles = program.arc(index).map(|arc| (arc.start_angle, arc.sweep));
                sample_view(&view, index, sampling, angles, None, &mut samples);
            }
        }
        for s in &samples {
            walk.sample(s, &[], each);
        }
    }
    walk.finish()
}

/// One program's measure as it goes (see the module documentation).
pub struct Walk<'a> {
    program: &'a CompactPath,
    side: Side,
    /// How many points were measured, cutting or not (`Measured::sample_index`).
    measured: usize,
    play: Xz,
    follower: Follower<'a>,
    predictor: Predictor<'a>,
    tally: Tally,
    /// The distance, with its side, measured at the sample before, and that sample's move
    /// (none after a sample that does not cut).
    previous: Option<(f64, usize)>,
    worst: Option<Worst>,
    /// The last sample given, its move and its place along it.
    move_before: usize,
    param_before: f64,
}

impl<'a> Walk<'a> {
    /// The measure of `program` against `original` on `model`, from the program's start.
    pub fn new(program: &'a CompactPath, original: &'a Original<'a>, model: &'a ErrorModel, side: Side) -> Walk<'a> {
        Walk {
            program,
            side,
            measured: 0,
            play: model.play(),
            follower: Follower::new(original),
            predictor: Predictor::new(program.start, model),
            tally: Tally::default(),
            previous: None,
            worst: None,
            move_before: usize::MAX,
            param_before: 0.0,
        }
    }

    /// The figures' running sums, and the largest deviation and where it is.
    pub fn finish(self) -> (Tally, Option<Worst>) {
        (self.tally, self.worst)
    }

    /// Predict the next sample of the program, `s` (with its terms of time `terms`, or none
    /// for the model to evaluate them), measure it with the points the measure adds on the
    /// way to it, and give each to `each`; where the model puts the tool for `s`.
    pub fn sample(&mut self, s: &PathSample, terms: &[Xz], each: &mut dyn FnMut(Side, Measured)) -> Xz {
        let from = if s.move_index == self.move_before { self.param_before } else { 0.0 };
        (self.param_before, self.move_before) = (s.param, s.move_index);
        let long = self.longer_than_a_jog(s.move_index);
        if s.param == 0.0 && !long {
            // The start of a move too short to be measured but at its end: the tool is there
            // already (the end of the move before), and the point is neither measured nor
            // moved to.
            return self.predictor.clone().predict_one(s, terms);
        }
        // A stretch longer than two of the thesis' steps is also measured one step in from
        // each end where it is an end of its move.
        let mut points: SmallVec<[(f64, f64); 2]> = SmallVec::new();
        if s.cutting && s.param > from && s.covers_mm > 2.0 * SAMPLE_STEP_MM {
            let step = SAMPLE_STEP_MM / s.covers_mm * (s.param - from);
            if from == 0.0 {
                points.push((from + step, SAMPLE_STEP_MM));
            }
            if s.param >= 1.0 {
                let covered = points.iter().map(|p| p.1).sum::<f64>();
                points.push((s.param - step, s.covers_mm - SAMPLE_STEP_MM - covered));
            }
        }
        let mut at = from;
        let mut covered = 0.0;
        if !points.is_empty()
            && let Some(view) = MoveView::of_compact(self.program, s.move_index)
        {
            let angles = self.angles(s.move_index);
            for (param, covers_mm) in points {
                if let Some(inner) = sample_view_at(&view, s.move_index, angles, param) {
                    self.stretch(&PathSample { covers_mm, ..inner }, &[], at, long, each);
                    (at, covered) = (param, covered + covers_mm);
                }
            }
        }
        self.stretch(&PathSample { covers_mm: s.covers_mm - covered, ..*s }, terms, at, long, each)
    }

    /// The start angle and sweep of move `index` when it is an arc.
    fn angles(&self, index: usize) -> Option<(f64, f64)> {
        self.program.arc(index).map(|arc| (arc.start_angle, arc.sweep))
    }

    /// Measure `s`, reached from the point at `from` of its move, with the knees of a
    /// take-up on the way where the move is `long` enough to cut past its play; where the
    /// model puts the tool for `s`.
    fn stretch(
        &mut self,
        s: &PathSample,
        terms: &[Xz],
        from: f64,
        long: bool,
        each: &mut dyn FnMut(Side, Measured),
    ) -> Xz {
        let play = self.play;
        if (play.x > 0.0 || play.z > 0.0) && s.cutting && long {
            let (take_up, slide) = self.predictor.take_up(s.nominal);
            if take_up.x != 0.0 || take_up.z != 0.0 {
                let mut rest = *s;
                for mut knee in self.knees(s, from, take_up, slide) {
                    let share = (knee.param - from) / (s.param - from).max(f64::MIN_POSITIVE);
                    knee.covers_mm = s.covers_mm * share.clamp(0.0, 1.0) - (s.covers_mm - rest.covers_mm);
                    rest.covers_mm -= knee.covers_mm;
                    self.one(&knee, &[], each);
                }
                return self.one(&rest, terms, each);
            }
        }
        self.one(s, terms, each)
    }

    /// Predict and tally one point; where the model puts the tool for it.
    fn one(&mut self, s: &PathSample, terms: &[Xz], each: &mut dyn FnMut(Side, Measured)) -> Xz {
        let p = self.predictor.predict_one(s, terms);
        let sample_index = self.measured;
        self.measured += 1;
        if !s.cutting {
            self.previous = None;
            return p;
        }
        let found = match self.side {
            Side::Original => self.follower.measure_from(s.move_index, s.param, p),
            Side::Compensated => self.follower.measure(s.nominal, p),
        };
        let Some(found) = found else {
            self.previous = None;
            return p;
        };
        each(
            self.side,
            Measured {
                sample: *s,
                sample_index,
                predicted: p,
                distance_mm: found.distance,
                closest: found.point,
                original_move: found.move_index,
            },
        );
        let signed = found.distance * self.follower.side(&found, p);
        let d = signed.abs();
        // The side keeps its meaning along one move only: round a corner the part's surface
        // may lie on the other side of the travel, so across one the distances are taken as
        // they are, without a side.
        let previous = match self.previous {
            Some((before, k)) if k == s.move_index => Some(before),
            Some((before, _)) => Some(before.abs().copysign(signed)),
            None => None,
        };
        self.tally.add_signed_along(signed, previous, s.covers_mm / SAMPLE_STEP_MM);
        if self.worst.is_none_or(|w| d > w.deviation_mm) {
            let original_move = self.follower.matched_move();
            self.worst = Some(Worst { deviation_mm: d, original_move, measured_move: s.move_index });
        }
        self.previous = Some((signed, s.move_index));
        p
    }

    /// Whether move `index` is longer than a jog (`JOG_MM`, or four times the larger play):
    /// long enough for the tool to cut along the part while a reversing slide stands in its
    /// play.
    fn longer_than_a_jog(&self, index: usize) -> bool {
        let jog = JOG_MM.max(4.0 * self.play.x.max(self.play.z));
        self.program.moves().get(index).is_some_and(|m| self.program.start_of(index).distance(m.end) > jog)
    }

    /// The knees of a take-up on the way to the cutting sample `s` from the point at `from`
    /// of its move: for each axis that reverses there (`take_up`, from the slides at
    /// `slide`), the sample where the command reaches the far side of the play, in path
    /// order.
    fn knees(&self, s: &PathSample, from: f64, take_up: Xz, slide: Xz) -> SmallVec<[PathSample; 2]> {
        let mut out: SmallVec<[PathSample; 2]> = SmallVec::new();
        let Some(view) = MoveView::of_compact(self.program, s.move_index) else { return out };
        let angles = self.angles(s.move_index);
        let path = knee::Path {
            motion: view.motion,
            start: view.start,
            end: view.end,
            centre: view.centre,
            radius: self.program.arc(s.move_index).map_or(0.0, |arc| arc.radius),
            start_angle: angles.map_or(0.0, |a| a.0),
            sweep: angles.map_or(0.0, |a| a.1),
        };
        if !matches!(path.motion, Motion::Feed | Motion::Cw | Motion::Ccw) {
            return out;
        }
        let axes = [(take_up.x, slide.x, self.play.x, Axis::X), (take_up.z, slide.z, self.play.z, Axis::Z)];
        for (take_up, slide, play, axis) in axes {
            if take_up == 0.0 {
                continue;
            }
            let direction = take_up.signum();
            let edge = slide + direction * play / 2.0;
            let Some(param) = knee::knee(&path, axis, edge, direction, from, s.param) else { continue };
            if let Some(mut knee) = sample_view_at(&view, s.move_index, angles, param) {
                // The reversing slide has stood still up to the knee: it moves with no
                // velocity of its own there (a loop lag follows the slide, not the command
                // inside the play).
                match axis {
                    Axis::X => knee.velocity.x = 0.0,
                    Axis::Z => knee.velocity.z = 0.0,
                }
                out.push(knee);
            }
        }
        out.sort_by(|a, b| a.param.total_cmp(&b.param));
        out
    }
}

/// Moves at most this long (mm) are measured at their end only, unless a play is longer:
/// `compensate` writes such moves at reversals and corners, where the tool stands still but
/// for the slides' last micrometres, and the model's terms of velocity (a loop lag in steady
/// motion) do not describe a move of a few micrometres at a knee or at its start.
const JOG_MM: f64 = 0.01;
