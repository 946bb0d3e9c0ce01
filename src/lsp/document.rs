//! An open program: its text and its parse, kept as chunks, and incremental re-parsing.
//!
//! **Why chunks.** An edit changes a few bytes, but every byte and span after it moves. A
//! parse that is one arena of absolute spans would need every later word rewritten (a
//! 1-byte edit of an 8 MB program would touch 1.2 million words), and a text that is one
//! buffer would need every later byte moved (50 MB of memory traffic for a keystroke at the
//! top of a 50 MB program). The document instead keeps the text and its parse as chunks of
//! whole blocks (about [`DEFAULT_CHUNK_BYTES`] each, see `chunk.rs`), each with its own
//! bytes and spans relative to its own start. An edit:
//!
//! 1. takes the chunks the edited bytes touch and splices the edit into their text;
//! 2. widens that stretch by whole chunks until both ends are chunk boundaries in the new
//!    text (a `$` continuation line or a CR LF pair never straddles one);
//! 3. re-splits the stretch into chunks, scans their dialect evidence, and parses them
//!    (only those blocks), from the tape state the chunk before leaves;
//! 4. re-parses the chunks after it only while the tape state entering them changed (an
//!    edit that adds or removes a `%` line);
//! 5. re-decides the dialect from every chunk's evidence; when the decision changes, every
//!    chunk is parsed again (the block grammar depends on it).
//!
//! The chunks after the edit keep their text and parse; only their start offsets and first
//! line numbers, one integer each, move. [`Snapshot::program`] joins the chunks back into
//! one text and one [`Program`], equal (tested, and fuzzed, with random edit sequences) to
//! what [`crate::syntax::parse`] gives for the same text.

use std::ops::Range;
use std::sync::{Arc, OnceLock};

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::detect::{self, Detection};
use crate::dialect::{DialectChoice, DialectConfig};
use crate::source::Span;
use crate::syntax::{self, Block, Command, Expr, ExprId, ParseOptions, Parsed, Program, Statement, Tape, Word, WordId};

use super::chunk::{self, Chunk};
use super::position;

/// About how many bytes of text a chunk holds: a re-parse after an edit handles one or two
/// chunks, and the per-chunk bookkeeping of an 8 MB program stays at two thousand entries.
pub const DEFAULT_CHUNK_BYTES: usize = 4096;

/// A line and a UTF-16 column, both 0-based: the protocol's position.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct LinePosition {
    pub line: u32,
    pub column: u32,
}

#[derive(Debug, Clone)]
pub struct Document {
    /// The text and its parse, in order; empty for an empty text and for a text too large
    /// for 32-bit spans.
    chunks: Vec<Arc<Chunk>>,
    /// The text when it is too large for 32-bit spans: it is not parsed, and
    /// [`Document::diagnostics`] says so.
    oversized: Option<Arc<Vec<u8>>>,
    /// The length of the text.
    len: usize,
    /// Where each chunk starts in the text, and the text's length last.
    starts: Vec<u32>,
    /// The first line of each chunk, and the number of lines last.
    first_lines: Vec<u32>,
    /// How many diagnostics and errors each chunk's parse has, kept beside the chunks so that
    /// a keystroke's questions about the whole document (any error? how many diagnostics?)
    /// read one small array instead of every chunk.
    summaries: Vec<Summary>,
    options: ParseOptions,
    detection: Detection,
    chunk_bytes: usize,
}

/// An immutable view of a document at one version, cheap to take (the chunks are shared),
/// for work done away from the document (the semantic pass on another thread).
#[derive(Debug, Clone)]
pub struct Snapshot {
    chunks: Vec<Arc<Chunk>>,
    oversized: Option<Arc<Vec<u8>>>,
    len: usize,
    starts: Vec<u32>,
    detection: Detection,
    config: DialectConfig,
    /// The chunks' text joined into one, on first use: by the thread that runs the semantic
    /// pass, not by the one that answers the editor.
    joined: OnceLock<Vec<u8>>,
}

impl Document {
    pub fn new(text: Vec<u8>, options: ParseOptions) -> Document {
        Document::with_chunk_bytes(text, options, DEFAULT_CHUNK_BYTES)
    }

