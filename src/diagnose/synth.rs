//! Synthetic measurements from a truth model (`turnpass synth`), so that the workflow can
//! be tried on data in which an effect is known to hide.
//!
//! A ball bar trace has one row every `step_deg` of travel round each test circle of the
//! program, in program order; a CMM profile has points every `spacing_mm` along the
//! finished surface, on each part (a run of the program at its start time); an
//! interferometer table has both directions at each target. The readings
//! are the forward model's (`forward.rs`) on the truth model, with no set-up error, plus
//! normal noise of `noise_mm` from a seeded generator: the same seed gives the same file.
//! `glitches` readings, chosen by a generator of their own from the same seed (so the
//! other readings keep their noise), are off by `glitch_mm` either way: a probe's glitches.

use std::fmt::Write as _;

use super::forward::{Forward, ForwardError, Nominal, Projection, surface_points, test_circles};
use super::measured::{BallBarRow, Kind, Measured, ProfilePoint};
use super::noise::Noise;
use crate::error_model::ErrorModel;
use crate::error_model::interferometer::{Profile, SlideTable};

#[derive(Debug, Clone, PartialEq)]
pub struct SynthOptions {
    /// Standard deviation of the gauge's noise, mm.
    pub noise_mm: f64,
    pub seed: u64,
    /// Ball bar: degrees of travel between rows.
    pub step_deg: f64,
    /// CMM: mm along the surface between points.
    pub spacing_mm: f64,
    /// CMM: the start time of each part, minutes since machine start (`None`: right after
    /// the previous part, the first at the model's start).
    pub parts: Vec<Option<f64>>,
    /// Interferometer table: the targets, mm along the slide.
    pub targets: Vec<f64>,
    /// How many readings are glitches, and by how much (either sign), mm.
    pub glitches: usize,
    pub glitch_mm: f64,
}

impl Default for SynthOptions {
    fn default() -> SynthOptions {
        SynthOptions {
            noise_mm: 0.0,
            seed: 1,
            step_deg: 1.0,
            spacing_mm: 0.5,
            parts: vec![None],
            targets: (0..=20).map(|k| f64::from(k) * 5.0).collect(),
            glitches: 0,
            glitch_mm: 0.025,
        }
    }
}

/// Synthesise a measurement of `kind` of the program `nominal` on the machine `truth`.
pub fn synth(
    nominal: &Nominal,
    truth: &ErrorModel,
    kind: Kind,
    options: &SynthOptions,
) -> Result<Measured, ForwardError> {
    let template = match kind {
        Kind::BallBar => {
            let step = if options.step_deg.is_finite() && options.step_deg > 0.0 { options.step_deg } else { 1.0 };
            let mut rows = Vec::new();
            for (direction, start) in test_circles(nominal) {
                let count = (360.0 / step).round().max(1.0) as usize;
                for k in 1..=count {
                    let travel = 360.0 * k as f64 / count as f64;
                    // `+ 0.0` turns the −0 of a whole turn clockwise into 0.
                    let angle = (start + direction.sign() * travel).rem_euclid(360.0) + 0.0;
                    rows.push(BallBarRow { angle_deg: angle, deviation_mm: 0.0, direction, line: rows.len() + 2 });
                }
            }
            Measured::BallBar(rows)
        }
        Kind::Profile => {
            let mut surface = surface_points(nominal, options.spacing_mm);
            let spacing_mm = options.spacing_mm;
            if surface.is_empty() {
                let why = "every surface the program finishes is shorter than the spacing";
                return Err(ForwardError::NoSurfaceToProbe { spacing_mm, why });
            }
            if let Some(part) = &nominal.part {
                surface.retain(|&p| part.is_on_surface(p));
                if surface.is_empty() {
                    let why = "later cuts remove every point of the finished passes from the part";
                    return Err(ForwardError::NoSurfaceToProbe { spacing_mm, why });
                }
            }
            let parts = if options.parts.is_empty() { vec![None] } else { options.parts.clone() };
            let several = parts.len() > 1;
            let mut points = Vec::new();
            for (k, start) in parts.iter().enumerate() {
                for p in &surface {
                    points.push(ProfilePoint {
                        x_mm: p.x,
                        z_mm: p.z,
                        part: several.then(|| format!("P{}", k + 1)),
                        start_min: *start,
                        line: points.len() + 2,
                    });
                }
            }
            Measured::Profile(points)
        }
        Kind::Table(axis) => {
            let mut targets = options.targets.clone();
            targets.sort_by(f64::total_cmp);
            targets.dedup();
            let n = targets.len();
            let profile = Profile {
                targets,
                up: vec![0.0; n],
                down: vec![0.0; n],
                up_sigma: vec![0.0; n],
                down_sigma: vec![0.0; n],
                up_measured: vec![true; n],
                down_measured: vec![true; n],
                up_runs: vec![1; n],
                down_runs: vec![1; n],
            };
            let table = SlideTable {
                linear: Some(profile.clone()),
                straightness: Some(profile),
                angular: None,
                rows: 2 * n,
                straightness_by_reversal: false,
            };
            Measured::Table { axis, table: Box::new(table) }
        }
    };
    let forward = Forward::new(nominal, &template)?;
    let simulated = forward.simulate(truth);
    let mut noise = Noise::new(options.seed);
    let mut readings: Vec<f64> = simulated.readings.iter().map(|r| r + noise.normal(options.noise_mm)).collect();
    for (i, sign) in glitches(readings.len(), options.glitches, options.seed) {
        readings[i] += sign * options.glitch_mm;
    }
    readings.iter_mut().for_each(|r| *r = (*r * 1e7).round() / 1e7);
    Ok(match template {
        Measured::BallBar(rows) => Measured::BallBar(
            rows.into_iter().zip(&readings).map(|(row, &r)| BallBarRow { deviation_mm: r, ..row }).collect(),
        ),
        Measured::Profile(points) => Measured::Profile(
            points
                .into_iter()
                .zip(forward.points.iter().zip(&readings))
                .map(|(p, (point, &r))| {
                    let normal = match point.projection {
                        Projection::Normal { normal, .. } => normal,
                        Projection::Radial { .. } => crate::toolpath::Xz::default(),
                    };
                    ProfilePoint { x_mm: point.nominal.x + r * normal.x, z_mm: point.nominal.z + r * normal.z, ..p }
                })
                .collect(),
        ),
        Measured::Table { axis, mut table } => {
            // The points come quantity by quantity, target by target, up then down.
            let mut values = readings.iter();
            for profile in [&mut table.linear, &mut table.straightness].into_iter().flatten() {
                for k in 0..profile.targets.len() {
                    profile.up[k] = values.next().copied().unwrap_or(0.0);
                    profile.down[k] = values.next().copied().unwrap_or(0.0);
                }
            }
            Measured::Table { axis, table }
        }
    })
}

