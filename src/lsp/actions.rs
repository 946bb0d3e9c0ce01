//! Code actions: a quick fix for each diagnostic whose hint names its repair
//! (`Diagnostic::fix`), and renumbering a Fanuc program's sequence numbers.

use std::collections::HashMap;

use lsp_types::{CodeAction, CodeActionKind, TextEdit, Uri, WorkspaceEdit};

use crate::source::Span;

use super::analysis::{self, Pass, SemanticDiagnostics};
use super::document::Document;
use super::rename;

/// The semantic diagnostics looked at on each side of a code action's range: more than a
/// line holds, few enough that the request stays short in a program with thousands.
const SEMANTIC_FIXES_PER_SIDE: usize = 16;

/// The title of the renumbering action.
pub const RENUMBER: &str = "Renumber the sequence numbers N10, N20, … (P, Q, GOTO follow)";

/// The quick fixes of the diagnostics that touch bytes `range`: the parse's, and the
/// semantic pass's (moved across the edits since: a fix is checked against the text now).
pub fn quick_fixes(
    document: &Document,
    uri: &Uri,
    semantic: &SemanticDiagnostics,
    range: std::ops::Range<usize>,
) -> Vec<CodeAction> {
    let mut actions = Vec::new();
    let touches =
        |d: &crate::diagnostic::Diagnostic| d.span.start as usize <= range.end && range.start <= d.span.end as usize;
    let syntax = document.diagnostics_near(range.clone()).into_iter().map(|d| (d, Pass::Syntax));
    let near = semantic.around(range.start, SEMANTIC_FIXES_PER_SIDE).filter(touches).map(|d| (d, Pass::Semantic));
    for (diagnostic, pass) in syntax.chain(near) {
        let line = document.position_of(diagnostic.span.start as usize, false).line;
        let Some((line_start, text)) = document.line(line) else { continue };
        let Some(fix) = diagnostic.fix(text, line_start) else { continue };
        actions.push(CodeAction {
            title: fix.title,
            kind: Some(CodeActionKind::QUICKFIX),
            diagnostics: Some(vec![analysis::to_lsp(document, uri, &diagnostic, pass)]),
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
