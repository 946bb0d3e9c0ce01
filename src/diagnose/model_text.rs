//! `--write-model`: the working model's file with the effects `diagnose` found appended as
//! `[[effect]]` tables. The original text is kept byte for byte (the user's comments and
//! layout included); each new table follows a comment saying where it came from and the
//! parameters' standard uncertainties.

use std::fmt::Write as _;

use serde_json::Value;

use super::report::value_with_sigma;
use super::workflow::Diagnosis;
use crate::error_model::Effect;

/// `original` with the effects found in `d` appended; `source` names the measurement.
pub fn with_found_effects(original: &str, d: &Diagnosis, source: &str) -> String {
    let mut out = original.to_string();
    if !out.is_empty() && !out.ends_with('\n') {
        out.push('\n');
    }
    for (k, (effect, iteration)) in d.added.iter().zip(&d.iterations).enumerate() {
        let _ = writeln!(out);
        let _ = writeln!(
            out,
            "# Added by `turnpass diagnose` from {source} (iteration {}: RMS {:.4} → {:.4} mm).",
            k + 1,
            iteration.rms_before_mm,
            iteration.rms_after_mm
        );
        let fitted: Vec<String> =
            iteration.params.iter().map(|p| format!("{} = {}", p.name, value_with_sigma(p.value, p.sigma))).collect();
        let _ = writeln!(out, "# Fitted: {} (± one standard uncertainty).", fitted.join(", "));
        out.push_str(&effect_table(effect));
    }
    out
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
            let v = n.as_f64().unwrap_or(0.0);
            let rounded: f64 = format!("{v:.5e}").parse().unwrap_or(v);
            let text = format!("{rounded}");
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
            Effect::CyclicZ(CyclicZ { amp: 0.0019834461149, pitch: 11.94, phase: 0.99299540970 }),
            Effect::StraightnessX(StraightnessX { coeffs: vec![1.999364871858348e-6] }),
            Effect::BacklashX(BacklashX { b: 0.005 }),
            Effect::ToolOffsetX(ToolOffsetX { dx: -3.0 }),
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
