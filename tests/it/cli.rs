//! The command line, driven by the case lists in `tests/cases/commands/` (one file per topic;
//! the cases of all of them run in file order, each with its own snapshot).

use std::collections::BTreeMap;
use std::process::{Command, Stdio};

use serde::Deserialize;

use crate::support::{external, repo, with_snapshots};

#[derive(Deserialize)]
struct Cases {
    case: Vec<Case>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Case {
    name: String,
    args: Vec<String>,
    code: i32,
    #[serde(default)]
    stdin: Option<String>,
    #[serde(default)]
    setup: BTreeMap<String, String>,
    #[serde(default)]
    expect_files: BTreeMap<String, bool>,
    /// What the case reads from outside the repository (`support::external`).
    #[serde(default)]
    requires: Vec<Requirement>,
    /// Commands run after `args`, in order, each with its exit code; their output follows
    /// the first command's in the snapshot (to read back what it wrote).
    #[serde(default)]
    then: Vec<Then>,
}

#[derive(Deserialize, PartialEq)]
#[serde(rename_all = "lowercase")]
enum Requirement {
    /// The third-party corpus, `../shared/corpus/`.
    Corpus,
}

#[derive(Deserialize)]
struct Then {
    args: Vec<String>,
    code: i32,
}

#[test]
fn command_line_cases() {
    let mut lists: Vec<_> = std::fs::read_dir(repo().join("tests/cases/commands"))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "toml"))
        .collect();
    lists.sort();
    let mut names = std::collections::BTreeSet::new();
    let cases = lists.iter().flat_map(|path| {
        let cases: Cases = toml::from_str(&std::fs::read_to_string(path).unwrap())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        cases.case
    });
    for case in cases {
        assert!(names.insert(case.name.clone()), "two command cases are named {}", case.name);
        let uses_corpus = case.args.iter().any(|a| a.contains("{corpus}"));
        assert_eq!(
            uses_corpus,
            case.requires.contains(&Requirement::Corpus),
            "{}: a case names {{corpus}} in its arguments exactly when it requires the corpus",
            case.name
        );
        let corpus = if uses_corpus {
            match external::corpus_for(&format!("command case `{}`", case.name)) {
                Some(dir) => dir.to_string_lossy().into_owned(),
                None => continue,
            }
        } else {
            String::new()
        };
        let tmp = tempfile::tempdir().unwrap();
        let tmp_text = tmp.path().to_string_lossy().into_owned();
        for (from, to) in &case.setup {
            let target = tmp.path().join(to);
            std::fs::create_dir_all(target.parent().unwrap()).unwrap();
            std::fs::copy(repo().join(from), target).unwrap();
        }
        let args: Vec<String> =
            case.args.iter().map(|a| a.replace("{tmp}", &tmp_text).replace("{corpus}", &corpus)).collect();
        // The snapshot names the corpus by its placeholder, wherever it is.
        let placeholders = |text: &str| {
            let text = text.replace(&tmp_text, "{tmp}");
            if corpus.is_empty() { text } else { text.replace(&corpus, "{corpus}") }
        };
        let mut command = Command::new(env!("CARGO_BIN_EXE_turnpass"));
        command.args(&args).current_dir(repo()).env("NO_COLOR", "1");
        command.stdin(match &case.stdin {
            Some(path) => Stdio::from(std::fs::File::open(repo().join(path)).unwrap()),
            None => Stdio::null(),
        });
        let output = command.output().unwrap();
        let stdout = placeholders(&String::from_utf8_lossy(&output.stdout));
        let stderr = placeholders(&String::from_utf8_lossy(&output.stderr));
        assert_eq!(
            output.status.code(),
            Some(case.code),
            "{}: exit code\nstdout:\n{stdout}\nstderr:\n{stderr}",
            case.name
        );
        for (file, present) in &case.expect_files {
            assert_eq!(tmp.path().join(file).exists(), *present, "{}: {file}", case.name);
        }
        // No temporary file may be left behind by a failed write.
        let leftovers: Vec<_> = walk(tmp.path())
            .into_iter()
            .filter(|p| p.file_name().is_some_and(|n| n.to_string_lossy().starts_with(".tmp")))
            .collect();
        assert!(leftovers.is_empty(), "{}: leftovers {leftovers:?}", case.name);
        let mut text = format!(
            "$ turnpass {}\nexit code: {}\n----- STDOUT\n{stdout}\n----- STDERR\n{stderr}",
            placeholders(&args.join(" ")),
            case.code
        );
        for then in &case.then {
            let args: Vec<String> = then.args.iter().map(|a| a.replace("{tmp}", &tmp_text)).collect();
            let output = Command::new(env!("CARGO_BIN_EXE_turnpass"))
                .args(&args)
                .current_dir(repo())
                .env("NO_COLOR", "1")
                .stdin(Stdio::null())
                .output()
                .unwrap();
            let stdout = String::from_utf8_lossy(&output.stdout).replace(&tmp_text, "{tmp}");
            let stderr = String::from_utf8_lossy(&output.stderr).replace(&tmp_text, "{tmp}");
            let shown = args.join(" ").replace(&tmp_text, "{tmp}");
            assert_eq!(output.status.code(), Some(then.code), "{}: exit code of `{shown}`\n{stderr}", case.name);
            text.push_str(&format!(
                "\n$ turnpass {shown}\nexit code: {}\n----- STDOUT\n{stdout}\n----- STDERR\n{stderr}",
                then.code
            ));
        }
        with_snapshots("cli", || insta::assert_snapshot!(case.name.clone(), text));
    }
}

fn walk(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let path = entry.path();
        if path.is_dir() {
            out.extend(walk(&path));
        } else {
            out.push(path);
        }
    }
    out
}

/// `fmt` with no edits prints every program back byte for byte.
#[test]
fn fmt_is_lossless_on_every_case_file() {
    for dir in ["tests/cases/parse", "tests/cases/thesis", "examples/programs"] {
        // The settings file beside the example programs is no program.
        for path in walk(&repo().join(dir)).into_iter().filter(|p| p.extension().is_none_or(|e| e != "toml")) {
            let output = Command::new(env!("CARGO_BIN_EXE_turnpass")).arg("fmt").arg(&path).output().unwrap();
            assert_eq!(output.stdout, std::fs::read(&path).unwrap(), "{}", path.display());
        }
    }
}
