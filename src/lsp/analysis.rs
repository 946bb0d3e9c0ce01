//! Diagnostics for the editor: the parse's and the semantic pass's.
//!
//! The diagnostics are the ones `turnpass check` reports, with the same codes, messages and
//! spans; the protocol wants ranges in lines and UTF-16 columns (`position.rs`). A label
//! and a hint have no field of their own in the protocol: the hint is the message's second
//! line (`hint: …`), where every editor shows it, and both travel in `data` for tools,
//! with the byte offsets of the span and the pass that found it (`syntax` or `semantic`).
//!
//! **The semantic pass runs on a program with parse errors too**, as `check` runs it: the
//! blocks that parsed are checked, and the interpreter leaves out only what depends on a
//! damaged block (a `P`/`Q` naming it, a profile holding it, the position after it), so a
//! typo in `N20 G01 X1O.` gets its parse error and no "missing `N20`" on `G71 P20`.

use lsp_types::{DiagnosticRelatedInformation, DiagnosticSeverity, Location, NumberOrString, Uri};

use crate::diagnostic::{Diagnostic, Severity};
use crate::machine::{MachineSettings, StockSettings};
use crate::semantic::{LowerOptions, Machine};
use crate::source::Span;

use super::document::{Document, Snapshot};

/// The `source` of every diagnostic the server publishes.
pub const SOURCE: &str = "turnpass";

/// A run of the semantic pass over one version of a document. It owns what it needs, so it
/// can run on another thread while the editor goes on typing.
#[derive(Debug, Clone)]
pub struct SemanticJob {
    pub snapshot: Snapshot,
    pub machine: Machine,
    pub options: LowerOptions,
    /// The part model's stock, as `check` and `simulate` run it.
    pub part: crate::part::PartCheck,
}

impl SemanticJob {
    pub fn new(snapshot: Snapshot, settings: &MachineSettings, stock: Option<StockSettings>) -> SemanticJob {
        // As `simulate` runs it: nose-radius compensation on, the machine's block-delete switch.
        let options = LowerOptions::new(settings.block_delete_switch());
        let part = crate::part::PartCheck { stock };
        SemanticJob { snapshot, machine: Machine::from_settings(settings), options, part }
    }

    /// The semantic pass's diagnostics (none for a program it does not lower), the part
    /// model's among them.
    pub fn run(&self) -> Vec<Diagnostic> {
        crate::pipeline::semantic_diagnostics(&self.snapshot.program(), &self.machine, &self.options, Some(&self.part))
    }
}

/// Which pass found a diagnostic; `data.pass` says it to tools (`check` reports the parse's).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pass {
    Syntax,
    Semantic,
}

impl Pass {
    pub fn as_str(self) -> &'static str {
        match self {
            Pass::Syntax => "syntax",
            Pass::Semantic => "semantic",
        }
    }
}

/// How many diagnostics the server publishes for a document unless the client says
/// otherwise (`maxDiagnostics`): the crate's one cap. The protocol sends a document's whole
/// list after every keystroke, and each one costs a few microseconds to convert and
/// serialise, so a program with one on every block would cost a keystroke tens of
/// milliseconds; `turnpass check` lists them all.
pub const DEFAULT_MAX_DIAGNOSTICS: usize = crate::diagnostic::SHOWN_DIAGNOSTICS;

/// What the server publishes for a document: its parse diagnostics and the semantic pass's
/// (moved across the edits since), merged in order as `parse` sorts (the parse's first on a
/// tie). Only `limit` are converted; when there are more, the ones shown are those nearest
/// `focus` (where the user last edited; the first ones when there is no edit yet, as on
/// opening), and a note at the nearest one left out says how many are not shown.
pub fn publishable(
    document: &Document,
    uri: &Uri,
    semantic: &SemanticDiagnostics,
    limit: usize,
    focus: Option<usize>,
) -> Vec<lsp_types::Diagnostic> {
    match focus {
        Some(focus) if limit < usize::MAX => match near(document, uri, semantic, limit, focus) {
            Some(published) => published,
            None => first(document, uri, semantic, limit),
        },
        _ => first(document, uri, semantic, limit),
    }
}

