//! `compensate` end to end: the filter and file paths, the blocks it may and may not
//! touch, incremental programs without drift, and the compensated program verified on the
//! model. Programs and models are in `tests/cases/compensate/`; the snapshots hold only the
//! changed lines.

use std::io::Write as _;
use std::process::{Command, Stdio};

use turnpass::compensation::fit::{FitOptions, Strategy};
use turnpass::compensation::{CompensateOptions, Judged, Outcome, compensate_program};
use turnpass::dialect::{Address, DialectChoice, GCodeSystem};
use turnpass::error_model::ErrorModel;
use turnpass::error_model::model_file::ModelSpec;
use turnpass::machine::{MachineSettings, ModelFile};
use turnpass::pipeline::{Ready, Settings};
use turnpass::printer;
use turnpass::semantic::{LowerOptions, Machine};
use turnpass::syntax::{CodeLetter, ParseOptions, Program, WordKind, parse};
use turnpass::toolpath::Xz;

use crate::support::{analyse, repo, with_snapshots};

const MACHINE: &str = "tests/cases/compensate/machine.toml";
const HOWA: &str = "tests/cases/compensate/howa.toml";
const RADIUS_LATHE: &str = "tests/cases/compensate/generated.toml";

/// Every program with the model it runs on.
const PROGRAMS: [(&str, &str); 6] = [
    ("tests/cases/compensate/turn.nc", MACHINE),
    ("tests/cases/compensate/incremental.nc", MACHINE),
    ("tests/cases/compensate/cycle.nc", MACHINE),
    ("tests/cases/compensate/generated.nc", RADIUS_LATHE),
    ("examples/programs/thesis-o2005-arc.nc", HOWA),
    ("examples/programs/thesis-o2012-turn-face.nc", HOWA),
];

fn turnpass(args: &[&str], stdin: Option<&[u8]>) -> (i32, Vec<u8>, String) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_turnpass"));
    command.args(args).current_dir(repo()).env("NO_COLOR", "1").stdout(Stdio::piped()).stderr(Stdio::piped());
    command.stdin(if stdin.is_some() { Stdio::piped() } else { Stdio::null() });
    let mut child = command.spawn().unwrap();
    if let Some(bytes) = stdin {
        child.stdin.take().unwrap().write_all(bytes).unwrap();
    }
    let output = child.wait_with_output().unwrap();
    (output.status.code().unwrap(), output.stdout, String::from_utf8_lossy(&output.stderr).into_owned())
}

/// The lines of `a` and `b` that differ, as a unified list (`-` removed, `+` added), from
/// their longest common subsequence.
pub fn changed_lines(a: &str, b: &str) -> String {
    let (a, b): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    let mut lcs = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for i in (0..a.len()).rev() {
        for j in (0..b.len()).rev() {
            lcs[i][j] = if a[i] == b[j] { lcs[i + 1][j + 1] + 1 } else { lcs[i + 1][j].max(lcs[i][j + 1]) };
        }
    }
    let (mut i, mut j, mut out) = (0, 0, String::new());
    while i < a.len() || j < b.len() {
        if i < a.len() && j < b.len() && a[i] == b[j] {
            i += 1;
            j += 1;
        } else if j < b.len() && (i == a.len() || lcs[i][j + 1] >= lcs[i + 1][j]) {
            out.push_str(&format!("+ {}\n", b[j]));
            j += 1;
        } else {
            out.push_str(&format!("- {}\n", a[i]));
            i += 1;
        }
    }
    out
}

