//! Fuzzes the language server's incremental re-parse (`turnpass::lsp::Document`) with
//! arbitrary documents and edit sequences.
//!
//! The input's first byte chooses how the program is read (dialect detection, Okuma OSP or
//! Fanuc; G-code system A, B or C) and its second the chunk size (1 to 64 bytes, so that
//! chunk boundaries fall everywhere). The rest, split at 0xFF bytes, is the document and
//! then one edit per piece: two bytes place it (a fraction of the text's length), one byte
//! says how many bytes it deletes, and the rest is inserted. After every edit the target
//! checks that the document's chunks, spliced together, are exactly what a full parse of its
//! text gives (the program, the diagnostics and their first few as a capped publish takes
//! them, and the dialect decision), that every offset has the protocol position (line,
//! UTF-16 column) it has in a document read from scratch, and that every character
//! boundary survives the trip to a position and back.
//!
//! ```sh
//! RUSTC_BOOTSTRAP=1 cargo fuzz run lsp_edits -- -max_total_time=300 -rss_limit_mb=2048 -max_len=4096 -dict=fuzz/gcode.dict
//! ```

#![no_main]

use libfuzzer_sys::fuzz_target;
use turnpass::dialect::{Dialect, DialectChoice, GCodeSystem};
use turnpass::lsp::Document;
use turnpass::syntax::{ParseOptions, parse};

fuzz_target!(|data: &[u8]| {
    let [selector, size, rest @ ..] = data else { return };
    let dialect = match selector % 3 {
        0 => DialectChoice::Auto,
        1 => DialectChoice::Fixed(Dialect::Osp),
        _ => DialectChoice::Fixed(Dialect::Fanuc),
    };
    let gcode_system = [GCodeSystem::A, GCodeSystem::B, GCodeSystem::C][*selector as usize / 3 % 3];
    let options = ParseOptions { dialect, gcode_system, machine_kind: None, control: Default::default() };
    let mut pieces = rest.split(|&b| b == 0xFF);
    let mut text = pieces.next().unwrap_or_default().to_vec();
    let chunk_bytes = 1 + *size as usize % 64;
    let mut document = Document::with_chunk_bytes(text.clone(), options, chunk_bytes);
    check(&document, &text, &options, chunk_bytes);
    for edit in pieces {
        let (place, delete, insert) = match edit {
            [a, b, c, insert @ ..] => (u16::from_le_bytes([*a, *b]), *c as usize, insert),
            _ => continue,
        };
        let start = text.len() * place as usize / u16::MAX as usize;
        let end = (start + delete).min(text.len());
        text.splice(start..end, insert.iter().copied());
        document.replace(start..end, insert);
        check(&document, &text, &options, chunk_bytes);
    }
});

fn check(document: &Document, text: &[u8], options: &ParseOptions, chunk_bytes: usize) {
    assert_eq!(document.text(), text);
    let full = parse(text, options);
    let snapshot = document.snapshot();
    let incremental = snapshot.parsed();
    assert_eq!(format!("{:?}", incremental.program), format!("{:?}", full.program));
    assert_eq!(incremental.diagnostics, full.diagnostics);
    assert_eq!(incremental.detection, full.detection);
    assert_eq!(document.diagnostics(), full.diagnostics);
    // What a capped publish shows: the first diagnostics, and how many there are in all.
    for limit in [0, 1, 3] {
        let (first, total) = document.first_diagnostics(limit);
        assert_eq!(&first[..], &full.diagnostics[..limit.min(full.diagnostics.len())]);
        assert_eq!(total, full.diagnostics.len());
    }
    // Lines and columns, which an edit moves without looking at the chunks after it, are
    // those of the text read from scratch into other chunks.
    let fresh = Document::with_chunk_bytes(text.to_vec(), *options, chunk_bytes + 5);
    assert_eq!(document.line_count(), fresh.line_count());
    for offset in 0..=text.len() {
        assert_eq!(document.position_of(offset, false), fresh.position_of(offset, false), "offset {offset}");
    }
    // Positions: in UTF-8 text (what an editor sends), every character boundary that is not
    // the middle of a CR LF pair maps to a position and back to itself.
    if let Ok(utf8) = std::str::from_utf8(text) {
        for offset in (0..=text.len()).filter(|&o| utf8.is_char_boundary(o)) {
            if offset > 0 && text[offset - 1] == b'\r' && text.get(offset) == Some(&b'\n') {
                continue;
            }
            let position = document.position_of(offset, false);
            assert_eq!(document.offset_of(position), offset, "offset {offset} at {position:?}");
        }
    }
}
