//! `turnpass plot` and the plots of `report` and `diagnose --plot`, as SVG.
//!
//! **Path plot** (`path.rs`). Z across, X (radius) up, as a lathe drawing, at true scale:
//! a millimetre of Z and of X are the same length on the page. The error is drawn as what
//! it is on the part, the deviation along the surface normal, `(p − n)·N` for a predicted
//! point `p` measured from its point `n` of the nominal path with the unit normal `N` there
//! (from the part toward the tool); it is drawn at `n + k (p − n)·N N`, magnified `k` times,
//! the factor stated on the plot with a micrometre scale bar. Without `--magnify` the
//! factor is the round one that draws the largest deviation at a thirtieth of the part.
//! Deviation along the path slides a point along the surface, which cuts the same part, so
//! it is not drawn. Rapids are dashed and never magnified, and the tick labels read the
//! nominal millimetres they stand at. Under the drawing the same deviations in µm against
//! the cutting length, before and after.
//!
//! **Part plot** (`part_svg`: `plot --part`, and `report` when the measure is the part). The same
//! drawing with the finished part in place of the paths: the nominal surface where the part
//! measure probed it, and each actual part's signed deviation there along the nominal
//! surface's outward normal (+ material left, drawn away from the part), magnified as the
//! path plot is; under it the same in µm against the length along the surface. The probes
//! come ray by ray; `surface_runs` puts them in order along the surface.
//!
//! **Polar plot** (`polar.rs`, a ball-bar test: a program that goes all the way round a
//! circle). The radial deviation of each predicted point, `|p − c| − |n − c|`, against its
//! angle about the circle's centre, for each direction the program goes round, before and
//! after, with the ISO 230-4 figures of each (`diagnose/iso230_4.rs`) and the test's radius,
//! feed and directions beside the drawing.
//!
//! **Residual plots** (`diagnose --plot`, `residuals.rs`): the measured − simulated
//! residual before and after the effects found, polar for a ball bar, along the surface
//! for a CMM profile, with the same figures.
//!
//! Colours are Okabe and Ito's (`palette.rs`). The SVG is written to a string; the caller
//! writes the file.

mod palette;
mod path;
mod polar;
pub mod residuals;
mod scale;

use crate::compensation::Paths;
use crate::compensation::verify::PartPoint;
use crate::diagnose::iso230_4;
use crate::diagnose::measured::Direction;
use crate::geometry;
use crate::part::Part;
use crate::toolpath::{Motion, Toolpath, ValidToolpath, Xz};

pub use path::Drawn;
use path::{Along, NormalDeviation, PathFigure, Section, Series};
use polar::{PolarFigure, PolarSeries};
use scale::micrometres;

/// A plot that could not be drawn.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlotError {
    #[error("the program has no cutting moves to plot")]
    NothingToPlot,
    #[error("the program has no full circle (arcs about one centre sweeping 360°) for a polar plot")]
    NoFullCircle,
    #[error("drawing failed: {0}")]
    Drawing(String),
    #[error("no plot is drawn for {0}")]
    NotDrawn(&'static str),
}

fn drawing<E: std::fmt::Debug>(e: E) -> PlotError {
    PlotError::Drawing(format!("{e:?}"))
}

/// Polylines in the (Z, X) plane.
pub(crate) type Lines = Vec<Vec<(f64, f64)>>;

/// A predicted cutting point measured from its point of the nominal path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPoint {
    /// The point of the nominal path it is measured from, and the nominal toolpath's move
    /// that point lies on.
    pub nominal: Xz,
    pub move_index: usize,
    /// The motion of the point's own move (in the program it was predicted for), which
    /// gives a ball bar trace its direction.
    pub motion: Motion,
    /// The unit normal of the surface there, from the part toward the tool (zero where the
    /// tool's side is not known: no nose-radius compensation and no tip direction).
    pub normal: Xz,
    /// The direction of travel there (any length above zero).
    pub travel: Xz,
    /// Where the model puts the tool.
    pub predicted: Xz,
    /// Cutting length along the nominal path, mm.
    pub along_mm: f64,
    /// The point follows the one before it along the cut (no rapid or other break between).
    pub joined: bool,
}

