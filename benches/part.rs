//! The part model's cost on `simulate` (issue 24): the generated program
//! (`python3 ../shared/bench/gen_lathe.py target/bench-data/big-<MB>.nc <MB>`, 50 MB unless
//! `TURNPASS_BENCH_PART_MB` says otherwise) on the bench lathe of
//! `benches/compensate-model.toml` (radius-programmed, as the generator writes; no tool table
//! and no `[stock]`, so the bar is assumed), simulated as `turnpass simulate` does it (parse,
//! lower, validate, summary, every row written as CSV, here to a sink) without the part model
//! and with it. Each run is a child process of this bench, so that its peak memory (VmHWM)
//! is its own; the variants are interleaved, `TURNPASS_BENCH_ROUNDS` rounds (3 unless given),
//! and the bench prints the medians of wall and CPU time, the peak memory, and the ratio.

#![allow(clippy::disallowed_methods, clippy::unwrap_used, clippy::expect_used)]

use std::process::Command;
use std::time::Instant;

use turnpass::dialect::{DialectChoice, GCodeSystem};
use turnpass::machine::ModelFile;
use turnpass::part::PartCheck;
use turnpass::pipeline::Settings;
use turnpass::semantic::LowerOptions;
use turnpass::syntax::ParseOptions;

mod support;

const CHILD: &str = "TURNPASS_BENCH_PART_CHILD";

fn main() {
    let megabytes = std::env::var("TURNPASS_BENCH_PART_MB").unwrap_or_else(|_| "50".to_string());
    if let Ok(variant) = std::env::var(CHILD) {
        child(&variant, &megabytes);
        return;
    }
    // Generated before any timing.
    support::generated(&megabytes);
    let rounds: usize = std::env::var("TURNPASS_BENCH_ROUNDS").ok().and_then(|r| r.parse().ok()).unwrap_or(3);
    let exe = std::env::current_exe().unwrap();
    let mut results: Vec<(&str, Vec<[f64; 3]>, String)> =
        vec![("without", Vec::new(), String::new()), ("with", Vec::new(), String::new())];
    for _ in 0..rounds {
        for (variant, runs, facts) in &mut results {
            let output =
                Command::new(&exe).env(CHILD, *variant).env("TURNPASS_BENCH_PART_MB", &megabytes).output().unwrap();
            assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
            let text = String::from_utf8_lossy(&output.stdout).into_owned();
            let value = |key: &str| -> f64 {
                text.split_whitespace().find_map(|w| w.strip_prefix(key)).and_then(|v| v.parse().ok()).unwrap()
            };
            runs.push([value("wall="), value("cpu="), value("peak_mb=")]);
            *facts = text.lines().filter(|l| !l.starts_with("wall=")).collect::<Vec<_>>().join("\n");
        }
    }
    let median = |runs: &[[f64; 3]], k: usize| support::median(&mut runs.iter().map(|r| r[k]).collect::<Vec<_>>());
    println!(
        "\nturnpass-bench: simulate, {megabytes} MB generated program, without and with the part model (median of {rounds})"
    );
    println!("{:<8} {:>10} {:>10} {:>12}", "", "wall s", "cpu s", "peak MB");
    for (variant, runs, _) in &results {
        println!("{variant:<8} {:>10.2} {:>10.2} {:>12.0}", median(runs, 0), median(runs, 1), median(runs, 2));
    }
    let (without, with) = (&results[0].1, &results[1].1);
    println!(
        "with ÷ without: wall {:.2}, cpu {:.2}",
        median(with, 0) / median(without, 0),
        median(with, 1) / median(without, 1)
    );
    println!("{}", results[1].2);
}

/// One run of one variant, printing `wall= cpu= peak_mb=` and what the part model found.
fn child(variant: &str, megabytes: &str) {
    let bytes = support::generated(megabytes);
    let model = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/benches/compensate-model.toml")).unwrap();
    let machine = ModelFile::from_toml(&model).unwrap().machine;
    let options = ParseOptions {
        dialect: machine.dialect.map_or(DialectChoice::Auto, DialectChoice::Fixed),
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    let mut settings = Settings::new(options, &machine, LowerOptions::new(false));
    if variant == "with" {
        settings = settings.with_part(PartCheck::default());
    }
    let (start, cpu) = (Instant::now(), cpu_seconds());
    let ready = support::ready(&bytes, &settings);
    let summary =
        turnpass::simulation::summary(ready.program(), &ready.lowered, &ready.machine).with_part(ready.part.as_ref());
    let rows = turnpass::simulation::rows(ready.program(), ready.valid());
    turnpass::simulation::write_csv(rows, std::io::sink()).unwrap();
    let (wall, cpu) = (start.elapsed().as_secs_f64(), cpu_seconds() - cpu);
    println!("wall={wall:.3} cpu={cpu:.3} peak_mb={:.0}", peak_kb() / 1024.0);
    println!("moves: {}", summary.moves);
    if let (Some(part), Some(run)) = (&summary.part, &ready.part) {
        let surface = run.part.as_ref().map_or(0, |p| p.surface().count());
        println!(
            "stock: Ø{:.1} × {:.1} mm (assumed: {}), rays {:.4} mm apart; surface points {surface}; air-cutting moves {}; \
             notes and warnings {}; stopped at move {:?}",
            part.stock_diameter_mm,
            part.stock_length_mm,
            part.stock_assumed,
            run.part.as_ref().map_or(0.0, |p| p.spacing()),
            part.air_moves,
            run.diagnostics.len(),
            part.stopped_at_move
        );
    }
}

/// CPU time of this process so far, s.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // utime and stime are fields 14 and 15, after the parenthesised command name.
    let fields: Vec<&str> = stat.rsplit(')').next().unwrap_or("").split_whitespace().collect();
    let ticks = |i: usize| fields.get(i).and_then(|f| f.parse::<f64>().ok()).unwrap_or(0.0);
    (ticks(11) + ticks(12)) / 100.0
}

/// Peak resident memory of this process, KiB.
fn peak_kb() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.split_whitespace().next())
        .and_then(|v| v.parse().ok())
        .unwrap_or(0.0)
}
