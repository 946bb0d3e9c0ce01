//! OSP compound (multi-pass) thread cutting: `G71` longitudinal, `G72` on a face
//! ([M3277] P-166…170, [OKB], dialects.md §1.6; not the Fanuc roughing cycles):
//!
//! `G71 X Z [A | I] B D [U] H [L] [E] F [J] M3x M7x [Q]`
//!
//! `X` is the root diameter at the thread's end `Z`, `H` the thread height and `D` the
//! first depth (both diameters: `H1.84` is the 0.92 mm height of an M20×1.5 thread; [M3277]
//! P-166…170, dialects.md §1.6, and for `G88` 5238-E P-175, "D, DA, DB, XA, XB, U and H
//! words must be commanded as diameter values"; the 5238-E page of `G71` itself was not
//! reached), `U` the finishing allowance (diameter; no finishing pass without it), `B` the tool's included angle (0 ≤ B < 180, radial infeed at 0), `M32`/
//! `M33`/`M34` the infeed mode and `M73`/`M74`/`M75` the pattern (`thread_infeed.rs` gives
//! the depths), `Q` the number of starts. `G72` swaps the axes: `X` is where the thread
//! ends, `Z` the root, `W` the allowance, `K` the taper; its `D`, `H` and `W` run along Z
//! and are plain lengths.
//!
//! Every pass is the `G33` pass of `thread_pass.rs` from the tool's position S: the crest
//! lies `H/2` outside the root (toward S), a pass at depth `d` cuts `(H − d)/2` outside the
//! root, and with a flank mode its start moves along the thread's axis by
//! `flank · (H − d)/2 · tan(B/2)`, so that successive passes walk down one flank (or
//! alternate) to the centred last pass. Each depth is cut once per start, one start after
//! the other (`Q`); the phase of a start turns the spindle and changes no move, only where
//! its grooves fall (start `j` of `Q` begins `j/Q` of a turn on, `Move::phase`).
//!
//! Readings of the sources, and what this module does:
//!
//! - `M32` moves the shallow passes toward the thread's start (the tool walks toward its
//!   end as it deepens); `M34` the other way; `M33` alternates, beginning as `M32`.
//! - Only the start of a pass shifts, as `G33 K` shifts it; the end stays at `Z`.
//! - The chamfer (`M23`, length `L`, one lead without `L`) ends every pass, not only the
//!   last; [OKB] says "at the last thread cutting cycle", which reads as each pass of it.
//! - `E` changes the lead per revolution as written; the time uses the mean lead.

use crate::diagnostic::DiagnosticKind;
use crate::dialect::{GFunction, Role};
use crate::source::Span;
use crate::syntax::{Command, WordKind};

use super::super::interpreter::{Flow, Interpreter};
use super::Call;
use super::thread_infeed::{self, Infeed, InfeedError, InfeedMode, InfeedPattern, Plan};
use super::thread_pass::{self, Axes, Pass};

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command, function: GFunction) -> Flow {
    let Some(Call { span, start: from }) = interp.cycle_call(index) else { return Flow::Next };
    let axes = Axes { face: function == GFunction::CompoundThreadFace };
    let Some(infeed) = infeed_of(interp, command, span) else { return Flow::Next };
    let frame = interp.modal.frame;
    let end = interp.cycle_end(command, from);
    let length = (axes.along(end) - axes.along(from)).abs();
    thread_pass::warn_if_no_length(interp, length, span);
    let taper = thread_pass::taper(interp, command, length);
    let (modal, lead_mm) = thread_pass::thread_modal(interp, command);
    let change = thread_pass::lead_change(interp, command);
    let chamfer = thread_pass::chamfer(interp, command, lead_mm);
    let to_mm = |d: f64| if axes.face { frame.mm(d) } else { frame.x_mm(d) };
    let out = thread_pass::outward(axes, from, end);
    let toward_start = if axes.along(from) >= axes.along(end) { 1.0 } else { -1.0 };
    let height = to_mm(infeed.height);
    if !axes.face {
        height_read_as_diameter(interp, command, &infeed, lead_mm);
    }
    for pass in &infeed.plan.passes {
        let above_root = height - to_mm(pass.depth);
        let shift = pass.flank * above_root * infeed.flank_slope * toward_start;
        let end_depth = axes.depth(end) + out * above_root;
        let thread = Pass {
            axes,
            from,
            points: vec![
                axes.point(axes.along(from) + shift, end_depth + taper),
                axes.point(axes.along(end), end_depth),
            ],
            chamfer,
        };
        for start in 0..infeed.starts {
            // The starts share the turn evenly: start `j` begins `j/Q` of a turn on.
            interp.emitter.thread_phase = f64::from(start) / f64::from(infeed.starts);
            let lasts = thread.emit(interp, &modal, (lead_mm, change));
            thread_pass::report_lead_to_nothing(interp, lasts, span);
        }
        interp.emitter.thread_phase = 0.0;
    }
    interp.report_zero_feed(span);
    Flow::Next
}

/// The height of a 60° thread as a diameter, per unit of pitch: twice the ISO external
/// thread's 0.6134 × pitch (ISO 68-1 basic profile, h3).
pub(super) const THREAD_HEIGHT_DIAMETER_PER_PITCH: f64 = 2.0 * 0.6134;

