//! Fanuc `G71` stock removal in turning and `G72` in facing; two-block form
//! (`G71 U(Δd) R(e)` then `G71 P Q U(Δu) W(Δw) F S T`) and one-block form
//! (`G71 P Q U W D(Δd) F [R1]`, Haas and Fanuc 15).
//!
//! The roughing region lies between the start point A (the tool's position at the call)
//! and the finishing profile P…Q shifted by the allowance (Δu/2 in X, Δw in Z). In the
//! canonical frame (see `canonical.rs`: levels step toward the profile in `u`, passes cut
//! toward it in `v`):
//!
//! ```txt
//!        A ●───────────────────────────  level u₀
//!          │ infeed Δd (G00 or G01 as the P block)
//!          ├──cut F────────────╮ ╱ 45° retract e (rapid)
//!          │◀──rapid return────╯
//!          ├──cut──────────╮
//!          ⋮               ╰─ … last level above the profile's lowest point
//!          then one pass along the shifted profile (leaving exactly Δu, Δw),
//!          and a rapid back to A (first in u, then in v)
//! ```
//!
//! A pass at level `u` cuts where the level lies above the shifted profile: from A's `v`
//! to where it meets the profile (Type I, a profile monotonic in both axes), or over every
//! stretch above the profile (Type II, chosen when the P block names both axes, or by `R1`
//! in the one-block form; Z must still be monotonic and X may dip into pockets). In Type II
//! the tool follows the profile up from the end of each stretch to the previous level
//! (along its arcs; where the profile ends or turns down below that level, straight up to
//! it) before it retracts, and enters a pocket from the safe level: A's, or the profile's
//! where it rises above A's on the way. A retract never reaches back past the stretch it
//! ends (a pocket narrower than e). The property tests (`tests/it/stock_removal.rs`) check
//! that no move enters the shifted profile and no rapid runs through stock not yet cut.
//!
//! F, S and T inside P…Q are for finishing (`G70`); roughing uses the cycle's own F. After
//! the cycle the program continues after the Q block: the profile is a definition. Lines at
//! the end of the profile that leave the part back toward the start point, outside the stock
//! (Haas profiles end `N20 G00 G40 Z0.1`), are not part of the shape the passes cut.

use crate::diagnostic::DiagnosticKind;
use crate::dialect::{GFunction, Role};
use crate::source::Span;
use crate::syntax::Command;
use crate::toolpath::Xz;

use super::super::frame::Frame;
use super::super::interpreter::{Flow, Interpreter};
use super::super::profile::{Profile, Shape};
use super::Call;
use super::canonical::{self, Canon, Element, Uv};

/// The retract when neither the program nor its first block gives one (Fanuc's usual
/// parameter value), mm.
const DEFAULT_RETRACT_MM: f64 = 0.5;

