//! `turnpass compensate` end to end on generated programs: the release binary run as a
//! child process on a file, timed from spawn to exit, so the figure covers everything a
//! user waits for (read, parse, lower, sample, invert, fit, rewrite, print, write).
//!
//! Run with `cargo bench --bench compensate`. Inputs: `python3 ../shared/bench/gen_lathe.py
//! target/bench-data/big-<MB>.nc <MB>` (generated on first use; the bench says so and
//! measures nothing when python3 is missing), compensated for `benches/compensate-model.toml`
//! (backlash, tool offset, scale, squareness, warm-up). The main figure is the 50 MB program
//! (`TURNPASS_BENCH_MB` overrides it); 1, 2, 5 and 10 MB show how the time scales. Each size
//! is run `TURNPASS_BENCH_ROUNDS` times (default 3 for the largest, 5 for the others),
//! interleaved, and the bench prints the median wall time, MB/s, the median CPU time of the
//! child (both cores count) and seconds per MB, which is what the README quotes.
//!
//! A criterion group then times the library path in-process (parse, lower, compensate,
//! print) on the 1 MB program, for comparing builds. The README quotes both (50 MB: 1.78 s
//! wall, 3.02 s CPU; 1 MB in process: 39.1 ms).

#![allow(clippy::disallowed_methods, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;
use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use turnpass::compensation::fit::{FitOptions, Strategy};
use turnpass::compensation::{CompensateOptions, Judged, compensate_program};
use turnpass::dialect::{Dialect, DialectChoice, GCodeSystem, MachineKind};
use turnpass::error_model::model_file::ModelSpec;
use turnpass::machine::ModelFile;
use turnpass::pipeline::Settings;
use turnpass::printer::print;
use turnpass::semantic::LowerOptions;
use turnpass::syntax::ParseOptions;

mod support;

const SCALING_MB: [&str; 4] = ["1", "2", "5", "10"];

fn manifest() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn model_path() -> PathBuf {
    manifest().join("benches/compensate-model.toml")
}

/// The generated program of `megabytes`, or `None` when it cannot be generated.
fn generated(megabytes: &str) -> Option<PathBuf> {
    let dir = manifest().join("target/bench-data");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("big-{megabytes}.nc"));
    if !path.exists() {
        let script = manifest().join("../shared/bench/gen_lathe.py");
        match Command::new("python3").arg(&script).arg(&path).arg(megabytes).status() {
            Ok(status) if status.success() => {}
            Ok(status) => {
                println!("turnpass-bench: gen_lathe.py failed ({status}); nothing measured");
                return None;
            }
            Err(error) => {
                println!("turnpass-bench: python3 cannot run ({error}); nothing measured");
                return None;
            }
        }
    }
    Some(path)
}

/// CPU seconds used by finished children so far (user + system).
#[cfg(target_os = "linux")]
fn children_cpu() -> f64 {
    // SAFETY: getrusage writes the struct it is given and nothing else.
    let usage = unsafe {
        let mut usage: libc::rusage = std::mem::zeroed();
        libc::getrusage(libc::RUSAGE_CHILDREN, &mut usage);
        usage
    };
    let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    seconds(usage.ru_utime) + seconds(usage.ru_stime)
}

#[cfg(not(target_os = "linux"))]
fn children_cpu() -> f64 {
    f64::NAN
}

