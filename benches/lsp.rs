//! Language-server latency: re-analysis after a one-character edit, and the full analysis
//! of a program when it is opened, with tree-sitter-gcode's incremental re-parse of the
//! same edit beside it.
//!
//! Run with `cargo bench --bench lsp`. Inputs: `python3 ../shared/bench/gen_lathe.py
//! target/bench-data/big-<n>.nc <n>` for 1, 8 and 50 MB (generated on first use; the report's
//! sizes are `TURNPASS_BENCH_LSP_MB`, default `1,8,50`). Measured:
//!
//! * **edit**: one character typed into a number in the middle of the program (and, in the
//!   next round, deleted again), then everything the server publishes for it: the
//!   incremental re-parse (`Document::replace`), the document's diagnostics and their
//!   protocol form (`analysis::publishable`). Also at the start of the program, where the text
//!   after the edit is longest, and in the middle while a snapshot of the document is held
//!   (as the semantic pass's job on a worker thread holds one).
//! * **open**: a program opened from scratch: parse into chunks, diagnostics, the semantic
//!   pass (`SemanticJob::run`, which assembles the chunks into one program and lowers it),
//!   and the protocol form of all the diagnostics; each part is also timed alone.
//! * **tree-sitter-gcode**: `Tree::edit` and `Parser::parse` with the old tree, for the same
//!   one-byte insertion (tree-sitter 0.25, tree-sitter-gcode 0.1.1 from crates.io).
//!
//! Besides the criterion groups, the bench prints medians of interleaved runs, which is
//! what the README quotes.

#![allow(clippy::disallowed_methods, clippy::unwrap_used, clippy::expect_used)]

mod support;

use std::hint::black_box;
use std::time::Instant;

use criterion::{Criterion, criterion_group, criterion_main};
use lsp_types::Uri;
use turnpass::dialect::{DialectChoice, GCodeSystem};
use turnpass::lsp::Document;
use turnpass::lsp::analysis::{self, SemanticJob};
use turnpass::machine::MachineSettings;
use turnpass::syntax::ParseOptions;

use support::{generated, median, median_seconds};

/// As an editor opens a program with no settings: the dialect decided from the text.
fn options() -> ParseOptions {
    ParseOptions { dialect: DialectChoice::Auto, gcode_system: GCodeSystem::A, machine_kind: None }
}

fn uri() -> Uri {
    "file:///bench/big.nc".parse().unwrap()
}

/// What the server publishes for a document's parse: its diagnostics in protocol form.
fn publish(document: &Document, uri: &Uri) -> Vec<lsp_types::Diagnostic> {
    analysis::publishable(document, uri, &[])
}

/// Everything the server does for a program it opens.
fn open(text: &[u8], uri: &Uri) -> usize {
    let document = Document::new(text.to_vec(), options());
    let semantic = SemanticJob::new(document.snapshot(), &MachineSettings::default()).run();
    analysis::publishable(&document, uri, &semantic).len()
}

/// The offset just after the first digit of a number at or after `from`: where a
/// machinist types another digit.
fn digit_after(text: &[u8], from: usize) -> usize {
    from + text[from..].windows(2).position(|w| w[0] == b'X' && w[1].is_ascii_digit()).unwrap() + 2
}

/// One typed character, then its deletion, alternately; returns seconds per edit.
fn median_edit_seconds(document: &mut Document, at: usize, uri: &Uri, rounds: usize) -> f64 {
    let mut times: Vec<f64> = (0..rounds)
        .map(|round| {
            let start = Instant::now();
            if round % 2 == 0 {
                document.replace(at..at, b"5");
            } else {
                document.replace(at..at + 1, b"");
            }
            black_box(publish(document, uri));
            start.elapsed().as_secs_f64()
        })
        .collect();
    median(&mut times)
}

/// tree-sitter-gcode: the whole parse, and the re-parse after inserting one byte at `at`.
struct TreeSitter {
    parser: tree_sitter::Parser,
    tree: tree_sitter::Tree,
    edited: Vec<u8>,
    edit: tree_sitter::InputEdit,
}

impl TreeSitter {
    fn new(text: &[u8], at: usize) -> TreeSitter {
        let mut parser = tree_sitter::Parser::new();
        parser.set_language(&tree_sitter_gcode::LANGUAGE.into()).unwrap();
        let tree = parser.parse(text, None).unwrap();
        let mut edited = text.to_vec();
        edited.insert(at, b'5');
        let row = text[..at].iter().filter(|&&b| b == b'\n').count();
        let column = at - text[..at].iter().rposition(|&b| b == b'\n').map_or(0, |p| p + 1);
        let point = tree_sitter::Point { row, column };
        let edit = tree_sitter::InputEdit {
            start_byte: at,
            old_end_byte: at,
            new_end_byte: at + 1,
            start_position: point,
            old_end_position: point,
            new_end_position: tree_sitter::Point { row, column: column + 1 },
        };
        TreeSitter { parser, tree, edited, edit }
    }