impl PathPoint {
    /// The unit normal the deviation is measured along, and whether it is the surface's
    /// (from the part toward the tool) or, where the tool's side is not known, the left of
    /// the direction of travel.
    pub fn side(&self) -> (Xz, bool) {
        if self.normal.x != 0.0 || self.normal.z != 0.0 {
            return (self.normal, true);
        }
        let length = self.travel.x.hypot(self.travel.z);
        if length > 0.0 {
            (Xz::new(self.travel.z / length, -self.travel.x / length), false)
        } else {
            (Xz::new(0.0, 0.0), false)
        }
    }

    /// The deviation along the normal (`side`), mm: positive away from the part.
    pub fn normal_deviation_mm(&self) -> f64 {
        let (normal, _) = self.side();
        (self.predicted.x - self.nominal.x) * normal.x + (self.predicted.z - self.nominal.z) * normal.z
    }

    /// The radial deviation about `centre`, mm: positive outward.
    fn radial_deviation_mm(&self, centre: Xz) -> f64 {
        self.predicted.distance(centre) - self.nominal.distance(centre)
    }
}

/// The points of `compensate`'s paths of `toolpath` (one per cutting sample, before and
/// after), each measured from its own sample.
pub fn points_of(toolpath: ValidToolpath<'_>, paths: &Paths) -> [Vec<PathPoint>; 2] {
    let mut out = [Vec::new(), Vec::new()];
    let mut along = 0.0;
    let mut previous: Option<usize> = None;
    for (j, s) in paths.samples.iter().enumerate() {
        if !s.cutting {
            continue;
        }
        along += s.covers_mm;
        let joined = previous == Some(j.wrapping_sub(1));
        previous = Some(j);
        for (points, predicted) in out.iter_mut().zip([&paths.uncompensated, &paths.compensated]) {
            let Some(&predicted) = predicted.get(j) else { continue };
            points.push(PathPoint {
                nominal: s.nominal,
                move_index: s.move_index,
                motion: toolpath.moves.get(s.move_index).map_or(Motion::Feed, |m| m.motion),
                normal: s.normal,
                travel: s.velocity,
                predicted,
                along_mm: along,
                joined,
            });
        }
    }
    out
}

/// The path plot of `toolpath` (the nominal part), with `before` (as programmed) and
/// `after` (compensated) drawn along the normal, magnified `magnify` times or as much as
/// makes the largest deviation plain.
pub fn path_svg(
    title: &str,
    toolpath: ValidToolpath<'_>,
    (before, after): (&[PathPoint], &[PathPoint]),
    magnify: Option<f64>,
    part: Option<&Part>,
) -> Result<Drawn, PlotError> {
    let (nominal, rapids) = nominal_lines(&toolpath);
    let series = |label, colour, points: &[PathPoint]| Series { label, colour, runs: runs(points) };
    let side_unknown = before.iter().chain(after).any(|p| !p.side().1);
    path::draw(&PathFigure {
        title,
        side_unknown,
        nominal_label: "nominal",
        nominal,
        rapids,
        series: vec![series("as programmed", palette::BEFORE, before), series("compensated", palette::AFTER, after)],
        magnify,
        section: part.map(section),
        along: Along::Cut,
        notes: Vec::new(),
    })
}

/// The most points of a part figure; a larger part's are taken at even intervals along
/// each run (its ends kept).
const PART_POINTS: usize = 20_000;

