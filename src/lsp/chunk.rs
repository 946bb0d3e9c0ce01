//! A chunk: a run of whole blocks of a document, parsed on its own.
//!
//! The parser works block by block and a line break is its synchronisation point, so a run
//! of whole lines parses the same alone as inside the program, given three facts from
//! outside: the dialect configuration (decided once for the whole text), the tape state
//! before the run (before the opening `%`, inside, or after the closing `%`), and whether
//! the run starts the program (a byte-order mark). A chunk keeps its parse with every span
//! and index relative to its own start, so the chunks after an edit stay valid when the
//! text before them changes length.
//!
//! A chunk may end only where a new block starts whatever the text after it says: right
//! after a line terminator that is not the CR of a CR LF pair, and before a line that does
//! not start with `$` (an OSP continuation line, which joins the block before it).

use crate::dialect::DialectConfig;
use crate::dialect::detect::{self, Evidence};
use crate::source::Span;
use crate::syntax::{self, Part, Tape};

#[derive(Debug, Clone)]
pub(crate) struct Chunk {
    /// The chunk's text: whole lines of the document.
    pub text: Vec<u8>,
    /// Where each line of the chunk starts, relative to the chunk; the first is 0.
    pub line_starts: Vec<u32>,
    /// The dialect evidence of the chunk's lines, spans relative to the chunk.
    pub evidence: Vec<Evidence>,
    /// The tape state the chunk was parsed from.
    pub tape_in: Tape,
    pub part: Part,
}

impl Chunk {
    /// A chunk of `text` with its lines and evidence, not parsed yet.
    pub fn new(text: Vec<u8>, scan: bool) -> Chunk {
        Chunk {
            line_starts: line_starts(&text),
            evidence: if scan { detect::scan(&text) } else { Vec::new() },
            text,
            tape_in: Tape::Before,
            part: Part::default(),
        }
    }

    /// The length of the chunk's text (a document's chunks hold less than 4 GiB in all).
    pub fn byte_len(&self) -> u32 {
        self.text.len() as u32
    }

    /// Parse the chunk's text from the tape state `tape_in`.
    pub fn parse(&mut self, config: DialectConfig, tape_in: Tape, document_start: bool) {
        self.tape_in = tape_in;
        self.part = syntax::parse_part(&self.text, config, tape_in, document_start);
        self.part.diagnostics.sort_by_key(|d| (d.span.start, d.span.end));
    }

    /// The tape state after the chunk.
    pub fn tape_out(&self) -> Tape {
        self.part.tape
    }

    pub fn line_count(&self) -> usize {
        self.line_starts.len()
    }
}

/// Where each line of `text` starts: 0, and after every LF, CR LF, or CR no LF follows. A
/// terminator at the very end starts no line inside `text`.
fn line_starts(text: &[u8]) -> Vec<u32> {
    let mut starts = vec![0u32];
    for at in memchr::memchr2_iter(b'\n', b'\r', text) {
        if text[at] == b'\r' && text.get(at + 1) == Some(&b'\n') {
            continue;
        }
        if at + 1 < text.len() {
            starts.push(at as u32 + 1);
        }
    }
    starts
}

/// Whether a chunk may end at `at` in `text`: see the module documentation.
pub(crate) fn is_boundary(text: &[u8], at: usize) -> bool {
    let before = at.checked_sub(1).and_then(|b| text.get(b)).copied();
    is_boundary_between(before, text.get(at).copied())
}

/// Whether a chunk may end between the bytes `before` and `after`; `None` is the start or
/// the end of the text, where a chunk may always end.
pub(crate) fn is_boundary_between(before: Option<u8>, after: Option<u8>) -> bool {
    let (Some(before), Some(after)) = (before, after) else { return true };
    let after_terminator = match before {
        b'\n' => true,
        b'\r' => after != b'\n',
        _ => false,
    };
    after_terminator && after != b'$'
}

/// Cut `text[range]` into chunks of about `target` bytes at boundaries; returns the lengths.
/// A range with no boundary inside is one chunk, however long.
pub(crate) fn split(text: &[u8], range: std::ops::Range<usize>, target: usize) -> Vec<usize> {
    let mut lengths = Vec::new();
    let mut chunk_start = range.start;
    let mut search = range.start;
    while chunk_start < range.end {
        let want = chunk_start.saturating_add(target.max(1)).min(range.end);
        search = search.max(want);
        let cut = loop {
            if search >= range.end {
                break range.end;
            }
            match memchr::memchr2(b'\n', b'\r', &text[search..range.end]) {
                Some(found) => {
                    let candidate = search + found + 1;
                    if candidate >= range.end {
                        break range.end;
                    }
                    if is_boundary(text, candidate) {
                        break candidate;
                    }
                    search = candidate;
                }
                None => break range.end,
            }
        };
        lengths.push(cut - chunk_start);
        chunk_start = cut;
        search = cut;
    }
    lengths
}

/// A span of a chunk moved to the document's offsets.
pub(crate) fn shifted(span: Span, by: u32) -> Span {
    Span::new(span.start + by, span.end + by)
}

#[cfg(test)]
mod tests;
