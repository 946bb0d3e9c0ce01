//! Hostile inputs: a 10 MB line, brackets nested 100 000 deep, 400-digit numbers, bytes that
//! are not UTF-8, odd line endings. Each must parse without panic or stack overflow, print
//! back byte-identical, keep the span invariants, and get the diagnostics the dialect calls
//! for. The inputs are generated here (10 MB does not belong in the repository); what they
//! produce is a snapshot.

use turnpass::dialect::{Dialect, DialectChoice, GCodeSystem, MachineKind};
use turnpass::printer::{CanonicalOptions, Edits, print, print_canonical};
use turnpass::source::LineIndex;
use turnpass::syntax::{ParseOptions, parse};

use crate::support::{check_spans, with_snapshots};

fn options(dialect: Dialect) -> ParseOptions {
    ParseOptions {
        dialect: DialectChoice::Fixed(dialect),
        gcode_system: GCodeSystem::A,
        machine_kind: Some(MachineKind::Lathe),
        control: Default::default(),
    }
}

/// Parse, check, print back, and summarise as `line:column code` per diagnostic.
fn summary(name: &str, source: &[u8], dialect: Dialect) -> String {
    let parsed = parse(source, &options(dialect));
    check_spans(&parsed);
    assert!(print(&parsed.program, &Edits::new()) == source, "{name}: lossless");
    let canonical =
        print_canonical(&parsed.program, &CanonicalOptions { decimal_input: Default::default(), increment_places: 3 });
    let _ = parse(&canonical, &options(dialect));
    let lines = LineIndex::new(source);
    let mut out = format!("{name}: {} bytes, {} blocks\n", source.len(), parsed.program.blocks().len());
    for d in &parsed.diagnostics {
        let (line, column) = lines.position(d.span.start);
        out.push_str(&format!("  {line}:{column} {} {}\n", d.severity.as_str(), d.code()));
    }
    out
}

#[test]
fn hostile_inputs() {
    let mut report = String::new();
    let ten_mb = 10 * 1024 * 1024;

    // A 10 MB line of words: one block, one diagnostic (the repeated X), linear time.
    let mut line = Vec::with_capacity(ten_mb + 16);
    while line.len() < ten_mb {
        line.extend_from_slice(b"X1.5 Z-2. ");
    }
    line.extend_from_slice(b"\nM30\n");
    report += &summary("10 MB line of words", &line, Dialect::Fanuc);

    // A 10 MB comment and a 10 MB run of damage.
    let mut comment = b"(".to_vec();
    comment.resize(ten_mb, b'A');
    comment.extend_from_slice(b")\nG00 X1.\n");
    report += &summary("10 MB comment", &comment, Dialect::Fanuc);
    let mut damage = vec![b'}'; ten_mb];
    damage.extend_from_slice(b"\nG00 X1.\n");
    report += &summary("10 MB of `}`", &damage, Dialect::Osp);

    // Brackets nested 100 000 deep, in both dialects, and as long unary chains.
    let deep = |open: &str, close: &str, prefix: &str| {
        let mut text = prefix.as_bytes().to_vec();
        text.extend(std::iter::repeat_n(open.as_bytes(), 100_000).flatten());
        text.push(b'1');
        text.extend(std::iter::repeat_n(close.as_bytes(), 100_000).flatten());
        text.extend_from_slice(b"\nG00 X1.\n");
        text
    };
    report += &summary("Fanuc [ x 100000", &deep("[", "]", "#1="), Dialect::Fanuc);
    report += &summary("OSP [ x 100000", &deep("[", "]", "X="), Dialect::Osp);
    report += &summary("unclosed [ x 100000", &deep("[", "", "G00 X"), Dialect::Fanuc);
    report += &summary("unary - x 100000", &deep("-", "", "#1="), Dialect::Fanuc);
    let mut nots = b"V1=[".to_vec();
    nots.extend(std::iter::repeat_n(b"NOT ".as_slice(), 100_000).flatten());
    nots.extend_from_slice(b"1]\nG00 X1\n");
    report += &summary("NOT x 100000", &nots, Dialect::Osp);
    report += &summary("function calls x 100000", &deep("SIN[", "]", "#1="), Dialect::Fanuc);

    // 400-digit numbers as a word, in an expression, as a sequence number and as a code.
    let digits = "9".repeat(400);
    let numbers = format!("G01 X{digits}\n#1={digits}\nN{digits} G00\nG{digits}\nX.{digits}\nG00 X1.\n");
    report += &summary("400-digit numbers", numbers.as_bytes(), Dialect::Fanuc);

    // Line endings: CR only, mixed, none at the end; a BOM; NUL, tabs, bytes >= 0x80.
    report += &summary("CR only", b"G00 X1.\rG01 Z-1. F0.1\rM30\r", Dialect::Fanuc);
    report += &summary("mixed endings", b"G00 X1.\r\nG01 Z-1.\nG01 X2.\rM30", Dialect::Fanuc);
    report += &summary("BOM", b"\xEF\xBB\xBFG00 X1.\n", Dialect::Fanuc);
    report += &summary("NUL and tabs", b"\tG00\tX1.\n\0\0\0\nG00 X\x001.\n(\0)\nM30\n", Dialect::Fanuc);
    report += &summary(
        "Shift-JIS and Latin-1",
        b"(\x83e\x83X\x83g)\nG00 X1. (\xe9t\xe9)\nG00 X\x82\xa0\nNAT00 (\x93\xfa\x96\x7b)\nM02\n",
        Dialect::Osp,
    );
    report += &summary("BOM before an OSP header", b"\xEF\xBB\xBF$A.MIN%\nG00 X1\n%\nafter the tape\n", Dialect::Osp);
    report += &summary("tape marks after blanks", b" %\nG00 X1.\n\t%\nafter the tape\n", Dialect::Fanuc);
    report += &summary("only line breaks", b"\n\r\n\r\n\n", Dialect::Osp);
    report += &summary("empty", b"", Dialect::Osp);
    report += &summary("lone percent signs", b"%\n%\n%\n", Dialect::Fanuc);
    report += &summary("continuation with no block", b"$ G84 XA=60\n$ XB=40\nM02\n", Dialect::Osp);

    with_snapshots("robustness", || insta::assert_snapshot!("hostile_inputs", report));
}

/// Every program the repository holds, and the third-party corpus when it is beside the
/// repository, is text by the rule that keeps binary files from being parsed
/// (`source::not_text`); the hostile files with a stray NUL among them stay programs whose
/// NUL is a diagnostic of the parse.
#[test]
fn every_program_is_text() {
    let mut dirs = vec![crate::support::repo().join("tests/cases"), crate::support::repo().join("examples")];
    dirs.push(crate::support::repo().join("../shared/corpus"));
    let mut read = 0;
    for dir in dirs {
        for path in files_under(&dir) {
            if path.starts_with(crate::support::repo().join("tests/cases/cli")) {
                continue; // the command-line cases hold files that are not text on purpose
            }
            let bytes = std::fs::read(&path).unwrap();
            assert_eq!(turnpass::source::not_text(&bytes), None, "{}", path.display());
            read += 1;
        }
    }
    assert!(read > 100, "only {read} files were read");
}

fn files_under(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let path = entry.path();
        if path.is_dir() { out.extend(files_under(&path)) } else { out.push(path) }
    }
    out
}