/// The first block of the two-block form only sets Δd and e.
pub(super) fn depth_block(
    interp: &mut Interpreter<'_, '_>,
    index: usize,
    command: &Command,
    function: GFunction,
) -> Flow {
    let depth = interp.param(command, Role::DepthOfCut);
    let depth = depth.map(|d| (d, interp.param_span(command, Role::DepthOfCut, Span::SYNTHETIC)));
    let retract = interp.param(command, Role::Retract);
    let memory = &mut interp.cycle_memory;
    memory.depth_block = Some(index);
    if function == GFunction::StockRemovalTurning {
        memory.turning_depth = depth.or(memory.turning_depth);
        memory.turning_retract = retract.or(memory.turning_retract);
    } else {
        memory.facing_depth = depth.or(memory.facing_depth);
        memory.facing_retract = retract.or(memory.facing_retract);
    }
    Flow::Next
}

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command, function: GFunction) -> Flow {
    // With the tool's position unknown the cycle moves nothing (warned), but its profile is
    // still the cycle's, not blocks to run: the control goes on after `Q`.
    let Some(Call { span, start }) = interp.cycle_call(index) else { return interp.after_profile(command, index) };
    let facing = function == GFunction::StockRemovalFacing;
    let frame = interp.modal.frame;
    let one_block = command.param(Role::DepthOfCut).is_some();
    let depth = if one_block {
        let written = interp.param(command, Role::DepthOfCut);
        written.map(|d| (d, interp.param_span(command, Role::DepthOfCut, span)))
    } else if facing {
        interp.cycle_memory.facing_depth
    } else {
        interp.cycle_memory.turning_depth
    };
    let Some((depth, depth_at)) = depth.filter(|(d, _)| d.abs() > 0.0) else {
        interp.error(DiagnosticKind::CycleNeedsDepth, span);
        return Flow::Next;
    };
    // The control reads the depth to its least increment: less than one is a depth of 0,
    // which it refuses; a cycle would otherwise cut without end.
    if depth.abs() < frame.increment * (1.0 - 1e-9) {
        let at = if depth_at.is_synthetic() { span } else { depth_at };
        interp.error(DiagnosticKind::DepthBelowIncrement { depth: depth.abs(), increment: frame.increment }, at);
        return Flow::Next;
    }
    let depth = frame.mm(depth.abs());
    let retract = if facing { interp.cycle_memory.facing_retract } else { interp.cycle_memory.turning_retract }
        .map(|e| frame.mm(e.abs()))
        .unwrap_or(DEFAULT_RETRACT_MM);
    let allowance = Xz::new(
        interp.param(command, Role::AllowanceX).map_or(0.0, |u| frame.x_mm(u)),
        interp.param(command, Role::AllowanceZ).map_or(0.0, |w| frame.mm(w)),
    );
    let type_ii_flag = interp.param(command, Role::TypeIi).is_some_and(|r| r >= 1.0);
    let Some(profile) = interp.profile_of(command, span, start) else { return Flow::Next };
    let after_q = interp.after_profile(command, index);
    // The profile and the first block are part of the cycle: `expand` deletes them.
    interp.consume(profile.blocks.clone());
    interp.consume_skipped(index, *profile.blocks.start(), after_q);
    if !one_block {
        interp.consume_setup(interp.cycle_memory.depth_block);
    }
    if profile.segments.is_empty() {
        interp.error(DiagnosticKind::EmptyProfile, span);
        return after_q;
    }
    let type_ii = type_ii_flag || (!facing && profile.first_block_has_both_axes);
    let feed = interp.param(command, Role::Feed).unwrap_or(interp.modal.feed);
    let speed = interp.param(command, Role::Speed);
    let rough = Rough { depth, retract, allowance, type_ii, feed, speed, facing };
    if let Err((kind, at)) = rough.cut(interp, &without_exit(&profile, start, allowance, facing), start) {
        let (frame, shift) = (interp.modal.frame, interp.modal.shift);
        let reported = match (rough.wrong_side(&profile, start, frame, shift), at) {
            (Some(kind), _) => {
                interp.error(kind, span);
                span
            }
            // A profile that turns back is marked where it turns, and points to its cycle.
            (None, Some(block)) => {
                interp.diagnostics.push(
                    crate::diagnostic::Diagnostic::error(kind, block)
                        .with_related(span, "the cycle that roughs this profile"),
                );
                block
            }
            (None, None) => {
                interp.error(kind, span);
                span
            }
        };
        // The profile's words decide its shape: one read without its decimal point is the
        // likelier cause (`decimal_point.rs`).
        let (first, last) =
            (interp.program.block(*profile.blocks.start()).span, interp.program.block(*profile.blocks.end()).span);
        interp.slip_scope(reported, first.start, last.end);
    }
    // F and S written in the cycle block are words of that block: they stay modal after
    // it, as every F and S does (a G70 with no F of its own then finishes at that feed
    // where the profile gives none).
    interp.modal.feed = feed;
    if let Some(s) = speed {
        interp.modal.speed = s;
    }
    after_q
}

