//! What each move becomes: the segments to write for it, in the program's contour frame.
//!
//! A move keeps its programmed form when the programmed element, from where the previous
//! written move ends, passes within the tolerance of every point to write for it and its
//! end point rounds to the same place on the grid: such a block is left as it is. Any
//! other move is re-expressed by `choose_segments` from its written points
//! (`written.rs`).
//!
//! **Backlash at a reversal.** When an axis reverses, the inverse takes up the play by
//! commanding a jump of the play in the new direction (`inverse.rs`). Smeared into the
//! move after the reversal, that jump would tilt its first segment across the part; it is
//! written instead as its own short move at the reversal point, and the move goes on from
//! there. A jump is what the inverse records where it reversed an axis: the command's
//! travel inside the play before the slide moves (`Tracker::take_up`). A correction that
//! drifts along a move without reversing its slide (squareness along a long turn) is no
//! jump, however far apart its samples: it is written into the move itself. Under
//! nose-radius compensation a jump at a concave corner is shorter than the control's
//! cut-back there, and `nose_room.rs` takes it into its neighbours.
//!
//! Rapids are sampled only at their end and written as one move to the corrected end;
//! thread moves stay one move (a thread cannot be cut in pieces), to their corrected end;
//! so does a move that switches nose-radius compensation on or off (`G41`/`G42`/`G40`):
//! the control makes its approach or departure over the whole block, and split into pieces
//! it would make it over the first piece only.

use std::ops::Range;

use smallvec::{SmallVec, smallvec};

use crate::back::grid::{ArcWords, Grid};
use crate::geometry;
use crate::semantic::nose_radius::ToolTable;
use crate::toolpath::{Motion, Move, Toolpath, Xz};

use super::fit::{self, FitOptions, MovePoints, NominalShape, Segment, Segments, distance_to_chord};
use super::written;
use crate::error_model::sampling::PathSample;

/// One move's plan.
#[derive(Debug, Clone, PartialEq)]
pub struct MovePlan {
    /// Where the written move starts: the exact end of the previous written move.
    pub start: Xz,
    /// The segments to write, in the contour frame; empty for a move that is not written
    /// (a dwell, a corner the control makes under `G41`/`G42`).
    pub segments: Segments,
    /// Whether the segments differ from the programmed move.
    pub changed: bool,
    /// The backlash jumps written as their own moves.
    pub jumps: usize,
    /// The first segment takes up the play before a move that switches nose-radius
    /// compensation: it is written as a positioning block of its own, before the block.
    pub lead_in: bool,
    /// For each segment, the words `settle_arcs` chose for it (`ArcWords::Line` for a
    /// line), so that rounding and rewriting do not choose them again; empty for a plan
    /// that was not settled (the move as programmed).
    pub words: SmallVec<[ArcWords; 2]>,
}

impl MovePlan {
    /// Where the written move ends.
    pub fn end(&self) -> Xz {
        self.segments.last().map_or(self.start, Segment::end)
    }
}

/// What planning needs besides the path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanOptions {
    pub fit: FitOptions,
    /// The model's play per axis (its backlash), mm; zero for none.
    pub play: Xz,
}

/// The segments for one move's points, by the strategy asked for (`fit::reexpress`); this
/// is the one place that chooses.
pub fn choose_segments(points: &MovePoints<'_>, options: &FitOptions) -> Segments {
    fit::reexpress(points, options)
}

/// The inputs of planning, one entry per sample or per move.
pub struct PlanInput<'a> {
    pub toolpath: &'a Toolpath,
    pub samples: &'a [PathSample],
    pub commanded: &'a [Xz],
    /// The backlash taken up on the way to each sample (`Compensated::take_ups`).
    pub take_ups: &'a [Xz],
    /// `written::sample_ranges`.
    pub ranges: &'a [Range<usize>],
    /// Whether each move can be written back (its block is a motion block, or it belongs
    /// to a cycle that can be expanded).
    pub writable: &'a [bool],
    /// Whether each move's arcs prefer the radius form (`rewrite::MoveForms::radius`).
    pub radius: &'a [bool],
    pub tools: &'a ToolTable,
    /// What the check before writing judges: moves it does not are left as written
    /// (`air.rs`).
    pub judged: Judged<'a>,
}

/// Plan every move.
#[cfg(test)]
pub fn plan_moves(input: &PlanInput<'_>, grid_of: impl Fn(usize) -> Grid, options: &PlanOptions) -> Vec<MovePlan> {
    let mut plans = Vec::with_capacity(input.toolpath.moves.len());
    plan_range(input, 0..input.toolpath.moves.len(), input.toolpath.start, grid_of, options, &mut plans);
    plans
}

