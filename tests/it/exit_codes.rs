//! One exit-code rule for every command (README, "Exit codes"), run on every command with
//! the inputs where commands used to disagree:
//!
//! - **0**: the command did what was asked; what it writes is written whole, and no `error`
//!   is printed;
//! - **1**: the input cannot give what was asked (errors in the program, nothing to run, not
//!   a lathe program, a refusal or violation found): nothing is written, to a file or to
//!   standard output (only the findings of `check`, `verify` and `diagnose` are printed, on
//!   standard output), and standard error, or those findings, say why;
//! - **2**: usage or I/O.
//!
//! `check` and `fmt` read a program without running it: a program with nothing to run, or an
//! OSP machining-centre program, checks and prints back (0); every command that runs one
//! refuses it (1). `plot` draws what compensation would do even where `compensate` refuses
//! (its refusals are warnings there).

use std::path::Path;
use std::process::{Command, Stdio};

use crate::support::repo;

const MODEL: &str = "tests/cases/compensate/machine.toml";

/// The inputs: a name, the program, the model, and each command's exit code in the order
/// of [`COMMANDS`].
const INPUTS: &[(&str, &str, &str, [i32; 10])] = &[
    // check fmt expand simulate compensate plot verify report diagnose synth
    // On a machine with no error terms, so that the program verifies against itself.
    ("clean", "tests/cases/compensate/face.nc", "tests/cases/compensate/nominal.toml", [0, 0, 0, 0, 0, 0, 0, 0, 0, 0]),
    ("empty", "tests/cases/cli/empty.nc", MODEL, [0, 0, 1, 1, 1, 1, 1, 1, 1, 1]),
    ("leading Ctrl-Z", "tests/cases/cli/leading-ctrl-z.nc", MODEL, [0, 0, 1, 1, 1, 1, 1, 1, 1, 1]),
    (
        "OSP machining centre",
        "tests/cases/cli/machining-centre.min",
        "tests/cases/corpus-machines/osp-lathe.toml",
        [0, 0, 1, 1, 1, 1, 1, 1, 1, 1],
    ),
    ("an error", "tests/cases/cli/one-error.nc", MODEL, [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]),
    // compensate refuses (a corrected point leaves the travel), and plot draws it; verify of
    // the program against itself finds its deviation (a violation), which report puts on its
    // page.
    (
        "refused by compensate",
        "tests/cases/compensate/face.nc",
        "tests/cases/compensate/tight-travel.toml",
        [0, 0, 0, 0, 1, 0, 1, 0, 0, 0],
    ),
];

/// Each command's arguments for a program and a model, the file it writes into `tmp` (none:
/// standard output), and whether its findings go to standard output whatever it finds.
struct Run {
    name: &'static str,
    args: fn(&str, &str, &Path) -> Vec<String>,
    writes: Option<&'static str>,
    findings_on_stdout: bool,
}

const COMMANDS: [Run; 10] = [
    Run { name: "check", args: |p, m, _| strings(&["check", p, "--model", m]), writes: None, findings_on_stdout: true },
    Run {
        name: "fmt",
        args: |p, m, t| with_out(&["fmt", p, "--model", m], t, "fmt.nc"),
        writes: Some("fmt.nc"),
        findings_on_stdout: false,
    },
    Run {
        name: "expand",
        args: |p, m, t| with_out(&["expand", p, "--model", m], t, "expand.nc"),
        writes: Some("expand.nc"),
        findings_on_stdout: false,
    },
    Run {
        name: "simulate",
        args: |p, m, _| strings(&["simulate", p, "--model", m]),
        writes: None,
        findings_on_stdout: false,
    },
    Run {
        name: "compensate",
        args: |p, m, t| with_out(&["compensate", p, "--model", m], t, "compensate.nc"),
        writes: Some("compensate.nc"),
        findings_on_stdout: false,
    },
    Run {
        name: "plot",
        args: |p, m, t| with_out(&["plot", p, "--model", m], t, "plot.svg"),
        writes: Some("plot.svg"),
        findings_on_stdout: false,
    },
    Run {
        name: "verify",
        args: |p, m, _| strings(&["verify", p, p, "--model", m]),
        writes: None,
        findings_on_stdout: true,
    },
    Run {
        name: "report",
        args: |p, m, t| with_out(&["report", p, p, "--model", m], t, "report.html"),
        writes: Some("report.html"),
        findings_on_stdout: false,
    },
    Run {
        name: "diagnose",
        args: |p, m, t| {
            let mut args = strings(&["diagnose", p, "--model", m, "--measured"]);
            args.push(t.join("measured.csv").to_string_lossy().into_owned());
            args
        },
        writes: None,
        findings_on_stdout: true,
    },
    Run {
        name: "synth",
        args: |p, m, t| with_out(&["synth", p, "--model", m, "--kind", "profile"], t, "synth.csv"),
        writes: Some("synth.csv"),
        findings_on_stdout: false,
    },
];

