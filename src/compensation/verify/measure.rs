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
use crate::error_model::sampling::{
    MoveView, PathSample, Sampling, sample_view, sample_view_at, samples_needed_compact,
};
use crate::toolpath::compact::CompactPath;
use crate::toolpath::{Motion, Xz};

use super::super::deviation::Tally;
use super::super::inverse::Predictor;
use super::super::program::SAMPLE_STEP_MM;
use super::arc_steps;
use super::follow::{Follower, Original};
use super::knee::{self, Axis};
use super::lead::ThreadPoints;
use super::{Measured, Side, Worst};

/// Moves sampled and measured at a time, and samples (past the first move's): memory
/// follows them, not the program.
const CHUNK_MOVES: usize = 4096;
const CHUNK_SAMPLES: usize = 1 << 16;

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
) -> (Tally, Option<Worst>, ThreadPoints) {
    let mut walk = Walk::new(program, original, model, sampling, side);
    walk_all(&mut walk, sampling, each);
    walk.finish()
}

/// Every point of `program` as `model` puts the tool there, in path order: the points
/// `measure` measures (the knees of a take-up and the points one step in from a cutting
/// move's ends among them), rapids and moves that do not cut included, each given to `each`
/// with its predicted point (`Measured::predicted`; its distance is none, `closest` the
/// predicted point itself). The part measure (`part.rs`) cuts the part along these points.
/// The points the lead measure needs (`lead.rs`) are kept and returned.
pub fn predicted(
    program: &CompactPath,
    model: &ErrorModel,
    sampling: &Sampling,
    side: Side,
    each: &mut dyn FnMut(Side, Measured),
) -> ThreadPoints {
    let mut walk = Walk::predicting(program, model, sampling, side);
    walk_all(&mut walk, sampling, each);
    walk.threads
}

/// Give `walk` every sample of its program, a piece of moves at a time.
fn walk_all(walk: &mut Walk<'_>, sampling: &Sampling, each: &mut dyn FnMut(Side, Measured)) {
    let program = walk.program;
    let mut samples = Vec::new();
    let count = program.len();
    let mut next = 0;
    while next < count {
        let first = next;
        let mut held = 0;
        while next < count && next - first < CHUNK_MOVES && (next == first || held < CHUNK_SAMPLES) {
            held = samples_needed_compact(program, next, sampling).saturating_add(held);
            next += 1;
        }
        samples.clear();
        for index in first..next {
            if let Some(view) = MoveView::of_compact(program, index) {
                let angles = program.arc(index).map(|arc| (arc.start_angle, arc.sweep));
                sample_view(&view, index, sampling, angles, None, &mut samples);
            }
        }
        for s in &samples {
            walk.sample(s, &[], each);
        }
    }
}

/// One program's measure as it goes (see the module documentation).
pub struct Walk<'a> {
    program: &'a CompactPath,
    side: Side,
    /// How many points were measured, cutting or not (`Measured::sample_index`).
    measured: usize,
    play: Xz,
    /// None where the points are only predicted, not measured against a path (`predicted`):
    /// each is then given to `each` as predicted, cutting or not.
    follower: Option<Follower<'a>>,
    predictor: Predictor<'a>,
    tally: Tally,
    /// The point measured before (none after a point that does not cut).
    previous: Option<Point>,
    worst: Option<Worst>,
    /// The predicted points a lead measure needs (`lead.rs`).
    threads: ThreadPoints,
    /// The last sample given, its move and its place along it.
    move_before: usize,
    param_before: f64,
    /// The model's allowance (`Sampling::allowance`), which the pieces of an arc's step may
    /// use again (`arc_steps.rs`).
    allowance: f64,
}

/// A point as measured, for the stretch of path from it to the next.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Point {
    /// Its distance with its side, and the program's move it lies on.
    signed: f64,
    own_move: usize,
    /// The nominal point, where the model puts the tool, and the play's part of that.
    nominal: Xz,
    predicted: Xz,
    play: Xz,
    /// Its place along its move, and the original's move it was measured against.
    param: f64,
    found_move: usize,
}