/// A longitudinal OSP thread's `H` is a diameter (see the module documentation): say how
/// the expansion reads it, and warn where it is nearer the radial height of the thread's
/// pitch than its height as a diameter (under their geometric mean, the full height / √2),
/// as a programmer used to Fanuc's radial `G76` heights writes it: `H0.92` for M20×1.5 cuts
/// 0.46 mm deep, half the thread.
pub(super) fn height_read_as_diameter(
    interp: &mut Interpreter<'_, '_>,
    command: &Command,
    infeed: &CheckedInfeed,
    lead_mm: f64,
) {
    let frame = interp.modal.frame;
    let Some(id) = command.param(Role::ThreadHeight) else { return };
    let word = *interp.program.word(id);
    let written = match word.kind {
        WordKind::Number { address, number } => {
            format!("{}{}", address.name(), crate::syntax::spelling::plain(number))
        }
        _ => "H".to_string(),
    };
    let depth_mm = frame.x_mm(infeed.height);
    let passes = infeed.plan.passes.len() * infeed.starts as usize;
    interp.expansion_note = Some(DiagnosticKind::ThreadHeightAsDiameter { word: written.clone(), depth_mm, passes });
    let pitch_mm = lead_mm / f64::from(infeed.starts.max(1));
    let full_mm = THREAD_HEIGHT_DIAMETER_PER_PITCH * pitch_mm;
    let height_mm = frame.mm(infeed.height);
    if !frame.diameter || pitch_mm <= 0.0 || height_mm >= full_mm / std::f64::consts::SQRT_2 {
        return;
    }
    let meant = match word.kind {
        WordKind::Number { .. } => Some(format!("H{}", crate::dialect::roles::short(infeed.height * 2.0))),
        _ => None,
    };
    let kind = DiagnosticKind::ThreadHeightRadial { word: written, depth_mm, pitch_mm, meant };
    interp.warning(kind, word.span);
}

/// The infeed a multi-pass thread block asks for, checked: the pass plan (program units),
/// `tan(B/2)`, the thread height and the number of starts.
pub(super) struct CheckedInfeed {
    pub plan: Plan,
    pub flank_slope: f64,
    pub height: f64,
    pub starts: u32,
}

/// Read and check `D`, `H`, `U`/`W`, `B`, `Q` and the infeed M codes of a `G71`/`G72`/`G88`
/// block; what the control rejects becomes an error on the word at fault.
pub(super) fn infeed_of(interp: &mut Interpreter<'_, '_>, command: &Command, span: Span) -> Option<CheckedInfeed> {
    let angle = interp.param(command, Role::InfeedAngle).unwrap_or(0.0);
    if !(0.0..180.0).contains(&angle) {
        let at = interp.param_span(command, Role::InfeedAngle, span);
        interp.error(DiagnosticKind::InfeedAngleOutOfRange { angle }, at);
        return None;
    }
    let functions = &interp.tables.m_functions;
    let mode = match interp.m_params(command, Role::InfeedMode).first() {
        Some(m) if functions.infeed_zigzag.contains(m) => InfeedMode::Zigzag,
        Some(m) if functions.infeed_other_flank.contains(m) => InfeedMode::OtherFlank,
        _ => InfeedMode::OneFlank,
    };
    let functions = &interp.tables.m_functions;
    let pattern = match interp.m_params(command, Role::InfeedPattern).first() {
        Some(m) if functions.infeed_pattern_2.contains(m) => InfeedPattern::ConstantArea,
        Some(m) if functions.infeed_pattern_3.contains(m) => InfeedPattern::Pattern3,
        _ => InfeedPattern::ConstantDepth,
    };
    let height = interp.param(command, Role::ThreadHeight).unwrap_or(0.0);
    let infeed = Infeed {
        mode,
        pattern,
        first_depth: interp.param(command, Role::FirstDepth).unwrap_or(0.0),
        height,
        allowance: interp.param(command, Role::FinishAllowance),
    };
    let plan = match thread_infeed::plan(&infeed) {
        Ok(plan) => plan,
        Err(error) => {
            let (kind, role) = match error {
                InfeedError::FirstDepthNotPositive => {
                    (DiagnosticKind::ThreadDepthNotPositive { address: 'D' }, Role::FirstDepth)
                }
                InfeedError::HeightNotPositive => {
                    (DiagnosticKind::ThreadDepthNotPositive { address: 'H' }, Role::ThreadHeight)
                }
                InfeedError::RoughDepthBelowFirstCut { rough_depth } => (
                    DiagnosticKind::ThreadRoughDepthBelowFirstCut { rough_depth, first_depth: infeed.first_depth },
                    Role::FirstDepth,
                ),
                InfeedError::AllowanceOverHeight => (
                    DiagnosticKind::ThreadAllowanceOverHeight { height, allowance: infeed.allowance.unwrap_or(0.0) },
                    Role::FinishAllowance,
                ),
                InfeedError::TooManyPasses { passes } => {
                    (DiagnosticKind::TooManyPasses { passes, max: thread_infeed::MAX_PASSES }, Role::FirstDepth)
                }
            };
            let at = interp.param_span(command, role, span);
            interp.error(kind, at);
            return None;
        }
    };
    if plan.approximated {
        let at = interp.param_span(command, Role::InfeedPattern, span);
        interp.warning(DiagnosticKind::InfeedPatternApproximated, at);
    }
    let starts = interp.param(command, Role::Starts).map_or(1.0, |q| q.round().max(1.0));
    if starts * plan.passes.len() as f64 > thread_infeed::MAX_PASSES as f64 {
        let passes = (starts * plan.passes.len() as f64).min(usize::MAX as f64) as usize;
        let at = interp.param_span(command, Role::Starts, span);
        interp.error(DiagnosticKind::TooManyPasses { passes, max: thread_infeed::MAX_PASSES }, at);
        return None;
    }
    Some(CheckedInfeed { plan, flank_slope: (angle / 2.0).to_radians().tan(), height, starts: starts as u32 })
}
