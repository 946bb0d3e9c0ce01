//! The measurement's forward model: what a ball bar or a CMM would read if the machine
//! were exactly the error model, computed with the same forward model as `compensate`
//! (`sample_toolpath` and `predict` on the program's nominal toolpath).
//!
//! Each measured point is tied to a point of the program's path: a ball bar row to the
//! point of its test circle at its angle (`ballbar.rs`), a CMM point to the closest point of
//! the finishing path (`profile.rs`). The toolpath's moves are split at those points, so
//! that each is the end of a move and so a sample of its own, with the time, velocity and
//! machine state of that exact place; the split moves are then sampled and predicted as
//! `compensate` does. The simulated reading of a point is
//!
//! * ball bar: the radial deviation of the predicted point from the test circle,
//!   `|actual − centre| − radius`;
//! * CMM: the deviation of the cut surface along its normal. The tool is a rigid body, so
//!   the surface point moves with the tool reference point: `(actual − nominal) · n`.
//!
//! Set-up terms are columns beside the fit (`setup`), as a real test removes them: the
//! ball bar's centring (`sin θ`, `cos θ`) and length (a constant) per test circle, and the
//! CMM datum (a Z shift, `n_z`) per part.
//!
//! A CMM file may hold several parts: each is one run of the program, the runs in the
//! order of their start times, one after the other on the same machine (the slides' state
//! and the tool's cut length carry over; a tool wears across parts).

mod ballbar;
mod profile;
mod table;

pub(crate) use ballbar::{smallest_radius, test_circles};
pub(crate) use profile::surface_points;

use std::ops::Range;

use crate::error_model::sampling::SAMPLE_STEP_MM;
use crate::error_model::sampling::states;
use crate::error_model::sampling::{PathSample, sample_toolpath};
use crate::error_model::{Effect, ErrorModel, Sample};
use crate::geometry;
use crate::machine::ScrewPitch;
use crate::semantic::nose_radius::ToolTable;
use crate::semantic::{Lowered, Machine};
use crate::source::LineIndex;
use crate::syntax::Program;
use crate::toolpath::{Motion, Move, Toolpath, Validated, Xz};

use super::measured::{Direction, Kind, Measured};

/// The program as the measurement needs it: the nominal toolpath, the tool table, the
/// finishing passes (for CMM points), the source line of each move, and what the machine
/// settings say about the screws.
#[derive(Debug, Clone)]
pub struct Nominal {
    pub toolpath: Toolpath,
    pub tools: ToolTable,
    /// The moves of the finishing passes.
    pub finishing: Vec<Range<usize>>,
    /// The program line each move comes from (0 for none).
    pub move_lines: Vec<usize>,
    pub screw_pitch: ScrewPitch,
    /// The finished part, where the part model ran: a synthesised CMM profile is sampled
    /// only where its surface is (a finishing pass's lead-in in front of the stock, or a
    /// stretch a later groove or thread cut away, is no place a probe can touch).
    pub part: Option<crate::part::Part>,
}

impl Nominal {
    /// The nominal program of a validated lowering.
    pub fn new(program: &Program<'_>, lowered: &Validated<Lowered>, machine: &Machine) -> Nominal {
        let toolpath = lowered.valid().toolpath();
        let lines = LineIndex::new(program.source());
        let move_lines = toolpath
            .moves
            .iter()
            .map(|m| if m.source.is_synthetic() { 0 } else { lines.position(m.source.start).0 })
            .collect();
        let finishing = crate::simulation::finishing_moves(program, lowered).into_iter().map(|(_, r)| r).collect();
        Nominal {
            toolpath: toolpath.clone(),
            tools: ToolTable::from_machine(machine),
            finishing,
            move_lines,
            screw_pitch: ScrewPitch::default(),
            part: None,
        }
    }
}

/// A measurement that cannot be tied to the program.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ForwardError {
    #[error("the measurement has no points")]
    Empty,
    #[error(
        "the program has no test circle: a ball bar trace needs the program's full circles (G02/G03 with I K \
         ending where they start)"
    )]
    NoTestCircle,
    #[error("line {line}: this {found} trace has no test circle left in the program ({circles} in all, in order)")]
    NoCircleLeft { line: usize, found: &'static str, circles: usize },
    #[error("line {line}: a {found} trace, but the program's next test circle (line {circle_line}) is {expected}")]
    DirectionMismatch { line: usize, found: &'static str, expected: &'static str, circle_line: usize },
    #[error("the program has no cutting moves to match CMM points to")]
    NoCuts,
    /// A profile to make, with no point on the finished surface at the spacing asked for.
    #[error("no point of the program's finished surface to probe at a spacing of {spacing_mm} mm: {why}")]
    NoSurfaceToProbe { spacing_mm: f64, why: &'static str },
    #[error(
        "line {line}: the point x {x:.4} z {z:.4} is {distance:.3} mm from the nearest finished surface of the program"
    )]
    NotOnPart {
        line: usize,
        x: f64,
        z: f64,
        distance: f64,
        /// How far the point would be with its x halved, when that puts it on the part: its x
        /// was most likely a diameter.
        halved: Option<f64>,
    },
}

