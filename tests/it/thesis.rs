//! The two part programs of the thesis' Appendix A, copied exactly as printed (with their
//! OCR damage), and their reconstructions in `examples/programs/`.

use turnpass::diagnostic::DiagnosticKind;
use turnpass::dialect::Dialect;
use turnpass::machine::ModelFile;
use turnpass::printer::{Edits, print};
use turnpass::source::LineIndex;
use turnpass::syntax::{Statement, parse};

use crate::support::{check_spans, options_for, render, repo, with_snapshots};

/// `check` reports exactly the damaged blocks, with the damage hint, and parses every other.
#[test]
fn appendix_a_as_printed_reports_exactly_the_damaged_blocks() {
    let cases: [(&str, Vec<usize>); 2] =
        [("o2005-as-printed.nc", vec![]), ("o2012-as-printed.nc", vec![10, 24, 25, 26, 27, 28, 29, 30, 31, 32])];
    for (file, damaged_lines) in cases {
        let path = repo().join("tests/cases/thesis").join(file);
        let source = std::fs::read(&path).unwrap();
        let parsed = parse(&source, &options_for(&source));
        check_spans(&parsed);
        assert_eq!(parsed.detection.dialect, Dialect::Fanuc, "{file}");
        let lines = LineIndex::new(&source);
        let error_lines: Vec<usize> =
            parsed.diagnostics.iter().filter(|d| d.is_error()).map(|d| lines.position(d.span.start).0).collect();
        assert_eq!(error_lines, damaged_lines, "{file}");
        assert!(parsed.diagnostics.iter().all(|d| matches!(d.kind, DiagnosticKind::DamagedNumber { .. })));
        let invalid_lines: Vec<usize> = parsed
            .program
            .blocks()
            .iter()
            .filter(|b| b.statement == Statement::Invalid)
            .map(|b| lines.position(b.span.start).0)
            .collect();
        assert_eq!(invalid_lines, damaged_lines, "{file}: every undamaged block parses");
        assert_eq!(print(&parsed.program, &Edits::new()), source);
        with_snapshots("thesis", || insta::assert_snapshot!(file, render(file, &source, &parsed.diagnostics)));
    }
}

/// The reconstructions parse with no diagnostics, and differ from the printed programs only
/// in added comment lines and in the damaged blocks, which keep their undamaged words.
#[test]
fn reconstructed_examples_differ_only_where_the_print_is_damaged() {
    for (printed, example) in
        [("o2005-as-printed.nc", "thesis-o2005-arc.nc"), ("o2012-as-printed.nc", "thesis-o2012-turn-face.nc")]
    {
        let printed = std::fs::read_to_string(repo().join("tests/cases/thesis").join(printed)).unwrap();
        let example_text = std::fs::read(repo().join("examples/programs").join(example)).unwrap();
        let parsed = parse(&example_text, &options_for(&example_text));
        check_spans(&parsed);
        assert!(parsed.diagnostics.is_empty(), "{example}:\n{}", render(example, &example_text, &parsed.diagnostics));
        let example_text = String::from_utf8(example_text).unwrap();
        let example_lines: Vec<&str> = example_text.lines().filter(|l| !l.starts_with('(')).collect();
        let printed_lines: Vec<&str> = printed.lines().collect();
        assert_eq!(example_lines.len(), printed_lines.len(), "{example}: same blocks");
        for (ours, theirs) in example_lines.iter().zip(&printed_lines) {
            match theirs.find('}') {
                None => assert_eq!(ours, theirs),
                Some(damage) => {
                    // The words before the damaged value are kept as printed.
                    let intact = theirs[..damage]
                        .trim_end_matches([' ', '.', '-'])
                        .trim_end_matches(|c: char| c.is_ascii_uppercase());
                    assert!(ours.starts_with(intact), "{ours:?} keeps {intact:?}");
                    assert!(ours.contains("(RECONSTRUCTED: PRINTED"), "{ours:?} documents its reconstruction");
                }
            }
        }
    }
}

/// The `turnpass.toml` beside the example programs holds the thesis lathe's `[machine]`
/// table, so they read without `--model` as the inch programs they are.
#[test]
fn example_programs_read_on_the_thesis_lathe() {
    let machine = |path: &str| {
        let text = std::fs::read_to_string(repo().join(path)).unwrap();
        ModelFile::from_toml(&text).unwrap_or_else(|e| panic!("{path}: {e}")).machine
    };
    assert_eq!(machine("examples/programs/turnpass.toml"), machine("examples/machines/okuma-howa-v40r.toml"));
}
