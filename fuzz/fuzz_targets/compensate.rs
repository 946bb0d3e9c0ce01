//! Fuzzes compensation and its check: `compensate` then `verify`, on built programs and
//! built models.
//!
//! An input whose first byte is 0xFF is a structured job (`common/program.rs` and
//! `common/model.rs`: a program from blocks and cycles, a model file from effects of every
//! kind with parameters of every size and inline slide tables); any other input is a
//! program's text (the seeds: the case files and the corpus) compensated on a fixed model
//! of several effects. The model file is read as `compensate` reads it (a file that does
//! not read, or holds a value out of its range, is refused: that is the reading's work);
//! the program is parsed, lowered with a small bound on the moves and validated, then
//! compensated with the strategy the input chooses. The target checks that nothing panics
//! or hangs, and that a compensation that is not refused prints a program that `compensate`'s
//! own check (`verify::check_written`: read back, lowered, validated and measured as `verify`
//! measures it) either refuses or finds keeping every word `verify` checks (a printed
//! program that does not lower cleanly, or with a move of more samples than a measure
//! holds, is refused there, as `compensate` refuses it).
//!
//! ```sh
//! RUSTC_BOOTSTRAP=1 cargo fuzz run compensate fuzz/corpus/compensate ../shared/corpus -- \
//!     -max_total_time=1800 -rss_limit_mb=2048 -max_len=16384 -dict=fuzz/gcode.dict -jobs=1
//! ```

#![no_main]

#[path = "common/model.rs"]
mod model;
#[path = "common/program.rs"]
mod program;

use arbitrary::{Arbitrary, Unstructured};
use libfuzzer_sys::fuzz_target;
use turnpass::compensation::fit::{FitOptions, Strategy};
use turnpass::compensation::verify;
use turnpass::compensation::{CompensateOptions, Judged, compensate_program};
use turnpass::dialect::{DialectChoice, GCodeSystem};
use turnpass::error_model::model_file::ModelSpec;
use turnpass::pipeline;
use turnpass::printer;
use turnpass::semantic::LowerOptions;
use turnpass::semantic::nose_radius::ToolTable;
use turnpass::syntax::ParseOptions;

/// The model of a program given as text: several effects, on the first fuzz machine.
const FIXED_EFFECTS: &str = "[[effect]]\nkind = \"backlash_x\"\nb = 0.004\n[[effect]]\nkind = \"scale_z\"\nppm = 30.0\n\
[[effect]]\nkind = \"cyclic_z\"\namp = 0.0015\npitch = 11.94\nphase = 0.0\n[[effect]]\nkind = \"thermal_z\"\namp = 0.008\n\
tau_min = 54.59\n[[effect]]\nkind = \"squareness\"\nurad = 20.0\n";

fuzz_target!(|data: &[u8]| {
    let (text, model_text, strategy) = match data {
        [0xFF, choice, rest @ ..] => {
            let mut u = Unstructured::new(rest);
            let (Ok(program), Ok(model)) = (program::Program::arbitrary(&mut u), model::Model::arbitrary(&mut u))
            else {
                return;
            };
            let machine = program::MACHINES[usize::from(*choice) % 2];
            (
                program.text().into_bytes(),
                model.text(machine),
                Strategy::ALL[usize::from(*choice / 2) % Strategy::ALL.len()],
            )
        }
        _ => (data.to_vec(), format!("{}{FIXED_EFFECTS}", program::MACHINES[0]), Strategy::Auto),
    };
    let Ok(spec) = ModelSpec::read(&model_text) else { return };
    let Ok(model) = spec.build(|_| Err("no table files".to_string())) else { return };
    let settings = &spec.machine;
    let options = ParseOptions {
        dialect: settings.dialect.map_or(DialectChoice::Auto, DialectChoice::Fixed),
        gcode_system: settings.gcode_system.unwrap_or(GCodeSystem::A),
        machine_kind: None,
        control: settings.control.unwrap_or_default(),
    };
    let lower_options = LowerOptions { max_moves: 5_000, max_executed_blocks: 20_000, ..LowerOptions::new(false) };
    let reading = pipeline::Settings::new(options, settings, lower_options);
    // A program with an error, or whose text was cut, is refused before compensation.
    let Ok(ready) = pipeline::analyse(&text, &reading).ready() else { return };
    if ready.lowered.cut_off.is_some() {
        return;
    }
    let machine = &ready.machine;
    let compensate_options = CompensateOptions {
        fit: FitOptions { strategy, tolerance_mm: machine.increment * machine.scale() / 2.0, step_mm: None },
        max_shift_mm: 0.1,
        expand_cycles: false,
        profiles_in_place: true,
        profiles_copied: true,
        threads_in_place: true,
        singles_in_place: true,
        others_as_written: false,
        thread_pieces_every_pass: false,
        paths: false,
        block_reports: true,
    };
    let outcome =
        compensate_program(ready.program(), &ready.lowered, machine, &model, &compensate_options, Judged::EveryFeed);
    if outcome.refused() {
        return;
    }
    let printed = printer::print(ready.program(), &outcome.edits);
    // What `compensate` checks before it writes: read back as the original was read (with
    // `--dialect auto`, the evidence may be in the blocks an edit replaced), lowered,
    // validated and measured as `verify` measures it. A program that does not run cleanly
    // (the nose left no room under G41/G42 by a backlash take-up, a point off the travel)
    // is refused there: that is its check, not a finding.
    let read_back = pipeline::Settings { parse: printer::read_back_options(ready.program()), ..reading };
    let tools = ToolTable::from_machine(machine);
    let original = || {
        let words = verify::Words::of(ready.program(), &ready.lowered.expansions);
        Ok(verify::Held::from_toolpath(words, ready.valid(), &tools))
    };
    let measure = (&model, verify::Measure::Part, verify::PartFrom::default());
    let Ok(verify::Written { lost, .. }) = verify::check_written(original, &printed, &read_back, &tools, measure)
    else {
        return;
    };
    // Every word verify checks is kept (`compensate` refuses a program that would lose one,
    // as a defect of turnpass).
    assert!(
        lost.is_none(),
        "compensation loses {lost:?}:\n{}\n--- compensated:\n{}",
        String::from_utf8_lossy(&text),
        String::from_utf8_lossy(&printed)
    );
});
