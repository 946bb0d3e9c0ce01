//! `diagnose --plot`: the residual (measured − simulated, set-up removed) before and after
//! the effects `diagnose` found.
//!
//! * Ball bar: a polar plot, as `turnpass plot --polar`, of the residual against the angle,
//!   each direction before and after.
//! * CMM profile: the finished contour (Z across, X up) with the residual drawn along the
//!   surface normal, magnified so that the largest shows at about a twentieth of the part.

use plotters::prelude::*;

use super::{PlotError, PolarSeries, nice_division, path_chart, polar_chart};
use crate::diagnose::Diagnosis;
use crate::diagnose::forward::Projection;
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

fn ball_bar(title: &str, d: &Diagnosis) -> Result<String, PlotError> {
    let points = &d.forward.points;
    let series_of = |direction: Direction, residual: &[f64]| -> Vec<(f64, f64)> {
        points
            .iter()
            .zip(residual)
            .filter(|(p, _)| p.direction == Some(direction))
            .map(|(p, r)| (p.angle_deg.unwrap_or(0.0).to_radians(), r * 1000.0))
            .collect()
    };
    let series = [
        ("counter-clockwise, working model", Direction::Ccw, &d.residual_before, MAGENTA),
        ("counter-clockwise, with the effects found", Direction::Ccw, &d.residual_after, CYAN),
        ("clockwise, working model", Direction::Cw, &d.residual_before, RED),
        ("clockwise, with the effects found", Direction::Cw, &d.residual_after, BLUE),
    ]
    .map(|(label, direction, residual, colour)| PolarSeries {
        label: label.to_string(),
        colour,
        points: series_of(direction, residual),
    });
    polar_chart(|division| format!("{title}: residual before and after, {division} µm/div"), &series)
}

fn profile(title: &str, d: &Diagnosis) -> Result<String, PlotError> {
    let f = &d.forward;
    let mut order: Vec<usize> = (0..f.len()).collect();
    order.sort_by_key(|&i| (f.points[i].run, f.points[i].sample));
    let largest = d.residual_before.iter().chain(&d.residual_after).fold(0.0, |m: f64, r| m.max(r.abs()));
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in &f.points {
        lo = lo.min(p.nominal.x.min(p.nominal.z));
        hi = hi.max(p.nominal.x.max(p.nominal.z));
    }
    let size = (hi - lo).max(1.0);
    // A round magnification that draws the largest residual at about size / 20.
    let magnify = if largest > 0.0 { nice_division(size / 20.0 / largest) } else { 1.0 };
    // Lines along the path, broken between parts and across gaps of more than 2 mm.
    let lines = |value: &dyn Fn(usize) -> (f64, f64)| -> Vec<Vec<(f64, f64)>> {
        let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
        let mut previous: Option<usize> = None;
        for &i in &order {
            let p = &f.points[i];
            let joined =
                previous.is_some_and(|j| f.points[j].run == p.run && f.points[j].nominal.distance(p.nominal) <= 2.0);
            if !joined {
                out.push(Vec::new());
            }
            if let Some(line) = out.last_mut() {
                line.push(value(i));
            }
            previous = Some(i);
        }
        out.retain(|l| l.len() > 1);
        out
    };
    let along = |residual: &[f64]| {
        lines(&|i| {
            let p = &f.points[i];
            let normal = match p.projection {
                Projection::Normal { normal, .. } => normal,
                Projection::Radial { .. } => crate::toolpath::Xz::default(),
            };
            let r = residual.get(i).copied().unwrap_or(0.0) * magnify;
            (p.nominal.z + r * normal.z, p.nominal.x + r * normal.x)
        })
    };
    let nominal = lines(&|i| (f.points[i].nominal.z, f.points[i].nominal.x));
    let (before, after) = (along(&d.residual_before), along(&d.residual_after));
    path_chart(
        &format!("{title}: residual along the surface normal, magnified ×{magnify}"),
        &[
            ("nominal surface", &nominal, BLACK),
            ("residual, working model", &before, RED),
            ("residual, with the effects found", &after, BLUE),
        ],
    )
}