    fn reparse_after_edit(&mut self) -> tree_sitter::Tree {
        let mut old = self.tree.clone();
        old.edit(&self.edit);
        self.parser.parse(&self.edited, Some(&old)).unwrap()
    }
}

fn lsp(c: &mut Criterion) {
    let uri = uri();
    // The sizes of the report; the criterion groups use the 1 and 8 MB programs.
    let sizes = std::env::var("TURNPASS_BENCH_LSP_MB").unwrap_or_else(|_| "1,8,50".to_string());
    let small = generated("1");
    let large = generated("8");

    // The figures the README quotes: medians of runs in this one process.
    let mut report = String::new();
    for megabytes in sizes.split(',') {
        let text = generated(megabytes.trim());
        let mb = text.len() as f64 / 1e6;
        // Opening a program grows with its size: fewer rounds for the large ones.
        let open_rounds = if mb < 10.0 { 7 } else { 3 };
        let mut document = Document::new(text.to_vec(), options());
        let middle = digit_after(&text, text.len() / 2);
        let first = digit_after(&text, 0);
        let edit_middle = median_edit_seconds(&mut document, middle, &uri, 201);
        let edit_start = median_edit_seconds(&mut document, first, &uri, 201);
        // As on a large program whose semantic pass runs on a worker thread: the job holds a
        // snapshot of the document while the machinist goes on typing.
        let held = document.snapshot();
        let edit_held = median_edit_seconds(&mut document, middle, &uri, 201);
        drop(held);
        let opened = median_seconds(|| _ = black_box(open(&text, &uri)), open_rounds);
        let parse_only = median_seconds(|| drop(black_box(Document::new(text.to_vec(), options()))), open_rounds);
        let job = SemanticJob::new(document.snapshot(), &MachineSettings::default());
        let semantic_diagnostics = job.run();
        let semantic = median_seconds(|| drop(black_box(job.run())), open_rounds);
        let publish = median_seconds(
            || drop(black_box(analysis::publishable(&document, &uri, &semantic_diagnostics))),
            open_rounds,
        );
        report.push_str(&format!(
            "turnpass-bench: {mb:.2} MB, {} chunks, {} parse and {} semantic diagnostics: one-character edit + \
             publish {:.3} ms (middle), {:.3} ms (start), {:.3} ms (middle, snapshot held); open {:.1} ms (parse \
             into chunks {:.1} ms, semantic pass {:.1} ms, publish {:.1} ms)\n",
            document.chunk_count(),
            document.diagnostics().len(),
            semantic_diagnostics.len(),
            edit_middle * 1e3,
            edit_start * 1e3,
            edit_held * 1e3,
            opened * 1e3,
            parse_only * 1e3,
            semantic * 1e3,
            publish * 1e3,
        ));
    }
    let middle = digit_after(&large, large.len() / 2);
    let mut peer = TreeSitter::new(&large, middle);
    let peer_edit = median_seconds(|| drop(black_box(peer.reparse_after_edit())), 7);
    let peer_full = median_seconds(
        || {
            let mut parser = tree_sitter::Parser::new();
            parser.set_language(&tree_sitter_gcode::LANGUAGE.into()).unwrap();
            drop(black_box(parser.parse(&large, None)));
        },
        3,
    );
    report.push_str(&format!(
        "turnpass-bench: tree-sitter-gcode on {:.2} MB: one-byte edit re-parse {:.1} ms, full parse {:.1} ms, \
         tree has errors: {}\n",
        large.len() as f64 / 1e6,
        peer_edit * 1e3,
        peer_full * 1e3,
        peer.tree.root_node().has_error()
    ));
    println!("\n{report}");

    let mut group = c.benchmark_group("lsp");
    group.sample_size(20);
    for (name, text) in [("1MB", &small), ("8MB", &large)] {
        let mut document = Document::new(text.to_vec(), options());
        let at = digit_after(text, text.len() / 2);
        let mut typed = false;
        group.bench_function(format!("edit_and_publish_{name}"), |b| {
            b.iter(|| {
                if typed {
                    document.replace(at..at + 1, b"");
                } else {
                    document.replace(at..at, b"5");
                }
                typed = !typed;
                black_box(publish(&document, &uri))
            })
        });
    }
    group.bench_function("open_with_semantic_1MB", |b| b.iter(|| open(black_box(&small), &uri)));
    group.sample_size(10);
    group.bench_function("tree_sitter_gcode_edit_8MB", |b| b.iter(|| peer.reparse_after_edit()));
    group.finish();
}

criterion_group!(benches, lsp);
criterion_main!(benches);