impl ForwardError {
    /// The line of the measurement file the error is about, if it is about one.
    pub fn line(&self) -> Option<usize> {
        match self {
            ForwardError::NoCircleLeft { line, .. }
            | ForwardError::DirectionMismatch { line, .. }
            | ForwardError::NotOnPart { line, .. } => Some(*line),
            _ => None,
        }
    }

    /// What is wrong, without the line.
    pub fn message(&self) -> String {
        let text = self.to_string();
        match self.line() {
            Some(line) => text.strip_prefix(&format!("line {line}: ")).unwrap_or(&text).to_string(),
            None => text,
        }
    }

    /// What would put it right, where a guess is possible.
    pub fn hint(&self) -> Option<String> {
        match self {
            ForwardError::NotOnPart { halved: Some(distance), .. } => Some(format!(
                "with its x halved the point lies {distance:.4} mm from the surface: the file's x is most likely a \
                 diameter; turnpass's own x_mm is a radius, so name the column `x_dia_mm` or `X diameter (mm)`, or \
                 write `x: diameter` above the header"
            )),
            ForwardError::NotOnPart { .. } => Some(
                "check that the file measures this program's part in its work coordinates: x from the axis of \
                 rotation, z from the program's Z0"
                    .to_string(),
            ),
            ForwardError::DirectionMismatch { .. } => {
                Some("the rows of a run follow the program's test circles in order; check the file's direction".into())
            }
            ForwardError::NoSurfaceToProbe { .. } => {
                Some("a surface shorter than the spacing gets no point: give --spacing a smaller figure".into())
            }
            _ => None,
        }
    }
}

/// How a point's reading follows from the predicted tool position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// Ball bar: `|actual − centre| − radius`.
    Radial { centre: Xz, radius: f64 },
    /// CMM: `(actual − nominal) · normal`.
    Normal { nominal: Xz, normal: Xz },
}

impl Projection {
    pub fn reading(&self, actual: Xz) -> f64 {
        match *self {
            Projection::Radial { centre, radius } => actual.distance(centre) - radius,
            Projection::Normal { nominal, normal } => {
                (actual.x - nominal.x) * normal.x + (actual.z - nominal.z) * normal.z
            }
        }
    }
}

/// One measured point and where it sits on the program.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Which run of the program (part) and which sample of the run.
    pub run: usize,
    pub sample: usize,
    pub projection: Projection,
    /// The measured reading (ball bar deviation, or normal deviation of the CMM point).
    pub measured: f64,
    /// The program line of the move the point lies on.
    pub line: usize,
    /// The point on the nominal surface (CMM) or circle (ball bar), for plots.
    pub nominal: Xz,
    /// Ball bar: the angle from +Z toward +X about the centre, degrees, and the direction.
    pub angle_deg: Option<f64>,
    pub direction: Option<Direction>,
    /// The set-up group: the test circle (ball bar) or the part (CMM).
    pub group: usize,
}

/// The set-up terms of one group of points, as a real test removes them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SetupTerms {
    /// Ball bar: the bar's length and its centring, `1, sin θ, cos θ`.
    LengthAndCentring,
    /// CMM: the datum's Z shift, `n_z`.
    DatumShift,
    /// Interferometer positioning: the laser's zero.
    Zero,
    /// Interferometer straightness: zero and alignment (a slope along the slide's axis).
    ZeroAndSlope { along_x: bool },
}

/// The forward model of one measurement.
#[derive(Debug, Clone)]
pub struct Forward {
    pub kind: Kind,
    /// The samples of one run of the (split) program.
    samples: Vec<PathSample>,
    start: Xz,
    /// Each run's start, minutes since machine start (`None`: the model's start for the
    /// first run, the end of the previous run for the others).
    runs: Vec<Option<f64>>,
    duration_s: f64,
    pub points: Vec<Point>,
    /// The names of the set-up groups (test circles, parts, or a table's quantities).
    pub groups: Vec<String>,
    /// Each group's set-up terms.
    pub setup: Vec<SetupTerms>,
}

/// The simulated reading of every point, and the machine state there.
#[derive(Debug, Clone)]
pub struct Simulation {
    pub readings: Vec<f64>,
    pub states: Vec<Sample>,
    pub actual: Vec<Xz>,
}

