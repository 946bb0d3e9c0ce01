//! The provenance comment of a compensated program (`compensation::provenance`): where it is
//! inserted, in which comment style, and how a program that carries one is found and refused.
//!
//! A case is a program under `tests/cases/provenance/`; its snapshot holds the program
//! printed with a provenance comment inserted, the provenance comments the case itself
//! carries, and the diagnostic `compensate` refuses it with. Every case also checks that the
//! printed program parses as cleanly as the case, that its other blocks are byte for byte
//! the case's, and that the comment inserted reads back as what was written.

use turnpass::compensation::fit::Strategy;
use turnpass::compensation::provenance::{self, Provenance};
use turnpass::printer::{Edits, print};
use turnpass::source::LineIndex;
use turnpass::syntax::parse;

use crate::support::{check_spans, options_for, render, repo, with_snapshots};

fn provenance() -> Provenance {
    Provenance {
        version: "0.1.0".to_string(),
        model: "Test lathe (bay 2)".to_string(),
        model_sha256: "3e3e70e7fa2c".to_string(),
        table_sha256: None,
        tolerance_mm: 0.0005,
        strategy: Strategy::Densify,
        step_mm: Some(0.254),
        start_min: 200.0,
        dialect: None,
    }
}

fn run_case(path: &std::path::Path) -> String {
    let source = std::fs::read(path).unwrap();
    let options = options_for(&source);
    let parsed = parse(&source, &options);
    check_spans(&parsed);
    let program = &parsed.program;
    let lines = LineIndex::new(&source);
    let carried = provenance::marks(program);
    let mut edits = Edits::new();
    provenance::insert(program, &mut edits, &provenance());
    let output = print(program, &edits);

    let reparsed = parse(&output, &options);
    check_spans(&reparsed);
    assert_eq!(reparsed.error_count(), parsed.error_count(), "{}", render("output", &output, &reparsed.diagnostics));
    // One block more, and the others as they were.
    assert_eq!(reparsed.program.blocks().len(), program.blocks().len() + 1);
    let without: Vec<u8> = {
        let marks = provenance::marks(&reparsed.program);
        let new = marks.iter().find(|m| !carried.iter().any(|c| program.text(c.span) == reparsed.program.text(m.span)));
        let new = new.expect("the comment inserted is found");
        let block =
            reparsed.program.blocks().iter().position(|b| b.span.start <= new.span.start && new.span.end <= b.span.end);
        let block = block.unwrap();
        let end = reparsed.program.blocks().get(block + 1).map_or(output.len(), |b| b.span.start as usize);
        let start = reparsed.program.blocks()[block].span.start as usize;
        // It reads back as written: the name as the comment may hold it, in the program's case.
        let read = new.provenance.clone().expect("the comment inserted reads");
        assert!(provenance().same_model(&read.model_sha256));
        assert_eq!((read.strategy, read.step_mm, read.start_min), (Strategy::Densify, Some(0.254), 200.0));
        assert!(read.model.eq_ignore_ascii_case("Test lathe bay 2"), "{}", read.model);
        [&output[..start], &output[end..]].concat()
    };
    // On a last line without a line end the inserted block supplies the one before it.
    let trimmed = |text: &[u8]| String::from_utf8_lossy(text).trim_end().to_string();
    assert_eq!(trimmed(&without), trimmed(&source), "the program's own blocks are unchanged");

    let mut text = format!(
        "----- OUTPUT ({:?}; line ends shown as ␍␊)\n{}\n",
        program.config().dialect,
        String::from_utf8_lossy(&output).replace('\r', "␍").replace('\n', "␊\n")
    );
    text.push_str("----- PROVENANCE COMMENTS THE CASE CARRIES\n");
    for mark in &carried {
        let (line, column) = lines.position(mark.span.start);
        match &mark.provenance {
            Ok(made) => text.push_str(&format!("{line}:{column}: {made:?}\n")),
            Err(why) => text.push_str(&format!("{line}:{column}: does not read: {why}\n")),
        }
    }
    text.push_str("----- COMPENSATE REFUSES IT\n");
    match provenance::refusal(program) {
        Some(diagnostic) => {
            text.push_str(&render(&path.file_name().unwrap().to_string_lossy(), &source, &[diagnostic]))
        }
        None => text.push_str("no\n"),
    }
    text
}

#[test]
fn provenance_cases() {
    let mut paths: Vec<_> = std::fs::read_dir(repo().join("tests/cases/provenance"))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "nc"))
        .collect();
    paths.sort();
    assert!(paths.len() >= 10);
    for path in paths {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let text = run_case(&path);
        with_snapshots("provenance", || insta::assert_snapshot!(name, text));
    }
}