    /// A document cut into chunks of about `chunk_bytes` (tests use tiny chunks to put
    /// boundaries everywhere).
    pub fn with_chunk_bytes(text: Vec<u8>, options: ParseOptions, chunk_bytes: usize) -> Document {
        let detection = detect::decide(b"", given(&options), options.machine_kind);
        let mut document = Document {
            chunks: Vec::new(),
            oversized: None,
            len: 0,
            starts: vec![0],
            first_lines: vec![0],
            summaries: Vec::new(),
            options,
            detection,
            chunk_bytes: chunk_bytes.max(1),
        };
        document.rebuild(text);
        document
    }

    /// The whole text, joined from the chunks (a copy: its cost grows with the text).
    pub fn text(&self) -> Vec<u8> {
        match &self.oversized {
            Some(text) => text.to_vec(),
            None => join(&self.chunks, self.len),
        }
    }

    /// The length of the text in bytes.
    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    pub fn options(&self) -> ParseOptions {
        self.options
    }

    pub fn detection(&self) -> &Detection {
        &self.detection
    }

    pub fn config(&self) -> DialectConfig {
        DialectConfig::new(self.detection.dialect, self.options.gcode_system, self.detection.machine_kind)
            .with_control(self.options.control)
    }

    /// How many chunks the parse is kept in.
    pub fn chunk_count(&self) -> usize {
        self.chunks.len()
    }

    /// Replace the whole text.
    pub fn set_text(&mut self, text: Vec<u8>) {
        self.rebuild(text);
    }

    /// Read the program with other options (new machine settings); parses it again.
    pub fn set_options(&mut self, options: ParseOptions) {
        if options != self.options {
            self.options = options;
            self.rebuild(self.text());
        }
    }

    /// Replace the bytes `range` (clamped to the text) by `insert`, and re-parse the blocks
    /// the change touches. See the module documentation.
    pub fn replace(&mut self, range: Range<usize>, insert: &[u8]) {
        let old_len = self.len;
        let start = range.start.min(old_len);
        let end = range.end.clamp(start, old_len);
        if start == end && insert.is_empty() {
            return;
        }
        let new_len = old_len - (end - start) + insert.len();
        if self.chunks.is_empty() || new_len >= u32::MAX as usize || old_len >= u32::MAX as usize {
            let mut text = self.text();
            text.splice(start..end, insert.iter().copied());
            self.rebuild(text);
            return;
        }

        // The chunks the edited bytes touch, in old offsets: the one holding `start` through
        // the one holding the last replaced byte; their text with the edit made.
        let mut first = self.chunk_at(start as u32);
        let mut last = if end > start { self.chunk_at(end as u32 - 1) } else { first };
        let mut region: Vec<u8> = self.chunks[first..=last].iter().flat_map(|c| c.text.iter().copied()).collect();
        let base = self.starts[first] as usize;
        region.splice(start - base..end - base, insert.iter().copied());
        // Widen by whole chunks until both ends are boundaries in the new text.
        loop {
            let last_byte_before =
                |first: usize| first.checked_sub(1).and_then(|p| self.chunks[p].text.last().copied());
            let first_byte_after = |last: usize| self.chunks.get(last + 1).and_then(|c| c.text.first().copied());
            let at_start = (last_byte_before(first), region.first().copied().or_else(|| first_byte_after(last)));
            let at_end = (region.last().copied().or_else(|| last_byte_before(first)), first_byte_after(last));
            if first > 0 && !chunk::is_boundary_between(at_start.0, at_start.1) {
                first -= 1;
                region.splice(0..0, self.chunks[first].text.iter().copied());
            } else if last + 1 < self.chunks.len() && !chunk::is_boundary_between(at_end.0, at_end.1) {
                last += 1;
                region.extend_from_slice(&self.chunks[last].text);
            } else {
                break;
            }
        }
        let scan = self.scans();
        let old_evidence = region_evidence(&self.chunks[first..=last]);
        let old_region_end = self.starts[last + 1];
        let mut at = 0;
        let fresh: Vec<Arc<Chunk>> = chunk::split(&region, 0..region.len(), self.chunk_bytes)
            .into_iter()
            .map(|len| {
                let chunk = Chunk::new(region[at..at + len].to_vec(), scan);
                at += len;
                Arc::new(chunk)
            })
            .collect();
        let fresh_count = fresh.len();
        let same_evidence = !scan || region_evidence(&fresh) == old_evidence;
        self.respan(first..last + 1, &fresh, new_len);
        self.chunks.splice(first..=last, fresh);
        self.summaries.splice(first..=last, std::iter::repeat_n(Summary::default(), fresh_count));
        self.len = new_len;

        if same_evidence {
            // The region's evidence is what it was, so the decision is too: only the first
            // occurrences after the region move (the usual keystroke, without a look at
            // every chunk).
            let delta = new_len as i64 - old_len as i64;
            for evidence in &mut self.detection.evidence {
                if evidence.first.start >= old_region_end {
                    let moved = |offset: u32| (offset as i64 + delta) as u32;
                    evidence.first = Span::new(moved(evidence.first.start), moved(evidence.first.end));
                }
            }
        } else {
            let config = self.config();
            self.detection = self.decide();
            if self.config() != config {
                self.parse_all();
                return;
            }
        }
        let after = first + fresh_count;
        for index in first..after {
            self.parse_chunk(index);
        }
        // Later chunks keep their parse while the tape state entering them is unchanged.
        for index in after..self.chunks.len() {
            if self.chunks[index].tape_in == self.tape_before(index) {
                break;
            }
            self.parse_chunk(index);
        }
    }

