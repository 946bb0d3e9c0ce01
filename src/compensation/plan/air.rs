//! Moves left as written: compensation changes what shapes the part and leaves the rest of
//! the program as the programmer wrote it (issue 25, "rapids, and moves that cut no finished
//! surface, are left alone").
//!
//! A rapid shapes nothing either measure judges: only its end matters, and only where the
//! next move starts from it. So a straight rapid whose next move is a rapid too, or that
//! ends the program, ends where the program puts it: a retract, the rapids to the tool
//! change and home. Its correction is not carried by any later move: each move is planned
//! from the samples of the inverse, which solves every point on its own, so the move after
//! it still ends where it needs to. A rapid that ends where a feed move, a cycle or a thread
//! starts is corrected: there the start is part of what is cut. It is corrected only along
//! the axes the cut takes from it: where the next move is a rapid along an axis too (down to
//! a thread's depth, a thread cycle's to its first pass, a single turning or facing cycle's
//! to the start of its cut), the rapid ends as written along that axis (`with_axes_left`).
//!
//! Where the check before writing measures the finished part, a straight feed move whose
//! whole tool keeps clear of the finished part (`part::clearance`) cuts no finished surface:
//! a roughing pass a later pass cuts away, a retract or an approach in the air. It is left
//! as written on the same terms as a rapid (the move after it is left too, or the program
//! ends), and only where its path as written stays within half that clearance of its
//! corrected one, so that the model's correction cannot carry it into the finished part. A
//! move under nose-radius compensation is corrected still: the control offsets its corners
//! with its neighbours', which are corrected. The move after the last one left, which starts
//! the cut, is corrected, so a cut starts where it is planned to.
//!
//! A move is left alone only where the move after it is left alone too, or travels no axis
//! the other way than it does from the corrected end: a reversal the inverse did not plan
//! for, on the way to a cut, would take up play the model has there. Moves of a cycle, and
//! one whose next move begins with a jog of its own, are planned as before.

use crate::toolpath::{Motion, Move, Toolpath, Xz};

use super::super::fit::{Segment, distance_to_chord};
use super::super::written;
use super::MovePlan;
use crate::part::clearance::Clearance;
use crate::toolpath::Compensation;

/// Which moves the check before writing judges, so that compensation must correct them.
#[derive(Debug, Clone, Copy)]
pub enum Judged<'a> {
    /// Every move, rapids too: none is left as written.
    Every,
    /// Every feed move: rapids shape nothing judged (both measures judge only what is cut).
    EveryFeed,
    /// The feed moves that come near the finished part: the part measure judges only the
    /// finished part, and the others keep clear of it.
    Shaping(&'a Clearance),
}

impl Judged<'_> {
    fn judges(self, m: &Move, index: usize) -> bool {
        match self {
            Judged::Every => true,
            Judged::EveryFeed => m.motion != Motion::Rapid,
            Judged::Shaping(clearance) => {
                m.motion != Motion::Rapid
                    && !(m.motion == Motion::Feed && m.compensation == Compensation::Off && clearance.is_clear(index))
            }
        }
    }

    /// How far a feed move left as written may run from its corrected path, mm.
    fn leeway(self) -> f64 {
        match self {
            Judged::Shaping(clearance) => clearance.by_mm() / 2.0,
            Judged::Every | Judged::EveryFeed => 0.0,
        }
    }
}

/// How many moves were left as written.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LeftAlone {
    pub rapids: usize,
    pub feeds: usize,
}

impl std::ops::AddAssign for LeftAlone {
    fn add_assign(&mut self, other: LeftAlone) {
        self.rapids += other.rapids;
        self.feeds += other.feeds;
    }
}