/// The part figure: `part`'s half-section (the nominal part `toolpath` cuts) with the
/// deviation of each actual part at `points` (`PartDeviation::points`, probed `spacing_mm`
/// apart) drawn along the nominal surface's outward normal, magnified `magnify` times or
/// as much as makes the largest plain; under it the same in µm along the surface.
pub fn part_svg(
    title: &str,
    toolpath: ValidToolpath<'_>,
    (points, spacing_mm): (&[PartPoint], f64),
    magnify: Option<f64>,
    part: Option<&Part>,
) -> Result<Drawn, PlotError> {
    let surface = surface_runs(&toolpath, points, spacing_mm);
    if surface.iter().all(|run| run.len() < 2) {
        return Err(PlotError::NotDrawn("a part with no probed stretch of surface"));
    }
    let stride = points.len().div_ceil(PART_POINTS).max(1);
    let surface: Vec<Vec<(PartPoint, f64)>> = surface
        .into_iter()
        .map(|run| {
            let last = run.len() - 1;
            run.into_iter().enumerate().filter(|(k, _)| k % stride == 0 || *k == last).map(|(_, p)| p).collect()
        })
        .collect();
    let nominal: Lines = surface
        .iter()
        .filter(|run| run.len() > 1)
        .map(|run| run.iter().map(|(p, _)| (p.at.z, p.at.x)).collect())
        .collect();
    // Each series unbroken where its part was probed at every point of a run.
    let runs = |deviation: fn(&PartPoint) -> Option<f64>| {
        let mut out: Vec<Vec<NormalDeviation>> = Vec::new();
        for run in &surface {
            let mut open = false;
            for (p, along_mm) in run {
                match deviation(p) {
                    Some(mm) => {
                        let d = NormalDeviation { at: p.at, normal: p.normal, mm, along_mm: *along_mm };
                        match out.last_mut() {
                            Some(current) if open => current.push(d),
                            _ => out.push(vec![d]),
                        }
                        open = true;
                    }
                    None => open = false,
                }
            }
        }
        out
    };
    let notes = vec![
        format!(
            "the finished part each program cuts on the model, probed at {} points of the nominal surface {:.4} mm \
             apart,",
            points.len(),
            spacing_mm
        ),
        "along the nominal part's outward normal: + material left, − material removed inside the part".to_string(),
    ];
    path::draw(&PathFigure {
        title,
        side_unknown: false,
        nominal_label: "nominal surface (probed)",
        nominal,
        rapids: Vec::new(),
        series: vec![
            Series { label: "as programmed", colour: palette::BEFORE, runs: runs(|p| p.before_mm) },
            Series { label: "compensated", colour: palette::AFTER, runs: runs(|p| p.after_mm) },
        ],
        magnify,
        section: part.map(section),
        along: Along::Surface,
        notes,
    })
}