    /// Split, scan and parse a whole new text.
    fn rebuild(&mut self, text: Vec<u8>) {
        self.len = text.len();
        if text.len() >= u32::MAX as usize {
            // Too large for 32-bit spans: no chunks, and `diagnostics` says so.
            self.chunks.clear();
            self.summaries.clear();
            self.detection = detect::decide(&text, given(&self.options), self.options.machine_kind);
            self.oversized = Some(Arc::new(text));
            self.recount();
            return;
        }
        self.oversized = None;
        let scan = self.scans();
        let mut at = 0;
        self.chunks = chunk::split(&text, 0..text.len(), self.chunk_bytes)
            .into_iter()
            .map(|len| {
                let chunk = Chunk::new(text[at..at + len].to_vec(), scan);
                at += len;
                Arc::new(chunk)
            })
            .collect();
        self.summaries = vec![Summary::default(); self.chunks.len()];
        self.recount();
        self.detection = self.decide();
        self.parse_all();
    }

    /// Parse every chunk (after a new dialect decision: the block grammar depends on it).
    fn parse_all(&mut self) {
        for index in 0..self.chunks.len() {
            self.parse_chunk(index);
        }
    }

    fn parse_chunk(&mut self, index: usize) {
        let tape = self.tape_before(index);
        let config = self.config();
        Arc::make_mut(&mut self.chunks[index]).parse(config, tape, index == 0);
        self.summaries[index] = Summary::of(&self.chunks[index]);
    }

    fn tape_before(&self, index: usize) -> Tape {
        match index.checked_sub(1) {
            Some(previous) => self.chunks[previous].tape_out(),
            None => Tape::Before,
        }
    }

    fn scans(&self) -> bool {
        detect::scan_needed(given(&self.options), self.options.machine_kind)
    }

    /// The dialect decision from every chunk's evidence, as one scan of the text would give.
    fn decide(&self) -> Detection {
        let mut evidence = Vec::new();
        if self.scans() {
            for (chunk, &start) in self.chunks.iter().zip(&self.starts) {
                detect::merge_evidence(
                    &mut evidence,
                    chunk
                        .evidence
                        .iter()
                        .map(|e| detect::Evidence { first: chunk::shifted(e.first, start), ..e.clone() }),
                );
            }
        }
        detect::decide_from(evidence, given(&self.options), self.options.machine_kind)
    }

    /// Recompute where each chunk starts and its first line.
    fn recount(&mut self) {
        self.starts.clear();
        self.first_lines.clear();
        let (mut at, mut line) = (0u32, 0u32);
        for chunk in &self.chunks {
            self.starts.push(at);
            self.first_lines.push(line);
            at += chunk.byte_len();
            line += chunk.line_count() as u32;
        }
        self.starts.push(at);
        self.first_lines.push(line);
    }

