//! Parse cases: `tests/cases/parse/ok/**` must read with no errors, `tests/cases/parse/err/**`
//! must report at least one problem and still parse their last block (every err case ends
//! with a valid block). Each case's AST dump and diagnostics are a snapshot.

use turnpass::printer::{Edits, print, print_canonical};
use turnpass::syntax::{Statement, parse};

use crate::support::{canonical_options_for, check_spans, dump, options_for, render, with_snapshots};

fn run_case(path: &std::path::Path) -> String {
    let source = std::fs::read(path).unwrap();
    let options = options_for(&source);
    let parsed = parse(&source, &options);
    check_spans(&parsed);
    assert_eq!(print(&parsed.program, &Edits::new()), source, "lossless print of {}", path.display());
    let err_case = path.components().any(|c| c.as_os_str() == "err");
    if err_case {
        assert!(!parsed.diagnostics.is_empty(), "{} should report a problem", path.display());
        let last = parsed.program.blocks().iter().rev().find(|b| !b.span.is_empty());
        assert!(last.is_some_and(|b| b.statement != Statement::Invalid), "{}: parsing stopped early", path.display());
    } else {
        assert_eq!(parsed.error_count(), 0, "{}:\n{}", path.display(), render("case", &source, &parsed.diagnostics));
        // Its canonical form reads as cleanly and is a fixed point.
        let canonical_options = canonical_options_for(&source);
        let canonical = print_canonical(&parsed.program, &canonical_options);
        let reparsed = parse(&canonical, &options);
        check_spans(&reparsed);
        assert_eq!(
            reparsed.error_count(),
            0,
            "{}:\n{}",
            path.display(),
            render("canonical", &canonical, &reparsed.diagnostics)
        );
        assert_eq!(print_canonical(&reparsed.program, &canonical_options), canonical, "{}", path.display());
    }
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    format!(
        "----- SOURCE\n{}\n----- DIALECT\n{} ({:?})\n----- AST\n{}----- DIAGNOSTICS\n{}",
        String::from_utf8_lossy(&source).trim_end(),
        parsed.detection.dialect,
        parsed.detection.choice,
        dump(&parsed.program),
        render(&name, &source, &parsed.diagnostics)
    )
}

#[test]
fn parse_cases() {
    with_snapshots("parse", || {
        insta::glob!("../cases/parse", "**/*.nc", |path| {
            insta::assert_snapshot!(run_case(path));
        });
    });
}
