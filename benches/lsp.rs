//! Language-server latency: re-analysis after a one-character edit, and the full analysis
//! of a program when it is opened, with tree-sitter-gcode's incremental re-parse of the
//! same edit beside it.
//!
//! Run with `cargo bench --bench lsp`. Inputs: `python3 ../shared/bench/gen_lathe.py
//! target/bench-data/big-<n>.nc <n>`, generated on first use; the report's sizes are
//! `TURNPASS_BENCH_LSP_MB`, default `0.24,1,8,50` (0.24 MB is just under the size up to
//! which the semantic pass runs in the keystroke's own publish). The generator writes X as
//! a radius and turnpass reads it as a diameter, so most arcs are reported as not reaching
//! (one semantic diagnostic every 450 bytes): a program with very many diagnostics, the
//! hard case for a server that must send a document's whole list after every keystroke.
//!
//! Everything is measured through the server itself (`turnpass::lsp::server::Server`, in
//! process, with no settings files), up to the JSON text of the messages it would write:
//!
//! * **keystroke**: `textDocument/didChange` typing one digit into a number in the middle of
//!   the program (and, in the next round, deleting it), then the server's idle moment: the
//!   publishes per keystroke are counted (the worker's included), and for a keystroke that
//!   changes no value (a `0` after a number's last decimal), which must cost one; the
//!   incremental re-parse, the semantic pass when the program is small enough to run it
//!   inline, and the `publishDiagnostics` notification serialised. Also at the start of the
//!   program, where the text after the edit is longest. For a larger program the semantic
//!   pass is a job for a worker thread; the bench runs it after the timed part, as the
//!   worker would, so that the next keystroke carries its diagnostics moved across the edit.
//! * **open**: `textDocument/didOpen` of the whole program until the first publish (the
//!   parse's diagnostics), and until the last (the semantic pass's too), serialised.
//! * the parts of an open alone: the parse into chunks (`Document::new`) and the semantic
//!   pass (`SemanticJob::run`, which joins the chunks into one program and lowers it).
//! * **tree-sitter-gcode**: `Tree::edit` and `Parser::parse` with the old tree, for a
//!   one-byte insertion into the 8 MB program (tree-sitter 0.25, tree-sitter-gcode 0.1.1
//!   from crates.io), and its full parse.
//!
//! Besides the criterion groups, the bench prints medians of runs in this one process,
//! which is what the README quotes.

#![allow(clippy::disallowed_methods, clippy::unwrap_used, clippy::expect_used)]

mod support;

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use lsp_server::{Message, Notification};
use serde_json::json;
use turnpass::dialect::{DialectChoice, GCodeSystem};
use turnpass::lsp::Document;
use turnpass::lsp::analysis::SemanticJob;
use turnpass::lsp::server::{Host, Server};
use turnpass::machine::MachineSettings;
use turnpass::syntax::ParseOptions;

use support::{generated, median, median_seconds};

const URI: &str = "file:///bench/big.nc";

/// An editor's session with no settings files: the dialect is decided from the text.
struct NoFiles;

impl Host for NoFiles {
    fn model_file(&self, _: Option<&Path>, _: Option<&Path>) -> Option<(PathBuf, Result<String, String>)> {
        None
    }
}

fn options() -> ParseOptions {
    ParseOptions {
        dialect: DialectChoice::Auto,
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    }
}

fn notification(method: &str, params: serde_json::Value) -> Message {
    Message::Notification(Notification::new(method.to_string(), params))
}

/// The JSON text the server would write for `messages`; returns its length.
fn serialised(messages: &[Message]) -> usize {
    messages.iter().map(|m| serde_json::to_vec(m).unwrap().len()).sum()
}

/// A server with the program open and its semantic diagnostics published.
fn opened(text: &str) -> Server<NoFiles> {
    opened_with(text, json!({ "capabilities": {} }))
}

/// `opened` for a server initialised with `initialize`.
fn opened_with(text: &str, initialize: serde_json::Value) -> Server<NoFiles> {
    let (mut server, _, _) = Server::initialize(NoFiles, initialize);
    let item = json!({ "uri": URI, "languageId": "gcode", "version": 1, "text": text });
    server.handle(notification("textDocument/didOpen", json!({ "textDocument": item })));
    let (_, jobs) = server.idle();
    for job in jobs {
        server.finished(job.run());
    }
    server
}

/// The initialisation of a server for the generated programs read as they are written: X
/// as a radius (`diameter_programming = false`). Then the semantic pass finds nothing
/// wrong, as in a program a machinist has open; the default (diameter) reading is the
/// stress case with a semantic diagnostic every 450 bytes.
fn radius_machine() -> serde_json::Value {
    json!({ "capabilities": {}, "initializationOptions": { "machine": { "diameter_programming": false } } })
}

/// didOpen until the first publish and until the last, in seconds, and the bytes written.
fn open(text: &str) -> (f64, f64, usize) {
    open_with(text, json!({ "capabilities": {} }))
}