    /// Where each chunk starts and its first line, when the chunks `replaced` give way to
    /// `fresh` and the text's length becomes `new_len`: the chunks after them move by the
    /// same number of bytes and lines, without being looked at.
    fn respan(&mut self, replaced: Range<usize>, fresh: &[Arc<Chunk>], new_len: usize) {
        let (mut at, mut line) = (self.starts[replaced.start], self.first_lines[replaced.start]);
        let line_delta = fresh.iter().map(|c| c.line_count() as i64).sum::<i64>()
            - (self.first_lines[replaced.end] as i64 - line as i64);
        let byte_delta = new_len as i64 - self.len as i64;
        let (mut starts, mut lines) = (Vec::with_capacity(fresh.len()), Vec::with_capacity(fresh.len()));
        for chunk in fresh {
            starts.push(at);
            lines.push(line);
            at += chunk.byte_len();
            line += chunk.line_count() as u32;
        }
        let moved = replaced.start + fresh.len();
        self.starts.splice(replaced.clone(), starts);
        self.first_lines.splice(replaced, lines);
        for start in &mut self.starts[moved..] {
            *start = (*start as i64 + byte_delta) as u32;
        }
        for first_line in &mut self.first_lines[moved..] {
            *first_line = (*first_line as i64 + line_delta) as u32;
        }
    }

    /// The chunk holding byte `offset` (the last chunk for the end of the text).
    pub(crate) fn chunk_at(&self, offset: u32) -> usize {
        let after = self.starts[..self.chunks.len()].partition_point(|&s| s <= offset);
        after.saturating_sub(1)
    }

