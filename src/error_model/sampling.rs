//! Sampling a toolpath for the error model: points along every move with the state an
//! effect needs (time, velocity, tool, whether it cuts, the surface normal, the tip).
//!
//! Cutting moves (feeds and arcs) are split evenly into as few steps as a `Sampling`
//! allows, and also sampled at their start where the model's correction steps at a corner
//! (`ArcTerms::steps_at_corners`: the step is then the difference between the end of one
//! move and the start of the next, at the same point): `compensate` asks its model how closely (`error_model/spacing.rs`: one sample
//! per line when every term is affine along it), `verify`, `diagnose` and `plot` sample
//! every 0.254 mm whatever the model. A rapid is sampled only at
//! its end, where the next cut starts (what the tool does between is not on the part);
//! a dwell not at all. The toolpath's start is the machine's position before the program
//! and is not a sample: nothing commands it.

use std::ops::Range;

use crate::error_model::spacing::{ArcTerms, TABLE_STEP_MM};
use crate::error_model::{ErrorModel, Sample, SampleInputs, Spacing, Tracker};
use crate::geometry;
use crate::semantic::nose_radius::{ToolTable, tip_vector};
use crate::toolpath::compact::CompactPath;
use crate::toolpath::{Compensation, Motion, Move, Toolpath, Xz};

/// Samples along cutting moves at most this far apart where an axis table or a measure
/// independent of the model needs them, mm: the thesis interpolated its error tables
/// every 0.254 mm (0.01 in).
pub const SAMPLE_STEP_MM: f64 = TABLE_STEP_MM;

/// One point of the nominal path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathSample {
    /// The move it lies on, and where along it (0 at the start, 1 at the end).
    pub move_index: usize,
    pub param: f64,
    /// The nominal tool reference point, mm, X as a radius.
    pub nominal: Xz,
    /// The length of path this sample stands for, mm: from the previous sample of its move
    /// (or the move's start) to it. Figures along the path weigh each sample by it, so they
    /// do not depend on how closely the path was sampled.
    pub covers_mm: f64,
    /// Seconds since the program started.
    pub t_s: f64,
    /// Commanded velocity, mm/min.
    pub velocity: Xz,
    pub tool: u16,
    pub cutting: bool,
    /// Unit normal from the part toward the tool (zero when not cutting).
    pub normal: Xz,
    /// The tool's tip direction (nose radii).
    pub tip: Xz,
}

/// What sampling reads of one move: its geometry, times and feed, whether it cuts, its
/// tool's tip and which side of it the part is on. `MoveView::of` takes it from a move of a
/// `Toolpath`, and `toolpath::compact`'s moves give the same fields, so both are sampled by
/// the one code path below and give the same samples to the bit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MoveView {
    pub start: Xz,
    pub end: Xz,
    /// The arc's centre (NaN for a move that is no arc).
    pub centre: Xz,
    pub motion: Motion,
    pub compensation: Compensation,
    pub cutting: bool,
    /// Feed, mm/min.
    pub feed: f64,
    pub t_start: f64,
    pub t_end: f64,
    pub tool: u16,
    /// The tool's tip direction (`tip_vector`).
    pub tip: Xz,
}

impl MoveView {
    /// Move `index` of `toolpath` with its tool's tip from `tools`; none for a move that
    /// does not exist.
    pub fn of(toolpath: &Toolpath, index: usize, tools: &ToolTable) -> Option<MoveView> {
        let m = toolpath.moves.get(index)?;
        Some(MoveView {
            start: toolpath.start_of(index),
            end: m.end,
            centre: m.centre,
            motion: m.motion,
            compensation: m.compensation,
            cutting: m.cutting,
            feed: m.feed,
            t_start: m.t_start,
            t_end: m.t_end,
            tool: m.tool,
            tip: tip_vector(tools.lookup(m.tool, m.offset).1),
        })
    }

    /// Move `index` of the compact `path`: the same fields as `of` takes from the move it
    /// was made from.
    pub fn of_compact(path: &CompactPath, index: usize) -> Option<MoveView> {
        let m = path.moves().get(index)?;
        Some(MoveView {
            start: path.start_of(index),
            end: m.end,
            centre: path.centre(index),
            motion: m.motion,
            compensation: m.compensation,
            cutting: m.cutting,
            feed: m.feed,
            t_start: m.t_start,
            t_end: m.t_end,
            tool: m.tool,
            tip: tip_vector(m.tip),
        })
    }

