//! Semantic-pass throughput: lowering a large generated program (blocks per second) and
//! expanding canned cycles (moves per second), with LinuxCNC's `rs274` on the same cycle
//! load in the same run when it is installed.
//!
//! Run with `cargo bench --bench lower`. Inputs:
//! * lowering: `python3 ../shared/bench/gen_lathe.py target/bench-data/big-10.nc 10`
//!   (straight lines and arcs written in radius, so the bench machine is radius-programmed);
//! * expansion: 2,000 × (`G71` two-block form + `G70`) on one ten-element profile, written
//!   here in the Fanuc form for turnpass and in LinuxCNC's form (`G71 Q<sub> D`, `G70 Q`)
//!   for rs274. rs274 runs as a child process (`rs274 -g`), timed from spawn to exit, its
//!   moves counted from the canonical calls it prints. The two controls' G71 pass rules
//!   differ (see `tests/it/differential.rs`), so the move counts differ: the figure compared
//!   is moves per second.
//!
//! Besides the criterion groups, the bench prints medians of interleaved runs, which is
//! what the README quotes: lowering with its arcs timed on a second thread (the default for
//! a program this long) and in place, and the cycle expansion beside rs274.

#![allow(clippy::disallowed_methods, clippy::unwrap_used, clippy::expect_used)]

mod support;

use std::fmt::Write as _;
use std::hint::black_box;
use std::process::Command;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use turnpass::dialect::{Dialect, DialectChoice, GCodeSystem, MachineKind};
use turnpass::machine::MachineSettings;
use turnpass::parallel::Tuning;
use turnpass::semantic::{LowerOptions, Machine, lower, lower_tuned};
use turnpass::syntax::{ParseOptions, parse};

use support::{data_dir, generated, median, median_seconds};

const CYCLES: usize = 2000;

/// The profile both forms cut: a face, a chamfer, steps, a taper, a fillet and a shoulder.
const PROFILE: [&str; 10] = [
    "G00 X20.",
    "G01 Z0.",
    "X24. Z-2.",
    "Z-15.",
    "X30.",
    "X36. Z-25.",
    "Z-35.",
    "G02 X46. Z-40. R5.",
    "G01 X56.",
    "Z-50.",
];

fn fanuc_cycles() -> String {
    let mut out = String::from("%\nO0001\nG21 G99\nG97 S1000 M03\n");
    for i in 0..CYCLES {
        out.push_str("G00 X62. Z2.\nG71 U1.5 R0.5\nG71 P10 Q20 U0.4 W0.1 F0.25\n");
        if i == 0 {
            let last = PROFILE.len() - 1;
            for (k, block) in PROFILE.iter().enumerate() {
                let label = if k == 0 {
                    "N10 "
                } else if k == last {
                    "N20 "
                } else {
                    ""
                };
                let _ = writeln!(out, "{label}{block}");
            }
        }
        out.push_str("G70 P10 Q20\n");
    }
    out.push_str("G00 X200. Z100.\nM30\n%\n");
    out
}

fn linuxcnc_cycles() -> String {
    let mut out = String::from("o100 sub\n");
    for block in PROFILE {
        let _ = writeln!(out, "{block}");
    }
    out.push_str("o100 endsub\nG18 G7 G21 G90 G95\nS1000 M3\nF0.25\n");
    for _ in 0..CYCLES {
        out.push_str("G0 X62 Z2\nG71 Q100 D1.5\nG70 Q100\n");
    }
    out.push_str("G0 X200 Z100\nM2\n");
    out
}

/// rs274's moves per second on the LinuxCNC form, or `None` when it is not installed.
fn rs274(rounds: usize) -> Option<(usize, f64)> {
    let path = data_dir().join("cycles.ngc");
    std::fs::write(&path, linuxcnc_cycles()).unwrap();
    let run = || Command::new("rs274").arg("-g").arg(&path).output().ok();
    let output = run()?;
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(!text.contains("rror"), "rs274 rejected the cycle program:\n{}", &text[..text.len().min(2000)]);
    let moves = text
        .lines()
        .filter(|l| l.contains("STRAIGHT_TRAVERSE") || l.contains("STRAIGHT_FEED") || l.contains("ARC_FEED"))
        .count();
    let seconds = median_seconds(|| drop(black_box(run())), rounds);
    Some((moves, seconds))
}

