//! Every program of `../shared/corpus/` and both thesis examples, lowered on the machine
//! `tests/corpus.toml` names for it: the parse reports exactly its `faults`, the semantic
//! pass exactly its `lowering_faults` (line and code); a program with no error gives a
//! valid toolpath, and its `expand` output re-parses with no error and, lowered again,
//! moves through the same points. The snapshot is a compact summary per program
//! (`snapshots/corpus/semantic/`): the diagnostics, the move count, the cycle time and path
//! length, and the moves of each cycle call; not every move. The thesis examples run
//! always; the corpus programs when the corpus is there (`support::external`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

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

#[test]
fn every_corpus_program_and_thesis_example_lowers_with_only_its_real_faults() {
    let manifest = manifest();
    let corpus = match external::corpus_for("its corpus programs (the thesis examples run)") {
        Some(dir) => manifest.file.iter().map(|e| (dir.join(&e.path), e.path.replace('/', "__"), e)).collect(),
        None => Vec::new(),
    };
    let programs = corpus.into_iter().chain(manifest.example.iter().map(|e| {
        let path: PathBuf = repo().join(&e.path);
        let name = format!("example__{}", path.file_name().unwrap().to_string_lossy());
        (path, name, e)
    }));
    // Every program runs, and the failures are reported together.
    let mut failed = Vec::new();
    for (path, name, entry) in programs {
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