/// The `limit` diagnostics nearest byte `focus`, in order, and the note; `None` when the
/// first `limit` are all there are or the nearest are the first ones anyway.
fn near(
    document: &Document,
    uri: &Uri,
    semantic: &SemanticDiagnostics,
    limit: usize,
    focus: usize,
) -> Option<Vec<lsp_types::Diagnostic>> {
    let (_, syntax_total) = document.first_diagnostics(0);
    let total = syntax_total + semantic.len();
    if total <= limit {
        return None;
    }
    // Candidates: `limit` on each side of the focus from each pass; the nearest `limit`
    // of them are the nearest of all.
    let mut candidates: Vec<(Diagnostic, Pass)> =
        document.diagnostics_around(focus, limit).into_iter().map(|d| (d, Pass::Syntax)).collect();
    candidates.extend(semantic.around(focus, limit).map(|d| (d, Pass::Semantic)));
    candidates.sort_by_key(|(d, pass)| (d.span.start, d.span.end, *pass == Pass::Semantic));
    let distance = |d: &Diagnostic| {
        let (start, end) = (d.span.start as usize, d.span.end as usize);
        if focus < start { start - focus } else { focus.saturating_sub(end) }
    };
    // The window of `limit` consecutive candidates nearest the focus: the distance grows
    // away from the focus on both sides, so a window's farthest is one of its ends.
    let reach = |from: usize| distance(&candidates[from].0).max(distance(&candidates[from + limit - 1].0));
    let mut from = 0;
    for start in 1..=candidates.len().saturating_sub(limit) {
        if reach(start) < reach(from) {
            from = start;
        }
    }
    if from == 0 {
        return None;
    }
    let to = (from + limit).min(candidates.len());
    let mut published: Vec<lsp_types::Diagnostic> =
        candidates[from..to].iter().map(|(d, pass)| to_lsp(document, uri, d, *pass)).collect();
    // The note goes at the nearest one left out: after the window, else before it.
    let left_out = candidates.get(to).or_else(|| candidates.get(from - 1)).map(|(d, _)| d)?;
    let note = omitted(document, left_out, total - published.len(), false);
    let at = if left_out.span.start as usize >= focus { published.len() } else { 0 };
    published.insert(at, note);
    Some(published)
}

/// The first `limit` diagnostics and the note at the first one left out.
fn first(document: &Document, uri: &Uri, semantic: &SemanticDiagnostics, limit: usize) -> Vec<lsp_types::Diagnostic> {
    // One more than shown, so that the first one left out is known exactly.
    let (syntax, syntax_total) = document.first_diagnostics(limit.saturating_add(1));
    let total = syntax_total + semantic.len();
    let mut published = Vec::with_capacity(total.min(limit) + 1);
    let (mut syntax, mut semantic) = (syntax.into_iter().peekable(), semantic.iter().peekable());
    let key = |d: &Diagnostic| (d.span.start, d.span.end);
    loop {
        let next = match (syntax.peek(), semantic.peek()) {
            (Some(parse), Some(pass)) if key(pass) < key(parse) => semantic.next().map(|d| (d, Pass::Semantic)),
            (Some(_), _) => syntax.next().map(|d| (d, Pass::Syntax)),
            (None, _) => semantic.next().map(|d| (d, Pass::Semantic)),
        };
        let Some((diagnostic, pass)) = next else { break };
        if published.len() == limit {
            published.push(omitted(document, &diagnostic, total - limit, true));
            break;
        }
        published.push(to_lsp(document, uri, &diagnostic, pass));
    }
    published
}

/// The note that stands for the `count` diagnostics left out, at the first of them (all
/// after it when `after`), or the nearest to an edit.
fn omitted(document: &Document, first: &Diagnostic, count: usize, after: bool) -> lsp_types::Diagnostic {
    let message = format!(
        "{count} more problem{} {}{} not shown; `turnpass check` lists them all",
        if count == 1 { "" } else { "s" },
        if after { "from here on " } else { "away from the edit " },
        if count == 1 { "is" } else { "are" },
    );
    lsp_types::Diagnostic {
        range: document.range(first.span),
        severity: Some(DiagnosticSeverity::INFORMATION),
        code: Some(NumberOrString::String("more-diagnostics".to_string())),
        source: Some(SOURCE.to_string()),
        message,
        data: Some(serde_json::json!({
            "offset": { "start": first.span.start, "end": first.span.end },
            "omitted": count,
            "pass": "server",
        })),
        ..lsp_types::Diagnostic::default()
    }
}

