use super::*;
use crate::dialect::{Dialect, GCodeSystem};

fn fanuc() -> ParseOptions {
    ParseOptions {
        dialect: DialectChoice::Fixed(Dialect::Fanuc),
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    }
}

fn at(line: u32, column: u32) -> LinePosition {
    LinePosition { line, column }
}

#[test]
fn positions_cross_chunks_line_endings_and_wide_characters() {
    let text = "N1 (30°)\r\nG01 X𝑥\rZ2\n".as_bytes().to_vec();
    for chunk_bytes in [1, 3, 4096] {
        let document = Document::with_chunk_bytes(text.clone(), fanuc(), chunk_bytes);
        assert_eq!(document.line_count(), 4, "three lines and the empty one after the last LF");
        let degree = text.iter().position(|&b| b == 0xC2).unwrap();
        assert_eq!(document.position_of(degree, false), at(0, 6));
        assert_eq!(document.position_of(degree + 1, false), at(0, 6), "inside `°`, rounded down");
        assert_eq!(document.position_of(degree + 1, true), at(0, 7), "inside `°`, rounded up");
        assert_eq!(document.position_of(degree + 2, false), at(0, 7));
        let wide = text.iter().position(|&b| b == 0xF0).unwrap();
        assert_eq!(document.position_of(wide, false), at(1, 5));
        assert_eq!(document.position_of(wide + 4, false), at(1, 7), "`𝑥` is two UTF-16 units");
        assert_eq!(document.position_of(text.len() - 3, false), at(2, 0), "after a lone CR");
        assert_eq!(document.position_of(text.len(), false), at(3, 0));
        assert_eq!(document.offset_of(at(1, 7)), wide + 4);
        assert_eq!(document.offset_of(at(1, 6)), wide, "inside the surrogate pair: the character's start");
        assert_eq!(document.offset_of(at(0, 99)), degree + 3, "past the end of the line: before its CR LF");
        assert_eq!(document.offset_of(at(3, 0)), text.len());
        assert_eq!(document.offset_of(at(9, 9)), text.len());
    }
}

#[test]
fn an_edit_keeps_the_chunks_after_it_and_their_positions() {
    let text = b"G00 X1\nG01 Z-1\nG01 X2\nG01 Z-2\n".to_vec();
    let mut document = Document::with_chunk_bytes(text, fanuc(), 1);
    assert_eq!(document.chunk_count(), 4);
    let before = Arc::clone(&document.chunks[3]);
    document.replace(1..1, b"0");
    assert!(Arc::ptr_eq(&before, &document.chunks[3]), "the last chunk was not parsed again");
    assert_eq!(document.text(), b"G000 X1\nG01 Z-1\nG01 X2\nG01 Z-2\n");
    assert_eq!(document.position_of(document.text().len() - 2, false), at(3, 6));
}

#[test]
fn an_empty_document_has_one_empty_line() {
    let mut document = Document::new(Vec::new(), fanuc());
    assert_eq!(document.line_count(), 1);
    assert_eq!(document.position_of(0, false), at(0, 0));
    assert_eq!(document.offset_of(at(0, 5)), 0);
    document.replace(0..0, b"G1O X1");
    assert_eq!(document.diagnostics().len(), 1);
    document.replace(0..6, b"");
    assert!(document.diagnostics().is_empty());
}
