//! Where the model and the measurement disagree: the residual's statistics grouped by the
//! program segment, the angle sector (ball bar) or surface feature (CMM), the direction of
//! motion, the axis-reversal zones and the time.

use serde::Serialize;

use super::forward::{Forward, Projection};
use super::measured::{Axis, Kind};
use crate::error_model::Sample;

/// Points within this travel (mm) of an axis reversal are in its reversal zone.
pub const REVERSAL_ZONE_MM: f64 = 1.0;
/// Time is split into this many equal spans.
const TIME_BINS: usize = 4;

/// The residual of one group of points.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Group {
    pub label: String,
    pub points: usize,
    pub mean_mm: f64,
    pub rms_mm: f64,
    pub peak_mm: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Breakdown {
    pub by_segment: Vec<Group>,
    /// Ball bar: 45° sectors; CMM: diameters, faces, arcs and tapers.
    pub by_place: Vec<Group>,
    pub by_direction: Vec<Group>,
    pub by_reversal: Vec<Group>,
    pub by_time: Vec<Group>,
}

/// Group `residual` (one value per point of `forward`), the points' machine state taken
/// from `states` (the working model's simulation); the points `kept` marks false (the
/// outliers) count nowhere.
pub fn breakdown(forward: &Forward, states: &[Sample], residual: &[f64], kept: &[bool]) -> Breakdown {
    let n = forward.points.len().min(states.len()).min(residual.len());
    let counts = |i: usize| kept.get(i).copied().unwrap_or(true);
    let label_by = |label: &dyn Fn(usize) -> Vec<String>| -> Vec<Group> {
        let mut groups: Vec<(String, Vec<f64>)> = Vec::new();
        for (i, &r) in residual.iter().enumerate().take(n).filter(|(i, _)| counts(*i)) {
            for l in label(i) {
                match groups.iter_mut().find(|(g, _)| *g == l) {
                    Some((_, values)) => values.push(r),
                    None => groups.push((l, vec![r])),
                }
            }
        }
        groups.into_iter().map(|(label, values)| group(label, &values)).collect()
    };
    let points = &forward.points;
    let table = match forward.kind {
        Kind::Table(axis) => Some(axis == Axis::X),
        _ => None,
    };
    let by_segment = label_by(&|i| {
        let p = &points[i];
        vec![match p.direction {
            Some(d) => format!("line {} ({})", p.line, d.name()),
            None if table.is_some() => forward.groups[p.group].clone(),
            None if forward.groups.len() > 1 => format!("line {}, {}", p.line, forward.groups[p.group]),
            None => format!("line {}", p.line),
        }]
    });
    // A table's travel in thirds.
    let (low, high) = points.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
        let at = if table == Some(true) { p.nominal.x } else { p.nominal.z };
        (lo.min(at), hi.max(at))
    });
    let by_place = label_by(&|i| {
        let p = &points[i];
        vec![match (p.angle_deg, p.projection, table) {
            (Some(angle), _, _) => {
                let sector = (angle.rem_euclid(360.0) / 45.0).floor() as i32 * 45;
                format!("{sector}°–{}°", sector + 45)
            }
            (None, _, Some(along_x)) => {
                let at = if along_x { p.nominal.x } else { p.nominal.z };
                let third = (((at - low) / (high - low).max(1e-9)) * 3.0).floor().clamp(0.0, 2.0);
                let from = low + (high - low) * third / 3.0;
                format!("targets {from:.1}–{:.1} mm", from + (high - low) / 3.0)
            }
            (None, Projection::Normal { normal, .. }, None) if normal.x.abs() > 0.999 => "diameters".to_string(),
            (None, Projection::Normal { normal, .. }, None) if normal.z.abs() > 0.999 => "faces".to_string(),
            _ => "arcs and tapers".to_string(),
        }]
    });
    let by_direction = label_by(&|i| {
        let p = &points[i];
        vec![match (p.direction, table) {
            (Some(d), _) => d.name().to_string(),
            (None, Some(along_x)) => {
                let d = if along_x { states[i].direction.x } else { states[i].direction.z };
                if d > 0 { "approached upward" } else { "approached downward" }.to_string()
            }
            (None, None) => {
                let v = states[i].velocity;
                let sign = |v: f64| {
                    if v > 1e-9 {
                        "+"
                    } else if v < -1e-9 {
                        "−"
                    } else {
                        "0"
                    }
                };
                format!("X{} Z{}", sign(v.x), sign(v.z))
            }
        }]
    });
    let by_reversal = label_by(&|i| {
        let s = &states[i];
        let mut out = Vec::new();
        if s.since_reversal.x < REVERSAL_ZONE_MM {
            out.push(format!("within {REVERSAL_ZONE_MM} mm after an X reversal"));
        }
        if s.since_reversal.z < REVERSAL_ZONE_MM {
            out.push(format!("within {REVERSAL_ZONE_MM} mm after a Z reversal"));
        }
        if out.is_empty() {
            out.push("away from reversals".to_string());
        }
        out
    });
    let (t0, t1) =
        states[..n].iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| (lo.min(s.t_min), hi.max(s.t_min)));
    let span = (t1 - t0).max(1e-9);
    let mut bins: Vec<Vec<f64>> = vec![Vec::new(); TIME_BINS];
    for i in (0..n).filter(|&i| counts(i)) {
        let k = (((states[i].t_min - t0) / span * TIME_BINS as f64).floor() as usize).min(TIME_BINS - 1);
        bins[k].push(residual[i]);
    }
    let by_time = bins
        .iter()
        .enumerate()
        .filter(|(_, values)| !values.is_empty())
        .map(|(k, values)| {
            let from = t0 + span * k as f64 / TIME_BINS as f64;
            let to = t0 + span * (k + 1) as f64 / TIME_BINS as f64;
            group(format!("t {from:.1}–{to:.1} min"), values)
        })
        .collect();
    Breakdown { by_segment, by_place, by_direction, by_reversal, by_time }
}

fn group(label: String, values: &[f64]) -> Group {
    let n = values.len().max(1) as f64;
    Group {
        label,
        points: values.len(),
        mean_mm: values.iter().sum::<f64>() / n,
        rms_mm: (values.iter().map(|v| v * v).sum::<f64>() / n).sqrt(),
        peak_mm: values.iter().fold(0.0, |m: f64, v| m.max(v.abs())),
    }
}
