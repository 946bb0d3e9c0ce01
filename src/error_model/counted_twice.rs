//! The same error held in two places of one model: a slide table that measured it, and a
//! parametric effect that adds it again. The model sums its terms, so the compensation
//! would take the error out twice. Two pairs are told: a table's reversal (the play the
//! slide showed when the laser approached its targets both ways) and a `backlash_<axis>`
//! effect; a table's slope (its positioning deviation growing along the travel, a scale
//! error) and a `scale_<axis>` effect. Each is a warning at read, on the table with the
//! effect as a second place. Only terms in the same sense add up: a table's mean reversal
//! value `B` (ISO 230-2: approach up − approach down) is `−b` for a slide with play `b`
//! (the slide lags its command), and an effect of the other sense takes some of the table's
//! error back out (a correction found on top of the table, as `diagnose --write-model`
//! appends one), which is not the same error twice.
//!
//! What a table holds depends on how it was taken: with the control's pitch-error and
//! backlash compensation on, it holds what those leave (the machine as it runs programs);
//! with them off, the slide's whole error. The `[[axis_table]]` says which
//! (`pitch_error_compensation`, `backlash_compensation`); the warning quotes it.

use super::effects::Effect;
use super::interferometer::{self, Profile};
use super::model_file::{Axis, ModelSpec, ReadTable, Switch};
use crate::diagnostic::{Diagnostic, DiagnosticKind, ModelProblem};

/// How much must be counted twice for a warning, mm: half a micrometre, the tolerance
/// `compensate` works to on a 0.001 mm machine. Less is within what a laser run repeats.
pub const COUNTED_MM: f64 = 0.0005;

/// The warnings of `spec`, whose tables are `tables` (read from it).
pub fn counted_twice(spec: &ModelSpec, tables: &[ReadTable<'_>]) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for read in tables {
        let Some(linear) = &read.table.linear else { continue };
        let axis = read.spec.axis;
        for (index, effect) in spec.effect.iter().enumerate() {
            let at = spec.effect_spans.get(index).copied().unwrap_or(read.spec.span);
            let problem = match (axis, effect) {
                (Axis::X, Effect::BacklashX(e)) => play(linear, e.b, read, index),
                (Axis::Z, Effect::BacklashZ(e)) => play(linear, e.b, read, index),
                (Axis::X, Effect::ScaleX(e)) => scale(linear, e.ppm, read, index),
                (Axis::Z, Effect::ScaleZ(e)) => scale(linear, e.ppm, read, index),
                _ => None,
            };
            if let Some((problem, effect_label)) = problem {
                out.push(
                    Diagnostic::warning(DiagnosticKind::ModelFile(Box::new(problem)), read.spec.span)
                        .with_related(at, effect_label),
                );
            }
        }
    }
    out
}

/// A table's mean reversal beside a backlash effect of play `b`.
fn play(linear: &Profile, b: f64, read: &ReadTable<'_>, index: usize) -> Option<(ModelProblem, String)> {
    let reversal = interferometer::report(linear).mean_reversal?;
    // The table's play is −B; the same sense as the effect's when the signs agree.
    if -reversal * b <= 0.0 || reversal.abs().min(b.abs()) < COUNTED_MM {
        return None;
    }
    let axis = read.spec.axis.letter();
    let kind = format!("backlash_{}", axis.to_ascii_lowercase());
    let problem = ModelProblem::CountedTwice {
        axis,
        what: "play",
        table: format!(
            "a play of {} µm (its mean reversal value is {} µm)",
            micrometres(-reversal),
            micrometres(reversal)
        ),
        effect: format!("[[effect]] {} ({kind}) adds a play b = {} µm", index + 1, micrometres(b)),
        switch: "backlash_compensation",
        measured_with: read.spec.backlash_compensation,
    };
    Some((problem, format!("and this effect adds a play of {} µm", micrometres(b))))
}

/// A table's slope beside a scale effect of `ppm`.
fn scale(linear: &Profile, ppm: f64, read: &ReadTable<'_>, index: usize) -> Option<(ModelProblem, String)> {
    let (slope, travel) = slope(linear)?;
    if slope * ppm <= 0.0 || slope.abs().min((ppm * 1e-6).abs()) * travel < COUNTED_MM {
        return None;
    }
    let axis = read.spec.axis.letter();
    let kind = format!("scale_{}", axis.to_ascii_lowercase());
    let problem = ModelProblem::CountedTwice {
        axis,
        what: "scale",
        table: format!(
            "a positioning slope of {:.1} ppm ({} µm over its {} mm of targets)",
            slope * 1e6,
            micrometres(slope * travel),
            travel
        ),
        effect: format!("[[effect]] {} ({kind}) adds {ppm} ppm", index + 1),
        switch: "pitch_error_compensation",
        measured_with: read.spec.pitch_error_compensation,
    };
    Some((problem, format!("and this effect adds {ppm} ppm")))
}

/// The least-squares slope of the mean bidirectional deviation along the targets, mm per
/// mm, and the travel the targets span, mm; `None` for fewer than two targets.
pub fn slope(p: &Profile) -> Option<(f64, f64)> {
    let n = p.targets.len();
    let (first, last) = (*p.targets.first()?, *p.targets.last()?);
    if n < 2 || last <= first {
        return None;
    }
    let means: Vec<f64> = (0..n).map(|i| (p.up[i] + p.down[i]) / 2.0).collect();
    let mean_t = p.targets.iter().sum::<f64>() / n as f64;
    let mean_v = means.iter().sum::<f64>() / n as f64;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (t, v) in p.targets.iter().zip(&means) {
        sxy += (t - mean_t) * (v - mean_v);
        sxx += (t - mean_t) * (t - mean_t);
    }
    Some((sxy / sxx, last - first))
}

/// `mm` in micrometres, to a tenth.
fn micrometres(mm: f64) -> String {
    format!("{:.1}", mm * 1000.0)
}

/// How a table was taken, as its `[[axis_table]]` says it (for the words of the warning).
pub fn said(switch: Option<Switch>) -> &'static str {
    match switch {
        Some(Switch::On) => "on",
        Some(Switch::Off) => "off",
        None => "not said",
    }
}