#[test]
fn the_filter_and_the_file_paths_write_the_same_program_and_it_verifies() {
    let tmp = tempfile::tempdir().unwrap();
    for (program, model) in PROGRAMS {
        let original = std::fs::read(repo().join(program)).unwrap();
        // On the finished part the generated-style profile's arcs keep up to 6.6 µm (the
        // inverse follows the path, issue 25): its bound is widened, for what this test is
        // about (the filter and the file paths write the same program, and it verifies).
        let bound: &[&str] = if program.ends_with("generated.nc") { &["--max-deviation", "0.01"] } else { &[] };
        let (code, filtered, stderr) =
            turnpass(&[&["compensate", "-", "--model", model][..], bound].concat(), Some(&original));
        assert_eq!(code, 0, "{program}: {stderr}");
        let out = tmp.path().join("out.nc");
        let out_text = out.to_string_lossy().into_owned();
        let (code, stdout, stderr) =
            turnpass(&[&["compensate", program, "--model", model, "-o", &out_text][..], bound].concat(), None);
        assert_eq!(code, 0, "{program}: {stderr}");
        assert!(stdout.is_empty());
        assert_eq!(std::fs::read(&out).unwrap(), filtered, "{program}: the filter and -o differ");
        let (code, stdout, stderr) =
            turnpass(&[&["verify", program, &out_text, "--model", model][..], bound].concat(), None);
        let report = String::from_utf8_lossy(&stdout);
        assert_eq!(code, 0, "{program}: verify\n{report}{stderr}");
        if program.starts_with("tests/") {
            let name = std::path::Path::new(program).file_stem().unwrap().to_string_lossy().into_owned();
            let diff = changed_lines(&String::from_utf8_lossy(&original), &String::from_utf8_lossy(&filtered));
            // The provenance comment names the tool's version; a release must not change them all.
            let version = env!("CARGO_PKG_VERSION");
            let diff = diff.replace(&format!("TURNPASS {version} "), "TURNPASS {version} ");
            with_snapshots("compensate", || insta::assert_snapshot!(format!("{name}-changed-lines"), diff));
        }
    }
}

/// A program read, lowered, validated and compensated with its model.
struct Compensated {
    source: Vec<u8>,
    options: ParseOptions,
    settings: Settings,
    machine: Machine,
}

impl Compensated {
    fn new(program: &str, model: &str) -> (Compensated, ErrorModel) {
        let text = std::fs::read_to_string(repo().join(model)).unwrap();
        let settings: MachineSettings = ModelFile::from_toml(&text).unwrap().machine;
        let model = ModelSpec::from_toml(&text).unwrap().build(|_| Err("no tables".into())).unwrap();
        let options = ParseOptions {
            dialect: DialectChoice::Auto,
            gcode_system: settings.gcode_system.unwrap_or(GCodeSystem::A),
            machine_kind: None,
            control: Default::default(),
        };
        let source = std::fs::read(repo().join(program)).unwrap();
        let pipeline = Settings::new(options, &settings, LowerOptions::new(false));
        (Compensated { source, options, machine: pipeline.machine.clone(), settings: pipeline }, model)
    }

    /// `source` read, lowered and validated on the case's machine; it must have no error.
    fn ready<'s>(&self, source: &'s [u8]) -> Ready<'s> {
        match analyse(source, &self.settings).ready() {
            Ok(ready) => ready,
            Err(analysed) => panic!("the program has errors: {:?}", analysed.diagnostics),
        }
    }

    /// Compensated as `compensate` writes it: the cycles kept with their profile or words
    /// edited in place, and, where the program so written does not read back cleanly (a
    /// profile the roughing cycle refuses), expanded instead.
    fn run(&self, ready: &Ready<'_>, model: &ErrorModel, fit: FitOptions) -> Outcome {
        let options = |in_place: bool| CompensateOptions {
            fit,
            max_shift_mm: 0.1,
            expand_cycles: false,
            profiles_in_place: in_place,
            profiles_copied: in_place,
            threads_in_place: in_place,
            singles_in_place: in_place,
            others_as_written: false,
            thread_pieces_every_pass: false,
            paths: false,
            block_reports: true,
        };
        let outcome = compensate_program(
            ready.program(),
            &ready.lowered,
            &ready.machine,
            model,
            &options(true),
            Judged::EveryFeed,
        );
        let output = printer::print(ready.program(), &outcome.edits);
        if outcome.refused() || analyse(&output, &self.settings).ready().is_ok() {
            return outcome;
        }
        compensate_program(ready.program(), &ready.lowered, &ready.machine, model, &options(false), Judged::EveryFeed)
    }

    fn fit(&self) -> FitOptions {
        FitOptions {
            strategy: Strategy::Auto,
            tolerance_mm: self.machine.increment * self.machine.scale() / 2.0,
            step_mm: None,
        }
    }
}

