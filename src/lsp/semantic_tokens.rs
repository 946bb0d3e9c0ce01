//! Semantic tokens: colour for what a word is, as NC editors colour programs (codes,
//! addresses and values apart, comments, sequence names, variables).
//!
//! A word with an address is two tokens, the address (`property`) and its value (`number`,
//! or `variable` for an expression), so that addresses get a colour of their own, as CIMCO
//! gives them. A block that does not parse has no words and no tokens: its diagnostic marks
//! it.

use lsp_types::{SemanticToken, SemanticTokenModifier, SemanticTokenType, SemanticTokensLegend};

use crate::source::Span;
use crate::syntax::{CodeLetter, ExprKind, WordKind};

use super::document::{BlockRef, Document};

/// The token types, in the legend's order.
const TYPES: [SemanticTokenType; 10] = [
    SemanticTokenType::KEYWORD,
    SemanticTokenType::MACRO,
    SemanticTokenType::PROPERTY,
    SemanticTokenType::NUMBER,
    SemanticTokenType::VARIABLE,
    SemanticTokenType::new("label"),
    SemanticTokenType::COMMENT,
    SemanticTokenType::FUNCTION,
    SemanticTokenType::STRING,
    SemanticTokenType::OPERATOR,
];
const KEYWORD: u32 = 0;
const MACRO: u32 = 1;
const PROPERTY: u32 = 2;
const NUMBER: u32 = 3;
const VARIABLE: u32 = 4;
const LABEL: u32 = 5;
const COMMENT: u32 = 6;
const FUNCTION: u32 = 7;
const STRING: u32 = 8;
const OPERATOR: u32 = 9;

/// Bit 0: the word declares the name (a block's sequence name, a program's name).
const DECLARATION: u32 = 1;

/// How many bytes of a program `semanticTokens/full` colours: beyond it the answer would
/// be tens of megabytes; clients colour the rest with range requests (VS Code does for what
/// it shows) or leave it plain.
pub const FULL_LIMIT: usize = 4 << 20;

pub fn legend() -> SemanticTokensLegend {
    SemanticTokensLegend { token_types: TYPES.to_vec(), token_modifiers: vec![SemanticTokenModifier::DECLARATION] }
}

/// The tokens of the blocks that touch bytes `range`, encoded as the protocol wants them.
pub fn tokens(document: &Document, range: std::ops::Range<usize>) -> Vec<SemanticToken> {
    let mut found: Vec<(Span, u32, u32)> = Vec::new();
    for block in document.blocks_near(range.clone()) {
        let own = block.absolute(block.block().span);
        if (own.end as usize) < range.start || own.start as usize > range.end {
            continue;
        }
        block_tokens(&block, &mut found);
    }
    encode(document, &found)
}

fn block_tokens(block: &BlockRef<'_>, found: &mut Vec<(Span, u32, u32)>) {
    for word in block.words() {
        let span = block.absolute(word.span);
        let text = block.text(word.span);
        let mut push = |span: Span, kind: u32, modifiers: u32| {
            if span.end > span.start {
                found.push((span, kind, modifiers));
            }
        };
        match word.kind {
            WordKind::Code { letter: CodeLetter::G, .. } => push(span, KEYWORD, 0),
            WordKind::Code { letter: CodeLetter::M, .. } => push(span, MACRO, 0),
            WordKind::Number { address, .. } | WordKind::Expr { address, .. } => {
                // The address letters, `=` and blanks, then the value.
                let letters = address.name().len().min(text.len());
                let value = letters + text[letters..].iter().take_while(|c| matches!(c, b'=' | b' ' | b'\t')).count();
                push(Span::new(span.start, span.start + letters as u32), PROPERTY, 0);
                let kind = if matches!(word.kind, WordKind::Number { .. }) { NUMBER } else { VARIABLE };
                push(Span::new(span.start + value as u32, span.end), kind, 0);
            }
            WordKind::Sequence { .. } => push(span, LABEL, DECLARATION),
            WordKind::Label { .. } => push(span, LABEL, 0),
            WordKind::ProgramName => push(span, FUNCTION, DECLARATION),
            WordKind::ProgramRef => push(span, FUNCTION, 0),
            WordKind::Keyword { .. } => push(span, KEYWORD, 0),
            WordKind::Operand { expr } => {
                let number = block.expr(expr).is_some_and(|e| matches!(e.kind, ExprKind::Number(_)));
                push(span, if number { NUMBER } else { VARIABLE }, 0);
            }
            WordKind::Assign { .. } => push(span, VARIABLE, 0),
            WordKind::Comment(_) => push(span, COMMENT, 0),
            WordKind::Header | WordKind::Verbatim => push(span, STRING, 0),
            WordKind::TapeMark | WordKind::BlockDelete { .. } | WordKind::OptionalSkip { .. } => {
                push(span, OPERATOR, 0)
            }
        }
    }
}

/// The protocol's encoding: each token's line and start relative to the one before, in
/// UTF-16 units. Tokens that run over a line end (a word continued on a `$` line) are left
/// out, as clients without multi-line token support need.
fn encode(document: &Document, found: &[(Span, u32, u32)]) -> Vec<SemanticToken> {
    let mut out = Vec::with_capacity(found.len());
    let (mut line, mut start) = (0u32, 0u32);
    for &(span, kind, modifiers) in found {
        let from = document.position_of(span.start as usize, false);
        let to = document.position_of(span.end as usize, true);
        if to.line != from.line || to.column <= from.column {
            continue;
        }
        let delta_line = from.line - line;
        let delta_start = if delta_line == 0 { from.column - start } else { from.column };
        out.push(SemanticToken {
            delta_line,
            delta_start,
            length: to.column - from.column,
            token_type: kind,
            token_modifiers_bitset: modifiers,
        });
        (line, start) = (from.line, from.column);
    }
    out
}