    /// How long the move takes, minutes.
    fn minutes(&self) -> f64 {
        (self.t_end - self.t_start) / 60.0
    }
}

/// How far apart the samples of a cutting move may be.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sampling {
    /// Along the path and in time (`Spacing::steps` splits each move evenly).
    pub spacing: Spacing,
    /// What turns the correction around an arc: an arc is sampled at least at the angle
    /// step `ArcTerms::radians` gives for its radius and feed with `allowance`, and at
    /// least every `MAX_ARC_RADIANS`.
    pub arc: ArcTerms,
    /// How far the chord between samples may stray from the correction, mm (zero, with no
    /// arc terms: no angle step at all, as `every_mm` samples).
    pub allowance: f64,
    /// The largest angle between an arc's samples, radians (`MAX_ARC_RADIANS`; the
    /// measure of a deviation cuts an arc's steps further as it needs, `verify/arc_steps.rs`).
    pub max_arc_radians: f64,
    /// The play of each slide where the approach to a thread is sampled through an
    /// overshoot (`thread_approach`; compensation only), mm; zero for none.
    pub play: Xz,
}

impl Sampling {
    /// The largest angle between an arc's samples, whatever the model: an eighth of a
    /// turn. The fits follow it (they hold an arc to the programmed arc's bulge between two
    /// points with the programmed radius, which a translation of the arc leaves as it is),
    /// and so does compensate's own prediction of `densify`, whose rounded path is walked
    /// to each sample across all the lines between two samples (`quantised::Walk`).
    pub const MAX_ARC_RADIANS: f64 = std::f64::consts::PI / 8.0;

    /// Every `step` mm along cutting moves, whatever the model: how `verify`, `diagnose`
    /// and `plot` measure a path, and how the thesis sampled.
    pub fn every_mm(step: f64) -> Sampling {
        let step = if step.is_finite() && step > 0.0 { step } else { TABLE_STEP_MM };
        Sampling {
            spacing: Spacing::mm(step),
            arc: ArcTerms::default(),
            allowance: 0.0,
            max_arc_radians: Self::MAX_ARC_RADIANS,
            play: Xz::new(0.0, 0.0),
        }
    }

    /// How many equal steps an arc of `radius` sweeping `sweep` radians at `feed` needs by
    /// its angle (`every_mm` asks none).
    fn arc_steps(&self, radius: f64, sweep: f64, feed: f64) -> usize {
        if self.allowance <= 0.0 && self.arc == ArcTerms::default() {
            return 0;
        }
        let step = self.arc.radians(radius, feed, self.allowance).min(self.max_arc_radians);
        // `as` saturates; a NaN (a degenerate arc) is no step.
        if step > 0.0 { (sweep / step).ceil() as usize } else { 0 }
    }
}

/// The most samples one move may need. Compensation holds a piece's samples at once, and a
/// move's samples are all in one piece: a move that needs more (ten kilometres at the
/// thesis' 0.254 mm, a metre where the model asks for a sample every micrometre, hours of
/// a slow feed where it drifts with time) is refused before it is sampled, so that memory
/// follows the program and not the product of its lengths and the model's steps.
pub const MAX_SAMPLES_PER_MOVE: usize = 1_000_000;

/// How many samples [`sample_move`] makes of move `index` as `sampling` allows (an arc's
/// axis reversals aside, at most four more), counted without making them.
pub fn samples_needed(toolpath: &Toolpath, index: usize, sampling: &Sampling) -> usize {
    let Some(m) = toolpath.moves.get(index) else { return 0 };
    let start = toolpath.start_of(index);
    let arc = matches!(m.motion, Motion::Cw | Motion::Ccw).then(|| {
        let a0 = geometry::angle(start, m.centre);
        (start.distance(m.centre), geometry::sweep_from(a0, start, m.end, m.centre, m.motion == Motion::Ccw))
    });
    steps_needed(m.motion, start.distance(m.end), minutes(m), m.feed, arc, sampling)
}

/// [`samples_needed`] of move `index` of a compact path, whose arcs hold their radius and
/// sweep (the same as those `samples_needed` finds).
pub fn samples_needed_compact(path: &CompactPath, index: usize, sampling: &Sampling) -> usize {
    let Some(m) = path.moves().get(index) else { return 0 };
    let length = path.start_of(index).distance(m.end);
    let arc = path.arc(index).map(|arc| (arc.radius, arc.sweep));
    steps_needed(m.motion, length, (m.t_end - m.t_start) / 60.0, m.feed, arc, sampling)
}

