//! The workflow's report: for a machinist (`--format human`) and for tools
//! (`--format json`, exactly the keys of the issue).

use std::fmt::Write as _;

use serde_json::{Map, Value, json};

use super::advice::shown_by;
use super::breakdown::{Breakdown, Group, breakdown};
use super::forward::Forward;
use super::iso230_4::{Figures, figures};
use super::measured::Axis;
use super::measured::{Direction, Kind};
use super::unexplained::{Quantity, Unexplained};
use super::workflow::{Diagnosis, OUTLIER_SIGMAS, Param, Ranked, Stop, shrink};

/// The JSON report: `{"iterations":[{"effect","stale","params","rms_before_mm",
/// "rms_after_mm","p_value","delta_bic","refitted","dropped"}], "updated":[{"effect",
/// "params"}], "outliers":[{"line","residual_mm","sigmas"}], "unexplained", "stop",
/// "rms_before_mm","rms_after_mm","noise_floor_mm","confounded"}`; each parameter is
/// `{"value", "sigma"}` (`sigma` null for a value from the machine settings or kept from
/// the model), with `"previous"` for a stale value's; a p-value below 1e-300 is 0.
pub fn json(d: &Diagnosis) -> Value {
    let iterations: Vec<Value> = d
        .iterations
        .iter()
        .map(|it| {
            json!({
                "effect": it.effect.name(),
                "stale": it.stale.is_some(),
                "params": params_json(&it.params),
                "rms_before_mm": it.rms_before_mm,
                "rms_after_mm": it.rms_after_mm,
                "p_value": it.p_value,
                "delta_bic": it.delta_bic,
                "refitted": it.refitted,
                "dropped": it.dropped,
            })
        })
        .collect();
    let updated: Vec<Value> =
        d.updated.iter().map(|u| json!({ "effect": u.new.name(), "params": params_json(&u.params) })).collect();
    let outliers: Vec<Value> = d
        .outliers
        .iter()
        .map(|o| json!({ "line": o.line, "residual_mm": o.residual_mm, "sigmas": finite(o.sigmas) }))
        .collect();
    json!({
        "iterations": iterations,
        "updated": updated,
        "outliers": outliers,
        "unexplained": d.unexplained,
        "stop": d.stop,
        "rms_before_mm": d.rms_before_mm(),
        "rms_after_mm": d.rms_after_mm(),
        "noise_floor_mm": d.noise_floor_mm,
        "confounded": d.confounded,
    })
}

fn finite(value: f64) -> Value {
    if value.is_finite() { json!(value) } else { Value::Null }
}

fn params_json(params: &[Param]) -> Value {
    let mut map = Map::new();
    for p in params {
        let mut entry = json!({ "value": p.value, "sigma": p.sigma });
        if let Some(previous) = p.previous {
            entry["previous"] = json!(previous);
        }
        map.insert(p.name.clone(), entry);
    }
    Value::Object(map)
}

/// A p-value as the report prints it: below what a double holds reliably, as a bound.
pub fn p_text(p: f64) -> String {
    if p < 1e-300 { "p < 1e-300".to_string() } else { format!("p = {p:.1e}") }
}

fn um(mm: f64) -> f64 {
    mm * 1000.0
}

/// A value with its uncertainty, to two significant digits of the uncertainty.
pub fn value_with_sigma(value: f64, sigma: Option<f64>) -> String {
    let Some(sigma) = sigma.filter(|s| s.is_finite() && *s > 0.0) else {
        return format!("{} (given)", significant(value, 5));
    };
    let exponent = sigma.log10().floor() as i32 - 1;
    if value != 0.0 && value.abs() < 1e-3 {
        // Scientific, with as many mantissa digits as the uncertainty allows.
        let scale = 10f64.powi(value.abs().log10().floor() as i32);
        let digits = (scale.log10() as i32 - exponent).clamp(0, 8) as usize;
        return format!("{:.*e} ± {:.1e}", digits, value, sigma);
    }
    let decimals = (-exponent).clamp(0, 9) as usize;
    format!("{value:.decimals$} ± {sigma:.decimals$}")
}

fn significant(value: f64, digits: i32) -> String {
    if value == 0.0 || !value.is_finite() {
        return format!("{value}");
    }
    let decimals = (digits - 1 - value.abs().log10().floor() as i32).clamp(0, 12) as usize;
    format!("{value:.decimals$}")
}

