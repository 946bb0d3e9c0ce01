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
    /// Lines the written program holds as given (an edit that changes only some words).
    #[serde(default)]
    written: Vec<String>,
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
        for line in &case.written {
            assert!(lines.contains(&line.as_str()), "{}: `{line}` is not written\n{written}", case.name);
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
        text.push_str(&summary_and_changes(&stderr, &case.program, &written));
        text.push_str(&report_cycles(&reported));
        with_snapshots("compensate", || insta::assert_snapshot!(format!("cycles-{}", case.name), text));
    }
}

/// The copy on OSP, asked for alone (LAP accepts the contour this model compensates in
/// place, so `compensate` keeps it there): the `G87` call names a contour of its own written
/// right after it under a new name, as OSP programs write a finishing contour; the `G85`
/// call and the contour it roughs print as written, and `verify` passes what is written.
#[test]
fn an_osp_finishing_call_runs_its_own_compensated_contour() {
    use turnpass::compensation::fit::{FitOptions, Strategy};
    use turnpass::compensation::{CompensateOptions, Judged, compensate_program};
    use turnpass::dialect::{DialectChoice, GCodeSystem};
    use turnpass::error_model::model_file::ModelSpec;
    use turnpass::machine::{MachineSettings, ModelFile};
    use turnpass::pipeline::Settings;
    use turnpass::semantic::LowerOptions;
    use turnpass::syntax::ParseOptions;

    let (program, model) =
        ("tests/cases/compensate/cycles/osp-lap-thread.nc", "tests/cases/compensate/cycles/osp-scale.toml");
    let text = std::fs::read_to_string(repo().join(model)).unwrap();
    let machine: MachineSettings = ModelFile::from_toml(&text).unwrap().machine;
    let errors = ModelSpec::from_toml(&text).unwrap().build(|_| Err("no tables".into())).unwrap();
    let options = ParseOptions {
        dialect: DialectChoice::Auto,
        gcode_system: machine.gcode_system.unwrap_or(GCodeSystem::A),
        machine_kind: None,
        control: Default::default(),
    };
    let settings = Settings::new(options, &machine, LowerOptions::new(false));
    let source = std::fs::read(repo().join(program)).unwrap();
    let analysed = crate::support::analyse(&source, &settings);
    let Ok(ready) = analysed.ready() else { panic!("{program} has errors") };
    let increment = ready.machine.increment * ready.machine.scale();
    let options = CompensateOptions {
        fit: FitOptions { strategy: Strategy::Auto, tolerance_mm: increment / 2.0, step_mm: None },
        max_shift_mm: 0.1,
        expand_cycles: false,
        profiles_in_place: false,
        profiles_copied: true,
        threads_in_place: true,
        singles_in_place: true,
        others_as_written: false,
        thread_pieces_every_pass: false,
        paths: false,
        block_reports: true,
    };
    let outcome =
        compensate_program(ready.program(), &ready.lowered, &ready.machine, &errors, &options, Judged::EveryFeed);
    assert!(!outcome.refused(), "{:?}", outcome.diagnostics);
    let written = String::from_utf8(turnpass::printer::print(ready.program(), &outcome.edits)).unwrap();
    let lines: Vec<&str> = written.lines().collect();
    let original = String::from_utf8(source.clone()).unwrap();
    // The roughing call and its contour, as written.
    for line in original.lines().skip(5).take(7) {
        assert!(lines.contains(&line), "`{line}` is not written as it was\n{written}");
    }
    assert!(!lines.contains(&"G87 N0207"), "the finishing call still names the contour as written\n{written}");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("copied.nc");
    std::fs::write(&out, &written).unwrap();
    let (code, json, stderr) =
        turnpass(&["verify", program, &out.to_string_lossy(), "--model", model, "--format", "json"]);
    assert_eq!(code, 0, "verify failed what was written\n{json}{stderr}\n{written}");
    let changed = crate::compensate::changed_lines(&original, &written);
    let cycles = serde_json::to_string_pretty(&outcome.report.cycles).unwrap();
    let text = format!("{program} on {model}\n\nchanged lines:\n{changed}\nreport, cycles:\n{cycles}\n");
    with_snapshots("compensate", || insta::assert_snapshot!("cycles-osp-contour-copied", text));
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LeadCases {
    case: Vec<LeadCase>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LeadCase {
    name: String,
    program: String,
    model: String,
    /// Lines the written program holds byte-identical.
    kept: Vec<String>,
    /// More arguments of `compensate` (`--expand-cycles`).
    #[serde(default)]
    args: Vec<String>,
    /// Where the thread cycle is written out as thread moves: the lead word every written
    /// thread move (`G32`) carries, which the report gives as the cycle's lead.
    #[serde(default)]
    expanded_lead: Option<String>,
}

/// `verify` of `program` against itself on `model` fails it: on the part its thread's flanks
/// lie off by more than 0.002 mm, the lead error gathered along the thread. Its JSON, and its
/// text for the snapshot.
fn verify_fails_on_its_lead(name: &str, program: &str, model: &str) -> (serde_json::Value, String) {
    let (code, stdout, stderr) = turnpass(&["verify", program, program, "--model", model, "--format", "json"]);
    assert_eq!(code, 1, "{name}: verify passes a thread whose lead errs\n{stdout}{stderr}");
    let verified: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert!(verified["deviation"]["after"]["max_mm"].as_f64().unwrap() > 0.002, "{name}: {verified}");
    let (_, uncorrected, _) = turnpass(&["verify", program, program, "--model", model]);
    (verified, uncorrected)
}

/// `tests/cases/compensate/cycles/leads.toml`: on a Z slide with a scale error the thread's
/// lead errs, and its flanks on the part lie off by more than the bound where the thread
/// ends. `verify` of the program against itself says so; `compensate` keeps the thread cycle
/// and writes its lead word so that the slide cuts the programmed lead (or, where it writes
/// the cycle out, the lead word of every thread move it writes), says which lead changed and
/// by how much, and `verify` passes what it wrote, its lead error a fifth of the uncorrected
/// one or less.
#[test]
fn a_scale_error_along_the_thread_is_a_lead_error_compensate_corrects() {
    let list = std::fs::read_to_string(repo().join("tests/cases/compensate/cycles/leads.toml")).unwrap();
    let cases: LeadCases = toml::from_str(&list).unwrap();
    let dir = tempfile::tempdir().unwrap();
    for case in &cases.case {
        let (verified, uncorrected) = verify_fails_on_its_lead(&case.name, &case.program, &case.model);
        let lead_before = verified["deviation"]["lead"]["before_mm"].as_f64().unwrap();
        let (out, report) =
            (dir.path().join(format!("{}.nc", case.name)), dir.path().join(format!("{}.json", case.name)));
        let (out_text, report_text) = (out.to_string_lossy(), report.to_string_lossy());
        let mut args = vec!["compensate", &case.program, "--model", &case.model, "-o", &out_text];
        args.extend(["--report", "json", "--report-file", &report_text]);
        args.extend(case.args.iter().map(String::as_str));
        let (code, _, compensated) = turnpass(&args);
        assert_eq!(code, 0, "{}: compensate refused\n{compensated}", case.name);
        let written = std::fs::read_to_string(&out).unwrap();
        for kept in &case.kept {
            assert!(written.lines().any(|l| l == kept), "{}: `{kept}` is not written as it was\n{written}", case.name);
        }
        let (code, json, verify_stderr) =
            turnpass(&["verify", &case.program, &out_text, "--model", &case.model, "--format", "json"]);
        assert_eq!(code, 0, "{}: verify failed what compensate wrote\n{json}{verify_stderr}", case.name);
        let verified: serde_json::Value = serde_json::from_str(&json).unwrap();
        let reported: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
        if let Some(word) = &case.expanded_lead {
            let cycle = &reported["report"]["cycles"][0];
            assert_eq!(cycle["outcome"], "expanded", "{}: {cycle}", case.name);
            assert_eq!(cycle["lead"]["to"].as_str(), Some(word.as_str()), "{}: {cycle}", case.name);
            let thread_moves: Vec<&str> = written.lines().filter(|l| l.split(' ').any(|w| w == "G32")).collect();
            assert!(!thread_moves.is_empty(), "{}: no thread move written\n{written}", case.name);
            for line in thread_moves {
                assert!(line.split(' ').any(|w| w == word), "{}: `{line}` is not cut at {word}\n{written}", case.name);
            }
        }
        let lead_after = verified["deviation"]["lead"]["after_mm"].as_f64().unwrap();
        assert!(lead_after <= lead_before / 5.0, "{}: the lead is not corrected: {verified}", case.name);
        let (_, corrected, _) = turnpass(&["verify", &case.program, &out_text, "--model", &case.model]);
        let mut snapshot = format!("{} on {}\n\nverify, the program against itself:\n", case.program, case.model);
        let lead_lines = |text: &str| -> String {
            text.lines()
                .filter(|l| l.starts_with("thread lead") || l.starts_with("violation"))
                .map(|l| format!("{l}\n"))
                .collect()
        };
        snapshot.push_str(&lead_lines(&uncorrected));
        snapshot.push_str("\ncompensate:\n");
        snapshot.push_str(&summary_and_changes(&compensated, &case.program, &written));
        snapshot.push_str("\nverify, the written program:\n");
        snapshot.push_str(&lead_lines(&corrected));
        snapshot.push_str(&report_cycles(&reported));
        with_snapshots("compensate", || insta::assert_snapshot!(format!("leads-{}", case.name), snapshot));
    }
}

/// Compensate's summary lines in `stderr`, and the lines `written` changed of `program`.
fn summary_and_changes(stderr: &str, program: &str, written: &str) -> String {
    let mut text = String::new();
    for line in stderr.lines().filter(|l| l.starts_with("compensate: ")) {
        text.push_str(line);
        text.push('\n');
    }
    let original = std::fs::read_to_string(repo().join(program)).unwrap();
    let version = env!("CARGO_PKG_VERSION");
    let changed = crate::compensate::changed_lines(&original, written)
        .replace(&format!("TURNPASS {version} "), "TURNPASS {version} ");
    text.push_str("\nchanged lines:\n");
    text.push_str(&changed);
    text
}

/// The report's cycles, as the snapshots show them.
fn report_cycles(reported: &serde_json::Value) -> String {
    format!("\nreport, cycles:\n{}\n", serde_json::to_string_pretty(&reported["report"]["cycles"]).unwrap())
}

#[derive(serde::Deserialize)]
struct CyclicLeadCases {
    case: Vec<CyclicLeadCase>,
}

#[derive(serde::Deserialize)]
struct CyclicLeadCase {
    name: String,
    program: String,
    model: String,
    kept: Vec<String>,
    /// The thread cycle is written out (and the report says the lead error is why).
    #[serde(default)]
    expanded: bool,
}

/// `tests/cases/compensate/cycles/cyclic-leads.toml`: a periodic screw error along Z is a
/// lead error that changes along the thread. `verify` of the program against itself fails
/// it on the part; `compensate` writes the passes that shape the finished thread as
/// consecutive thread blocks (a `G32` followed by blocks of its own run, each with a lead
/// word of its own where its lead changes), says so for an expanded cycle, and `verify`
/// passes what it wrote.
#[test]
fn a_periodic_screw_error_is_written_as_thread_blocks_of_their_own_leads() {
    let list = std::fs::read_to_string(repo().join("tests/cases/compensate/cycles/cyclic-leads.toml")).unwrap();
    let cases: CyclicLeadCases = toml::from_str(&list).unwrap();
    let dir = tempfile::tempdir().unwrap();
    for case in &cases.case {
        let (_, uncorrected) = verify_fails_on_its_lead(&case.name, &case.program, &case.model);
        let (out, report) =
            (dir.path().join(format!("{}.nc", case.name)), dir.path().join(format!("{}.json", case.name)));
        let (out_text, report_text) = (out.to_string_lossy(), report.to_string_lossy());
        let args = ["compensate", &case.program, "--model", &case.model, "-o", &out_text];
        let (code, _, compensated) =
            turnpass(&[&args[..], &["--report", "json", "--report-file", &report_text]].concat());
        assert_eq!(code, 0, "{}: compensate refused\n{compensated}", case.name);
        let written = std::fs::read_to_string(&out).unwrap();
        for kept in &case.kept {
            assert!(written.lines().any(|l| l == kept), "{}: `{kept}` is not written as it was\n{written}", case.name);
        }
        // The final pass: the last `G32` block and the blocks of its run after it.
        let lines: Vec<&str> = written.lines().collect();
        let last = lines.iter().rposition(|l| l.split(' ').any(|w| w == "G32")).unwrap();
        let run = lines[last + 1..].iter().take_while(|l| !l.split(' ').any(|w| w.starts_with('G'))).count();
        assert!(run >= 2, "{}: the final pass is not written as thread blocks\n{written}", case.name);
        let (code, json, verify_stderr) =
            turnpass(&["verify", &case.program, &out_text, "--model", &case.model, "--format", "json"]);
        assert_eq!(code, 0, "{}: verify failed what compensate wrote\n{json}{verify_stderr}", case.name);
        let reported: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
        if case.expanded {
            let cycle = &reported["report"]["cycles"][0];
            assert_eq!(cycle["outcome"], "expanded", "{}: {cycle}", case.name);
            assert!(
                cycle["reason"].as_str().unwrap().contains("not uniform along the thread"),
                "{}: {cycle}",
                case.name
            );
            assert!(cycle["lead"]["pieces"].as_u64().unwrap() >= 2, "{}: {cycle}", case.name);
        }
        let (_, corrected, _) = turnpass(&["verify", &case.program, &out_text, "--model", &case.model]);
        let part_lines = |text: &str| -> String {
            text.lines()
                .filter(|l| {
                    l.starts_with("  as programmed")
                        || l.starts_with("  compensated")
                        || l.starts_with("thread lead")
                        || l.starts_with("deepest")
                        || l.starts_with("violation")
                        || l == &"ok"
                })
                .map(|l| format!("{l}\n"))
                .collect()
        };
        let mut snapshot = format!("{} on {}\n\nverify, the program against itself:\n", case.program, case.model);
        snapshot.push_str(&part_lines(&uncorrected));
        snapshot.push_str("\ncompensate:\n");
        snapshot.push_str(&summary_and_changes(&compensated, &case.program, &written));
        snapshot.push_str("\nverify, the written program:\n");
        snapshot.push_str(&part_lines(&corrected).replace(out_text.as_ref(), "{written}"));
        snapshot.push_str(&report_cycles(&reported));
        with_snapshots("compensate", || insta::assert_snapshot!(format!("cyclic-leads-{}", case.name), snapshot));
    }
}
