//! Predicted points measured against the original's nominal path, by following the
//! original along as a program runs.
//!
//! **The measure.** A predicted cutting point's distance to the closest cutting move of the
//! original within `WINDOW_MM` of cutting length either side of the point's own nominal
//! point on the original's path (and at least the `NEIGHBOURS` cutting moves either side of
//! its move). That is the closest point of the whole path wherever it lies on the point's
//! own pass or on a pass that overlaps it within the window; a pass that comes back over the
//! same place later in the program (a finishing pass over the roughing, a program whose
//! passes pile up over the same area) is not the surface being cut, as `compensate`'s
//! `LocalPath` has it, and is what made a whole-path search quadratic on such programs. The
//! window holds a bounded number of moves, so a program is measured in linear time.
//!
//! **The own point.** An original's sample knows its own point. A compensated sample's
//! nominal point `c` lies on the compensated path, whose moves do not correspond to the
//! original's one for one (edited blocks, densified lines, moves added at reversals), so its
//! own point is found by a monotone walk. The candidates are the cutting moves of the
//! original from the previous match's move forward over `WINDOW_MM` of cutting length (and
//! the `NEIGHBOURS` next cutting moves, however long); the match is the first candidate
//! within `SLACK_MM` of the closest candidate's distance to `c` (and within `MATCH_MM`), at
//! its closest point to `c`. The point is then measured against the moves within the window
//! about the match and the rest of the candidates.
//!
//! **Why the walk is exact.** Both programs cut in the same order, and `compensate` moves
//! each point by its correction, at most `--max-shift` (`MATCH_MM`, 0.1 mm, by default; a few
//! micrometres on a healthy machine). So `c` is within the shift of the original point `n`
//! it was corrected from, on the move `own`. From one sample to the next the compensated
//! path goes on by at most a sampling step and `n` by at most a step and twice the shift
//! along the original's cutting path (rapids and other moves that do not cut count for no
//! length: a cut resumes where the next pass starts), far less than the window, so `own` is
//! a candidate while the previous match is not past it. The match is never past `own`: a
//! later candidate is taken only where `own` is further from `c` than the closest candidate
//! by more than `SLACK_MM`, which a correction of micrometres never is. It may be an earlier
//! move that comes as close to `c` (the move before a corner, a pass crossing `own`, the
//! way back of a zigzag running beside its way out); the moves measured against hold the
//! candidates, and so `own` and every pass overlapping it ahead within the window, and the
//! window about the match every pass overlapping behind. The closest of them is found. With
//! the first candidate within `MATCH_MM` as the match, the walk would stay on the way out of
//! a zigzag while its way back goes on beside it, beyond the window; with the closest, it
//! would run ahead onto a later pass that happens to come closer to `c`, and lose `own`
//! behind it.
//!
//! **Where the walk fails.** A compensated point further than `MATCH_MM` from every
//! candidate (an added excursion, a program that is not a compensation of the original, a
//! `--max-shift` above the default) is measured against the whole original path
//! (`PathIndex`, built the first time it is needed), and the walk resumes from the whole
//! path's closest point to `c` where that is within `MATCH_MM`. Such points cost a
//! whole-path search each.

use std::cell::OnceCell;
use std::ops::RangeInclusive;

use smallvec::SmallVec;

use crate::compensation::deviation::{Closest, LocalPath, PathIndex};
use crate::toolpath::{Motion, Xz};

/// How far ahead of the previous match, in cutting length along the original's path, the
/// next match is searched for, and how far either side of a point's own point its closest
/// point is, mm: many sampling steps and shifts.
const WINDOW_MM: f64 = 10.0;
/// How much further from a compensated nominal point than the closest candidate the match
/// may be, mm: the first candidate this close is taken (see the module documentation).
const SLACK_MM: f64 = 0.02;
/// The cutting moves either side of a match that every window holds, however long.
const NEIGHBOURS: usize = 2;
/// The farthest a compensated nominal point is taken to be from its own point on the
/// original's path, mm: `compensate`'s default `--max-shift`.
const MATCH_MM: f64 = 0.1;
/// The most moves a window looks at either side of the previous match, whatever their
/// length (a run of moves that do not cut counts for no length).
const WINDOW_MOVES: usize = 4096;

/// A predicted point's closest point on the original's path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Found {
    pub distance: f64,
    /// The closest point, and the original's move it lies on.
    pub point: Xz,
    pub move_index: usize,
}

impl Found {
    fn on(move_index: usize, closest: Closest) -> Found {
        Found { distance: closest.distance, point: closest.point, move_index }
    }
}

/// The original's nominal path, followed through the compensated program's samples in order.
pub struct Follower<'a> {
    path: &'a LocalPath<'a>,
    /// The cutting length of the original's path up to the end of each move, mm.
    cut_ends: Vec<f64>,
    /// The previous match: its move and its cutting length along the path.
    move_index: usize,
    at: f64,
    /// The whole path, for points the window does not match.
    index: OnceCell<PathIndex<'a>>,
}

