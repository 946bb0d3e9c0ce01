//! Finishing profiles: the blocks between a Fanuc cycle's `P` and `Q` sequence numbers, or
//! an OSP LAP contour between `G81`/`G82` and `G80`, as a chain of lines and arcs.
//!
//! The profile is read by running its blocks through the ordinary motion code on a scratch
//! copy of the state (so incremental words, `R`/`L`/`I K` arcs, OSP angles and corners all
//! work inside a profile), collecting the moves, and putting the state back: the roughing
//! cycles do not execute the profile, they use its shape.

use std::ops::RangeInclusive;

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::{Address, GFunction};
use crate::source::Span;
use crate::syntax::{CodeLetter, Statement, WordKind};
use crate::toolpath::{Compensation, Motion, Xz};

use super::block::effective_words;
use super::interpreter::Interpreter;
use super::modal::Modal;

/// The shape of one profile element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    Line,
    Arc { centre: Xz, ccw: bool },
}

/// One element of a profile, ending at `end` (it starts where the previous one ends).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    pub end: Xz,
    pub shape: Shape,
    /// Programmed as a rapid (`G00`), which matters for the approach of a roughing pass.
    pub rapid: bool,
    /// F and S in effect on this element, program units, for finishing.
    pub feed: f64,
    pub speed: f64,
    pub compensation: Compensation,
    pub source: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    /// The blocks that define it (from the `P` block to the `Q` block, or a LAP contour
    /// from `G81`/`G82` to `G80`).
    pub blocks: RangeInclusive<usize>,
    /// Where the profile starts: the position before its first block.
    pub start: Xz,
    pub segments: Vec<Segment>,
    /// Whether the first block names both axes (Fanuc `G71` Type II).
    pub first_block_has_both_axes: bool,
    /// The modal state after the profile's last block, for finishing.
    pub modal_after: Modal,
}

impl Profile {
    pub fn end(&self) -> Xz {
        self.segments.last().map_or(self.start, |s| s.end)
    }

    /// The points of the chain: its start, then each element's end.
    pub fn points(&self) -> impl Iterator<Item = Xz> + '_ {
        std::iter::once(self.start).chain(self.segments.iter().map(|s| s.end))
    }
}

