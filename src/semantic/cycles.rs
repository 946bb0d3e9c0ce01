//! Canned cycles: one file per cycle, named for what it does. This module dispatches on the
//! G-code's function (from `grammar/`; one arm for every function, so a new one is placed
//! here or the build fails), keeps what a cycle leaves for a later block (`CycleMemory`),
//! reads typed parameters, and records which moves each call produced (for `expand`). Whose
//! a cycle block's F and S are is `feed_and_speed` in `grammar/`, read by `block.rs`.
//!
//! Parameter units follow the controls: Fanuc `U`/`W` allowances are diameter/length
//! values; `Δd` depths of cut are radius values; the `P`/`Q` words of `G74`/`G75`/`G76`
//! count least increments; OSP `D`, `U`, `H` are diameters.

mod canonical;
mod compound_thread;
pub(super) mod drilling;
mod face_boring;
mod face_drilling;
mod face_tapping;
mod finishing;
mod grooving;
mod lap_contour;
mod lap_copy;
mod lap_finish;
mod lap_frame;
mod lap_rough;
mod lap_thread;
mod multiple_threading;
// `G76 P` decoded as the cycle reads it, for the language server's inlay hints.
pub use multiple_threading::decode_parameters;
mod pattern_repeat;
mod peck_grooving;
mod side_drilling;
mod single;
mod stock_removal;
mod tapping;
pub(crate) mod thread_infeed;
pub(crate) mod thread_pass;
mod thread_single;

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::{GFunction, Role};
use crate::source::Span;
use crate::syntax::{Command, CommandId, WordKind};
use crate::toolpath::Xz;

use super::Expansion;
use super::emitter::Context;
use super::interpreter::{Flow, Interpreter};

use single::SingleCycleMemory;
pub(super) use single::single_cycle_again;

/// What a cycle leaves for a later block: the first block of a two-block Fanuc cycle for
/// its second, the last single cycle for its modal repetitions, and modes set by M codes.
/// A cycle that needs such a memory keeps its type in its own file and a field here.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct CycleMemory {
    /// `G71 U(Δd) R(e)`, `G72 W(Δd) R(e)`: depth of cut (with its word) and retract,
    /// program units.
    pub turning_depth: Option<(f64, crate::source::Span)>,
    pub turning_retract: Option<f64>,
    pub facing_depth: Option<(f64, crate::source::Span)>,
    pub facing_retract: Option<f64>,
    /// The block that last set a depth (the first block of a two-block cycle).
    pub depth_block: Option<usize>,
    /// The last Fanuc single cycle, for its modal repetitions.
    pub single: Option<SingleCycleMemory>,
    /// OSP thread-end chamfering (`M23` on, `M22` off, off at the start): a mode.
    pub thread_chamfer: bool,
    /// `G73 U(Δi) W(Δk) R(d)`.
    pub pattern: pattern_repeat::PatternMemory,
    /// `G74 R(e)`, `G75 R(e)`.
    pub peck: peck_grooving::PeckMemory,
    /// `G76 P(m)(r)(a) Q(Δdmin) R(d)`.
    pub thread: multiple_threading::ThreadMemory,
    /// The last cycle block that made no move (a two-block cycle's first block) and the
    /// modal words before it: when the cycle block consumes it, `expand` deletes it, so the
    /// written blocks start from the words before it (its F and S are the cycle's).
    pub setup_block: Option<(usize, crate::semantic::ModalAfter)>,
    /// The modal drilling cycle and the return level.
    pub drilling: drilling::DrillingModes,
}

