//! OSP LAP `G85 N<name> D F [U] [W] [E] [M85]`: rough bar turning (AP mode I), with the
//! cutting-condition changes `$ G84 XA= DA= FA=` / `$ XB= DB= FB=` (`ZA=`/`ZB=` for a
//! transverse contour) on the call's continuation lines.
//!
//! **The reading of M-P195 implemented here.** In the canonical frame of `lap_frame.rs`
//! (levels step down in `u`, passes cut toward decreasing `v`; `G81` longitudinal: `u` = X,
//! `v` = Z; `G82` transverse: swapped):
//!
//! ```txt
//!   A (Xs, Zs) ●──────────────────────────────  level u_s
//!               ╲ infeed line A → C0 (M-P195's Zp)
//!                ●──cut F─────────────╮  ╱ relief 0.1 mm at 45° (rapid)
//!                 ╲◀──rapid back──────╯
//!                  ●──cut F───────╮        levels step D (a diameter for G81)
//!                   ╲             ╰─ …     while the level stays above Xa + U
//!                C0 ●━━ then one pass along the contour offset by (U, W) ━━━
//!                    and the return: Z to Zs, then X to Xs (unless M85)
//! ```
//!
//! - Pass N's infeed point is `(Xp, Zp)` with `Xp = Xs − N·D` and `Zp` from M-P195, i.e. the
//!   point of the line from A to C0 = (Xa + U, Za + W) at that level, where (Xa, Za) is the
//!   contour's start point, the end of its first block. (`dialects.md` calls it the contour
//!   end; only its start makes `Xs − Xa − U` the depth of stock the passes step through, and
//!   OSP7000L's contours start at their smallest diameter.) Condition changes make the
//!   steps uneven; the infeed point is then the line's point at the level reached.
//! - The pass cuts at F parallel to the cutting axis until it meets the contour offset by
//!   (U, W) (M-P205: "up to point B where the straight line parallel to the Z-axis … intersects
//!   the final contour"), and beyond the contour's end when it never meets it.
//!   Pockets further on are left to the last pass, which is what a pass that stops at the
//!   first meeting implies; OSP7000L's contour has two such dips (X48.018 → X47.62,
//!   X73.1 → X72.7), so the control accepts contours that are not monotonic across the cut.
//!   Along the cut the contour must be monotonic: a contour that turns back is rejected.
//! - After each pass the tool relieves by the relief parameter (0.1 mm by default, M-P175) at
//!   45° away from the cut and returns at rapid along the level to the next infeed point:
//!   everything at that height between the infeed line and the contour was cut.
//! - "Until the infeed point reaches or exceeds Xa + U" (M-P195 step 8): a level at or below
//!   Xa + U is not cut as a pass; the last pass runs along the contour offset by (U, W),
//!   entered from C0 as the contour's first block moves (G00 rapid, G01 fed), at the contour
//!   feed `E` written in the contour (modal), else the call's `E`, else the feed in force.
//! - M-P195's XOFF/ZOFF (the contour shifted to start at the infeed point) describe the copy
//!   pass that `G86` makes; bar turning uses only the infeed points.
//!
//! **Condition changes** (M-P177, M-P204): before each infeed the depth and feed are chosen
//! from where the tool is: past XA (reached or beyond) DA/FA, past XB DB/FB (B wins when
//! both apply). A pass that crosses XA is still cut with D. A word left out keeps the value
//! in force. The points must follow the cut (outside Xs > XA > XB, inside the reverse), and a
//! longitudinal call takes no `ZA=`/`ZB=`, a transverse one no `XA=`/`XB=`.
//!
//! **Defaults assumed:** no `F` → the feed in force (M-P204); `U`, `W` → 0 (M-P175); relief
//! 0.1 mm in each axis; roughing moves are not nose-radius compensated (the `G41`/`G42` of
//! the contour is for `G87`); the spindle runs at the speed in force (the contour's `S` is
//! for finishing).

use crate::diagnostic::DiagnosticKind;
use crate::dialect::Role;
use crate::source::Span;
use crate::syntax::Command;
use crate::toolpath::Xz;