/// The profile without its exit: the lines at its end that lie wholly at or beyond the
/// start point's level (outside the stock, allowance included) and run back toward the start
/// point, as in the Haas profiles that end `N20 G00 G40 Z0.1` (the NIMS template,
/// nims1001.nc, teaches it). No pass reaches them and the cycle returns to the start point
/// itself after its final pass; read as part of the shape, they would turn the profile back
/// along the cut. `G70` still runs them.
fn without_exit(profile: &Profile, start: Xz, allowance: Xz, facing: bool) -> Profile {
    let level = Canon { swap: facing, mirror_u: start_below(start, profile, allowance, facing), mirror_v: false };
    let a = level.to(start);
    let shifted = |p: Xz| level.to(Xz::new(p.x + allowance.x, p.z + allowance.z));
    // The approach and at least one element of the shape stay.
    let mut keep = profile.segments.len();
    while keep > 2 {
        let (from, last) = (shifted(profile.segments[keep - 2].end), profile.segments[keep - 1]);
        let to = shifted(last.end);
        let outside = from.u >= a.u - 1e-9 && to.u >= a.u - 1e-9;
        // Toward the start point's plane, perhaps past it by the allowance.
        let back = (to.v - from.v) * (a.v - from.v) > 1e-12;
        if !(outside && back && last.shape == Shape::Line) {
            break;
        }
        keep -= 1;
    }
    let mut trimmed = profile.clone();
    trimmed.segments.truncate(keep);
    trimmed
}

/// Whether the start point lies below the profile across the levels (toward smaller X when
/// turning, an inside cut; toward smaller Z when facing). The start point and the point the
/// P block goes to decide; where they lie at the same level (`N10 G00 X20 Z2` from X20 Z5),
/// the sign of the allowance across the levels does, and without one the side the rest of
/// the profile lies on.
fn start_below(start: Xz, profile: &Profile, allowance: Xz, facing: bool) -> bool {
    let across = |p: Xz| if facing { p.z } else { p.x };
    let first = profile.segments.first().map_or(profile.start, |s| s.end);
    let (a, p) = (across(start), across(first));
    if (a - p).abs() > 1e-9 {
        a < p
    } else if across(allowance) != 0.0 {
        across(allowance) < 0.0
    } else {
        profile.points().any(|q| across(q) > a + 1e-9)
    }
}

struct Rough {
    depth: f64,
    retract: f64,
    allowance: Xz,
    type_ii: bool,
    feed: f64,
    speed: Option<f64>,
    facing: bool,
}

impl Rough {
    /// The canonical frame seen from `start`, and the profile shifted by the allowance in it
    /// (the approach left out), checked against the cycle's type.
    fn shape(&self, profile: &Profile, start: Xz) -> Result<(Canon, Vec<Element>), ShapeError> {
        let shifted_end = Xz::new(profile.end().x + self.allowance.x, profile.end().z + self.allowance.z);
        let canon = Canon {
            swap: self.facing,
            mirror_u: start_below(start, profile, self.allowance, self.facing),
            mirror_v: if self.facing { shifted_end.x > start.x } else { shifted_end.z > start.z },
        };
        // The profile proper starts where the P block goes; that first move is the approach.
        let elements = canonical::elements(&canon, profile, self.allowance, true);
        if elements.is_empty() {
            return Err((DiagnosticKind::EmptyProfile, None));
        }
        check_shape(&elements, self.type_ii, self.facing).map_err(|(kind, at)| (kind, Some(at)))?;
        Ok((canon, elements))
    }

