//! Fanuc `G73` pattern repeating: two-block form (`G73 U(Δi) W(Δk) R(d)` then
//! `G73 P Q U(Δu) W(Δw) F S T`) and the Haas one-block form (`G73 P Q U W I(Δi) K(Δk) D(d) F`).
//!
//! The cycle cuts the finishing profile P…Q `d` times, each time shifted a little less, for
//! blanks (castings, forgings) whose stock already follows the part. Pass `k` of `d` is the
//! profile shifted by the allowance (Δu/2 in X, Δw in Z) plus the relief (Δi in X, radius;
//! Δk in Z) scaled by `(d − k)/(d − 1)`: the first pass lies the whole relief out, the last
//! exactly at the allowance (with `d = 1` the only pass is the last one).
//!
//! ```txt
//!   A ●◀─────────────────────────╮ rapid back to A after every pass
//!     ╲ approach (as the P block)│
//!      ●━━━━━━━━━╮ pass 1        │ (profile + allowance + relief)
//!       ●━━━━━━━╮ ╲ pass 2       │
//!        ●━━━━━╮ ╲ ╲ …           │
//!         ●━━━╮ ╲ ╲ ╲ pass d ────╯ (profile + allowance)
//! ```
//!
//! Each pass moves from A to the shifted start of the profile the way the P block moves
//! (`G00` or `G01`), follows the shifted profile at the cycle's F (a `G00` inside the
//! profile stays a rapid), and returns to A at rapid: first away from the part in X, then
//! along Z, then to A's X, so that the return never crosses the stock. F, S and T inside
//! P…Q are for finishing (`G70`). The passes run under the compensation in effect at the
//! call. After the cycle the program continues after the Q block: the profile is a
//! definition.

use crate::diagnostic::DiagnosticKind;
use crate::dialect::Role;
use crate::syntax::Command;
use crate::toolpath::Xz;

use super::super::interpreter::{Flow, Interpreter};
use super::super::profile::{Profile, Shape};
use super::Call;
use super::MAX_CYCLE_PASSES;

/// What `G73 U(Δi) W(Δk) R(d)` set, program units (Δi a radius), kept for the cycle block.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PatternMemory {
    pub relief_x: Option<f64>,
    pub relief_z: Option<f64>,
    pub divisions: Option<f64>,
    /// The first block, which the cycle block consumes.
    pub first_block: Option<usize>,
}

/// The first block of the two-block form only sets the relief and the number of passes.
pub(super) fn relief_block(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command) -> Flow {
    let relief_x = interp.param(command, Role::ReliefX);
    let relief_z = interp.param(command, Role::ReliefZ);
    let divisions = interp.param_count(command, Role::Divisions);
    let memory = &mut interp.cycle_memory.pattern;
    memory.first_block = Some(index);
    memory.relief_x = relief_x.or(memory.relief_x);
    memory.relief_z = relief_z.or(memory.relief_z);
    memory.divisions = divisions.or(memory.divisions);
    Flow::Next
}

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command) -> Flow {
    // With the tool's position unknown the cycle moves nothing (warned), but its profile is
    // still the cycle's, not blocks to run: the control goes on after `Q`.
    let Some(Call { span, start }) = interp.cycle_call(index) else { return interp.after_profile(command, index) };
    let frame = interp.modal.frame;
    let one_block = interp.form_name(command) == "one_block";
    let (relief_x, relief_z, divisions) = if one_block {
        (
            interp.param(command, Role::ReliefX),
            interp.param(command, Role::ReliefZ),
            interp.param_count(command, Role::Divisions),
        )
    } else {
        let memory = interp.cycle_memory.pattern;
        (memory.relief_x, memory.relief_z, memory.divisions)
    };
    // Δi is a radius value whatever the X programming: only the units change.
    let relief = Xz::new(relief_x.map_or(0.0, |i| frame.mm(i)), relief_z.map_or(0.0, |k| frame.mm(k)));
    let allowance = Xz::new(
        interp.param(command, Role::AllowanceX).map_or(0.0, |u| frame.x_mm(u)),
        interp.param(command, Role::AllowanceZ).map_or(0.0, |w| frame.mm(w)),
    );
    let Some(profile) = interp.profile_of(command, span, start) else { return Flow::Next };
    let after_q = interp.after_profile(command, index);
    // The profile and the first block are part of the cycle: `expand` deletes them.
    interp.consume(profile.blocks.clone());
    interp.consume_skipped(index, *profile.blocks.start(), after_q);
    if !one_block {
        interp.consume_setup(interp.cycle_memory.pattern.first_block);
    }
    if profile.segments.is_empty() {
        interp.error(DiagnosticKind::EmptyProfile, span);
        return after_q;
    }
    let passes = match divisions.map(f64::round) {
        Some(d) if d >= 1.0 && d <= MAX_CYCLE_PASSES as f64 => d as u32,
        Some(d) if d > MAX_CYCLE_PASSES as f64 => {
            let passes = if d.is_finite() { d as u64 } else { u64::MAX };
            interp.error(DiagnosticKind::CycleTooManyPasses { passes, max: MAX_CYCLE_PASSES }, span);
            return after_q;
        }
        _ => {
            interp.error(DiagnosticKind::CycleNeedsDivisions, span);
            return after_q;
        }
    };

    let saved = interp.modal.clone();
    interp.modal.feed = interp.param(command, Role::Feed).unwrap_or(saved.feed);
    if let Some(s) = interp.param(command, Role::Speed) {
        interp.modal.speed = s;
    }
    for k in 1..=passes {
        cut_pass(interp, &profile, pass_offset(relief, allowance, k, passes), start);
    }
    interp.modal = saved;
    interp.report_zero_feed(span);
    after_q
}