use super::super::interpreter::{Flow, Interpreter};
use super::Call;
use super::canonical::{self, Uv};
use super::lap_contour::{self, Contour, Direction};
use super::lap_frame::{self, MAX_PASSES, RELIEF_MM, RoughFrame};

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command) -> Flow {
    let Some((Call { span, start }, contour)) = lap_contour::call(interp, index, command) else { return Flow::Next };
    let flow = contour.flow_after();
    let Some(words) = CallWords::read(interp, command, &contour) else { return flow };
    if !contour.roughable(interp, span) {
        return flow;
    }
    let frame = RoughFrame::new(&contour, start, words.x_allowance, words.z_allowance);
    let Some(conditions) = Conditions::read(interp, command, &contour, &frame) else { return flow };
    let smallest = conditions.depths().fold(words.depth, f64::min);
    if words.too_many_passes(interp, frame.stock_depth(), smallest, span) {
        return flow;
    }
    let passes = match plan(&frame, words.depth, words.feed, &conditions) {
        Ok(passes) => passes,
        Err(kind) => {
            interp.error(kind, span);
            return flow;
        }
    };
    cut(interp, &contour, &frame, &passes, &conditions, &words);
    words.end_call(interp, &contour, start);
    flow
}

/// The call's words, checked and in mm (depths along the infeed axis, X as a radius).
pub(super) struct CallWords {
    pub depth: f64,
    /// `D` as written, for diagnostics.
    pub depth_written: f64,
    /// Program units, as the modal feed.
    pub feed: f64,
    pub contour_feed: Option<f64>,
    pub x_allowance: f64,
    pub z_allowance: f64,
    pub no_return: bool,
}

impl CallWords {
    /// Read `D F U W E M85`; `None` after a diagnostic when one is out of range.
    pub fn read(interp: &mut Interpreter<'_, '_>, command: &Command, contour: &Contour) -> Option<CallWords> {
        let frame = interp.modal.frame;
        let depth_written = interp.param(command, Role::DepthOfCut)?;
        let u = interp.param(command, Role::AllowanceX).unwrap_or(0.0);
        let w = interp.param(command, Role::AllowanceZ).unwrap_or(0.0);
        for (role, name, value, ok, rule) in [
            (Role::DepthOfCut, "D", depth_written, depth_written > 0.0, "the depth of cut must be greater than 0"),
            (Role::AllowanceX, "U", u, u >= 0.0, "an allowance is 0 or more"),
            (Role::AllowanceZ, "W", w, w >= 0.0, "an allowance is 0 or more"),
        ] {
            if !ok {
                let span = command.param(role).map_or(Span::SYNTHETIC, |id| interp.program.word(id).span);
                interp.error(DiagnosticKind::LapWordOutOfRange { word: name.into(), value, rule }, span);
                return None;
            }
        }
        Some(CallWords {
            depth: along_infeed(frame, contour.direction, depth_written),
            depth_written,
            feed: interp.param(command, Role::Feed).unwrap_or(interp.modal.feed),
            contour_feed: interp.param(command, Role::ContourFeed),
            x_allowance: frame.x_mm(u),
            z_allowance: frame.mm(w),
            no_return: command.param(Role::NoReturn).is_some(),
        })
    }

    /// Whether cutting `stock` mm at depths of at least `smallest` takes more passes than
    /// turnpass simulates; if so, an error on the call's `D`.
    pub fn too_many_passes(&self, interp: &mut Interpreter<'_, '_>, stock: f64, smallest: f64, call: Span) -> bool {
        let too_many = stock / smallest > MAX_PASSES;
        if too_many {
            let rule = "it would take more than 10000 passes";
            interp.error(DiagnosticKind::LapWordOutOfRange { word: "D".into(), value: self.depth_written, rule }, call);
        }
        too_many
    }