    /// Why a profile that fails from `start` fails, when the start point lies on the other
    /// side of it than the sign of the allowance across the passes asks for (`U-1`, inside,
    /// from a start point outside the part), and the profile passes from a start point moved
    /// across to that side: beyond the profile's extreme there, allowance included.
    fn wrong_side(&self, profile: &Profile, start: Xz, frame: Frame, shift: Xz) -> Option<DiagnosticKind> {
        let allowance_mm = if self.facing { self.allowance.z } else { self.allowance.x };
        let inside = allowance_mm < 0.0;
        if allowance_mm == 0.0 || start_below(start, profile, self.allowance, self.facing) == inside {
            return None;
        }
        // Program values across the passes: X as written (a diameter), or Z.
        let across = |p: Xz| if self.facing { frame.program(p.z - shift.z) } else { frame.x_program(p.x - shift.x) };
        let ends = profile.segments.iter().map(|s| across(s.end));
        let extreme = if inside { ends.fold(f64::INFINITY, f64::min) } else { ends.fold(f64::NEG_INFINITY, f64::max) };
        let allowance = if self.facing { frame.program(allowance_mm) } else { frame.x_program(allowance_mm) };
        let target = extreme + allowance;
        let moved = if self.facing {
            Xz::new(start.x, frame.mm(target) + shift.z)
        } else {
            Xz::new(frame.x_mm(target) + shift.x, start.z)
        };
        let from_there = without_exit(profile, moved, self.allowance, self.facing);
        self.shape(&from_there, moved).ok()?;
        Some(DiagnosticKind::StartOnWrongSide {
            x: frame.x_program(start.x - shift.x),
            z: frame.program(start.z - shift.z),
            axis: if self.facing { 'Z' } else { 'X' },
            address: if self.facing { 'W' } else { 'U' },
            allowance,
            extreme,
        })
    }

    fn cut(&self, interp: &mut Interpreter<'_, '_>, profile: &Profile, start: Xz) -> Result<(), ShapeError> {
        let (canon, elements) = self.shape(profile, start)?;
        let first = profile.segments[0];
        let a = canon.to(start);
        let v_end = elements.last().map_or(a.v, |e| e.end.v);
        let u_min = elements.iter().flat_map(|e| [e.start.u, e.end.u]).fold(f64::INFINITY, f64::min);
        let u_min = u_min.min(lowest_arc_point(&elements));
        let approach_rapid = first.rapid;

        let saved = interp.modal.clone();
        interp.modal.feed = self.feed;
        if let Some(s) = self.speed {
            interp.modal.speed = s;
        }
        let go = |interp: &mut Interpreter<'_, '_>, p: Uv, rapid: bool| {
            let modal = interp.modal.clone();
            let to = canon.from(p);
            if rapid { interp.emitter.rapid(&modal, to) } else { interp.emitter.line(&modal, to, true) }
        };

        let mut level = a.u - self.depth;
        let mut previous_level = a.u;
        // Every stretch cut so far, with its level: the tool may rapid along `v` at a
        // height only over a stretch cut at or below that height, and otherwise climbs to
        // A's level first (after a pocket, the stock between it and A is still there).
        let mut cleared = Cleared::default();
        let mut at = a;
        while level > u_min + 1e-9 && !interp.emitter.is_full() {
            let stretches = stretches(&elements, level, a.v, v_end);
            for (v_in, v_out) in stretches.iter().copied() {
                if (v_in - a.v).abs() < 1e-9 {
                    // Back to A's v, then infeed as the P block moves (rapid or feed).
                    travel(interp, &go, &cleared, &elements, at, a.v, a.u);
                    go(interp, Uv { u: level, v: a.v }, approach_rapid);
                } else {
                    // Into a pocket: across, down at rapid to just over the stock the
                    // previous level left, then feed.
                    at = travel(interp, &go, &cleared, &elements, at, v_in, a.u);
                    let opened = cleared.highest_at_or_below(previous_level).iter().any(|s| s.holds(v_in));
                    let clear = if opened { (previous_level + self.retract).min(at.u) } else { at.u };
                    go(interp, Uv { u: clear, v: v_in }, true);
                    go(interp, Uv { u: level, v: v_in }, false);
                }
                go(interp, Uv { u: level, v: v_out }, false);
                cleared.push(Stretch { u: level, hi: v_in, lo: v_out });
                let mut here = Uv { u: level, v: v_out };
                if self.type_ii && v_out > v_end + 1e-9 {
                    // Follow the rising profile up to the previous level.
                    for piece in follow_up(&elements, here, previous_level) {
                        cut_along(interp, &canon, &piece);
                        here = piece.end;
                    }
                    if here.u < previous_level - 1e-9 {
                        // The profile ended, or turned down, below the previous level: the
                        // stock over it up to that level is still there, and a retract
                        // at 45° would run through it. Cut straight up through it first.
                        here.u = previous_level;
                        go(interp, here, false);
                    }
                }
                let retract = self.retract.min(retract_room(&cleared, here, a));
                here = Uv { u: here.u + retract, v: here.v + retract };
                go(interp, here, true);
                at = here;
            }
            previous_level = level;
            level -= self.depth;
        }

        // The semi-finishing pass along the shifted profile, entered at A's v.
        let shifted_start = canon.to(Xz::new(first.end.x + self.allowance.x, first.end.z + self.allowance.z));
        travel(interp, &go, &cleared, &elements, at, a.v, a.u);
        go(interp, shifted_start, approach_rapid);
        for e in &elements {
            cut_along(interp, &canon, e);
        }
        // Back to A: away from the part first. Where the profile rises above A's level on
        // the way back (a land left at the stock diameter), a straight line down to A would
        // cross it: along the cut above it first.
        let last = canon.to(interp.emitter.at);
        let away = a.u.max(last.u);
        go(interp, Uv { u: away, v: last.v }, true);
        let (lo, hi) = (last.v.min(a.v) + 1e-6, last.v.max(a.v) - 1e-6);
        let over = if lo < hi { highest(&elements, lo, hi) } else { f64::NEG_INFINITY };
        if over > a.u + 1e-9 {
            let height = away.max(over);
            go(interp, Uv { u: height, v: last.v }, true);
            go(interp, Uv { u: height, v: a.v }, true);
        }
        go(interp, a, true);
        interp.modal = saved;
        Ok(())
    }
}

