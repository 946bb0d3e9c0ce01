//! What no catalogued effect explains: when the workflow stops with a residual above the
//! noise floor and no candidate significant, it says so, says where the residual is, and
//! offers the fallback a metrologist uses — the residual itself as a measured table of one
//! slide (`[[axis_table]]`, `error_model::interferometer`), which `--write-model` writes
//! when the data cover that slide.
//!
//! A table is a function of one slide's position: its straightness (the displacement
//! across it, X as a function of z for the Z slide, Z of x for the X slide) or its
//! positioning error (along it). Each is fitted to the residual as a piecewise-linear
//! function of the position (a tent at each target, the table's own interpolation), its
//! reading at each point the displacement times the point's sensitivity to a displacement
//! in that direction (a CMM point on a face does not see X). The targets are spaced 0.5,
//! 1, 2, 5 or 10 mm apart; the quantity and spacing with the lowest BIC are kept, if the
//! table is significant by the F-test and the BIC, and the targets with data cover at
//! least `COVERED` of the span between the first and the last. Then the model with the
//! table is simulated, and the residual it leaves is reported: a table that does not close
//! the gap through the forward model is not offered.

use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use super::breakdown::{Group, breakdown};
use super::forward::{Forward, Simulation};
use super::lsq::{self, Base};
use super::measured::{Axis, Kind};
use super::select::{ALPHA, BIC_MARGIN};
use crate::error_model::effects::{ToolOffsetX, ToolOffsetZ, X, Z};
use crate::error_model::htm::AxisTables;
use crate::error_model::interferometer::{Profile, SlideTable};
use crate::error_model::{Effect, ErrorModel};

/// A residual RMS above this many times the noise floor is a residual to explain: the part
/// beyond the noise, `√(1.5² − 1) ≈ 1.1` noise standard deviations, is then as large as the
/// noise itself. Closer to the floor, the floor's own estimate (a median over the points)
/// is too uncertain to tell a remainder from noise.
pub const ABOVE_NOISE: f64 = 1.5;
/// The share of the targets between the first and the last that must have data.
pub const COVERED: f64 = 0.8;
/// The target spacings tried, mm.
const SPACINGS: [f64; 5] = [0.5, 1.0, 2.0, 5.0, 10.0];
/// A place whose RMS is this much above the whole residual's is named.
const NAMED_ABOVE: f64 = 1.2;

/// Which quantity of a slide's table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// The displacement across the slide as it travels (`straightness_mm`).
    Straightness,
    /// The displacement along it (`linear_mm`).
    Positioning,
}

impl Quantity {
    /// The table's column.
    pub fn column(self) -> &'static str {
        match self {
            Quantity::Straightness => "straightness_mm",
            Quantity::Positioning => "linear_mm",
        }
    }
}

/// The residual as a measured table of one slide.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResidualTable {
    /// The slide (the table's `axis`).
    #[serde(serialize_with = "axis_name")]
    pub axis: Axis,
    pub quantity: Quantity,
    pub spacing_mm: f64,
    pub targets: Vec<f64>,
    /// The displacement at each target, mm (X as a radius).
    pub values: Vec<f64>,
    /// The share of the residual sum of squares the fit explains, %.
    pub explained_percent: f64,
    pub p_value: f64,
    pub delta_bic: f64,
    /// The residual RMS of the model with the table, simulated, mm.
    pub rms_after_mm: f64,
}

fn axis_name<S: serde::Serializer>(axis: &Axis, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(match axis {
        Axis::X => "x",
        Axis::Z => "z",
    })
}

