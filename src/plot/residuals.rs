//! `diagnose --plot`: the residual (measured − simulated, set-up removed) before and after
//! the effects `diagnose` found.
//!
//! * Ball bar: a polar plot, as `turnpass plot --polar`, of the residual against the angle,
//!   each direction before and after, with the ISO 230-4 figures of the residual.
//! * CMM profile: the finished contour at true scale with the residual drawn along the
//!   surface normal, magnified so that the largest shows plainly, with a micrometre scale
//!   bar, and under it the residual in µm along the cut.

use super::palette::{AFTER, AFTER_SECOND, BEFORE, BEFORE_SECOND};
use super::path::{self, Along, NormalDeviation, PathFigure, Series};
use super::polar::{self, PolarFigure, PolarSeries};
use super::{PlotError, iso_table};
use crate::diagnose::Diagnosis;
use crate::diagnose::forward::Projection;
use crate::diagnose::iso230_4;
use crate::diagnose::measured::{Direction, Kind};

/// The residual plot of a diagnosis.
pub fn residuals_svg(title: &str, d: &Diagnosis) -> Result<String, PlotError> {
    match d.forward.kind {
        Kind::BallBar => ball_bar(title, d),
        Kind::Profile => profile(title, d),
        Kind::Table(_) => {
            Err(PlotError::NotDrawn("an interferometer table (`turnpass model report` gives its figures)"))
        }
    }
}

const STATES: [&str; 2] = ["working model", "with the effects found"];

fn ball_bar(title: &str, d: &Diagnosis) -> Result<String, PlotError> {
    let points = &d.forward.points;
    let residuals = [&d.residual_before, &d.residual_after];
    let series_of = |direction: Direction, residual: &[f64]| -> Vec<(f64, f64)> {
        points
            .iter()
            .zip(residual)
            .filter(|(p, _)| p.direction == Some(direction))
            .map(|(p, r)| (p.angle_deg.unwrap_or(0.0).to_radians(), r * 1000.0))
            .collect()
    };
    let mut series = Vec::new();
    for (k, direction) in [Direction::Cw, Direction::Ccw].into_iter().enumerate() {
        for (after, residual) in residuals.iter().enumerate() {
            let colour = [[BEFORE, BEFORE_SECOND], [AFTER, AFTER_SECOND]][after][k];
            let name = if k == 0 { "clockwise" } else { "counter-clockwise" };
            series.push(PolarSeries {
                label: format!("{name}, {}", STATES[after]),
                colour,
                dashed: k == 1,
                points: series_of(direction, residual),
            });
        }
    }
    series.retain(|s| !s.points.is_empty());
    let figures = residuals.map(|residual| {
        let (mut angles, mut values, mut directions) = (Vec::new(), Vec::new(), Vec::new());
        for (p, r) in points.iter().zip(residual.iter()) {
            if let (Some(angle), Some(direction)) = (p.angle_deg, p.direction) {
                angles.push(angle);
                values.push(*r);
                directions.push(direction);
            }
        }
        iso230_4::figures(&angles, &values, &directions)
    });
    polar::draw(&PolarFigure {
        title,
        what: "residual, measured − simulated (set-up removed)",
        series,
        zero_label: "0 µm: no residual".to_string(),
        notes: vec![format!("{} readings; noise floor {:.2} µm", points.len(), d.noise_floor_mm * 1000.0)],
        table_title: "ISO 230-4 of the residual (µm)".to_string(),
        table: iso_table(STATES, &figures),
    })
}

fn profile(title: &str, d: &Diagnosis) -> Result<String, PlotError> {
    let f = &d.forward;
    let mut order: Vec<usize> = (0..f.len()).collect();
    order.sort_by_key(|&i| (f.points[i].run, f.points[i].sample));
    // Runs along the path, broken between parts and across gaps of more than 2 mm, with
    // the length along each.
    let mut runs: Vec<Vec<usize>> = Vec::new();
    let mut previous: Option<usize> = None;
    for &i in &order {
        let p = &f.points[i];
        let joined =
            previous.is_some_and(|j| f.points[j].run == p.run && f.points[j].nominal.distance(p.nominal) <= 2.0);
        match runs.last_mut() {
            Some(run) if joined => run.push(i),
            _ => runs.push(vec![i]),
        }
        previous = Some(i);
    }
    runs.retain(|r| r.len() > 1);
    let mut along = vec![0.0; f.len()];
    let mut length = 0.0;
    for run in &runs {
        for pair in run.windows(2) {
            along[pair[0]] = length;
            length += f.points[pair[0]].nominal.distance(f.points[pair[1]].nominal);
        }
        if let Some(&last) = run.last() {
            along[last] = length;
        }
    }
    let nominal =
        runs.iter().map(|run| run.iter().map(|&i| (f.points[i].nominal.z, f.points[i].nominal.x)).collect()).collect();
    let deviations = |residual: &[f64]| -> Vec<Vec<NormalDeviation>> {
        runs.iter()
            .map(|run| {
                run.iter()
                    .map(|&i| {
                        let p = &f.points[i];
                        let normal = match p.projection {
                            Projection::Normal { normal, .. } => normal,
                            Projection::Radial { .. } => crate::toolpath::Xz::default(),
                        };
                        NormalDeviation {
                            at: p.nominal,
                            normal,
                            mm: residual.get(i).copied().unwrap_or(0.0),
                            along_mm: along[i],
                        }
                    })
                    .collect()
            })
            .collect()
    };
    let drawn = path::draw(&PathFigure {
        title,
        side_unknown: false,
        nominal_label: "nominal surface",
        nominal,
        rapids: Vec::new(),
        series: vec![
            Series { label: "residual, working model", colour: BEFORE, runs: deviations(&d.residual_before) },
            Series { label: "residual, with the effects found", colour: AFTER, runs: deviations(&d.residual_after) },
        ],
        magnify: None,
        section: None,
        along: Along::Cut,
        notes: Vec::new(),
    })?;
    Ok(drawn.svg)
}
