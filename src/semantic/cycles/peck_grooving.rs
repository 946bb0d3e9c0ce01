//! Fanuc peck grooving: `G74` on the face (pecks along Z, steps in X; peck drilling when X
//! and the step are left out) and `G75` on a diameter (pecks along X, steps in Z; one
//! groove when Z and the step are left out). Two-block form `G74 R(e)` then
//! `G74 X(U) Z(W) P(Δi) Q(Δk) R(Δd) F` (`G75` alike, with P and Q the other way round), and
//! the Haas one-block form `G75 X Z I K D F` (`G74 X Z I K D F`).
//!
//! Both cycles are one pattern in a frame of two axes: the *depth* axis the tool pecks along
//! (Z for `G74`, X for `G75`) and the *step* axis it moves along between plunges:
//!
//! ```txt
//!   A ●──rapid step──●──rapid step──● end of the step axis     (start level)
//!     │feed Δ        ▲              │
//!     │◀╴rapid back e│ rapid out    │ …
//!     │feed e + Δ    │              │
//!     ▼  bottom ─Δd─▶╯ relief       ▼ bottom (end of the depth axis)
//! ```
//!
//! At each plunge the tool feeds Δ, backs off `e` at rapid to break the chip, feeds on
//! (`e + Δ`), and so on down to the bottom (the last peck is what is left). There it
//! relieves by Δd along the step axis, away from the next plunge (the stock ahead is still
//! uncut; with one plunge only, Δd's sign gives the direction), rapids out to the start
//! level, and steps on by the step (the last step is what is left, so the last plunge lies
//! exactly at the end point). After the last plunge it returns to A.
//!
//! Units: Fanuc `P`/`Q` count least increments (`Interpreter::param_increments`), the Haas
//! `I`/`K` are lengths; all are radius values in X. The retract `e` comes from the first
//! block (`G74 R`/`G75 R`, shared between both as the control's parameter is); without
//! one it is taken as 0, since the control's parameter is not in the machine settings. A
//! missing or zero peck depth plunges to the bottom in one feed.

use crate::diagnostic::DiagnosticKind;
use crate::dialect::{GFunction, Role};
use crate::syntax::{Command, Word};
use crate::toolpath::Xz;

use super::super::interpreter::{Flow, Interpreter};
use super::Call;
use super::MAX_CYCLE_PASSES;

const EPSILON: f64 = 1e-9;

/// What `G74 R(e)`/`G75 R(e)` set (program units), kept for the cycle blocks.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PeckMemory {
    pub retract: Option<f64>,
    /// The first block, which the cycle block consumes.
    pub first_block: Option<usize>,
}

/// The first block of the two-block form only sets the retract.
pub(super) fn retract_block(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command) -> Flow {
    let retract = interp.param(command, Role::Retract);
    let memory = &mut interp.cycle_memory.peck;
    memory.first_block = Some(index);
    memory.retract = retract.or(memory.retract);
    Flow::Next
}

/// A point in the cycle's frame: `depth` along the pecks, `step` across them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    pub depth: f64,
    pub step: f64,
}

/// One move of the plan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PeckMove {
    Rapid(Point),
    Feed(Point),
}

/// The cycle's parameters in its own frame, mm; `peck`, `step` and `retract` are sizes
/// (not signed), `relief` is signed only when there is a single plunge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grooving {
    pub start: Point,
    pub end: Point,
    pub peck: f64,
    pub step: f64,
    pub retract: f64,
    pub relief: f64,
}

impl Grooving {
    /// How many plunges the groove takes: `None` when it has width but no step.
    pub fn plunge_count(&self) -> Option<f64> {
        let width = (self.end.step - self.start.step).abs();
        if width <= EPSILON {
            Some(1.0)
        } else if self.step <= EPSILON {
            None
        } else {
            Some((width / self.step - EPSILON).ceil().max(1.0) + 1.0)
        }
    }