/// Plan the moves `moves`, the first written from `at` (the end of the previous move's
/// plan), appending to `plans`, and leave as written the moves that need no correction
/// (`air::leave_alone`); returns where the last ends and how many were left. A move left as
/// written is decided by the move after it, so one at the end of `moves` is left only at the
/// end of the program. `input.ranges` must give the
/// samples of these moves (a program planned in pieces plans as it does whole, given each
/// piece's samples and the one before them, which `jumps` compares the first with).
pub fn plan_range(
    input: &PlanInput<'_>,
    moves: Range<usize>,
    mut at: Xz,
    grid_of: impl Fn(usize) -> Grid,
    options: &PlanOptions,
    plans: &mut Vec<MovePlan>,
) -> (Xz, LeftAlone) {
    let toolpath = input.toolpath;
    let first = moves.start;
    let base = plans.len();
    let mut points: Vec<Xz> = Vec::new();
    let mut jogs = SmallVec::<[Xz; 2]>::new();
    for (index, m) in toolpath.moves.get(moves).unwrap_or_default().iter().enumerate() {
        let index = first + index;
        jogs.clear();
        let contour_start = written::contour_start(toolpath, index);
        let range = input.ranges.get(index).cloned().unwrap_or(0..0);
        let grid = grid_of(index);
        let mut plan = if m.motion == Motion::Dwell || written::is_corner_of_contour(m, contour_start) {
            MovePlan {
                start: at,
                segments: Segments::new(),
                changed: false,
                jumps: 0,
                lead_in: false,
                words: SmallVec::new(),
            }
        } else if range.is_empty() || !input.writable.get(index).copied().unwrap_or(false) {
            nominal_plan(m, at, input.tools)
        } else {
            // One buffer for every move's points: most moves have one or a few.
            points.clear();
            let jumps = written_points(input, m, contour_start, range.clone(), options.play, &mut points);
            jogs.extend(jumps.iter().map(|&(_, jump)| jump));
            let switches = index > 0
                && index.checked_sub(1).and_then(|k| toolpath.moves.get(k)).map(|p| p.compensation)
                    != Some(m.compensation);
            let piece = Piece { m, at, points: &points, grid, jumps };
            if m.motion == Motion::Rapid || m.threading {
                one_move(&piece, input.tools)
            } else if switches {
                switching_move(input, &piece)
            } else {
                plan_one(input, &piece, options)
            }
        };
        if plan.changed {
            settle_arcs(&mut plan, &grid, input.radius.get(index).copied().unwrap_or(false));
        }
        let earlier = plans.len() - (index - first);
        if nose_room::make_room_at(input, index, &mut plans[earlier..], first, &mut plan, &jogs) {
            settle_arcs(&mut plan, &grid, input.radius.get(index).copied().unwrap_or(false));
        }
        at = plan.end();
        plans.push(plan);
    }
    let planned = plans.get_mut(base..).unwrap_or_default();
    let left = air::leave_alone(planned, first, toolpath, input.writable, input.judged);
    (plans.last().map_or(at, MovePlan::end), left)
}

/// The plan with its arcs made writable on `grid`: an arc that no words can write (its
/// rounded ends coincide: `Grid::arc_words`) becomes the straight move the control would
/// make for it, and an arc that the control, given its rounded words, would run more than
/// an increment away from the exact one is cut in halves until it does not.
///
/// The second is the long way round: an `I K` arc of most of a turn has a short chord, and
/// when rounding leaves its end radii a micrometre apart, the control moves the centre
/// along the chord by that micrometre times the radius over the chord (3 µm for a 340°
/// arc of radius 13.5): the far side of the circle moves with it. Each half has a long
/// chord. Cutting keeps the exact geometry; only the cut point is rounded.
fn settle_arcs(plan: &mut MovePlan, grid: &Grid, prefer_radius: bool) {
    if !plan.segments.iter().any(|s| matches!(s, Segment::Arc { .. })) {
        // Nothing to choose: lines have no words to keep.
        return;
    }
    // The settled segments go back into the plan's own storage (a plan of more than two
    // segments has it on the heap), so only the words take new room: as many as there are
    // segments, unless an arc is cut.
    let unsettled: SmallVec<[Segment; 8]> = SmallVec::from_slice(&plan.segments);
    plan.segments.clear();
    let mut words = SmallVec::with_capacity(unsettled.len());
    let mut from = plan.start;
    for &segment in &unsettled {
        settle(grid, prefer_radius, from, segment, MAX_HALVINGS, &mut plan.segments, &mut words);
        from = segment.end();
    }
    plan.words = words;
}

