//! Fanuc `G76` multiple threading: two-block form (`G76 P(m)(r)(a) Q(Δdmin) R(d)` then
//! `G76 X(U) Z(W) R(i) P(k) Q(Δd) F(L)`) and the Haas one-block form
//! (`G76 X Z K(k) D(Δd) F(L) [A(a) I(i) P(mode)]`).
//!
//! The end point (X, Z) is the thread's root at its end; `k` is the thread height and `Δd`
//! the first depth of cut (radius values; Fanuc `P`/`Q` in least increments), `i` the
//! taper (radius at the start minus radius at the end, as in `G92`), `L` the lead.
//!
//! ```txt
//!   A ●◀───────────────────────────────╮ rapid back to A
//!     │ rapid infeed to the pass depth │ rapid out to A's X
//!     ●━━━━━━━━━ thread (G32) ━━━━━━━━━╮
//!                                      ╲ chamfer: 45° pull-out over r·L/10
//!   depth of pass n: Δd·√n (at least Δdmin deeper than the pass before), up to k − d;
//!   then one pass at k (removing the finishing allowance d) and m − 1 spring passes at k
//! ```
//!
//! Infeed follows the tool's flank (single-edge cutting): the pass at depth `D` lies
//! `(k − D)·tan(a/2)` toward the start in Z from the last, so the trailing edge of the tool
//! slides down the flank on the start side and only the leading edge cuts; the finishing
//! passes lie at the programmed end. Haas `P2`/`P4` alternate the flank from pass to pass,
//! `P3`/`P4` cut a constant depth `Δd` per pass instead of a constant area.
//!
//! The first block's values are modal. Without one the control uses its parameters, which
//! are not in the machine settings: turnpass takes one finishing pass, no chamfer, a radial
//! infeed (`a = 0`), no minimum depth and no allowance. The Haas form has no chamfer here:
//! its size is Haas Setting 95 (and both corpus programs turn it off with `M24`). The Haas
//! `Q`, the start angle of one start of a multi-start thread (0.001°), does not change the
//! path in XZ: it turns the spindle past its index before each pass (`Move::phase`).

use crate::diagnostic::DiagnosticKind;
use crate::dialect::Role;
use crate::source::Span;
use crate::syntax::{Command, Word};
use crate::toolpath::Xz;

use super::super::interpreter::{Flow, Interpreter};
use super::MAX_CYCLE_PASSES;

const EPSILON: f64 = 1e-9;

/// What `G76 P(m)(r)(a) Q(Δdmin) R(d)` set (program units), kept for the cycle blocks.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ThreadMemory {
    pub parameters: Option<ThreadParameters>,
    pub min_depth: Option<f64>,
    pub allowance: Option<f64>,
    /// The first block, which the cycle block consumes.
    pub first_block: Option<usize>,
    /// The last first block had `P` digits the control rejects (already reported): the
    /// control stops there, so its cycle block cuts nothing.
    pub rejected: bool,
}

/// The six digits of `G76 P(m)(r)(a)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ThreadParameters {
    /// `m`: passes at the full depth (the first removes the finishing allowance).
    pub finishing_passes: u32,
    /// `r`: the chamfer at the thread's end, in tenths of the lead.
    pub chamfer_tenths: u32,
    /// `a`: the tool's included angle, degrees.
    pub tool_angle: u32,
}

impl Default for ThreadParameters {
    fn default() -> Self {
        ThreadParameters { finishing_passes: 1, chamfer_tenths: 0, tool_angle: 0 }
    }
}

/// The tool angles a Fanuc control takes in `G76 P`.
const FANUC_TOOL_ANGLES: [u32; 6] = [0, 29, 30, 55, 60, 80];

/// Decode `P(m)(r)(a)`: two digits each, `P010060` is one finishing pass, no chamfer, 60°.
/// Leading zeros may be left out (`P10060`). `None` when the value is not six digits of
/// which `m` is 01-99 and `a` one of the angles the control takes.
pub fn decode_parameters(value: f64) -> Option<ThreadParameters> {
    if !value.is_finite() || value < 0.0 || value.fract() != 0.0 || value > 999_999.0 {
        return None;
    }
    let digits = value as u32;
    let parameters = ThreadParameters {
        finishing_passes: digits / 10_000,
        chamfer_tenths: digits / 100 % 100,
        tool_angle: digits % 100,
    };
    (parameters.finishing_passes >= 1 && FANUC_TOOL_ANGLES.contains(&parameters.tool_angle)).then_some(parameters)
}

