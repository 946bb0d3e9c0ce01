//! Measurement files as instruments and their software write them: CSV text, with `#`
//! comment lines and blank lines anywhere, an optional preamble of `Key: value` lines
//! before the header row (the units, the direction of a run, what X is), a header row whose
//! cells name a quantity and, in it, its unit (`Target (mm)`, `Run 1 Fwd [µm]`,
//! `deviation_mm`), and rows of values. Cells are separated by commas, or by semicolons or
//! tabs when the header row has no comma (a spreadsheet's export in a locale whose decimal
//! mark is the comma; there a number may be written with a decimal comma).
//!
//! This module reads the file's form and nothing of its meaning: each kind of measurement
//! has one reader that maps the columns onto its quantities (`diagnose::measured` for ball
//! bar traces and CMM profiles, `error_model::interferometer` for slide tables), and a new
//! layout of an instrument is a mapping there. Every problem is a [`DataError`] at the line
//! and the text it is about, with a hint where one is likely.

mod columns;
#[cfg(test)]
pub(crate) mod tests;

pub use columns::{ColumnName, Unit, column_name};

use crate::source::Span;

/// What is wrong with a measurement file: the line of the file (counting the preamble,
/// header and comments), the text it is about (a value, a header cell, a preamble line, or
/// the line) and what is wrong; `unknown_column` when it is a header cell the reader cannot
/// place (the model file's diagnostics name it so).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("line {line}: {message}")]
pub struct DataError {
    pub line: usize,
    pub span: Span,
    pub label: &'static str,
    pub message: String,
    /// What was probably meant, or what would place the column or value.
    pub hint: Option<String>,
    /// The name of a header cell that names no column the reader knows.
    pub unknown_column: Option<String>,
}

impl DataError {
    pub fn new(line: usize, span: Span, label: &'static str, message: impl Into<String>) -> DataError {
        DataError { line, span, label, message: message.into(), hint: None, unknown_column: None }
    }

    pub fn with_hint(mut self, hint: impl Into<String>) -> DataError {
        self.hint = Some(hint.into());
        self
    }
}

/// One `Key: value` line of the preamble.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// The key in lower case, its words joined by `_` (`Start Angle` is `start_angle`).
    pub key: String,
    /// The value as written, without blanks, quotes and separators around it.
    pub value: String,
    pub line: usize,
    /// The key's text and the value's.
    pub key_span: Span,
    pub value_span: Span,
}

/// A header cell: its text (without blanks and quotes) and where it is.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    pub text: String,
    pub span: Span,
}

/// A measurement file being read: its preamble and header, and its rows one at a time.
pub struct DataFile<'t> {
    text: &'t str,
    /// Where the header row starts: the CSV reader reads from there.
    base: usize,
    delimiter: u8,
    pub preamble: Vec<Entry>,
    pub header: Vec<Cell>,
    pub header_line: usize,
    reader: csv::Reader<&'t [u8]>,
    lines: RecordLines<'t>,
    record: csv::StringRecord,
    rows: usize,
}

/// A row: its line, the span of the line, its cells' spans and values.
pub struct Row<'r> {
    pub line: usize,
    pub span: Span,
    cells: Vec<Span>,
    record: &'r csv::StringRecord,
    decimal_comma: bool,
}

/// Whether the line `line` (without its line break) of a preamble is a `Key: value` line:
/// its key and value, each with its byte range in the line.
fn preamble_entry(line: &str) -> Option<((usize, usize), (usize, usize))> {
    let colon = line.find(':')?;
    let key = line[..colon].trim().trim_matches('"').trim();
    // A key is words: it starts with a letter and holds no cell separator.
    if key.is_empty() || !key.starts_with(|c: char| c.is_alphabetic()) || key.contains([',', ';', '\t']) {
        return None;
    }
    let key_start = line.find(key)?;
    let rest = &line[colon + 1..];
    let value = rest.trim_matches(|c: char| c.is_whitespace() || matches!(c, ',' | ';' | '\t' | '"'));
    let value_start = if value.is_empty() { colon + 1 } else { colon + 1 + rest.find(value)? };
    Some(((key_start, key_start + key.len()), (value_start, value_start + value.len())))
}

/// A key's words in lower case, joined by `_`.
pub fn normal_key(key: &str) -> String {
    key.to_lowercase().split(|c: char| !c.is_alphanumeric()).filter(|w| !w.is_empty()).collect::<Vec<_>>().join("_")
}

