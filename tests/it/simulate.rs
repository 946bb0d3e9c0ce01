//! Simulate cases: `tests/cases/simulate/**/*.nc`, each lowered on the machine of the
//! nearest `machine.toml` (or its own `<name>.toml`). Cases under `err/` must report an
//! error; all others must lower with none and give a valid toolpath. The snapshot holds
//! the diagnostics, the summary, every move, and the `expand` output.
//!
//! Every case also checks that expansion is faithful: the expanded program, parsed and
//! lowered again, moves the tool through the same points (to the least increment).

use std::fmt::Write as _;
use std::path::Path;

use turnpass::dialect::{DialectChoice, GCodeSystem};
use turnpass::machine::{MachineSettings, ModelFile};
use turnpass::pipeline::{Lowering, Settings};
use turnpass::printer::print;
use turnpass::semantic::LowerOptions;
use turnpass::syntax::ParseOptions;
use turnpass::toolpath::{Motion, Toolpath};

use crate::support::{analyse, render, repo, with_snapshots};

/// The machine settings of a case: `<case>.toml` beside it, else the nearest `machine.toml`
/// in its directory or above (up to `tests/cases/simulate`).
pub fn settings_for(case: &Path) -> MachineSettings {
    let own = case.with_extension("toml");
    let path = if own.is_file() {
        own
    } else {
        let root = repo().join("tests/cases/simulate");
        case.ancestors()
            .skip(1)
            .take_while(|dir| dir.starts_with(&root))
            .map(|dir| dir.join("machine.toml"))
            .find(|p| p.is_file())
            .unwrap_or_else(|| panic!("no machine.toml for {}", case.display()))
    };
    ModelFile::from_toml(&std::fs::read_to_string(&path).unwrap()).unwrap().machine
}

pub fn parse_options(settings: &MachineSettings) -> ParseOptions {
    ParseOptions {
        dialect: settings.dialect.map_or(DialectChoice::Auto, DialectChoice::Fixed),
        gcode_system: settings.gcode_system.unwrap_or(GCodeSystem::A),
        machine_kind: None,
        control: settings.control.unwrap_or_default(),
    }
}

/// Moves as text: one line each, X as radius, mm, four decimals.
pub fn moves_text(program: &turnpass::syntax::Program<'_>, toolpath: &Toolpath) -> String {
    let lines = turnpass::source::LineIndex::new(program.source());
    let mut out = String::new();
    let _ = writeln!(out, "start X{:.4} Z{:.4}", toolpath.start.x, toolpath.start.z);
    for m in &toolpath.moves {
        let line = if m.source.is_synthetic() { 0 } else { lines.position(m.source.start).0 };
        let _ = write!(out, "{line:>4} {:<5} X{:.4} Z{:.4}", m.motion.name(), m.end.x, m.end.z);
        if m.is_arc() {
            let _ = write!(out, " C{:.4},{:.4}", m.centre.x, m.centre.z);
        }
        if m.motion == Motion::Dwell {
            let _ = write!(out, " {:.3}s", m.t_end - m.t_start);
        } else if m.motion != Motion::Rapid {
            let _ = write!(out, " F{:.2}", m.feed);
        }
        let _ = write!(out, " S{:.0} t{:.3}", m.rpm, m.t_end);
        if m.cutting {
            out.push_str(" cut");
        }
        if m.threading {
            out.push_str(" thread");
            if m.phase != 0.0 {
                let _ = write!(out, " phase{:.4}", m.phase);
            }
        }
        out.push('\n');
    }
    out
}

/// The pipeline's settings for a case's machine `settings` (its block-delete switch
/// included), with nose-radius compensation on as `simulate` runs, or off as `expand` does.
pub fn pipeline_settings(settings: &MachineSettings, compensation: bool) -> Settings {
    let block_delete = settings.block_delete.unwrap_or(false);
    let lower = LowerOptions { nose_radius_compensation: compensation, ..LowerOptions::new(block_delete) };
    Settings::new(parse_options(settings), settings, lower)
}

fn run_case(path: &Path) -> String {
    let source = std::fs::read(path).unwrap();
    let settings = settings_for(path);
    let analysed = analyse(&source, &pipeline_settings(&settings, true));
    let diagnostics = &analysed.diagnostics;
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let errors = diagnostics.iter().any(|d| d.is_error());
    let err_case = path.components().any(|c| c.as_os_str() == "err");
    assert_eq!(errors, err_case, "{}:\n{}", path.display(), render(&name, &source, diagnostics));

    let mut out = String::new();
    let _ = writeln!(out, "----- SOURCE\n{}", String::from_utf8_lossy(&source).trim_end());
    let _ = writeln!(out, "----- DIAGNOSTICS\n{}", render(&name, &source, diagnostics).trim_end());
    let program = &analysed.parsed.program;
    if let Lowering::Valid(lowered) = &analysed.lowering {
        let summary = turnpass::simulation::summary(program, lowered, &analysed.machine);
        let _ = writeln!(
            out,
            "----- SUMMARY\ncycle {:.3} s, cutting {:.3} s, path {:.3} mm, cutting {:.3} mm, {} moves",
            summary.cycle_time_s,
            summary.cutting_time_s,
            summary.path_length_mm,
            summary.cutting_length_mm,
            summary.moves
        );
        for pass in &summary.finishing_passes {
            let _ = writeln!(
                out,
                "finishing line {} tool {} f {:.4} mm/rev r {:.4} mm Rt {}",
                pass.line,
                pass.tool,
                pass.feed_per_rev_mm,
                pass.nose_radius_mm,
                pass.roughness_mm.map_or("-".to_string(), |rt| format!("{:.3} µm ({})", rt * 1000.0, pass.formula))
            );
        }
    }
    let lowered = analysed.lowered().expect("every simulate case is a lathe program");
    let _ = write!(out, "----- MOVES\n{}", moves_text(program, &lowered.toolpath));
    if !errors {
        let _ = write!(out, "----- EXPANDED\n{}", expand_and_compare(path, &source, &settings));
    }
    out
}