/// The samples of a move of `motion`, `length` mm long (a line's), taking `minutes`, at
/// `feed`, an arc's radius and sweep in `arc`.
fn steps_needed(
    motion: Motion,
    length: f64,
    minutes: f64,
    feed: f64,
    arc: Option<(f64, f64)>,
    sampling: &Sampling,
) -> usize {
    match motion {
        Motion::Dwell => 0,
        Motion::Rapid => 1,
        Motion::Feed => sampling.spacing.steps(length, minutes),
        Motion::Cw | Motion::Ccw => {
            let (radius, sweep) = arc.unwrap_or((0.0, 0.0));
            let by_angle = sampling.arc_steps(radius, sweep, feed);
            sampling.spacing.steps(radius * sweep, minutes).max(by_angle).max(2)
        }
    }
}

/// Sample every move of `toolpath`; cutting moves at most `step` mm apart.
pub fn sample_toolpath(toolpath: &Toolpath, tools: &ToolTable, step: f64) -> Vec<PathSample> {
    let mut out = Vec::with_capacity(toolpath.moves.len() * 2);
    sample_moves(toolpath, 0..toolpath.moves.len(), tools, &Sampling::every_mm(step), &mut out);
    out
}

/// Sample the moves `moves` of `toolpath` as `sampling` allows, appending to `out`.
pub fn sample_moves(
    toolpath: &Toolpath,
    moves: Range<usize>,
    tools: &ToolTable,
    sampling: &Sampling,
    out: &mut Vec<PathSample>,
) {
    for index in moves.start..moves.end.min(toolpath.moves.len()) {
        sample_move(toolpath, index, tools, sampling, None, out);
    }
}

/// Sample move `index` of `toolpath` as `sampling` allows, appending to `out` (nothing for a
/// move that does not exist). For an arc, `angles` may give its start's angle about its
/// centre and its sweep (`geometry::angle` and `geometry::sweep`) where the caller has them
/// measured already (`LocalPath::arc_angles`); they are measured here otherwise.
pub fn sample_move(
    toolpath: &Toolpath,
    index: usize,
    tools: &ToolTable,
    sampling: &Sampling,
    angles: Option<(f64, f64)>,
    out: &mut Vec<PathSample>,
) {
    let Some(view) = MoveView::of(toolpath, index, tools) else { return };
    let approach = if view.motion == Motion::Rapid { thread_approach(toolpath, index, sampling.play) } else { None };
    sample_view(&view, index, sampling, angles, approach, out);
}