/// At most this many halvings of one arc (into 2⁴ pieces).
const MAX_HALVINGS: u32 = 4;

fn settle(
    grid: &Grid,
    prefer_radius: bool,
    from: Xz,
    segment: Segment,
    halvings: u32,
    out: &mut Segments,
    words_out: &mut SmallVec<[ArcWords; 2]>,
) {
    let Segment::Arc { end, centre, ccw } = segment else {
        out.push(segment);
        words_out.push(ArcWords::Line);
        return;
    };
    let (words, strays) = grid.arc_words_straying(from, end, centre, ccw, prefer_radius, grid.increment_mm());
    if words == ArcWords::Line {
        out.push(Segment::Line { end });
        words_out.push(ArcWords::Line);
        return;
    }
    if halvings > 0 && strays {
        let sweep = geometry::sweep(from, end, centre, ccw);
        let sign = if ccw { 1.0 } else { -1.0 };
        let radius = (from.distance(centre) + end.distance(centre)) / 2.0;
        let middle = geometry::on_circle(centre, radius, geometry::angle(from, centre) + sign * sweep / 2.0);
        let half = Segment::Arc { end: middle, centre, ccw };
        settle(grid, prefer_radius, from, half, halvings - 1, out, words_out);
        settle(grid, prefer_radius, middle, segment, halvings - 1, out, words_out);
        return;
    }
    out.push(segment);
    words_out.push(words);
}

/// The programmed move as a segment of the contour.
pub(crate) fn nominal_segment(m: &Move, tools: &ToolTable) -> Segment {
    if m.is_arc() {
        Segment::Arc { end: m.contour, centre: written::contour_centre(m, tools), ccw: m.motion == Motion::Ccw }
    } else {
        Segment::Line { end: m.contour }
    }
}

fn nominal_plan(m: &Move, start: Xz, tools: &ToolTable) -> MovePlan {
    MovePlan {
        start,
        segments: smallvec![nominal_segment(m, tools)],
        changed: false,
        jumps: 0,
        lead_in: false,
        words: SmallVec::new(),
    }
}

/// One move to plan: where its written form starts, the points to write for its samples,
/// the jumps among them (`written_points`), and the grid they are rounded on.
struct Piece<'a> {
    m: &'a Move,
    at: Xz,
    points: &'a [Xz],
    grid: Grid,
    jumps: Jumps,
}

/// A move written as one move to its corrected end (when that moved on the grid); a rapid
/// sampled through an overshoot before a thread (`sampling::thread_approach`) as a move to
/// each of its points.
fn one_move(piece: &Piece<'_>, tools: &ToolTable) -> MovePlan {
    let Piece { m, at, points, grid, .. } = piece;
    if m.motion == Motion::Rapid && points.len() > 1 {
        return MovePlan {
            start: *at,
            segments: points.iter().map(|&end| Segment::Line { end }).collect(),
            changed: true,
            jumps: 0,
            lead_in: false,
            words: SmallVec::new(),
        };
    }
    match points.last() {
        Some(&last) if grid.point(last) != grid.point(m.contour) => MovePlan {
            start: *at,
            segments: smallvec![Segment::Line { end: last }],
            changed: true,
            jumps: 0,
            lead_in: false,
            words: SmallVec::new(),
        },
        _ => nominal_plan(m, *at, tools),
    }
}

/// A move that switches compensation: one move, after the play its start reverses taken
/// up by a positioning move of its own (`lead_in`).
fn switching_move(input: &PlanInput<'_>, piece: &Piece<'_>) -> MovePlan {
    let Piece { m, at, points, ref jumps, .. } = *piece;
    let Some(&(_, jump)) = jumps.first().filter(|(at, _)| *at == 0) else {
        return one_move(piece, input.tools);
    };
    let Some(&last) = points.last() else { return nominal_plan(m, at, input.tools) };
    let taken_up = Xz::new(at.x + jump.x, at.z + jump.z);
    MovePlan {
        start: at,
        segments: smallvec![Segment::Line { end: taken_up }, Segment::Line { end: last }],
        changed: true,
        jumps: 1,
        lead_in: true,
        words: SmallVec::new(),
    }
}

