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
//! (`WholePath`, built the first time it is needed), and the walk resumes from the whole
//! path's closest point to `c` where that is within `MATCH_MM`. Such points cost a
//! whole-path search each.
//!
//! **What it costs.** A window's ends move on with the walk, so each is found from where it
//! was (`Cursors`), not by walking the window's moves again. Of a window's moves only those
//! whose bounding box comes nearer the point than the closest move found so far are
//! measured (`Original::lower_bound`), and the own move (or the match) is measured first,
//! so on a pass that keeps its distance from the others a point costs the distances to its
//! own move and to the neighbours its corners touch. No angle is taken but where a match on
//! an arc needs its place along the arc: the closest point of a line is its projection,
//! of an arc the point's projection onto its circle.

use std::cell::OnceCell;
use std::collections::HashMap;
use std::ops::RangeInclusive;

use crate::compensation::fit::distance_to_chord;
use crate::geometry::{self, Sector};
use crate::toolpath::compact::{CompactMove, CompactPath};
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
/// How much nearer than the closest distance found so far a move's bounding box must come
/// for the move to be measured, mm: far more than the rounding of a distance (a few 1e-14
/// mm on a lathe's coordinates), so a move left out is further by more than rounding and
/// can be neither the closest nor as close.
const BOUND_MARGIN_MM: f64 = 1e-9;

/// How far from an anchor move's bounding box the moves kept as its neighbourhood lie at
/// most, mm (`Near`): far more than twice a point's distance from its own move (a model's
/// errors and a correction are micrometres, the shift at most `MATCH_MM`), so a point is
/// measured against the neighbourhood alone but where it lies further from its own move.
const NEAR_MM: f64 = 0.5;

/// A predicted point's closest point on the original's path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Found {
    pub distance: f64,
    /// The closest point, and the original's move it lies on.
    pub point: Xz,
    pub move_index: usize,
}

/// The original's nominal path as points are measured against it: its compact moves, their
/// lengths along the path and along the cut.
pub struct Original<'a> {
    path: &'a CompactPath,
    /// The length of the path up to the end of each move, mm.
    ends: Vec<f64>,
    /// The cutting length of the path up to the end of each move, mm.
    cut_ends: Vec<f64>,
    /// Each move's bounding box (`x_low, z_low, x_high, z_high`), an arc's taken as its whole
    /// circle's, rounded outward to single precision: the box of every point of the move
    /// (empty, low above high, for a move that does not cut). Scanned for every point
    /// measured, so kept small.
    boxes: Vec<[f32; 4]>,
}

/// A bounding box of move `m` of `path` (move `k`), rounded outward (`Original::boxes`).
fn bounding_box(path: &CompactPath, k: usize, m: &CompactMove) -> [f32; 4] {
    if !m.cuts() {
        return [f32::INFINITY, f32::INFINITY, f32::NEG_INFINITY, f32::NEG_INFINITY];
    }
    let (lo, hi) = match path.arc(k) {
        Some(arc) => (
            Xz::new(arc.centre.x - arc.radius, arc.centre.z - arc.radius),
            Xz::new(arc.centre.x + arc.radius, arc.centre.z + arc.radius),
        ),
        None => {
            let start = path.start_of(k);
            (Xz::new(start.x.min(m.end.x), start.z.min(m.end.z)), Xz::new(start.x.max(m.end.x), start.z.max(m.end.z)))
        }
    };
    // `as` rounds to nearest; a step outward makes the box hold the move.
    let down = |v: f64| step_down(v as f32);
    let up = |v: f64| -step_down(-(v as f32));
    [down(lo.x), down(lo.z), up(hi.x), up(hi.z)]
}

/// The next single-precision value below `f` (`f32::next_down`, which the crate's
/// rust-version does not have): one unit in the last place down, through zero to the
/// smallest negative subnormal; NaN and negative infinity stay.
fn step_down(f: f32) -> f32 {
    if f.is_nan() || f == f32::NEG_INFINITY {
        f
    } else if f == 0.0 {
        -f32::from_bits(1)
    } else if f > 0.0 {
        f32::from_bits(f.to_bits() - 1)
    } else {
        f32::from_bits(f.to_bits() + 1)
    }
}