/// The depths of the roughing passes, mm: pass `n` at `first·√n` (constant area) or
/// `first·n` (constant depth), at least `min` deeper than the pass before, the last one at
/// `limit` (the height less the finishing allowance). Strictly increasing; empty when
/// `limit` is not above zero. `Err` with the number of passes when there would be more than
/// `max`.
pub fn roughing_depths(first: f64, min: f64, limit: f64, constant_area: bool, max: u64) -> Result<Vec<f64>, u64> {
    if limit <= EPSILON {
        return Ok(Vec::new());
    }
    // An upper bound on the count: the minimum step bounds it too.
    let by_first = if constant_area { (limit / first).powi(2) } else { limit / first };
    let by_min = if min > EPSILON { limit / min } else { f64::INFINITY };
    let bound = by_first.min(by_min).ceil() + 1.0;
    if !bound.is_finite() || bound > max as f64 {
        return Err(if bound.is_finite() { bound as u64 } else { u64::MAX });
    }
    let mut depths: Vec<f64> = Vec::new();
    let mut n = 1.0_f64;
    loop {
        let previous = depths.last().copied().unwrap_or(0.0);
        let wanted = if constant_area { first * n.sqrt() } else { first * n };
        let depth = wanted.max(previous + min);
        if depth >= limit - EPSILON || depths.len() as u64 >= max {
            depths.push(limit);
            return Ok(depths);
        }
        depths.push(depth);
        n += 1.0;
    }
}

/// One thread pass: its depth below the crest and its shift toward the start in Z, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pass {
    pub depth: f64,
    pub shift: f64,
}

/// How the tool feeds in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Infeed {
    pub constant_area: bool,
    /// Alternate flanks (Haas `P2`, `P4`) instead of one.
    pub alternate: bool,
    /// The tool's included angle, degrees.
    pub angle: f64,
}

/// Every pass of the cycle: the roughing passes, then `finishing` passes at `height`.
pub fn passes(roughing: &[f64], height: f64, finishing: u32, infeed: Infeed) -> Vec<Pass> {
    let flank = (infeed.angle.to_radians() / 2.0).tan();
    let mut out: Vec<Pass> = roughing
        .iter()
        .enumerate()
        .map(|(n, &depth)| {
            let side = if infeed.alternate && n % 2 == 1 { -1.0 } else { 1.0 };
            Pass { depth, shift: side * (height - depth) * flank }
        })
        .collect();
    out.extend((0..finishing.max(1)).map(|_| Pass { depth: height, shift: 0.0 }));
    out
}

/// The first block of the two-block form only sets the passes' parameters.
pub(super) fn passes_block(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command) -> Flow {
    let span = interp.program.block(index).span;
    let raw = interp.param_count(command, Role::ThreadParameters);
    let min_depth = interp.param_increments(command, Role::MinDepth);
    let allowance = interp.param(command, Role::FinishAllowance);
    let parameters = raw.map(decode_parameters);
    if let Some(None) = parameters {
        reject_word(interp, command, Role::ThreadParameters, span);
    }
    let memory = &mut interp.cycle_memory.thread;
    memory.first_block = Some(index);
    memory.rejected = matches!(parameters, Some(None));
    let parameters = parameters.flatten();
    memory.parameters = parameters.or(memory.parameters);
    memory.min_depth = min_depth.or(memory.min_depth);
    memory.allowance = allowance.or(memory.allowance);
    Flow::Next
}