/// The words of a block that are not its motion: everything but the coordinates and the
/// motion code, as written.
fn other_words(program: &Program<'_>, index: usize) -> Vec<String> {
    let block = program.block(index);
    let tables = program.config().tables();
    program
        .words_of(block)
        .iter()
        .filter(|w| match w.kind {
            WordKind::Number { address, .. } | WordKind::Expr { address, .. } => {
                ![Address::X, Address::Z, Address::U, Address::W, Address::R, Address::I, Address::K].contains(&address)
            }
            WordKind::Code { letter: CodeLetter::G, code } => !matches!(
                tables.g(code).and_then(|g| g.function),
                Some(
                    turnpass::dialect::GFunction::Rapid
                        | turnpass::dialect::GFunction::Linear
                        | turnpass::dialect::GFunction::Cw
                        | turnpass::dialect::GFunction::Ccw
                )
            ),
            _ => true,
        })
        .map(|w| String::from_utf8_lossy(program.text(w.span)).into_owned())
        .collect()
}

#[test]
fn untouched_blocks_print_byte_identical_and_edited_blocks_change_only_their_motion() {
    for (path, model_path) in PROGRAMS {
        let (case, model) = Compensated::new(path, model_path);
        let ready = case.ready(&case.source);
        let parsed = &ready.parsed;
        let outcome = case.run(&ready, &model, case.fit());
        assert!(!outcome.refused(), "{path}: {:?}", outcome.diagnostics);
        let output = printer::print(&parsed.program, &outcome.edits);
        let lowered = &ready.lowered;
        // Blocks an expanded cycle consumed go with it.
        let mut gone: Vec<usize> = Vec::new();
        for edited in outcome.edited.iter().filter(|e| e.cycle) {
            for expansion in lowered.expansions.iter().filter(|x| x.block == edited.block) {
                gone.extend(&expansion.consumed);
            }
        }
        let edited: Vec<usize> = outcome.edited.iter().map(|e| e.block).collect();
        assert!(!edited.is_empty(), "{path}: nothing edited");
        // Every other block, with its line ending, appears in the output byte for byte and
        // in order.
        let mut at = 0;
        for (index, block) in parsed.program.blocks().iter().enumerate() {
            if edited.contains(&index) || gone.contains(&index) {
                continue;
            }
            let mut line = parsed.program.text(block.span).to_vec();
            line.extend_from_slice(parsed.program.terminator(index));
            let found = output[at..].windows(line.len().max(1)).position(|w| w == line.as_slice());
            let Some(found) = found else {
                panic!("{path}: block {index} `{}` is not in the output as it was", String::from_utf8_lossy(&line))
            };
            at += found + line.len();
        }
        // An edited motion block's first written block keeps all its other words, in order.
        let reparsed = parse(&output, &case.options);
        assert_eq!(reparsed.error_count(), 0, "{path}");
        let written: Vec<Vec<String>> =
            (0..reparsed.program.blocks().len()).map(|k| other_words(&reparsed.program, k)).collect();
        // A finishing call that runs a compensated copy of its profile names the copy instead
        // (its `P`/`Q` or its contour's name).
        let copied: Vec<usize> = outcome
            .cycles
            .iter()
            .filter(|c| matches!(c.form, turnpass::compensation::CycleForm::ProfileCopied { .. }))
            .map(|c| c.block)
            .collect();
        for e in outcome.edited.iter().filter(|e| !e.cycle && !copied.contains(&e.block)) {
            let words = other_words(&parsed.program, e.block);
            assert!(written.contains(&words), "{path}: block {} lost some of {words:?}", e.block);
        }
        // And nothing that is not motion went missing anywhere.
        use turnpass::compensation::verify::{Words, check_words};
        let check = check_words(
            &Words::of(&parsed.program, &lowered.expansions),
            &Words::of(&reparsed.program, &case.ready(&output).lowered.expansions),
        );
        assert_eq!(check.missing, None, "{path}");
    }
}

#[test]
fn a_model_with_no_errors_edits_nothing() {
    for (path, model_path) in PROGRAMS {
        let (case, _) = Compensated::new(path, model_path);
        let ready = case.ready(&case.source);
        let parsed = &ready.parsed;
        let outcome = case.run(&ready, &ErrorModel::default(), case.fit());
        assert!(outcome.edits.is_empty(), "{path}: {:?}", outcome.edited);
        assert_eq!(printer::print(&parsed.program, &outcome.edits), case.source);
    }
}