/// A stretch cut at level `u`, from `hi` down to `lo` along `v`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Stretch {
    u: f64,
    hi: f64,
    lo: f64,
}

impl Stretch {
    fn holds(&self, v: f64) -> bool {
        v <= self.hi + 1e-9 && v >= self.lo - 1e-9
    }
}

/// The stretches cut so far, in the order they were cut: level after level, each below the
/// one before. The stock above the profile narrows as the levels go down (the profile is a
/// function of `v`, so the part of a level above it shrinks with the level), and so a
/// stretch lies inside a stretch of every level above it. What a stretch at or below a
/// height can do (hold a point, cover a span) a stretch of the highest level at or below
/// that height does too: a question about every level at or below a height is asked of
/// that one level, found by bisection. The work of a pass does not grow with the passes cut
/// before it, and the cycle is linear in its passes.
#[derive(Default)]
struct Cleared {
    stretches: Vec<Stretch>,
}

impl Cleared {
    fn push(&mut self, stretch: Stretch) {
        self.stretches.push(stretch);
    }

    /// The stretches of the highest level at or below `u` that has any.
    fn highest_at_or_below(&self, u: f64) -> &[Stretch] {
        let first = self.stretches.partition_point(|s| s.u > u + 1e-9);
        let rest = &self.stretches[first..];
        let Some(level) = rest.first().map(|s| s.u) else { return rest };
        let found = &rest[..rest.partition_point(|s| s.u == level)];
        #[cfg(test)]
        tests::count_looked_at(self.stretches.len(), found.len());
        found
    }
}

/// How far the tool at `here` may retract at 45° (up and back along the cut) through stock
/// already cut: as far back as the stretches cut at or below its height reach over it. A
/// stretch that begins at A's `v` opens onto the outside; one in a pocket ends at the
/// pocket's near side, and a full retract from a pocket narrower than the retract would
/// run at rapid into that side (the part, or the stock the previous level left on it).
fn retract_room(cleared: &Cleared, here: Uv, a: Uv) -> f64 {
    if here.u >= a.u - 1e-9 {
        return f64::INFINITY;
    }
    cleared
        .highest_at_or_below(here.u)
        .iter()
        .filter(|s| s.holds(here.v))
        .map(|s| if s.hi >= a.v - 1e-9 { f64::INFINITY } else { s.hi - here.v })
        .fold(0.0, f64::max)
}