impl<'a> Original<'a> {
    pub fn new(path: &'a CompactPath) -> Original<'a> {
        let (mut total, mut cut) = (0.0, 0.0);
        let mut ends = Vec::with_capacity(path.len());
        let mut cut_ends = Vec::with_capacity(path.len());
        let mut boxes = Vec::with_capacity(path.len());
        for (k, m) in path.moves().iter().enumerate() {
            boxes.push(bounding_box(path, k, m));
            let before = total;
            total += path.length(k);
            ends.push(total);
            // The move's length as the difference of the sums, as `length_of` gives it.
            if m.cuts() {
                cut += (total - before).max(0.0);
            }
            cut_ends.push(cut);
        }
        Original { path, ends, cut_ends, boxes }
    }

    /// The length of move `k`, mm (0 for a dwell or a move that does not exist).
    pub fn length_of(&self, k: usize) -> f64 {
        let end = self.ends.get(k).copied().unwrap_or(0.0);
        let start = if k == 0 { 0.0 } else { self.ends.get(k - 1).copied().unwrap_or(end) };
        (end - start).max(0.0)
    }

    /// The cutting length of the path up to the start of move `k`, mm.
    fn cut_start(&self, k: usize) -> f64 {
        if k == 0 { 0.0 } else { self.cut_ends.get(k - 1).copied().unwrap_or(0.0) }
    }

    fn cuts(&self, k: usize) -> Option<&CompactMove> {
        self.path.moves().get(k).filter(|m| m.cuts())
    }

    /// The arc's sector of move `m` (move `k`), its angles as measured once.
    fn sector(&self, k: usize, m: &CompactMove) -> Option<(Sector, f64, Xz)> {
        let arc = self.path.arc(k)?;
        let start = self.path.start_of(k);
        let ccw = m.motion == Motion::Ccw;
        Some((Sector::with_angles(start, m.end, arc.centre, ccw, arc.start_angle, arc.sweep), arc.radius, arc.centre))
    }

    /// The distance from `p` to move `k` when it cuts (infinity otherwise): to the arc where
    /// `p` lies in its sector, else to its nearer end; to the line's closest point.
    pub fn distance(&self, p: Xz, k: usize) -> f64 {
        let Some(m) = self.cuts(k) else { return f64::INFINITY };
        let start = self.path.start_of(k);
        match self.sector(k, m) {
            Some((sector, radius, centre)) => {
                if sector.contains(p) {
                    (p.distance(centre) - radius).abs()
                } else {
                    p.distance(start).min(p.distance(m.end))
                }
            }
            None => distance_to_chord(p, start, m.end),
        }
    }

    /// A lower bound of the square of `distance(p, k)` (infinity for a move that does not
    /// cut): the square of the distance from `p` to the move's bounding box (`boxes`).
    fn lower_bound_squared(&self, p: Xz, k: usize) -> f64 {
        let Some(b) = self.boxes.get(k) else { return f64::INFINITY };
        let dx = (f64::from(b[0]) - p.x).max(p.x - f64::from(b[2])).max(0.0);
        let dz = (f64::from(b[1]) - p.z).max(p.z - f64::from(b[3])).max(0.0);
        dx * dx + dz * dz
    }

    /// The closest point of move `k` to `p`, where `distance` measures to: the projection onto
    /// the line, onto the arc's circle where `p` lies in its sector, else the nearer end (the
    /// start where both are as near). No angle is taken.
    pub fn closest_point(&self, p: Xz, k: usize) -> Xz {
        let Some(m) = self.path.moves().get(k) else { return p };
        let start = self.path.start_of(k);
        match self.sector(k, m) {
            Some((sector, radius, centre)) => match onto_circle(p, centre, radius).filter(|_| sector.contains(p)) {
                Some(on) => on,
                None if p.distance(m.end) < p.distance(start) => m.end,
                None => start,
            },
            None => {
                let (dx, dz) = (m.end.x - start.x, m.end.z - start.z);
                let length2 = dx * dx + dz * dz;
                let t = if length2 > 0.0 {
                    (((p.x - start.x) * dx + (p.z - start.z) * dz) / length2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                Xz::new(start.x + dx * t, start.z + dz * t)
            }
        }
    }

    /// Where along move `k` (0 at its start, 1 at its end; by length along an arc) its
    /// closest point to `p` lies: the walk's place on the original's path. An arc's needs
    /// the angle of `p` about its centre.
    fn param_of(&self, p: Xz, k: usize) -> f64 {
        let Some(m) = self.path.moves().get(k) else { return 0.0 };
        let start = self.path.start_of(k);
        match self.path.arc(k) {
            Some(arc) => {
                let a = geometry::angle(p, arc.centre);
                let (a0, total) = (arc.start_angle, arc.sweep);
                let ccw = m.motion == Motion::Ccw;
                let delta = if ccw {
                    (a - a0).rem_euclid(std::f64::consts::TAU)
                } else {
                    (a0 - a).rem_euclid(std::f64::consts::TAU)
                };
                if delta <= total + 1e-12 {
                    if total > 0.0 { (delta / total).min(1.0) } else { 0.0 }
                } else if p.distance(m.end) < p.distance(start) {
                    1.0
                } else {
                    0.0
                }
            }
            None => {
                let (dx, dz) = (m.end.x - start.x, m.end.z - start.z);
                let length2 = dx * dx + dz * dz;
                if length2 > 0.0 {
                    (((p.x - start.x) * dx + (p.z - start.z) * dz) / length2).clamp(0.0, 1.0)
                } else {
                    0.0
                }
            }
        }
    }

    /// Which side of move `k` the point `p` lies on, from its closest point `closest` on it:
    /// +1 to the left of the direction of travel (X up, Z to the right), −1 to the right, 0
    /// on it. Along a contour the side keeps its meaning from move to move, so a distance
    /// with its side changes sign only where the path crosses the contour.
    pub fn side(&self, k: usize, closest: Xz, p: Xz) -> f64 {
        let Some(m) = self.path.moves().get(k) else { return 0.0 };
        let start = self.path.start_of(k);
        let tangent = match self.path.arc(k) {
            Some(arc) => {
                let radial = Xz::new(closest.x - arc.centre.x, closest.z - arc.centre.z);
                // Counter-clockwise turns from +Z toward +X: the tangent is the radial turned
                // a quarter that way.
                if m.motion == Motion::Ccw { Xz::new(radial.z, -radial.x) } else { Xz::new(-radial.z, radial.x) }
            }
            None => Xz::new(m.end.x - start.x, m.end.z - start.z),
        };
        let off = Xz::new(p.x - closest.x, p.z - closest.z);
        let cross = tangent.z * off.x - tangent.x * off.z;
        if cross > 0.0 {
            1.0
        } else if cross < 0.0 {
            -1.0
        } else {
            0.0
        }
    }

    /// The moves within `back` and `ahead` mm of cutting length of the point `at` of move
    /// `index`, and the `NEIGHBOURS` cutting moves either side of its move, whatever their
    /// length, at most `WINDOW_MOVES` either side; `cursors` holds where the ends were found
    /// last, to start from.
    ///
    /// The window is what walking out from the match finds, move by move, going on while a
    /// move lies within the length or fewer than `NEIGHBOURS` cutting moves were passed:
    /// each of those conditions holds up to some move and not beyond it, so the walk stops
    /// at the nearest move where both fail (or at a bound), found here from the cutting
    /// lengths (sorted) and the neighbours.
    fn window(&self, index: usize, at: f64, back: f64, ahead: f64, cursors: &mut Cursors) -> RangeInclusive<usize> {
        let original = self;
        let moves = original.path.len();
        if moves == 0 {
            return 0..=0;
        }
        let cuts = |k: usize| original.path.moves()[k].cuts();
        // Behind: stop at the last move whose cut starts more than `back` before the match
        // and with two cutting moves between it and the match's move.
        let behind = partition_from(moves, cursors.behind, |k| original.cut_start(k) < at - back);
        cursors.behind = behind;
        let near = index.saturating_sub(WINDOW_MOVES)..index.min(moves);
        let neighbour = near.rev().filter(|&k| cuts(k)).nth(NEIGHBOURS - 1);
        let both = behind.checked_sub(1).zip(neighbour).map(|(a, b)| a.min(b));
        let first = [Some(0), index.checked_sub(WINDOW_MOVES), both].into_iter().flatten().max().unwrap_or(0);
        // Ahead: stop at the first move after which a cut starts more than `ahead` on and
        // with two cutting moves after the match's.
        let beyond = partition_from(moves, cursors.ahead, |k| original.cut_start(k) <= at + ahead);
        cursors.ahead = beyond;
        let near = index + 1..moves.min(index + WINDOW_MOVES);
        let neighbour = near.filter(|&k| cuts(k)).nth(NEIGHBOURS - 1);
        let both = (beyond < moves).then_some(beyond.saturating_sub(1)).zip(neighbour).map(|(a, b)| a.max(b));
        let last = [Some(moves - 1), Some(index + WINDOW_MOVES - 1), both].into_iter().flatten().min().unwrap_or(0);
        first.min(index)..=last.max(index.min(moves - 1))
    }

    /// The closest cutting move of `moves` to `p` and its distance (the earliest move where
    /// several are equally close), `anchor` measured first: only a move whose bounding box
    /// comes nearer than the closest so far is measured.
    fn closest_in(&self, moves: RangeInclusive<usize>, p: Xz, anchor: usize) -> Option<(f64, usize)> {
        let mut best = (f64::INFINITY, usize::MAX);
        if moves.contains(&anchor) {
            best = (self.distance(p, anchor), anchor);
        }
        for k in moves {
            let bound = best.0 + BOUND_MARGIN_MM;
            if k == anchor || self.lower_bound_squared(p, k) > bound * bound {
                continue;
            }
            let distance = self.distance(p, k);
            if distance < best.0 || (distance == best.0 && k < best.1) {
                best = (distance, k);
            }
        }
        best.0.is_finite().then_some(best)
    }
}

/// The point of the circle about `centre` of `radius` closest to `p`: its projection
/// from the centre, without an angle; none for the centre itself, which every point of the
/// circle is as near.
fn onto_circle(p: Xz, centre: Xz, radius: f64) -> Option<Xz> {
    let v = Xz::new(p.x - centre.x, p.z - centre.z);
    let length = p.distance(centre);
    (length > 0.0).then(|| Xz::new(centre.x + radius * v.x / length, centre.z + radius * v.z / length))
}

/// The neighbourhood of an anchor move (the own move of the points measured, or their
/// match): the moves of every window about a point of it (`Original::window`) whose
/// bounding box comes within `NEAR_MM` of the anchor's, nearest first.
///
/// A point `p` at distance `δ` from the anchor is within `δ` of the anchor's box, so its
/// distance from a move whose box lies `d` from the anchor's is at least `d − δ`: measured
/// in order of `d`, the moves can stop where `d − δ` passes the closest distance found
/// (the anchor's, `δ`, to begin with), and where `2δ` stays below `NEAR_MM` no move left
/// out of the neighbourhood can come as close. A point on a long pass costs the distances
/// to its own move and to the moves its corners touch, whatever the window holds.
#[derive(Debug)]
struct Near {
    anchor: Option<usize>,
    /// The moves of the windows about the anchor's points.
    span: RangeInclusive<usize>,
    /// Box distance and move, nearest first.
    moves: Vec<(f64, usize)>,
    cursors: (Cursors, Cursors),
}

impl Default for Near {
    fn default() -> Near {
        Near { anchor: None, span: 0..=0, moves: Vec::new(), cursors: Default::default() }
    }
}

/// The distance between two bounding boxes (`Original::boxes`), a lower bound of the
/// distance between any two points of their moves.
fn box_distance(a: &[f32; 4], b: &[f32; 4]) -> f64 {
    let gap = |low_a: f32, high_a: f32, low_b: f32, high_b: f32| {
        (f64::from(low_b) - f64::from(high_a)).max(f64::from(low_a) - f64::from(high_b)).max(0.0)
    };
    let (dx, dz) = (gap(a[0], a[2], b[0], b[2]), gap(a[1], a[3], b[1], b[3]));
    (dx * dx + dz * dz).sqrt()
}

/// Where a window's ends were found last, to find them again from there: the window's
/// ends move on with the walk (`partition_from`).
#[derive(Debug, Clone, Copy, Default)]
struct Cursors {
    behind: usize,
    ahead: usize,
}

/// The original's nominal path, followed through the compensated program's samples in order.
pub struct Follower<'a> {
    original: &'a Original<'a>,
    /// The previous match: its move and its cutting length along the path.
    move_index: usize,
    at: f64,
    /// The ends of the window ahead of the previous match (`measure`), and of the window
    /// about the match.
    search: Cursors,
    about: Cursors,
    /// The distances of the candidates `measure` measured, by their place in the window
    /// (NaN: not measured).
    distances: Vec<f64>,
    /// The whole path, for points the window does not match.
    whole: OnceCell<WholePath>,
    /// The neighbourhood of the last anchor.
    near: Near,
    /// The candidates `matched` measured: distance and move.
    candidates: Vec<(f64, usize)>,
}

impl<'a> Follower<'a> {
    pub fn new(original: &'a Original<'a>) -> Follower<'a> {
        Follower {
            original,
            move_index: 0,
            at: 0.0,
            search: Cursors::default(),
            about: Cursors::default(),
            distances: Vec::new(),
            whole: OnceCell::new(),
            near: Near::default(),
            candidates: Vec::new(),
        }
    }

    /// The distance of `p`, predicted for the cutting sample at `nominal`, from the
    /// original's nominal path (see the module documentation), the closest point of that
    /// path and its move.
    pub fn measure(&mut self, nominal: Xz, p: Xz) -> Option<Found> {
        let original = self.original;
        let window = self.window(0.0, WINDOW_MM, false);
        let ahead = self.move_index.max(*window.start())..=*window.end();
        let matched = self.matched(ahead.clone(), nominal);
        let Some(k) = matched else {
            // Lost: match over the whole path, measure against the whole path.
            if let Some((distance, k)) = self.whole().closest(original, nominal)
                && distance <= MATCH_MM
                && original.cuts(k).is_some()
            {
                let param = original.param_of(nominal, k);
                self.move_to(k, param);
            }
            let (distance, k) = self.whole().closest(original, p)?;
            let point = if original.cuts(k).is_some() { original.closest_point(p, k) } else { p };
            return Some(Found { distance, point, move_index: k });
        };
        let param = original.param_of(nominal, k);
        self.move_to(k, param);
        // The window about the match, and the rest of the window searched, which holds the
        // point's own move wherever the match is an earlier move that comes as close.
        let around = self.window(WINDOW_MM, WINDOW_MM, true);
        let moves = *around.start().min(ahead.start())..=*around.end().max(ahead.end());
        self.found(moves, p, k)
    }

    /// The first candidate of `ahead` within `SLACK_MM` of the closest candidate's distance
    /// to `nominal` (and within `MATCH_MM`), if any.
    fn matched(&mut self, ahead: RangeInclusive<usize>, nominal: Xz) -> Option<usize> {
        // Every candidate that may come within `SLACK_MM` of the closest, from the previous
        // match's neighbourhood.
        if let Some((best, _)) = self.nearest(&ahead, nominal, self.move_index, SLACK_MM) {
            let limit = MATCH_MM.min(best + SLACK_MM);
            return self.candidates.iter().filter(|(distance, _)| *distance <= limit).map(|&(_, k)| k).min();
        }
        let original = self.original;
        let first = *ahead.start();
        self.distances.clear();
        self.distances.resize(ahead.clone().count(), f64::NAN);
        // The closest candidate's distance, the previous match's measured first.
        let mut best = f64::INFINITY;
        let anchor = self.move_index;
        if ahead.contains(&anchor) {
            let distance = original.distance(nominal, anchor);
            self.distances[anchor - first] = distance;
            best = distance;
        }
        for k in ahead.clone() {
            let bound = best + SLACK_MM.max(BOUND_MARGIN_MM);
            if k == anchor || original.lower_bound_squared(nominal, k) > bound * bound {
                continue;
            }
            let distance = original.distance(nominal, k);
            self.distances[k - first] = distance;
            best = best.min(distance);
        }
        if !best.is_finite() {
            return None;
        }
        let limit = MATCH_MM.min(best + SLACK_MM);
        // The first within the limit, in path order: a candidate not measured above has a
        // bounding box further than the limit, or was measured.
        ahead.into_iter().find(|&k| {
            let distance = self.distances[k - first];
            distance.is_finite() && distance <= limit
        })
    }

    /// The distance of `p`, predicted for the point at `param` of the original's move `k`,
    /// from the original's nominal path, its closest point and move: the closest cutting
    /// move within `WINDOW_MM` of that point (and the `NEIGHBOURS` cutting moves either
    /// side).
    pub fn measure_from(&mut self, k: usize, param: f64, p: Xz) -> Option<Found> {
        self.move_to(k, param);
        let moves = self.window(WINDOW_MM, WINDOW_MM, true);
        self.found(moves, p, k)
    }

    /// The closest move of `moves` to `p` and its closest point; `anchor`, one of `moves`,
    /// is the own move or the match.
    fn found(&mut self, moves: RangeInclusive<usize>, p: Xz, anchor: usize) -> Option<Found> {
        let original = self.original;
        let (distance, k) = match self.nearest(&moves, p, anchor, 0.0) {
            Some(best) => best,
            None => original.closest_in(moves, p, anchor)?,
        };
        Some(Found { distance, point: original.closest_point(p, k), move_index: k })
    }

    /// The closest move to `p` of the moves of `moves` in the anchor's neighbourhood (`Near`),
    /// and the other moves of `moves` whose distance from `p` may come within `slack` of
    /// it, into `candidates`: each move's distance, the earliest of equally close moves
    /// first; `None` where the neighbourhood cannot tell (the anchor does not cut, `p` lies
    /// too far from it, or `moves` reach beyond the neighbourhood).
    fn nearest(&mut self, moves: &RangeInclusive<usize>, p: Xz, anchor: usize, slack: f64) -> Option<(f64, usize)> {
        let original = self.original;
        self.neighbourhood(anchor);
        let delta = original.distance(p, anchor);
        let reach = 2.0 * delta + slack + BOUND_MARGIN_MM;
        let span = &self.near.span;
        if reach.is_nan()
            || reach >= NEAR_MM
            || moves.start() < span.start()
            || moves.end() > span.end()
            || !moves.contains(&anchor)
        {
            return None;
        }
        self.candidates.clear();
        self.candidates.push((delta, anchor));
        let mut best = (delta, anchor);
        for &(d, m) in &self.near.moves {
            if d - delta > best.0 + slack + BOUND_MARGIN_MM {
                break;
            }
            if m == anchor || !moves.contains(&m) {
                continue;
            }
            let distance = original.distance(p, m);
            if distance.is_finite() {
                self.candidates.push((distance, m));
            }
            if distance < best.0 || (distance == best.0 && m < best.1) {
                best = (distance, m);
            }
        }
        Some(best)
    }

    /// Make `near` the neighbourhood of move `anchor`.
    fn neighbourhood(&mut self, anchor: usize) {
        if self.near.anchor == Some(anchor) {
            return;
        }
        let original = self.original;
        let start = original.cut_start(anchor);
        let (behind, ahead) = &mut self.near.cursors;
        let first = *original.window(anchor, start, WINDOW_MM, WINDOW_MM, behind).start();
        let last = *original.window(anchor, start + original.length_of(anchor), WINDOW_MM, WINDOW_MM, ahead).end();
        self.near.anchor = Some(anchor);
        self.near.span = first..=last;
        self.near.moves.clear();
        let Some(own) = original.boxes.get(anchor) else { return };
        for m in first..=last {
            let d = original.boxes.get(m).map_or(f64::INFINITY, |b| box_distance(own, b));
            if d <= NEAR_MM {
                self.near.moves.push((d, m));
            }
        }
        self.near.moves.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    }

    /// The side of the original's path `p` lies on, from what measuring it found
    /// (`Original::side`).
    pub fn side(&self, found: &Found, p: Xz) -> f64 {
        self.original.side(found.move_index, found.point, p)
    }

    /// The original's move the last point was matched to (its own point's move).
    pub fn matched_move(&self) -> usize {
        self.move_index
    }

    /// The original's path it follows.
    pub fn path(&self) -> &'a CompactPath {
        self.original.path
    }

