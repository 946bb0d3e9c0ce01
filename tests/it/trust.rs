//! Compensation a shop can trust (`tests/cases/compensate/trust.toml`): programs that
//! isolate where `compensate` said ok while `verify` of what it wrote failed. For every
//! strategy, `compensate` exits 0, `verify` of its output exits 0, and the figures the
//! report gives are verify's own: compensate reads back what it writes and measures it as
//! verify does. The snapshot holds each strategy's figures and take-ups, and the lines the
//! first strategy changed.

use std::path::Path;
use std::process::Command;

use serde::Deserialize;

use crate::support::{repo, with_snapshots};

const STRATEGIES: [&str; 6] = ["auto", "circle", "semicircle", "quadrant", "arcs", "densify"];

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Cases {
    case: Vec<Case>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Case {
    name: String,
    program: String,
    model: String,
    #[serde(default)]
    args: Vec<String>,
    /// Compensate's arguments (besides the strategy) whose take-up count this case's may not
    /// exceed.
    #[serde(default)]
    no_more_take_ups_than: Option<Vec<String>>,
}

fn turnpass(args: &[&str]) -> (i32, String, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_turnpass"))
        .args(args)
        .current_dir(repo())
        .env("NO_COLOR", "1")
        .output()
        .unwrap();
    let text = |bytes: &[u8]| String::from_utf8_lossy(bytes).into_owned();
    (output.status.code().unwrap(), text(&output.stdout), text(&output.stderr))
}

/// Compensate `case` with `strategy` and `args` into `out`: the report, and stderr.
fn compensate(case: &Case, strategy: &str, args: &[String], out: &Path) -> (serde_json::Value, String) {
    let report = out.with_extension("json");
    let (out_text, report_text) = (out.to_string_lossy(), report.to_string_lossy());
    let mut all = vec!["compensate", &case.program, "--model", &case.model, "--strategy", strategy];
    all.extend(args.iter().map(String::as_str));
    all.extend(["-o", &out_text, "--report", "json", "--report-file", &report_text]);
    let (code, _, stderr) = turnpass(&all);
    assert_eq!(code, 0, "{} {strategy}: compensate refused\n{stderr}", case.name);
    let value: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    (value["report"].clone(), stderr)
}

fn take_ups(report: &serde_json::Value) -> u64 {
    report["blocks"].as_array().unwrap().iter().map(|b| b["backlash_moves"].as_u64().unwrap()).sum()
}

#[test]
fn compensate_says_ok_only_where_verify_agrees() {
    let list = std::fs::read_to_string(repo().join("tests/cases/compensate/trust.toml")).unwrap();
    let cases: Cases = toml::from_str(&list).unwrap();
    let dir = tempfile::tempdir().unwrap();
    for case in &cases.case {
        let mut text = format!("{} on {}\n\n", case.program, case.model);
        text.push_str("| strategy | max before µm | RMS before µm | max after µm | RMS after µm | take-ups |\n");
        text.push_str("|---|---|---|---|---|---|\n");
        let mut notes = String::new();
        for strategy in STRATEGIES {
            let out = dir.path().join(format!("{}-{strategy}.nc", case.name));
            let (report, stderr) = compensate(case, strategy, &case.args, &out);
            let args = ["verify", &case.program, &out.to_string_lossy(), "--model", &case.model, "--format", "json"];
            let (code, json, verify_stderr) = turnpass(&args);
            assert_eq!(code, 0, "{} {strategy}: verify failed what compensate wrote\n{json}{verify_stderr}", case.name);
            let verified: serde_json::Value = serde_json::from_str(&json).unwrap();
            let totals = &report["totals"];
            for side in ["before", "after"] {
                assert_eq!(
                    totals[side], verified["deviation"][side],
                    "{} {strategy}: compensate reports other figures than verify finds",
                    case.name
                );
            }
            let takes = take_ups(&report);
            if let Some(other) = &case.no_more_take_ups_than {
                let (baseline, _) = compensate(case, strategy, other, &dir.path().join("baseline.nc"));
                assert!(
                    takes <= take_ups(&baseline),
                    "{} {strategy}: {takes} take-ups, against {} with {other:?}",
                    case.name,
                    take_ups(&baseline)
                );
            }
            let um = |side: &str, key: &str| totals[side][key].as_f64().unwrap() * 1000.0;
            text.push_str(&format!(
                "| {strategy} | {:.2} | {:.2} | {:.2} | {:.2} | {takes} |\n",
                um("before", "max_mm"),
                um("before", "rms_mm"),
                um("after", "max_mm"),
                um("after", "rms_mm"),
            ));
            if strategy == "auto" {
                for note in stderr.lines().filter(|l| l.contains("note:")) {
                    notes.push_str(&format!("\n{note}\n"));
                }
            }
        }
        text.push_str(&notes);
        let original = std::fs::read_to_string(repo().join(&case.program)).unwrap();
        let written = std::fs::read_to_string(dir.path().join(format!("{}-auto.nc", case.name))).unwrap();
        text.push_str("\nauto, changed lines:\n");
        text.push_str(&crate::compensate::changed_lines(&original, &written));
        with_snapshots("trust", || insta::assert_snapshot!(case.name.clone(), text));
    }
}