impl ResidualTable {
    /// The table's slide, lower case, as a model file names it.
    pub fn axis_name(&self) -> &'static str {
        match self.axis {
            Axis::X => "x",
            Axis::Z => "z",
        }
    }

    /// The table as the model's ISO 230-2 CSV, one direction only: the residual is not
    /// told apart by direction, so no reversal was measured, and a table of one direction
    /// gives both the same values (and `model report` no reversal value).
    pub fn csv(&self) -> String {
        let mut out = format!("target_mm,direction,{}\n", self.quantity.column());
        for (t, v) in self.targets.iter().zip(&self.values) {
            out.push_str(&format!("{t:.4},up,{v:.7}\n"));
        }
        out
    }

    /// The table as `csv` reads back.
    fn profile(&self) -> Profile {
        let n = self.targets.len();
        Profile {
            targets: self.targets.clone(),
            up: self.values.clone(),
            down: self.values.clone(),
            up_sigma: vec![0.0; n],
            down_sigma: vec![0.0; n],
            up_measured: vec![true; n],
            down_measured: vec![false; n],
            up_runs: vec![1; n],
            down_runs: vec![0; n],
        }
    }

    /// `model` with this table as its slide's.
    pub fn applied_to(&self, model: &ErrorModel) -> ErrorModel {
        let mut out = model.clone();
        let tables = out.tables.get_or_insert_with(AxisTables::default);
        let slide = match self.axis {
            Axis::X => &mut tables.x,
            Axis::Z => &mut tables.z,
        };
        match self.quantity {
            Quantity::Straightness => slide.straightness = Some(self.profile()),
            Quantity::Positioning => slide.linear = Some(self.profile()),
        }
        out
    }
}

/// A significant residual that no catalogued effect explains.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Unexplained {
    pub rms_mm: f64,
    pub noise_floor_mm: f64,
    /// Where the residual is largest: the places (segments, features or sectors,
    /// directions, reversal zones, times) whose RMS is well above the whole residual's.
    pub places: Vec<Group>,
    /// The residual as a measured table, when one holds it.
    pub table: Option<ResidualTable>,
    /// Why no table is offered, when none is.
    pub no_table: Option<String>,
}

/// What the analysis needs of the workflow's end.
pub struct Inputs<'a> {
    pub forward: &'a Forward,
    /// The final model and its simulation.
    pub model: &'a ErrorModel,
    pub simulation: &'a Simulation,
    pub measured: &'a [f64],
    /// The fixed columns (set-up, outliers) and the found effects' columns.
    pub base: Base,
    /// The final residual, and which points count.
    pub residual: &'a [f64],
    pub kept: &'a [bool],
    pub noise_floor_mm: f64,
}

pub fn analyse(inputs: &Inputs<'_>) -> Unexplained {
    let rms_mm = rms_kept(inputs.residual, inputs.kept);
    let b = breakdown(inputs.forward, &inputs.simulation.states, inputs.residual, inputs.kept);
    let mut places: Vec<Group> = [&b.by_segment, &b.by_place, &b.by_direction, &b.by_reversal, &b.by_time]
        .into_iter()
        .flat_map(|groups| groups.iter().filter(|g| g.points > 1 && g.rms_mm > NAMED_ABOVE * rms_mm).cloned())
        .collect();
    places.sort_by(|a, b| b.rms_mm.total_cmp(&a.rms_mm));
    places.truncate(4);
    let (table, no_table) = match table(inputs) {
        Ok(table) => (Some(table), None),
        Err(why) => (None, Some(why)),
    };
    Unexplained { rms_mm, noise_floor_mm: inputs.noise_floor_mm, places, table, no_table }
}

/// A table that might hold the residual, fitted.
struct Trial {
    axis: Axis,
    quantity: Quantity,
    spacing: f64,
    targets: Vec<f64>,
    values: Vec<f64>,
    rss: f64,
    p_value: f64,
    delta_bic: f64,
}