fn semantic(c: &mut Criterion) {
    let fanuc = ParseOptions {
        dialect: DialectChoice::Fixed(Dialect::Fanuc),
        gcode_system: GCodeSystem::A,
        machine_kind: Some(MachineKind::Lathe),
        control: Default::default(),
    };
    let options = LowerOptions::new(false);

    // Lowering: the generated program is in radius, on a radius-programmed machine.
    let big = generated(&std::env::var("TURNPASS_BENCH_MB").unwrap_or_else(|_| "10".to_string()));
    let parsed = parse(&big, &fanuc);
    assert_eq!(parsed.error_count(), 0);
    let radius_machine = Machine::from_settings(&MachineSettings {
        diameter_programming: Some(false),
        home: Some(turnpass::machine::AxisPair { x: 200.0, z: 200.0 }),
        ..MachineSettings::default()
    });
    let lowered = lower(&parsed.program, &radius_machine, &options);
    assert!(!lowered.diagnostics.iter().any(|d| d.is_error()), "the generated program lowers cleanly");
    let blocks = parsed.program.blocks().len();
    // Arcs timed on a second thread (`parallel::Tuning::arc_times_blocks`, on for this
    // program) against timed in place, in alternate runs.
    let in_place = Tuning { arc_times_blocks: usize::MAX, ..Tuning::DEFAULT };
    let (mut beside, mut itself) = (Vec::new(), Vec::new());
    for _ in 0..7 {
        beside.push(median_seconds(|| drop(black_box(lower(&parsed.program, &radius_machine, &options))), 1));
        let tuned = || drop(black_box(lower_tuned(&parsed.program, &radius_machine, &options, &in_place)));
        itself.push(median_seconds(tuned, 1));
    }
    let (lowering, in_place) = (median(&mut beside), median(&mut itself));

    // Expansion: 2,000 × G71 + G70.
    let cycles_text = fanuc_cycles();
    let cycles = parse(cycles_text.as_bytes(), &fanuc);
    assert_eq!(cycles.error_count(), 0);
    let machine = Machine::from_settings(&MachineSettings {
        home: Some(turnpass::machine::AxisPair { x: 200.0, z: 100.0 }),
        ..MachineSettings::default()
    });
    let expanded = lower(&cycles.program, &machine, &options);
    assert!(!expanded.diagnostics.iter().any(|d| d.is_error()), "{:?}", expanded.diagnostics.first());
    let moves = expanded.toolpath.moves.len();
    assert_eq!(expanded.expansions.len(), 2 * CYCLES, "every G71 and G70 expands");
    let expansion = median_seconds(|| drop(black_box(lower(&cycles.program, &machine, &options))), 9);
    let peer = rs274(5);

    println!(
        "\nturnpass-bench: lowering {blocks} blocks in {:.1} ms: {:.2} M blocks/s ({} moves)",
        lowering * 1e3,
        blocks as f64 / lowering / 1e6,
        lowered.toolpath.moves.len()
    );
    println!(
        "turnpass-bench: the same with arcs timed in place (one thread): {:.1} ms: {:.2} M blocks/s",
        in_place * 1e3,
        blocks as f64 / in_place / 1e6
    );
    println!(
        "turnpass-bench: {CYCLES} x G71+G70: turnpass {moves} moves in {:.1} ms: {:.2} M moves/s",
        expansion * 1e3,
        moves as f64 / expansion / 1e6
    );
    match peer {
        Some((peer_moves, seconds)) => println!(
            "turnpass-bench: {CYCLES} x G71+G70: rs274 {peer_moves} moves in {:.1} ms: {:.2} M moves/s; turnpass/rs274 {:.1}x\n",
            seconds * 1e3,
            peer_moves as f64 / seconds / 1e6,
            (moves as f64 / expansion) / (peer_moves as f64 / seconds)
        ),
        None => println!("turnpass-bench: rs274 is not installed (Debian: linuxcnc-uspace); no peer figure\n"),
    }
    drop(lowered);
    drop(expanded);

    let mut group = c.benchmark_group("semantic");
    group.sample_size(10);
    group.throughput(Throughput::Elements(blocks as u64));
    group.bench_function("lower_generated_blocks", |b| b.iter(|| lower(&parsed.program, &radius_machine, &options)));
    group.throughput(Throughput::Elements(moves as u64));
    group.bench_function("expand_2000_g71_g70_moves", |b| b.iter(|| lower(&cycles.program, &machine, &options)));
    group.finish();
}

criterion_group!(benches, semantic);
criterion_main!(benches);