    /// The end of a roughing call: back to the AP start point `start` unless `M85` keeps the
    /// tool where the last pass left it, and the contour consumed when it belongs to the call.
    pub fn end_call(&self, interp: &mut Interpreter<'_, '_>, contour: &Contour, start: Xz) {
        if !self.no_return {
            lap_contour::return_to_start(interp, contour, start);
        }
        contour.consume(interp);
    }
}

/// A depth written along the infeed axis, in mm: X depths are diameters (M-P175).
fn along_infeed(frame: super::super::Frame, direction: Direction, value: f64) -> f64 {
    match direction {
        Direction::Longitudinal => frame.x_mm(value),
        Direction::Transverse => frame.mm(value),
    }
}

/// A `G84` change point: from canonical level `at` on, this depth (mm) and feed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Change {
    pub at: f64,
    pub depth: Option<f64>,
    pub feed: Option<f64>,
}

#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct Conditions {
    pub a: Option<Change>,
    pub b: Option<Change>,
}

impl Conditions {
    /// The depth and feed for the infeed that starts from level `from`.
    pub fn in_force(&self, from: f64, depth: f64, feed: f64) -> (f64, f64) {
        let (mut depth, mut feed) = (depth, feed);
        for change in [self.a, self.b].into_iter().flatten() {
            if from <= change.at + 1e-9 {
                depth = change.depth.unwrap_or(depth);
                feed = change.feed.unwrap_or(feed);
            }
        }
        (depth, feed)
    }

    fn depths(&self) -> impl Iterator<Item = f64> + '_ {
        [self.a, self.b].into_iter().flatten().filter_map(|c| c.depth)
    }

    /// Read the change points of the call; `None` after a diagnostic.
    fn read(
        interp: &mut Interpreter<'_, '_>,
        command: &Command,
        contour: &Contour,
        frame: &RoughFrame,
    ) -> Option<Self> {
        let longitudinal = contour.direction == Direction::Longitudinal;
        let (point_a, point_b, wrong_a, wrong_b, axis) = if longitudinal {
            (Role::ConditionXA, Role::ConditionXB, Role::ConditionZA, Role::ConditionZB, "X")
        } else {
            (Role::ConditionZA, Role::ConditionZB, Role::ConditionXA, Role::ConditionXB, "Z")
        };
        for (role, name) in [(wrong_a, "A="), (wrong_b, "B=")] {
            if let Some(id) = command.param(role) {
                let word = format!("{}{name}", if longitudinal { "Z" } else { "X" });
                let reason = if longitudinal {
                    "a longitudinal contour (G81) changes conditions at XA=/XB=, never ZA=/ZB="
                } else {
                    "a transverse contour (G82) changes conditions at ZA=/ZB=, never XA=/XB="
                };
                let span = interp.program.word(id).span;
                interp.error(DiagnosticKind::LapConditionMisplaced { word, reason }, span);
                return None;
            }
        }
        let modal = interp.modal.clone();
        let position = |value: f64| -> f64 {
            let p = if longitudinal {
                Xz::new(modal.frame.x_mm(value) + modal.shift.x, 0.0)
            } else {
                Xz::new(0.0, modal.frame.mm(value) + modal.shift.z)
            };
            frame.canon.to(p).u
        };
        let start_written = if longitudinal {
            modal.frame.x_program(frame.canon.from(frame.start).x - modal.shift.x)
        } else {
            modal.frame.program(frame.canon.from(frame.start).z - modal.shift.z)
        };
        let mut conditions = Conditions::default();
        let mut before = (axis.to_string(), start_written, frame.start.u);
        for (point, depth_role, feed_role, letter) in [
            (point_a, Role::ConditionDepthA, Role::ConditionFeedA, "A="),
            (point_b, Role::ConditionDepthB, Role::ConditionFeedB, "B="),
        ] {
            let Some(id) = command.param(point) else { continue };
            let written = interp.param(command, point)?;
            let span = interp.program.word(id).span;
            let at = position(written);
            let word = format!("{axis}{letter}");
            if at >= before.2 - 1e-9 {
                let (before_word, before_value, _) = before.clone();
                let outside = !frame.canon.mirror_u;
                let kind = DiagnosticKind::LapConditionOrder {
                    word,
                    value: written,
                    before: before_word,
                    before_value,
                    outside,
                };
                interp.error(kind, span);
                return None;
            }
            let depth = interp.param(command, depth_role);
            if let Some(d) = depth.filter(|d| *d <= 0.0) {
                let span = command.param(depth_role).map_or(span, |id| interp.program.word(id).span);
                let rule = "the depth of cut must be greater than 0";
                interp.error(DiagnosticKind::LapWordOutOfRange { word: format!("D{letter}"), value: d, rule }, span);
                return None;
            }
            let change = Change {
                at,
                depth: depth.map(|d| along_infeed(modal.frame, contour.direction, d)),
                feed: interp.param(command, feed_role),
            };
            if letter == "A=" {
                conditions.a = Some(change);
            } else {
                conditions.b = Some(change);
            }
            before = (word, written, at);
        }
        Some(conditions)
    }
}