/// Leave the moves of `plans` (the plans of moves `first..`, each planned from the end of
/// the one before) that need no correction as written (module documentation). Returns how
/// many were left as written.
pub(super) fn leave_alone(
    plans: &mut [MovePlan],
    first: usize,
    toolpath: &Toolpath,
    writable: &[bool],
    judged: Judged<'_>,
) -> LeftAlone {
    let moves = toolpath.moves.get(first..first + plans.len()).unwrap_or_default();
    let free = |offset: usize| {
        let index = first + offset;
        let m = &moves[offset];
        !judged.judges(m, index)
            && m.cycle.is_synthetic()
            && !m.threading
            && !m.is_arc()
            && writable.get(index).copied().unwrap_or(false)
    };
    // The program's last moves end where they are programmed whatever follows them in the
    // piece: nothing starts from them.
    let ends_program = first + plans.len() >= toolpath.moves.len();
    // A dwell or a corner the control makes has no segments: the move after it starts where
    // the one before ends. `next[k]` is the move after move `k` that is written.
    let mut next: Vec<Option<usize>> = vec![None; plans.len()];
    let mut left = vec![false; plans.len()];
    let mut after = None;
    for offset in (0..plans.len()).rev() {
        if plans[offset].segments.is_empty() {
            continue;
        }
        next[offset] = after;
        // The next move cuts (or is a cycle's, a thread's): it starts at the corrected end.
        left[offset] = free(offset) && after.map_or(ends_program, free);
        after = Some(offset);
    }
    // Each move left ends as its block puts it from where the one before ends, which is
    // known only once the one before is decided: the moves that cannot be left so are
    // dropped until every one left can.
    let ends = loop {
        let ends = written_ends(plans, &left, toolpath, first);
        let mut dropped = false;
        for offset in 0..plans.len() {
            let Some((start, to)) = ends[offset] else { continue };
            let holds = (moves[offset].motion == Motion::Rapid
                || runs_off(&plans[offset], start, to) <= judged.leeway())
                && next[offset].is_none_or(|after| left[after] || travel_kept(&plans[after], to, plans[offset].end()));
            if !holds {
                left[offset] = false;
                dropped = true;
            }
        }
        if !dropped {
            break ends;
        }
    };
    let ends = with_axes_left(plans, &left, &next, ends, (toolpath, first), judged);
    let mut count = LeftAlone::default();
    let mut from: Option<Xz> = None;
    for (offset, end) in ends.into_iter().enumerate() {
        if let Some(Ends { start, to, whole }) = end {
            if !whole {
                // Along the axes still corrected, the block is written as planned.
                plans[offset].segments = smallvec::smallvec![Segment::Line { end: to }];
                plans[offset].changed = to.distance(moves[offset].contour) > 1e-9;
                plans[offset].words = smallvec::SmallVec::new();
                from = Some(to);
                continue;
            }
            plans[offset] = MovePlan {
                start,
                segments: smallvec::smallvec![Segment::Line { end: to }],
                changed: false,
                jumps: 0,
                lead_in: false,
                words: smallvec::SmallVec::new(),
            };
            from = Some(to);
            if moves[offset].motion == Motion::Rapid {
                count.rapids += 1;
            } else {
                count.feeds += 1;
            }
        } else if let Some(to) = from {
            // The moves after one left start where it ends, up to the next one written.
            plans[offset].start = to;
            if !plans[offset].segments.is_empty() {
                from = None;
            }
        }
    }
    count
}

/// Where a move written from its block ends (`leave_alone`): wholly as written, or as
/// written only along some axes (`with_axes_left`).
#[derive(Debug, Clone, Copy)]
struct Ends {
    start: Xz,
    to: Xz,
    whole: bool,
}