    /// The step-axis positions of the plunges: from the start, `step` apart, the last at
    /// the end (call after checking `plunge_count`).
    pub fn plunges(&self) -> Vec<f64> {
        let count = self.plunge_count().unwrap_or(1.0);
        if count <= 1.0 {
            return vec![self.start.step];
        }
        let direction = (self.end.step - self.start.step).signum();
        let mut out: Vec<f64> =
            (0..count as usize - 1).map(|j| self.start.step + direction * self.step * j as f64).collect();
        out.push(self.end.step);
        out
    }

    /// How many pecks one plunge takes.
    pub fn pecks_per_plunge(&self) -> f64 {
        let depth = (self.end.depth - self.start.depth).abs();
        if self.peck <= EPSILON { 1.0 } else { (depth / self.peck - EPSILON).ceil().max(1.0) }
    }

    /// The moves of the cycle, from A back to A.
    pub fn plan(&self, plunges: &[f64]) -> Vec<PeckMove> {
        let mut out = Vec::new();
        let total = (self.end.depth - self.start.depth).abs();
        let down = (self.end.depth - self.start.depth).signum();
        let at_depth = |reached: f64| self.start.depth + down * reached;
        let relief = if (self.end.step - self.start.step).abs() > EPSILON {
            -(self.end.step - self.start.step).signum() * self.relief.abs()
        } else {
            self.relief
        };
        for (j, &step) in plunges.iter().enumerate() {
            if j > 0 {
                out.push(PeckMove::Rapid(Point { depth: self.start.depth, step }));
            }
            if total > EPSILON {
                let mut reached = 0.0_f64;
                loop {
                    let next = if self.peck > EPSILON { (reached + self.peck).min(total) } else { total };
                    out.push(PeckMove::Feed(Point { depth: at_depth(next), step }));
                    reached = next;
                    if reached >= total - EPSILON {
                        break;
                    }
                    if self.retract > EPSILON {
                        out.push(PeckMove::Rapid(Point { depth: at_depth((reached - self.retract).max(0.0)), step }));
                    }
                }
            }
            let off = step + relief;
            if relief.abs() > EPSILON {
                out.push(PeckMove::Rapid(Point { depth: at_depth(total), step: off }));
            }
            out.push(PeckMove::Rapid(Point { depth: self.start.depth, step: off }));
        }
        out.push(PeckMove::Rapid(self.start));
        out
    }
}

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command, function: GFunction) -> Flow {
    let Some(Call { span, start }) = interp.cycle_call(index) else { return Flow::Next };
    let face = function == GFunction::FacePeck;
    let frame = interp.modal.frame;
    let one_block = interp.form_name(command) == "one_block";
    let words: Vec<Word> = command.params.iter().map(|p| *interp.program.word(p.word)).collect();
    let axes = interp.axis_target(&words);
    let target = axes.target.unwrap_or(start);
    let end = Xz::new(if axes.x_given { target.x } else { start.x }, if axes.z_given { target.z } else { start.z });
    let step_role = if face { Role::StepX } else { Role::StepZ };
    let (peck, step) = if one_block {
        (interp.param(command, Role::PeckDepth), interp.param(command, step_role))
    } else {
        (interp.param_increments(command, Role::PeckDepth), interp.param_increments(command, step_role))
    };
    let relief = interp.param(command, Role::BottomRelief).map_or(0.0, |d| frame.mm(d));
    let retract = interp.cycle_memory.peck.retract.map_or(0.0, |e| frame.mm(e.abs()));
    // Pecks along Z on the face, along X on a diameter.
    let to_frame = |p: Xz| if face { Point { depth: p.z, step: p.x } } else { Point { depth: p.x, step: p.z } };
    let from_frame = |p: Point| if face { Xz::new(p.step, p.depth) } else { Xz::new(p.depth, p.step) };
    let grooving = Grooving {
        start: to_frame(start),
        end: to_frame(end),
        peck: peck.map_or(0.0, |v| frame.mm(v.abs())),
        step: step.map_or(0.0, |v| frame.mm(v.abs())),
        retract,
        relief,
    };
    let Some(plunge_count) = grooving.plunge_count() else {
        interp.error(DiagnosticKind::GrooveStepMissing { axis: if face { 'X' } else { 'Z' } }, span);
        return Flow::Next;
    };
    // Counted before any is planned: a runaway step or peck must not allocate the plan.
    let pecks = plunge_count * grooving.pecks_per_plunge();
    if pecks.is_nan() || pecks > MAX_CYCLE_PASSES as f64 {
        let passes = if pecks.is_finite() { pecks as u64 } else { u64::MAX };
        interp.error(DiagnosticKind::CycleTooManyPasses { passes, max: MAX_CYCLE_PASSES }, span);
        return Flow::Next;
    }

    // The first block is part of the cycle: `expand` deletes it.
    if !one_block {
        interp.consume_setup(interp.cycle_memory.peck.first_block);
    }
    let saved = interp.modal.clone();
    interp.modal.feed = interp.param(command, Role::Feed).unwrap_or(saved.feed);
    let modal = interp.modal.clone();
    for step in grooving.plan(&grooving.plunges()) {
        match step {
            PeckMove::Rapid(p) => interp.emitter.rapid(&modal, from_frame(p)),
            PeckMove::Feed(p) => interp.emitter.line(&modal, from_frame(p), true),
        }
    }
    interp.modal = saved;
    interp.report_zero_feed(span);
    Flow::Next
}

