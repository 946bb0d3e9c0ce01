//! Rendering diagnostics: codespan-reporting for people (with or without colour), plain text
//! for snapshots, JSON for tools. The only module that imports codespan-reporting.
//!
//! Sources are bytes; codespan needs text. Rendering goes through [`DisplayText`], which
//! replaces bytes that are not UTF-8 with U+FFFD and maps every span across the change, so a
//! label on a Shift-JIS program still underlines the right characters.

use std::borrow::Cow;

use codespan_reporting::diagnostic::{Diagnostic as CsDiagnostic, Label, Severity as CsSeverity};
use codespan_reporting::files::SimpleFile;
use codespan_reporting::term::{self, Config};
use serde::Serialize;

use super::{Diagnostic, Severity};
use crate::source::{DisplayText, Span, escape_controls};

/// A source prepared for rendering: its name, its display text and where its lines start
/// (found once: a location is a bisection, so thousands of diagnostics cost no more than
/// one pass over the text each would otherwise make).
pub struct RenderSource<'a> {
    /// The file's name as given (JSON escapes it its own way), and as shown to people, its
    /// control characters escaped.
    name: &'a str,
    shown_name: Cow<'a, str>,
    display: DisplayText,
    line_starts: Vec<usize>,
}

impl<'a> RenderSource<'a> {
    pub fn new(name: &'a str, source: &[u8]) -> RenderSource<'a> {
        let display = DisplayText::new(source);
        let line_starts = codespan_reporting::files::line_starts(&display.text).collect();
        RenderSource { name, shown_name: escape_controls(name), display, line_starts }
    }

    fn range(&self, span: Span) -> std::ops::Range<usize> {
        let start = self.display.offset(span.start);
        let end = self.display.offset(span.end).max(start);
        start..end
    }

    fn file(&self) -> SimpleFile<&str, &str> {
        SimpleFile::new(&self.shown_name, self.display.text.as_str())
    }

    /// 1-based line and character column of a source offset, as codespan counts them, an
    /// escaped control character counting as the one character it is in the source.
    pub fn location(&self, offset: u32) -> (usize, usize) {
        let text = self.display.text.as_str();
        let at = self.display.offset(offset);
        let line = self.line_starts.partition_point(|&start| start <= at).saturating_sub(1);
        let start = self.line_starts.get(line).copied().unwrap_or(0);
        let end = self.line_starts.get(line + 1).copied().unwrap_or(text.len());
        #[cfg(test)]
        tests::count_looked_at(self.line_starts.len(), end.min(at).saturating_sub(start));
        (line + 1, self.display.source_columns(start, end.min(at).max(start)) + 1)
    }
}

fn to_codespan(diagnostic: &Diagnostic, source: &RenderSource<'_>) -> CsDiagnostic<()> {
    let severity = match diagnostic.severity {
        Severity::Note => CsSeverity::Note,
        Severity::Warning => CsSeverity::Warning,
        Severity::Error => CsSeverity::Error,
    };
    // The words may quote the program (a word, a name): shown escaped, as its text is.
    let words = diagnostic.words();
    let shown = |text: &str| escape_controls(text).into_owned();
    let mut labels = vec![Label::primary((), source.range(diagnostic.span)).with_message(shown(&words.label))];
    for (span, message) in &diagnostic.related {
        labels.push(Label::secondary((), source.range(*span)).with_message(shown(message)));
    }
    let mut notes = Vec::new();
    if let Some(hint) = words.hint {
        notes.push(format!("hint: {}", shown(&hint)));
    }
    notes.extend(diagnostic.repeats_note());
    CsDiagnostic::new(severity)
        .with_code(words.code)
        .with_message(shown(&words.message))
        .with_labels(labels)
        .with_notes(notes)
}

/// Plain text, as the terminal shows it without colour; used for snapshots.
pub fn render_plain(source: &RenderSource<'_>, diagnostics: &[Diagnostic]) -> String {
    let file = source.file();
    let config = Config::default();
    let mut out = String::new();
    for diagnostic in diagnostics {
        let cs = to_codespan(diagnostic, source);
        match term::emit_into_string(&config, &file, &cs) {
            Ok(text) => out.push_str(&text),
            Err(error) => out.push_str(&format!("{diagnostic} (could not render: {error})\n")),
        }
    }
    out
}

/// Terminal output, with ANSI colour when `color` is set (the CLI sets it on a TTY only).
pub fn render_terminal(source: &RenderSource<'_>, diagnostics: &[Diagnostic], color: bool) -> Vec<u8> {
    if !color {
        return render_plain(source, diagnostics).into_bytes();
    }
    let file = source.file();
    let config = Config::default();
    let mut buffer = term::termcolor::Buffer::ansi();
    for diagnostic in diagnostics {
        let cs = to_codespan(diagnostic, source);
        if term::emit_to_write_style(&mut buffer, &config, &file, &cs).is_err() {
            return render_plain(source, diagnostics).into_bytes();
        }
    }
    buffer.into_inner()
}

#[derive(Debug, Serialize)]
pub struct JsonPosition {
    pub line: usize,
    pub column: usize,
    pub offset: u32,
}

#[derive(Debug, Serialize)]
pub struct JsonRange {
    pub start: JsonPosition,
    pub end: JsonPosition,
}

#[derive(Debug, Serialize)]
pub struct JsonRelated {
    pub range: JsonRange,
    pub message: String,
}

/// One diagnostic for tools: file, range, severity, code, message, hint.
#[derive(Debug, Serialize)]
pub struct JsonDiagnostic {
    pub file: String,
    pub range: JsonRange,
    pub severity: &'static str,
    pub code: &'static str,
    pub message: String,
    pub label: String,
    pub hint: Option<String>,
    pub related: Vec<JsonRelated>,
    /// How many more times the run found it there (`Diagnostic::repeats`); absent for none.
    #[serde(skip_serializing_if = "is_zero")]
    pub repeats: u32,
}

fn is_zero(n: &u32) -> bool {
    *n == 0
}

fn json_range(source: &RenderSource<'_>, span: Span) -> JsonRange {
    let (line, column) = source.location(span.start);
    let (end_line, end_column) = source.location(span.end);
    JsonRange {
        start: JsonPosition { line, column, offset: span.start },
        end: JsonPosition { line: end_line, column: end_column, offset: span.end },
    }
}

pub fn to_json(source: &RenderSource<'_>, diagnostics: &[Diagnostic]) -> Vec<JsonDiagnostic> {
    diagnostics
        .iter()
        .map(|d| {
            let words = d.words();
            JsonDiagnostic {
                file: source.name.to_string(),
                range: json_range(source, d.span),
                severity: d.severity.as_str(),
                code: words.code,
                message: words.message.into_owned(),
                label: words.label.into_owned(),
                hint: words.hint.map(Cow::into_owned),
                related: d
                    .related
                    .iter()
                    .map(|(span, message)| JsonRelated { range: json_range(source, *span), message: message.clone() })
                    .collect(),
                repeats: d.repeats,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests;