    /// The block whose text holds byte `offset`, or whose text ends at it (a cursor just
    /// after a word). The text after a closing `%` is no block here.
    pub(crate) fn block_at(&self, offset: usize) -> Option<BlockRef<'_>> {
        if self.chunks.is_empty() {
            return None;
        }
        let index = self.chunk_at(offset as u32);
        let base = self.starts[index];
        let chunk = &self.chunks[index];
        let local = offset as u32 - base.min(offset as u32);
        let block = chunk.part.blocks.partition_point(|b| b.span.start <= local).checked_sub(1)?;
        let found = BlockRef { chunk, base, index: block };
        (local <= found.block().span.end).then_some(found)
    }

    /// Every block of the program, in order (without the text after a closing `%`).
    pub(crate) fn blocks(&self) -> impl Iterator<Item = BlockRef<'_>> {
        (0..self.chunks.len()).flat_map(move |index| {
            let chunk = &*self.chunks[index];
            let base = self.starts[index];
            (0..chunk.part.blocks.len()).map(move |block| BlockRef { chunk, base, index: block })
        })
    }

    /// The blocks of the chunks that hold bytes `range` (a few blocks on either side of it):
    /// for answers about what the editor shows, whose work follows the range, not the text.
    pub(crate) fn blocks_near(&self, range: Range<usize>) -> impl Iterator<Item = BlockRef<'_>> {
        let (first, last) = if self.chunks.is_empty() {
            (0, 0)
        } else {
            (self.chunk_at(range.start as u32), self.chunk_at(range.end as u32) + 1)
        };
        (first..last).flat_map(move |index| {
            let chunk = &*self.chunks[index];
            let base = self.starts[index];
            (0..chunk.part.blocks.len()).map(move |block| BlockRef { chunk, base, index: block })
        })
    }

    /// The text of a span (usually a word: inside one chunk, no copy of the rest).
    pub fn text_of(&self, span: Span) -> Vec<u8> {
        let (start, end) = (span.start as usize, (span.end as usize).min(self.len));
        if let Some(text) = &self.oversized {
            return text.get(start..end).unwrap_or(&[]).to_vec();
        }
        let mut out = Vec::with_capacity(end.saturating_sub(start));
        if self.chunks.is_empty() || start >= end {
            return out;
        }
        let mut index = self.chunk_at(start as u32);
        while index < self.chunks.len() && (self.starts[index] as usize) < end {
            let base = self.starts[index] as usize;
            let text = &self.chunks[index].text;
            let from = start.saturating_sub(base).min(text.len());
            let to = (end - base).min(text.len());
            out.extend_from_slice(&text[from..to]);
            index += 1;
        }
        out
    }

    /// The parse diagnostics whose spans touch bytes `range`, in order.
    pub fn diagnostics_near(&self, range: Range<usize>) -> Vec<Diagnostic> {
        if self.chunks.is_empty() {
            return Vec::new();
        }
        let (first, last) = (self.chunk_at(range.start as u32), self.chunk_at(range.end as u32));
        let mut found: Vec<Diagnostic> = (first..=last)
            .flat_map(|i| self.chunks[i].part.diagnostics.iter().map(move |d| shift_diagnostic(d, self.starts[i])))
            .filter(|d| d.span.start as usize <= range.end && range.start <= d.span.end as usize)
            .collect();
        found.sort_by_key(|d| (d.span.start, d.span.end));
        found
    }

    /// The diagnostics `syntax::parse` gives for the text, in the same order.
    pub fn diagnostics(&self) -> Vec<Diagnostic> {
        let chunks = self.chunks.iter().map(|c| &**c).zip(self.starts.iter().copied());
        collect_diagnostics(&self.detection, self.oversized.is_some(), chunks, usize::MAX)
    }

    /// The first `limit` of [`Document::diagnostics`], and how many there are in all. The
    /// work grows with `limit`, not with the number of diagnostics, and reads only the
    /// chunks that have some.
    pub fn first_diagnostics(&self, limit: usize) -> (Vec<Diagnostic>, usize) {
        let with_diagnostics = (0..self.chunks.len()).filter(|&i| self.summaries[i].diagnostics > 0);
        let chunks = with_diagnostics.map(|i| (&*self.chunks[i], self.starts[i]));
        let first = collect_diagnostics(&self.detection, self.oversized.is_some(), chunks, limit);
        let in_chunks: usize = self.summaries.iter().map(|s| s.diagnostics as usize).sum();
        let outside = syntax::detection_diagnostics(&self.detection).len() + usize::from(self.oversized.is_some());
        (first, outside + in_chunks)
    }

    /// At least `per_side` parse diagnostics on each side of byte `focus` where there are
    /// that many (those of whole chunks, so a few more), in order: the candidates for a
    /// publish that shows the diagnostics nearest an edit. Reads only the chunks it needs.
    pub fn diagnostics_around(&self, focus: usize, per_side: usize) -> Vec<Diagnostic> {
        let mut diagnostics = syntax::detection_diagnostics(&self.detection);
        if self.oversized.is_some() {
            diagnostics.push(Diagnostic::error(DiagnosticKind::SourceTooLarge, Span::new(0, 0)));
        }
        if self.chunks.is_empty() {
            return diagnostics;
        }
        let at = self.chunk_at(focus as u32);
        let count = |range: &mut dyn Iterator<Item = usize>| -> usize {
            let mut seen = 0;
            let mut last = None;
            for index in range {
                last = Some(index);
                seen += self.summaries[index].diagnostics as usize;
                if seen >= per_side {
                    break;
                }
            }
            last.unwrap_or(at)
        };
        let first = count(&mut (0..=at).rev());
        let last = count(&mut (at..self.chunks.len()));
        for index in first..=last {
            let start = self.starts[index];
            diagnostics.extend(self.chunks[index].part.diagnostics.iter().map(|d| shift_diagnostic(d, start)));
        }
        diagnostics.sort_by_key(|d| (d.span.start, d.span.end));
        diagnostics
    }

    /// Whether the parse found errors (the semantic pass waits until it finds none).
    pub fn has_errors(&self) -> bool {
        self.oversized.is_some() || self.summaries.iter().any(|s| s.errors > 0)
    }

    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            chunks: self.chunks.clone(),
            oversized: self.oversized.clone(),
            len: self.len,
            starts: self.starts.clone(),
            detection: self.detection.clone(),
            config: self.config(),
            joined: OnceLock::new(),
        }
    }

    /// The last byte of the text.
    fn last_byte(&self) -> Option<u8> {
        match &self.oversized {
            Some(text) => text.last().copied(),
            None => self.chunks.last().and_then(|c| c.text.last().copied()),
        }
    }

    /// Whether the text ends with a line terminator, which starts one more (empty) line.
    fn ends_with_terminator(&self) -> bool {
        matches!(self.last_byte(), Some(b'\n' | b'\r'))
    }

    /// The number of lines as the protocol counts them: a terminator at the end of the text
    /// starts one more, empty, line.
    pub fn line_count(&self) -> u32 {
        let lines = self.first_lines.last().copied().unwrap_or(0);
        if self.len == 0 || self.ends_with_terminator() { lines + 1 } else { lines }
    }

    /// The text of line `line` without its terminator, and where it starts.
    pub fn line(&self, line: u32) -> Option<(usize, &[u8])> {
        let index = self.first_lines[..self.chunks.len()].partition_point(|&l| l <= line).checked_sub(1)?;
        let chunk = &self.chunks[index];
        let local = (line - self.first_lines[index]) as usize;
        let start = *chunk.line_starts.get(local)? as usize;
        let end = chunk.line_starts.get(local + 1).map_or(chunk.text.len(), |&s| s as usize);
        let base = self.starts[index] as usize;
        Some((base + start, position::without_terminator(&chunk.text[start..end])))
    }

    /// The protocol position of byte `offset`; an offset inside a character goes to the
    /// character's start, or its end when `round_up` (the end of a range).
    pub fn position_of(&self, offset: usize, round_up: bool) -> LinePosition {
        let offset = offset.min(self.len);
        if self.chunks.is_empty() || (offset == self.len && self.ends_with_terminator()) {
            return LinePosition { line: self.line_count().saturating_sub(1), column: 0 };
        }
        let index = self.chunk_at(offset as u32);
        let chunk = &self.chunks[index];
        let local = offset as u32 - self.starts[index];
        let line_in_chunk = chunk.line_starts.partition_point(|&s| s <= local).saturating_sub(1);
        let line = self.first_lines[index] + line_in_chunk as u32;
        match self.line(line) {
            Some((start, text)) => LinePosition { line, column: position::column_of(text, offset - start, round_up) },
            None => LinePosition { line, column: 0 },
        }
    }

    /// The protocol range of a span.
    pub fn range(&self, span: Span) -> lsp_types::Range {
        let start = self.position_of(span.start as usize, false);
        let end = self.position_of(span.end as usize, true).max(start);
        lsp_types::Range {
            start: lsp_types::Position { line: start.line, character: start.column },
            end: lsp_types::Position { line: end.line, character: end.column },
        }
    }

    /// The byte offset of a protocol position, clamped to the text: a column past the end
    /// of its line is the line's end, a line past the last is the end of the text.
    pub fn offset_of(&self, position: LinePosition) -> usize {
        match self.line(position.line) {
            Some((start, text)) => start + position::offset_of(text, position.column),
            None => self.len,
        }
    }
}

