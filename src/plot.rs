//! `turnpass plot`: the nominal, actual and compensated paths as SVG.
//!
//! **Path plot.** Z across, X (radius) up, as a lathe drawing. Each sample's predicted
//! point is drawn at `nominal + magnify · (predicted − nominal)`: the error magnified
//! about the nominal path (×10 by default, as the thesis' Fig. 66), so micrometres show on
//! a part of tens of millimetres. Three paths: the nominal cutting path, the actual one
//! (the program as written, through the model) and the compensated one (the compensated
//! program, rounded as written, through the model).
//!
//! **Polar plot** (a ball-bar test: a program that goes all the way round a circle). The
//! radial deviation of each predicted point, `|p − c| − |n − c|`, against its angle about
//! the circle's centre, drawn around a base circle with rings one division apart, for each
//! direction the program goes round (clockwise and counter-clockwise), before and after.
//!
//! **Residual plots** (`diagnose --plot`, `residuals.rs`): the measured − simulated
//! residual before and after the effects found, polar for a ball bar, along the surface
//! for a CMM profile.
//!
//! The SVG is written to a string; the caller writes the file.

pub mod residuals;

use plotters::prelude::*;

use crate::compensation::program::Paths;
use crate::geometry;
use crate::toolpath::{Motion, Toolpath, Xz};

const SIZE: (u32, u32) = (1000, 750);

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

/// The magnified path plot.
pub fn path_svg(title: &str, paths: &Paths, magnify: f64) -> Result<String, PlotError> {
    let magnified = |points: &[Xz]| -> Vec<Vec<(f64, f64)>> {
        runs(paths, |j| {
            let (n, p) = (paths.samples[j].nominal, points[j]);
            (n.z + magnify * (p.z - n.z), n.x + magnify * (p.x - n.x))
        })
    };
    let nominal = runs(paths, |j| (paths.samples[j].nominal.z, paths.samples[j].nominal.x));
    if nominal.is_empty() {
        return Err(PlotError::NothingToPlot);
    }
    let actual = magnified(&paths.uncompensated);
    let compensated = magnified(&paths.compensated);
    let caption = format!("{title}: error magnified ×{magnify}");
    path_chart(
        &caption,
        &[("nominal", &nominal, BLACK), ("actual (as programmed)", &actual, RED), ("compensated", &compensated, BLUE)],
    )
}

/// Polylines in the (Z, X) plane.
pub(crate) type Lines = Vec<Vec<(f64, f64)>>;

/// Lines in the (Z, X) plane, each series a colour and a legend entry, drawn to fit.
pub(crate) fn path_chart(caption: &str, series: &[(&str, &Lines, RGBColor)]) -> Result<String, PlotError> {
    let all = series.iter().flat_map(|(_, lines, _)| lines.iter().flatten());
    let (mut z0, mut z1, mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for &(z, x) in all {
        (z0, z1, x0, x1) = (z0.min(z), z1.max(z), x0.min(x), x1.max(x));
    }
    if !z0.is_finite() {
        return Err(PlotError::NothingToPlot);
    }
    let pad = 0.05 * (z1 - z0).max(x1 - x0).max(1e-3);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(caption, ("sans-serif", 22))
            .margin(20)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(z0 - pad..z1 + pad, x0 - pad..x1 + pad)
            .map_err(drawing)?;
        chart.configure_mesh().x_desc("Z (mm)").y_desc("X, radius (mm)").draw().map_err(drawing)?;
        for &(label, lines, colour) in series {
            for (k, line) in lines.iter().enumerate() {
                let drawn = chart.draw_series(LineSeries::new(line.iter().copied(), colour)).map_err(drawing)?;
                if k == 0 {
                    drawn.label(label).legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
                }
            }
        }
        chart.configure_series_labels().background_style(WHITE).border_style(BLACK).draw().map_err(drawing)?;
        root.present().map_err(drawing)?;
    }
    Ok(svg)
}

