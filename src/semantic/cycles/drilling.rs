//! What the drilling cycles share: reading a cycle block into a hole (its position, R point,
//! bottom, pecks and dwell), running it `K` times, and the modal repetition. The words and
//! what each control does are in `grammar/fanuc.toml` (the `G80`-`G89` entries, with their
//! sources); the cut of each kind of hole is in its own file: `face_drilling.rs`,
//! `face_tapping.rs`, `face_boring.rs`, and `side_drilling.rs` for the holes along X.
//!
//! A drilling code is modal (group 10): after it, a block that gives only a hole position
//! (`X`/`U`, `C`/`H`, and a new bottom `Z`/`W`) drills the same hole there, until `G80` or a
//! code of the motion group. The tool rapids to each hole's line at the level it is at, to
//! the R point, cuts, and returns to the initial level, the Z it was at when the cycle
//! began (after `G80`), or to the R point under Fanuc `G99` of systems B and C. A `C`
//! position turns the part, not the tool: its holes drill along the same line of the XZ
//! plane.
//!
//! `expand` keeps every drilling block as it is: a hole's `C` index, its M codes and the
//! blocks that repeat it by position have no form in plain moves that the written program
//! would run the same way.

use crate::dialect::{DrillingFacts, GFunction, Role};
use crate::source::Span;
use crate::syntax::{Command, Word};
use crate::toolpath::Xz;

use super::super::interpreter::{Flow, Interpreter};
use super::super::modal::MotionMode;
use super::{MAX_CYCLE_PASSES, face_boring, face_drilling, face_tapping, side_drilling};
use crate::diagnostic::DiagnosticKind;

/// Why `expand` leaves a drilling block as it is.
pub(super) const KEPT: &str = "a drilling cycle's C positions, M codes and modal repetitions have no plain-block form";

/// Back from the bottom of each peck of a high-speed peck cycle, mm: Fanuc parameter 5114,
/// the machine's; this value stands in for it [assumed, not a manual's default].
pub(super) const HIGH_SPEED_PECK_RETRACT_MM: f64 = 1.0;
/// Above the last depth where the feed resumes after a full retract, mm: Haas Setting 22
/// (0.05 in) [from memory of the Haas manual, not verified].
pub(super) const FULL_PECK_CLEARANCE_MM: f64 = 1.27;

/// How deep each peck goes, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Pecks {
    None,
    /// Fanuc and Haas `Q`.
    Constant(f64),
    /// Haas `I` first, each `J` shorter, never shorter than `K`.
    Shrinking {
        first: f64,
        less: f64,
        least: f64,
    },
}

impl Pecks {
    /// The depth of peck `n` (from 0), mm.
    pub fn depth(self, n: u64) -> Option<f64> {
        match self {
            Pecks::None => None,
            Pecks::Constant(q) => Some(q),
            Pecks::Shrinking { first, less, least } => Some((first - less * n as f64).max(least)),
        }
    }
}

/// One hole: where it is and how it is cut, in the IR frame (mm, X a radius).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hole {
    /// The hole's line: X (a radius) for a face hole, Z for a side hole.
    pub at: f64,
    /// Where the cycle began: the level it returns to.
    pub initial: Xz,
    /// The R point and the bottom along the drilling axis (Z on the face, X on the side).
    pub r_point: f64,
    pub bottom: f64,
    pub pecks: Pecks,
    pub dwell_seconds: f64,
    /// Return to the R point instead of the initial level (Fanuc `G99`, systems B and C).
    pub to_r_point: bool,
}

impl Hole {
    /// A point on a face hole's line at depth `z`.
    pub fn at_z(&self, z: f64) -> Xz {
        Xz::new(self.at, z)
    }

    /// Where the hole ends: the return level on its line.
    pub fn end(&self) -> Xz {
        self.at_z(if self.to_r_point { self.r_point } else { self.initial.z })
    }

    /// The peck depths down to the bottom, from the R point; `None` when they are more
    /// than the simulation runs.
    pub fn peck_depths(&self) -> Option<Vec<f64>> {
        let direction = (self.bottom - self.r_point).signum();
        let mut depths = Vec::new();
        let mut at = self.r_point;
        for n in 0..MAX_CYCLE_PASSES {
            let Some(step) = self.pecks.depth(n).filter(|q| *q > 0.0) else {
                depths.push(self.bottom);
                return Some(depths);
            };
            at += direction * step;
            if (at - self.bottom) * direction >= 0.0 {
                depths.push(self.bottom);
                return Some(depths);
            }
            depths.push(at);
        }
        None
    }
}

/// The modal drilling cycle, for the blocks that repeat it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrillingMemory {
    pub function: GFunction,
    pub facts: DrillingFacts,
    pub hole: Hole,
    /// The motion mode before the cycle, back in force after `G80`.
    pub motion_before: MotionMode,
    /// The cycle's code, for messages.
    pub code: crate::dialect::Code,
}