    fn move_to(&mut self, k: usize, param: f64) {
        self.move_index = k;
        self.at = self.original.cut_start(k) + self.original.length_of(k) * param.clamp(0.0, 1.0);
    }

    /// The window about the previous match (`Original::window`); `about` names the
    /// window's cursors.
    fn window(&mut self, back: f64, ahead: f64, about: bool) -> RangeInclusive<usize> {
        let cursors = if about { &mut self.about } else { &mut self.search };
        self.original.window(self.move_index, self.at, back, ahead, cursors)
    }

    fn whole(&self) -> &WholePath {
        self.whole.get_or_init(|| WholePath::new(self.original))
    }
}

/// The number of `k` in `0..n` for which `below(k)` holds, where it holds for the first few
/// and for none after: searched outward from `hint` in doubling steps, then by halving, so
/// an answer near the last one is found in a few steps.
fn partition_from(n: usize, hint: usize, below: impl Fn(usize) -> bool) -> usize {
    let hint = hint.min(n);
    // `below(low)` holds (or `low` is none) and `below(high)` does not (or `high` is `n`).
    let (mut low, mut high): (Option<usize>, usize);
    if hint < n && below(hint) {
        let mut step = 1;
        low = Some(hint);
        loop {
            let probe = hint.saturating_add(step);
            if probe >= n {
                high = n;
                break;
            }
            if !below(probe) {
                high = probe;
                break;
            }
            low = Some(probe);
            step = step.saturating_mul(2);
        }
    } else {
        high = hint;
        let mut step = 1;
        loop {
            match hint.checked_sub(step) {
                None => {
                    low = None;
                    break;
                }
                Some(probe) if below(probe) => {
                    low = Some(probe);
                    break;
                }
                Some(probe) => {
                    high = probe;
                    step = step.saturating_mul(2);
                }
            }
        }
    }
    // The answer is in (low, high]: the first index there for which `below` fails, or `high`.
    let mut from = low.map_or(0, |l| l + 1);
    while from < high {
        let middle = from + (high - from) / 2;
        if below(middle) {
            from = middle + 1;
        } else {
            high = middle;
        }
    }
    from
}

