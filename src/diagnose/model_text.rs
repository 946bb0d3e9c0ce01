//! `--write-model`: the working model's file with what `diagnose` found. The original text
//! is kept byte for byte (the user's comments and layout included) but for the values of
//! stale effects, which are replaced in place (the value's own text, found by its span, so
//! a comment after it stays), each such table getting a comment line that says what
//! changed. The effects found are appended as `[[effect]]` tables, each after a comment
//! saying where it came from and the parameters' standard uncertainties; a residual that
//! no catalogued effect explains is appended as the measured table of its slide
//! (`[[axis_table]]` with its CSV inline), when the data gave one.

use std::fmt::Write as _;

use serde_json::Value;

use super::report::{as_written, value_with_sigma};
use super::workflow::{Diagnosis, Param};
use crate::error_model::Effect;
use crate::toml_spans::{Document, Step};

/// `original` with what `d` found; `source` names the measurement. The text is read back
/// before it is returned: its effects must be the diagnosed model's (the stale values
/// updated, the found ones appended, to the six digits written), or it is an error.
pub fn with_found_effects(original: &str, d: &Diagnosis, source: &str) -> Result<String, String> {
    let mut out = updated_in_place(original, d, source)?;
    if !out.is_empty() && !out.ends_with('\n') {
        out.push('\n');
    }
    for added in &d.added {
        let iteration =
            d.iterations.iter().position(|it| it.stale.is_none() && it.effect.name() == added.effect.name());
        let _ = writeln!(out);
        match iteration {
            Some(k) => {
                let it = &d.iterations[k];
                let _ = writeln!(
                    out,
                    "# Added by `turnpass diagnose` from {source} (iteration {}: RMS {:.2} → {:.2} µm).",
                    k + 1,
                    it.rms_before_mm * 1000.0,
                    it.rms_after_mm * 1000.0
                );
            }
            None => {
                let _ = writeln!(out, "# Added by `turnpass diagnose` from {source}.");
            }
        }
        let _ = writeln!(out, "# Fitted: {} (± one standard uncertainty).", fitted(&added.params));
        out.push_str(&effect_table(&added.effect));
    }
    if let Some(table) = d.unexplained.as_ref().and_then(|u| u.table.as_ref()) {
        let _ = writeln!(out);
        let (first, last) =
            (table.targets.first().copied().unwrap_or(0.0), table.targets.last().copied().unwrap_or(0.0));
        let _ =
            writeln!(out, "# Added by `turnpass diagnose` from {source}: the residual no catalogued effect explains,");
        let _ = writeln!(
            out,
            "# as the {} slide's {} at {} targets {} mm apart (RMS {:.2} → {:.2} µm with it).",
            table.axis.letter(),
            table.quantity.column(),
            table.targets.len(),
            table.spacing_mm,
            d.rms_after_mm() * 1000.0,
            table.rms_after_mm * 1000.0
        );
        let _ = writeln!(
            out,
            "# Measured from {} to {} mm only: beyond that the table holds its end values. One direction\n\
             # is written: the residual is not told apart by direction, and both take these values.",
            as_written(first),
            as_written(last)
        );
        let _ = writeln!(out, "[[axis_table]]");
        let _ = writeln!(out, "axis = \"{}\"", table.axis_name());
        let _ = writeln!(out, "csv = \"\"\"\n{}\"\"\"", table.csv());
    }
    check_effects(&out, d)?;
    Ok(out)
}

/// The effects `text` holds are the diagnosed model's, kind by kind and value by value to
/// the six significant digits written.
fn check_effects(text: &str, d: &Diagnosis) -> Result<(), String> {
    let spec = crate::error_model::model_file::ModelSpec::from_toml(text)
        .map_err(|e| format!("the written model does not read: {e}"))?;
    let want = &d.model.effects;
    if spec.effect.len() != want.len() {
        return Err(format!("the written model has {} effects, the diagnosed one {}", spec.effect.len(), want.len()));
    }
    for (got, want) in spec.effect.iter().zip(want) {
        let (a, b) =
            (serde_json::to_value(got).unwrap_or(Value::Null), serde_json::to_value(want).unwrap_or(Value::Null));
        if got.name() != want.name() || !same_values(&a, &b) {
            return Err(format!("the written model's {} is not the diagnosed {}", got.name(), want.name()));
        }
    }
    Ok(())
}

/// Numbers equal to six significant digits, everything else exactly.
fn same_values(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap_or(f64::NAN), y.as_f64().unwrap_or(f64::NAN));
            (x - y).abs() <= 1e-5 * x.abs().max(y.abs())
        }
        (Value::Array(p), Value::Array(q)) => p.len() == q.len() && p.iter().zip(q).all(|(p, q)| same_values(p, q)),
        (Value::Object(p), Value::Object(q)) => {
            p.len() == q.len() && p.iter().all(|(key, x)| q.get(key).is_some_and(|y| same_values(x, y)))
        }
        _ => a == b,
    }
}