impl<'t> DataFile<'t> {
    /// Read the preamble and the header row of `text`.
    pub fn open(text: &'t str) -> Result<DataFile<'t>, DataError> {
        let mut preamble = Vec::new();
        let mut at = 0;
        let mut line = 1;
        let header = loop {
            if at >= text.len() {
                let end = Span::new(text.len() as u32, text.len() as u32);
                let message = if preamble.is_empty() { "the file is empty" } else { "the file has no header row" };
                return Err(DataError::new(line, end, "here", message));
            }
            let (end, next) = next_line_end(text.as_bytes(), at, text.len()).unwrap_or((text.len(), text.len()));
            let content = &text[at..end];
            let trimmed = content.trim();
            if !(trimmed.is_empty() || trimmed.starts_with('#')) {
                match preamble_entry(content) {
                    Some(((k0, k1), (v0, v1))) => preamble.push(Entry {
                        key: normal_key(&content[k0..k1]),
                        value: content[v0..v1].to_string(),
                        line,
                        key_span: Span::new((at + k0) as u32, (at + k1) as u32),
                        value_span: Span::new((at + v0) as u32, (at + v1) as u32),
                    }),
                    None => break (at, line),
                }
            }
            line += 1;
            at = next;
        };
        let (base, header_line) = header;
        let header_text = &text[base..next_line_end(text.as_bytes(), base, text.len()).map_or(text.len(), |e| e.0)];
        let delimiter = if header_text.contains(',') {
            b','
        } else if header_text.contains(';') {
            b';'
        } else if header_text.contains('\t') {
            b'\t'
        } else {
            b','
        };
        let reader = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            .flexible(true)
            .has_headers(false)
            .delimiter(delimiter)
            .from_reader(&text.as_bytes()[base..]);
        let mut file = DataFile {
            text,
            base,
            delimiter,
            preamble,
            header: Vec::new(),
            header_line,
            reader,
            lines: RecordLines::new(text),
            record: csv::StringRecord::new(),
            rows: 0,
        };
        let Some((line, line_span, cells)) = file.next_record()? else {
            let end = Span::new(text.len() as u32, text.len() as u32);
            return Err(DataError::new(header_line, end, "here", "the file has no header row"));
        };
        // The header is the first record that is not blank, which may be below the line the
        // preamble ends on; a quoted cell that runs over a line break has no span of its
        // own on the line, and takes the line's.
        file.header_line = line;
        file.header = file
            .record
            .iter()
            .enumerate()
            .map(|(i, value)| Cell { text: value.to_string(), span: cells.get(i).copied().unwrap_or(line_span) })
            .collect();
        file.rows = 0;
        Ok(file)
    }

    /// The preamble's entry for `key` (normalised, `start_angle`), if it has one.
    pub fn meta(&self, key: &str) -> Option<&Entry> {
        self.preamble.iter().find(|e| e.key == key)
    }

    /// The preamble's entry for the first of `keys` it has.
    pub fn meta_any(&self, keys: &[&str]) -> Option<&Entry> {
        keys.iter().find_map(|k| self.meta(k))
    }

    /// Refuse a preamble key near one of `known` but not it (a misspelt `untis: um` would
    /// otherwise be read as an instrument's remark and leave the values in the wrong unit).
    /// Keys far from every known one are the instrument's remarks (machine, operator, date)
    /// and are left alone.
    pub fn check_preamble(&self, known: &[&str]) -> Result<(), DataError> {
        for entry in &self.preamble {
            if known.contains(&entry.key.as_str()) {
                continue;
            }
            let near = known
                .iter()
                .map(|k| (strsim::jaro_winkler(&entry.key, k), *k))
                .filter(|(score, _)| *score >= 0.9)
                .max_by(|a, b| a.0.total_cmp(&b.0));
            if let Some((_, near)) = near {
                let message = format!("the preamble key `{}` is none this reader takes", entry.key);
                return Err(DataError::new(entry.line, entry.key_span, "unknown key", message)
                    .with_hint(format!("did you mean `{near}`?")));
            }
        }
        Ok(())
    }

    /// The error of the whole header row.
    pub fn header_error(&self, label: &'static str, message: impl Into<String>) -> DataError {
        let start = self.header.iter().map(|c| c.span.start).min();
        let end = self.header.iter().map(|c| c.span.end).max();
        let span = match (start, end) {
            (Some(start), Some(end)) => Span::new(start, end),
            _ => Span::new(self.base as u32, self.base as u32),
        };
        DataError::new(self.header_line, span, label, message)
    }

    /// The error of header cell `i`.
    pub fn cell_error(&self, i: usize, label: &'static str, message: impl Into<String>) -> DataError {
        let span = self.header.get(i).map_or(Span::new(self.base as u32, self.base as u32), |c| c.span);
        DataError::new(self.header_line, span, label, message)
    }

    /// The error of a preamble entry's value.
    pub fn meta_error(entry: &Entry, label: &'static str, message: impl Into<String>) -> DataError {
        DataError::new(entry.line, entry.value_span, label, message)
    }

    /// How many rows of values have been read.
    pub fn rows_read(&self) -> usize {
        self.rows
    }

    /// The next record that is not blank: its line, the line's span and its cells' spans.
    fn next_record(&mut self) -> Result<Option<(usize, Span, Vec<Span>)>, DataError> {
        loop {
            let read = self.reader.read_record(&mut self.record).map_err(|e| {
                let line = e.position().map_or(self.header_line, |p| self.lines.line_of(p.byte() + self.base as u64));
                let span = line_span(self.text, &mut self.lines, line);
                DataError::new(line, span, "here", e.to_string())
            })?;
            if !read {
                return Ok(None);
            }
            #[cfg(test)]
            tests::count_row_read();
            if self.record.len() == 1 && self.record[0].is_empty() {
                continue;
            }
            let line = self.record.position().map_or(1, |p| self.lines.line_of(p.byte() + self.base as u64));
            let span = line_span(self.text, &mut self.lines, line);
            let cells = line_cells(self.text, span.start as usize, self.delimiter);
            return Ok(Some((line, span, cells)));
        }
    }

    /// The next row of values, read and not yet checked.
    pub fn next_row(&mut self) -> Result<Option<Row<'_>>, DataError> {
        let Some((line, span, cells)) = self.next_record()? else { return Ok(None) };
        self.rows += 1;
        Ok(Some(Row { line, span, cells, record: &self.record, decimal_comma: self.delimiter != b',' }))
    }

