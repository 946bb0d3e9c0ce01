//! Rapids left as written: compensation changes what shapes the part and leaves the rest
//! of the program as the programmer wrote it (issue 25, "rapids ... are left alone").
//!
//! A rapid shapes nothing either measure judges: only its end matters, and only where the
//! next move starts from it. So a straight rapid whose next move is a rapid too, or that
//! ends the program, ends where the program puts it: a retract, the rapids to the tool
//! change and home. Its correction is not carried by any later move: each move is planned
//! from the samples of the inverse, which solves every point on its own, so the move after
//! it still ends where it needs to. A rapid that ends where a feed move, a cycle or a thread
//! starts is corrected: there the start is part of what is cut.
//!
//! A rapid is left alone only where the rapid after it is left alone too, or travels no axis
//! the other way than it does from the corrected end: a reversal the inverse did not plan
//! for, on the way to a cut, would take up play the model has there. Rapids of a cycle, and
//! one whose next move begins with a jog of its own, are planned as before.
//!
//! Feed moves in the air (an approach, a roughing pass a later pass cuts away) are corrected
//! still, as is a rapid's end where the cut after it starts along its line: which of them
//! shape the finished part, and where a cut's start is clear of the material, needs the
//! whole tool's shape against the part (the insert's body cuts too), which is not built.

use crate::toolpath::{Motion, Move, Toolpath, Xz};

use super::super::fit::Segment;
use super::super::written;
use super::MovePlan;

/// Which moves the check before writing judges, so that compensation must correct them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Judged {
    /// Every move, rapids too: none is left as written.
    Every,
    /// Every feed move: rapids shape nothing judged (both measures judge only what is cut).
    EveryFeed,
}

impl Judged {
    fn judges(self, m: &Move) -> bool {
        match self {
            Judged::Every => true,
            Judged::EveryFeed => m.motion != Motion::Rapid,
        }
    }
}

/// Leave the rapids of `plans` (the plans of moves `first..`, each planned from the end of
/// the one before) that need no correction as written (module documentation). Returns the
/// number left as written.
pub(super) fn leave_alone(
    plans: &mut [MovePlan],
    first: usize,
    toolpath: &Toolpath,
    writable: &[bool],
    judged: Judged,
) -> usize {
    let moves = toolpath.moves.get(first..first + plans.len()).unwrap_or_default();
    let free = |offset: usize| {
        let index = first + offset;
        let m = &moves[offset];
        !judged.judges(m)
            && m.cycle.is_synthetic()
            && !m.threading
            && !m.is_arc()
            && writable.get(index).copied().unwrap_or(false)
    };
    // The program's last moves end where they are programmed whatever follows them in the
    // piece: nothing starts from them.
    let ends_program = first + plans.len() >= toolpath.moves.len();
    let mut left = 0;
    // From the last move back: whether a move may end as written depends on the plan of the
    // move after it, which is final by then.
    let mut next: Option<(usize, bool)> = None;
    for offset in (0..plans.len()).rev() {
        if plans[offset].segments.is_empty() {
            // A dwell or a corner the control makes: the move after it starts where the one
            // before ends.
            continue;
        }
        let after = next.replace((offset, false));
        if !free(offset) {
            continue;
        }
        let until = match after {
            None if ends_program => plans.len() - 1,
            None => continue,
            Some((after, after_left)) => {
                if !free(after) {
                    // The next move cuts (or is a cycle's, a thread's): it starts at the
                    // corrected end.
                    continue;
                }
                // The rapid after ends where it is programmed, or corrected for the cut after
                // it: it may start anywhere that leaves its travel as planned.
                let corrected = plans[offset].end();
                let next_plan = &plans[after];
                let to = as_written(plans[offset].start, toolpath, first + offset);
                let travel_kept = after_left
                    || (!next_plan.lead_in
                        && next_plan.jumps == 0
                        && next_plan.segments.first().is_some_and(|s| same_directions(to, corrected, s.end())));
                if !travel_kept {
                    continue;
                }
                after
            }
        };
        let to = as_written(plans[offset].start, toolpath, first + offset);
        plans[offset] = MovePlan {
            start: plans[offset].start,
            segments: smallvec::smallvec![Segment::Line { end: to }],
            changed: false,
            jumps: 0,
            lead_in: false,
            words: smallvec::SmallVec::new(),
        };
        for plan in plans.iter_mut().take(until + 1).skip(offset + 1) {
            plan.start = to;
        }
        next = Some((offset, true));
        left += 1;
    }
    left
}

/// Where move `index` ends when its block runs as written from `start`: at its programmed
/// end along each axis it travels, and where it starts along one it does not (its block
/// does not move that axis, whatever the moves before it were corrected to).
fn as_written(start: Xz, toolpath: &Toolpath, index: usize) -> Xz {
    let (from, to) = (written::contour_start(toolpath, index), toolpath.moves[index].contour);
    let axis = |from: f64, to: f64, start: f64| if from == to { start } else { to };
    Xz::new(axis(from.x, to.x, start.x), axis(from.z, to.z, start.z))
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