/// What the drilling blocks leave for later ones.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DrillingModes {
    pub cycle: Option<DrillingMemory>,
    /// Fanuc systems B and C: `G99` returns to the R point, `G98` (the default) to the
    /// initial level.
    pub return_to_r_point: bool,
}

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command, function: GFunction) -> Flow {
    let Some(info) = interp.tables.g(match interp.program.word(command.code_word).kind {
        crate::syntax::WordKind::Code { code, .. } => code,
        _ => return Flow::Next,
    }) else {
        return Flow::Next;
    };
    let Some(facts) = info.drilling else { return Flow::Next };
    let code = info.code;
    // A cycle block while a drilling cycle is modal keeps its initial level: the level is
    // where the tool was when the cycle began (after `G80`), as the controls keep it.
    let modal_before =
        (interp.modal.motion == MotionMode::Drilling).then_some(interp.cycle_memory.drilling.cycle).flatten();
    let motion_before = modal_before.map_or(interp.modal.motion, |m| m.motion_before);
    interp.modal.motion = MotionMode::Drilling;
    interp.expansion_kept = Some(KEPT);
    let Some(super::Call { span, start }) = interp.cycle_call(index) else { return Flow::Next };
    let level = match (modal_before, function) {
        (Some(m), GFunction::SideDrilling) => Xz::new(m.hole.initial.x, start.z),
        (Some(m), _) => Xz::new(start.x, m.hole.initial.z),
        (None, _) => start,
    };
    let Some(hole) = read_hole(interp, command, (function, facts), (start, level), span) else {
        interp.cycle_memory.drilling.cycle = None;
        return Flow::Next;
    };
    interp.cycle_memory.drilling.cycle = Some(DrillingMemory { function, facts, hole, motion_before, code });
    let repeats = interp.param_count(command, Role::Repeats).map_or(1, |k| k.round().max(0.0) as u64);
    if repeats > MAX_CYCLE_PASSES {
        interp.error(DiagnosticKind::CycleTooManyPasses { passes: repeats, max: MAX_CYCLE_PASSES }, span);
        return Flow::Next;
    }
    // `K` repeats the hole, each time moved by the block's incremental `U` (`W` on the side).
    let step = match function {
        GFunction::SideDrilling => interp.param(command, Role::IncrementalZ).map(|w| interp.modal.frame.mm(w)),
        _ => interp.param(command, Role::IncrementalX).map(|u| interp.modal.frame.x_mm(u)),
    }
    .unwrap_or(0.0);
    let mut hole = hole;
    for n in 0..repeats {
        if n > 0 {
            hole.at += step;
        }
        if !cut_hole(interp, function, facts, &hole, span) {
            break;
        }
    }
    Flow::Next
}

/// A block that gives a hole position while a drilling cycle is modal: the same hole there.
pub(in crate::semantic) fn again(interp: &mut Interpreter<'_, '_>, index: usize, words: &[Word]) -> Flow {
    let Some(memory) = interp.cycle_memory.drilling.cycle else { return Flow::Next };
    // A side hole is off the plane; its cycle block said so once.
    if memory.function == GFunction::SideDrilling {
        return Flow::Next;
    }
    let span = interp.program.block(index).span;
    if interp.known_position(span).is_none() {
        return Flow::Next;
    }
    interp.emitter.context = super::super::emitter::Context { source: span, cycle: span };
    let target = interp.axis_target(words);
    let mut hole = memory.hole;
    let side = memory.function == GFunction::SideDrilling;
    // The position on the line of holes and, when given, a new bottom.
    match (side, target.target) {
        (false, Some(to)) => {
            if target.x_given {
                hole.at = to.x;
            }
            if target.z_given {
                hole.bottom = to.z;
            }
        }
        (true, Some(to)) => {
            if target.z_given {
                hole.at = to.z;
            }
            if target.x_given {
                hole.bottom = to.x;
            }
        }
        (_, None) => {}
    }
    let first_move = interp.emitter.moves.len();
    cut_hole(interp, memory.function, memory.facts, &hole, span);
    interp.cycle_memory.drilling.cycle = Some(DrillingMemory { hole, ..memory });
    interp.report_zero_feed(span);
    interp.expansions.push(crate::semantic::Expansion {
        block: index,
        frame: interp.modal.frame,
        consumed: Vec::new(),
        setup: None,
        traced: Vec::new(),
        traced_end: first_move,
        root: Vec::new(),
        moves: first_move..interp.emitter.moves.len(),
        before: interp.modal_before_block,
        after: crate::semantic::ModalAfter::of(&interp.modal),
        kept: Some(KEPT),
        note: None,
        feed_read_after: true,
        motion_read_after: true,
    });
    interp.emitter.context.cycle = Span::SYNTHETIC;
    Flow::Next
}