/// A diagnostic in the protocol's terms.
pub fn to_lsp(document: &Document, uri: &Uri, diagnostic: &Diagnostic, pass: Pass) -> lsp_types::Diagnostic {
    let range = document.range(diagnostic.span);
    let related: Vec<DiagnosticRelatedInformation> = diagnostic
        .related
        .iter()
        .map(|(span, message)| DiagnosticRelatedInformation {
            location: Location { uri: uri.clone(), range: document.range(*span) },
            message: message.clone(),
        })
        .collect();
    let hint = diagnostic.hint();
    // The hint goes in the message: editors show the message everywhere (virtual text,
    // the problems list, the echo area) and related information rarely.
    let mut message = match &hint {
        Some(hint) => format!("{}\nhint: {hint}", diagnostic.message()),
        None => diagnostic.message(),
    };
    if let Some(repeats) = diagnostic.repeats_note() {
        message.push_str(&format!("\n{repeats}"));
    }
    lsp_types::Diagnostic {
        range,
        severity: Some(match diagnostic.severity {
            Severity::Error => DiagnosticSeverity::ERROR,
            Severity::Warning => DiagnosticSeverity::WARNING,
            Severity::Note => DiagnosticSeverity::INFORMATION,
        }),
        code: Some(NumberOrString::String(diagnostic.code().to_string())),
        code_description: None,
        source: Some(SOURCE.to_string()),
        message,
        related_information: if related.is_empty() { None } else { Some(related) },
        tags: None,
        data: Some(serde_json::json!({
            "label": diagnostic.label(),
            "hint": hint,
            "offset": { "start": diagnostic.span.start, "end": diagnostic.span.end },
            "pass": pass.as_str(),
        })),
    }
}

/// The semantic pass's diagnostics of an earlier version of a document, followed across the
/// edits since: those after an edit move, those with an edit inside them stretch, those an
/// edit crosses the edge of go.
///
/// A program read with the wrong settings can have a diagnostic on every block, and every
/// keystroke moves them all; their spans are therefore kept apart, eight bytes each, so that
/// moving a hundred thousand of them stays a short loop, and a diagnostic is copied out only
/// when a publish shows it.
#[derive(Debug, Clone, Default)]
pub struct SemanticDiagnostics {
    /// As the pass reported them, sorted by position (their related spans kept moved).
    reported: Vec<Diagnostic>,
    /// Each one's span now; `None` once an edit touched its text.
    spans: Vec<Option<Span>>,
    alive: usize,
    /// The ones with related spans (few: those of LAP contours).
    with_related: Vec<usize>,
}

impl SemanticDiagnostics {
    pub fn new(mut reported: Vec<Diagnostic>) -> SemanticDiagnostics {
        reported.sort_by_key(|d| (d.span.start, d.span.end));
        let spans = reported.iter().map(|d| Some(d.span)).collect();
        let with_related = (0..reported.len()).filter(|&i| !reported[i].related.is_empty()).collect();
        SemanticDiagnostics { alive: reported.len(), reported, spans, with_related }
    }

    /// How many are left.
    pub fn len(&self) -> usize {
        self.alive
    }

    pub fn is_empty(&self) -> bool {
        self.alive == 0
    }

    pub fn clear(&mut self) {
        *self = SemanticDiagnostics::default();
    }