/// `open` for a server initialised with `initialize`.
fn open_with(text: &str, initialize: serde_json::Value) -> (f64, f64, usize) {
    let start = Instant::now();
    let (mut server, _, _) = Server::initialize(NoFiles, initialize);
    let item = json!({ "uri": URI, "languageId": "gcode", "version": 1, "text": text });
    server.handle(notification("textDocument/didOpen", json!({ "textDocument": item })));
    let (messages, jobs) = server.idle();
    let mut bytes = serialised(&messages);
    let first = start.elapsed().as_secs_f64();
    for job in jobs {
        bytes += serialised(&server.finished(job.run()));
    }
    (first, start.elapsed().as_secs_f64(), bytes)
}

/// Where a machinist types a digit: just after the first digit of an `X` word on or after
/// line `from`; the protocol position (line, UTF-16 column; the program is ASCII).
fn digit_after(text: &str, from: usize) -> (usize, usize) {
    text.lines()
        .enumerate()
        .skip(from)
        .find_map(|(line, content)| {
            let column = content.as_bytes().windows(2).position(|w| w[0] == b'X' && w[1].is_ascii_digit())?;
            Some((line, column + 2))
        })
        .unwrap()
}

/// One keystroke: a digit typed at `at` in even rounds, deleted again in odd ones, and the
/// server's idle moment. Returns the messages it would write, and the semantic jobs it
/// hands to a worker thread.
fn keystroke(
    server: &mut Server<NoFiles>,
    round: usize,
    at: (usize, usize),
) -> (Vec<Message>, Vec<turnpass::lsp::server::Job>) {
    typed(server, round, at, "5")
}

/// `keystroke` typing `digit`.
fn typed(
    server: &mut Server<NoFiles>,
    round: usize,
    at: (usize, usize),
    digit: &str,
) -> (Vec<Message>, Vec<turnpass::lsp::server::Job>) {
    let (line, column) = at;
    let (end, text) = if round.is_multiple_of(2) { (column, digit) } else { (column + 1, "") };
    let range = json!({ "start": { "line": line, "character": column }, "end": { "line": line, "character": end } });
    let params = json!({
        "textDocument": { "uri": URI, "version": round + 2 },
        "contentChanges": [{ "range": range, "text": text }],
    });
    server.handle(notification("textDocument/didChange", params));
    let (mut messages, jobs) = server.idle();
    let mut background = Vec::new();
    for job in jobs {
        if job.inline {
            messages.extend(server.finished(job.run()));
        } else {
            background.push(job);
        }
    }
    (messages, background)
}

/// Where typing a `0` changes no value: after the last digit of an `X` word with a decimal
/// fraction on or after line `from` (`X12.5` becomes `X12.50`).
fn trailing_zero_after(text: &str, from: usize) -> (usize, usize) {
    text.lines()
        .enumerate()
        .skip(from)
        .find_map(|(line, content)| {
            let bytes = content.as_bytes();
            let x = bytes.iter().position(|&b| b == b'X')?;
            let number = bytes[x + 1..].iter().take_while(|b| b.is_ascii_digit() || matches!(b, b'.' | b'-')).count();
            let word = &bytes[x + 1..x + 1 + number];
            let point = word.iter().position(|&b| b == b'.')?;
            (point + 1 < word.len()).then_some((line, x + 1 + number))
        })
        .unwrap()
}

/// The publishes per keystroke of `rounds` keystrokes typing a `0` that changes no value
/// at `at` (and deleting it), the worker's included.
fn noop_publishes(server: &mut Server<NoFiles>, at: (usize, usize), rounds: usize) -> f64 {
    let mut published = 0;
    for round in 0..rounds {
        let (messages, background) = typed(server, round, at, "0");
        published += publishes(&messages);
        for job in background {
            published += publishes(&server.finished(job.run()));
        }
    }
    published as f64 / rounds as f64
}

/// How many `publishDiagnostics` notifications `messages` hold.
fn publishes(messages: &[Message]) -> usize {
    messages
        .iter()
        .filter(|m| matches!(m, Message::Notification(n) if n.method == "textDocument/publishDiagnostics"))
        .count()
}