/// The cutting samples in runs of consecutive cutting samples, mapped through `point`.
fn runs(paths: &Paths, point: impl Fn(usize) -> (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut open = false;
    for (j, s) in paths.samples.iter().enumerate() {
        if !s.cutting {
            open = false;
            continue;
        }
        if !open {
            out.push(Vec::new());
            open = true;
        }
        if let Some(line) = out.last_mut() {
            line.push(point(j));
        }
    }
    out.retain(|l| l.len() > 1);
    out
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

/// The polar (ball-bar) plot.
pub fn polar_svg(title: &str, toolpath: &Toolpath, paths: &Paths) -> Result<String, PlotError> {
    let centre = full_circle(toolpath).ok_or(PlotError::NoFullCircle)?;
    // Per direction, the angle and the radial deviations (µm) before and after.
    let mut points: [Vec<(f64, f64, f64)>; 2] = [Vec::new(), Vec::new()];
    for (j, s) in paths.samples.iter().enumerate() {
        let Some(m) = toolpath.moves.get(s.move_index) else { continue };
        if !m.is_arc() || !s.cutting || m.centre.distance(centre) >= 1e-6 {
            continue;
        }
        let radius = s.nominal.distance(centre);
        let deviation = |p: Xz| (p.distance(centre) - radius) * 1000.0;
        let angle = geometry::angle(s.nominal, centre);
        let direction = usize::from(m.motion == Motion::Ccw);
        points[direction].push((angle, deviation(paths.uncompensated[j]), deviation(paths.compensated[j])));
    }
    let series = [
        ("clockwise, as programmed", 0, false, RED),
        ("clockwise, compensated", 0, true, BLUE),
        ("counter-clockwise, as programmed", 1, false, MAGENTA),
        ("counter-clockwise, compensated", 1, true, CYAN),
    ]
    .map(|(label, direction, after, colour)| PolarSeries {
        label: label.to_string(),
        colour,
        points: points[direction]
            .iter()
            .map(|&(angle, before, compensated)| (angle, if after { compensated } else { before }))
            .collect(),
    });
    polar_chart(
        |division| {
            format!("{title}: radial deviation, {division} µm/div, centre Z{:.3} X{:.3} (radius)", centre.z, centre.x)
        },
        &series,
    )
}

/// One line of a polar plot: (angle from +Z toward +X, radial deviation in µm) points.
pub(crate) struct PolarSeries {
    pub label: String,
    pub colour: RGBColor,
    pub points: Vec<(f64, f64)>,
}

/// Radial deviations drawn around a base circle with rings one division apart; the
/// caption is given the division (µm) the data need.
pub(crate) fn polar_chart(caption: impl Fn(f64) -> String, series: &[PolarSeries]) -> Result<String, PlotError> {
    let largest = series.iter().flat_map(|s| &s.points).map(|&(_, d)| d.abs()).fold(0.0, f64::max);
    let division = nice_division(largest / 2.0);
    let base = 4.0 * division;
    let extent = base + 3.0 * division;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 800)).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(caption(division), ("sans-serif", 18))
            .margin(20)
            .build_cartesian_2d(-extent..extent, -extent..extent)
            .map_err(drawing)?;
        let ring = |r: f64| (0..=360).map(move |d| polar(r, f64::from(d).to_radians()));
        for k in -2..=2 {
            let style = if k == 0 { BLACK.stroke_width(2) } else { BLACK.mix(0.3).stroke_width(1) };
            chart.draw_series(LineSeries::new(ring(base + f64::from(k) * division), style)).map_err(drawing)?;
        }
        for s in series {
            let mut line: Vec<(f64, f64)> = s.points.iter().map(|&(angle, d)| polar(base + d, angle)).collect();
            if line.len() < 2 {
                continue;
            }
            line.dedup();
            let colour = s.colour;
            chart
                .draw_series(LineSeries::new(line, colour))
                .map_err(drawing)?
                .label(s.label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
        }
        chart.configure_series_labels().background_style(WHITE).border_style(BLACK).draw().map_err(drawing)?;
        root.present().map_err(drawing)?;
    }
    Ok(svg)
}

/// A point at radius `r` and angle `a` (from +Z toward +X) in the plot's (Z, X) axes.
fn polar(r: f64, a: f64) -> (f64, f64) {
    (r * a.cos(), r * a.sin())
}

/// 1, 2 or 5 times a power of ten, at least `value` (and at least 0.1 µm).
fn nice_division(value: f64) -> f64 {
    let value = value.max(0.1);
    let power = 10f64.powf(value.log10().floor());
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|k| k * power).find(|d| *d >= value).unwrap_or(10.0 * power)
}