    /// The rows, each read and checked by `each` before the next is read (the first bad one
    /// ends the reading); a file with a header and no rows is refused.
    pub fn rows(&mut self, mut each: impl FnMut(&Row<'_>) -> Result<(), DataError>) -> Result<(), DataError> {
        while let Some(row) = self.next_row()? {
            each(&row)?;
        }
        if self.rows > 0 { Ok(()) } else { Err(self.header_error("this header", "the file has a header but no rows")) }
    }
}

impl Row<'_> {
    /// The span of cell `column`, else of the line.
    pub fn span(&self, column: usize) -> Span {
        self.cells.get(column).copied().unwrap_or(self.span)
    }

    pub fn error(&self, column: usize, label: &'static str, message: impl Into<String>) -> DataError {
        DataError::new(self.line, self.span(column), label, message)
    }

    /// Cell `column`'s text, empty when the row has no such cell.
    pub fn cell(&self, column: usize) -> &str {
        self.record.get(column).unwrap_or("")
    }

    /// Cell `column`'s text; an empty one is refused.
    pub fn text(&self, column: usize, name: &str) -> Result<&str, DataError> {
        match self.record.get(column) {
            Some(value) if !value.is_empty() => Ok(value),
            _ => Err(self.error(column, "no value", format!("no value for `{name}`"))),
        }
    }

    /// Cell `column` as a finite number; an empty one is refused.
    pub fn number(&self, column: usize, name: &str) -> Result<f64, DataError> {
        let text = self.text(column, name)?;
        self.parse(column, name, text)
    }

    /// Cell `column` as a finite number, or `None` when it is empty.
    pub fn number_or_empty(&self, column: usize, name: &str) -> Result<Option<f64>, DataError> {
        match self.record.get(column) {
            Some(text) if !text.is_empty() => self.parse(column, name, text).map(Some),
            _ => Ok(None),
        }
    }

    fn parse(&self, column: usize, name: &str, text: &str) -> Result<f64, DataError> {
        let value = if self.decimal_comma && text.matches(',').count() == 1 && !text.contains('.') {
            text.replace(',', ".").parse::<f64>()
        } else {
            text.parse::<f64>()
        };
        match value {
            Ok(value) if value.is_finite() => Ok(value),
            _ => {
                let mut error =
                    self.error(column, "not a finite number", format!("`{name}` is `{text}`, not a finite number"));
                // OCR and typing put the letter O for a zero, as in programs.
                let zeros = text.replace(['O', 'o'], "0");
                if zeros != text && zeros.parse::<f64>().is_ok_and(f64::is_finite) {
                    error.hint = Some(format!("`O` typed for `0`? did you mean `{zeros}`?"));
                } else if text.contains(',') && text.replace(',', ".").parse::<f64>().is_ok_and(f64::is_finite) {
                    error.hint = Some(format!("a decimal comma? write `{}`", text.replace(',', ".")));
                }
                Err(error)
            }
        }
    }
}

