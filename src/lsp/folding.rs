//! Folding ranges: the structure a machinist folds away.
//!
//! - a program (`O1234`, `OSUB`), from its name to the block before the next program;
//! - a LAP contour (`NLAP1 G81` … `G80`);
//! - a cycle's finishing profile, from the block `P` names to the one `Q` names (the
//!   blocks the cycle reads and does not run as written).

use std::collections::BTreeSet;

use lsp_types::{FoldingRange, FoldingRangeKind};

use crate::dialect::Role;
use crate::syntax::{Statement, WordKind};

use super::document::Document;
use super::names::{self, Use};
use super::names::{ends_contour, starts_contour};

pub fn folding_ranges(document: &Document) -> Vec<FoldingRange> {
    let tables = document.config().tables();
    let mut ranges: BTreeSet<(u32, u32, String)> = BTreeSet::new();
    let line_of = |offset: u32| document.position_of(offset as usize, false).line;
    let mut program: Option<(u32, String)> = None;
    let mut contour: Option<(u32, String)> = None;
    let mut last_line = 0;
    let mut profiles: Vec<(String, String)> = Vec::new();
    for block in document.blocks() {
        let own = block.absolute(block.block().span);
        let text =
            || String::from_utf8_lossy(block.text(block.block().span)).trim().chars().take(60).collect::<String>();
        let line = line_of(own.start);
        let statement = block.block().statement;
        if statement == Statement::ProgramName {
            if let Some((start, name)) = program.take() {
                ranges.insert((start, last_line, name));
            }
            program = Some((line, text()));
        }
        if matches!(statement, Statement::LapMarker(_)) {
            if starts_contour(&block, tables) {
                contour = Some((line, text()));
            } else if ends_contour(&block, tables)
                && let Some((start, name)) = contour.take()
            {
                ranges.insert((start, line, name));
            }
        }
        if let Some(command) = block.command() {
            let key = |role: Role| {
                let param = command.params.iter().find(|p| p.role == role)?;
                match block.word(param.word)?.kind {
                    WordKind::Number { number, .. } => Some(names::whole_key(number.to_f64())),
                    _ => None,
                }
            };
            if let (Some(first), Some(last)) = (key(Role::ProfileStart), key(Role::ProfileEnd)) {
                profiles.push((first, last));
            }
        }
        // A program ends at its last block with words: not at blank lines or a tape mark.
        if !matches!(statement, Statement::Empty | Statement::TapeMark | Statement::Trailing) {
            last_line = line_of(own.end.saturating_sub(1).max(own.start));
        }
    }
    if let Some((start, name)) = program {
        ranges.insert((start, last_line, name));
    }
    if !profiles.is_empty() {
        let all = names::all(document);
        let line_of_key = |key: &str| {
            all.iter().find(|n| n.use_ == Use::Definition && n.key == key).map(|n| (line_of(n.block.start), n.block))
        };
        for (first, last) in profiles {
            if let (Some((start, block)), Some((end, _))) = (line_of_key(&first), line_of_key(&last)) {
                let text = String::from_utf8_lossy(&document.text_of(block)).trim().chars().take(60).collect();
                ranges.insert((start, end, text));
            }
        }
    }
    ranges
        .into_iter()
        .filter(|(start, end, _)| end > start)
        .map(|(start_line, end_line, text)| FoldingRange {
            start_line,
            end_line,
            kind: Some(FoldingRangeKind::Region),
            collapsed_text: Some(text),
            ..FoldingRange::default()
        })
        .collect()
}
