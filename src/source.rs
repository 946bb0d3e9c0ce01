//! Source text and the crate's one span type.
//!
//! A program is bytes, not always UTF-8: Shift-JIS or Latin-1 comments, NUL bytes and
//! stray control characters occur in real files. Every span is a pair of byte offsets into
//! those bytes; line and column numbers are computed only when a diagnostic is rendered.

use std::fmt;

mod not_text;

pub use not_text::{NotText, not_text};

/// The largest input read, by default, in mebibytes (2^20 bytes): 2.5 times the 100 MB
/// programs turnpass is built for, and every other input (a model, an axis table, a
/// measurement, a thermal log) far below it. A stream that never ends (`yes`, `/dev/zero`)
/// stops here, with an error, instead of growing until memory runs out. The command line
/// raises it (`--max-input-mb`).
pub const DEFAULT_INPUT_LIMIT_MIB: u64 = 256;

/// The most the limit may be raised to, in mebibytes: spans are `u32` byte offsets, so the
/// parser reads less than 4 GiB.
pub const MAX_INPUT_LIMIT_MIB: u64 = 4095;

/// Read `reader` to its end, holding at most `limit` bytes: `Ok(None)` when it has more, so
/// that an endless stream is refused after `limit` bytes, never allocated without end.
pub fn read_at_most(reader: impl std::io::Read, limit: u64) -> std::io::Result<Option<Vec<u8>>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    reader.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    Ok((bytes.len() as u64 <= limit).then_some(bytes))
}

/// A half-open byte range `start..end` into a program's source bytes.
///
/// Offsets are `u32` to keep AST nodes small; the parser refuses sources of 4 GiB or more.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct Span {
    pub start: u32,
    pub end: u32,
}

impl Span {
    pub const fn new(start: u32, end: u32) -> Span {
        Span { start, end }
    }

    /// A span for text that does not come from the source, such as a block inserted by an edit.
    pub const SYNTHETIC: Span = Span { start: u32::MAX, end: u32::MAX };

    pub fn is_synthetic(self) -> bool {
        self == Span::SYNTHETIC
    }

    pub fn len(self) -> u32 {
        self.end - self.start
    }

    pub fn is_empty(self) -> bool {
        self.start == self.end
    }

    /// The smallest span covering both `self` and `other`.
    ///
    /// ```txt
    /// self:   [----)
    /// other:          [---)
    /// merge:  [-----------)
    /// ```
    pub fn merge(self, other: Span) -> Span {
        Span { start: self.start.min(other.start), end: self.end.max(other.end) }
    }

    pub fn contains(self, other: Span) -> bool {
        self.start <= other.start && other.end <= self.end
    }

    pub fn range(self) -> std::ops::Range<usize> {
        self.start as usize..self.end as usize
    }

    /// The bytes this span covers.
    pub fn text(self, source: &[u8]) -> &[u8] {
        &source[self.range()]
    }
}

impl fmt::Debug for Span {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}..{}", self.start, self.end)
    }
}

/// Where each line starts, for turning byte offsets into 1-based line and column numbers.
///
/// A line ends at LF, at CR LF, or at a CR that no LF follows, because old controls and
/// editors wrote CR-only files and real programs mix the conventions.
#[derive(Debug, Clone)]
pub struct LineIndex {
    starts: Vec<u32>,
}

impl LineIndex {
    pub fn new(source: &[u8]) -> LineIndex {
        let mut starts = vec![0u32];
        let mut i = 0;
        while let Some(found) = memchr::memchr2(b'\n', b'\r', &source[i..]) {
            let at = i + found;
            let next = if source[at] == b'\r' && source.get(at + 1) == Some(&b'\n') { at + 2 } else { at + 1 };
            starts.push(next as u32);
            i = next;
        }
        LineIndex { starts }
    }

    /// The 0-based line holding `offset`.
    pub fn line_of(&self, offset: u32) -> usize {
        match self.starts.binary_search(&offset) {
            Ok(line) => line,
            Err(next) => next - 1,
        }
    }

    pub fn line_start(&self, line: usize) -> u32 {
        self.starts[line]
    }

    pub fn line_count(&self) -> usize {
        self.starts.len()
    }

    /// 1-based line and 1-based column in bytes of `offset`.
    pub fn position(&self, offset: u32) -> (usize, usize) {
        let line = self.line_of(offset);
        (line + 1, (offset - self.starts[line]) as usize + 1)
    }
}