/// The probed points in runs along the surface, each with its length along the surface
/// (mm, counted on from run to run). The points come ray by ray, so they are ordered by the
/// original's move that cut them (the stock's own faces after, by their normal) and, within
/// one, along that move (its projection on the move's path: a line's direction, an arc's
/// angle; points level with each other across it, as on a groove's bottom, by their offset
/// from it). A point joins the run nearest it that ends within twice the rays' spacing, else
/// starts one: a move's two sides (a groove's walls) are two runs, not one zigzag. Runs whose
/// ends meet (the next move's stretch of the same surface, a groove's other wall, a thread
/// flank cut pass by pass) are then joined, so that each run is a stretch of one surface.
fn surface_runs(toolpath: &Toolpath, points: &[PartPoint], spacing_mm: f64) -> Vec<Vec<(PartPoint, f64)>> {
    let reach = 2.0 * spacing_mm;
    // Along the move and across it, mm.
    let place = |p: &PartPoint| -> (f64, f64) {
        let Some((k, m)) = p.original_move.and_then(|k| toolpath.moves.get(k).map(|m| (k, m))) else {
            // A face of the stock is straight: along its tangent, across along its normal.
            return (p.normal.z * p.at.x - p.normal.x * p.at.z, p.normal.x * p.at.x + p.normal.z * p.at.z);
        };
        let start = toolpath.start_of(k);
        if m.is_arc() {
            let ccw = m.motion == Motion::Ccw;
            let sweep = geometry::sweep(start, m.end, m.centre, ccw);
            let turned = geometry::angle(p.at, m.centre) - geometry::angle(start, m.centre);
            let turned = if ccw { turned } else { -turned }.rem_euclid(std::f64::consts::TAU);
            // A point before the start (cut by the nose as it arrives) is a little short of
            // a whole turn: it counts from the start backwards.
            let turned =
                if turned > (sweep + std::f64::consts::TAU) / 2.0 { turned - std::f64::consts::TAU } else { turned };
            return (turned * start.distance(m.centre), p.at.distance(m.centre));
        }
        let (dz, dx) = (m.end.z - start.z, m.end.x - start.x);
        let length = dz.hypot(dx);
        if length.is_nan() || length <= 0.0 {
            return (0.0, 0.0);
        }
        let (vz, vx) = (p.at.z - start.z, p.at.x - start.x);
        ((vz * dz + vx * dx) / length, (vx * dz - vz * dx) / length)
    };
    // The stock's faces grouped by their normal, after every move.
    let group = |p: &PartPoint| match p.original_move {
        Some(k) => (k, 0, 0),
        None => (usize::MAX, (p.normal.z.round() as i64 + 1) as usize, (p.normal.x.round() as i64 + 1) as usize),
    };
    // Level across the move: the same place along it to a nanometre.
    let level = |along: f64| (along * 1e6).round();
    let mut ordered: Vec<(PartPoint, (f64, f64))> = points.iter().map(|p| (*p, place(p))).collect();
    ordered.sort_by(|a, b| {
        (group(&a.0).cmp(&group(&b.0))).then(level(a.1.0).total_cmp(&level(b.1.0))).then(a.1.1.total_cmp(&b.1.1))
    });
    // The runs, each with where its last point is along its move; the runs still open (their
    // last point within reach of where the points have come to along the move).
    let mut runs: Vec<(Vec<PartPoint>, f64)> = Vec::new();
    let mut open: Vec<usize> = Vec::new();
    let mut current = None;
    for (p, (along, _)) in ordered {
        if current != Some(group(&p)) {
            open.clear();
            current = Some(group(&p));
        }
        open.retain(|&r| along - runs[r].1 <= reach);
        let nearest = open
            .iter()
            .map(|&r| (r, runs[r].0.last().map_or(f64::INFINITY, |q| q.at.distance(p.at))))
            .filter(|(_, d)| *d <= reach)
            .min_by(|a, b| a.1.total_cmp(&b.1));
        match nearest {
            Some((r, _)) => {
                runs[r].0.push(p);
                runs[r].1 = along;
            }
            None => {
                runs.push((vec![p], along));
                open.push(runs.len() - 1);
            }
        }
    }
    let joined = joined(runs.into_iter().map(|(run, _)| run).collect(), reach);
    let mut along = 0.0;
    joined
        .into_iter()
        .map(|run| {
            let mut previous: Option<Xz> = None;
            run.into_iter()
                .map(|p| {
                    along += previous.map_or(0.0, |q| q.distance(p.at));
                    previous = Some(p.at);
                    (p, along)
                })
                .collect()
        })
        .collect()
}

