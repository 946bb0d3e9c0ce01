//! Inlay hints: what a packed or counted value means, written after it.
//!
//! - `G76 P020060` → `2 finishing passes, chamfer 0.0 × lead, 60°` (the six digits as the
//!   cycle reads them, `semantic::cycles::decode_parameters`);
//! - a Fanuc cycle word the schema in `grammar/` counts in least increments (`G76 Q100`,
//!   written without a point) → `0.100 mm` at the machine's least increment;
//! - a dwell in milliseconds (`G04 P1500`) → `1.5 s`.

use lsp_types::{InlayHint, InlayHintKind, InlayHintLabel};

use crate::dialect::{Dialect, Role};
use crate::machine::{MachineSettings, Units};
use crate::semantic::cycles::decode_parameters;
use crate::syntax::WordKind;

use super::document::Document;
use super::roles::{self, Unit};

/// The hints of the blocks that touch bytes `range`.
pub fn inlay_hints(document: &Document, range: std::ops::Range<usize>, settings: &MachineSettings) -> Vec<InlayHint> {
    let tables = document.config().tables();
    let dialect = tables.config.dialect;
    let inch = settings.units == Some(Units::Inch);
    let increment = settings.least_increment.unwrap_or(if inch { 0.0001 } else { 0.001 });
    let places = settings.increment_places();
    let length = if inch { "inch" } else { "mm" };
    let mut hints = Vec::new();
    for block in document.blocks_near(range.clone()) {
        let own = block.absolute(block.block().span);
        if (own.end as usize) < range.start || own.start as usize > range.end {
            continue;
        }
        let Some(command) = block.command() else { continue };
        let Some(form) = tables.schema(command.schema).forms.get(command.form as usize) else { continue };
        for param in &command.params {
            let Some(word) = block.word(param.word) else { continue };
            let WordKind::Number { address, number } = word.kind else { continue };
            let value = number.to_f64();
            let (_, unit) = roles::describe(param.role);
            let label = match param.role {
                Role::ThreadParameters => decode_parameters(value).map(|p| {
                    let passes = if p.finishing_passes == 1 { "pass" } else { "passes" };
                    format!(
                        "{} finishing {passes}, chamfer {:.1} × lead, {}°",
                        p.finishing_passes,
                        p.chamfer_tenths as f64 / 10.0,
                        p.tool_angle
                    )
                }),
                Role::DwellMilliseconds => Some(format!("{} s", short(value / 1000.0, 3))),
                _ if dialect == Dialect::Fanuc
                    && form.counts_without_point(address)
                    && !number.has_point()
                    && matches!(unit, Unit::Length | Unit::XLength) =>
                {
                    let as_x = if unit == Unit::XLength && settings.diameter_programming.unwrap_or(true) {
                        " (diameter)"
                    } else {
                        ""
                    };
                    Some(format!("{:.*} {length}{as_x}", places as usize, value * increment))
                }
                _ => None,
            };
            let Some(label) = label else { continue };
            let end = document.position_of(block.absolute(word.span).end as usize, true);
            hints.push(InlayHint {
                position: lsp_types::Position { line: end.line, character: end.column },
                label: InlayHintLabel::String(label),
                kind: Some(InlayHintKind::PARAMETER),
                text_edits: None,
                tooltip: None,
                padding_left: Some(true),
                padding_right: None,
                data: None,
            });
        }
    }
    hints
}

/// A value with at most `places` decimals and no trailing zeros.
fn short(value: f64, places: usize) -> String {
    let text = format!("{value:.places$}");
    if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.').to_string() } else { text }
}
