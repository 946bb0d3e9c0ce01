//! `turnpass table`, driven by the cases in `tests/cases/control_table/`: each gives a model
//! (inline), the control and the arguments; the snapshot holds the command's summary and
//! every file it wrote. Each table written is then read back as `--with-table` reads it,
//! and what it leaves of the errors it works on (the summary's figures, from the model of
//! the machine with it loaded) must be within the case's bound.

use std::process::Command;

use serde::Deserialize;

use crate::support::{case_files, repo, with_snapshots};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Case {
    control: String,
    args: Vec<String>,
    model: String,
    #[serde(default)]
    code: i32,
    /// The most, in µm either way, the table may leave of what it works on (exit 0 cases).
    #[serde(default)]
    leaves_at_most_um: Option<f64>,
}

#[test]
fn table_cases() {
    let mut failing = Vec::new();
    for path in case_files(&repo().join("tests/cases/control_table"), "toml") {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let case: Case = toml::from_str(&std::fs::read_to_string(&path).unwrap())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        if std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| run_case(&name, &case))).is_err() {
            failing.push(name);
        }
    }
    assert!(failing.is_empty(), "failing table cases: {failing:?}");
}

fn run_case(name: &str, case: &Case) {
    let tmp = tempfile::tempdir().unwrap();
    let model = tmp.path().join("model.toml");
    std::fs::write(&model, &case.model).unwrap();
    let extension = match case.control.as_str() {
        "linuxcnc" => "ini",
        "fanuc" => "tape",
        _ => "csv",
    };
    let output = tmp.path().join(format!("table.{extension}"));
    let mut args = vec![
        "table".to_string(),
        model.to_string_lossy().into_owned(),
        "--control".to_string(),
        case.control.clone(),
        "-o".to_string(),
        output.to_string_lossy().into_owned(),
    ];
    args.extend(case.args.iter().cloned());
    let run = Command::new(env!("CARGO_BIN_EXE_turnpass")).args(&args).env("NO_COLOR", "1").output().unwrap();
    let tmp_text = tmp.path().to_string_lossy().into_owned();
    let placeholders = |text: &str| {
        let version = env!("CARGO_PKG_VERSION");
        text.replace(&tmp_text, "{tmp}")
            .replace(&format!("turnpass {version}"), "turnpass {version}")
            .replace(&format!("TURNPASS {version}"), "TURNPASS {version}")
    };
    let stderr = placeholders(&String::from_utf8_lossy(&run.stderr));
    assert_eq!(run.status.code(), Some(case.code), "{name}: exit code\n{stderr}");
    let mut text =
        format!("$ turnpass {}\nexit code: {}\n----- STDERR\n{stderr}", placeholders(&args[1..].join(" ")), case.code);
    let mut files: Vec<_> = std::fs::read_dir(tmp.path())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.file_name().is_some_and(|n| n != "model.toml"))
        .collect();
    files.sort();
    if case.code != 0 {
        assert!(files.is_empty(), "{name}: a refused table writes nothing: {files:?}");
    }
    for file in &files {
        let name = file.file_name().unwrap().to_string_lossy();
        text.push_str(&format!("----- {name}\n{}", placeholders(&std::fs::read_to_string(file).unwrap())));
    }
    if let Some(bound) = case.leaves_at_most_um {
        // "works on: ±H µm about C µm": the spread about a constant, which the program takes.
        let spreads: Vec<f64> = stderr
            .lines()
            .filter_map(|line| line.split_once("works on: ±")?.1.split_once(" µm"))
            .map(|(half, _)| half.parse::<f64>().unwrap())
            .collect();
        assert!(!spreads.is_empty(), "{name}: no figure of what the table leaves\n{stderr}");
        for half in spreads {
            assert!(half <= bound, "{name}: the table leaves ±{half} µm, beyond ±{bound}");
        }
    }
    with_snapshots("control_table", || insta::assert_snapshot!(name.to_string(), text));
}