/// How far pass `k` (1-based) of `passes` lies from the profile: the allowance plus the
/// relief scaled by `(passes − k)/(passes − 1)`, so the last pass lies at the allowance.
pub fn pass_offset(relief: Xz, allowance: Xz, k: u32, passes: u32) -> Xz {
    let fraction = if passes <= 1 { 0.0 } else { f64::from(passes.saturating_sub(k)) / f64::from(passes - 1) };
    Xz::new(allowance.x + relief.x * fraction, allowance.z + relief.z * fraction)
}

/// One pass: from A along the shifted profile, and back to A.
fn cut_pass(interp: &mut Interpreter<'_, '_>, profile: &Profile, offset: Xz, start: Xz) {
    let shift = |p: Xz| Xz::new(p.x + offset.x, p.z + offset.z);
    let modal = interp.modal.clone();
    let Some((first, rest)) = profile.segments.split_first() else { return };
    let entry = shift(first.end);
    if first.rapid {
        interp.emitter.rapid(&modal, entry);
    } else {
        interp.emitter.line(&modal, entry, true);
    }
    for segment in rest {
        let to = shift(segment.end);
        match segment.shape {
            _ if segment.rapid => interp.emitter.rapid(&modal, to),
            Shape::Line => interp.emitter.line(&modal, to, true),
            Shape::Arc { centre, ccw } => interp.emitter.arc(&modal, to, shift(centre), ccw, true),
        }
    }
    // Back to A: out past A's X (outside when A lies outside the entry point), along Z, in.
    let at = interp.emitter.at;
    let outside = start.x >= entry.x;
    let clear_x = if outside { at.x.max(start.x) } else { at.x.min(start.x) };
    interp.emitter.rapid(&modal, Xz::new(clear_x, at.z));
    interp.emitter.rapid(&modal, Xz::new(clear_x, start.z));
    interp.emitter.rapid(&modal, start);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_pass_carries_the_whole_relief_and_the_last_none() {
        let relief = Xz::new(3.0, -1.5);
        let allowance = Xz::new(0.2, 0.1);
        assert_eq!(pass_offset(relief, allowance, 1, 4), Xz::new(3.2, -1.4));
        assert_eq!(pass_offset(relief, allowance, 4, 4), allowance);
        let second = pass_offset(relief, allowance, 2, 4);
        assert!((second.x - (0.2 + 2.0)).abs() < 1e-12 && (second.z - (0.1 - 1.0)).abs() < 1e-12);
        // One pass: at the allowance.
        assert_eq!(pass_offset(relief, allowance, 1, 1), allowance);
    }
}