/// The median seconds of `rounds` keystrokes at `at`, up to the serialised publish, the
/// bytes of the last one, and the publishes per keystroke (the worker's included).
fn median_keystroke_seconds(server: &mut Server<NoFiles>, at: (usize, usize), rounds: usize) -> (f64, usize, f64) {
    let mut bytes = 0;
    let mut published = 0;
    let mut times: Vec<f64> = (0..rounds)
        .map(|round| {
            let start = Instant::now();
            let (messages, background) = keystroke(server, round, at);
            bytes = serialised(&messages);
            let elapsed = start.elapsed().as_secs_f64();
            published += publishes(&messages);
            // The worker thread's part, not the keystroke's.
            for job in background {
                published += publishes(&server.finished(job.run()));
            }
            elapsed
        })
        .collect();
    (median(&mut times), bytes, published as f64 / rounds as f64)
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

/// The byte offset of a protocol position in ASCII text.
fn byte_offset(text: &str, (line, column): (usize, usize)) -> usize {
    text.split_inclusive('\n').take(line).map(str::len).sum::<usize>() + column
}

fn lsp(c: &mut Criterion) {
    let sizes = std::env::var("TURNPASS_BENCH_LSP_MB").unwrap_or_else(|_| "0.24,1,8,50".to_string());

    // The figures the README quotes: medians of runs in this one process.
    let mut report = String::new();
    for megabytes in sizes.split(',') {
        let bytes = generated(megabytes.trim());
        let text = String::from_utf8(bytes).expect("the generated program is ASCII");
        let mb = text.len() as f64 / 1e6;
        let lines = text.lines().count();
        let rounds = if mb < 10.0 { 7 } else { 3 };

        let mut server = opened(&text);
        let (middle, middle_bytes, middle_publishes) =
            median_keystroke_seconds(&mut server, digit_after(&text, lines / 2), 101);
        let (start, _, _) = median_keystroke_seconds(&mut server, digit_after(&text, 0), 101);
        drop(server);
        // A `0` typed after a number's last decimal changes no value, so no diagnostic: it
        // must be published once, not twice (the worker's identical result is not sent). On
        // a server of its own: the keystrokes above leave a digit typed in the middle.
        let mut fresh = opened(&text);
        let noop = noop_publishes(&mut fresh, trailing_zero_after(&text, lines / 2), 21);
        drop(fresh);

        let mut opens: Vec<(f64, f64, usize)> = (0..rounds).map(|_| open(&text)).collect();
        let open_bytes = opens[0].2;
        let first_publish = median(&mut opens.iter().map(|o| o.0).collect::<Vec<_>>());
        let last_publish = median(&mut opens.iter_mut().map(|o| o.1).collect::<Vec<_>>());
        let mut clean: Vec<(f64, f64, usize)> = (0..rounds).map(|_| open_with(&text, radius_machine())).collect();
        let clean_last = median(&mut clean.iter_mut().map(|o| o.1).collect::<Vec<_>>());
        let document = Document::new(text.as_bytes().to_vec(), options());
        let parse = median_seconds(|| drop(black_box(Document::new(text.as_bytes().to_vec(), options()))), rounds);
        let job = SemanticJob::new(document.snapshot(), &MachineSettings::default(), None);
        let semantic_count = job.run().len();
        let radius = MachineSettings { diameter_programming: Some(false), ..MachineSettings::default() };
        let clean_count = SemanticJob::new(document.snapshot(), &radius, None).run().len();
        let semantic = median_seconds(|| drop(black_box(job.run())), rounds);
        report.push_str(&format!(
            "turnpass-bench: {mb:.2} MB, {} chunks, {} parse and {semantic_count} semantic diagnostics: keystroke \
             {:.3} ms (middle), {:.3} ms (start), publish {} bytes, {middle_publishes:.2} publishes per keystroke \
             ({noop:.2} per no-op keystroke); open: first publish {:.1} ms, last {:.1} ms \
             ({open_bytes} bytes); open read with X as a radius ({clean_count} semantic diagnostics): last \
             publish {:.1} ms; parse into chunks {:.1} ms, semantic pass {:.1} ms\n",
            document.chunk_count(),
            document.diagnostics().len(),
            middle * 1e3,
            start * 1e3,
            middle_bytes,
            first_publish * 1e3,
            last_publish * 1e3,
            clean_last * 1e3,
            parse * 1e3,
            semantic * 1e3,
        ));
    }

    let small = String::from_utf8(generated("1")).unwrap();
    let large = String::from_utf8(generated("8")).unwrap();
    let middle = byte_offset(&large, digit_after(&large, large.lines().count() / 2));
    let mut peer = TreeSitter::new(large.as_bytes(), middle);
    let peer_edit = median_seconds(|| drop(black_box(peer.reparse_after_edit())), 7);
    let peer_full = median_seconds(
        || {
            let mut parser = tree_sitter::Parser::new();
            parser.set_language(&tree_sitter_gcode::LANGUAGE.into()).unwrap();
            drop(black_box(parser.parse(large.as_bytes(), None)));
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
        let mut server = opened(text);
        let at = digit_after(text, text.lines().count() / 2);
        let mut round = 0;
        group.bench_function(format!("keystroke_{name}"), |b| {
            // Timed up to the serialised publish; the worker thread's semantic pass is not.
            b.iter_custom(|iterations| {
                let mut total = Duration::ZERO;
                for _ in 0..iterations {
                    let start = Instant::now();
                    let (messages, background) = keystroke(&mut server, round, at);
                    black_box(serialised(&messages));
                    total += start.elapsed();
                    round += 1;
                    for job in background {
                        server.finished(job.run());
                    }
                }
                total
            })
        });
    }
    group.bench_function("open_1MB", |b| b.iter(|| open(black_box(&small))));
    group.bench_function("open_1MB_x_as_radius", |b| b.iter(|| open_with(black_box(&small), radius_machine())));
    group.sample_size(10);
    group.bench_function("tree_sitter_gcode_edit_8MB", |b| b.iter(|| peer.reparse_after_edit()));
    group.finish();
}

criterion_group!(benches, lsp);
criterion_main!(benches);