fn table(inputs: &Inputs<'_>) -> Result<ResidualTable, String> {
    if matches!(inputs.forward.kind, Kind::Table(_)) {
        return Err("the measurement is an interferometer table already".into());
    }
    let f = inputs.forward;
    let n = inputs.measured.len();
    // The readings' change for a unit displacement of the tool in X, and in Z.
    let probe = 1e-3;
    let sensitivity = |effect: Effect| -> Vec<f64> {
        f.response(inputs.model, inputs.simulation, &effect).iter().map(|r| r / probe).collect()
    };
    let along_x = sensitivity(Effect::ToolOffsetX(ToolOffsetX { d: probe, axis: X }));
    let along_z = sensitivity(Effect::ToolOffsetZ(ToolOffsetZ { d: probe, axis: Z }));
    let x: Vec<f64> = inputs.simulation.states.iter().map(|s| s.at.x).collect();
    let z: Vec<f64> = inputs.simulation.states.iter().map(|s| s.at.z).collect();
    let has_table = |axis: Axis| {
        inputs.model.tables.as_ref().is_some_and(|t| {
            let slide: &SlideTable = if axis == Axis::X { &t.x } else { &t.z };
            slide.linear.is_some() || slide.straightness.is_some() || slide.angular.is_some()
        })
    };
    let residual: Vec<f64> = inputs.measured.iter().zip(&inputs.simulation.readings).map(|(m, s)| m - s).collect();
    let residual_perp = inputs.base.residual_of(&residual);
    let rss0: f64 = residual_perp.iter().map(|r| r * r).sum();
    let kept = inputs.kept.iter().filter(|k| **k).count();
    let options = [
        (Axis::Z, Quantity::Straightness, &z, &along_x),
        (Axis::X, Quantity::Straightness, &x, &along_z),
        (Axis::Z, Quantity::Positioning, &z, &along_z),
        (Axis::X, Quantity::Positioning, &x, &along_x),
    ];
    let mut best: Option<Trial> = None;
    let mut reasons: Vec<String> = Vec::new();
    for (axis, quantity, position, sensitivity) in options {
        if has_table(axis) {
            reasons.push(format!("the model has a table of the {} slide already", axis.letter()));
            continue;
        }
        let seen: Vec<usize> =
            (0..n).filter(|&i| inputs.kept[i] && sensitivity[i].abs() > 1e-3).collect::<Vec<usize>>();
        if seen.len() < 5 {
            continue;
        }
        let (low, high) = seen
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &i| (lo.min(position[i]), hi.max(position[i])));
        for spacing in SPACINGS {
            let first = (low / spacing).floor() * spacing;
            let count = ((high - first) / spacing).ceil() as usize + 1;
            if !(3..=200).contains(&count) || count * 4 > kept {
                continue;
            }
            let targets: Vec<f64> = (0..count).map(|k| first + spacing * k as f64).collect();
            // A tent at each target: the table's linear interpolation.
            let columns: Vec<(f64, Vec<f64>)> = targets
                .iter()
                .map(|&t| {
                    let column: Vec<f64> = (0..n)
                        .map(|i| {
                            let w = 1.0 - (position[i] - t).abs() / spacing;
                            if w > 0.0 { w * sensitivity[i] } else { 0.0 }
                        })
                        .collect();
                    (t, column)
                })
                .filter(|(_, c)| c.iter().any(|v| v.abs() > 1e-6))
                .collect();
            if (columns.len() as f64) < COVERED * count as f64 {
                reasons.push(format!(
                    "the data cover {} of {count} places {spacing} mm apart along the {} slide",
                    columns.len(),
                    axis.letter()
                ));
                continue;
            }
            let projected: Vec<Vec<f64>> = columns.iter().map(|(_, c)| inputs.base.residual_of(c)).collect();
            let Some((values, rank)) = least_squares(&projected, &residual_perp) else { continue };
            let fitted: Vec<f64> = (0..n).map(|i| projected.iter().zip(&values).map(|(c, v)| c[i] * v).sum()).collect();
            let rss: f64 = residual_perp.iter().zip(&fitted).map(|(r, f)| (r - f).powi(2)).sum();
            let dof = n.saturating_sub(inputs.base.rank() + rank);
            let (_, p_value) = lsq::f_test(rss0, rss, rank, dof);
            let delta_bic = kept as f64 * (rss.max(f64::MIN_POSITIVE) / rss0).ln() + rank as f64 * (kept as f64).ln();
            if best.as_ref().is_none_or(|b| delta_bic < b.delta_bic) {
                best = Some(Trial {
                    axis,
                    quantity,
                    spacing,
                    targets: columns.iter().map(|(t, _)| *t).collect(),
                    values,
                    rss,
                    p_value,
                    delta_bic,
                });
            }
        }
    }
    let Some(best) = best else {
        reasons.sort();
        reasons.dedup();
        return Err(if reasons.is_empty() {
            "no slide's position is covered by enough points".to_string()
        } else {
            reasons.join("; ")
        });
    };
    if best.p_value >= ALPHA || best.delta_bic >= -BIC_MARGIN {
        return Err(format!(
            "no table of a slide explains it (the best, the {} slide's {}, p = {:.1e}, ΔBIC = {:.1})",
            best.axis.letter(),
            best.quantity.column(),
            best.p_value,
            best.delta_bic
        ));
    }
    let mut table = ResidualTable {
        axis: best.axis,
        quantity: best.quantity,
        spacing_mm: best.spacing,
        targets: best.targets,
        values: best.values,
        explained_percent: if rss0 > 0.0 { 100.0 * (rss0 - best.rss) / rss0 } else { 0.0 },
        p_value: best.p_value,
        delta_bic: best.delta_bic,
        rms_after_mm: f64::NAN,
    };
    // Through the forward model: the set-up, outliers and found effects refitted beside it.
    let with = table.applied_to(inputs.model);
    let simulated = f.simulate(&with);
    let difference: Vec<f64> = inputs.measured.iter().zip(&simulated.readings).map(|(m, s)| m - s).collect();
    table.rms_after_mm = rms_kept(&inputs.base.residual_of(&difference), inputs.kept);
    if table.rms_after_mm.partial_cmp(&rms_kept(inputs.residual, inputs.kept)) != Some(std::cmp::Ordering::Less) {
        return Err(format!(
            "the best table, the {} slide's {}, does not close the gap through the model",
            table.axis.letter(),
            table.quantity.column()
        ));
    }
    Ok(table)
}