/// The original's cutting moves in a uniform grid of cells, for closest-point queries over
/// the whole path.
struct WholePath {
    cell: f64,
    cells: HashMap<(i64, i64), Vec<u32>>,
    /// Moves too large to enter cell by cell; checked on every query.
    large: Vec<u32>,
}

/// A move covering more cells than this is kept aside.
const MAX_CELLS_PER_MOVE: i64 = 4096;

impl WholePath {
    fn new(original: &Original<'_>) -> WholePath {
        let path = original.path;
        let cell = 1.0;
        let mut whole = WholePath { cell, cells: HashMap::new(), large: Vec::new() };
        for (k, m) in path.moves().iter().enumerate() {
            if !m.cuts() {
                continue;
            }
            let (lo, hi) = bounds(path, k);
            if !(lo.is_finite() && hi.is_finite()) {
                continue;
            }
            let (x0, z0) = whole.key(lo);
            let (x1, z1) = whole.key(hi);
            if (x1 - x0 + 1).saturating_mul(z1 - z0 + 1) > MAX_CELLS_PER_MOVE {
                whole.large.push(k as u32);
                continue;
            }
            for x in x0..=x1 {
                for z in z0..=z1 {
                    whole.cells.entry((x, z)).or_default().push(k as u32);
                }
            }
        }
        whole
    }