/// `count` blocks of a zig-zag profile, written as `U`/`W` increments or as absolutes.
fn zig_zag(count: usize, incremental: bool) -> String {
    let mut text = String::from("%\nO2001\nG21 G99\nG97 S800 M03\nG00 X40. Z2.\nG01 Z0 F0.1\n");
    let (mut x, mut z) = (40_000i64, 0i64);
    for k in 0..count {
        // Steps of odd sizes, so that the exact corrected points fall anywhere on the grid.
        let du = if k % 2 == 0 { 1_237 } else { -1_119 };
        let dw = -(313 + (k as i64 * 37) % 200);
        (x, z) = (x + du, z + dw);
        let number = |v: i64| format!("{}{}.{:03}", if v < 0 { "-" } else { "" }, v.abs() / 1000, v.abs() % 1000);
        if incremental {
            text.push_str(&format!("U{} W{}\n", number(du), number(dw)));
        } else {
            text.push_str(&format!("X{} Z{}\n", number(x), number(z)));
        }
    }
    text.push_str("G00 X200. Z100.\nM30\n%\n");
    text
}

#[test]
fn an_incremental_program_comes_out_on_the_same_points_as_its_absolute_twin() {
    let (case, model) = Compensated::new("tests/cases/compensate/turn.nc", MACHINE);
    let mut ends: Vec<Vec<Xz>> = Vec::new();
    for incremental in [true, false] {
        let text = zig_zag(400, incremental);
        let ready = case.ready(text.as_bytes());
        let parsed = &ready.parsed;
        let outcome = case.run(&ready, &model, case.fit());
        assert!(!outcome.refused(), "{:?}", outcome.diagnostics);
        let output = printer::print(&parsed.program, &outcome.edits);
        if incremental {
            let out = String::from_utf8_lossy(&output);
            assert!(out.lines().filter(|l| l.starts_with('U') || l.starts_with('W')).count() > 400, "{out}");
            assert!(!out.lines().any(|l| l.starts_with('X') && l.contains('W')), "mixed forms:\n{out}");
        }
        let lowered = case.ready(&output).lowered;
        ends.push(lowered.toolpath.moves.iter().map(|m| m.end).collect());
    }
    // The increments are differences of rounded absolutes: the incremental program reaches
    // every point the absolute one does, to the last of the 400 blocks (within the float
    // noise of summing increments).
    assert_eq!(ends[0].len(), ends[1].len());
    for (k, (a, b)) in ends[0].iter().zip(&ends[1]).enumerate() {
        assert!(a.distance(*b) < 1e-9, "move {k}: {a:?} against {b:?}");
    }
}

#[test]
fn the_report_shows_each_edited_block_improving() {
    let (case, model) = Compensated::new("tests/cases/compensate/turn.nc", MACHINE);
    let ready = case.ready(&case.source);
    let outcome = case.run(&ready, &model, case.fit());
    let report = &outcome.report;
    assert_eq!(report.blocks.len(), outcome.edited.len());
    for block in &report.blocks {
        assert!(block.max_correction_mm > 0.0 && block.max_correction_mm < 0.01, "{block:?}");
        assert!(block.rms_correction_mm <= block.max_correction_mm, "{block:?}");
        assert!(block.ssq_after_mm <= block.ssq_before_mm, "{block:?}");
    }
    let totals = &report.totals;
    assert!(totals.improvement_percent.is_some_and(|p| p >= 90.0), "{totals:?}");
    assert!(totals.after.max_mm <= case.machine.increment, "{totals:?}");
}

#[test]
fn plots_draw_every_path_and_both_directions_of_a_ball_bar() {
    for (program, polar, labels) in [
        ("tests/cases/compensate/turn.nc", false, &["nominal", "as programmed", "compensated"][..]),
        (
            "tests/cases/compensate/ballbar.nc",
            true,
            &["clockwise (G02), as programmed", "clockwise (G02), compensated", "counter-clockwise (G03), compensated"]
                [..],
        ),
    ] {
        let tmp = tempfile::tempdir().unwrap();
        let out = tmp.path().join("plot.svg").to_string_lossy().into_owned();
        let mut args = vec!["plot", program, "--model", MACHINE, "-o", &out];
        if polar {
            args.push("--polar");
        }
        let (code, _, stderr) = turnpass(&args, None);
        assert_eq!(code, 0, "{stderr}");
        let svg = std::fs::read_to_string(&out).unwrap();
        assert!(svg.starts_with("<svg"), "{program}");
        for label in labels {
            assert!(svg.contains(label), "{program}: no `{label}`");
        }
    }
}