/// `ends` (the moves left wholly as written) and the rapids left as written along the axes
/// the move after them travels by a rapid of its own: a rapid's end along such an axis is
/// only where the next rapid starts from, as that one's end is written in its own block
/// (the rapid down to a thread's depth before a `G32`). A thread cycle's first move, its
/// rapid to the first pass, counts along its depth axis only: the cycle takes nothing else
/// from its start point along it than where to retract to between passes, in the air, while
/// along the other axis it starts every pass there (the thread's `Z` start), which stays
/// corrected; so does a single turning or facing cycle's, along the axis its move back out of
/// the cut ends at the start point (`single_cycle_axis`). As for a whole move, the next move must travel that axis the same way from
/// either end, with no jog of its own.
fn with_axes_left(
    plans: &[MovePlan],
    left: &[bool],
    next: &[Option<usize>],
    ends: Vec<Option<(Xz, Xz)>>,
    (toolpath, first): (&Toolpath, usize),
    judged: Judged<'_>,
) -> Vec<Option<Ends>> {
    let moves = toolpath.moves.get(first..first + plans.len()).unwrap_or_default();
    let mut out: Vec<Option<Ends>> =
        ends.into_iter().map(|e| e.map(|(start, to)| Ends { start, to, whole: true })).collect();
    for offset in 0..plans.len() {
        let (m, plan) = (&moves[offset], &plans[offset]);
        let Some(after) = next[offset] else { continue };
        let (n, next_plan) = (&moves[after], &plans[after]);
        let rapid = |m: &Move, index: usize| m.motion == Motion::Rapid && !judged.judges(m, first + index);
        if left[offset]
            || left[after]
            || !rapid(m, offset)
            || !rapid(n, after)
            || !m.cycle.is_synthetic()
            || plan.segments.len() != 1
            || plan.jumps > 0
            || plan.lead_in
            || next_plan.jumps > 0
            || next_plan.lead_in
        {
            continue;
        }
        let (from, to) = (written::contour_start(toolpath, first + after), n.contour);
        let (along_x, along_z) = if n.cycle.is_synthetic() {
            (from.x != to.x, from.z != to.z)
        } else {
            match thread_depth_axis(toolpath, first + after).or_else(|| single_cycle_axis(toolpath, first + after)) {
                Some(DepthAxis::X) => (from.x != to.x, false),
                Some(DepthAxis::Z) => (false, from.z != to.z),
                None => continue,
            }
        };
        let corrected = plan.end();
        let written = as_written(plan.start, toolpath, first + offset);
        let end = Xz::new(if along_x { written.x } else { corrected.x }, if along_z { written.z } else { corrected.z });
        let same_way = same_directions(end, corrected, plan.start);
        if end.distance(corrected) <= 1e-9
            || !same_way
            || !next_plan.segments.first().is_some_and(|s| same_directions(end, corrected, s.end()))
        {
            continue;
        }
        out[offset] = Some(Ends { start: plan.start, to: end, whole: false });
    }
    out
}

/// The axis a thread cycle cuts its depth along, or a single turning or facing cycle runs
/// its approach and its move back out along (`single_cycle_axis`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum DepthAxis {
    X,
    Z,
}

/// Where move `index` is the first of a thread cycle's, the axis its passes cut their depth
/// along (the one its first thread move travels less): the cycle returns to its start point
/// along that axis only as a retract in the air. `None` for another cycle, whose passes may
/// take their depth from the start point (a roughing cycle's depths of cut).
fn thread_depth_axis(toolpath: &Toolpath, index: usize) -> Option<DepthAxis> {
    let cycle = toolpath.moves.get(index)?.cycle;
    let moves = toolpath.moves.get(index..)?.iter().take_while(|m| m.cycle == cycle);
    let k = index + moves.take_while(|m| !m.threading).count();
    let thread = toolpath.moves.get(k).filter(|m| m.threading && m.cycle == cycle)?;
    let (from, to) = (written::contour_start(toolpath, k), thread.contour);
    Some(if (to.x - from.x).abs() < (to.z - from.z).abs() { DepthAxis::X } else { DepthAxis::Z })
}