impl Snapshot {
    /// The whole text (joined from the chunks on first use).
    pub fn text(&self) -> &[u8] {
        match &self.oversized {
            Some(text) => text,
            None => self.joined.get_or_init(|| join(&self.chunks, self.len)),
        }
    }

    /// The chunks spliced back into one program over the snapshot's text.
    pub fn program(&self) -> Program<'_> {
        super::assemble::program(
            self.text(),
            self.config,
            self.chunks.iter().map(|c| &**c).zip(self.starts.iter().copied()),
        )
    }

    /// What `syntax::parse` returns for the text, built from the chunks.
    pub fn parsed(&self) -> Parsed<'_> {
        let chunks = self.chunks.iter().map(|c| &**c).zip(self.starts.iter().copied());
        let diagnostics = collect_diagnostics(&self.detection, self.oversized.is_some(), chunks, usize::MAX);
        Parsed { program: self.program(), diagnostics, detection: self.detection.clone() }
    }
}

/// The chunks' text as one.
fn join(chunks: &[Arc<Chunk>], len: usize) -> Vec<u8> {
    let mut text = Vec::with_capacity(len);
    for chunk in chunks {
        text.extend_from_slice(&chunk.text);
    }
    text
}

/// The first `limit` diagnostics of a whole parse from its chunks (with where each starts):
/// those of the dialect decision, then each chunk's in order, sorted as `syntax::parse`
/// sorts them (a stable sort on the same order of reports gives the same list).
///
/// A chunk's diagnostics lie inside it, so they sort after those of the chunks before it
/// (a tie at the boundary keeps the earlier chunk's first): once `limit` diagnostics of
/// chunks are collected, the later chunks cannot hold one of the first `limit`.
fn collect_diagnostics<'c>(
    detection: &Detection,
    oversized: bool,
    chunks: impl Iterator<Item = (&'c Chunk, u32)>,
    limit: usize,
) -> Vec<Diagnostic> {
    let mut diagnostics = syntax::detection_diagnostics(detection);
    if oversized {
        diagnostics.push(Diagnostic::error(DiagnosticKind::SourceTooLarge, Span::new(0, 0)));
    }
    let mut from_chunks = 0;
    for (chunk, start) in chunks {
        if from_chunks >= limit {
            break;
        }
        diagnostics.extend(chunk.part.diagnostics.iter().map(|d| shift_diagnostic(d, start)));
        from_chunks += chunk.part.diagnostics.len();
    }
    diagnostics.sort_by_key(|d| (d.span.start, d.span.end));
    diagnostics.truncate(limit);
    diagnostics
}