impl Forward {
    pub fn new(nominal: &Nominal, measured: &Measured) -> Result<Forward, ForwardError> {
        if measured.is_empty() {
            return Err(ForwardError::Empty);
        }
        match measured {
            Measured::BallBar(rows) => ballbar::forward(nominal, rows),
            Measured::Profile(points) => profile::forward(nominal, points),
            Measured::Table { axis, table } => Ok(table::forward(*axis, table)),
        }
    }

    pub fn len(&self) -> usize {
        self.points.len()
    }

    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    pub fn measured(&self) -> Vec<f64> {
        self.points.iter().map(|p| p.measured).collect()
    }

    /// Each run's start, minutes since machine start, for a model starting at `start_min`.
    pub fn run_starts(&self, start_min: f64) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.runs.len());
        for (k, given) in self.runs.iter().enumerate() {
            let previous = if k == 0 { start_min } else { out[k - 1] + self.duration_s / 60.0 };
            out.push(given.unwrap_or(previous));
        }
        out
    }

    /// The samples of every run, one after another, each timed from its run's start (in
    /// seconds after the model's start, as `predict` reads them).
    fn timed_samples(&self, start_min: f64) -> Vec<PathSample> {
        let starts = self.run_starts(start_min);
        let mut out = Vec::with_capacity(self.samples.len() * starts.len());
        for run_start in starts {
            let offset = (run_start - start_min) * 60.0;
            out.extend(self.samples.iter().map(|s| PathSample { t_s: s.t_s + offset, ..*s }));
        }
        out
    }

    /// Simulate the measurement on `model`.
    pub fn simulate(&self, model: &ErrorModel) -> Simulation {
        let samples = self.timed_samples(model.start_min);
        let nominal: Vec<Xz> = samples.iter().map(|s| s.nominal).collect();
        let all_states = states(&samples, &nominal, self.start, model);
        let per_run = self.samples.len();
        let mut out = Simulation {
            readings: Vec::with_capacity(self.points.len()),
            states: Vec::with_capacity(self.points.len()),
            actual: Vec::with_capacity(self.points.len()),
        };
        for p in &self.points {
            let index = p.run * per_run + p.sample;
            let Some(state) = all_states.get(index) else { continue };
            let actual = model.actual(state);
            out.readings.push(p.projection.reading(actual));
            out.states.push(*state);
            out.actual.push(actual);
        }
        out
    }

    /// How the readings change when `effect` is added to `model`, whose simulation is
    /// `base`. A term without play leaves the machine state where it was, so the change is
    /// its displacement at the states of `base`; one with play changes the state, and the
    /// measurement is simulated again.
    pub fn response(&self, model: &ErrorModel, base: &Simulation, effect: &Effect) -> Vec<f64> {
        let play = effect.play();
        if play.x == 0.0 && play.z == 0.0 {
            return self
                .points
                .iter()
                .zip(base.states.iter().zip(&base.actual))
                .zip(&base.readings)
                .map(|((p, (state, actual)), reading)| {
                    let d = effect.displacement(state);
                    p.projection.reading(Xz::new(actual.x + d.x, actual.z + d.z)) - reading
                })
                .collect();
        }
        let mut with = model.clone();
        with.effects.push(effect.clone());
        let simulated = self.simulate(&with);
        simulated.readings.iter().zip(&base.readings).map(|(a, b)| a - b).collect()
    }

    /// The set-up columns: the ball bar's length and centring per test circle, the CMM
    /// datum's Z shift per part, an interferometer's zero (and alignment).
    pub fn setup_columns(&self) -> Vec<Vec<f64>> {
        let mut columns = Vec::new();
        for (group, terms) in self.setup.iter().enumerate() {
            let of = |f: &dyn Fn(&Point) -> f64| -> Vec<f64> {
                self.points.iter().map(|p| if p.group == group { f(p) } else { 0.0 }).collect()
            };
            let angle = |p: &Point| p.angle_deg.unwrap_or(0.0).to_radians();
            match *terms {
                SetupTerms::LengthAndCentring => {
                    columns.push(of(&|_| 1.0));
                    columns.push(of(&|p| angle(p).sin()));
                    columns.push(of(&|p| angle(p).cos()));
                }
                SetupTerms::DatumShift => columns.push(of(&|p| match p.projection {
                    Projection::Normal { normal, .. } => normal.z,
                    Projection::Radial { .. } => 0.0,
                })),
                SetupTerms::Zero => columns.push(of(&|_| 1.0)),
                SetupTerms::ZeroAndSlope { along_x } => {
                    columns.push(of(&|_| 1.0));
                    columns.push(of(&|p| if along_x { p.nominal.x } else { p.nominal.z }));
                }
            }
        }
        columns
    }
}

/// A place on the program's path: a move and the fraction along it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Place {
    index: usize,
    param: f64,
}

/// Params closer than this along one move are one split point (for a full circle of
/// 50 mm radius, 3 nm of arc: far below any measurement, far above rounding).
const SAME_PARAM: f64 = 1e-8;