/// `runs` joined where an end of one is within `reach` of an end of another (the nearest),
/// each chain grown from its first run forward, then backward, in the order of `runs`.
fn joined(runs: Vec<Vec<PartPoint>>, reach: f64) -> Vec<Vec<PartPoint>> {
    use std::collections::{HashMap, VecDeque};
    let cell = |p: Xz| ((p.z / reach).floor() as i64, (p.x / reach).floor() as i64);
    // Each run's ends by the cell they are in: the run, and whether it is its last point.
    let mut ends: HashMap<(i64, i64), Vec<(usize, bool)>> = HashMap::new();
    for (r, run) in runs.iter().enumerate() {
        if let (Some(first), Some(last)) = (run.first(), run.last()) {
            ends.entry(cell(first.at)).or_default().push((r, false));
            ends.entry(cell(last.at)).or_default().push((r, true));
        }
    }
    let mut runs: Vec<Option<Vec<PartPoint>>> = runs.into_iter().map(Some).collect();
    let nearest = |at: Xz, runs: &[Option<Vec<PartPoint>>]| -> Option<(usize, bool)> {
        let (cz, cx) = cell(at);
        let mut best: Option<(usize, bool, f64)> = None;
        for (dz, dx) in (-1..=1).flat_map(|dz| (-1..=1).map(move |dx| (dz, dx))) {
            for &(r, last) in ends.get(&(cz + dz, cx + dx)).into_iter().flatten() {
                let Some(run) = &runs[r] else { continue };
                let end = if last { run.last() } else { run.first() };
                let Some(d) = end.map(|p| p.at.distance(at)) else { continue };
                if d <= reach && best.is_none_or(|b| d < b.2) {
                    best = Some((r, last, d));
                }
            }
        }
        best.map(|(r, last, _)| (r, last))
    };
    let mut out = Vec::new();
    for r in 0..runs.len() {
        let Some(first) = runs[r].take() else { continue };
        let mut chain: VecDeque<PartPoint> = first.into();
        while let Some((s, last)) = chain.back().and_then(|p| nearest(p.at, &runs)) {
            let mut next = runs[s].take().unwrap_or_default();
            if last {
                next.reverse();
            }
            chain.extend(next);
        }
        while let Some((s, last)) = chain.front().and_then(|p| nearest(p.at, &runs)) {
            let mut before = runs[s].take().unwrap_or_default();
            if !last {
                before.reverse();
            }
            for p in before.into_iter().rev() {
                chain.push_front(p);
            }
        }
        out.push(chain.into());
    }
    out
}

/// The half-section of `part`: its stock's outline and the part's.
fn section(part: &Part) -> Section {
    let stock = &part.stock;
    Section {
        stock: vec![
            (stock.back, stock.bore),
            (stock.front, stock.bore),
            (stock.front, stock.outer),
            (stock.back, stock.outer),
        ],
        stock_assumed: stock.assumed,
        part: part.outline(),
    }
}

/// The points in unbroken runs, as deviations along the normal.
fn runs(points: &[PathPoint]) -> Vec<Vec<NormalDeviation>> {
    let mut out: Vec<Vec<NormalDeviation>> = Vec::new();
    for p in points {
        let d =
            NormalDeviation { at: p.nominal, normal: p.side().0, mm: p.normal_deviation_mm(), along_mm: p.along_mm };
        match out.last_mut() {
            Some(run) if p.joined => run.push(d),
            _ => out.push(vec![d]),
        }
    }
    out
}

/// The cutting moves as polylines (arcs in steps of at most 2°), and the other moves.
fn nominal_lines(toolpath: &Toolpath) -> (Lines, Lines) {
    let (mut cuts, mut rapids): (Lines, Lines) = (Vec::new(), Vec::new());
    let mut previous_cut: Option<bool> = None;
    for (k, m) in toolpath.moves.iter().enumerate() {
        if m.motion == Motion::Dwell {
            continue;
        }
        let start = toolpath.start_of(k);
        let lines = if m.cutting { &mut cuts } else { &mut rapids };
        if previous_cut != Some(m.cutting) || lines.is_empty() {
            lines.push(vec![(start.z, start.x)]);
        }
        previous_cut = Some(m.cutting);
        let Some(line) = lines.last_mut() else { continue };
        if m.is_arc() {
            let ccw = m.motion == Motion::Ccw;
            let sweep = geometry::sweep(start, m.end, m.centre, ccw);
            let (a0, radius) = (geometry::angle(start, m.centre), start.distance(m.centre));
            let steps = (sweep.to_degrees() / 2.0).ceil().max(1.0) as usize;
            for i in 1..steps {
                let a = a0 + if ccw { 1.0 } else { -1.0 } * sweep * i as f64 / steps as f64;
                line.push((m.centre.z + radius * a.cos(), m.centre.x + radius * a.sin()));
            }
        }
        line.push((m.end.z, m.end.x));
    }
    cuts.retain(|l| l.len() > 1);
    rapids.retain(|l| l.len() > 1);
    (cuts, rapids)
}