/// The span of line `line` (1-based) of `text`, without its line break.
fn line_span(text: &str, lines: &mut RecordLines<'_>, line: usize) -> Span {
    let start = lines.start_of(line);
    let rest = &text[start..];
    let end = start + rest.find(['\n', '\r']).unwrap_or(rest.len());
    Span::new(start as u32, end as u32)
}

/// The spans of the cells of the line that starts at byte `start` of `text`, one per cell
/// separated by `delimiter`, each without its blanks and quotes (a quoted cell with the
/// separator in it shifts the ones after it; the cells of these files are numbers and
/// names).
pub(crate) fn line_cells(text: &str, start: usize, delimiter: u8) -> Vec<Span> {
    let line_end = text[start..].find(['\n', '\r']).map_or(text.len(), |n| start + n);
    let mut cells = Vec::new();
    let mut cell_start = start;
    for piece in text[start..line_end].split(char::from(delimiter)) {
        // The cell is the piece without its blanks and quotes, however many: its place is
        // where that slice starts in the piece.
        let trimmed = piece.trim().trim_matches('"');
        let from = cell_start + (trimmed.as_ptr() as usize - piece.as_ptr() as usize);
        cells.push(Span::new(from as u32, (from + trimmed.len()) as u32));
        cell_start += piece.len() + 1;
    }
    cells
}

/// The 1-based lines of the CSV records of a text, found as a reader goes through it. The
/// reader's own line count skips blank lines, and a record's position is where the reader
/// started looking for it, before the blank and `#` comment lines it passed over: lines are
/// counted up to the position, then over those. Positions come in order, so each count goes
/// on from the last one and reading a file is one pass over its text, not one per row.
pub struct RecordLines<'t> {
    text: &'t str,
    /// Where each line starts, up to the furthest line counted.
    starts: Vec<usize>,
}

impl<'t> RecordLines<'t> {
    pub fn new(text: &'t str) -> RecordLines<'t> {
        RecordLines { text, starts: vec![0] }
    }

    /// Count lines up to byte `to`.
    fn count_to(&mut self, to: usize) {
        let from = self.starts.last().copied().unwrap_or(0);
        if to > from {
            #[cfg(test)]
            tests::count_looked_at(to - from);
            let mut at = from;
            while let Some((_, next)) = next_line_end(self.text.as_bytes(), at, to) {
                if next > to {
                    break;
                }
                self.starts.push(next);
                at = next;
            }
        }
    }

    /// The line of the record a reader found at `byte`.
    pub fn line_of(&mut self, byte: u64) -> usize {
        let mut at = (byte as usize).min(self.text.len());
        let mut line = self.line_at(at);
        loop {
            let (piece, next) = match next_line_end(self.text.as_bytes(), at, self.text.len()) {
                Some((end, next)) => (&self.text[at..end], Some(next)),
                None => (&self.text[at..], None),
            };
            #[cfg(test)]
            tests::count_looked_at(piece.len());
            let trimmed = piece.trim();
            if !(trimmed.is_empty() || trimmed.starts_with('#')) {
                return line;
            }
            line += 1;
            match next {
                Some(next) => at = next,
                None => return line,
            }
        }
    }

    /// The 1-based line that byte `at` is on.
    fn line_at(&mut self, at: usize) -> usize {
        self.count_to(at);
        self.starts.partition_point(|&s| s <= at).max(1)
    }

    /// Where line `line` (1-based) starts, counting lines as far as needed.
    pub fn start_of(&mut self, line: usize) -> usize {
        while self.starts.len() < line {
            let from = self.starts.last().copied().unwrap_or(0);
            let found = next_line_end(self.text.as_bytes(), from, self.text.len());
            #[cfg(test)]
            tests::count_looked_at(found.map_or(self.text.len() - from, |(_, next)| next - from));
            match found {
                Some((_, next)) => self.starts.push(next),
                None => return self.text.len(),
            }
        }
        self.starts[line.max(1) - 1]
    }
}

/// The first line end in `text[from..to]`: where the line's text ends and where the next
/// line starts. A line ends at LF, CR LF or a lone CR, as [`crate::source::LineIndex`]
/// counts lines and as the CSV reader ends records; a CR LF cut by `to` still counts as one
/// end.
fn next_line_end(text: &[u8], from: usize, to: usize) -> Option<(usize, usize)> {
    let at = from + memchr::memchr2(b'\n', b'\r', &text[from..to])?;
    let next = if text[at] == b'\r' && text.get(at + 1) == Some(&b'\n') { at + 2 } else { at + 1 };
    Some((at, next))
}
