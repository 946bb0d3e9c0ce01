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
use crate::diagnose::iso230_4;
use crate::diagnose::measured::Direction;
use crate::geometry;
use crate::part::Part;
use crate::toolpath::{Motion, Toolpath, ValidToolpath, Xz};

pub use path::Drawn;
use path::{NormalDeviation, PathFigure, Section, Series};
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
    })
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