fn strings(args: &[&str]) -> Vec<String> {
    args.iter().map(|a| a.to_string()).collect()
}

fn with_out(args: &[&str], tmp: &Path, file: &str) -> Vec<String> {
    let mut args = strings(args);
    args.push("-o".into());
    args.push(tmp.join(file).to_string_lossy().into_owned());
    args
}

fn turnpass(args: &[String]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_turnpass"))
        .args(args)
        .current_dir(repo())
        .env("NO_COLOR", "1")
        .stdin(Stdio::null())
        .output()
        .unwrap()
}

#[test]
fn every_command_follows_one_exit_code_rule() {
    let mut broken = Vec::new();
    for (input, program, model, codes) in INPUTS {
        let tmp = tempfile::tempdir().unwrap();
        // A measurement of the clean program for `diagnose` (for the others it is refused
        // before the measurement is read).
        let made = turnpass(&with_out(
            &["synth", "tests/cases/compensate/face.nc", "--model", MODEL, "--kind", "profile"],
            tmp.path(),
            "measured.csv",
        ));
        assert!(made.status.success(), "{}", String::from_utf8_lossy(&made.stderr));
        for (run, &code) in COMMANDS.iter().zip(codes) {
            let output = turnpass(&(run.args)(program, model, tmp.path()));
            let stderr = String::from_utf8_lossy(&output.stderr);
            let mut wrong = Vec::new();
            if output.status.code() != Some(code) {
                wrong.push(format!("exit {:?}, not {code}", output.status.code()));
            }
            let written = run.writes.is_some_and(|file| tmp.path().join(file).exists());
            match code {
                0 => {
                    if stderr.contains("error[") || stderr.contains("error:") {
                        wrong.push("an error printed with exit 0".into());
                    }
                    if run.writes.is_some() && !written {
                        wrong.push("nothing written with exit 0".into());
                    }
                    if run.writes.is_none() && !run.findings_on_stdout && output.stdout.is_empty() {
                        wrong.push("nothing on standard output with exit 0".into());
                    }
                }
                _ => {
                    if written {
                        wrong.push(format!("a file written with exit {code}"));
                    }
                    if !run.findings_on_stdout && !output.stdout.is_empty() {
                        wrong.push(format!("standard output written with exit {code}"));
                    }
                    let findings = if run.findings_on_stdout { output.stdout.as_slice() } else { b"" };
                    if output.stderr.trim_ascii().is_empty() && findings.trim_ascii().is_empty() {
                        wrong.push(format!("exit {code} with nothing said why"));
                    }
                }
            }
            if let Some(file) = run.writes {
                let _ = std::fs::remove_file(tmp.path().join(file));
            }
            if !wrong.is_empty() {
                broken.push(format!("{} on {input}: {}\n{stderr}", run.name, wrong.join("; ")));
            }
        }
    }
    assert!(broken.is_empty(), "{} disagreements:\n{}", broken.len(), broken.join("\n"));
}
