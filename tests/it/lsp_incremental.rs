//! The language server's incremental re-parse: after any sequence of edits, the document's
//! chunks spliced back together are exactly what a full parse of its text gives (the
//! program, its diagnostics and the dialect decision), whatever the chunk size, and its
//! lines and columns are those of the text read from scratch; the first few of its
//! diagnostics, which a capped publish shows, are the first few of the full parse's.

use proptest::prelude::*;
use turnpass::lsp::Document;
use turnpass::syntax::parse;

use crate::roundtrip::{line, options, program};
use crate::support::check_spans;

/// One edit: where (a fraction of the text's length), how many bytes go, what comes in.
fn edit() -> impl Strategy<Value = (f64, usize, Vec<u8>)> {
    let insert = prop_oneof![
        3 => line(),
        2 => prop::sample::select(vec![
            b"\n".to_vec(), b"\r".to_vec(), b"\r\n".to_vec(), b"%".to_vec(), b"%\n".to_vec(), b"$".to_vec(),
            b"$ X=1\n".to_vec(), b"\n%\n".to_vec(), b"#".to_vec(), b"NAT00".to_vec(), b"\xEF\xBB\xBF".to_vec(),
            "°".as_bytes().to_vec(), b"G1O".to_vec(), b"".to_vec(),
        ]),
        1 => prop::collection::vec(any::<u8>(), 0..6),
    ];
    (0.0..=1.0f64, prop_oneof![3 => 0usize..3, 1 => 0usize..60], insert)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 384, ..ProptestConfig::default() })]

    #[test]
    fn incremental_reparse_equals_a_full_parse(
        source in program(),
        options in options(),
        chunk_bytes in 1usize..48,
        edits in prop::collection::vec(edit(), 1..12),
    ) {
        let mut text = source.clone();
        let mut document = Document::with_chunk_bytes(source, options, chunk_bytes);
        for (at, delete, insert) in edits {
            let start = ((text.len() as f64) * at) as usize;
            let end = (start + delete).min(text.len());
            text.splice(start..end, insert.iter().copied());
            document.replace(start..end, &insert);
            prop_assert_eq!(document.text(), &text[..]);
            let full = parse(&text, &options);
            let snapshot = document.snapshot();
            let incremental = snapshot.parsed();
            check_spans(&incremental);
            prop_assert_eq!(format!("{:?}", incremental.program), format!("{:?}", full.program));
            prop_assert_eq!(&incremental.diagnostics, &full.diagnostics);
            prop_assert_eq!(&incremental.detection, &full.detection);
            prop_assert_eq!(document.diagnostics(), &full.diagnostics[..]);
            // What a publish shows when it is capped: the first ones, and how many in all.
            for limit in [0, 1, 3] {
                let (first, total) = document.first_diagnostics(limit);
                prop_assert_eq!(&first[..], &full.diagnostics[..limit.min(full.diagnostics.len())]);
                prop_assert_eq!(total, full.diagnostics.len());
            }
            // Lines and columns, which an edit moves without looking at the chunks after
            // it, are those of a document read from scratch (cut into other chunks).
            let fresh = Document::with_chunk_bytes(text.clone(), options, chunk_bytes + 5);
            prop_assert_eq!(document.line_count(), fresh.line_count());
            for offset in 0..=text.len() {
                prop_assert_eq!(document.position_of(offset, false), fresh.position_of(offset, false), "{}", offset);
            }
        }
    }
}
