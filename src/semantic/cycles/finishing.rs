//! Fanuc `G70 P Q [F S]`: one pass along the profile `P`…`Q` with the F and S written in it
//! (the `G70` F where the profile has none), then a rapid back to the start point. The
//! profile blocks are not executed again afterwards; the program continues after `G70`.

use crate::dialect::Role;
use crate::syntax::Command;
use crate::toolpath::Xz;

use super::super::interpreter::{Flow, Interpreter};
use super::super::modal::MotionMode;
use super::super::profile::{Profile, Shape};
use super::Call;

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command) -> Flow {
    let Some(Call { span, start }) = interp.cycle_call(index) else { return Flow::Next };
    let Some(profile) = interp.profile_of(command, span, start) else { return Flow::Next };
    // In the expanded program the profile's blocks are gone: the moves say it all.
    interp.consume(profile.blocks.clone());
    let feed = interp.param(command, Role::Feed);
    interp.trace_profile(&profile, feed);
    let modal = interp.modal.clone();
    interp.emitter.rapid(&modal, start);
    Flow::Next
}

impl Interpreter<'_, '_> {
    /// The profile named by a command's `P` and `Q` (profile start and end roles).
    pub(in crate::semantic) fn profile_of(
        &mut self,
        command: &Command,
        span: crate::source::Span,
        start: Xz,
    ) -> Option<Profile> {
        let p = self.param(command, Role::ProfileStart)?;
        let q = self.param(command, Role::ProfileEnd)?;
        // Each word that names no block (or several) is reported on itself.
        let word_span = |role| command.param(role).map_or(span, |id| self.program.word(id).span);
        let (p_span, q_span) = (word_span(Role::ProfileStart), word_span(Role::ProfileEnd));
        let first = self.sequence_block(p, p_span);
        let last = self.sequence_block(q, q_span);
        let (first, last) = (first?, last?);
        if last < first {
            self.error(crate::diagnostic::DiagnosticKind::ProfileBackwards, span);
            return None;
        }
        match self.profile(first..=last, start) {
            Ok(profile) => Some(profile),
            Err(diagnostic) => {
                self.diagnostics.push(diagnostic);
                None
            }
        }
    }

    /// Cut along a profile with its own F, S and compensation (`feed` where it has no F).
    pub(in crate::semantic) fn trace_profile(&mut self, profile: &Profile, feed: Option<f64>) {
        let saved = self.modal.clone();
        self.emitter.at = profile.start;
        for segment in &profile.segments {
            // The profile's blocks run here, each from the first move its elements make.
            let block = self.program.blocks().partition_point(|b| b.span.start <= segment.source.start);
            if let Some(block) = block.checked_sub(1).filter(|&b| profile.blocks.contains(&b))
                && self.cycle_traced.last().is_none_or(|&(_, last)| last != block)
            {
                self.cycle_traced.push((self.emitter.moves.len(), block));
            }
            self.modal.feed = if segment.feed > 0.0 { segment.feed } else { feed.unwrap_or(saved.feed) };
            if segment.speed > 0.0 {
                self.modal.speed = segment.speed;
            }
            self.modal.compensation = segment.compensation;
            let modal = self.modal.clone();
            match segment.shape {
                _ if segment.rapid => self.emitter.rapid(&modal, segment.end),
                Shape::Line => self.emitter.line(&modal, segment.end, true),
                Shape::Arc { centre, ccw } => self.emitter.arc(&modal, segment.end, centre, ccw, true),
            }
        }
        self.cycle_traced_end = Some(self.emitter.moves.len());
        // The profile's blocks ran: their motion code, F, S and compensation stay in force
        // after the cycle, as after any executed block.
        let (feed, speed, compensation) = (self.modal.feed, self.modal.speed, self.modal.compensation);
        let motion = profile.segments.last().map(|segment| match segment.shape {
            _ if segment.rapid => MotionMode::Rapid,
            Shape::Line => MotionMode::Linear,
            Shape::Arc { ccw: true, .. } => MotionMode::Ccw,
            Shape::Arc { ccw: false, .. } => MotionMode::Cw,
        });
        self.modal = saved;
        self.modal.feed = feed;
        self.modal.speed = speed;
        self.modal.compensation = compensation;
        if let Some(motion) = motion {
            self.modal.motion = motion;
        }
        let span = self.emitter.context.source;
        self.report_zero_feed(span);
    }
}
