//! Every program of `../shared/corpus/` and both thesis examples, lowered on the machine
//! `tests/corpus.toml` names for it: the parse reports exactly its `faults`, the semantic
//! pass exactly its `lowering_faults` (line and code); a program with no error gives a
//! valid toolpath, and its `expand` output re-parses with no error and, lowered again,
//! moves through the same points. The snapshot is a compact summary per program
//! (`snapshots/corpus/semantic/`): the diagnostics, the move count, the cycle time and path
//! length, and the moves of each cycle call; not every move. The thesis examples run
//! always; the corpus programs when the corpus is there (`support::external`).
//!
//! `missing_points` reads each again as if its machine counted least increments, and with no
//! `decimal_input` at all: the words without a decimal point that read implausibly then
//! (README, "Decimal input") are as many as `tests/corpus.toml` says.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use turnpass::diagnostic::DiagnosticKind;
use turnpass::dialect::GCodeSystem;
use turnpass::machine::{MachineSettings, ModelFile};
use turnpass::pipeline::Lowering;
use turnpass::printer::print;
use turnpass::semantic::Lowered;
use turnpass::source::LineIndex;
use turnpass::syntax::{Program, parse};

use crate::corpus::{Entry, Fault, manifest};
use crate::simulate::{expand_and_compare, parse_options, pipeline_settings};
use crate::support::{analyse, check_spans, external, render, repo, with_snapshots};

/// The machine file's settings, with the entry's G-code system.
fn settings_for(entry: &Entry) -> MachineSettings {
    let text = std::fs::read_to_string(repo().join(&entry.machine))
        .unwrap_or_else(|e| panic!("{}: machine file {}: {e}", entry.path, entry.machine));
    let mut settings = ModelFile::from_toml(&text).unwrap().machine;
    if let Some(system) = &entry.gcode_system {
        let system: GCodeSystem = system.parse().unwrap();
        assert!(
            settings.gcode_system.is_none_or(|s| s == system),
            "{}: the entry and its machine file disagree on the G-code system",
            entry.path
        );
        settings.gcode_system = Some(system);
    }
    settings
}

fn faults(program: &Program<'_>, diagnostics: &[turnpass::diagnostic::Diagnostic]) -> Vec<Fault> {
    let lines = LineIndex::new(program.source());
    diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| Fault { line: lines.position(d.span.start).0, code: d.code().to_string() })
        .collect()
}

/// The moves of each cycle call: its line, its text, how many moves, how many blocks it
/// consumed.
fn cycles_text(program: &Program<'_>, lowered: &Lowered) -> String {
    let lines = LineIndex::new(program.source());
    let mut out = String::new();
    for expansion in &lowered.expansions {
        let block = program.block(expansion.block);
        let text = String::from_utf8_lossy(program.text(block.span)).trim().to_string();
        let _ = writeln!(
            out,
            "  line {} `{}`: {} moves, {} blocks consumed",
            lines.position(block.span.start).0,
            text,
            expansion.moves.len(),
            expansion.consumed.len()
        );
    }
    out
}

fn run(path: &Path, name: &str, entry: &Entry) -> String {
    let source = std::fs::read(path).unwrap();
    let settings = settings_for(entry);
    let analysed = analyse(&source, &pipeline_settings(&settings, true));
    let (parsed, diagnostics) = (&analysed.parsed, &analysed.diagnostics);
    assert_eq!(parsed.program.config().dialect.cli_name(), entry.dialect, "{name}: dialect");
    let rendered = render(name, &source, diagnostics);

    assert_eq!(faults(&parsed.program, &parsed.diagnostics), entry.faults, "{name}: parse errors\n{rendered}");
    // The semantic pass's and the validation's: every diagnostic the parse did not give.
    let lowering_errors: Vec<_> = diagnostics.iter().filter(|d| !parsed.diagnostics.contains(d)).cloned().collect();
    assert_eq!(
        faults(&parsed.program, &lowering_errors),
        entry.lowering_faults,
        "{name}: errors of the semantic pass\n{rendered}"
    );

    let mut out = String::new();
    let system = settings.gcode_system.unwrap_or(GCodeSystem::A);
    let _ = writeln!(out, "machine: {}, G-code system {system:?}", entry.machine);
    let _ = writeln!(out, "----- DIAGNOSTICS\n{}", rendered.trim_end());
    let lowered = match &analysed.lowering {
        Lowering::NotLowered => {
            // An OSP machining-centre program: only its syntax is checked.
            assert_eq!(diagnostics, &parsed.diagnostics, "{name}: not lowered");
            out.push_str("----- NOT LOWERED (machining-centre program)\n");
            return out;
        }
        Lowering::Invalid(lowered) => lowered,
        Lowering::Valid(lowered) => lowered,
    };
    let errors = diagnostics.iter().any(|d| d.is_error());
    match &analysed.lowering {
        Lowering::Valid(valid) => {
            let summary = turnpass::simulation::summary(&parsed.program, valid, &analysed.machine);
            let _ = writeln!(
                out,
                "----- SUMMARY\n{} moves, cycle {:.3} s, cutting {:.3} s, path {:.3} mm, cutting {:.3} mm",
                summary.moves,
                summary.cycle_time_s,
                summary.cutting_time_s,
                summary.path_length_mm,
                summary.cutting_length_mm
            );
        }
        _ => assert!(errors, "{name}: an invalid toolpath is an error"),
    }
    let _ = write!(out, "----- CYCLES\n{}", cycles_text(&parsed.program, lowered));

    if errors {
        // A program with errors is not expanded by the CLI; what expansion there is of a
        // valid toolpath must still re-parse.
        if let Lowering::Valid(valid) = &analysed.lowering {
            let (edits, _) = turnpass::expand::expansion_edits(&parsed.program, valid);
            let expanded = print(&parsed.program, &edits);
            let reparsed = parse(&expanded, &parse_options(&settings));
            check_spans(&reparsed);
            assert_eq!(
                reparsed.error_count(),
                parsed.error_count(),
                "{name}: the expanded program re-parses with the same errors\n{}",
                render("expanded", &expanded, &reparsed.diagnostics)
            );
        }
    } else {
        let _ = expand_and_compare(path, &source, &settings);
    }
    out
}