/// Rapid from `at` to `v`: straight along `v` when every point of the way lies over a
/// stretch cut at or below the tool's height, else up to the safe level first: A's level, or
/// higher where the profile (allowance included) rises above it on the way.
fn travel(
    interp: &mut Interpreter<'_, '_>,
    go: &impl Fn(&mut Interpreter<'_, '_>, Uv, bool),
    cleared: &Cleared,
    elements: &[Element],
    at: Uv,
    v: f64,
    a_u: f64,
) -> Uv {
    let (hi, lo) = (at.v.max(v), at.v.min(v));
    let covered = cleared.highest_at_or_below(at.u).iter().any(|s| s.hi >= hi - 1e-9 && s.lo <= lo + 1e-9);
    let safe_u = a_u.max(highest(elements, lo, hi));
    let height = if covered || at.u >= safe_u - 1e-9 { at.u } else { safe_u };
    if height != at.u {
        go(interp, Uv { u: height, v: at.v }, true);
    }
    let to = Uv { u: height, v };
    go(interp, to, true);
    to
}

/// The highest point of the profile over `v` from `lo` to `hi`: where it is at both ends, the
/// ends of its elements between, and the crest of an arc that rises above its ends there.
fn highest(elements: &[Element], lo: f64, hi: f64) -> f64 {
    let within = |p: Uv| p.v >= lo - 1e-9 && p.v <= hi + 1e-9;
    let as_xz = |q: Uv| Xz::new(q.u, q.v);
    let mut top = canonical::u_at(elements, lo).max(canonical::u_at(elements, hi));
    for e in elements {
        for p in [e.start, e.end].into_iter().filter(|p| within(*p)) {
            top = top.max(p.u);
        }
        if let Some((c, ccw)) = e.arc {
            let crest = Uv { u: c.u + e.radius(), v: c.v };
            if within(crest) && crate::geometry::angle_within(as_xz(crest), as_xz(e.start), as_xz(e.end), as_xz(c), ccw)
            {
                top = top.max(crest.u);
            }
        }
    }
    top
}

/// The lowest point of the arcs, when an arc dips below its end points.
fn lowest_arc_point(elements: &[Element]) -> f64 {
    elements
        .iter()
        .filter_map(|e| e.arc.map(|(c, _)| (e, c)))
        .filter_map(|(e, c)| {
            let bottom = Uv { u: c.u - e.radius(), v: c.v };
            let as_xz = |q: Uv| Xz::new(q.u, q.v);
            let (_, ccw) = e.arc?;
            crate::geometry::angle_within(as_xz(bottom), as_xz(e.start), as_xz(e.end), as_xz(c), ccw)
                .then_some(bottom.u)
        })
        .fold(f64::INFINITY, f64::min)
}

/// The stretches of level `u`, from `v_start` toward `v_end`, that lie above the profile.
fn stretches(elements: &[Element], u: f64, v_start: f64, v_end: f64) -> Vec<(f64, f64)> {
    let mut cuts: Vec<f64> =
        canonical::crossings(elements, u).into_iter().filter(|v| *v < v_start && *v > v_end).collect();
    cuts.insert(0, v_start);
    cuts.push(v_end);
    let mut out: Vec<(f64, f64)> = Vec::new();
    for pair in cuts.windows(2) {
        let (hi, lo) = (pair[0], pair[1]);
        if hi - lo < 1e-9 {
            continue;
        }
        let mid = (hi + lo) / 2.0;
        if u > canonical::u_at(elements, mid) + 1e-9 {
            match out.last_mut() {
                Some((_, end)) if (*end - hi).abs() < 1e-9 => *end = lo,
                _ => out.push((hi, lo)),
            }
        }
    }
    out
}