/// The finest `step_deg` of a ball bar trace of `nominal` on a machine whose finest
/// increment is `increment_mm`: a row moves the tool at least an increment round the
/// program's smallest test circle (rows closer than that are rows of one position, and
/// their number would follow the option, not the test). `None` for a program with no test
/// circle.
pub fn finest_step_deg(nominal: &Nominal, increment_mm: f64) -> Option<f64> {
    super::forward::smallest_radius(nominal).map(|radius| (increment_mm / radius).to_degrees())
}

/// `count` distinct readings of `n` (in order) and the sign of each one's glitch, from a
/// generator of their own for `seed`.
pub fn glitches(n: usize, count: usize, seed: u64) -> Vec<(usize, f64)> {
    let mut pick = Noise::new(seed ^ 0x6C69_7463_6867);
    let mut out: Vec<(usize, f64)> = Vec::new();
    while out.len() < count.min(n) {
        let i = ((pick.uniform() * n as f64) as usize).min(n - 1);
        let sign = if pick.uniform() < 0.5 { -1.0 } else { 1.0 };
        if !out.iter().any(|(j, _)| *j == i) {
            out.push((i, sign));
        }
    }
    out.sort_by_key(|(i, _)| *i);
    out
}

/// A measurement as the CSV `diagnose` reads.
pub fn to_csv(measured: &Measured) -> String {
    let mut out = String::new();
    match measured {
        Measured::BallBar(rows) => {
            out.push_str("angle_deg,deviation_mm,direction\n");
            for r in rows {
                let _ = writeln!(out, "{:.4},{:.7},{}", r.angle_deg, r.deviation_mm, r.direction.name());
            }
        }
        Measured::Profile(points) => {
            let parts = points.iter().any(|p| p.part.is_some());
            let times = points.iter().any(|p| p.start_min.is_some());
            let mut header = vec!["x_mm", "z_mm"];
            if parts {
                header.push("part");
            }
            if times {
                header.push("start_min");
            }
            let _ = writeln!(out, "{}", header.join(","));
            for p in points {
                let _ = write!(out, "{:.7},{:.7}", p.x_mm, p.z_mm);
                if parts {
                    let _ = write!(out, ",{}", p.part.as_deref().unwrap_or(""));
                }
                if times {
                    let _ = write!(out, ",{}", p.start_min.map_or(String::new(), |t| format!("{t}")));
                }
                out.push('\n');
            }
        }
        Measured::Table { table, .. } => {
            let quantities: Vec<(&str, &Profile)> =
                [("linear_mm", &table.linear), ("straightness_mm", &table.straightness)]
                    .into_iter()
                    .filter_map(|(name, p)| p.as_ref().map(|p| (name, p)))
                    .collect();
            let names: Vec<&str> = quantities.iter().map(|q| q.0).collect();
            let _ = writeln!(out, "target_mm,direction,{}", names.join(","));
            let targets = quantities.first().map_or(&[][..], |q| &q.1.targets[..]);
            for (k, target) in targets.iter().enumerate() {
                for (direction, up) in [("up", true), ("down", false)] {
                    let values: Vec<String> = quantities
                        .iter()
                        .map(|(_, p)| format!("{:.7}", if up { p.up[k] } else { p.down[k] }))
                        .collect();
                    let _ = writeln!(out, "{target:.4},{direction},{}", values.join(","));
                }
            }
        }
    }
    out
}
