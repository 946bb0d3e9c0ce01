//! Diagnostics for the editor: the parse's, and the semantic pass's once the program parses.
//!
//! The diagnostics are the ones `turnpass check` reports, with the same codes, messages and
//! spans; the protocol wants ranges in lines and UTF-16 columns (`position.rs`). A label
//! and a hint have no field of their own in the protocol: the hint is added to the related
//! information at the diagnostic's own range (editors show it under the message), and both
//! travel in `data` for tools, with the byte offsets of the span and the pass that found it
//! (`syntax`: the diagnostics `check` reports; `semantic`).
//!
//! **Why the semantic pass waits for a clean parse.** An invalid block loses its words, so
//! a typo in `N20 G01 X1O.` would make `G71 P20` report a missing `N20`: the semantic pass
//! would explain the typo's consequences instead of the typo. It therefore runs when the
//! parse has no errors (warnings are fine), as `simulate` would run it.

use lsp_types::{DiagnosticRelatedInformation, DiagnosticSeverity, Location, NumberOrString, Uri};

use crate::diagnostic::{Diagnostic, Severity};
use crate::machine::MachineSettings;
use crate::semantic::{self, LowerOptions, Machine};

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
        let options = LowerOptions::new(settings.block_delete.unwrap_or(false));
        SemanticJob { snapshot, machine: Machine::from_settings(settings), options }
    }

    /// The semantic pass's diagnostics (none for a program it does not lower).
    pub fn run(&self) -> Vec<Diagnostic> {
        let program = self.snapshot.program();
        if !semantic::lowers(&program) {
            return Vec::new();
        }
        semantic::lower(&program, &self.machine, &self.options).diagnostics
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

/// What the server publishes for a document: its parse diagnostics and the semantic pass's,
/// sorted by position as `parse` sorts (the parse's first on a tie).
pub fn publishable(document: &Document, uri: &Uri, semantic: &[Diagnostic]) -> Vec<lsp_types::Diagnostic> {
    let syntax = document.diagnostics();
    let mut all: Vec<(&Diagnostic, Pass)> = Vec::with_capacity(syntax.len() + semantic.len());
    all.extend(syntax.iter().map(|d| (d, Pass::Syntax)));
    all.extend(semantic.iter().map(|d| (d, Pass::Semantic)));
    all.sort_by_key(|(d, _)| (d.span.start, d.span.end));
    let mut published = Vec::with_capacity(all.len());
    published.extend(all.into_iter().map(|(d, pass)| to_lsp(document, uri, d, pass)));
    published
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

/// Move a diagnostic's spans across an edit that replaced `removed` (old offsets) by
/// `inserted` bytes; `None` when the edit touched its text.
pub fn across_edit(diagnostic: &Diagnostic, removed: std::ops::Range<usize>, inserted: usize) -> Option<Diagnostic> {
    let (start, end) = (removed.start as i64, removed.end as i64);
    let delta = inserted as i64 - (end - start);
    let map = |span: crate::source::Span| -> Option<crate::source::Span> {
        let (s, e) = (span.start as i64, span.end as i64);
        if e <= start {
            Some(span)
        } else if s >= end {
            Some(crate::source::Span::new((s + delta) as u32, (e + delta) as u32))
        } else {
            None
        }
    };
    let span = map(diagnostic.span)?;
    let related = diagnostic.related.iter().filter_map(|(s, label)| Some((map(*s)?, label.clone()))).collect();
    Some(Diagnostic { span, related, ..diagnostic.clone() })
}
