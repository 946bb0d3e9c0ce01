//! Document symbols: the outline of a program.
//!
//! Programs (`O1234`, `OSUB`) hold what follows them up to the next program; LAP contours
//! (`N0207 G81` … `G80`) hold their blocks; sequence names (`N20`, `NAT00`) are the leaves.
//! An OSP file header (`$PART.MIN%`) is a symbol of its own.

use lsp_types::{DocumentSymbol, SymbolKind};

use crate::source::Span;
use crate::syntax::{Statement, Word, WordKind};

use super::document::{BlockRef, Document};
use super::names::{ends_contour, starts_contour};

/// The longest block text shown beside a symbol.
const DETAIL_CHARS: usize = 60;

/// A symbol being built, with its children.
struct Open {
    name: String,
    detail: String,
    kind: SymbolKind,
    span: Span,
    name_span: Span,
    children: Vec<Open>,
}

pub fn symbols(document: &Document) -> Vec<DocumentSymbol> {
    let tables = document.config().tables();
    let mut top: Vec<Open> = Vec::new();
    let mut program: Option<Open> = None;
    let mut contour: Option<Open> = None;
    for block in document.blocks() {
        let span = block.absolute(block.block().span);
        let words = block.words();
        let sequence = words.iter().find(|w| matches!(w.kind, WordKind::Sequence { .. }));
        let statement = block.block().statement;
        let lap_marker = matches!(statement, Statement::LapMarker(_));
        let contour_start = lap_marker && starts_contour(&block, tables);
        let contour_end = lap_marker && !contour_start && ends_contour(&block, tables);
        if statement == Statement::ProgramName {
            close(&mut contour, &mut program, &mut top);
            top.extend(program.take());
            let name = words.iter().find(|w| matches!(w.kind, WordKind::ProgramName));
            program = Some(leaf(&block, name, SymbolKind::FUNCTION));
        } else {
            if let Some(open) = program.as_mut() {
                open.span = open.span.merge(span);
            }
            if contour_start {
                close(&mut contour, &mut program, &mut top);
                let mut open = leaf(&block, sequence, SymbolKind::STRUCT);
                open.name.push_str(" contour");
                contour = Some(open);
            } else if let Some(open) = contour.as_mut() {
                open.span = open.span.merge(span);
            }
        }
        if statement == Statement::Header {
            top.push(leaf(&block, None, SymbolKind::FILE));
        }
        if statement != Statement::ProgramName
            && !contour_start
            && let Some(sequence) = sequence
        {
            add(&mut contour, &mut program, &mut top, leaf(&block, Some(sequence), SymbolKind::KEY));
        }
        if contour_end {
            close(&mut contour, &mut program, &mut top);
        }
    }
    close(&mut contour, &mut program, &mut top);
    top.extend(program);
    top.into_iter().map(|open| finish(document, open)).collect()
}

/// A symbol for a block, named by the text of `name` (the whole block when it has none).
fn leaf(block: &BlockRef<'_>, name: Option<&Word>, kind: SymbolKind) -> Open {
    let own = block.block().span;
    let name_span = name.map_or(own, |w| w.span);
    let text = String::from_utf8_lossy(block.text(name_span)).trim().to_string();
    let detail = String::from_utf8_lossy(block.text(own)).trim().chars().take(DETAIL_CHARS).collect();
    Open {
        name: if text.is_empty() { "(unnamed)".to_string() } else { text },
        detail,
        kind,
        span: block.absolute(own),
        name_span: block.absolute(name_span),
        children: Vec::new(),
    }
}

/// Add a symbol to the innermost open container.
fn add(contour: &mut Option<Open>, program: &mut Option<Open>, top: &mut Vec<Open>, symbol: Open) {
    match (contour.as_mut(), program.as_mut()) {
        (Some(open), _) | (None, Some(open)) => open.children.push(symbol),
        (None, None) => top.push(symbol),
    }
}

fn close(contour: &mut Option<Open>, program: &mut Option<Open>, top: &mut Vec<Open>) {
    if let Some(done) = contour.take() {
        match program.as_mut() {
            Some(open) => open.children.push(done),
            None => top.push(done),
        }
    }
}

#[allow(deprecated)] // `DocumentSymbol::deprecated` has no other spelling in lsp-types.
fn finish(document: &Document, open: Open) -> DocumentSymbol {
    DocumentSymbol {
        name: open.name,
        detail: Some(open.detail),
        kind: open.kind,
        tags: None,
        deprecated: None,
        range: document.range(open.span),
        selection_range: document.range(open.name_span),
        children: if open.children.is_empty() {
            None
        } else {
            Some(open.children.into_iter().map(|child| finish(document, child)).collect())
        },
    }
}
