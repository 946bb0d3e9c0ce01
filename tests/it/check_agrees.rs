//! `turnpass check` is the full check: on every program of the case folders, of
//! `examples/programs/` and of the corpus (read in place, each on its machine from
//! `tests/corpus.toml`), `check --format json` and `simulate` give the same verdict (exit
//! code) and report the same diagnostics (severity, code, line and column), and
//! `check --syntax-only` reports exactly the parse's, a subset of them. `simulate` renders
//! its diagnostics for people; each one's header (`error[code]: …`) and the location line
//! under it (`┌─ file:line:column`) are read back.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

use crate::corpus::manifest;
use crate::support::{external, repo};

/// A diagnostic as both commands name it.
type Found = (String, String, u64, u64);

fn programs(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap().flatten() {
        let path = entry.path();
        if path.is_dir() {
            programs(&path, out);
        } else if path.extension().is_some_and(|e| ["nc", "min", "ssb", "sub", "NC", "MIN"].iter().any(|x| e == *x)) {
            out.push(path);
        }
    }
}

/// `check --format json` over `files` with `settings`: each file's diagnostics, without
/// the finding about a file with nothing to run (a warning to `check`, which reads it, and a
/// refusal, exit 1, to `simulate`, which would run it).
fn check(files: &[PathBuf], settings: &[String], syntax_only: bool) -> (i32, BTreeMap<String, Vec<Found>>) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_turnpass"));
    command.args(["check", "--format", "json", "--color", "never"]).args(settings);
    if syntax_only {
        command.arg("--syntax-only");
    }
    let output = command.args(files).current_dir(repo()).output().unwrap();
    let json: Vec<Value> = serde_json::from_slice(&output.stdout).unwrap();
    let mut found: BTreeMap<String, Vec<Found>> = BTreeMap::new();
    for d in json.iter().filter(|d| d["code"] != "empty-program") {
        found.entry(d["file"].as_str().unwrap().to_string()).or_default().push((
            d["severity"].as_str().unwrap().to_string(),
            d["code"].as_str().unwrap().to_string(),
            d["range"]["start"]["line"].as_u64().unwrap(),
            d["range"]["start"]["column"].as_u64().unwrap(),
        ));
    }
    (output.status.code().unwrap(), found)
}

/// `simulate`'s exit code, the diagnostics it renders on standard error (the first 200 of
/// a long list, without the finding about a file with nothing to run), how many more it says
/// there are, and whether it refused a program it cannot run (nothing to run, or an OSP
/// machining-centre program).
fn simulate(file: &Path, settings: &[String]) -> (i32, Vec<Found>, usize, bool) {
    let output = Command::new(env!("CARGO_BIN_EXE_turnpass"))
        .args(["simulate", "--color", "never"])
        .args(settings)
        .arg(file)
        .current_dir(repo())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    let cannot_run = stderr.contains("holds no block to run") || stderr.contains("is an OSP machining-centre program");
    let lines: Vec<&str> = stderr.lines().collect();
    let mut found = Vec::new();
    let mut more = 0;
    for (i, line) in lines.iter().enumerate() {
        if let Some((_, count)) = line.split_once(": ")
            && let Some((count, _)) = count.split_once(" more diagnostic")
        {
            more = count.parse().unwrap();
        }
        let Some((severity, rest)) = line.split_once('[') else { continue };
        if !["error", "warning", "note"].contains(&severity) {
            continue;
        }
        let Some((code, _)) = rest.split_once("]: ") else { continue };
        if code == "empty-program" {
            continue;
        }
        let location = lines[i + 1].split("┌─ ").nth(1).unwrap();
        let mut parts = location.rsplitn(3, ':');
        let column = parts.next().unwrap().parse().unwrap();
        let line = parts.next().unwrap().parse().unwrap();
        found.push((severity.to_string(), code.to_string(), line, column));
    }
    (output.status.code().unwrap(), found, more, cannot_run)
}

fn agree(files: &[PathBuf], settings: &[String]) -> usize {
    let (_, checked) = check(files, settings, false);
    let (_, syntax) = check(files, settings, true);
    let mut compared = 0;
    for file in files {
        let name = file.display().to_string();
        let from_check = checked.get(&name).cloned().unwrap_or_default();
        // A file that is not text is one `not-text` diagnostic, which `simulate` refuses to read.
        if from_check.iter().any(|d| d.1 == "not-text") {
            continue;
        }
        let (code, mut from_simulate, more, cannot_run) = simulate(file, settings);
        let errors = from_check.iter().any(|d| d.0 == "error");
        assert_eq!(from_check.len(), from_simulate.len() + more, "{name} {settings:?}: how many diagnostics");
        // Both lists are in program order; simulate shows the first ones of a long list.
        let mut shown = from_check[..from_simulate.len()].to_vec();
        shown.sort();
        from_simulate.sort();
        assert_eq!(shown, from_simulate, "{name} {settings:?}: check (left) and simulate (right) differ");
        assert_eq!(code, i32::from(errors || cannot_run), "{name} {settings:?}: simulate's exit code");
        let parse_only = syntax.get(&name).cloned().unwrap_or_default();
        assert!(
            parse_only.iter().all(|d| from_check.contains(d)),
            "{name}: --syntax-only reports what the full check does not: {parse_only:?}"
        );
        compared += from_check.len();
    }
    compared
}

#[test]
fn check_and_simulate_agree_on_every_program() {
    let mut files = Vec::new();
    programs(&repo().join("tests/cases"), &mut files);
    programs(&repo().join("examples/programs"), &mut files);
    files.sort();
    // Relative names, as a user types them and as both commands print them.
    let files: Vec<PathBuf> = files.iter().map(|f| f.strip_prefix(repo()).unwrap().to_path_buf()).collect();
    assert!(files.len() > 100, "{} programs", files.len());
    let mut compared = agree(&files, &[]);

    if let Some(dir) = external::corpus_for("the corpus programs") {
        for entry in manifest().file {
            let mut settings = vec!["--model".to_string(), entry.machine.clone()];
            if let Some(system) = &entry.gcode_system {
                settings.extend(["--gcode-system".to_string(), system.clone()]);
            }
            compared += agree(&[dir.join(&entry.path)], &settings);
        }
    }
    // Enough diagnostics that the comparison means something.
    assert!(compared > 200, "{compared} diagnostics compared");
}