fn plan_one(input: &PlanInput<'_>, piece: &Piece<'_>, options: &PlanOptions) -> MovePlan {
    let Piece { m, at, points, grid, ref jumps, .. } = *piece;
    let Some(&last) = points.last() else { return nominal_plan(m, at, input.tools) };
    let tolerance = options.fit.tolerance_mm;
    let centre = written::contour_centre(m, input.tools);
    let end_stays = || grid.point(last) == grid.point(m.contour);
    if jumps.is_empty() && end_stays() && nominal_holds(m, centre, at, points, tolerance) {
        return nominal_plan(m, at, input.tools);
    }
    let nominal = if m.is_arc() {
        NominalShape::Arc { centre, ccw: m.motion == Motion::Ccw, radius: m.contour.distance(centre) }
    } else {
        NominalShape::Line
    };
    if jumps.is_empty() {
        let segments = choose_segments(&MovePoints { start: at, points, nominal }, &options.fit);
        return MovePlan { start: at, segments, changed: true, jumps: 0, lead_in: false, words: SmallVec::new() };
    }
    let mut segments = Segments::new();
    let mut from = at;
    let mut piece = 0;
    let mut written_jumps = 0;
    for &(local, jump) in jumps {
        if local > piece {
            let part = MovePoints { start: from, points: &points[piece..local], nominal };
            segments.extend_from_slice(&choose_segments(&part, &options.fit));
            from = points[local - 1];
        }
        let before = from;
        from = Xz::new(from.x + jump.x, from.z + jump.z);
        // A jump within an increment is no move the control can make: its block would
        // repeat the point the one before ends at.
        if grid.point(from) != grid.point(before) {
            segments.push(Segment::Line { end: from });
            written_jumps += 1;
        }
        piece = local;
    }
    if piece < points.len() {
        let rest = MovePoints { start: from, points: &points[piece..], nominal };
        segments.extend_from_slice(&choose_segments(&rest, &options.fit));
    }
    MovePlan { start: at, segments, changed: true, jumps: written_jumps, lead_in: false, words: SmallVec::new() }
}

/// Whether the programmed element (an arc about the contour's `centre`), started from
/// `at`, passes within `tolerance` of every point.
fn nominal_holds(m: &Move, centre: Xz, at: Xz, points: &[Xz], tolerance: f64) -> bool {
    if m.is_arc() {
        let radius = m.contour.distance(centre);
        (at.distance(centre) - radius).abs() <= tolerance
            && points.iter().all(|p| (p.distance(centre) - radius).abs() <= tolerance)
    } else {
        points.iter().all(|&p| distance_to_chord(p, at, m.contour) <= tolerance)
    }
}

/// The jumps of a move: the written path's steps at a point, each with the index of the
/// written point it leads to (`points`), and the step. A jump is the play the inverse took
/// up on the way to a sample (`Compensated::take_ups`), or, at a move's start sample (where
/// the model's correction steps at a corner: `ArcTerms::steps_at_corners`), the whole
/// change of the correction from the sample before, at the same point.
type Jumps = SmallVec<[(usize, Xz); 2]>;

/// Append to `points` the point to write for each sample of `range` (of move `m`), and
/// return the move's jumps (`Jumps`); a move's start sample is a jump, not a point.
fn written_points(
    input: &PlanInput<'_>,
    m: &Move,
    contour_start: Xz,
    range: Range<usize>,
    play: Xz,
    points: &mut Vec<Xz>,
) -> Jumps {
    let first = points.len();
    let mut jumps = Jumps::new();
    let with_play = play.x > 0.0 || play.z > 0.0;
    for j in range {
        let sample = &input.samples[j];
        let now = written::offset(sample, input.commanded[j]);
        if sample.param == 0.0 {
            if let Some(before) = j.checked_sub(1).map(|k| written::offset(&input.samples[k], input.commanded[k])) {
                let step = Xz::new(now.x - before.x, now.z - before.z);
                if step.x != 0.0 || step.z != 0.0 {
                    jumps.push((points.len() - first, step));
                }
            }
            continue;
        }
        if with_play {
            let jump = input.take_ups.get(j).copied().unwrap_or_default();
            if jump.x != 0.0 || jump.z != 0.0 {
                jumps.push((points.len() - first, jump));
            }
        }
        // `written::written_from`, with the correction taken here.
        let contour = written::contour_at(m, contour_start, sample, input.tools);
        points.push(Xz::new(contour.x + now.x, contour.z + now.z));
    }
    jumps
}

mod air;
mod kept;
mod nose_room;
pub(crate) use air::{DepthAxis, single_cycle_axis};
pub use air::{Judged, LeftAlone};
pub use kept::KeptPlans;

#[cfg(test)]
mod tests;