/// One run of `turnpass ARGS`: wall and CPU seconds.
fn run_once(args: &[&std::ffi::OsStr]) -> (f64, f64) {
    let cpu = children_cpu();
    let start = Instant::now();
    let result = Command::new(env!("CARGO_BIN_EXE_turnpass")).args(args).output().unwrap();
    let wall = start.elapsed().as_secs_f64();
    assert!(result.status.success(), "turnpass {args:?} failed: {}", String::from_utf8_lossy(&result.stderr));
    (wall, children_cpu() - cpu)
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn env_or(name: &str, default: &str) -> String {
    std::env::var(name).unwrap_or_else(|_| default.to_string())
}

fn end_to_end(c: &mut Criterion) {
    let big = env_or("TURNPASS_BENCH_MB", "50");
    let mut sizes: Vec<String> = SCALING_MB.iter().map(|s| s.to_string()).collect();
    if !sizes.contains(&big) {
        sizes.push(big.clone());
    }
    let mut inputs = Vec::new();
    for size in &sizes {
        let Some(path) = generated(size) else { return };
        inputs.push((size.clone(), path));
    }
    let output = manifest().join("target/bench-data/compensated.nc");
    let rounds = |size: &str| -> usize {
        let default = if *size == big { "3" } else { "5" };
        env_or("TURNPASS_BENCH_ROUNDS", default).parse().unwrap()
    };
    // Interleaved rounds: a busy moment of the machine spreads over every size. Each round
    // compensates, then verifies what it wrote, as the README recommends.
    type Times = [(Vec<f64>, Vec<f64>); 2];
    let mut times: Vec<Times> = vec![Default::default(); inputs.len()];
    let most = inputs.iter().map(|(size, _)| rounds(size)).max().unwrap_or(0);
    let model = model_path();
    for round in 0..most {
        for ((size, path), [compensate, verify]) in inputs.iter().zip(&mut times) {
            if round < rounds(size) {
                let (input, out, model) = (path.as_os_str(), output.as_os_str(), model.as_os_str());
                let (wall, cpu) =
                    run_once(&["compensate".as_ref(), input, "--model".as_ref(), model, "-o".as_ref(), out]);
                compensate.0.push(wall);
                compensate.1.push(cpu);
                let (wall, cpu) = run_once(&["verify".as_ref(), input, out, "--model".as_ref(), model]);
                verify.0.push(wall);
                verify.1.push(cpu);
            }
        }
    }
    println!("\nturnpass-bench: compensate, then verify of its output, {} (median of the rounds)", model.display());
    for ((size, path), [(compensate_walls, compensate_cpus), (verify_walls, verify_cpus)]) in inputs.iter().zip(times) {
        let mb = std::fs::metadata(path).unwrap().len() as f64 / 1e6;
        let n = compensate_walls.len();
        let (wall, cpu) = (median(compensate_walls), median(compensate_cpus));
        let (verify_wall, verify_cpu) = (median(verify_walls), median(verify_cpus));
        println!(
            "turnpass-bench: {size:>3} MB file ({mb:.1} MB): compensate {wall:.2} s wall, {:.1} MB/s, {cpu:.2} s CPU; \
             verify {verify_wall:.2} s wall ({:.2}x), {verify_cpu:.2} s CPU ({n} runs)",
            mb / wall,
            verify_wall / wall
        );
    }
    println!();
    std::fs::remove_file(&output).ok();

    // The library path in-process on the smallest program, for criterion.
    let Some((_, small)) = inputs.first() else { return };
    let bytes = std::fs::read(small).unwrap();
    let text = std::fs::read_to_string(model_path()).unwrap();
    let settings = ModelFile::from_toml(&text).unwrap().machine;
    let model = ModelSpec::from_toml(&text).unwrap().build(|_| Err("no tables".into())).unwrap();
    let parse_options = ParseOptions {
        dialect: DialectChoice::Fixed(Dialect::Fanuc),
        gcode_system: GCodeSystem::A,
        machine_kind: Some(MachineKind::Lathe),
        control: Default::default(),
    };
    let lower_options = LowerOptions { nose_radius_compensation: true, ..LowerOptions::new(false) };
    let settings = Settings::new(parse_options, &settings, lower_options);
    let machine = settings.machine.clone();
    let options = CompensateOptions {
        fit: FitOptions {
            strategy: Strategy::Auto,
            tolerance_mm: machine.increment * machine.scale() / 2.0,
            step_mm: None,
        },
        max_shift_mm: 0.1,
        expand_cycles: false,
        profiles_in_place: true,
        profiles_copied: true,
        threads_in_place: true,
        singles_in_place: true,
        others_as_written: false,
        thread_pieces_every_pass: false,
        paths: false,
        block_reports: false,
    };
    let mut group = c.benchmark_group("compensate");
    group.throughput(Throughput::Bytes(bytes.len() as u64));
    group.sample_size(10);
    group.bench_function("library_1mb", |b| {
        b.iter(|| {
            let program = support::ready(black_box(&bytes), &settings);
            let outcome = compensate_program(
                program.program(),
                &program.lowered,
                &program.machine,
                &model,
                &options,
                Judged::EveryFeed,
            );
            print(program.program(), &outcome.edits)
        })
    });
    group.finish();
}

criterion_group!(benches, end_to_end);
criterion_main!(benches);