/// The circle a ball-bar program goes round: the centre whose cutting arcs sweep the most,
/// when they sweep a full turn.
fn full_circle(toolpath: &Toolpath) -> Option<Xz> {
    let mut sweeps: Vec<(Xz, f64)> = Vec::new();
    for (k, m) in toolpath.moves.iter().enumerate() {
        if !m.is_arc() || !m.cutting {
            continue;
        }
        let sweep = geometry::sweep(toolpath.start_of(k), m.end, m.centre, m.motion == Motion::Ccw);
        match sweeps.iter_mut().find(|(c, _)| c.distance(m.centre) < 1e-6) {
            Some((_, total)) => *total += sweep,
            None => sweeps.push((m.centre, sweep)),
        }
    }
    let (centre, sweep) = sweeps.into_iter().max_by(|a, b| a.1.total_cmp(&b.1))?;
    (sweep >= std::f64::consts::TAU - 1e-6).then_some(centre)
}

/// The polar (ball-bar) plot of `toolpath`'s full circle, `before` (as programmed) and
/// `after` (compensated).
pub fn polar_svg(
    title: &str,
    toolpath: ValidToolpath<'_>,
    before: &[PathPoint],
    after: &[PathPoint],
) -> Result<String, PlotError> {
    let centre = full_circle(&toolpath).ok_or(PlotError::NoFullCircle)?;
    let on_circle =
        |k: usize| toolpath.moves.get(k).filter(|m| m.is_arc() && m.cutting && m.centre.distance(centre) < 1e-6);
    // The test: radius, feeds and directions in the order the program goes round.
    let (mut radius, mut feeds, mut order) = (0.0, Vec::<f64>::new(), Vec::<Direction>::new());
    for k in (0..toolpath.moves.len()).filter(|&k| on_circle(k).is_some()) {
        let m = &toolpath.moves[k];
        radius = toolpath.start_of(k).distance(centre);
        if !feeds.iter().any(|f| (f - m.feed).abs() < 1e-9) {
            feeds.push(m.feed);
        }
        let direction = if m.motion == Motion::Ccw { Direction::Ccw } else { Direction::Cw };
        if order.last() != Some(&direction) {
            order.push(direction);
        }
    }
    // Per state, the angles (degrees), radial deviations (mm) and directions.
    let traces = |points: &[PathPoint]| {
        let mut trace = (Vec::new(), Vec::new(), Vec::new());
        for p in points.iter().filter(|p| p.motion.is_arc() && on_circle(p.move_index).is_some()) {
            trace.0.push(geometry::angle(p.nominal, centre).to_degrees());
            trace.1.push(p.radial_deviation_mm(centre));
            trace.2.push(if p.motion == Motion::Ccw { Direction::Ccw } else { Direction::Cw });
        }
        trace
    };
    let states = [("as programmed", traces(before)), ("compensated", traces(after))];
    let mut series = Vec::new();
    for (k, direction) in [Direction::Cw, Direction::Ccw].into_iter().enumerate() {
        for (state, (angles, deviations, directions)) in &states {
            let points: Vec<(f64, f64)> = (angles.iter().zip(deviations).zip(directions))
                .filter(|(_, d)| **d == direction)
                .map(|((a, d), _)| (a.to_radians(), d * 1000.0))
                .collect();
            if points.is_empty() {
                continue;
            }
            let after = *state == "compensated";
            let colour = match (after, k) {
                (false, 0) => palette::BEFORE,
                (false, _) => palette::BEFORE_SECOND,
                (true, 0) => palette::AFTER,
                (true, _) => palette::AFTER_SECOND,
            };
            series.push(PolarSeries {
                label: format!("{}, {state}", name_of(direction)),
                colour,
                dashed: k == 1,
                points,
            });
        }
    }
    let feeds: Vec<String> = feeds.iter().map(|f| format!("{} mm/min", micrometres(*f))).collect();
    let notes = vec![
        format!("radius {radius:.3} mm (X as a radius)"),
        format!("centre Z {:.3}, X {:.3} mm", centre.z, centre.x),
        format!("feed {}", feeds.join(", ")),
        format!("direction {}", order.iter().map(|d| name_of(*d)).collect::<Vec<_>>().join(", then ")),
    ];
    let figures = states.each_ref().map(|(_, (a, d, dir))| iso230_4::figures(a, d, dir));
    polar::draw(&PolarFigure {
        title,
        what: "radial deviation predicted on the model",
        series,
        zero_label: format!("0 µm: the nominal radius, {radius:.3} mm"),
        notes,
        table_title: "ISO 230-4 (µm)".to_string(),
        table: iso_table(["as programmed", "compensated"], &figures),
    })
}