/// Whether `c` is shown escaped in text for people: a control character (C0 but tab and the
/// line breaks, DEL, C1), which a terminal would act on (ESC starts a colour, a title, a
/// clear screen) instead of showing.
fn shown_escaped(c: char) -> bool {
    c.is_control() && !matches!(c, '\t' | '\n' | '\r')
}

/// `c` as its escape: `\x1b` below U+0100, `\u{9b}` above.
fn push_escaped(c: char, out: &mut String) {
    use std::fmt::Write as _;
    let code = u32::from(c);
    let _ = if code < 0x80 { write!(out, "\\x{code:02x}") } else { write!(out, "\\u{{{code:x}}}") };
}

/// `text` with its control characters escaped ([`shown_escaped`]: ESC as `\x1b`, and CR),
/// for every output people read: a diagnostic's words, a file name, a word a message
/// quotes. Line feeds and tabs stay.
pub fn escape_controls(text: &str) -> std::borrow::Cow<'_, str> {
    let escaped = |c: char| c == '\r' || shown_escaped(c);
    if !text.chars().any(escaped) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if escaped(c) { push_escaped(c, &mut out) } else { out.push(c) }
    }
    std::borrow::Cow::Owned(out)
}

/// Text for display: the source with every byte sequence that is not UTF-8 replaced by
/// U+FFFD, plus the map from source byte offsets to offsets in that text.
///
/// Diagnostics on Shift-JIS or Latin-1 programs must still point at the right character, so
/// rendering translates every span through [`DisplayText::offset`].
#[derive(Debug, Clone)]
pub struct DisplayText {
    pub text: String,
    /// `(source offset, shift)` at each replaced sequence, sorted: from that source offset on,
    /// display offsets are source offsets plus `shift`.
    shifts: Vec<(u32, i64)>,
    /// Where each escaped control character's escape starts in `text`, and its length, in
    /// order: one character of the source, several of the display ([`Self::source_columns`]).
    escapes: Vec<(usize, usize)>,
}

impl DisplayText {
    pub fn new(source: &[u8]) -> DisplayText {
        let mut text = String::with_capacity(source.len());
        let mut shifts = Vec::new();
        let mut escapes = Vec::new();
        let mut source_pos = 0usize;
        for chunk in source.utf8_chunks() {
            let mut rest = chunk.valid();
            // A control character is shown escaped (a terminal would act on ESC, OSC or a
            // bell), and a lone CR as the line break the parser reads it as.
            while let Some(at) = rest.find(|c: char| c == '\r' || shown_escaped(c)) {
                text.push_str(&rest[..at]);
                source_pos += at;
                let c = rest[at..].chars().next().unwrap_or('\r');
                let len = c.len_utf8();
                if c == '\r' {
                    text.push(if rest[at + 1..].starts_with('\n') { '\r' } else { '\n' });
                } else {
                    let at = text.len();
                    push_escaped(c, &mut text);
                    escapes.push((at, text.len() - at));
                    shifts.push(((source_pos + len) as u32, text.len() as i64 - (source_pos + len) as i64));
                }
                source_pos += len;
                rest = &rest[at + len..];
            }
            text.push_str(rest);
            source_pos += rest.len();
            let invalid = chunk.invalid();
            if !invalid.is_empty() {
                text.push(char::REPLACEMENT_CHARACTER);
                source_pos += invalid.len();
                shifts.push((source_pos as u32, text.len() as i64 - source_pos as i64));
            }
        }
        DisplayText { text, shifts, escapes }
    }

    /// How many characters of the source the display characters of `text[from..to]` stand
    /// for: each escape (`\x1b`, all ASCII) is one.
    pub fn source_columns(&self, from: usize, to: usize) -> usize {
        let shown = self.text.get(from..to).map_or(0, |t| t.chars().count());
        let first = self.escapes.partition_point(|&(at, _)| at < from);
        let last = self.escapes.partition_point(|&(at, _)| at < to);
        let extra: usize = self.escapes[first..last].iter().map(|&(_, len)| len - 1).sum();
        shown.saturating_sub(extra)
    }

    /// The display offset of a source offset; an offset inside a replaced sequence maps to
    /// the start of its replacement character.
    pub fn offset(&self, source_offset: u32) -> usize {
        let idx = self.shifts.partition_point(|&(at, _)| at <= source_offset);
        let shift = if idx == 0 { 0 } else { self.shifts[idx - 1].1 };
        let mapped = (source_offset as i64 + shift).max(0) as usize;
        let mut mapped = mapped.min(self.text.len());
        while !self.text.is_char_boundary(mapped) {
            mapped -= 1;
        }
        mapped
    }
}

#[cfg(test)]
mod tests;
