//! Front-end throughput on the 50 MB generated program, side by side with the `gcode` crate.
//!
//! Run with `cargo bench --bench parse`. The input comes from
//! `python3 ../shared/bench/gen_lathe.py target/bench-data/big.nc 50` (generated on first
//! use). Besides the criterion groups, the bench prints the AST memory per block and the
//! median throughput ratio, which is what the README quotes.

#![allow(clippy::disallowed_methods, clippy::unwrap_used, clippy::expect_used)]

mod support;

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use turnpass::dialect::{Dialect, DialectChoice, GCodeSystem, MachineKind};
use turnpass::printer::{Edits, print};
use turnpass::syntax::{ParseOptions, parse};

use support::{generated, median_seconds};

fn input() -> Vec<u8> {
    generated(&std::env::var("TURNPASS_BENCH_MB").unwrap_or_else(|_| "50".to_string()))
}

fn options() -> ParseOptions {
    ParseOptions {
        dialect: DialectChoice::Fixed(Dialect::Fanuc),
        gcode_system: GCodeSystem::A,
        machine_kind: Some(MachineKind::Lathe),
        control: Default::default(),
    }
}

fn front_end(c: &mut Criterion) {
    let bytes = input();
    let text = std::str::from_utf8(&bytes).expect("the generated program is ASCII");
    let options = options();

    // The figures the README quotes: medians of interleaved runs in this one process.
    let parsed = parse(&bytes, &options);
    assert_eq!(parsed.error_count(), 0, "the generated program parses cleanly");
    let blocks = parsed.program.blocks().len();
    let per_block = parsed.program.heap_bytes() as f64 / blocks as f64;
    let mb = bytes.len() as f64 / 1e6;
    assert!(per_block <= 150.0, "the AST budget is 150 bytes per block; it is {per_block:.1}");
    let ours = median_seconds(|| drop(black_box(parse(black_box(&bytes), &options))), 7);
    let scan = median_seconds(|| drop(black_box(turnpass::dialect::detect::scan(black_box(&bytes)))), 7);
    let printing = median_seconds(|| drop(black_box(print(&parsed.program, &Edits::new()))), 7);
    let peer = median_seconds(|| drop(black_box(gcode::parse(black_box(text)))), 7);
    println!(
        "\nturnpass-bench: {mb:.1} MB, {blocks} blocks, AST {per_block:.1} bytes/block\n\
         turnpass-bench: turnpass parse {:.0} MB/s, lossless print {:.0} MB/s, gcode 0.7 parse {:.0} MB/s, parse ratio {:.2}x\n\
         turnpass-bench: dialect auto-detection scan {:.0} MB/s (runs before parsing when the dialect is not given)\n",
        mb / ours,
        mb / printing,
        mb / peer,
        peer / ours,
        mb / scan
    );
    drop(parsed);

    let mut group = c.benchmark_group("front_end");
    group.throughput(Throughput::Bytes(bytes.len() as u64));
    group.sample_size(10);
    group.bench_function("turnpass_parse", |b| b.iter(|| parse(black_box(&bytes), &options)));
    let parsed = parse(&bytes, &options);
    group.bench_function("turnpass_print_lossless", |b| b.iter(|| print(black_box(&parsed.program), &Edits::new())));
    group.bench_function("gcode_0_7_parse", |b| b.iter(|| gcode::parse(black_box(text))));
    group.finish();
}

criterion_group!(benches, front_end);
criterion_main!(benches);