#[cfg(test)]
mod tests {
    use super::*;

    fn groove(peck: f64, step: f64, retract: f64, relief: f64) -> Grooving {
        Grooving {
            start: Point { depth: 35.0, step: -18.0 },
            end: Point { depth: 20.0, step: -24.0 },
            peck,
            step,
            retract,
            relief,
        }
    }

    #[test]
    fn plunges_are_a_step_apart_and_the_last_at_the_end() {
        assert_eq!(groove(2.0, 4.0, 1.0, 0.0).plunges(), vec![-18.0, -22.0, -24.0]);
        assert_eq!(groove(2.0, 3.0, 1.0, 0.0).plunges(), vec![-18.0, -21.0, -24.0]);
        assert_eq!(groove(2.0, 3.0, 1.0, 0.0).plunge_count(), Some(3.0));
        assert_eq!(groove(2.0, 0.0, 1.0, 0.0).plunge_count(), None);
        let narrow = Grooving { end: Point { depth: 20.0, step: -18.0 }, ..groove(2.0, 0.0, 1.0, 0.0) };
        assert_eq!((narrow.plunge_count(), narrow.plunges()), (Some(1.0), vec![-18.0]));
    }

    #[test]
    fn a_plunge_pecks_backs_off_and_relieves_away_from_the_next() {
        let g = Grooving { end: Point { depth: 30.0, step: -20.0 }, ..groove(2.0, 4.0, 0.5, 0.25) };
        let plan = g.plan(&g.plunges());
        let p = |depth: f64, step: f64| Point { depth, step };
        assert_eq!(
            plan,
            vec![
                PeckMove::Feed(p(33.0, -18.0)),
                PeckMove::Rapid(p(33.5, -18.0)),
                PeckMove::Feed(p(31.0, -18.0)),
                PeckMove::Rapid(p(31.5, -18.0)),
                PeckMove::Feed(p(30.0, -18.0)),
                PeckMove::Rapid(p(30.0, -17.75)),
                PeckMove::Rapid(p(35.0, -17.75)),
                PeckMove::Rapid(p(35.0, -20.0)),
                PeckMove::Feed(p(33.0, -20.0)),
                PeckMove::Rapid(p(33.5, -20.0)),
                PeckMove::Feed(p(31.0, -20.0)),
                PeckMove::Rapid(p(31.5, -20.0)),
                PeckMove::Feed(p(30.0, -20.0)),
                PeckMove::Rapid(p(30.0, -19.75)),
                PeckMove::Rapid(p(35.0, -19.75)),
                PeckMove::Rapid(p(35.0, -18.0)),
            ]
        );
    }
}