/// Report the word of `role` as a threading parameter the control rejects.
fn reject_word(interp: &mut Interpreter<'_, '_>, command: &Command, role: Role, span: Span) {
    let at = interp.param_span(command, role, span);
    let word = String::from_utf8_lossy(interp.program.text(at)).into_owned();
    interp.error(DiagnosticKind::ThreadParametersInvalid { word }, at);
}

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command, name: &str) -> Flow {
    let span = interp.program.block(index).span;
    let frame = interp.modal.frame;
    let one_block = interp.form_name(command) == "one_block";
    if !one_block && interp.cycle_memory.thread.rejected {
        return Flow::Next;
    }
    let (height, first) = if one_block {
        (interp.param(command, Role::ThreadHeight), interp.param(command, Role::FirstDepth))
    } else {
        (interp.param_increments(command, Role::ThreadHeight), interp.param_increments(command, Role::FirstDepth))
    };
    let (Some(height), Some(first)) =
        (height.map(|k| frame.mm(k.abs())).filter(|k| *k > 0.0), first.map(|d| frame.mm(d.abs())).filter(|d| *d > 0.0))
    else {
        let words = if one_block {
            "`K` (the thread height) and `D` (the first depth of cut)"
        } else {
            "`P` (the thread height) and `Q` (the first depth of cut)"
        };
        interp.error(DiagnosticKind::MissingWord { command: name.to_string(), words: words.to_string() }, span);
        return Flow::Next;
    };
    if height < first - EPSILON {
        let at = interp.param_span(command, Role::ThreadHeight, span);
        interp.error(DiagnosticKind::ThreadHeightBelowFirstDepth { height_mm: height, first_depth_mm: first }, at);
        return Flow::Next;
    }
    let lead = interp.param(command, Role::Lead).unwrap_or(interp.modal.feed);
    let lead_mm = frame.feed_mm(lead);
    if !(lead_mm > 0.0 && lead_mm.is_finite()) {
        let at = interp.param_span(command, Role::Lead, span);
        interp.error(DiagnosticKind::ThreadLeadNotPositive, at);
        return Flow::Next;
    }
    let Some((infeed, parameters)) = infeed(interp, command, one_block, span) else { return Flow::Next };
    let Some(start) = interp.known_position(span) else { return Flow::Next };
    let memory = interp.cycle_memory.thread;
    let min_depth = memory.min_depth.map_or(0.0, |q| frame.mm(q.abs()));
    let allowance = memory.allowance.map_or(0.0, |r| frame.mm(r.abs()));
    let roughing = match roughing_depths(first, min_depth, height - allowance, infeed.constant_area, MAX_CYCLE_PASSES) {
        Ok(depths) => depths,
        Err(passes) => {
            interp.error(DiagnosticKind::CycleTooManyPasses { passes, max: MAX_CYCLE_PASSES }, span);
            return Flow::Next;
        }
    };

    let words: Vec<Word> = command.params.iter().map(|p| *interp.program.word(p.word)).collect();
    let axes = interp.axis_target(&words);
    let target = axes.target.unwrap_or(start);
    let end = Xz::new(if axes.x_given { target.x } else { start.x }, if axes.z_given { target.z } else { start.z });
    super::thread_pass::warn_if_no_length(interp, (end.z - start.z).abs(), span);
    let thread = Thread {
        start,
        end,
        taper: interp.param(command, Role::Taper).map_or(0.0, |i| frame.mm(i)),
        height,
        lead_mm,
        chamfer: f64::from(parameters.chamfer_tenths) / 10.0 * lead_mm,
    };
    // The first block is part of the cycle: `expand` deletes it.
    if !one_block {
        interp.consume_setup(interp.cycle_memory.thread.first_block);
    }
    let saved = interp.modal.clone();
    // The lead is the F of the thread moves (what `expand` writes on its `G32` blocks).
    interp.modal.feed = lead;
    // Haas's `Q`: every pass of this start begins that far past the spindle's index.
    interp.emitter.thread_phase =
        interp.param(command, Role::ShiftAngle).map_or(0.0, super::thread_pass::start_angle_turns);
    for pass in passes(&roughing, height, parameters.finishing_passes, infeed) {
        thread.cut(interp, pass);
    }
    interp.emitter.thread_phase = 0.0;
    interp.modal = saved;
    interp.report_zero_feed(span);
    Flow::Next
}

/// The infeed and the first block's parameters; `None` (reported) when a Haas `P` or `A`
/// is outside what the control takes.
fn infeed(
    interp: &mut Interpreter<'_, '_>,
    command: &Command,
    one_block: bool,
    span: Span,
) -> Option<(Infeed, ThreadParameters)> {
    let parameters = interp.cycle_memory.thread.parameters.unwrap_or_default();
    if !one_block {
        let infeed = Infeed { constant_area: true, alternate: false, angle: f64::from(parameters.tool_angle) };
        return Some((infeed, parameters));
    }
    // Haas: `A` in whole degrees (written without a decimal point), `P` the infeed mode.
    let angle = interp.param_count(command, Role::ToolAngle).unwrap_or(0.0);
    if !(0.0..=120.0).contains(&angle) {
        reject_word(interp, command, Role::ToolAngle, span);
        return None;
    }
    let mode = interp.param_count(command, Role::InfeedMode).unwrap_or(1.0);
    let whole = if mode.fract() == 0.0 && (1.0..=4.0).contains(&mode) { mode as u8 } else { 0 };
    let (constant_area, alternate) = match whole {
        1 => (true, false),
        2 => (true, true),
        3 => (false, false),
        4 => (false, true),
        _ => {
            reject_word(interp, command, Role::InfeedMode, span);
            return None;
        }
    };
    let haas = ThreadParameters { chamfer_tenths: 0, ..parameters };
    Some((Infeed { constant_area, alternate, angle }, haas))
}

/// The thread in the toolpath frame, mm.
struct Thread {
    start: Xz,
    /// The root at the thread's end.
    end: Xz,
    taper: f64,
    height: f64,
    lead_mm: f64,
    chamfer: f64,
}

