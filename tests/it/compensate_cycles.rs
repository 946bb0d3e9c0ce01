//! Compensation that keeps cycles (`tests/cases/compensate/cycles/cases.toml`): a roughing
//! cycle and its finishing cycle stay calls with their profile compensated word by word, a
//! thread cycle keeps its call with its final pass's words compensated, and where the
//! program so written misses the bound the cycle is expanded with the reason said. Every
//! written program verifies with the figures compensate reported.

use std::process::Command;

use serde::Deserialize;

use crate::support::{repo, with_snapshots};

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
    /// Lines the written program holds byte-identical.
    kept: Vec<String>,
    /// Lines the written program no longer holds as they were.
    edited: Vec<String>,
    /// Compensate and verify pass by pass (`--passes`), not on the finished part.
    #[serde(default)]
    passes: bool,
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

#[test]
fn cycles_stay_calls_and_what_is_written_verifies() {
    let list = std::fs::read_to_string(repo().join("tests/cases/compensate/cycles/cases.toml")).unwrap();
    let cases: Cases = toml::from_str(&list).unwrap();
    let dir = tempfile::tempdir().unwrap();
    for case in &cases.case {
        let out = dir.path().join(format!("{}.nc", case.name));
        let report = dir.path().join(format!("{}.json", case.name));
        let (out_text, report_text) = (out.to_string_lossy(), report.to_string_lossy());
        let measure: &[&str] = if case.passes { &["--passes"] } else { &[] };
        let args = ["compensate", &case.program, "--model", &case.model, "-o", &out_text];
        let (code, _, stderr) =
            turnpass(&[&args[..], measure, &["--report", "json", "--report-file", &report_text]].concat());
        assert_eq!(code, 0, "{}: compensate refused\n{stderr}", case.name);
        let written = std::fs::read_to_string(&out).unwrap();
        let lines: Vec<&str> = written.lines().collect();
        for kept in &case.kept {
            assert!(lines.contains(&kept.as_str()), "{}: `{kept}` is not written as it was\n{written}", case.name);
        }
        for edited in &case.edited {
            assert!(!lines.contains(&edited.as_str()), "{}: `{edited}` is not compensated\n{written}", case.name);
        }
        let args = ["verify", &case.program, &out_text, "--model", &case.model, "--format", "json"];
        let (code, json, verify_stderr) = turnpass(&[&args[..], measure].concat());
        assert_eq!(code, 0, "{}: verify failed what compensate wrote\n{json}{verify_stderr}", case.name);
        let verified: serde_json::Value = serde_json::from_str(&json).unwrap();
        let reported: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
        for side in ["before", "after"] {
            assert_eq!(
                reported["report"]["totals"][side], verified["deviation"][side],
                "{}: compensate reports other figures than verify finds",
                case.name
            );
        }
        let mut text = format!("{} on {}\n\n", case.program, case.model);
        for line in stderr.lines().filter(|l| l.starts_with("compensate: ")) {
            text.push_str(line);
            text.push('\n');
        }
        let original = std::fs::read_to_string(repo().join(&case.program)).unwrap();
        let version = env!("CARGO_PKG_VERSION");
        let changed = crate::compensate::changed_lines(&original, &written)
            .replace(&format!("TURNPASS {version} "), "TURNPASS {version} ");
        text.push_str("\nchanged lines:\n");
        text.push_str(&changed);
        text.push_str("\nreport, cycles:\n");
        text.push_str(&serde_json::to_string_pretty(&reported["report"]["cycles"]).unwrap());
        text.push('\n');
        with_snapshots("compensate", || insta::assert_snapshot!(format!("cycles-{}", case.name), text));
    }
}