/// A cycle call may run at most this many passes (or pecks): more is a runaway parameter
/// (a depth of a thousandth over a long groove), reported instead of simulated.
pub(super) const MAX_CYCLE_PASSES: u64 = 10_000;

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
    // A decimal point the control refuses: the block alarms, and runs no cycle.
    if !interp.cycle_points_taken(&command) {
        return Flow::Next;
    }
    interp.observe_cycle_words(&command);
    interp.finish_corner();
    let first_move = interp.emitter.moves.len();
    interp.emitter.context = Context { source: block.span, cycle: block.span };
    let flow = match function {
        GFunction::TurningCycle | GFunction::ThreadCycle | GFunction::FacingCycle => {
            single::run(interp, index, &command, function)
        }
        GFunction::Finishing => finishing::run(interp, index, &command),
        GFunction::StockRemovalTurning | GFunction::StockRemovalFacing => {
            if interp.form_name(&command) == "depth" {
                stock_removal::depth_block(interp, index, &command, function)
            } else {
                stock_removal::run(interp, index, &command, function)
            }
        }
        GFunction::ThreadSingle
        | GFunction::ThreadSingleAlias
        | GFunction::ThreadSingleFace
        | GFunction::ThreadSingleLeadIncreasing
        | GFunction::ThreadSingleLeadDecreasing => thread_single::run(interp, index, &command, function),
        GFunction::CompoundThreadLongitudinal | GFunction::CompoundThreadFace => {
            compound_thread::run(interp, index, &command, function)
        }
        GFunction::LapThread => lap_thread::run(interp, index, &command),
        GFunction::OspGrooving | GFunction::OspFaceCutting => grooving::run(interp, index, &command, function),
        GFunction::Tapping => tapping::run(interp, index, &command),
        GFunction::PatternRepeat => {
            if interp.form_name(&command) == "relief" {
                pattern_repeat::relief_block(interp, index, &command)
            } else {
                pattern_repeat::run(interp, index, &command)
            }
        }
        GFunction::FacePeck | GFunction::DiameterGrooving => {
            if interp.form_name(&command) == "retract" {
                peck_grooving::retract_block(interp, index, &command)
            } else {
                peck_grooving::run(interp, index, &command, function)
            }
        }
        GFunction::MultipleThreading => {
            if interp.form_name(&command) == "passes" {
                multiple_threading::passes_block(interp, index, &command)
            } else {
                let name = info.map_or(String::new(), |g| g.code.display('G'));
                multiple_threading::run(interp, index, &command, &name)
            }
        }
        GFunction::LapRough => lap_rough::run(interp, index, &command),
        GFunction::LapCopy => lap_copy::run(interp, index, &command),
        GFunction::LapFinish => lap_finish::run(interp, index, &command),
        GFunction::FaceDrilling | GFunction::FaceTapping | GFunction::FaceBoring | GFunction::SideDrilling => {
            drilling::run(interp, index, &command, function)
        }
        // The drilling cycles are not simulated; the other functions are those of no cycle,
        // which no `cycle` or `lap_call` code of `grammar/` names.
        GFunction::Drilling
        | GFunction::Absolute
        | GFunction::AtcHome
        | GFunction::Ccw
        | GFunction::ChamferCorner
        | GFunction::CompensationLeft
        | GFunction::CompensationOff
        | GFunction::CompensationRight
        | GFunction::CoordinateSetOrClamp
        | GFunction::Cw
        | GFunction::DrillingCancel
        | GFunction::DrillReturnInitial
        | GFunction::DrillReturnRPoint
        | GFunction::Dwell
        | GFunction::FeedPerMinute
        | GFunction::FeedPerRev
        | GFunction::Inch
        | GFunction::Incremental
        | GFunction::LapBlank
        | GFunction::LapCondition
        | GFunction::LapContourLongitudinal
        | GFunction::LapContourTransverse
        | GFunction::LapEnd
        | GFunction::Linear
        | GFunction::LocalShift
        | GFunction::MachineCoordinates
        | GFunction::MacroCall
        | GFunction::Metric
        | GFunction::Rapid
        | GFunction::ReferenceCheck
        | GFunction::ReferenceReturn
        | GFunction::RoundCorner
        | GFunction::Rpm
        | GFunction::SecondReferenceReturn
        | GFunction::SurfaceSpeed
        | GFunction::ThreadMove
        | GFunction::VariableLeadThreadMove
        | GFunction::WorkOffset => {
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
    let consumed = std::mem::take(&mut interp.cycle_consumed);
    let setup = interp.cycle_setup.take();
    let traced = std::mem::take(&mut interp.cycle_traced);
    let traced_end = interp.cycle_traced_end.take().unwrap_or(first_move);
    let root = std::mem::take(&mut interp.cycle_root);
    let before = match interp.cycle_memory.setup_block {
        Some((setup, before)) if setup < index && consumed.contains(&setup) => before,
        _ => interp.modal_before_block,
    };
    let kept = interp.expansion_kept.take();
    let note = interp.expansion_note.take();
    if interp.emitter.moves.len() > first_move || !consumed.is_empty() {
        interp.expansions.push(Expansion {
            block: index,
            frame: interp.modal.frame,
            consumed,
            setup,
            traced,
            traced_end,
            root,
            moves: first_move..interp.emitter.moves.len(),
            before,
            after: crate::semantic::ModalAfter::of(&interp.modal),
            kept,
            note,
            feed_read_after: true,
            motion_read_after: true,
        });
    } else {
        interp.cycle_memory.setup_block = Some((index, interp.modal_before_block));
    }
    flow
}

/// A cycle call: its block, and the tool's position there, which the cycle's moves start
/// from and return to.
#[derive(Debug, Clone, Copy)]
pub(super) struct Call {
    pub span: Span,
    pub start: Xz,
}

impl Interpreter<'_, '_> {
    /// The call of the cycle in block `index`, or `None` when the tool's position is not
    /// known (no home and no move yet): the cycle then moves nothing, and the program is
    /// warned once.
    pub(super) fn cycle_call(&mut self, index: usize) -> Option<Call> {
        let span = self.program.block(index).span;
        let start = self.known_position(span)?;
        Some(Call { span, start })
    }

    /// The tool's position, or `None` (warned once per program, on `span`) when it is not
    /// known.
    pub(super) fn known_position(&mut self, span: Span) -> Option<Xz> {
        let at = self.emitter.at;
        if at.is_finite() {
            Some(at)
        } else {
            self.unknown_position(span);
            None
        }
    }

    /// Blocks the cycle being run consumes: `expand` deletes them with its call.
    pub(super) fn consume(&mut self, blocks: impl IntoIterator<Item = usize>) {
        self.cycle_consumed.extend(blocks);
    }

    /// The first block of a two-block cycle, consumed: it ran where it is
    /// (`Expansion::setup`).
    pub(super) fn consume_setup(&mut self, block: Option<usize>) {
        self.cycle_consumed.extend(block);
        self.cycle_setup = block.or(self.cycle_setup);
    }

    /// The name of the schema form a command matched (`depth`, `profile`, `one_block`, …).
    pub(super) fn form_name(&self, command: &Command) -> &'static str {
        self.tables.schema(command.schema).forms.get(command.form as usize).map_or("", |f| f.name.as_str())
    }

    /// The value of a cycle parameter in program units, read as any word of its address
    /// reads (an integer `P`/`Q` is its plain value here).
    pub(super) fn param(&mut self, command: &Command, role: Role) -> Option<f64> {
        let id = command.param(role)?;
        let word = *self.program.word(id);
        self.word_value(&word)
    }

    /// The end point a cycle's `X`/`Z` words give (absolute, or from the tool under `G91`);
    /// an axis the block does not name stays where the tool is. Read from the schema roles,
    /// not the motion words, so that an OSP taper angle `A` is not taken for a direction.
    pub(super) fn cycle_end(&mut self, command: &Command, at: Xz) -> Xz {
        let (frame, shift, absolute) = (self.modal.frame, self.modal.shift, self.modal.absolute);
        let x = self
            .param(command, Role::EndX)
            .map(|v| if absolute { frame.x_mm(v) + shift.x } else { at.x + frame.x_mm(v) });
        let z =
            self.param(command, Role::EndZ).map(|v| if absolute { frame.mm(v) + shift.z } else { at.z + frame.mm(v) });
        Xz::new(x.unwrap_or(at.x), z.unwrap_or(at.z))
    }

    /// Where the word playing `role` is written, else `fallback` (the block).
    /// A cycle parameter as written, not scaled: a count (`G73` divisions) or a code
    /// (`G76 P(m)(r)(a)`). A literal is its digits; an expression its value.
    pub(super) fn param_count(&mut self, command: &Command, role: Role) -> Option<f64> {
        let id = command.param(role)?;
        let word = *self.program.word(id);
        match word.kind {
            WordKind::Number { number, .. } => Some(number.to_f64()),
            _ => self.word_value(&word),
        }
    }

    /// An integer length parameter (`P`/`Q` of `G74`-`G76`): the control reads it in least
    /// input increments whatever the decimal-point setting, so `P2000` is 2 mm on a 0.001 mm
    /// control. Program units. Written with a decimal point where the schema lets a control
    /// take one (`point_unverified`: `G83 Q3.`, warned of), it is the length as written.
    pub(super) fn param_increments(&mut self, command: &Command, role: Role) -> Option<f64> {
        let id = command.param(role)?;
        if let WordKind::Number { number, .. } = self.program.word(id).kind
            && number.has_point()
        {
            return Some(number.to_f64());
        }
        let count = self.param_count(command, role)?;
        Some(count * self.modal.frame.increment)
    }

    /// The span of a cycle parameter's word, else `fallback` (the block).
    pub(super) fn param_span(&self, command: &Command, role: Role, fallback: Span) -> Span {
        command.param(role).map_or(fallback, |id| self.program.word(id).span)
    }

    /// The M-code numbers written for `role` (`M32` as an infeed mode).
    pub(super) fn m_params(&self, command: &Command, role: Role) -> Vec<u16> {
        command
            .params
            .iter()
            .filter(|p| p.role == role)
            .filter_map(|p| match self.program.word(p.word).kind {
                WordKind::Code { code, .. } => Some(code.major()),
                _ => None,
            })
            .collect()
    }

    /// The block with sequence number `value` (a `P`/`Q` reference), which must be unique.
    pub(super) fn sequence_block(&mut self, value: f64, span: Span) -> Option<usize> {
        let key = (value.round() as i64).to_string();
        let blocks = self.labels().blocks(&key).to_vec();
        match blocks.as_slice() {
            [one] => Some(*one),
            [] => {
                match self.labels().damaged(&key) {
                    Some(damaged) => {
                        let damaged = self.program.block(damaged).span;
                        let note = Diagnostic::note(DiagnosticKind::DependsOnDamagedBlock { what: "it names" }, span)
                            .with_related(damaged, format!("N{key}, which does not parse"));
                        self.diagnostics.push(note);
                    }
                    None => self.error(DiagnosticKind::MissingSequence { number: key }, span),
                }
                None
            }
            _ => {
                let mut error = Diagnostic::error(
                    DiagnosticKind::DuplicateSequence { number: key.clone(), count: blocks.len() },
                    span,
                );
                for &block in &blocks {
                    error = error.with_related(self.program.block(block).span, format!("a block numbered N{key}"));
                }
                self.diagnostics.push(error);
                None
            }
        }
    }
}