/// The `expand` output of `source`, a program with no errors on the machine `settings`
/// describe, after checking that it moves the tool as the original does.
pub fn expand_and_compare(path: &Path, source: &[u8], settings: &MachineSettings) -> String {
    let plain = pipeline_settings(settings, false);
    let ready = match analyse(source, &plain).ready() {
        Ok(ready) => ready,
        Err(analysed) => {
            panic!("{}: lowered without nose-radius compensation:\n{:?}", path.display(), analysed.diagnostics)
        }
    };
    let (program, machine) = (ready.program(), &ready.machine);
    let (edits, notes) = turnpass::expand::expansion_edits(program, &ready.lowered);
    let expanded = print(program, &edits);
    let again = analyse(&expanded, &plain);
    assert_eq!(
        again.parsed.error_count(),
        0,
        "{}: expanded program:\n{}",
        path.display(),
        render("expanded", &expanded, &again.parsed.diagnostics)
    );
    assert!(again.error_count() == 0, "{}: expanded program lowers with errors", path.display());
    let again = again.lowered().expect("the expanded program lowers");
    let lowered = &ready.lowered;
    // Expansion rounds to the least increment, and rapids of zero length vanish.
    let tolerance = machine.increment * machine.scale() * 1.01;
    // Each move's kind, end point, and the F and S words in force (as written), so that an
    // expansion that leaves another feed or speed in force for later blocks shows; a thread
    // move's phase, so that a start of a multi-start thread written without its angle shows.
    let points = |t: &Toolpath| -> Vec<(Motion, bool, f64, f64, f64, f64, f64)> {
        let mut out = Vec::new();
        let mut at = t.start;
        for m in &t.moves {
            if m.motion == Motion::Dwell || (m.end.distance(at) <= tolerance && !m.is_arc()) {
                continue;
            }
            let f_word = if m.motion == Motion::Rapid { 0.0 } else { m.f_word };
            out.push((m.motion, m.threading, m.end.x, m.end.z, f_word, m.s_word, m.phase));
            at = m.end;
        }
        out
    };
    let (a, b) = (points(&lowered.toolpath), points(&again.toolpath));
    assert_eq!(a.len(), b.len(), "{}: the expanded program has a different number of moves", path.display());
    for (i, (p, q)) in a.iter().zip(&b).enumerate() {
        assert!(
            p.0 == q.0
                && p.1 == q.1
                && (p.2 - q.2).abs() <= tolerance
                && (p.3 - q.3).abs() <= tolerance
                && (p.4 - q.4).abs() <= 1e-9
                && (p.5 - q.5).abs() <= 1e-9
                && (p.6 - q.6).abs() <= 1e-6,
            "{}: move {i} differs after expansion: {p:?} vs {q:?}",
            path.display()
        );
    }
    let mut out = String::from_utf8_lossy(&expanded).into_owned();
    if !notes.is_empty() {
        out.push_str(&render("expand", program.source(), &notes));
    }
    out
}

#[test]
fn simulate_cases() {
    with_snapshots("simulate", || {
        insta::glob!("../cases/simulate", "**/*.nc", |path| {
            insta::assert_snapshot!(run_case(path));
        });
    });
}

/// `expand`'s check before it writes (`expand::check_written`) compares each cutting move
/// with the original's, its thread's start angle included: a printing of
/// `simulate/fanuc/thread-start-angles.nc` that loses the start angles of its `G32` passes
/// (tests/cases/expand-check/) cuts the same points, and the second starts recut the
/// first's grooves. It is refused at the first such pass.
#[test]
fn expand_check_refuses_a_printing_that_loses_a_start_angle() {
    let case = repo().join("tests/cases/simulate/fanuc/thread-start-angles.nc");
    let plain = pipeline_settings(&settings_for(&case), false);
    let source = std::fs::read(&case).unwrap();
    let ready = analyse(&source, &plain).ready().expect("the case lowers");
    let written =
        std::fs::read(repo().join("tests/cases/expand-check/thread-start-angles-written-without-the-angles.nc"))
            .unwrap();
    with_snapshots("simulate", || {
        insta::assert_debug_snapshot!(turnpass::expand::check_written(&ready.lowered, &written, &plain));
    });
}