/// Cut along a profile element (or a piece of one) at the feed: a line, or an arc about
/// its centre.
fn cut_along(interp: &mut Interpreter<'_, '_>, canon: &Canon, e: &Element) {
    let modal = interp.modal.clone();
    match e.arc {
        None => interp.emitter.line(&modal, canon.from(e.end), true),
        Some((c, ccw)) => interp.emitter.arc(&modal, canon.from(e.end), canon.from(c), ccw ^ canon.flips(), true),
    }
}

/// The profile from `from` (a point on it, where a stretch ended) onward, as pieces of its
/// elements, until it rises to `ceiling` or turns down below `from` again (a new stretch
/// cuts there). Arcs stay arcs: the chord of a convex arc runs inside the part. It starts
/// on the element that holds `from`: at a wall, the wall, not the element before it that
/// ends at the wall's foot at the same `v`.
fn follow_up(elements: &[Element], from: Uv, ceiling: f64) -> Vec<Element> {
    let Some(first) = elements.iter().position(|e| e.contains(from)) else { return Vec::new() };
    let mut out = Vec::new();
    let mut at = from;
    for e in &elements[first..] {
        if at.u >= ceiling - 1e-9 || e.end.u < from.u - 1e-9 {
            break;
        }
        let piece = Element { start: at, ..*e };
        // The first point along the piece at the ceiling, if it gets there.
        let reach = canonical::crossings(&[piece], ceiling).into_iter().filter(|v| *v <= at.v + 1e-9).reduce(f64::max);
        let end = reach.map_or(e.end, |v| Uv { u: ceiling, v });
        if at.distance(end) > 1e-12 {
            out.push(Element { end, ..piece });
        }
        if reach.is_some() {
            break;
        }
        at = end;
    }
    out
}

/// Type I: monotonic in both axes; Type II: monotonic along the cut. A profile that breaks
/// its type is what the control rejects.
/// The first element that breaks the type is where the error is marked.
fn check_shape(elements: &[Element], type_ii: bool, facing: bool) -> Result<(), (DiagnosticKind, Span)> {
    let along = |e: &Element| e.end.v - e.start.v;
    let across = |e: &Element| e.end.u - e.start.u;
    if let Some(e) = elements.iter().find(|e| along(e) > 1e-9) {
        return Err((DiagnosticKind::ProfileReverses { axis: if facing { 'X' } else { 'Z' } }, e.source));
    }
    if let Some(e) = elements.iter().find(|e| !type_ii && across(e) < -1e-9) {
        return Err((DiagnosticKind::ProfileNotMonotonic { axis: if facing { 'Z' } else { 'X' } }, e.source));
    }
    Ok(())
}

/// Why a profile cannot be roughed, and the block where it breaks its type (none when it
/// is empty).
type ShapeError = (DiagnosticKind, Option<Span>);

impl Interpreter<'_, '_> {
    /// Where the program continues after the cycle of block `index` that names a profile:
    /// after its Q block, when that lies ahead (a profile written before its cycle was
    /// already read past; jumping back to it would run the cycle again and again).
    /// Consume the blocks that the jump after the profile (`after_q`, from [`after_profile`])
    /// passes over between the call `index` and the profile's first block `first`: the
    /// control never runs them, so `expand` deletes them with the call. Left in place, they
    /// would run in the expanded program, whose call is plain moves (a second `G71 P Q`
    /// sharing the first one's depth block, which the expansion deletes, then has none).
    ///
    /// [`after_profile`]: Self::after_profile
    pub(in crate::semantic) fn consume_skipped(&mut self, index: usize, first: usize, after_q: Flow) {
        if let Flow::Jump(next) = after_q {
            self.consume(index + 1..first.min(next));
        }
    }

    pub(in crate::semantic) fn after_profile(&mut self, command: &Command, index: usize) -> Flow {
        let Some(q) = self.param(command, Role::ProfileEnd) else { return Flow::Next };
        let key = (q.round() as i64).to_string();
        match self.labels().blocks(&key) {
            [one] if *one > index => Flow::Jump(one + 1),
            _ => Flow::Next,
        }
    }
}

#[cfg(test)]
mod tests;