/// Sample the move `m`, move `index` of its path, as `sampling` allows, appending to `out`;
/// `angles` as for [`sample_move`]. A rapid that approaches a thread (`approach`, the
/// directions of [`thread_approach`]) is also sampled one play short of its end.
pub fn sample_view(
    m: &MoveView,
    index: usize,
    sampling: &Sampling,
    angles: Option<(f64, f64)>,
    approach: Option<Xz>,
    out: &mut Vec<PathSample>,
) {
    let (start, tip) = (m.start, m.tip);
    match m.motion {
        Motion::Dwell => {}
        Motion::Rapid => {
            if let Some(approach) = approach {
                let past = Xz::new(m.end.x - approach.x * sampling.play.x, m.end.z - approach.z * sampling.play.z);
                out.push(sample(index, m, 1.0, past, Xz::new(0.0, 0.0), false, tip));
            }
            out.push(PathSample {
                covers_mm: start.distance(m.end),
                ..sample(index, m, 1.0, m.end, Xz::new(0.0, 0.0), false, tip)
            });
        }
        Motion::Feed => {
            let length = start.distance(m.end);
            let n = sampling.spacing.steps(length, m.minutes());
            let direction = unit(Xz::new(m.end.x - start.x, m.end.z - start.z));
            let velocity = Xz::new(direction.x * m.feed, direction.z * m.feed);
            let normal = if m.cutting { normal_of(direction, m.compensation, tip) } else { Xz::new(0.0, 0.0) };
            if m.cutting && sampling.arc.steps_at_corners() {
                out.push(PathSample { velocity, ..sample(index, m, 0.0, start, normal, true, tip) });
            }
            for i in 1..=n {
                let t = i as f64 / n as f64;
                let p = Xz::new(start.x + (m.end.x - start.x) * t, start.z + (m.end.z - start.z) * t);
                let covers_mm = length / n as f64;
                out.push(PathSample { velocity, covers_mm, ..sample(index, m, t, p, normal, m.cutting, tip) });
            }
        }
        Motion::Cw | Motion::Ccw => {
            let ccw = m.motion == Motion::Ccw;
            let radius = start.distance(m.centre);
            let (a0, sweep) = angles.unwrap_or_else(|| geometry::turn(start, m.end, m.centre, ccw));
            let sign = if ccw { 1.0 } else { -1.0 };
            if m.cutting && sampling.arc.steps_at_corners() {
                let tangent = Xz::new(sign * a0.cos(), -sign * a0.sin());
                let velocity = Xz::new(tangent.x * m.feed, tangent.z * m.feed);
                let normal = normal_of(tangent, m.compensation, tip);
                out.push(PathSample { velocity, ..sample(index, m, 0.0, start, normal, true, tip) });
            }
            let by_angle = sampling.arc_steps(radius, sweep, m.feed);
            let n = sampling.spacing.steps(radius * sweep, m.minutes()).max(by_angle).max(2);
            let mut previous = 0.0;
            for t in arc_fractions(n, a0, sweep, ccw) {
                let covers_mm = radius * sweep * (t - previous);
                previous = t;
                let angle = a0 + sign * sweep * t;
                let p = if t >= 1.0 { m.end } else { geometry::on_circle(m.centre, radius, angle) };
                // The tangent of increasing angle is (cos, −sin) in (x, z).
                let tangent = Xz::new(sign * angle.cos(), -sign * angle.sin());
                let velocity = Xz::new(tangent.x * m.feed, tangent.z * m.feed);
                let normal = if m.cutting { normal_of(tangent, m.compensation, tip) } else { Xz::new(0.0, 0.0) };
                out.push(PathSample { velocity, covers_mm, ..sample(index, m, t, p, normal, m.cutting, tip) });
            }
        }
    }
}

/// The directions (−1, 0 or +1 per axis) the slides first move in along the thread that
/// rapid `index` of `toolpath` leads to, on the axes with `play`; none when no thread
/// follows, or no slide with play moves in it.
///
/// A thread cannot be cut in pieces, so the play of a slide that reverses inside it (the
/// pull-out of a straight thread, against the infeed) cannot be taken up by a move of its
/// own there, and the slide would stand still while the thread's chamfer is cut. So the
/// rapid that approaches the thread is sampled, and written, through a point one play short
/// of its end on each such axis: the slides then come to the start of the thread moving
/// the way they will move in it, their play taken up in the air.
fn thread_approach(toolpath: &Toolpath, index: usize, play: Xz) -> Option<Xz> {
    if play.x <= 0.0 && play.z <= 0.0 {
        return None;
    }
    let mut approach = Xz::new(0.0, 0.0);
    let mut k = index + 1;
    while let Some(m) = toolpath.moves.get(k).filter(|m| m.threading && m.compensation == Compensation::Off) {
        let start = toolpath.start_of(k);
        let sign = |d: f64| {
            if d > 1e-9 {
                1.0
            } else if d < -1e-9 {
                -1.0
            } else {
                0.0
            }
        };
        if approach.x == 0.0 && play.x > 0.0 {
            approach.x = sign(m.end.x - start.x);
        }
        if approach.z == 0.0 && play.z > 0.0 {
            approach.z = sign(m.end.z - start.z);
        }
        k += 1;
    }
    (approach.x != 0.0 || approach.z != 0.0).then_some(approach)
}