impl<'a> Walk<'a> {
    /// The measure of `program` against `original` on `model`, from the program's start.
    pub fn new(
        program: &'a CompactPath,
        original: &'a Original<'a>,
        model: &'a ErrorModel,
        sampling: &Sampling,
        side: Side,
    ) -> Walk<'a> {
        Walk { follower: Some(Follower::new(original)), ..Walk::predicting(program, model, sampling, side) }
    }

    /// The points of `program` on `model` predicted only, measured against no path
    /// (`predicted`).
    fn predicting(program: &'a CompactPath, model: &'a ErrorModel, sampling: &Sampling, side: Side) -> Walk<'a> {
        Walk {
            program,
            side,
            measured: 0,
            play: model.play(),
            follower: None,
            predictor: Predictor::new(program.start, model),
            tally: Tally::default(),
            previous: None,
            worst: None,
            threads: ThreadPoints::default(),
            move_before: usize::MAX,
            param_before: 0.0,
            allowance: sampling.allowance,
        }
    }

    /// The figures' running sums, the largest deviation and where it is, and the points
    /// kept for the lead measure.
    pub fn finish(self) -> (Tally, Option<Worst>, ThreadPoints) {
        (self.tally, self.worst, self.threads)
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
        self.threads.keep(self.program, s.move_index, s.param, p);
        let sample_index = self.measured;
        self.measured += 1;
        let Some(follower) = self.follower.as_mut() else {
            let measured =
                Measured { sample: *s, sample_index, predicted: p, distance_mm: 0.0, closest: p, original_move: 0 };
            each(self.side, measured);
            return p;
        };
        if !s.cutting {
            self.previous = None;
            return p;
        }
        let found = match self.side {
            Side::Original => follower.measure_from(s.move_index, s.param, p),
            Side::Compensated => follower.measure(s.nominal, p),
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
        let signed = found.distance * follower.side(&found, p);
        let point = Point {
            signed,
            own_move: s.move_index,
            nominal: s.nominal,
            predicted: p,
            play: self.predictor.backlash(),
            param: s.param,
            found_move: found.move_index,
        };
        let weight = s.covers_mm / SAMPLE_STEP_MM;
        match self.previous {
            // The side keeps its meaning along one move only: round a corner the part's
            // surface may lie on the other side of the travel, so across one the distances
            // are taken as they are, without a side.
            Some(before) if before.own_move != s.move_index => {
                self.add(signed, Some(before.signed.abs().copysign(signed)), weight, s.move_index)
            }
            Some(before) => {
                // Along an arc, the stretch from the point before in the pieces its bound asks
                // for (`arc_steps.rs`).
                let mut from = before.signed;
                let pieces = self.arc_pieces(&before, &point);
                for &value in &pieces {
                    self.add(value, Some(from), weight / (pieces.len() + 1) as f64, s.move_index);
                    from = value;
                }
                self.add(signed, Some(from), weight / (pieces.len() + 1) as f64, s.move_index);
            }
            None => self.add(signed, None, weight, s.move_index),
        }
        self.previous = Some(point);
        p
    }

    /// Tally a distance with its side at the end of `weight` points of path whose other end
    /// is at `previous` (`Tally::add_signed_along`), and keep the largest.
    fn add(&mut self, signed: f64, previous: Option<f64>, weight: f64, measured_move: usize) {
        self.tally.add_signed_along(signed, previous, weight);
        let d = signed.abs();
        if self.worst.is_none_or(|w| d > w.deviation_mm) {
            let original_move = self.follower.as_ref().map_or(0, Follower::matched_move);
            self.worst = Some(Worst { deviation_mm: d, original_move, measured_move });
        }
    }

    /// The distances with their sides at the points that cut the stretch of an arc from
    /// `before` to `after` into the pieces its bound asks for (`arc_steps.rs`), from the
    /// displacement interpolated between them; none where the stretch is no arc's, its
    /// ends were measured against different moves or no arc of the original, or the play
    /// changes along it (a take-up, whose knee is measured).
    fn arc_pieces(&self, before: &Point, after: &Point) -> SmallVec<[f64; 8]> {
        let none = SmallVec::new();
        let (Some(own), Some(reference)) =
            (self.program.arc(after.own_move), self.follower.as_ref().and_then(|f| f.path().arc(after.found_move)))
        else {
            return none;
        };
        let radians = own.sweep * (after.param - before.param);
        let same_play = (before.play.x - after.play.x).abs() <= 1e-12 && (before.play.z - after.play.z).abs() <= 1e-12;
        // The circle measured against is the arc's own: the original's own move, or for
        // the compensated program the original's arc it was written from, which its circle
        // follows within the shift (another pass that passes the ends may run elsewhere
        // between them).
        let own_circle = match self.side {
            Side::Original => after.found_move == after.own_move,
            Side::Compensated => {
                own.centre.distance(reference.centre) + (own.radius - reference.radius).abs() <= OWN_CIRCLE_MM
            }
        };
        if before.found_move != after.found_move
            || !own_circle
            || !same_play
            || radians.is_nan()
            || radians <= 0.0
            || self.allowance <= 0.0
        {
            return none;
        }
        // From the reference circle's centre: the arc's own radius along its own radial
        // (`u`), and the rest, `V` (the model's displacement and the centres' offset).
        let radial = |n: Xz| {
            let length = n.distance(own.centre);
            Xz::new((n.x - own.centre.x) / length, (n.z - own.centre.z) / length)
        };
        let rest = |point: &Point, u: Xz| {
            Xz::new(
                point.predicted.x - reference.centre.x - own.radius * u.x,
                point.predicted.z - reference.centre.z - own.radius * u.z,
            )
        };
        let (u0, u1) = (radial(before.nominal), radial(after.nominal));
        let (v0, v1) = (rest(before, u0), rest(after, u1));
        let norm = |v: Xz| v.distance(Xz::new(0.0, 0.0));
        let step = arc_steps::Step {
            radians,
            radius: own.radius,
            largest: norm(v0).max(norm(v1)) + self.allowance,
            change: norm(Xz::new(v1.x - v0.x, v1.z - v0.z)),
            allowance: self.allowance,
        };
        let pieces = arc_steps::pieces(&step).unwrap_or_else(|| arc_steps::fallback_pieces(radians));
        if pieces <= 1 {
            return none;
        }
        // The side: the sign that turns the distance from the circle into the measured one,
        // from the end that is off the circle.
        let off = |v: Xz, u: Xz| norm(Xz::new(own.radius * u.x + v.x, own.radius * u.z + v.z)) - reference.radius;
        let side = [(after, off(v1, u1)), (before, off(v0, u0))]
            .into_iter()
            .find(|(point, off)| *off != 0.0 && point.signed != 0.0)
            .map_or(1.0, |(point, off)| (point.signed / off).signum());
        // Both ends measured against the circle itself (not an end of its arc).
        let consistent = |point: &Point, v: Xz, u: Xz| (side * off(v, u) - point.signed).abs() <= 1e-9;
        if !consistent(before, v0, u0) || !consistent(after, v1, u1) {
            return none;
        }
        // Each piece's radial, turned from the start's by its share of the angle.
        let sense = if self.program.moves()[after.own_move].motion == Motion::Ccw { 1.0 } else { -1.0 };
        let (sin, cos) = (sense * radians / pieces as f64).sin_cos();
        let mut u = u0;
        let mut out = SmallVec::new();
        for piece in 1..pieces {
            // u(a + φ) = (sin(a + φ), cos(a + φ)) from u(a) = (sin a, cos a).
            u = Xz::new(u.x * cos + u.z * sin, u.z * cos - u.x * sin);
            let s = piece as f64 / pieces as f64;
            let v = Xz::new(v0.x + (v1.x - v0.x) * s, v0.z + (v1.z - v0.z) * s);
            out.push(side * (norm(Xz::new(own.radius * u.x + v.x, own.radius * u.z + v.z)) - reference.radius));
        }
        out
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

/// How far the circle of a compensated program's arc may lie from the original's it is
/// measured against, as the offset of the centres and the difference of the radii, mm, for
/// the distance between its points to be that from the circle: `compensate`'s default
/// `--max-shift`, the most it moves a point.
const OWN_CIRCLE_MM: f64 = 0.1;

/// Moves at most this long (mm) are measured at their end only, unless a play is longer:
/// `compensate` writes such moves at reversals and corners, where the tool stands still but
/// for the slides' last micrometres, and the model's terms of velocity (a loop lag in steady
/// motion) do not describe a move of a few micrometres at a knee or at its start.
const JOG_MM: f64 = 0.01;