    fn key(&self, p: Xz) -> (i64, i64) {
        ((p.x / self.cell).floor() as i64, (p.z / self.cell).floor() as i64)
    }

    /// The distance from `p` to the closest cutting move and that move's index, if any (the
    /// first such move in the program where several are equally close).
    fn closest(&self, original: &Original<'_>, p: Xz) -> Option<(f64, usize)> {
        let mut best = (f64::INFINITY, usize::MAX);
        let consider = |k: u32, best: &mut (f64, usize)| {
            let k = k as usize;
            let d = original.distance(p, k);
            if d < best.0 || (d == best.0 && k < best.1) {
                *best = (d, k);
            }
        };
        for &k in &self.large {
            consider(k, &mut best);
        }
        let (cx, cz) = self.key(p);
        // Search rings of cells outward: after ring r every unseen move is at least
        // r cells away.
        for r in 0..64i64 {
            for x in cx - r..=cx + r {
                for z in cz - r..=cz + r {
                    if (x - cx).abs() != r && (z - cz).abs() != r {
                        continue;
                    }
                    if let Some(moves) = self.cells.get(&(x, z)) {
                        for &k in moves {
                            consider(k, &mut best);
                        }
                    }
                }
            }
            if best.0 <= r as f64 * self.cell {
                return Some(best);
            }
        }
        // Far from everything: look at every move.
        for moves in self.cells.values() {
            for &k in moves {
                consider(k, &mut best);
            }
        }
        best.0.is_finite().then_some(best)
    }
}

