//! `turnpass model report M`: what a machine model holds, in the figures a metrologist
//! reads.
//!
//! For each slide table, each measured quantity gets the ISO 230-2 figures of
//! `interferometer::report` (A, E, M, B, R and the mean reversal value): for the linear
//! positioning errors these are the standard's figures, and the same statistics of the
//! straightness and angular deviations say how large and how direction-dependent those
//! are. Straightness measured as two reversed runs (`straightness_m1_mm`,
//! `straightness_m2_mm`) has been reduced by the reversal technique (eq. 2.5–2.7), which
//! the report says. A figure the table cannot give (B of a table measured one way, A and R
//! of a single run) is n/a, with the reason. Then the parametric effects with their
//! parameters.

use std::fmt;

use serde::Serialize;

use super::interferometer::{self, Iso230_2, Profile};
use super::model_file::{ModelError, ModelSpec, ReadTable};

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelReport {
    pub start_min: f64,
    pub abbe_y_mm: f64,
    pub tables: Vec<TableReport>,
    pub effects: Vec<EffectReport>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TableReport {
    pub axis: char,
    pub source: String,
    pub rows: Vec<QuantityReport>,
    /// The straightness was given as two reversed runs and reduced by eq. 2.7.
    pub straightness_by_reversal: bool,
    /// Whether the control's pitch-error and backlash compensation were on while the table
    /// was taken, as its `[[axis_table]]` says (`null` when it does not).
    pub pitch_error_compensation: Option<super::model_file::Switch>,
    pub backlash_compensation: Option<super::model_file::Switch>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct QuantityReport {
    pub quantity: &'static str,
    /// `mm`, or `µrad` for the angular error.
    pub unit: &'static str,
    pub targets: usize,
    pub iso: Iso230_2,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EffectReport {
    pub kind: &'static str,
    /// Each parameter and its value as the model file writes it.
    pub parameters: Vec<(String, String)>,
}

/// The report of a model file, reading its tables through `read`.
pub fn report(spec: &ModelSpec, read: impl FnMut(&str) -> Result<String, String>) -> Result<ModelReport, ModelError> {
    let mut tables = Vec::new();
    for ReadTable { spec: table, table: slide, source_name: source, .. } in spec.read_tables(read)? {
        let mut rows = Vec::new();
        let mut push = |quantity, unit, profile: &Option<Profile>, scale: f64| {
            if let Some(p) = profile {
                let scaled = Profile {
                    targets: p.targets.clone(),
                    up: p.up.iter().map(|v| v * scale).collect(),
                    down: p.down.iter().map(|v| v * scale).collect(),
                    up_sigma: p.up_sigma.iter().map(|v| v * scale).collect(),
                    down_sigma: p.down_sigma.iter().map(|v| v * scale).collect(),
                    ..p.clone()
                };
                rows.push(QuantityReport {
                    quantity,
                    unit,
                    targets: p.targets.len(),
                    iso: interferometer::report(&scaled),
                });
            }
        };
        push("linear", "mm", &slide.linear, 1.0);
        push("straightness", "mm", &slide.straightness, 1.0);
        push("angular", "µrad", &slide.angular, 1e6);
        tables.push(TableReport {
            axis: table.axis.letter(),
            source,
            rows,
            straightness_by_reversal: slide.straightness.is_some() && slide.straightness_by_reversal,
            pitch_error_compensation: table.pitch_error_compensation,
            backlash_compensation: table.backlash_compensation,
        });
    }
    let effects = spec.effect.iter().map(|e| EffectReport { kind: e.name(), parameters: parameters(e) }).collect();
    Ok(ModelReport { start_min: spec.model.start_min, abbe_y_mm: spec.model.abbe_y_mm, tables, effects })
}

fn parameters(effect: &super::Effect) -> Vec<(String, String)> {
    let Ok(serde_json::Value::Object(fields)) = serde_json::to_value(effect) else { return Vec::new() };
    fields.into_iter().map(|(k, v)| (k, v.to_string())).collect()
}

impl fmt::Display for ModelReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "program start: {} min after machine start; Abbe offset (Y): {} mm",
            self.start_min, self.abbe_y_mm
        )?;
        if self.tables.is_empty() {
            writeln!(f, "slide tables: none")?;
        }
        for table in &self.tables {
            writeln!(f, "\n{} slide ({}), ISO 230-2 figures:", table.axis, table.source)?;
            writeln!(
                f,
                "  taken with the control's pitch-error compensation {}, backlash compensation {}",
                super::counted_twice::said(table.pitch_error_compensation),
                super::counted_twice::said(table.backlash_compensation)
            )?;
            writeln!(
                f,
                "  {:<13} {:>7} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10}  unit",
                "quantity", "targets", "A", "E", "M", "B", "R", "mean B"
            )?;
            for row in &table.rows {
                let iso = &row.iso;
                let figures = [
                    iso.accuracy,
                    Some(iso.systematic),
                    Some(iso.mean_range),
                    iso.reversal,
                    iso.repeatability,
                    iso.mean_reversal,
                ];
                write!(f, "  {:<13} {:>7}", row.quantity, row.targets)?;
                for value in figures {
                    write!(f, " {:>10}", value.map_or_else(|| "n/a".to_string(), figure))?;
                }
                writeln!(f, "  {}", row.unit)?;
            }
            // Why a figure is n/a: the figures sharing a reason on one line, with the
            // quantities it holds for.
            let mut notes: Vec<(Vec<&str>, &str, Vec<&str>)> = Vec::new();
            for row in &table.rows {
                let mut reasons: Vec<(&str, Vec<&str>)> = Vec::new();
                for (field, name) in FIGURES {
                    let Some(reason) = row.iso.not_measured.get(field) else { continue };
                    match reasons.iter_mut().find(|(r, _)| r == reason) {
                        Some((_, names)) => names.push(name),
                        None => reasons.push((reason, vec![name])),
                    }
                }
                for (reason, names) in reasons {
                    match notes.iter_mut().find(|(n, r, _)| *n == names && *r == reason) {
                        Some((_, _, quantities)) => quantities.push(row.quantity),
                        None => notes.push((names, reason, vec![row.quantity])),
                    }
                }
            }
            for (names, reason, quantities) in notes {
                writeln!(f, "  {} n/a ({}): {reason}", names.join(" and "), quantities.join(", "))?;
            }
            if table.straightness_by_reversal {
                writeln!(
                    f,
                    "  straightness reduced from two reversed runs by the reversal technique (eq. 2.5-2.7): \
                     s = (m2 - m1) / 2"
                )?;
            }
        }
        writeln!(f, "\neffects:{}", if self.effects.is_empty() { " none" } else { "" })?;
        for effect in &self.effects {
            let parameters: Vec<String> = effect.parameters.iter().map(|(k, v)| format!("{k} = {v}")).collect();
            writeln!(f, "  {:<17} {}", effect.kind, parameters.join(", "))?;
        }
        Ok(())
    }
}

/// The figures' fields and their names in the table's heading.
const FIGURES: [(&str, &str); 6] = [
    ("accuracy", "A"),
    ("systematic", "E"),
    ("mean_range", "M"),
    ("reversal", "B"),
    ("repeatability", "R"),
    ("mean_reversal", "mean B"),
];

/// A figure to four decimals, with no minus sign on a value that rounds to zero.
fn figure(value: f64) -> String {
    let text = format!("{value:.4}");
    if text.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
        text.trim_start_matches('-').to_string()
    } else {
        text
    }
}