/// How many diagnostics, and how many errors, a chunk's parse has.
#[derive(Debug, Clone, Copy, Default)]
struct Summary {
    diagnostics: u32,
    errors: u32,
}

impl Summary {
    fn of(chunk: &Chunk) -> Summary {
        let diagnostics = &chunk.part.diagnostics;
        Summary {
            diagnostics: diagnostics.len() as u32,
            errors: diagnostics.iter().filter(|d| d.is_error()).count() as u32,
        }
    }
}

/// The dialect evidence of consecutive chunks, merged, first occurrences relative to the
/// first chunk's start.
fn region_evidence(chunks: &[Arc<Chunk>]) -> Vec<detect::Evidence> {
    let mut merged = Vec::new();
    let mut at = 0;
    for chunk in chunks {
        detect::merge_evidence(
            &mut merged,
            chunk.evidence.iter().map(|e| detect::Evidence { first: chunk::shifted(e.first, at), ..e.clone() }),
        );
        at += chunk.byte_len();
    }
    merged
}

fn given(options: &ParseOptions) -> Option<crate::dialect::Dialect> {
    match options.dialect {
        DialectChoice::Fixed(dialect) => Some(dialect),
        DialectChoice::Auto => None,
    }
}

#[cfg(test)]
mod tests;

pub(crate) fn shift_diagnostic(diagnostic: &Diagnostic, by: u32) -> Diagnostic {
    Diagnostic {
        severity: diagnostic.severity,
        kind: diagnostic.kind.clone(),
        span: chunk::shifted(diagnostic.span, by),
        related: diagnostic.related.iter().map(|(span, label)| (chunk::shifted(*span, by), label.clone())).collect(),
        repeats: diagnostic.repeats,
    }
}

/// A block of a document, read in place in its chunk: its nodes keep the chunk's relative
/// spans and indexes, and [`BlockRef::absolute`] moves a span to the document's offsets.
#[derive(Clone, Copy)]
pub(crate) struct BlockRef<'a> {
    chunk: &'a Chunk,
    base: u32,
    index: usize,
}

impl<'a> BlockRef<'a> {
    pub fn block(&self) -> &'a Block {
        &self.chunk.part.blocks[self.index]
    }

    pub fn words(&self) -> &'a [Word] {
        let block = self.block();
        let first = block.first_word as usize;
        self.chunk.part.words.get(first..first + block.word_count as usize).unwrap_or(&[])
    }

    /// The word of a command parameter or of `Command::code_word`.
    pub fn word(&self, id: WordId) -> Option<&'a Word> {
        self.chunk.part.words.get(id as usize)
    }

    pub fn command(&self) -> Option<&'a Command> {
        match self.block().statement {
            Statement::Cycle(id)
            | Statement::LapCall(id)
            | Statement::LapMarker(id)
            | Statement::Dwell(id)
            | Statement::OneShot(id) => self.chunk.part.commands.get(id as usize),
            _ => None,
        }
    }

    pub fn expr(&self, id: ExprId) -> Option<&'a Expr> {
        self.chunk.part.exprs.get(id as usize)
    }

    /// The source text of a span of this block (relative to the chunk).
    pub fn text(&self, span: Span) -> &'a [u8] {
        self.chunk.text.get(span.range()).unwrap_or(&[])
    }

    pub fn absolute(&self, span: Span) -> Span {
        chunk::shifted(span, self.base)
    }

    /// The word whose text holds the document offset `offset`, or ends at it.
    pub fn word_at(&self, offset: usize) -> Option<(WordId, &'a Word)> {
        let local = offset.checked_sub(self.base as usize)? as u32;
        let words = self.words();
        // Prefer the word the offset is inside; else the one that ends at it.
        let position = words
            .iter()
            .position(|w| w.span.start <= local && local < w.span.end)
            .or_else(|| words.iter().position(|w| w.span.end == local))?;
        Some((self.block().first_word + position as u32, &words[position]))
    }
}