/// `G80`, or a code of the motion group: the drilling cycle is no longer modal; after `G80`
/// the motion mode before it is back.
pub(in crate::semantic) fn cancel(interp: &mut Interpreter<'_, '_>) {
    if let Some(memory) = interp.cycle_memory.drilling.cycle.take()
        && interp.modal.motion == MotionMode::Drilling
    {
        interp.modal.motion = memory.motion_before;
    }
}

/// Cut one hole; `false` when it could not be (reported), so that its repeats stop.
fn cut_hole(
    interp: &mut Interpreter<'_, '_>,
    function: GFunction,
    facts: DrillingFacts,
    hole: &Hole,
    span: Span,
) -> bool {
    match function {
        GFunction::FaceDrilling => face_drilling::cut(interp, facts, hole, span),
        GFunction::FaceTapping => face_tapping::cut(interp, hole),
        GFunction::FaceBoring => face_boring::cut(interp, facts, hole, span),
        GFunction::SideDrilling => side_drilling::cut(interp, span),
        _ => true,
    }
}

/// The hole a cycle block describes, from the tool's position `start`; `None` (reported)
/// when its words do not make one.
fn read_hole(
    interp: &mut Interpreter<'_, '_>,
    command: &Command,
    (function, facts): (GFunction, DrillingFacts),
    (start, level): (Xz, Xz),
    span: Span,
) -> Option<Hole> {
    let frame = interp.modal.frame;
    let end = interp.cycle_end(command, start);
    let side = function == GFunction::SideDrilling;
    // The drilling axis: Z on the face, X on the side; `at` is the hole's line across it,
    // given absolute or (`U` on the face, `W` on the side) from where the tool is.
    let (initial, at, end_along) = if side { (level.x, end.z, end.x) } else { (level.z, end.x, end.z) };
    let at = match (side, interp.param(command, Role::IncrementalX), interp.param(command, Role::IncrementalZ)) {
        (false, Some(u), _) if command.param(Role::EndX).is_none() => start.x + frame.x_mm(u),
        (true, _, Some(w)) if command.param(Role::EndZ).is_none() => start.z + frame.mm(w),
        _ => at,
    };
    let scale = |v: f64| if side { frame.x_mm(v) } else { frame.mm(v) };
    let r_point = match interp.param(command, Role::RPoint) {
        // Haas: the R plane's position on the drilling axis, as that axis' words read.
        Some(r) if facts.r_plane => {
            let shift = if side { interp.modal.shift.x } else { interp.modal.shift.z };
            if interp.modal.absolute { scale(r) + shift } else { initial + scale(r) }
        }
        // Fanuc: the signed distance from the initial level.
        Some(r) => initial + scale(r),
        None => initial,
    };
    // An incremental bottom (`W` on the face, `U` on the side) counts from the R point.
    let incremental_bottom = if side { Role::IncrementalX } else { Role::IncrementalZ };
    let bottom = match interp.param(command, incremental_bottom) {
        Some(v) => r_point + scale(v),
        None => end_along,
    };
    // A `Q` the schema reads without a decimal point counts least increments (Fanuc).
    let form = interp.tables.schema(command.schema).forms.get(command.form as usize);
    let q_in_increments = form.is_some_and(|f| f.counts_without_point(crate::dialect::Address::Q));
    let q = if q_in_increments {
        interp.param_increments(command, Role::PeckDepth)
    } else {
        interp.param(command, Role::PeckDepth)
    };
    let pecks = match (facts.peck, q) {
        (Some(_), Some(q)) => Pecks::Constant(frame.mm(q.abs())),
        (Some(_), None) => match interp.param(command, Role::FirstDepth) {
            Some(first) => Pecks::Shrinking {
                first: frame.mm(first.abs()),
                less: interp.param(command, Role::PeckReduction).map_or(0.0, |j| frame.mm(j.abs())),
                least: interp.param(command, Role::MinDepth).map_or(0.0, |k| frame.mm(k.abs())),
            },
            None => Pecks::None,
        },
        (None, _) => Pecks::None,
    };
    let first_peck = match pecks {
        Pecks::None => None,
        Pecks::Constant(q) => Some((q, Role::PeckDepth)),
        Pecks::Shrinking { first, least, .. } => Some((first.max(least), Role::FirstDepth)),
    };
    if let Some((depth, role)) = first_peck
        && depth <= 0.0
    {
        interp.error(DiagnosticKind::DrillPeckNotPositive, interp.param_span(command, role, span));
        return None;
    }
    let dwell_seconds = interp
        .param(command, Role::DwellMilliseconds)
        .map(|ms| ms / 1000.0)
        .or_else(|| interp.param(command, Role::DwellSeconds))
        .unwrap_or(0.0)
        .max(0.0);
    let to_r_point = interp.cycle_memory.drilling.return_to_r_point;
    let initial_point = if side { Xz::new(initial, start.z) } else { Xz::new(start.x, initial) };
    Some(Hole { at, initial: initial_point, r_point, bottom, pecks, dwell_seconds, to_r_point })
}