/// The sample of the move `m`, move `index` of its path, at `t` (0 at its start, 1 at its
/// end), standing for no length of path (`covers_mm` is the caller's): where a measure needs
/// a point between the samples `sample_view` makes (the knee of a backlash take-up). None
/// for a dwell or a rapid. `angles` as for [`sample_move`].
pub fn sample_view_at(m: &MoveView, index: usize, angles: Option<(f64, f64)>, t: f64) -> Option<PathSample> {
    let (start, tip) = (m.start, m.tip);
    let t = t.clamp(0.0, 1.0);
    let (p, tangent) = match m.motion {
        Motion::Dwell | Motion::Rapid => return None,
        Motion::Feed => (
            Xz::new(start.x + (m.end.x - start.x) * t, start.z + (m.end.z - start.z) * t),
            unit(Xz::new(m.end.x - start.x, m.end.z - start.z)),
        ),
        Motion::Cw | Motion::Ccw => {
            let ccw = m.motion == Motion::Ccw;
            let (a0, sweep) = angles.unwrap_or_else(|| geometry::turn(start, m.end, m.centre, ccw));
            let sign = if ccw { 1.0 } else { -1.0 };
            let angle = a0 + sign * sweep * t;
            let p = geometry::on_circle(m.centre, start.distance(m.centre), angle);
            (p, Xz::new(sign * angle.cos(), -sign * angle.sin()))
        }
    };
    let velocity = Xz::new(tangent.x * m.feed, tangent.z * m.feed);
    let normal = if m.cutting { normal_of(tangent, m.compensation, tip) } else { Xz::new(0.0, 0.0) };
    Some(PathSample { velocity, ..sample(index, m, t, p, normal, m.cutting, tip) })
}

/// The fractions of an arc's sweep to sample at: `n` equal steps, and the points where an
/// axis reverses (the arc's extremes in X and Z, at the quarter angles). An axis reverses
/// there, and with it the backlash: the inverse takes up the play at the sample where the
/// slide's direction changes, and `plan.rs` writes that jump at the sample before it. Were
/// the reversal between two samples, the path from the sample before it to the reversal
/// would be written with the play already taken up the other way: off by the play. An
/// extreme within a hundredth of a step of a sample is that sample.
fn arc_fractions(n: usize, a0: f64, sweep: f64, ccw: bool) -> impl Iterator<Item = f64> {
    let mut extremes = [f64::INFINITY; 4];
    for (k, slot) in extremes.iter_mut().enumerate() {
        let target = k as f64 * std::f64::consts::FRAC_PI_2;
        let delta = if ccw { geometry::rem_turn(target - a0) } else { geometry::rem_turn(a0 - target) };
        let fraction = delta / sweep;
        let off_grid = (fraction * n as f64 - (fraction * n as f64).round()).abs() > 0.01;
        if fraction > 0.0 && fraction < 1.0 && off_grid {
            *slot = fraction;
        }
    }
    extremes.sort_by(f64::total_cmp);
    let mut extremes = extremes.into_iter().filter(|f| f.is_finite()).peekable();
    let mut uniform = (1..=n).map(move |i| i as f64 / n as f64).peekable();
    std::iter::from_fn(move || match (uniform.peek(), extremes.peek()) {
        (Some(&u), Some(&e)) if e < u => extremes.next(),
        _ => uniform.next(),
    })
}

fn sample(index: usize, m: &MoveView, t: f64, p: Xz, normal: Xz, cutting: bool, tip: Xz) -> PathSample {
    PathSample {
        move_index: index,
        param: t,
        nominal: p,
        covers_mm: 0.0,
        t_s: m.t_start + (m.t_end - m.t_start) * t,
        velocity: Xz::new(0.0, 0.0),
        tool: m.tool,
        cutting,
        normal,
        tip,
    }
}

/// How long a move takes, minutes.
fn minutes(m: &Move) -> f64 {
    (m.t_end - m.t_start) / 60.0
}

fn unit(v: Xz) -> Xz {
    let length = (v.x * v.x + v.z * v.z).sqrt();
    if length > 0.0 { Xz::new(v.x / length, v.z / length) } else { Xz::new(0.0, 0.0) }
}

/// The normal of the cut surface of move `m`, pointing to the tool: `normal_of` its
/// compensation.
pub(crate) fn surface_normal(direction: Xz, m: &Move, tip: Xz) -> Xz {
    normal_of(direction, m.compensation, tip)
}

/// The normal of the cut surface, pointing to the tool: to the left of the direction of
/// travel under `G41`, to the right under `G42`; without compensation, the side the tool's
/// body is on (opposite its tip direction); none for a tool with no tip direction.
fn normal_of(direction: Xz, compensation: Compensation, tip: Xz) -> Xz {
    // The left normal of (x, z) travel, seen with Z to the right and X up.
    let left = Xz::new(direction.z, -direction.x);
    let right = Xz::new(-left.x, -left.z);
    match compensation {
        Compensation::Left => left,
        Compensation::Right => right,
        Compensation::Off => {
            let body = Xz::new(-tip.x, -tip.z);
            let side = left.x * body.x + left.z * body.z;
            if side > 1e-9 {
                left
            } else if side < -1e-9 {
                right
            } else {
                Xz::new(0.0, 0.0)
            }
        }
    }
}