impl Thread {
    /// One pass: infeed from A, the thread (and its chamfer), out to A's X, back to A.
    fn cut(&self, interp: &mut Interpreter<'_, '_>, pass: Pass) {
        let modal = interp.modal.clone();
        let (a, end) = (self.start, self.end);
        // An outside thread has its crest outward of the root; A lies outside the crest.
        let outward = if a.x >= end.x + self.taper { 1.0 } else { -1.0 };
        let toward_start = if a.z >= end.z { 1.0 } else { -1.0 };
        let inset = outward * (self.height - pass.depth);
        let z_shift = toward_start * pass.shift;
        let from = Xz::new(end.x + self.taper + inset, a.z + z_shift);
        let to = Xz::new(end.x + inset, end.z + z_shift);
        let e = &mut interp.emitter;
        e.rapid(&modal, from);
        let chamfer = self.chamfer.min((to.z - from.z).abs());
        if chamfer > EPSILON {
            let z = to.z + toward_start * chamfer;
            let t = (z - from.z) / (to.z - from.z);
            e.thread(&modal, Xz::new(from.x + (to.x - from.x) * t, z), self.lead_mm);
            e.thread(&modal, Xz::new(to.x + outward * chamfer, to.z), self.lead_mm);
        } else {
            e.thread(&modal, to, self.lead_mm);
        }
        let at = e.at;
        let clear_x = if outward > 0.0 { at.x.max(a.x) } else { at.x.min(a.x) };
        e.rapid(&modal, Xz::new(clear_x, at.z));
        e.rapid(&modal, Xz::new(clear_x, a.z));
        e.rapid(&modal, a);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn p_digits_decode_two_by_two() {
        let p = |m, r, a| Some(ThreadParameters { finishing_passes: m, chamfer_tenths: r, tool_angle: a });
        assert_eq!(decode_parameters(10060.0), p(1, 0, 60));
        assert_eq!(decode_parameters(12060.0), p(1, 20, 60));
        assert_eq!(decode_parameters(21029.0), p(2, 10, 29));
        assert_eq!(decode_parameters(990000.0), p(99, 0, 0));
        // No finishing pass, an angle the control does not take, too many digits, a fraction.
        assert_eq!(decode_parameters(60.0), None);
        assert_eq!(decode_parameters(10045.0), None);
        assert_eq!(decode_parameters(1_010_060.0), None);
        assert_eq!(decode_parameters(10060.5), None);
        assert_eq!(decode_parameters(-10060.0), None);
    }

    #[test]
    fn depths_follow_the_square_root_clamped_by_the_minimum() {
        // leohiei-1: Δd 0.27, Δdmin 0.08, k 0.812, d 0.08 → roughing to 0.732.
        let depths = roughing_depths(0.27, 0.08, 0.732, true, 100).unwrap();
        let expected =
            [0.27, 0.27 * 2f64.sqrt(), 0.27 * 3f64.sqrt(), 0.27 * 3f64.sqrt() + 0.08, 0.27 * 3f64.sqrt() + 0.16];
        assert_eq!(depths.len(), 7);
        for (got, want) in depths.iter().zip(expected) {
            assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        }
        assert!((depths[5] - (0.27 * 3f64.sqrt() + 0.24)).abs() < 1e-12);
        assert_eq!(depths[6], 0.732);
        assert_eq!(roughing_depths(0.1, 0.0, 1.0, false, 100).unwrap().len(), 10);
        assert_eq!(roughing_depths(0.001, 0.0, 10.0, true, 100), Err(100_000_001));
        assert!(roughing_depths(0.3, 0.0, 0.0, true, 100).unwrap().is_empty());
    }

    #[test]
    fn flank_infeed_shifts_shallow_passes_toward_the_start() {
        let infeed = Infeed { constant_area: true, alternate: false, angle: 60.0 };
        let all = passes(&[0.5, 0.8], 1.0, 2, infeed);
        let tan30 = (30f64).to_radians().tan();
        assert_eq!(all.len(), 4);
        assert!((all[0].shift - 0.5 * tan30).abs() < 1e-12);
        assert!((all[1].shift - 0.2 * tan30).abs() < 1e-12);
        assert_eq!(all[2], Pass { depth: 1.0, shift: 0.0 });
        assert_eq!(all[3], Pass { depth: 1.0, shift: 0.0 });
        let alternate = passes(&[0.5, 0.8], 1.0, 1, Infeed { alternate: true, ..infeed });
        assert!((alternate[1].shift + 0.2 * tan30).abs() < 1e-12);
    }
}
