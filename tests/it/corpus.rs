//! Every program of `../shared/corpus/` (read in place): detected as the dialect it was
//! written in, parsed with zero errors except its real faults (listed in
//! `tests/corpus.toml`), printed back byte-identical, and in canonical form idempotently.
//! Skipped with a banner when the corpus is missing, a failure under CI
//! (`support::external`).

use std::path::Path;

use serde::Deserialize;
use turnpass::dialect::{DecimalInput, DialectChoice, GCodeSystem};
use turnpass::printer::{CanonicalOptions, Edits, print, print_canonical};
use turnpass::source::LineIndex;
use turnpass::syntax::{ParseOptions, Statement, parse};

use crate::support::{check_spans, external, render, repo, with_snapshots};

/// `tests/corpus.toml`: the corpus programs, and the thesis examples the semantic test
/// lowers with them.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    pub file: Vec<Entry>,
    #[serde(default)]
    pub example: Vec<Entry>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Entry {
    pub path: String,
    pub dialect: String,
    #[serde(default)]
    pub gcode_system: Option<String>,
    /// The machine model file, relative to the repository.
    pub machine: String,
    /// Errors of the parse.
    #[serde(default)]
    pub faults: Vec<Fault>,
    /// Errors of the semantic pass.
    #[serde(default)]
    pub lowering_faults: Vec<Fault>,
    /// Words without a decimal point that read implausibly when the control counts least
    /// increments (`decimal_input = "increment"`): warned of, or named as the cause of an
    /// error (`corpus_semantic::missing_points`).
    #[serde(default)]
    pub missing_points: usize,
}

#[derive(Deserialize, PartialEq, Debug, Clone)]
#[serde(deny_unknown_fields)]
pub struct Fault {
    pub line: usize,
    pub code: String,
}

pub fn manifest() -> Manifest {
    toml::from_str(&std::fs::read_to_string(repo().join("tests/corpus.toml")).unwrap()).unwrap()
}

fn programs(dir: &Path, out: &mut Vec<String>, root: &Path) {
    for entry in std::fs::read_dir(dir).unwrap().flatten() {
        let path = entry.path();
        if path.is_dir() {
            programs(&path, out, root);
        } else if path.file_name().is_some_and(|n| n != "SOURCES.md") {
            out.push(path.strip_prefix(root).unwrap().to_string_lossy().replace('\\', "/"));
        }
    }
}

#[test]
fn every_corpus_program_parses_prints_back_and_reports_only_its_real_faults() {
    let Some(dir) = external::corpus() else { return };
    let manifest = manifest();
    let mut found = Vec::new();
    programs(&dir, &mut found, &dir);
    found.sort();
    let mut listed: Vec<String> = manifest.file.iter().map(|e| e.path.clone()).collect();
    listed.sort();
    assert_eq!(found, listed, "tests/corpus.toml lists every corpus program");

    for entry in &manifest.file {
        let source = std::fs::read(dir.join(&entry.path)).unwrap();
        let gcode_system: GCodeSystem = entry.gcode_system.as_deref().unwrap_or("A").parse().unwrap();
        // The dialect is detected, not given: detection must agree with the manifest.
        let options = ParseOptions {
            dialect: DialectChoice::Auto,
            gcode_system,
            machine_kind: None,
            control: Default::default(),
        };
        let parsed = parse(&source, &options);
        check_spans(&parsed);
        assert_eq!(parsed.detection.dialect.cli_name(), entry.dialect, "{}: detected dialect", entry.path);
        let lines = LineIndex::new(&source);
        let errors: Vec<Fault> = parsed
            .diagnostics
            .iter()
            .filter(|d| d.is_error())
            .map(|d| Fault { line: lines.position(d.span.start).0, code: d.code().to_string() })
            .collect();
        assert_eq!(errors, entry.faults, "{}:\n{}", entry.path, render(&entry.path, &source, &parsed.diagnostics));
        let invalid = parsed.program.blocks().iter().filter(|b| b.statement == Statement::Invalid).count();
        assert_eq!(invalid, entry.faults.len(), "{}: only the faulty blocks are invalid", entry.path);

        assert_eq!(print(&parsed.program, &Edits::new()), source, "{}: lossless", entry.path);
        let canonical_options = CanonicalOptions { decimal_input: DecimalInput::Calculator, increment_places: 3 };
        let canonical = print_canonical(&parsed.program, &canonical_options);
        let reparsed = parse(&canonical, &options);
        assert_eq!(reparsed.error_count(), parsed.error_count(), "{}: canonical form parses", entry.path);
        assert_eq!(
            print_canonical(&reparsed.program, &canonical_options),
            canonical,
            "{}: canonical is idempotent",
            entry.path
        );

        let name = entry.path.replace('/', "__");
        let summary = format!(
            "dialect: {} ({:?}), machine: {:?}, blocks: {}\n{}",
            parsed.detection.dialect,
            parsed.detection.choice,
            parsed.detection.machine_kind,
            parsed.program.blocks().len(),
            render(&entry.path, &source, &parsed.diagnostics)
        );
        with_snapshots("corpus", || insta::assert_snapshot!(name, summary));
    }
}