    /// Those left, in position order, at their spans now.
    pub fn iter(&self) -> impl Iterator<Item = Diagnostic> + '_ {
        self.reported
            .iter()
            .zip(&self.spans)
            .filter_map(|(diagnostic, span)| Some(Diagnostic { span: (*span)?, ..diagnostic.clone() }))
    }

    /// At most `per_side` on each side of byte `focus`, in position order, at their spans
    /// now. One pass over the spans, no copy of them.
    pub fn around(&self, focus: usize, per_side: usize) -> impl Iterator<Item = Diagnostic> + '_ {
        let split =
            self.spans.iter().position(|s| s.is_some_and(|s| s.end as usize >= focus)).unwrap_or(self.spans.len());
        let alive = |(_, span): &(usize, &Option<Span>)| span.is_some();
        let from =
            self.spans[..split].iter().enumerate().rev().filter(alive).take(per_side).last().map_or(split, |(i, _)| i);
        let to = self.spans[split..]
            .iter()
            .enumerate()
            .filter(alive)
            .take(per_side)
            .last()
            .map_or(split, |(i, _)| split + i + 1);
        (from..to).filter_map(move |i| Some(Diagnostic { span: self.spans[i]?, ..self.reported[i].clone() }))
    }

    /// Whether these are the diagnostics a pass reported (`reported`, in any order), at the
    /// same places and in the same words: a finished pass that changes nothing the editor
    /// shows need not be published again. Diagnostics on one span compare as sets.
    pub fn same_as(&self, reported: &[Diagnostic]) -> bool {
        if reported.len() != self.alive {
            return false;
        }
        let key = |d: &Diagnostic| (d.span.start, d.span.end, d.code(), d.severity);
        let mut shown: Vec<Diagnostic> = self.iter().collect();
        let mut found: Vec<&Diagnostic> = reported.iter().collect();
        shown.sort_by_key(|d| key(d));
        found.sort_by_key(|d| key(d));
        let mut from = 0;
        while from < shown.len() {
            let group = key(&shown[from]);
            let to = from + shown[from..].iter().take_while(|d| key(d) == group).count();
            let alike =
                found[from..to].iter().all(|f| key(f) == group && shown[from..to].iter().any(|s| reads_alike(s, f)));
            if !alike {
                return false;
            }
            from = to;
        }
        true
    }

    /// Follow an edit that replaced `removed` (old offsets) by `inserted`. The order is kept:
    /// every span after the edit moves by the same amount.
    pub fn move_across_edit(&mut self, removed: std::ops::Range<usize>, inserted: &[u8]) {
        let edit = Edit::new(removed, inserted);
        for span in &mut self.spans {
            if let Some(current) = *span {
                *span = edit.stretch(current);
                if span.is_none() {
                    self.alive -= 1;
                }
            }
        }
        for &index in &self.with_related {
            if let Some(diagnostic) = self.reported.get_mut(index) {
                // A related span the edit touched goes; the diagnostic stays.
                diagnostic.related.retain_mut(|(related, _)| match edit.apply(*related) {
                    Some(moved) => {
                        *related = moved;
                        true
                    }
                    None => false,
                });
            }
        }
    }
}

/// Whether two diagnostics show the same: equal, or at the same spans with the same words
/// (a value that reads `X56.1530` instead of `X56.153` can differ in its last bit, not in
/// the message).
fn reads_alike(shown: &Diagnostic, found: &Diagnostic) -> bool {
    shown == found
        || (shown.span == found.span
            && shown.severity == found.severity
            && shown.related == found.related
            && shown.words() == found.words())
}

/// An edit in byte offsets: `start..end` of the old text replaced by `inserted` bytes.
#[derive(Clone, Copy)]
struct Edit {
    start: i64,
    end: i64,
    delta: i64,
    /// The inserted text holds no line break: typed at the end of a block, it is part of it.
    same_line: bool,
}

impl Edit {
    fn new(removed: std::ops::Range<usize>, inserted: &[u8]) -> Edit {
        let (start, end) = (removed.start as i64, removed.end as i64);
        let same_line = !inserted.iter().any(|&c| c == b'\n' || c == b'\r');
        Edit { start, end, delta: inserted.len() as i64 - (end - start), same_line }
    }

    /// Where a diagnostic's span is in the new text: as [`Edit::apply`], and stretched or
    /// shrunk with an edit inside it (a digit typed in a block the diagnostic covers): the
    /// diagnostic stays shown until the pass has looked at the new text, so a keystroke
    /// that changes nothing does not make it flicker away and back (two publishes).
    fn stretch(self, span: Span) -> Option<Span> {
        let (s, e) = (span.start as i64, span.end as i64);
        let stretched = Some(Span::new(s as u32, (e + self.delta) as u32));
        // Typed at its end: on the same line it grows (`X20.` becoming `X20.5` at the end of a
        // block); a line break there starts something else.
        if self.start == e && self.end == e && s < e {
            return if self.same_line { stretched } else { Some(span) };
        }
        if e > self.start && s < self.end && s <= self.start && self.end <= e {
            return stretched;
        }
        self.apply(span)
    }

    /// Where a span of the old text is in the new: the same before the edit, moved after
    /// it, `None` when the edit touched it.
    fn apply(self, span: Span) -> Option<Span> {
        let (s, e) = (span.start as i64, span.end as i64);
        if e <= self.start {
            Some(span)
        } else if s >= self.end {
            Some(Span::new((s + self.delta) as u32, (e + self.delta) as u32))
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests;
