//! Formatting: `fmt --canonical` as one text edit.
//!
//! The edit covers only what changes, from the first differing byte to the last, so the
//! editor keeps the cursor and the undo history of the lines around it.

use lsp_types::TextEdit;

use crate::printer::{CanonicalOptions, print_canonical};
use crate::source::Span;

use super::document::Document;

pub fn formatting(document: &Document, options: &CanonicalOptions) -> Vec<TextEdit> {
    let snapshot = document.snapshot();
    let output = print_canonical(&snapshot.program(), options);
    let old = snapshot.text();
    if output == old {
        return Vec::new();
    }
    let mut prefix = old.iter().zip(&output).take_while(|(a, b)| a == b).count();
    // Whole characters only: step back out of a UTF-8 sequence.
    while prefix > 0 && prefix < old.len() && is_continuation(old[prefix]) {
        prefix -= 1;
    }
    let room = old.len().min(output.len()) - prefix;
    let mut suffix = old.iter().rev().zip(output.iter().rev()).take(room).take_while(|(a, b)| a == b).count();
    while suffix > 0 && is_continuation(old[old.len() - suffix]) {
        suffix -= 1;
    }
    let span = Span::new(prefix as u32, (old.len() - suffix) as u32);
    let new_text = String::from_utf8_lossy(&output[prefix..output.len() - suffix]).into_owned();
    vec![TextEdit { range: document.range(span), new_text }]
}

fn is_continuation(byte: u8) -> bool {
    byte & 0xC0 == 0x80
}