fn name_of(direction: Direction) -> &'static str {
    match direction {
        Direction::Cw => "clockwise (G02)",
        Direction::Ccw => "counter-clockwise (G03)",
    }
}

/// The ISO 230-4 figures of two states as rows of text: G per direction (about the
/// minimum-zone centre), G(b), H, and F's largest and smallest.
fn iso_table(states: [&str; 2], figures: &[iso230_4::Figures; 2]) -> Vec<Vec<String>> {
    let um = |mm: Option<f64>| mm.map_or_else(|| "–".to_string(), |mm| format!("{:.2}", mm * 1000.0));
    let row = |label: &str, value: &dyn Fn(&iso230_4::Figures) -> Option<f64>| {
        let mut row = vec![label.to_string()];
        row.extend(figures.iter().map(|f| um(value(f))));
        row
    };
    vec![
        vec![String::new(), states[0].to_string(), states[1].to_string()],
        row("G, clockwise", &|f| f.cw.map(|c| c.g_mm)),
        row("G, counter-clockwise", &|f| f.ccw.map(|c| c.g_mm)),
        row("G(b), both", &|f| f.both.map(|c| c.g_mm)),
        row("H, hysteresis", &|f| f.hysteresis_mm),
        row("F, largest", &|f| f.both.or(f.cw).or(f.ccw).map(|c| c.f_max_mm)),
        row("F, smallest", &|f| f.both.or(f.cw).or(f.ccw).map(|c| c.f_min_mm)),
        vec!["G about the minimum-zone centre, F about the least-squares one".to_string()],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A groove plunged by one move: its bottom and both walls come ray by ray (both walls on
    /// each ray along Z) and leave as one run along its surface, down one wall, across the
    /// bottom and up the other, no two points in it more than twice the spacing apart.
    #[test]
    fn a_grooves_walls_and_bottom_are_one_run_along_its_surface() {
        let ready = crate::compensation::test_support::ready(
            "G21 G99\nG97 S1000 M03\nG00 X40. Z-5.\nG01 X20. F0.1\nG00 X40.\nM30\n",
        );
        let toolpath = ready.valid();
        let plunge = toolpath.moves.iter().position(|m| m.cutting).unwrap();
        let spacing = 0.1;
        let point = |z: f64, x: f64, normal: Xz| PartPoint {
            at: Xz::new(x, z),
            normal,
            original_move: Some(plunge),
            before_mm: Some(0.002),
            after_mm: Some(0.0),
        };
        let mut points: Vec<PartPoint> =
            (0..=30).map(|k| point(-6.5 + 0.1 * f64::from(k), 10.0, Xz::new(1.0, 0.0))).collect();
        for k in 1..=50 {
            let x = 10.0 + 0.1 * f64::from(k);
            points.push(point(-6.5, x, Xz::new(0.0, 1.0)));
            points.push(point(-3.5, x, Xz::new(0.0, -1.0)));
        }
        let runs = surface_runs(&toolpath, &points, spacing);
        assert_eq!(runs.len(), 1, "{:?}", runs.iter().map(Vec::len).collect::<Vec<_>>());
        let run = &runs[0];
        assert_eq!(run.len(), points.len());
        for pair in run.windows(2) {
            assert!(pair[0].0.at.distance(pair[1].0.at) <= 2.0 * spacing + 1e-9, "{:?}", (pair[0].0.at, pair[1].0.at));
            assert!(pair[1].1 > pair[0].1, "the length along the surface grows");
        }
        let ends = [run[0].0.at, run[run.len() - 1].0.at];
        assert!(
            ends.iter().all(|p| (p.x - 15.0).abs() < 1e-9),
            "the run goes from a wall's top to the other's: {ends:?}"
        );
    }
}