/// Split the toolpath's moves at `places` (each strictly inside its move, or at its end)
/// and sample it; returns the samples and, for each place, the index of its sample.
fn split_and_sample(toolpath: &Toolpath, tools: &ToolTable, places: &[Place]) -> (Vec<PathSample>, Vec<usize>) {
    // The split params of each move, sorted and merged.
    let mut cuts: Vec<Vec<f64>> = vec![Vec::new(); toolpath.moves.len()];
    for place in places {
        if let Some(list) = cuts.get_mut(place.index) {
            list.push(place.param.clamp(SAME_PARAM, 1.0));
        }
    }
    for list in &mut cuts {
        list.sort_by(f64::total_cmp);
        list.dedup_by(|b, a| *b - *a < SAME_PARAM);
        // The end of the move is its own end sample.
        if list.last().is_some_and(|&p| p > 1.0 - SAME_PARAM) {
            list.pop();
        }
    }
    let mut split = Toolpath { start: toolpath.start, moves: Vec::with_capacity(toolpath.moves.len() + places.len()) };
    // For each original move, the index of its first piece in the split path.
    let mut first_piece = Vec::with_capacity(toolpath.moves.len());
    for (index, m) in toolpath.moves.iter().enumerate() {
        first_piece.push(split.moves.len());
        let start = toolpath.start_of(index);
        let mut t_start = m.t_start;
        for &param in &cuts[index] {
            let part = Move { t_start, ..piece(start, m, param) };
            t_start = part.t_end;
            split.moves.push(part);
        }
        // The last piece is the move itself from the last cut on.
        split.moves.push(Move { t_start, ..*m });
    }
    // The sampling step `compensate` uses (the thesis' interpolation step).
    let samples = sample_toolpath(&split, tools, SAMPLE_STEP_MM);
    // The last sample of each piece is its end.
    let mut end_sample = vec![usize::MAX; split.moves.len()];
    for (i, s) in samples.iter().enumerate() {
        if let Some(slot) = end_sample.get_mut(s.move_index) {
            *slot = i;
        }
    }
    let index_of = places
        .iter()
        .map(|place| {
            let list = &cuts[place.index];
            let param = place.param.clamp(SAME_PARAM, 1.0);
            // The piece whose end is this param: the first cut at or after it (merged cuts
            // lie within SAME_PARAM), or the move's own end.
            let k = list.partition_point(|&c| c < param - SAME_PARAM);
            end_sample.get(first_piece[place.index] + k).copied().unwrap_or(usize::MAX)
        })
        .collect();
    (samples, index_of)
}

/// The part of move `m` (from `start`) up to `param`.
fn piece(start: Xz, m: &Move, param: f64) -> Move {
    let end = match m.motion {
        Motion::Cw | Motion::Ccw => {
            let ccw = m.motion == Motion::Ccw;
            let sweep = geometry::sweep(start, m.end, m.centre, ccw);
            let angle = geometry::angle(start, m.centre) + if ccw { sweep * param } else { -sweep * param };
            geometry::on_circle(m.centre, start.distance(m.centre), angle)
        }
        _ => Xz::new(start.x + (m.end.x - start.x) * param, start.z + (m.end.z - start.z) * param),
    };
    let t = m.t_start + (m.t_end - m.t_start) * param;
    Move { end, contour: end, t_end: t, ..*m }
}

/// Where `point` lies along move `index` of `toolpath` (fraction of its length or sweep),
/// for a point on or near the move.
fn param_on(toolpath: &Toolpath, index: usize, point: Xz) -> f64 {
    let m = &toolpath.moves[index];
    let start = toolpath.start_of(index);
    match m.motion {
        Motion::Cw | Motion::Ccw => {
            let ccw = m.motion == Motion::Ccw;
            let sweep = geometry::sweep(start, m.end, m.centre, ccw);
            let a0 = geometry::angle(start, m.centre);
            let a = geometry::angle(point, m.centre);
            let travelled = if ccw {
                (a - a0).rem_euclid(std::f64::consts::TAU)
            } else {
                (a0 - a).rem_euclid(std::f64::consts::TAU)
            };
            // Past the end of the sweep: the nearer end.
            if travelled > sweep {
                if travelled - sweep < std::f64::consts::TAU - travelled { 1.0 } else { 0.0 }
            } else {
                travelled / sweep
            }
        }
        _ => {
            let (dx, dz) = (m.end.x - start.x, m.end.z - start.z);
            let length2 = dx * dx + dz * dz;
            if length2 <= 0.0 {
                1.0
            } else {
                (((point.x - start.x) * dx + (point.z - start.z) * dz) / length2).clamp(0.0, 1.0)
            }
        }
    }
}

#[cfg(test)]
mod tests;