/// Where move `index` is the first of a single turning or facing cycle's run (`G90`, `G94`:
/// a rapid along one axis to where its cut starts, the cut, the feed back out along that axis
/// to the start point, the rapid to it), that axis: the run takes from its start point along
/// it only where its move back out ends, over the part, while along the other axis its cut
/// starts there. `None` for any other run.
pub(crate) fn single_cycle_axis(toolpath: &Toolpath, index: usize) -> Option<DepthAxis> {
    let cycle = toolpath.moves.get(index)?.cycle;
    let mut run = toolpath.moves.get(index..)?.iter().take_while(|m| m.cycle == cycle);
    let (Some(approach), Some(cut), Some(out), Some(back), None) =
        (run.next(), run.next(), run.next(), run.next(), run.next())
    else {
        return None;
    };
    let straight = |m: &Move, motion: Motion| m.motion == motion && !m.threading;
    let kinds = [(approach, Motion::Rapid), (cut, Motion::Feed), (out, Motion::Feed), (back, Motion::Rapid)];
    if !kinds.into_iter().all(|(m, motion)| straight(m, motion)) {
        return None;
    }
    let start = toolpath.start_of(index);
    let along_x = approach.end.z == start.z && out.end.z == cut.end.z && out.end.x == start.x;
    let along_z = approach.end.x == start.x && out.end.x == cut.end.x && out.end.z == start.z;
    match (along_x, along_z) {
        (true, false) => Some(DepthAxis::X),
        (false, true) => Some(DepthAxis::Z),
        _ => None,
    }
}

/// For each move `left`, where it starts and ends when its block runs as written: from where
/// the move before it ends (as written, if that one is left too).
fn written_ends(plans: &[MovePlan], left: &[bool], toolpath: &Toolpath, first: usize) -> Vec<Option<(Xz, Xz)>> {
    let mut ends = vec![None; plans.len()];
    let mut from: Option<Xz> = None;
    for (offset, plan) in plans.iter().enumerate() {
        if plan.segments.is_empty() {
            continue;
        }
        if left[offset] {
            let start = from.unwrap_or(plan.start);
            let to = as_written(start, toolpath, first + offset);
            ends[offset] = Some((start, to));
            from = Some(to);
        } else {
            from = None;
        }
    }
    ends
}

/// Whether the corrected move `next` may start from `to` instead of `corrected`: it leads in
/// with no jog of its own, and travels no axis the other way from either.
fn travel_kept(next: &MovePlan, to: Xz, corrected: Xz) -> bool {
    !next.lead_in && next.jumps == 0 && next.segments.first().is_some_and(|s| same_directions(to, corrected, s.end()))
}

/// Where move `index` ends when its block runs as written from `start`: at its programmed
/// end along each axis it travels, and where it starts along one it does not (its block
/// does not move that axis, whatever the moves before it were corrected to).
fn as_written(start: Xz, toolpath: &Toolpath, index: usize) -> Xz {
    let (from, to) = (written::contour_start(toolpath, index), toolpath.moves[index].contour);
    let axis = |from: f64, to: f64, start: f64| if from == to { start } else { to };
    Xz::new(axis(from.x, to.x, start.x), axis(from.z, to.z, start.z))
}

/// How far the straight move from `start` to `to` runs from `plan`'s path at most: from its
/// end, and from each of its segments' ends.
fn runs_off(plan: &MovePlan, start: Xz, to: Xz) -> f64 {
    let ends = plan.segments.iter().map(|s| distance_to_chord(s.end(), start, to));
    ends.fold(to.distance(plan.end()), f64::max)
}

/// Whether a move to `end` travels no axis the other way from `to` than from `corrected`:
/// an axis it travels from one and not from the other is no reversal.
fn same_directions(to: Xz, corrected: Xz, end: Xz) -> bool {
    let agree = |a: i8, b: i8| a * b >= 0;
    agree(sign(end.x - to.x), sign(end.x - corrected.x)) && agree(sign(end.z - to.z), sign(end.z - corrected.z))
}

/// The direction of a travel along an axis: none below a nanometre.
fn sign(d: f64) -> i8 {
    if d > 1e-6 {
        1
    } else if d < -1e-6 {
        -1
    } else {
        0
    }
}
