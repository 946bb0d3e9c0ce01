//! Canned cycles: one file per cycle, named for what it does. This module dispatches on the
//! G-code's function (from `grammar/`), reads typed parameters, and records which moves
//! each call produced (for `expand`).
//!
//! Parameter units follow the controls: Fanuc `U`/`W` allowances are diameter/length
//! values; `Δd` depths of cut are radius values; the `P`/`Q` words of `G74`/`G75`/`G76`
//! count least increments; OSP `D`, `U`, `H` are diameters.

mod canonical;
mod finishing;
mod single;
mod stock_removal;

use crate::diagnostic::DiagnosticKind;
use crate::dialect::{GFunction, Role};
use crate::source::Span;
use crate::syntax::{CommandId, WordKind};

use super::Expansion;
use super::emitter::Context;
use super::interpreter::{Flow, Interpreter};

pub(super) use single::{SingleCycleMemory, single_cycle_again};

/// Run the cycle of block `index`.
pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, id: CommandId) -> Flow {
    let command = interp.program.command(id).clone();
    let block = *interp.program.block(index);
    let code = interp.program.word(command.code_word);
    let info = match code.kind {
        WordKind::Code { code, .. } => interp.tables.g(code),
        _ => None,
    };
    let Some(function) = info.and_then(|g| g.function) else { return Flow::Next };
    interp.finish_corner();
    let first_move = interp.emitter.moves.len();
    interp.emitter.context = Context { source: block.span, cycle: block.span };
    let mut consumed = Vec::new();
    let flow = match function {
        GFunction::TurningCycle | GFunction::ThreadCycle | GFunction::FacingCycle => {
            single::run(interp, index, &command, function)
        }
        GFunction::Finishing => finishing::run(interp, index, &command, &mut consumed),
        GFunction::StockRemovalTurning | GFunction::StockRemovalFacing => {
            if interp.form_name(&command) == "depth" {
                stock_removal::depth_block(interp, index, &command, function)
            } else {
                stock_removal::run(interp, index, &command, function, &mut consumed)
            }
        }
        _ => {
            interp.warning(
                DiagnosticKind::CycleNotSimulated { code: info.map_or(String::new(), |g| g.code.display('G')) },
                block.span,
            );
            Flow::Next
        }
    };
    // A cut of the cycle with no feed is the cycle's fault, reported on its block (not left
    // for the next feed move to report).
    interp.report_zero_feed(block.span);
    interp.emitter.context = Context { source: block.span, cycle: Span::SYNTHETIC };
    if interp.emitter.moves.len() > first_move || !consumed.is_empty() {
        interp.expansions.push(Expansion {
            block: index,
            frame: interp.modal.frame,
            consumed,
            moves: first_move..interp.emitter.moves.len(),
        });
    }
    flow
}

impl Interpreter<'_, '_> {
    /// The name of the schema form a command matched (`depth`, `profile`, `one_block`, …).
    pub(super) fn form_name(&self, command: &crate::syntax::Command) -> &'static str {
        self.tables.schema(command.schema).forms.get(command.form as usize).map_or("", |f| f.name.as_str())
    }

    /// The value of a cycle parameter in program units. Parameters the schema takes as
    /// integers (`P`/`Q` of `G74`-`G76`) count least increments when they are lengths.
    pub(super) fn param(&mut self, command: &crate::syntax::Command, role: Role) -> Option<f64> {
        let id = command.param(role)?;
        let word = *self.program.word(id);
        self.word_value(&word)
    }

    /// The block with sequence number `value` (a `P`/`Q` reference), which must be unique.
    pub(super) fn sequence_block(&mut self, value: f64, span: Span) -> Option<usize> {
        let key = (value.round() as i64).to_string();
        let blocks = self.labels.blocks(&key).to_vec();
        match blocks.as_slice() {
            [one] => Some(*one),
            [] => {
                self.error(DiagnosticKind::MissingSequence { number: key }, span);
                None
            }
            _ => {
                self.error(DiagnosticKind::DuplicateSequence { number: key, count: blocks.len() }, span);
                None
            }
        }
    }
}
