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
    /// The strategies this case runs (default: every one).
    #[serde(default)]
    strategies: Option<Vec<String>>,
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
        let strategies: Vec<&str> =
            case.strategies.as_ref().map_or_else(|| STRATEGIES.to_vec(), |s| s.iter().map(String::as_str).collect());
        for strategy in strategies {
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
                for note in stderr.lines().filter(|l| l.contains("note:") || l.contains("--strategy auto:")) {
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

mod generated {
    //! The property behind the cases above, over generated programs and machines: whatever
    //! the program (profiles with tapers, faces, quarter arcs and half circles that reverse an
    //! axis inside the arc, nose radius compensation, G76/G92/G32 threads, inch or metric) and
    //! whatever the model (backlash with squareness, scale, cyclic errors, offsets, several at
    //! once), when `compensate` exits 0, `verify` of what it wrote exits 0 and finds the
    //! figures compensate reported. A refusal (exit 1) is allowed, but not as the rule.

    use std::fmt::Write as _;

    use proptest::prelude::*;

    use super::{STRATEGIES, turnpass};

    #[derive(Debug, Clone)]
    enum Segment {
        /// Along Z by this length (mm).
        Turn(f64),
        /// Out (or in) on the diameter and along Z.
        Taper { diameter: f64, length: f64 },
        /// Up a face on the diameter.
        Face(f64),
        /// A quarter circle of this radius out along Z, clockwise or not.
        Quarter { radius: f64, clockwise: bool },
        /// A half circle of this radius along Z: X goes out (or in) and back inside the arc.
        Half { radius: f64, clockwise: bool },
    }

    #[derive(Debug, Clone)]
    enum Thread {
        None,
        G76 { taper: f64 },
        G92,
        G32,
    }

    #[derive(Debug, Clone)]
    struct Job {
        inch: bool,
        start_diameter: f64,
        segments: Vec<Segment>,
        nose_radius_side: Option<bool>,
        thread: Thread,
        effects: Vec<(String, Vec<(String, f64)>)>,
        strategy: usize,
    }

    fn segment() -> impl Strategy<Value = Segment> {
        prop_oneof![
            (5.0..60.0f64).prop_map(Segment::Turn),
            (-4.0..6.0f64, 2.0..20.0f64).prop_map(|(diameter, length)| Segment::Taper { diameter, length }),
            (2.0..8.0f64).prop_map(Segment::Face),
            (1.0..5.0f64, any::<bool>()).prop_map(|(radius, clockwise)| Segment::Quarter { radius, clockwise }),
            (1.0..4.0f64, any::<bool>()).prop_map(|(radius, clockwise)| Segment::Half { radius, clockwise }),
        ]
    }

    fn thread() -> impl Strategy<Value = Thread> {
        prop_oneof![
            Just(Thread::None),
            prop_oneof![Just(0.0), -1.5..0.0f64].prop_map(|taper| Thread::G76 { taper }),
            Just(Thread::G92),
            Just(Thread::G32),
        ]
    }

    fn effect() -> impl Strategy<Value = (String, Vec<(String, f64)>)> {
        let one = |kind: &str, key: &str, range: std::ops::Range<f64>| {
            let (kind, key) = (kind.to_string(), key.to_string());
            range.prop_map(move |v| (kind.clone(), vec![(key.clone(), v)]))
        };
        prop_oneof![
            one("backlash_x", "b", 0.001..0.012),
            one("backlash_z", "b", 0.001..0.012),
            one("squareness", "urad", -50.0..50.0),
            one("scale_x", "ppm", -40.0..40.0),
            one("scale_z", "ppm", -40.0..40.0),
            one("tool_offset_x", "dx", -0.008..0.008),
            (0.001..0.004f64, 4.0..12.0f64, 0.0..3.0f64).prop_map(|(amp, pitch, phase)| (
                "cyclic_z".to_string(),
                vec![("amp".into(), amp), ("pitch".into(), pitch), ("phase".into(), phase)]
            )),
        ]
    }

    fn job() -> impl Strategy<Value = Job> {
        (
            any::<bool>(),
            20.0..40.0f64,
            prop::collection::vec(segment(), 1..6),
            prop_oneof![Just(None), any::<bool>().prop_map(Some)],
            thread(),
            prop::collection::vec(effect(), 1..4),
            0..STRATEGIES.len(),
        )
            .prop_map(|(inch, start_diameter, segments, nose_radius_side, thread, mut effects, strategy)| {
                // One entry per kind: a model names each effect once.
                effects.sort_by(|a, b| a.0.cmp(&b.0));
                effects.dedup_by(|a, b| a.0 == b.0);
                Job { inch, start_diameter, segments, nose_radius_side, thread, effects, strategy }
            })
    }

    /// A length in mm in the program's units, on its increment.
    fn length(job: &Job, mm: f64) -> String {
        if job.inch { format!("{:.4}", mm / 25.4) } else { format!("{mm:.3}") }
    }

    fn program(job: &Job) -> String {
        let mut p = String::new();
        let l = |mm: f64| length(job, mm);
        let units = if job.inch { "G20" } else { "G21" };
        let feed = if job.inch { "0.004" } else { "0.1" };
        writeln!(p, "{units} G99\nT0101\nG97 S800 M03").unwrap();
        let (mut x, mut z) = (job.start_diameter, 0.0f64);
        let comp = match job.nose_radius_side {
            Some(true) => "G42 ",
            Some(false) => "G41 ",
            None => "",
        };
        writeln!(p, "G00 X{} Z{}", l(x), l(2.0)).unwrap();
        writeln!(p, "{comp}G01 Z{} F{feed}", l(z)).unwrap();
        for segment in &job.segments {
            match *segment {
                Segment::Turn(length) => {
                    z -= length;
                    writeln!(p, "G01 Z{}", l(z)).unwrap();
                }
                Segment::Taper { diameter, length } => {
                    x = (x + diameter).max(12.0);
                    z -= length;
                    writeln!(p, "G01 X{} Z{}", l(x), l(z)).unwrap();
                }
                Segment::Face(diameter) => {
                    x += diameter;
                    writeln!(p, "G01 X{}", l(x)).unwrap();
                }
                Segment::Quarter { radius, clockwise } => {
                    x += 2.0 * radius;
                    z -= radius;
                    let code = if clockwise { "G02" } else { "G03" };
                    writeln!(p, "{code} X{} Z{} R{}", l(x), l(z), l(radius)).unwrap();
                }
                Segment::Half { radius, clockwise } => {
                    // Keep the inward bulge off the axis.
                    let clockwise = clockwise && x / 2.0 - radius > 3.0;
                    z -= 2.0 * radius;
                    let code = if clockwise { "G02" } else { "G03" };
                    writeln!(p, "{code} X{} Z{} I0 K{}", l(x), l(z), l(-radius)).unwrap();
                }
            }
        }
        let clear = x + 10.0;
        writeln!(p, "G01 X{}", l(clear)).unwrap();
        if job.nose_radius_side.is_some() {
            writeln!(p, "G40 G00 X{} Z{}", l(clear + 20.0), l(5.0)).unwrap();
        }
        let major = job.start_diameter;
        let (lead, depth) = (1.5, 0.92);
        let thread_end = (-20.0f64).min(-z.abs() / 2.0 - 5.0).max(-40.0);
        match job.thread {
            Thread::None => {}
            Thread::G76 { taper } => {
                let increment = if job.inch { 0.00254 } else { 0.001 };
                let units = |mm: f64| (mm / increment).round() as i64;
                writeln!(p, "G00 X{} Z{}", l(major + 4.0), l(5.0)).unwrap();
                writeln!(p, "G76 P011060 Q{} R{}", units(0.1), l(0.05)).unwrap();
                writeln!(
                    p,
                    "G76 X{} Z{} R{} P{} Q{} F{}",
                    l(major - 2.0 * depth),
                    l(thread_end),
                    l(taper),
                    units(depth),
                    units(0.3),
                    l(lead)
                )
                .unwrap();
            }
            Thread::G92 => {
                writeln!(p, "G00 X{} Z{}", l(major + 4.0), l(5.0)).unwrap();
                writeln!(p, "G92 X{} Z{} F{}", l(major - 0.6), l(thread_end), l(lead)).unwrap();
                writeln!(p, "X{}", l(major - 1.2)).unwrap();
                writeln!(p, "X{}", l(major - 2.0 * depth)).unwrap();
            }
            Thread::G32 => {
                for pass in [0.6, 2.0 * depth] {
                    writeln!(p, "G00 X{} Z{}", l(major + 4.0), l(5.0)).unwrap();
                    writeln!(p, "G00 X{}", l(major - pass)).unwrap();
                    writeln!(p, "G32 Z{} F{}", l(thread_end), l(lead)).unwrap();
                    writeln!(p, "G00 X{}", l(major + 4.0)).unwrap();
                }
            }
        }
        writeln!(p, "G00 X{} Z{}\nM30", l(200.0), l(100.0)).unwrap();
        p
    }

    fn model(job: &Job) -> String {
        let mut m = String::from("[machine]\ndiameter_programming = true\nmax_spindle_rpm = 3000\n");
        if job.inch {
            m.push_str("units = \"inch\"\nleast_increment = 0.0001\nhome = { x = 12.0, z = 12.0 }\n");
            m.push_str("[[machine.tool]]\nstation = 1\noffset = 1\nnose_radius = 0.0157\ntip = 3\n");
        } else {
            m.push_str("units = \"mm\"\nleast_increment = 0.001\nhome = { x = 300.0, z = 300.0 }\n");
            m.push_str("[[machine.tool]]\nstation = 1\noffset = 1\nnose_radius = 0.4\ntip = 3\n");
        }
        for (kind, values) in &job.effects {
            writeln!(m, "\n[[effect]]\nkind = \"{kind}\"").unwrap();
            for (key, value) in values {
                writeln!(m, "{key} = {value:.6}").unwrap();
            }
        }
        m
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

        #[test]
        fn compensate_exit_0_means_verify_exit_0_with_the_same_figures(job in job()) {
            let dir = tempfile::tempdir().unwrap();
            let (nc, toml, out, report) = (
                dir.path().join("part.nc"),
                dir.path().join("machine.toml"),
                dir.path().join("out.nc"),
                dir.path().join("report.json"),
            );
            std::fs::write(&nc, program(&job)).unwrap();
            std::fs::write(&toml, model(&job)).unwrap();
            let s = |p: &std::path::Path| p.to_string_lossy().into_owned();
            let strategy = STRATEGIES[job.strategy];
            let (code, _, stderr) = turnpass(&[
                "compensate", &s(&nc), "--model", &s(&toml), "--strategy", strategy, "-o", &s(&out),
                "--report", "json", "--report-file", &s(&report),
            ]);
            prop_assert!(code == 0 || code == 1, "compensate exit {code}\n{stderr}\n{}\n{}", program(&job), model(&job));
            if code == 1 {
                prop_assert!(!out.exists(), "a refused compensation wrote its output");
                return Ok(());
            }
            let (code, json, verify_stderr) =
                turnpass(&["verify", &s(&nc), &s(&out), "--model", &s(&toml), "--format", "json"]);
            prop_assert_eq!(
                code, 0,
                "{}: compensate said ok, verify failed\n{}{}\n{}\n{}", strategy, json, verify_stderr, program(&job), model(&job)
            );
            let verified: serde_json::Value = serde_json::from_str(&json).unwrap();
            let reported: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
            for side in ["before", "after"] {
                prop_assert_eq!(
                    &reported["report"]["totals"][side], &verified["deviation"][side],
                    "{}: compensate reports other figures than verify finds\n{}\n{}", strategy, program(&job), model(&job)
                );
            }
        }
    }

    /// The property allows a refusal; this holds refusals to a small share of the same inputs,
    /// so that the property is not met by refusing. About one job in nine is refused on the
    /// finished part (18, 24, 21, 19, 25 and 24 of 200 in six runs) and one in seven pass by
    /// pass (25, 29, 26, 20, 32 and 25):
    /// a thread on a periodic screw error is cut as thread blocks of their own leads, and an
    /// element of compensation's own the nose cannot follow under G41/G42 is joined into its
    /// neighbours. Among what is left: take-up steps between arcs the tool runs inside of
    /// (the control's interference check would refuse those too), and backlash or
    /// squareness the check before writing finds over the bound. Over 200 jobs (a few
    /// seconds) the bound of a quarter sits about four standard deviations above the pass
    /// measure's share. Each job is
    /// also compensated with the check before writing pass by pass (`--passes`), and both
    /// shares are printed: the pass measure does not see a thread's flanks.
    #[test]
    fn compensate_refuses_few_generated_jobs() {
        let mut runner = proptest::test_runner::TestRunner::new(ProptestConfig {
            cases: 200,
            failure_persistence: None,
            ..ProptestConfig::default()
        });
        let runs = std::cell::Cell::new(0usize);
        let (refused, refused_passes) = (std::cell::Cell::new(0usize), std::cell::Cell::new(0usize));
        runner
            .run(&job(), |job| {
                let dir = tempfile::tempdir().unwrap();
                let (nc, toml) = (dir.path().join("part.nc"), dir.path().join("machine.toml"));
                std::fs::write(&nc, program(&job)).unwrap();
                std::fs::write(&toml, model(&job)).unwrap();
                let s = |p: &std::path::Path| p.to_string_lossy().into_owned();
                let (nc, toml) = (s(&nc), s(&toml));
                let (out, out_passes) = (s(&dir.path().join("out.nc")), s(&dir.path().join("passes.nc")));
                let args = ["compensate", &nc, "--model", &toml, "--strategy", STRATEGIES[job.strategy]];
                let (code, _, _) = turnpass(&[&args[..], &["-o", &out]].concat());
                let (code_passes, _, _) = turnpass(&[&args[..], &["--passes", "-o", &out_passes]].concat());
                runs.set(runs.get() + 1);
                refused.set(refused.get() + usize::from(code != 0));
                refused_passes.set(refused_passes.get() + usize::from(code_passes != 0));
                Ok(())
            })
            .unwrap();
        let (runs, refused, refused_passes) = (runs.get(), refused.get(), refused_passes.get());
        // The shares, for `--nocapture`: the figures the notes on compensation quote.
        eprintln!(
            "compensate refused {refused} of {runs} generated jobs on the finished part, {refused_passes} pass by pass"
        );
        assert!(refused * 4 <= runs, "compensate refused {refused} of {runs} generated jobs");
        assert!(refused_passes * 4 <= runs, "compensate --passes refused {refused_passes} of {runs} generated jobs");
    }
}