/// The machine state at each sample when `commanded` is commanded in order: what
/// `predict` evaluates the model on. The states depend on the model only through its play
/// and start time, so a term without play added to the model moves each predicted point
/// by exactly its displacement at these states (the discrepancy workflow relies on this).
pub fn states(samples: &[PathSample], commanded: &[Xz], start: Xz, model: &ErrorModel) -> Vec<Sample> {
    let mut tracker = Tracker::new(start, model.play());
    samples
        .iter()
        .zip(commanded)
        .map(|(s, &c)| {
            // One step for the state and the move to it: the play operator runs once.
            let step = tracker.step(c);
            let state = tracker.sample_after(&step, s.tool, s.cutting, &inputs_of(s, model));
            tracker.take(&step, s.tool, s.cutting);
            state
        })
        .collect()
}

/// What the model reads of a sample besides the slides' state.
pub(crate) fn inputs_of(s: &PathSample, model: &ErrorModel) -> SampleInputs {
    SampleInputs { t_min: t_min(s, model), velocity: s.velocity, normal: s.normal, tip: s.tip }
}

/// Minutes since the machine started at a sample.
pub(crate) fn t_min(s: &PathSample, model: &ErrorModel) -> f64 {
    model.start_min + s.t_s / 60.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compensation::test_support::lower_program;

    #[test]
    fn an_arc_is_sampled_where_an_axis_reverses_inside_it() {
        // G02 from X40 Z0 to X40 Z-9 (diameters) with R5.1, centre X22.4 Z-4.5 (radii):
        // X falls to the circle's bottom, X17.3, between two of the 0.254 mm samples and
        // rises again.
        let (lowered, machine) =
            lower_program("G21 G99\nG97 S1000 M03\nG00 X40. Z2.\nG01 Z0 F0.2\nG02 X40. Z-9. R5.1\nM30\n");
        let path = &lowered.toolpath;
        let (index, arc) = path.moves.iter().enumerate().find(|(_, m)| m.is_arc()).unwrap();
        let samples: Vec<PathSample> = sample_toolpath(path, &ToolTable::from_machine(&machine), 0.254)
            .into_iter()
            .filter(|s| s.move_index == index)
            .collect();
        let bottom = arc.centre.x - path.start_of(index).distance(arc.centre);
        assert!((bottom - 17.3).abs() < 1e-3, "{bottom}");
        let at_bottom: Vec<&PathSample> = samples.iter().filter(|s| (s.nominal.x - bottom).abs() < 1e-9).collect();
        assert_eq!(at_bottom.len(), 1);
        // Between uniform samples, not on one: the steps on either side are shorter.
        let uniform = 1.0 / (samples.len() - 1) as f64;
        assert!((at_bottom[0].param / uniform - (at_bottom[0].param / uniform).round()).abs() > 0.01);
        assert!(samples.windows(2).all(|w| w[0].param < w[1].param));
        assert_eq!(samples.last().map(|s| s.nominal), Some(arc.end));
    }

    #[test]
    fn an_arc_sampled_with_the_path_measures_angles_is_sampled_alike() {
        let (lowered, machine) = lower_program(
            "G21 G99\nG97 S1000 M03\nG00 X40. Z2.\nG01 Z0 F0.2\nG02 X40. Z-9. R5.1\nG03 X30. Z-20. R12.\nM30\n",
        );
        let (path, tools) = (&lowered.toolpath, ToolTable::from_machine(&machine));
        let measures = crate::compensation::deviation::LocalPath::new(path);
        let sampling = Sampling::every_mm(0.254);
        let (mut given, mut measured) = (Vec::new(), Vec::new());
        for index in 0..path.moves.len() {
            sample_move(path, index, &tools, &sampling, measures.arc_angles(index), &mut given);
            sample_move(path, index, &tools, &sampling, None, &mut measured);
        }
        assert_eq!(path.moves.iter().filter(|m| m.is_arc()).count(), 2);
        assert!((0..path.moves.len()).filter(|&k| measures.arc_angles(k).is_some()).count() == 2);
        assert_eq!(given, measured);
    }
}