impl<'a> Follower<'a> {
    pub fn new(path: &'a LocalPath<'a>) -> Follower<'a> {
        let mut total = 0.0;
        let cut_ends = (path.toolpath().moves.iter().enumerate())
            .map(|(k, m)| {
                if m.cutting && m.motion != Motion::Dwell {
                    total += path.length_of(k);
                }
                total
            })
            .collect();
        Follower { path, cut_ends, move_index: 0, at: 0.0, index: OnceCell::new() }
    }

    /// The distance of `p`, predicted for the cutting sample at `nominal`, from the
    /// original's nominal path (see the module documentation), the closest point of that
    /// path and its move.
    pub fn measure(&mut self, nominal: Xz, p: Xz) -> Option<Found> {
        let window = self.window(0.0, WINDOW_MM);
        let ahead = self.move_index.max(*window.start())..=*window.end();
        // Distances first (no angles): the closest point is found for the match alone.
        let candidates: SmallVec<[(f64, usize); 32]> = ahead
            .clone()
            .filter_map(|k| {
                let distance = self.path.distance_to(nominal, k);
                distance.is_finite().then_some((distance, k))
            })
            .collect();
        let best = candidates.iter().map(|&(distance, _)| distance).fold(f64::INFINITY, f64::min);
        let limit = MATCH_MM.min(best + SLACK_MM);
        let matched = candidates.into_iter().find(|&(distance, _)| distance <= limit);
        let Some((k, closest)) = matched.and_then(|(_, k)| self.path.closest_on(k, nominal).map(|c| (k, c))) else {
            // Lost: match over the whole path, measure against the whole path.
            if let Some((distance, k)) = self.index().closest(nominal)
                && distance <= MATCH_MM
                && let Some(closest) = self.path.closest_on(k, nominal)
            {
                self.move_to(k, closest.param);
            }
            let (distance, k) = self.index().closest(p)?;
            let point = self.path.closest_on(k, p).map_or(p, |closest| closest.point);
            return Some(Found { distance, point, move_index: k });
        };
        self.move_to(k, closest.param);
        // The window about the match, and the rest of the window searched, which holds the
        // point's own move wherever the match is an earlier move that comes as close.
        let around = self.window(WINDOW_MM, WINDOW_MM);
        let moves = *around.start().min(ahead.start())..=*around.end().max(ahead.end());
        self.closest_in(moves, p).map(|(_, k, closest)| Found::on(k, closest))
    }

    /// The side of the original's path `p` lies on, from what measuring it found
    /// (`LocalPath::side`).
    pub fn side(&self, found: &Found, p: Xz) -> f64 {
        self.path.side(found.move_index, found.point, p)
    }

    /// The original's move the last point was matched to (its own point's move).
    pub fn matched_move(&self) -> usize {
        self.move_index
    }

    fn move_to(&mut self, k: usize, param: f64) {
        let start = if k == 0 { 0.0 } else { self.cut_ends.get(k - 1).copied().unwrap_or(0.0) };
        self.move_index = k;
        self.at = start + self.path.length_of(k) * param.clamp(0.0, 1.0);
    }

    /// The distance of `p`, predicted for the point at `param` of the original's move `k`,
    /// from the original's nominal path, its closest point and move: the closest cutting move within `WINDOW_MM` of that
    /// point (and the `NEIGHBOURS` cutting moves either side).
    pub fn measure_from(&mut self, k: usize, param: f64, p: Xz) -> Option<Found> {
        self.move_to(k, param);
        self.closest_in(self.window(WINDOW_MM, WINDOW_MM), p).map(|(_, k, closest)| Found::on(k, closest))
    }

    /// The moves within `back` and `ahead` mm of cutting length of the previous match, and
    /// the `NEIGHBOURS` cutting moves either side of its move, whatever their length.
    fn window(&self, back: f64, ahead: f64) -> RangeInclusive<usize> {
        let moves = self.path.toolpath().moves.len();
        let cut_start = |k: usize| if k == 0 { 0.0 } else { self.cut_ends.get(k - 1).copied().unwrap_or(0.0) };
        let cuts = |k: usize| self.path.toolpath().moves.get(k).is_some_and(|m| m.cutting && m.motion != Motion::Dwell);
        let mut first = self.move_index.min(moves.saturating_sub(1));
        let mut passed = 0;
        while first > 0
            && self.move_index - first < WINDOW_MOVES
            && (self.at - cut_start(first) <= back || passed < NEIGHBOURS)
        {
            first -= 1;
            passed += usize::from(cuts(first));
        }
        let mut last = self.move_index.min(moves.saturating_sub(1));
        let mut passed = 0;
        while last + 1 < moves
            && last + 1 - self.move_index < WINDOW_MOVES
            && (cut_start(last + 1) - self.at <= ahead || passed < NEIGHBOURS)
        {
            last += 1;
            passed += usize::from(cuts(last));
        }
        first..=last
    }

    /// The closest cutting move of `moves` to `point`: its distance, its index and the
    /// closest point (the earliest move where several are equally close).
    fn closest_in(&self, moves: RangeInclusive<usize>, point: Xz) -> Option<(f64, usize, Closest)> {
        // Distances first (no angles): the closest point is found for the closest move alone.
        let mut best: Option<(f64, usize)> = None;
        for k in moves {
            let distance = self.path.distance_to(point, k);
            if distance.is_finite() && best.is_none_or(|(closest, _)| distance < closest) {
                best = Some((distance, k));
            }
        }
        let (_, k) = best?;
        self.path.closest_on(k, point).map(|closest| (closest.distance, k, closest))
    }

    fn index(&self) -> &PathIndex<'a> {
        self.index.get_or_init(|| PathIndex::new(self.path.toolpath(), |m| m.cutting))
    }
}