/// One roughing pass in the canonical frame: infeed at `v_in` down to `level`, cut to `v_out`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Pass {
    pub level: f64,
    pub v_in: f64,
    pub v_out: f64,
    /// Program units.
    pub feed: f64,
}

/// The passes before the last one along the contour.
pub(super) fn plan(
    frame: &RoughFrame,
    depth: f64,
    feed: f64,
    conditions: &Conditions,
) -> Result<Vec<Pass>, DiagnosticKind> {
    let floor = frame.contour_start.u;
    if frame.start.u < floor - 1e-9 {
        return Err(DiagnosticKind::LapStartInsideContour);
    }
    let v_end = frame.elements.last().map_or(frame.contour_start.v, |e| e.end.v);
    let mut passes = Vec::new();
    let mut from = frame.start.u;
    loop {
        let (step, feed) = conditions.in_force(from, depth, feed);
        let level = from - step;
        // A level that is not a number (an overflowing expression) ends the passes too.
        if level.is_nan() || level <= floor + 1e-9 {
            return Ok(passes);
        }
        let v_in = frame.line_v(level);
        if canonical::u_at(&frame.elements, v_in) > level + 1e-9 {
            return Err(DiagnosticKind::LapStartInsideContour);
        }
        let v_out = canonical::crossings(&frame.elements, level)
            .into_iter()
            .find(|&v| v <= v_in + 1e-9)
            .unwrap_or(v_end)
            .min(v_in);
        passes.push(Pass { level, v_in, v_out, feed });
        from = level;
    }
}

/// Emit the passes, then the last pass along the contour offset by (U, W).
fn cut(
    interp: &mut Interpreter<'_, '_>,
    contour: &Contour,
    frame: &RoughFrame,
    passes: &[Pass],
    conditions: &Conditions,
    words: &CallWords,
) {
    let saved = interp.modal.clone();
    let plunge_rapid = !frame.plunge_cuts();
    let mut at = frame.start;
    for pass in passes {
        interp.modal.feed = pass.feed;
        frame.go(interp, Uv { u: at.u, v: pass.v_in }, true);
        frame.go(interp, Uv { u: pass.level, v: pass.v_in }, plunge_rapid);
        frame.go(interp, Uv { u: pass.level, v: pass.v_out }, false);
        at = Uv { u: pass.level + RELIEF_MM, v: pass.v_out + RELIEF_MM };
        frame.go(interp, at, true);
    }
    let last_level = passes.last().map_or(frame.start.u, |p| p.level);
    let feed = conditions.in_force(last_level, words.depth, words.feed).1;
    interp.modal.feed = feed;
    frame.go(interp, Uv { u: at.u, v: frame.contour_start.v }, true);
    frame.go(interp, frame.contour_start, plunge_rapid && contour.approach_rapid());
    let along = |i: usize| contour.contour_feed.get(i).copied().flatten().or(words.contour_feed).unwrap_or(feed);
    lap_frame::cut_along(interp, contour, frame.allowance, along);
    interp.modal = saved;
}

#[cfg(test)]
mod tests;
