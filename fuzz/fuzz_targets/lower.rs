//! Fuzzes lowering and what is made of it: `simulate` (the rows, the summary) and `expand`.
//!
//! An input whose first byte is 0xFF is a structured program (`common/program.rs`: blocks
//! and cycles, built with `arbitrary`, so that nearly every input parses and most of them
//! run); any other input is a program's text, as the seeds are (the case files and the
//! corpus, read in place). The machine's settings are chosen by the input. Each program is
//! parsed, lowered with a small bound on the moves (so that a runaway input stays fast),
//! validated, simulated and expanded. The target checks that nothing panics or hangs, and
//! that the expanded program of one that lowers without errors parses and lowers without
//! errors again and makes as many cutting moves.
//!
//! ```sh
//! RUSTC_BOOTSTRAP=1 cargo fuzz run lower fuzz/corpus/lower tests/cases ../shared/corpus -- \
//!     -max_total_time=1800 -rss_limit_mb=2048 -max_len=16384 -dict=fuzz/gcode.dict -jobs=1
//! ```

#![no_main]

#[path = "common/program.rs"]
mod program;

use libfuzzer_sys::fuzz_target;
use turnpass::dialect::{DialectChoice, GCodeSystem};
use turnpass::machine::ModelFile;
use turnpass::pipeline::{self, Lowering};
use turnpass::printer;
use turnpass::semantic::LowerOptions;
use turnpass::syntax::ParseOptions;

fuzz_target!(|data: &[u8]| {
    let Some((text, machine)) = program::program_text(data) else { return };
    let settings = ModelFile::from_toml(machine).expect("the fuzz machines read").machine;
    let options = ParseOptions {
        dialect: settings.dialect.map_or(DialectChoice::Auto, DialectChoice::Fixed),
        gcode_system: settings.gcode_system.unwrap_or(GCodeSystem::A),
        machine_kind: None,
        control: settings.control.unwrap_or_default(),
    };
    let lower_options = LowerOptions { max_moves: 20_000, max_executed_blocks: 50_000, ..LowerOptions::new(false) };
    let reading = pipeline::Settings::new(options, &settings, lower_options);
    let analysed = pipeline::analyse(&text, &reading);
    let Some(lowered) = analysed.lowered() else { return };
    let clean = analysed.error_count() == 0 && lowered.cut_off.is_none();
    // How deep an input gets, for the note on a corpus (`fuzz/README.md`): one line per input.
    if std::env::var_os("TURNPASS_FUZZ_DEPTH").is_some() {
        let structured = data.first() == Some(&0xFF);
        eprintln!("depth structured={structured} parsed={} clean={clean}", !analysed.parsed.has_errors());
    }
    // A toolpath that does not validate (a move off the travel, a number too large to be
    // finite) is reported as such by every command: that is the validation's work.
    let Lowering::Valid(lowered) = &analysed.lowering else { return };
    let program = &analysed.parsed.program;
    let rows = turnpass::simulation::rows(program, lowered.valid());
    let mut csv = Vec::new();
    turnpass::simulation::write_csv(rows, &mut csv).expect("CSV into memory");
    let _ = serde_json::to_vec(&rows).expect("JSON into memory");
    let _ = turnpass::simulation::summary(program, lowered, &analysed.machine);
    if !clean {
        return;
    }
    // `expand` lowers without nose-radius compensation: the blocks it writes stay under the
    // program's own G41/G42, and the control applies it to both programs alike.
    let expanding = pipeline::Settings {
        lower: LowerOptions { nose_radius_compensation: false, ..lower_options },
        ..reading.clone()
    };
    let Ok(ready) = pipeline::analyse(&text, &expanding).ready() else { return };
    let cutting = ready.valid().moves.iter().filter(|m| m.cutting).count();
    let (edits, _) = turnpass::expand::expansion_edits(ready.program(), &ready.lowered);
    let expanded = printer::print(ready.program(), &edits);
    // `expand` refuses an output that does not read (a coordinate past what the control
    // takes): that is its check, not a finding.
    if !printer::unreadable(ready.program(), &expanded).is_empty() {
        return;
    }
    let shown = || format!("{}\n--- expanded:\n{}", String::from_utf8_lossy(&text), String::from_utf8_lossy(&expanded));
    // Read back as the original was read: with `--dialect auto`, the evidence of the
    // dialect may be in the blocks expansion replaced.
    let again_settings = pipeline::Settings { parse: printer::read_back_options(ready.program()), ..expanding };
    let again = pipeline::analyse(&expanded, &again_settings);
    assert!(!again.parsed.has_errors(), "the expanded program does not parse:\n{}", shown());
    let errors: Vec<_> = again.diagnostics.iter().filter(|d| d.is_error()).collect();
    assert!(errors.is_empty(), "the expanded program does not lower: {errors:?}\n{}", shown());
    let cutting_again = again.lowered().map_or(0, |l| l.toolpath.moves.iter().filter(|m| m.cutting).count());
    assert_eq!(cutting, cutting_again, "the expanded program cuts otherwise:\n{}", shown());
});
