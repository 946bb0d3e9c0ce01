//! Programs that run but are unlikely to do what their author meant: warnings on the block.
//!
//! - A cutting feed far outside what its mode makes plausible: above
//!   [`FEED_PER_REV_MAX_MM`] per revolution (a feed per minute written under `G99`), or
//!   below [`FEED_PER_MIN_MIN_MM`] per minute (a feed per revolution written under `G98`:
//!   `G98 F0.05` is 0.05 mm/min, and the part takes days). Thread moves are left out: their
//!   F is a lead.
//! - Constant surface speed with no `G50 S` clamp reaching the spindle's top speed (toward
//!   X0): the spindle runs at the machine's maximum, from the settings or the documented
//!   default (`Machine::spindle_limit`).
//! - A thread cut under constant surface speed.
//!
//! Each is said once for as long as its cause stands: a feed once per value and mode, the
//! clamp once per `G96` block that starts constant surface speed.

use crate::diagnostic::DiagnosticKind;
use crate::source::Span;
use crate::toolpath::Motion;

use super::interpreter::Interpreter;
use super::modal::SpindleMode;

/// Above this feed per revolution (mm) a cutting move is implausible: turning and
/// grooving feeds lie between about 0.02 and 1 mm/rev, and a thread's lead is no feed.
pub const FEED_PER_REV_MAX_MM: f64 = 3.0;
/// Below this feed per minute (mm) a cutting move is implausible: it is a feed per
/// revolution's size (0.05–2), and the slowest real feeds per minute (drilling at low
/// speed) are several mm/min.
pub const FEED_PER_MIN_MIN_MM: f64 = 2.0;

/// What has been warned of, so that a cause is said once.
#[derive(Debug, Default)]
pub struct Warned {
    /// The feed word and mode last warned of.
    feed: Option<(u64, bool)>,
    /// The unclamped surface speed of the current `G96` has been warned of.
    surface_speed: bool,
    /// The surface speed the warning was given for (a new `G96 S` may be warned again).
    surface_speed_word: u64,
}

impl Interpreter<'_, '_> {
    /// Check the moves block `span` made (from `first_move` on).
    pub(super) fn check_moves(&mut self, first_move: usize, span: Span) {
        let Some(moves) = self.emitter.moves.get(first_move..) else { return };
        let scale = self.modal.frame.scale();
        let mut feed = None;
        let mut at_limit = false;
        let mut thread_under_css = false;
        let surface_speed = self.modal.surface_speed();
        let limit = surface_speed.clamp;
        for m in moves {
            if m.threading {
                thread_under_css |= self.modal.spindle == SpindleMode::SurfaceSpeed;
                continue;
            }
            if !m.cutting || m.motion == Motion::Rapid || m.motion == Motion::Dwell || m.f_word <= 0.0 {
                continue;
            }
            let mm = m.f_word * scale;
            let implausible = if m.per_revolution { mm > FEED_PER_REV_MAX_MM } else { mm < FEED_PER_MIN_MIN_MM };
            if implausible && feed.is_none() {
                feed = Some((m.f_word, m.per_revolution));
            }
            // A move's rpm is the one at its start; a cut toward X0 reaches the limit at its end.
            let top = m.rpm.max(surface_speed.rpm_at(m.end.x));
            at_limit |= self.modal.spindle == SpindleMode::SurfaceSpeed && top >= limit * (1.0 - 1e-9);
        }
        if let Some((f_word, per_revolution)) = feed
            && self.plausibility.feed != Some((f_word.to_bits(), per_revolution))
        {
            self.plausibility.feed = Some((f_word.to_bits(), per_revolution));
            let inch = self.modal.frame.inch;
            self.warning(DiagnosticKind::ImplausibleFeed { feed: f_word, per_revolution, inch }, span);
        }
        if self.plausibility.surface_speed && self.plausibility.surface_speed_word != self.modal.speed.to_bits() {
            self.plausibility.surface_speed = false;
        }
        if at_limit && !self.modal.clamp_programmed && !self.plausibility.surface_speed {
            self.plausibility.surface_speed = true;
            self.plausibility.surface_speed_word = self.modal.speed.to_bits();
            let (max_rpm, assumed) = self.machine.spindle_limit();
            self.warning(DiagnosticKind::SurfaceSpeedUnclamped { max_rpm, assumed }, span);
        }
        if thread_under_css {
            self.warning(DiagnosticKind::ThreadUnderSurfaceSpeed, span);
        }
    }
}