/// A value as a model file writes it: the shortest text that reads back as the value
/// rounded to six significant digits (`0.004`, not `0.0040000`).
pub fn as_written(value: f64) -> String {
    let rounded: f64 = format!("{value:.5e}").parse().unwrap_or(value);
    format!("{rounded}")
}

fn params_text(params: &[Param]) -> String {
    params
        .iter()
        .map(|p| match p.previous {
            // A stale value's parameter kept from the model is not news.
            Some(previous) if p.sigma.is_none() => format!("{} {} (kept)", p.name, as_written(previous)),
            Some(previous) => format!("{} {} → {}", p.name, as_written(previous), value_with_sigma(p.value, p.sigma)),
            None => format!("{} = {}", p.name, value_with_sigma(p.value, p.sigma)),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The report for a machinist.
pub fn human(d: &Diagnosis) -> String {
    let mut out = String::new();
    let f = &d.forward;
    let what = match f.kind {
        Kind::BallBar => "ball bar trace",
        Kind::Profile => "CMM profile",
        Kind::Table(_) => "interferometer table",
    };
    let setup = match f.kind {
        Kind::BallBar => "centring and length removed per test circle",
        Kind::Profile => "datum Z shift removed per part",
        Kind::Table(_) => "set-up removed per quantity",
    };
    let count = match f.kind {
        // A table's values are the means of its runs, per target, direction and quantity.
        Kind::Table(_) => {
            format!("{} rows, {} values (the mean of the runs per target, direction and quantity)", d.rows, f.len())
        }
        _ => format!("{} points", f.len()),
    };
    let _ = writeln!(out, "diagnose: {what}, {count}; {setup}:");
    for g in &f.groups {
        let _ = writeln!(out, "  {g}");
    }
    let _ = writeln!(
        out,
        "noise floor {:.2} µm (spread of the differences of neighbouring residuals)",
        um(d.noise_floor_mm)
    );
    let _ = writeln!(out);

    let before = breakdown(f, &d.simulated_before.states, &d.residual_before, &d.kept);
    let _ = writeln!(out, "Where the working model and the measurement disagree (residual before, µm):");
    write_breakdown(&mut out, &before, f.kind);

    if f.kind == Kind::BallBar {
        let _ = writeln!(out);
        write_iso(&mut out, d);
    }

    if !d.outliers.is_empty() {
        let _ = writeln!(out);
        let _ = writeln!(
            out,
            "Outliers: {} point{} departing from the median of their neighbours along the path by more than \
             {OUTLIER_SIGMAS} σ of the noise, excluded from every fit and figure:",
            d.outliers.len(),
            if d.outliers.len() == 1 { "" } else { "s" }
        );
        for o in &d.outliers {
            let _ = writeln!(out, "  line {:<6} residual {:>8.2} µm ({:.0} σ)", o.line, um(o.residual_mm), o.sigmas);
        }
    }

    let _ = writeln!(out);
    if d.iterations.is_empty() {
        let _ = writeln!(out, "No effect added.");
    } else {
        let _ = writeln!(
            out,
            "Iterations (RMS and peak of the residual in µm; parameters as the model file writes them, lengths in mm):"
        );
        let name = |it: &super::workflow::Iteration| match it.stale {
            Some(_) => format!("{} (stale)", it.effect.name()),
            None => it.effect.name().to_string(),
        };
        let width = d.iterations.iter().map(|it| name(it).chars().count()).max().unwrap_or(0).max(17);
        let _ =
            writeln!(out, "  #  {:<width$} RMS before → after   peak before → after   shrink   parameters", "effect");
        for (k, it) in d.iterations.iter().enumerate() {
            let _ = writeln!(
                out,
                "  {:<2} {:<width$} {:>6.2} → {:<6.2}        {:>6.2} → {:<6.2}        {:>5.1} %  {}",
                k + 1,
                name(it),
                um(it.rms_before_mm),
                um(it.rms_after_mm),
                um(it.peak_before_mm),
                um(it.peak_after_mm),
                it.shrink_percent(),
                params_text(&it.params)
            );
            let _ = writeln!(
                out,
                "     F = {:.1}, {}, ΔBIC = {:.1}; ranking: {}",
                it.f,
                p_text(it.p_value),
                it.delta_bic,
                ranking_text(&it.ranking, 4)
            );
            for r in &it.refitted {
                let _ = writeln!(
                    out,
                    "     refitted beside it: {} {} {} → {}",
                    r.effect,
                    r.param,
                    significant(r.before, 5),
                    significant(r.after, 5)
                );
            }
            for dropped in &it.dropped {
                let what = if dropped.stale { "reverted to the model's value" } else { "dropped" };
                let _ = writeln!(out, "     {} {what}: no longer significant ({})", dropped.effect, dropped.reason);
            }
        }
    }
    let stop = match d.stop {
        Stop::NoiseFloor => "the residual is at the noise floor",
        Stop::NothingSignificant => "no candidate is significant and determined",
        Stop::Confounded => "the best candidates cannot be told apart",
        Stop::IterationLimit => "the iteration limit",
    };
    let _ = writeln!(out, "Stopped: {stop}.");
    if !d.last_ranking.is_empty() {
        let _ = writeln!(out, "  ranking: {}", ranking_text(&d.last_ranking, 5));
    }
    for c in &d.confounded {
        let _ = writeln!(
            out,
            "Confounded: {} fit the residual alike. To separate them: {}.",
            c.effects.join(", "),
            c.separate_by
        );
    }
    let absorbed: Vec<String> = d
        .last_ranking
        .iter()
        .filter(|r| !r.stale && r.status.starts_with("aliased"))
        .map(|r| format!("{} ({})", r.effect, shown_by(r.effect, f.kind)))
        .collect();
    if !absorbed.is_empty() {
        let _ = writeln!(out, "Absorbed by the set-up terms here: {}.", absorbed.join("; "));
    }
    let silent: Vec<&str> =
        d.last_ranking.iter().filter(|r| !r.stale && r.status.starts_with("no signature")).map(|r| r.effect).collect();
    if !silent.is_empty() {
        let _ = writeln!(out, "No signature in this measurement: {}.", silent.join(", "));
    }
    let unchecked: Vec<&str> = d
        .last_ranking
        .iter()
        .filter(|r| r.stale && (r.status.starts_with("aliased") || r.status.starts_with("no signature")))
        .map(|r| r.effect)
        .collect();
    if !unchecked.is_empty() {
        let _ = writeln!(
            out,
            "The working model's own effects this measurement cannot check (set-up terms absorb them, or it does \
             not see them): {}.",
            unchecked.join(", ")
        );
    }
    if !d.updated.is_empty() {
        let _ = writeln!(out);
        let _ = writeln!(out, "Stale values of the working model (the model's value → the data's):");
        for u in &d.updated {
            let _ = writeln!(out, "  {} {}", u.new.name(), params_text(&u.params));
        }
    }
    if let Some(u) = &d.unexplained {
        write_unexplained(&mut out, u);
    }
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "Gap: RMS {:.2} → {:.2} µm ({:.1} %), peak {:.2} → {:.2} µm.",
        um(d.rms_before_mm()),
        um(d.rms_after_mm()),
        shrink(d.rms_before_mm(), d.rms_after_mm()),
        um(d.peak_before_mm()),
        um(d.peak_after_mm())
    );
    out
}

fn write_unexplained(out: &mut String, u: &Unexplained) {
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "Unexplained: a residual of {:.2} µm RMS remains, {:.1} × the noise floor, and no effect of the catalogue \
         explains it.",
        um(u.rms_mm),
        u.rms_mm / u.noise_floor_mm.max(f64::MIN_POSITIVE)
    );
    if !u.places.is_empty() {
        let places: Vec<String> =
            u.places.iter().map(|g| format!("{} ({:.2} µm RMS)", g.label, um(g.rms_mm))).collect();
        let _ = writeln!(out, "  It is largest at: {}.", places.join("; "));
    }
    match (&u.table, &u.no_table) {
        (Some(t), _) => {
            let (first, last) = (t.targets.first().copied().unwrap_or(0.0), t.targets.last().copied().unwrap_or(0.0));
            let what = match t.quantity {
                Quantity::Straightness => {
                    let across = if t.axis == Axis::Z { "X" } else { "Z" };
                    format!("straightness ({across} displaced as {} travels)", t.axis.letter())
                }
                Quantity::Positioning => format!("positioning error (along {})", t.axis.letter()),
            };
            let _ = writeln!(
                out,
                "  As a measured table it is the {} slide's {what}: {} targets {} mm apart from {first:.1} to {last:.1} \
                 mm, explaining {:.1} % ({}, ΔBIC = {:.1}); with it the model leaves {:.2} µm RMS.",
                t.axis.letter(),
                t.targets.len(),
                t.spacing_mm,
                t.explained_percent,
                p_text(t.p_value),
                t.delta_bic,
                um(t.rms_after_mm)
            );
            let _ = writeln!(
                out,
                "  --write-model writes it as an [[axis_table]] (axis = \"{}\", {}), valid over the span measured: \
                 beyond it the table holds its end values.",
                t.axis_name(),
                t.quantity.column()
            );
        }
        (None, Some(why)) => {
            let _ = writeln!(out, "  No measured table holds it: {why}.");
        }
        (None, None) => {}
    }
}

fn ranking_text(ranking: &[Ranked], count: usize) -> String {
    let shown: Vec<String> = ranking
        .iter()
        .filter(|r| !r.status.starts_with("no signature") && !r.status.starts_with("aliased"))
        .take(count)
        .map(|r| format!("{} {:.1} ({:.1} %, {})", r.label(), r.delta_bic, r.explained_percent, r.status))
        .collect();
    shown.join(", ")
}

fn write_breakdown(out: &mut String, b: &Breakdown, kind: Kind) {
    let place = if kind == Kind::BallBar { "sector" } else { "feature" };
    for (title, groups) in [
        ("segment", &b.by_segment),
        (place, &b.by_place),
        ("direction", &b.by_direction),
        ("reversal", &b.by_reversal),
        ("time", &b.by_time),
    ] {
        let _ = writeln!(out, "  by {title:<40} points    mean     RMS    peak");
        for g in groups.iter() {
            write_group(out, g);
        }
    }
}

fn write_group(out: &mut String, g: &Group) {
    let _ = writeln!(
        out,
        "    {:<41} {:>5} {:>7.2} {:>7.2} {:>7.2}",
        g.label,
        g.points,
        um(g.mean_mm),
        um(g.rms_mm),
        um(g.peak_mm)
    );
}

/// The ISO 230-4 figures of the measured trace and of the residual before and after.
pub fn iso_figures(d: &Diagnosis) -> [Figures; 3] {
    let f: &Forward = &d.forward;
    let angles: Vec<f64> = f.points.iter().map(|p| p.angle_deg.unwrap_or(0.0)).collect();
    let directions: Vec<Direction> = f.points.iter().map(|p| p.direction.unwrap_or(Direction::Ccw)).collect();
    [
        figures(&angles, &f.measured(), &directions),
        figures(&angles, &d.residual_before, &directions),
        figures(&angles, &d.residual_after, &directions),
    ]
}

/// One figure of a trace's figures.
type Figure = fn(&Figures) -> Option<f64>;

fn write_iso(out: &mut String, d: &Diagnosis) {
    let [measured, before, after] = iso_figures(d);
    let _ =
        writeln!(out, "ISO 230-4 (µm; G about the minimum-zone centre, G lsq and F about the least-squares centre):");
    let _ = writeln!(out, "  {:<14} {:>10} {:>17} {:>16}", "", "measured", "residual before", "residual after");
    let rows: [(&str, Figure); 8] = [
        ("G ccw", |f| f.ccw.map(|c| c.g_mm)),
        ("G ccw lsq", |f| f.ccw.map(|c| c.g_lsq_mm)),
        ("G cw", |f| f.cw.map(|c| c.g_mm)),
        ("G cw lsq", |f| f.cw.map(|c| c.g_lsq_mm)),
        ("G(b)", |f| f.both.map(|c| c.g_mm)),
        ("H", |f| f.hysteresis_mm),
        ("F max", |f| f.both.or(f.ccw).or(f.cw).map(|c| c.f_max_mm)),
        ("F min", |f| f.both.or(f.ccw).or(f.cw).map(|c| c.f_min_mm)),
    ];
    for (name, get) in rows {
        let cell = |f: &Figures| get(f).map_or("—".to_string(), |v| format!("{:.2}", um(v)));
        if get(&measured).is_none() {
            continue;
        }
        let _ = writeln!(out, "  {:<14} {:>10} {:>17} {:>16}", name, cell(&measured), cell(&before), cell(&after));
    }
}