fn fitted(params: &[Param]) -> String {
    params.iter().map(|p| format!("{} = {}", p.name, value_with_sigma(p.value, p.sigma))).collect::<Vec<_>>().join(", ")
}

/// `original` with each stale effect's values replaced where they are written, and a
/// comment line before its first key.
fn updated_in_place(original: &str, d: &Diagnosis, source: &str) -> Result<String, String> {
    if d.updated.is_empty() {
        return Ok(original.to_string());
    }
    let document = Document::parse(original).map_err(|e| format!("the working model does not read: {e}"))?;
    let mut edits: Vec<(std::ops::Range<usize>, String)> = Vec::new();
    for update in &d.updated {
        let table = [Step::from("effect"), Step::Index(update.index)];
        let Ok(Value::Object(fields)) = serde_json::to_value(&update.new) else { continue };
        let mut first = usize::MAX;
        for (key, value) in &fields {
            let path = [table[0].clone(), table[1].clone(), Step::from(key.as_str())];
            let Some(spanned) = document.get(&path) else { continue };
            edits.push((spanned.span(), toml_number(value)));
        }
        if let Some(kind) = document.get(&[table[0].clone(), table[1].clone(), Step::from("kind")]) {
            first = first.min(kind.span().start);
        }
        for key in fields.keys() {
            if let Some(spanned) = document.get(&[table[0].clone(), table[1].clone(), Step::from(key.as_str())]) {
                first = first.min(spanned.span().start);
            }
        }
        if first == usize::MAX {
            continue;
        }
        // The start of the line of the table's first key.
        let line_start = original[..first].rfind('\n').map_or(0, |i| i + 1);
        let changes: Vec<String> = update
            .params
            .iter()
            .filter(|p| p.sigma.is_some())
            .map(|p| match p.previous {
                Some(previous) => {
                    format!("{} {} → {}", p.name, as_written(previous), value_with_sigma(p.value, p.sigma))
                }
                None => format!("{} = {}", p.name, value_with_sigma(p.value, p.sigma)),
            })
            .collect();
        edits.push((
            line_start..line_start,
            format!(
                "# Updated by `turnpass diagnose` from {source}: {} (± one standard uncertainty).\n",
                changes.join(", ")
            ),
        ));
    }
    edits.sort_by_key(|(range, _)| std::cmp::Reverse((range.start, range.end)));
    let mut out = original.to_string();
    for (range, text) in edits {
        out.replace_range(range, &text);
    }
    Ok(out)
}

/// One `[[effect]]` table, numbers to six significant digits.
pub fn effect_table(effect: &Effect) -> String {
    let mut out = String::from("[[effect]]\n");
    let _ = writeln!(out, "kind = \"{}\"", effect.name());
    if let Ok(Value::Object(map)) = serde_json::to_value(effect) {
        for (key, value) in map {
            let _ = writeln!(out, "{key} = {}", toml_number(&value));
        }
    }
    out
}

fn toml_number(value: &Value) -> String {
    match value {
        Value::Number(n) => {
            let text = as_written(n.as_f64().unwrap_or(0.0));
            // TOML wants a float to look like one.
            if text.contains('.') || text.contains('e') || text.contains("inf") || text.contains("NaN") {
                text
            } else {
                format!("{text}.0")
            }
        }
        Value::Array(items) => format!("[{}]", items.iter().map(toml_number).collect::<Vec<_>>().join(", ")),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error_model::effects::*;
    use crate::error_model::model_file::ModelSpec;

    #[test]
    fn effect_tables_read_back_as_the_same_effects_to_six_digits() {
        for effect in [
            Effect::CyclicZ(CyclicZ { amp: 0.0019834461149, pitch: 11.94, phase: 0.99299540970, axis: Z }),
            Effect::StraightnessX(StraightnessX { coeffs: vec![1.999364871858348e-6], axis: X }),
            Effect::BacklashX(BacklashX { b: 0.005, axis: X }),
            Effect::ToolOffsetX(ToolOffsetX { d: -3.0, axis: X }),
        ] {
            let text = format!("# a comment the user wrote\n[model]\nstart_min = 5.0\n\n{}", effect_table(&effect));
            let spec = ModelSpec::from_toml(&text).unwrap();
            let back = &spec.effect[0];
            assert_eq!(back.name(), effect.name());
            let (a, b) = (serde_json::to_value(back).unwrap(), serde_json::to_value(&effect).unwrap());
            for (key, value) in a.as_object().unwrap() {
                if let (Some(x), Some(y)) = (value.as_f64(), b[key].as_f64()) {
                    assert!((x - y).abs() <= 1e-5 * y.abs(), "{key}: {x} vs {y}");
                }
            }
        }
    }
}
