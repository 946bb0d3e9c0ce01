//! Code actions: a quick fix for each diagnostic whose hint names its repair
//! (`Diagnostic::fix`), and renumbering a Fanuc program's sequence numbers.

use std::collections::HashMap;

use lsp_types::{CodeAction, CodeActionKind, TextEdit, Uri, WorkspaceEdit};

use crate::source::Span;

use super::analysis::{self, Pass};
use super::document::Document;
use super::rename;

/// The title of the renumbering action.
pub const RENUMBER: &str = "Renumber the sequence numbers N10, N20, … (P, Q, GOTO follow)";

/// The quick fixes of the parse diagnostics that touch bytes `range`.
pub fn quick_fixes(document: &Document, uri: &Uri, range: std::ops::Range<usize>) -> Vec<CodeAction> {
    let mut actions = Vec::new();
    for diagnostic in document.diagnostics_near(range) {
        let line = document.position_of(diagnostic.span.start as usize, false).line;
        let Some((line_start, text)) = document.line(line) else { continue };
        let Some(fix) = diagnostic.fix(text, line_start) else { continue };
        actions.push(CodeAction {
            title: fix.title,
            kind: Some(CodeActionKind::QUICKFIX),
            diagnostics: Some(vec![analysis::to_lsp(document, uri, &diagnostic, Pass::Syntax)]),
            edit: Some(edit(document, uri, fix.edits)),
            is_preferred: Some(true),
            ..CodeAction::default()
        });
    }
    actions
}

/// The renumbering action, with its edit when `resolved` (else the client asks for it with
/// `codeAction/resolve`, and `data` says which document); `None` when it does not apply.
pub fn renumbering(document: &Document, uri: &Uri, resolved: bool) -> Option<CodeAction> {
    let mut action = CodeAction {
        title: RENUMBER.to_string(),
        kind: Some(CodeActionKind::REFACTOR_REWRITE),
        data: Some(serde_json::json!({ "renumber": uri })),
        ..CodeAction::default()
    };
    if resolved {
        match rename::renumber(document)? {
            Ok(edits) if edits.is_empty() => {
                let reason = "the sequence numbers are N10, N20, … already".to_string();
                action.disabled = Some(lsp_types::CodeActionDisabled { reason });
            }
            Ok(edits) => action.edit = Some(edit(document, uri, edits)),
            Err(why) => action.disabled = Some(lsp_types::CodeActionDisabled { reason: why }),
        }
    } else if document.config().dialect != crate::dialect::Dialect::Fanuc {
        return None;
    }
    Some(action)
}

/// Edits of one document as a workspace edit.
pub fn edit(document: &Document, uri: &Uri, edits: Vec<(Span, String)>) -> WorkspaceEdit {
    let edits = edits.into_iter().map(|(span, new_text)| TextEdit { range: document.range(span), new_text }).collect();
    WorkspaceEdit { changes: Some(HashMap::from([(uri.clone(), edits)])), ..WorkspaceEdit::default() }
}
