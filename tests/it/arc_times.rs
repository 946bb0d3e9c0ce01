//! Arcs timed on a second thread while the program runs (`parallel::Tuning::
//! arc_times_blocks`, on for long programs) give the toolpath the emitter gives
//! when it times them itself, to the bit: every simulate case, and generated programs of
//! arcs under constant surface speed, per minute and at a fixed speed, with and without a
//! spindle clamp, among roughing cycles whose profiles are run as scratch moves and dropped.

use std::fmt::Write as _;

use turnpass::machine::{MachineSettings, ModelFile};
use turnpass::parallel::Tuning;
use turnpass::semantic::{self, LowerOptions, Lowered, Machine};
use turnpass::syntax::parse;

use crate::simulate::{parse_options, settings_for};
use crate::support::check_spans;

/// Everything lowering gives, floats by their exact text (`{:?}` prints the shortest text
/// that reads back to the same bits).
fn lowered_text(lowered: &Lowered) -> String {
    format!("{:?}\n{:?}\n{:?}\n{:?}", lowered.toolpath, lowered.diagnostics, lowered.expansions, lowered.coordinates)
}

/// The program lowered with its arcs timed beside and by the emitter: the two must agree.
fn assert_same_both_ways(name: &str, source: &[u8], settings: &MachineSettings) {
    let parsed = parse(source, &parse_options(settings));
    check_spans(&parsed);
    let machine = Machine::from_settings(settings);
    let lower = |from_blocks| {
        let tuning = Tuning { arc_times_blocks: from_blocks, ..Tuning::DEFAULT };
        lowered_text(&semantic::lower_tuned(&parsed.program, &machine, &LowerOptions::new(false), &tuning))
    };
    let (beside, itself) = (lower(0), lower(usize::MAX));
    assert!(beside == itself, "{name}: arcs timed beside differ from arcs timed in place");
}

#[test]
fn every_simulate_case_lowers_the_same_with_arcs_timed_beside() {
    let root = crate::support::repo().join("tests/cases/simulate");
    let mut count = 0;
    let mut dirs = vec![root];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "nc") {
                let source = std::fs::read(&path).unwrap();
                assert_same_both_ways(&path.display().to_string(), &source, &settings_for(&path));
                count += 1;
            }
        }
    }
    assert!(count > 50, "only {count} simulate cases found");
}

/// A program of many arcs in every timing mode, with a roughing cycle between them whose
/// profile has arcs (run as scratch moves, then dropped) and blocks with no usable feed.
fn generated(seed: u64) -> String {
    let mut state = seed;
    let mut next = move |range: f64| {
        // A small linear congruential generator: the program only needs variety.
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64 * range
    };
    let mut out = String::from("%\nO0001\nG50 S2500\nG00 X200. Z200.\nT0101\nG96 S180 M03\nG99\n");
    for block in 0..400 {
        match block % 50 {
            10 => out.push_str("G98 F300.\n"),
            20 => out.push_str("G97 S1200\nG99 F0.2\n"),
            30 => out.push_str("G96 S0\n"),
            31 => out.push_str("G96 S150\nG50 S900\n"),
            40 => out.push_str(
                "G00 X62. Z2.\nG71 U1.5 R0.5\nG71 P10 Q20 U0.4 W0.1 F0.25\nN10 G00 X20.\nG01 Z0.\n\
                 G03 X30. Z-5. R5.\nG01 Z-15.\nG02 X40. Z-20. R5.\nN20 G01 X56.\nG70 P10 Q20\n",
            ),
            _ => {}
        }
        let (x, z) = (20.0 + next(60.0), -next(150.0));
        if block % 3 == 0 {
            let _ = writeln!(out, "G01 X{x:.3} Z{z:.3} F{:.3}", 0.05 + next(0.3));
        } else {
            let code = if block % 2 == 0 { "G02" } else { "G03" };
            let _ = writeln!(out, "{code} X{x:.3} Z{z:.3} R{:.3}", 80.0 + next(40.0));
        }
    }
    out.push_str("G00 X0.0000001 Z5.\nG03 X0. Z4. R0.5\nM30\n%\n");
    out
}

#[test]
fn generated_arcs_lower_the_same_with_arcs_timed_beside() {
    let text = std::fs::read_to_string(crate::support::repo().join("tests/cases/simulate/fanuc/machine.toml")).unwrap();
    let mut settings = ModelFile::from_toml(&text).unwrap().machine;
    for seed in 0..4 {
        let source = generated(seed);
        assert_same_both_ways(&format!("generated {seed}"), source.as_bytes(), &settings);
    }
    // Without a top spindle speed, under constant surface speed near the axis.
    settings.max_spindle_rpm = None;
    assert_same_both_ways("generated without a clamp", generated(7).as_bytes(), &settings);
}