impl Interpreter<'_, '_> {
    /// Read the profile in `blocks`, starting from `start`. The modal state, the clock and
    /// the emitted moves are left as they were.
    pub fn profile(&mut self, blocks: RangeInclusive<usize>, start: Xz) -> Result<Profile, Diagnostic> {
        let saved_modal = self.modal.clone();
        let saved_at = self.emitter.at;
        let saved_time = self.emitter.time;
        let saved_context = self.emitter.context;
        let saved_first = self.emitter.first_start;
        let saved_len = self.emitter.moves.len();
        let saved_diagnostics = self.diagnostics.len();
        // A corner in the profile is written out by the cycle's expansion, not on its own.
        let saved_expansions = self.expansions.len();
        let saved_zero_feed = self.emitter.zero_feed;
        // The scratch moves' times are never read: their arcs are not handed to the arc
        // timer (`emitter/arc_times.rs`), so dropping the moves drops nothing of its work.
        let timing_beside = self.emitter.pause_timing_beside();
        self.emitter.at = start;

        let mut first_block_has_both_axes = false;
        let mut seen_motion = false;
        let mut segments = Vec::new();
        let mut failure = None;
        let range = blocks.clone();
        for index in blocks {
            let block = *self.program.block(index);
            let words = effective_words(self.program.words_of(&block), self.options.block_delete).to_vec();
            if self.options.block_delete && words.len() < self.program.words_of(&block).len() && words.is_empty() {
                continue;
            }
            match block.statement {
                Statement::Motion
                | Statement::Settings
                | Statement::ToolCall
                | Statement::Spindle
                | Statement::Empty => {}
                Statement::LapMarker(_) | Statement::Dwell(_) => continue,
                Statement::Invalid => {
                    // The shape is not known: the cycle that reads it is not checked.
                    let what = "the profile holds";
                    let note = Diagnostic::note(DiagnosticKind::DependsOnDamagedBlock { what }, saved_context.source)
                        .with_related(block.span, "this block of the profile does not parse");
                    failure = Some(note);
                    break;
                }
                _ => {
                    failure = Some(Diagnostic::error(DiagnosticKind::NotAllowedInProfile, block.span));
                    break;
                }
            }
            // An M code that calls, returns or ends takes the program elsewhere: the control
            // refuses it between P and Q (Fanuc: no M98/M99 in the finishing shape).
            let functions = &self.tables.m_functions;
            let leaves = words.iter().find(|w| match w.kind {
                WordKind::Code { letter: CodeLetter::M, code } => {
                    let m = code.major();
                    functions.subprogram_call.contains(&m)
                        || functions.subprogram_return.contains(&m)
                        || functions.end.contains(&m)
                }
                _ => false,
            });
            if let Some(word) = leaves {
                failure = Some(Diagnostic::error(DiagnosticKind::NotAllowedInProfile, word.span));
                break;
            }
            self.emitter.context.source = block.span;
            for (_, info) in self.g_infos(&words) {
                if info.function == Some(GFunction::LapEnd) {
                    continue;
                }
                self.apply_profile_modal(info);
            }
            if let Some(feed) = self.address_value(&words, Address::F) {
                self.modal.feed = feed;
            }
            if let Some(speed) = self.address_value(&words, Address::S) {
                self.modal.speed = speed;
            }
            if block.statement == Statement::Motion {
                let first_motion = !seen_motion;
                if first_motion {
                    let axes = self.axis_target(&words);
                    first_block_has_both_axes = axes.x_given && axes.z_given;
                    seen_motion = true;
                }
                let before = self.emitter.moves.len();
                let _ = self.motion_block(index, &words);
                let (feed, speed, compensation) = (self.modal.feed, self.modal.speed, self.modal.compensation);
                if first_motion && self.emitter.moves.len() == before {
                    // The first block is the approach of every cycle that reads the profile,
                    // even when it goes nowhere (a rapid to where the tool already is, as
                    // `G00 X50 W0` from X50): an element of no length keeps it in its place.
                    segments.push(Segment {
                        end: self.emitter.at,
                        shape: Shape::Line,
                        rapid: self.modal.motion == super::modal::MotionMode::Rapid,
                        feed,
                        speed,
                        compensation,
                        source: block.span,
                    });
                }
                for m in &self.emitter.moves[before..] {
                    segments.push(Segment {
                        end: m.end,
                        shape: match m.motion {
                            Motion::Cw => Shape::Arc { centre: m.centre, ccw: false },
                            Motion::Ccw => Shape::Arc { centre: m.centre, ccw: true },
                            _ => Shape::Line,
                        },
                        rapid: m.motion == Motion::Rapid,
                        feed,
                        speed,
                        compensation,
                        source: m.source,
                    });
                }
            }
        }
        self.finish_corner_into(&mut segments);
        let modal_after = self.modal.clone();

        // Problems inside the profile are the profile's; keep them, drop the scratch moves.
        // Except a missing feed: the scratch moves' times are thrown away, and the F of a
        // profile usually comes from its cycle (roughing uses the cycle's F, finishing the
        // profile's own or the cycle's), so the cycles that cut report a missing feed.
        let raised = self.diagnostics.split_off(saved_diagnostics);
        self.diagnostics.extend(raised.into_iter().filter(|d| d.kind != DiagnosticKind::NoFeed));
        self.emitter.zero_feed = saved_zero_feed;
        self.emitter.moves.truncate(saved_len);
        self.expansions.truncate(saved_expansions);
        self.emitter.resume_timing_beside(timing_beside);
        self.emitter.at = saved_at;
        self.emitter.time = saved_time;
        self.emitter.context = saved_context;
        self.emitter.first_start = saved_first;
        self.modal = saved_modal;
        if let Some(diagnostic) = failure {
            return Err(diagnostic);
        }
        Ok(Profile { blocks: range, start, segments, first_block_has_both_axes, modal_after })
    }

    fn apply_profile_modal(&mut self, info: &crate::dialect::GInfo) {
        use super::modal::MotionMode;
        use crate::dialect::GFunction as F;
        match info.function {
            Some(F::Rapid) => self.modal.motion = MotionMode::Rapid,
            Some(F::Linear) => self.modal.motion = MotionMode::Linear,
            Some(F::Cw) => self.modal.motion = MotionMode::Cw,
            Some(F::Ccw) => self.modal.motion = MotionMode::Ccw,
            Some(F::Absolute) => self.modal.absolute = true,
            Some(F::Incremental) => self.modal.absolute = false,
            Some(F::CompensationOff) => self.modal.compensation = Compensation::Off,
            Some(F::CompensationLeft) => self.modal.compensation = Compensation::Left,
            Some(F::CompensationRight) => self.modal.compensation = Compensation::Right,
            Some(F::SurfaceSpeed) => self.modal.spindle = super::modal::SpindleMode::SurfaceSpeed,
            Some(F::Rpm) => self.modal.spindle = super::modal::SpindleMode::Rpm,
            _ => {}
        }
    }

    /// A corner pending at the end of a profile ends the profile with its line.
    fn finish_corner_into(&mut self, segments: &mut Vec<Segment>) {
        if self.pending_corner.is_none() {
            return;
        }
        let before = self.emitter.moves.len();
        self.finish_corner();
        let (feed, speed, compensation) = (self.modal.feed, self.modal.speed, self.modal.compensation);
        for m in &self.emitter.moves[before..] {
            segments.push(Segment {
                end: m.end,
                shape: Shape::Line,
                rapid: false,
                feed,
                speed,
                compensation,
                source: m.source,
            });
        }
    }
}