/// The least-squares coefficients of `columns` for `y` by the normal equations, with the
/// directions the columns cannot tell apart (a constant that the set-up takes) left at
/// zero: the pseudo-inverse of `AᵀA`. Also the rank used.
fn least_squares(columns: &[Vec<f64>], y: &[f64]) -> Option<(Vec<f64>, usize)> {
    let m = columns.len();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let ata = DMatrix::from_fn(m, m, |i, j| dot(&columns[i], &columns[j]));
    let aty = DVector::from_fn(m, |i, _| dot(&columns[i], y));
    let eigen = ata.symmetric_eigen();
    let largest = eigen.eigenvalues.iter().fold(0.0f64, |a, &b| a.max(b));
    if largest <= 0.0 {
        return None;
    }
    let mut solution = DVector::zeros(m);
    let mut rank = 0;
    for (k, &lambda) in eigen.eigenvalues.iter().enumerate() {
        if lambda > 1e-10 * largest {
            let v = eigen.eigenvectors.column(k);
            solution += v * (v.dot(&aty) / lambda);
            rank += 1;
        }
    }
    Some((solution.iter().copied().collect(), rank))
}

/// The RMS of the values that count.
pub fn rms_kept(values: &[f64], kept: &[bool]) -> f64 {
    let (sum, count) = values
        .iter()
        .zip(kept.iter().chain(std::iter::repeat(&true)))
        .filter(|(_, k)| **k)
        .fold((0.0, 0usize), |(s, c), (v, _)| (s + v * v, c + 1));
    if count == 0 { 0.0 } else { (sum / count as f64).sqrt() }
}

pub fn peak_kept(values: &[f64], kept: &[bool]) -> f64 {
    values
        .iter()
        .zip(kept.iter().chain(std::iter::repeat(&true)))
        .filter(|(_, k)| **k)
        .fold(0.0, |m: f64, (v, _)| m.max(v.abs()))
}
