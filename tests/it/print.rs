//! The printer: edits written in the program's own style, untouched blocks byte-identical;
//! and the canonical form.
//!
//! An edit case is `tests/cases/print/edit/<name>.nc` with `<name>.edits.toml` beside it;
//! replacement blocks are written there as text, parsed in the program's dialect and handed
//! to the printer as typed words, so the case tests the style, not the text.

use serde::Deserialize;
use turnpass::printer::{BlockWriter, CanonicalOptions, Edits, NewBlock, NewWord, print, print_canonical};
use turnpass::source::LineIndex;
use turnpass::syntax::{ParseOptions, Program, WordKind, parse};

use crate::support::{canonical_options_for, check_spans, options_for, render, with_snapshots};

#[derive(Deserialize)]
struct EditFile {
    edit: Vec<EditCase>,
}

#[derive(Deserialize)]
struct EditCase {
    /// 1-based line of the block's first line.
    line: usize,
    #[serde(default)]
    replace: Option<Vec<String>>,
    #[serde(default)]
    delete: bool,
    #[serde(default)]
    insert_before: Vec<String>,
    #[serde(default)]
    insert_after: Vec<String>,
}

/// Typed words from a block written as text.
fn new_block(text: &str, options: &ParseOptions) -> NewBlock {
    let parsed = parse(text.as_bytes(), options);
    assert_eq!(parsed.error_count(), 0, "replacement `{text}` parses");
    let program: &Program<'_> = &parsed.program;
    let mut block = NewBlock::default();
    for word in program.words_of(&program.blocks()[0]) {
        let source = String::from_utf8_lossy(program.text(word.span)).into_owned();
        match word.kind {
            WordKind::Sequence { .. } => block.sequence = Some(source),
            WordKind::Code { letter, code } => block.words.push(NewWord::Code(letter, code)),
            WordKind::Number { address, number } => block.words.push(NewWord::Number(address, number)),
            WordKind::Comment(_) => block.words.push(NewWord::Comment(source.trim_matches(['(', ')']).to_string())),
            WordKind::TapeMark => block.words.push(NewWord::TapeMark),
            other => panic!("replacement word {other:?} is not supported by the test harness"),
        }
    }
    block
}

fn run_edit_case(path: &std::path::Path) -> String {
    let source = std::fs::read(path).unwrap();
    let options = options_for(&source);
    let parsed = parse(&source, &options);
    check_spans(&parsed);
    let program = &parsed.program;
    let lines = LineIndex::new(&source);
    let block_at_line = |line: usize| {
        program
            .blocks()
            .iter()
            .position(|b| lines.position(b.span.start).0 == line)
            .unwrap_or_else(|| panic!("no block at line {line}"))
    };
    let file: EditFile = toml::from_str(&std::fs::read_to_string(path.with_extension("edits.toml")).unwrap()).unwrap();
    let mut edits = Edits::new();
    for edit in &file.edit {
        let index = block_at_line(edit.line);
        if let Some(replacement) = &edit.replace {
            edits.replace(index, replacement.iter().map(|t| new_block(t, &options)).collect());
        }
        if edit.delete {
            edits.delete(index);
        }
        for text in &edit.insert_before {
            edits.insert_before(index, new_block(text, &options));
        }
        for text in &edit.insert_after {
            edits.insert_after(index, new_block(text, &options));
        }
    }
    let output = print(program, &edits);
    // The same replacements written ahead as text (`BlockWriter`, as compensation writes its
    // blocks) print the same.
    let mut written_edits = Edits::new();
    let mut writer = BlockWriter::new(program);
    let mut written = Vec::new();
    for edit in &file.edit {
        let index = block_at_line(edit.line);
        match (&edit.replace, edit.delete) {
            // A written replacement has at least one block; none is a deletion.
            (Some(replacement), false) if !replacement.is_empty() => {
                let start = writer.begin();
                for (k, text) in replacement.iter().enumerate() {
                    if k > 0 {
                        writer.next_block();
                    }
                    writer.block(&new_block(text, &options));
                }
                written.push((index, writer.finish(start)));
            }
            (Some(_), _) | (None, true) => written_edits.delete(index),
            (None, false) => {}
        }
        for text in &edit.insert_before {
            written_edits.insert_before(index, new_block(text, &options));
        }
        for text in &edit.insert_after {
            written_edits.insert_after(index, new_block(text, &options));
        }
    }
    written_edits.replace_written(writer, written);
    assert_eq!(
        String::from_utf8_lossy(&print(program, &written_edits)),
        String::from_utf8_lossy(&output),
        "replacements written ahead print as the same blocks given as words"
    );
    // Every untouched block appears byte for byte, with its terminator, in order.
    let mut cursor = 0;
    for (index, block) in program.blocks().iter().enumerate() {
        if edits.touches(index) {
            continue;
        }
        let mut original = program.text(block.span).to_vec();
        original.extend_from_slice(program.terminator(index));
        let found = output[cursor..].windows(original.len().max(1)).position(|w| w == original.as_slice());
        let found = found.unwrap_or_else(|| panic!("block {index} is not in the output unchanged"));
        cursor += found + original.len();
    }
    // The output is a program that parses as cleanly as the input.
    let reparsed = parse(&output, &options);
    assert_eq!(reparsed.error_count(), parsed.error_count(), "{}", render("output", &output, &reparsed.diagnostics));
    format!(
        "----- SOURCE\n{}\n----- OUTPUT (line ends shown as ␍␊)\n{}",
        String::from_utf8_lossy(&source),
        String::from_utf8_lossy(&output).replace('\r', "␍").replace('\n', "␊\n")
    )
}

#[test]
fn edits_are_written_in_the_programs_style() {
    with_snapshots("print", || {
        insta::glob!("../cases/print/edit", "*.nc", |path| {
            insta::assert_snapshot!(run_edit_case(path));
        });
    });
}

fn run_canonical_case(path: &std::path::Path) -> String {
    let source = std::fs::read(path).unwrap();
    let options = options_for(&source);
    let canonical_options: CanonicalOptions = canonical_options_for(&source);
    let parsed = parse(&source, &options);
    check_spans(&parsed);
    let output = print_canonical(&parsed.program, &canonical_options);
    let reparsed = parse(&output, &options);
    check_spans(&reparsed);
    assert_eq!(reparsed.error_count(), 0, "{}", render("canonical", &output, &reparsed.diagnostics));
    assert_eq!(print_canonical(&reparsed.program, &canonical_options), output, "canonical form is idempotent");
    format!("----- SOURCE\n{}\n----- CANONICAL\n{}", String::from_utf8_lossy(&source), String::from_utf8_lossy(&output))
}

#[test]
fn canonical_form() {
    with_snapshots("print", || {
        insta::glob!("../cases/print/canonical", "*.nc", |path| {
            insta::assert_snapshot!(run_canonical_case(path));
        });
    });
}