/// The programs of the manifest that are at hand: the corpus's when it is there, and the
/// thesis examples.
fn programs<'m>(manifest: &'m crate::corpus::Manifest, why: &str) -> Vec<(PathBuf, String, &'m Entry)> {
    let corpus = match external::corpus_for(why) {
        Some(dir) => manifest.file.iter().map(|e| (dir.join(&e.path), e.path.replace('/', "__"), e)).collect(),
        None => Vec::new(),
    };
    corpus
        .into_iter()
        .chain(manifest.example.iter().map(|e| {
            let path: PathBuf = repo().join(&e.path);
            let name = format!("example__{}", path.file_name().unwrap().to_string_lossy());
            (path, name, e)
        }))
        .collect()
}

/// How many words of `source` the semantic pass says read implausibly as least increments
/// on the machine `settings` describe: warnings and errors it names as their cause, and the
/// count of the note said where the settings do not give `decimal_input`.
fn missing_points(source: &[u8], settings: &MachineSettings) -> (usize, usize) {
    let analysed = analyse(source, &pipeline_settings(settings, true));
    let mut said = 0;
    let mut noted = 0;
    for d in &analysed.diagnostics {
        match &d.kind {
            DiagnosticKind::MissingDecimalPoint { .. } | DiagnosticKind::MissingPointCauses { .. } => said += 1,
            DiagnosticKind::DecimalInputUnset { count, .. } => noted += count,
            _ => {}
        }
    }
    (said, noted)
}

/// Each program read with increment input, with its own settings, and with no
/// `decimal_input`: the words read implausibly as increments are `missing_points` of the
/// manifest under the first, none under the second (calculator input, given), and said once
/// with that count under the third. The table printed (`--nocapture`) is README's.
#[test]
fn missing_points_are_those_the_manifest_counts() {
    use turnpass::dialect::DecimalInput;
    let manifest = manifest();
    let mut failed = Vec::new();
    println!("| program | decimal_input | increment: words warned of | unset: words counted by the note |");
    println!("|---|---|---|---|");
    for (path, name, entry) in programs(&manifest, "its corpus programs (the thesis examples run)") {
        let source = std::fs::read(&path).unwrap();
        let own = settings_for(entry);
        let increment = MachineSettings { decimal_input: Some(DecimalInput::Increment), ..own.clone() };
        let unset = MachineSettings { decimal_input: None, ..own.clone() };
        let (as_increments, _) = missing_points(&source, &increment);
        let (as_own, noted_own) = missing_points(&source, &own);
        let (_, noted) = missing_points(&source, &unset);
        let own_input = match own.decimal_input {
            _ if entry.dialect == "osp" => "(OSP reads a number as written)".to_string(),
            Some(input) => format!("{input:?}").to_lowercase(),
            None => "unset".to_string(),
        };
        println!("| {} | {own_input} | {as_increments} | {noted} |", entry.path);
        let expected = if entry.dialect == "fanuc" { entry.missing_points } else { 0 };
        let own_expected = if own.decimal_input == Some(DecimalInput::Increment) { expected } else { 0 };
        if as_increments != expected || noted != expected || (as_own, noted_own) != (own_expected, 0) {
            eprintln!(
                "{name}: increment input {as_increments}, unset {noted}, its own settings {as_own} (and a note of \
                 {noted_own}); the manifest says {expected}"
            );
            failed.push(name);
        }
    }
    assert!(failed.is_empty(), "failed (see the messages above): {failed:#?}");
}

#[test]
fn every_corpus_program_and_thesis_example_lowers_with_only_its_real_faults() {
    let manifest = manifest();
    // Every program runs, and the failures are reported together.
    let mut failed = Vec::new();
    for (path, name, entry) in programs(&manifest, "its corpus programs (the thesis examples run)") {
        let outcome = std::panic::catch_unwind(|| {
            let summary = run(&path, &name, entry);
            with_snapshots("corpus/semantic", || insta::assert_snapshot!(name.clone(), summary));
        });
        if outcome.is_err() {
            failed.push(name);
        }
    }
    assert!(failed.is_empty(), "failed (see the messages above): {failed:#?}");
}
