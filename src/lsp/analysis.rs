//! Diagnostics for the editor: the parse's and the semantic pass's.
//!
//! The diagnostics are the ones `turnpass check` reports, with the same codes, messages and
//! spans; the protocol wants ranges in lines and UTF-16 columns (`position.rs`). A label
//! and a hint have no field of their own in the protocol: the hint is added to the related
//! information at the diagnostic's own range (editors show it under the message), and both
//! travel in `data` for tools, with the byte offsets of the span and the pass that found it
//! (`syntax` or `semantic`).
//!
//! **The semantic pass runs on a program with parse errors too**, as `check` runs it: the
//! blocks that parsed are checked, and the interpreter leaves out only what depends on a
//! damaged block (a `P`/`Q` naming it, a profile holding it, the position after it), so a
//! typo in `N20 G01 X1O.` gets its parse error and no "missing `N20`" on `G71 P20`.

use lsp_types::{DiagnosticRelatedInformation, DiagnosticSeverity, Location, NumberOrString, Uri};

use crate::diagnostic::{Diagnostic, Severity};
use crate::machine::MachineSettings;
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
}

impl SemanticJob {
    pub fn new(snapshot: Snapshot, settings: &MachineSettings) -> SemanticJob {
        // As `simulate` runs it: nose-radius compensation on, the machine's block-delete switch.
        let options = LowerOptions::new(settings.block_delete_switch());
        SemanticJob { snapshot, machine: Machine::from_settings(settings), options }
    }

    /// The semantic pass's diagnostics (none for a program it does not lower).
    pub fn run(&self) -> Vec<Diagnostic> {
        crate::pipeline::semantic_diagnostics(&self.snapshot.program(), &self.machine, &self.options)
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
/// tie). Only the first `limit` are converted; when there are more, a note at the first one
/// left out says how many.
pub fn publishable(
    document: &Document,
    uri: &Uri,
    semantic: &SemanticDiagnostics,
    limit: usize,
) -> Vec<lsp_types::Diagnostic> {
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
            published.push(omitted(document, &diagnostic, total - limit));
            break;
        }
        published.push(to_lsp(document, uri, &diagnostic, pass));
    }
    published
}

/// The note that stands for the `count` diagnostics left out, at the first of them.
fn omitted(document: &Document, first: &Diagnostic, count: usize) -> lsp_types::Diagnostic {
    let message = format!(
        "{count} more problem{} from here on {} not shown; `turnpass check` lists them all",
        if count == 1 { "" } else { "s" },
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
    let mut related: Vec<DiagnosticRelatedInformation> = diagnostic
        .related
        .iter()
        .map(|(span, message)| DiagnosticRelatedInformation {
            location: Location { uri: uri.clone(), range: document.range(*span) },
            message: message.clone(),
        })
        .collect();
    let hint = diagnostic.hint();
    if let Some(hint) = &hint {
        related.push(DiagnosticRelatedInformation {
            location: Location { uri: uri.clone(), range },
            message: format!("hint: {hint}"),
        });
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
        message: diagnostic.message(),
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
/// edits since: those after an edit move, those whose text it touched go.
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

    /// Follow an edit that replaced `removed` (old offsets) by `inserted` bytes. The order is
    /// kept: every span after the edit moves by the same amount.
    pub fn move_across_edit(&mut self, removed: std::ops::Range<usize>, inserted: usize) {
        let edit = Edit::new(removed, inserted);
        for span in &mut self.spans {
            if let Some(current) = *span {
                *span = edit.apply(current);
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

/// An edit in byte offsets: `start..end` of the old text replaced by `inserted` bytes.
#[derive(Clone, Copy)]
struct Edit {
    start: i64,
    end: i64,
    delta: i64,
}

impl Edit {
    fn new(removed: std::ops::Range<usize>, inserted: usize) -> Edit {
        let (start, end) = (removed.start as i64, removed.end as i64);
        Edit { start, end, delta: inserted as i64 - (end - start) }
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