/// The bounding box of move `k` of `path`.
fn bounds(path: &CompactPath, k: usize) -> (Xz, Xz) {
    let start = path.start_of(k);
    let end = path.moves()[k].end;
    let mut lo = Xz::new(start.x.min(end.x), start.z.min(end.z));
    let mut hi = Xz::new(start.x.max(end.x), start.z.max(end.z));
    if let Some(arc) = path.arc(k) {
        let ccw = path.moves()[k].motion == Motion::Ccw;
        for p in geometry::arc_extremes(start, end, arc.centre, ccw) {
            lo = Xz::new(lo.x.min(p.x), lo.z.min(p.z));
            hi = Xz::new(hi.x.max(p.x), hi.z.max(p.z));
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn a_step_down_is_one_unit_in_the_last_place() {
        assert_eq!(step_down(1.0), 1.0 - f32::EPSILON / 2.0);
        assert_eq!(step_down(-1.0), -1.0 - f32::EPSILON);
        assert_eq!(step_down(0.0), -f32::from_bits(1));
        assert_eq!(step_down(f32::INFINITY), f32::MAX);
        assert_eq!(step_down(f32::NEG_INFINITY), f32::NEG_INFINITY);
        assert!(step_down(f32::NAN).is_nan());
    }

    proptest! {
        /// The closest point of a circle by projection is the one its angle gives
        /// (`geometry::on_circle` at `geometry::angle`), within a few roundings of the
        /// coordinates, and lies as far from the point as the circle does.
        #[test]
        fn the_projection_onto_a_circle_is_the_point_at_its_angle(
            cx in -200.0f64..200.0, cz in -300.0f64..50.0, radius in 0.01f64..300.0,
            a in -4.0f64..4.0, off in -0.5f64..2.0,
        ) {
            let centre = Xz::new(cx, cz);
            let p = geometry::on_circle(centre, radius * (1.0 + off), a);
            prop_assume!(p.distance(centre) > 1e-6);
            let projected = onto_circle(p, centre, radius).expect("off the centre");
            let by_angle = geometry::on_circle(centre, radius, geometry::angle(p, centre));
            let scale = 1.0 + cx.abs().max(cz.abs()) + radius;
            prop_assert!(projected.distance(by_angle) <= 1e-13 * scale, "{projected:?} {by_angle:?}");
            let from_circle = (p.distance(centre) - radius).abs();
            prop_assert!((p.distance(projected) - from_circle).abs() <= 1e-13 * scale);
        }
    }

    #[test]
    fn the_centre_has_no_single_closest_point() {
        assert_eq!(onto_circle(Xz::new(1.0, 2.0), Xz::new(1.0, 2.0), 3.0), None);
    }

    /// The window ends found from the cutting lengths are where walking out move by move
    /// from the match stops.
    #[test]
    fn partition_from_any_hint_counts_the_leading_run() {
        let values = [0.0, 0.0, 1.0, 2.5, 2.5, 2.5, 7.0, 9.0];
        for threshold in [-1.0, 0.0, 0.5, 2.5, 3.0, 8.0, 20.0] {
            let expected = values.iter().filter(|&&v| v < threshold).count();
            for hint in 0..=values.len() + 2 {
                assert_eq!(
                    partition_from(values.len(), hint, |k| values[k] < threshold),
                    expected,
                    "{threshold} {hint}"
                );
            }
        }
    }

    /// A part of lines and arcs, rapids between its passes, for the window and closest-point
    /// tests.
    const PART: &str = "G21 G99\nG97 S1000 M03\nG00 X42. Z2.\nG01 X20. Z0. F0.1\nG03 X30. Z-5. R5.\nG01 Z-20.\n\
                        G02 X34. Z-22. R2.\nG00 X50. Z2.\nX30. Z0.5\nG01 X40. Z-40.\nG03 X40. Z-60. I0. K-10.\n\
                        G01 X44. Z-61. F0.08\nG02 X44. Z-70. I0. K-4.5\nG01 X48.\nZ-90.\nG00 X60. Z2.\nM30\n";

    /// The window as walking out from the match move by move finds it.
    fn window_by_walking(
        original: &Original<'_>,
        index: usize,
        at: f64,
        back: f64,
        ahead: f64,
    ) -> RangeInclusive<usize> {
        let moves = original.path.len();
        let cuts = |k: usize| original.path.moves().get(k).is_some_and(|m| m.cuts());
        let mut first = index.min(moves.saturating_sub(1));
        let mut passed = 0;
        while first > 0
            && index - first < WINDOW_MOVES
            && (at - original.cut_start(first) <= back || passed < NEIGHBOURS)
        {
            first -= 1;
            passed += usize::from(cuts(first));
        }
        let mut last = index.min(moves.saturating_sub(1));
        let mut passed = 0;
        while last + 1 < moves
            && last + 1 - index < WINDOW_MOVES
            && (original.cut_start(last + 1) - at <= ahead || passed < NEIGHBOURS)
        {
            last += 1;
            passed += usize::from(cuts(last));
        }
        first..=last
    }

    #[test]
    fn the_window_is_where_walking_out_from_the_match_stops() {
        let (lowered, _) = crate::compensation::test_support::lower_program(PART);
        let path = crate::compensation::verify::compact(lowered.valid(), &Default::default());
        let original = Original::new(&path);
        let mut follower = Follower::new(&original);
        // Every move and place along it, in path order and back again, windows of several
        // lengths (the cursors start from wherever the last window left them).
        let places: Vec<(usize, f64)> = (0..path.len()).flat_map(|k| [0.0, 0.3, 1.0].map(|param| (k, param))).collect();
        for (k, param) in places.iter().chain(places.iter().rev()) {
            follower.move_to(*k, *param);
            for (back, ahead, about) in [(0.0, WINDOW_MM, false), (WINDOW_MM, WINDOW_MM, true), (2.0, 3.0, true)] {
                let walked = window_by_walking(&original, *k, follower.at, back, ahead);
                assert_eq!(
                    follower.window(back, ahead, about),
                    walked,
                    "move {k} at {param}, {back} back, {ahead} ahead"
                );
            }
        }
    }

    /// The closest point of each cutting move, without angles, is the one the angles give (on
    /// the circle at the point's angle where it lies in the arc's sector, else the nearer end),
    /// and lies as far from the point as `distance` says.
    #[test]
    fn the_closest_point_is_the_one_the_angles_give() {
        let (lowered, _) = crate::compensation::test_support::lower_program(PART);
        let path = crate::compensation::verify::compact(lowered.valid(), &Default::default());
        let original = Original::new(&path);
        let mut arcs = 0;
        for (k, m) in path.moves().iter().enumerate().filter(|(_, m)| m.cuts()) {
            let start = path.start_of(k);
            for i in 0..200 {
                // Points about the move, near and far, inside its sector and out.
                let angle = i as f64 * 2.399_963;
                let size = [0.001, 0.05, 2.0, 15.0][i % 4];
                let middle = Xz::new((start.x + m.end.x) / 2.0, (start.z + m.end.z) / 2.0);
                let p = Xz::new(middle.x + size * angle.sin(), middle.z + size * angle.cos());
                let reference = match path.arc(k) {
                    Some(arc) => {
                        let ccw = m.motion == Motion::Ccw;
                        if geometry::angle_within(p, start, m.end, arc.centre, ccw) {
                            geometry::on_circle(arc.centre, arc.radius, geometry::angle(p, arc.centre))
                        } else if p.distance(m.end) < p.distance(start) {
                            m.end
                        } else {
                            start
                        }
                    }
                    None => {
                        let t = original.param_of(p, k);
                        Xz::new(start.x + (m.end.x - start.x) * t, start.z + (m.end.z - start.z) * t)
                    }
                };
                let closest = original.closest_point(p, k);
                assert!(closest.distance(reference) < 1e-12, "move {k}, {p:?}: {closest:?} against {reference:?}");
                assert!((p.distance(closest) - original.distance(p, k)).abs() < 1e-12);
            }
            arcs += usize::from(m.is_arc());
        }
        assert_eq!(arcs, 4);
    }
}
