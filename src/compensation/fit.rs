//! Re-expressing a compensated move as G-code segments.
//!
//! Compensation gives, for each nominal move, the points to command along it. A move is
//! written back as lines and arcs that pass within the tolerance of every one of those
//! points (and, for arcs, whose every chord stays within it too), by one of the strategies:
//!
//! * `densify` — straight `G01` moves through the points, at `--step` or as few as the
//!   chord tolerance allows (the thesis' O2012 turn);
//! * `circle` — one least-squares circle per programmed arc (`fit/circle.rs`);
//! * `semicircle` / `quadrant` — the arc split at 0° and 180° (where Z reverses:
//!   [`SEMICIRCLE_CUTS`]) or at every quarter turn, one circle each (the thesis' Table 4–5
//!   modes);
//! * `arcs` — the fewest tangent-continuous arcs within the tolerance (`fit/arcs.rs`);
//! * `auto` — per move, the cheapest of these that meets the tolerance.
//!
//! A line stays one line when its points allow it, whatever the strategy. Every strategy
//! writes segments that start at the move's start, end exactly on its last point and keep
//! every point within the tolerance ([`max_deviation`] is the measure); a strategy that
//! cannot says so in [`Fitted::rejected`] and the move falls back to `densify`. The plan
//! (`plan.rs`) then puts the segments on the machine's grid (`back/grid.rs`).

mod arcs;
pub mod circle;
mod deviation;
mod grow;
mod lm;
pub(crate) mod pinned;
mod split;

use std::f64::consts::{PI, TAU};

use smallvec::{SmallVec, smallvec};

use crate::geometry;
use crate::toolpath::Xz;

pub use arcs::{Pieces, fit as fit_arcs};
pub use deviation::{
    Between, chord_deviation, deviation_by_piece, distance_to_segment, max_deviation, segment_deviation,
};
pub use split::{QUADRANT_CUTS, SEMICIRCLE_CUTS};

/// One written segment, from the end of the previous one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Segment {
    Line { end: Xz },
    Arc { end: Xz, centre: Xz, ccw: bool },
}

/// A move's segments: most moves are written as one, or two where a backlash jump leads.
pub type Segments = SmallVec<[Segment; 2]>;

impl Segment {
    pub fn end(&self) -> Xz {
        match *self {
            Segment::Line { end } | Segment::Arc { end, .. } => end,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Strategy {
    #[default]
    Auto,
    Circle,
    Semicircle,
    Quadrant,
    Arcs,
    Densify,
}

impl Strategy {
    /// Every strategy, in the order the command line lists them.
    pub const ALL: [Strategy; 6] =
        [Strategy::Auto, Strategy::Circle, Strategy::Semicircle, Strategy::Quadrant, Strategy::Arcs, Strategy::Densify];

    /// The strategy's name, as `--strategy` and the provenance comment write it.
    pub fn name(self) -> &'static str {
        match self {
            Strategy::Auto => "auto",
            Strategy::Circle => "circle",
            Strategy::Semicircle => "semicircle",
            Strategy::Quadrant => "quadrant",
            Strategy::Arcs => "arcs",
            Strategy::Densify => "densify",
        }
    }

    /// The strategy named `name` (any case).
    pub fn from_name(name: &str) -> Option<Strategy> {
        Strategy::ALL.into_iter().find(|s| s.name().eq_ignore_ascii_case(name))
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitOptions {
    pub strategy: Strategy,
    /// Every commanded point must lie this close to the written path, mm.
    pub tolerance_mm: f64,
    /// For `densify`: the length of each `G01`, mm; `None` lets the chord tolerance decide.
    pub step_mm: Option<f64>,
}

/// What the move was before compensation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NominalShape {
    Line,
    /// The programmed arc: its centre, sense and radius (the contour's, as programmed; the
    /// compensated points lie off it by their corrections).
    Arc {
        centre: Xz,
        ccw: bool,
        radius: f64,
    },
}

/// One compensated move: where it starts (the end of the previous written move) and the
/// points to command along it, the last of which is its end.
#[derive(Debug, Clone, Copy)]
pub struct MovePoints<'a> {
    pub start: Xz,
    pub points: &'a [Xz],
    pub nominal: NominalShape,
}

/// Distance from `p` to the segment `a`–`b`.
pub fn distance_to_chord(p: Xz, a: Xz, b: Xz) -> f64 {
    let (dx, dz) = (b.x - a.x, b.z - a.z);
    let length2 = dx * dx + dz * dz;
    if length2 <= 0.0 {
        return p.distance(a);
    }
    let t = (((p.x - a.x) * dx + (p.z - a.z) * dz) / length2).clamp(0.0, 1.0);
    p.distance(Xz::new(a.x + dx * t, a.z + dz * t))
}

/// `densify`: straight moves through the points. With a step, one line per step of path
/// length (ending on sample points), cut finer wherever a step would leave a skipped point
/// outside the tolerance; without, as few lines as keep every skipped point within the
/// tolerance of its chord (greedy from the start, `grow.rs`). Along a nominal arc the path
/// between two points is the arc's bulge, not their chord ([`path_between`]), and the lines
/// are held to it.
pub fn densify(m: &MovePoints<'_>, tolerance_mm: f64, step_mm: Option<f64>) -> Vec<Segment> {
    let points = m.points;
    let mut out = Vec::new();
    match step_mm.filter(|s| s.is_finite() && *s > 0.0) {
        Some(step) => {
            let mut travelled = 0.0;
            let mut previous = m.start;
            let mut from = m.start;
            let mut first = 0;
            for (i, &p) in points.iter().enumerate() {
                travelled += previous.distance(p);
                previous = p;
                if travelled >= step - 1e-9 || i + 1 == points.len() {
                    let chunk = points.get(first..=i).unwrap_or_default();
                    chord_lines(from, &path_between(m.nominal, from, chunk, tolerance_mm), tolerance_mm, &mut out);
                    from = p;
                    first = i + 1;
                    travelled = 0.0;
                }
            }
        }
        None => chord_lines(m.start, &path_between(m.nominal, m.start, points, tolerance_mm), tolerance_mm, &mut out),
    }
    out
}

/// The points of the path from `from` through `points` that lines are held to: the points
/// themselves where the path between them is straight (a nominal line), and along a
/// nominal arc, between each two, points of the arc's bulge close enough together that a
/// line between neighbours strays from it by at most a quarter of `tolerance`.
///
/// A line between two samples of an arc of radius R a chord c apart cuts inside the arc by
/// c²/8R: 5 µm for the 0.254 mm sampling step on a 1.6 mm fillet, ten times a half-micron
/// tolerance, and no sample lies between them to show it. The path between two samples is
/// taken as the `chord_deviation` bulge takes it: the arc of the programmed radius through
/// both, bulging the way the programmed arc does (exact where the correction moves the arc
/// without turning it between the samples, which the sampling sees to). Where no such arc
/// reaches across the chord, the arc about the programmed centre, its radius moving from
/// one point's to the other's.
pub fn path_between(nominal: NominalShape, from: Xz, points: &[Xz], tolerance: f64) -> Vec<Xz> {
    let NominalShape::Arc { centre: programmed, radius, .. } = nominal else { return points.to_vec() };
    let mut out = Vec::with_capacity(points.len());
    let mut a = from;
    for &b in points {
        let centre = through_both(a, b, radius, programmed).unwrap_or(programmed);
        let (ra, rb) = (a.distance(centre), b.distance(centre));
        let chord = a.distance(b);
        // Pieces of length √(2·R·tolerance) stray by a quarter of the tolerance.
        let longest = (2.0 * ra.min(rb) * tolerance).sqrt();
        let pieces = if longest > 0.0 && chord < 2.0 * ra.min(rb) {
            (chord / longest).ceil().clamp(1.0, MAX_PIECES_BETWEEN_POINTS) as usize
        } else {
            1
        };
        if pieces > 1 {
            let angle_a = geometry::angle(a, centre);
            // Consecutive points are less than half a turn apart about the centre: the
            // shorter way round is the way the path goes.
            let turn = (geometry::angle(b, centre) - angle_a + PI).rem_euclid(TAU) - PI;
            for i in 1..pieces {
                let f = i as f64 / pieces as f64;
                out.push(geometry::on_circle(centre, ra + (rb - ra) * f, angle_a + turn * f));
            }
        }
        out.push(b);
        a = b;
    }
    out
}

/// The centre of the circle of `radius` through `a` and `b` on the side of `programmed` (the
/// programmed centre): the short way round, as consecutive samples are.
fn through_both(a: Xz, b: Xz, radius: f64, programmed: Xz) -> Option<Xz> {
    let middle = Xz::new((a.x + b.x) / 2.0, (a.z + b.z) / 2.0);
    let half = a.distance(b) / 2.0;
    let height = (radius * radius - half * half).sqrt();
    if !(height.is_finite() && half > 0.0) {
        return None;
    }
    // The chord's normal, turned toward the programmed centre.
    let mut normal = Xz::new(-(b.z - a.z) / (2.0 * half), (b.x - a.x) / (2.0 * half));
    if normal.x * (programmed.x - middle.x) + normal.z * (programmed.z - middle.z) < 0.0 {
        normal = Xz::new(-normal.x, -normal.z);
    }
    Some(Xz::new(middle.x + normal.x * height, middle.z + normal.z * height))
}

/// At most this many pieces between two points (a tolerance near zero would ask for
/// unboundedly many).
const MAX_PIECES_BETWEEN_POINTS: f64 = 64.0;

/// The fewest lines from `from` through `points`, ending on the last, that each keep the
/// points they skip within `tolerance` of their chord.
fn chord_lines(mut from: Xz, points: &[Xz], tolerance: f64, out: &mut Vec<Segment>) {
    let mut first = 0;
    while first < points.len() {
        // A line to the next point skips nothing and always passes.
        let last = grow::longest(first, points.len(), |last| {
            let end = points.get(last)?;
            let skipped = points.get(first..last)?;
            skipped.iter().all(|&p| distance_to_chord(p, from, *end) <= tolerance).then_some(())
        })
        .map_or(first, |(last, ())| last);
        let Some(&end) = points.get(last) else { return };
        out.push(Segment::Line { end });
        from = end;
        first = last + 1;
    }
}

/// The strategy that was asked for and could not meet the tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rejected {
    pub strategy: Strategy,
    /// How close its best attempt came, mm (infinite: no circle of the programmed sense
    /// could be fitted at all).
    pub deviation_mm: f64,
}

/// A move re-expressed.
#[derive(Debug, Clone, PartialEq)]
pub struct Fitted {
    pub segments: Segments,
    /// What wrote them: never `Auto`; a nominal line kept as one line is `Densify`'s one
    /// `G01`, and a strategy that failed is `Densify` with `rejected` set.
    pub strategy_used: Strategy,
    /// The largest distance of a compensated point from the written segments, mm.
    pub max_deviation_mm: f64,
    /// Set when the strategy asked for failed and the move fell back to `densify`.
    pub rejected: Option<Rejected>,
}

/// The segments that write the move `m` (see [`fit_move`]).
pub fn reexpress(m: &MovePoints<'_>, options: &FitOptions) -> Segments {
    fit_move(m, options).segments
}

/// Re-express the move `m` by `options.strategy`:
///
/// * a nominal line stays one line when every point is within the tolerance of the chord
///   from the start to the last point; else it is densified, or, under `arcs` and `auto`,
///   fitted with arcs when that takes fewer segments;
/// * `circle`, `semicircle`, `quadrant` fit one circle per piece of a programmed arc
///   (`split.rs`), falling back to `densify` when they cannot meet the tolerance;
/// * `arcs` fits adaptive arcs (`arcs.rs`), `densify` writes lines;
/// * `auto` takes, per move, whichever of the nominal shape (one circle), `semicircle`,
///   `quadrant`, `arcs` and `densify` meets the tolerance in the fewest segments, the
///   earlier in that order on a tie.
pub fn fit_move(m: &MovePoints<'_>, options: &FitOptions) -> Fitted {
    let tolerance =
        if options.tolerance_mm >= 0.0 && options.tolerance_mm.is_finite() { options.tolerance_mm } else { 0.0 };
    let Some(&last) = m.points.last() else {
        return Fitted {
            segments: Segments::new(),
            strategy_used: Strategy::Densify,
            max_deviation_mm: 0.0,
            rejected: None,
        };
    };
    let fitting = Fitting { m, tolerance, step: options.step_mm };
    match m.nominal {
        NominalShape::Line => {
            let line = Segment::Line { end: last };
            let deviation = segment_deviation(m.start, &line, m.points);
            if deviation <= tolerance {
                return Fitted {
                    segments: smallvec![line],
                    strategy_used: Strategy::Densify,
                    max_deviation_mm: deviation,
                    rejected: None,
                };
            }
            match options.strategy {
                Strategy::Arcs | Strategy::Auto => fitting.arcs_or_densify(),
                Strategy::Circle | Strategy::Semicircle | Strategy::Quadrant | Strategy::Densify => fitting.densify(),
            }
        }
        NominalShape::Arc { centre, ccw, .. } => {
            let cuts: &[f64] = match options.strategy {
                Strategy::Semicircle => &SEMICIRCLE_CUTS,
                Strategy::Quadrant => &QUADRANT_CUTS,
                _ => &[],
            };
            match options.strategy {
                Strategy::Circle | Strategy::Semicircle | Strategy::Quadrant => {
                    fitting.circles(centre, ccw, cuts, options.strategy).unwrap_or_else(|deviation_mm| Fitted {
                        rejected: Some(Rejected { strategy: options.strategy, deviation_mm }),
                        ..fitting.densify()
                    })
                }
                Strategy::Arcs => fitting.arcs(),
                Strategy::Densify => fitting.densify(),
                Strategy::Auto => fitting.cheapest_for_arc(centre, ccw),
            }
        }
    }
}

struct Fitting<'a, 'p> {
    m: &'a MovePoints<'p>,
    tolerance: f64,
    step: Option<f64>,
}

impl Fitting<'_, '_> {
    fn densify(&self) -> Fitted {
        let segments = Segments::from_vec(densify(self.m, self.tolerance, self.step));
        let path = path_between(self.m.nominal, self.m.start, self.m.points, self.tolerance);
        let max_deviation_mm = deviation_by_piece(self.m.start, &segments, &path);
        Fitted { segments, strategy_used: Strategy::Densify, max_deviation_mm, rejected: None }
    }

    fn arcs(&self) -> Fitted {
        let pieces = arcs::fit(self.m, self.tolerance);
        Fitted {
            segments: Segments::from_vec(pieces.segments),
            strategy_used: Strategy::Arcs,
            max_deviation_mm: pieces.max_deviation_mm,
            rejected: None,
        }
    }

    /// Arcs, unless densify takes fewer segments.
    fn arcs_or_densify(&self) -> Fitted {
        let arcs = self.arcs();
        let lines = self.densify();
        if lines.segments.len() < arcs.segments.len() && lines.max_deviation_mm <= self.tolerance {
            lines
        } else {
            arcs
        }
    }

    fn circles(&self, centre: Xz, ccw: bool, cuts: &[f64], strategy: Strategy) -> Result<Fitted, f64> {
        self.circles_at(centre, ccw, &split::cut_indices(self.m, centre, ccw, cuts), strategy)
    }

    /// `circles` with the pieces' last points given (`split::cut_indices`).
    fn circles_at(&self, centre: Xz, ccw: bool, ends: &[usize], strategy: Strategy) -> Result<Fitted, f64> {
        let split::Circles { segments, deviation } = split::circles_at(self.m, centre, ccw, ends, self.tolerance)?;
        let max_deviation_mm = deviation.unwrap_or_else(|| max_deviation(self.m.start, &segments, self.m.points));
        if max_deviation_mm <= self.tolerance {
            Ok(Fitted { segments, strategy_used: strategy, max_deviation_mm, rejected: None })
        } else {
            Err(max_deviation_mm)
        }
    }

    fn cheapest_for_arc(&self, centre: Xz, ccw: bool) -> Fitted {
        let mut best: Option<Fitted> = None;
        let mut tried: SmallVec<[split::Ends; 3]> = SmallVec::new();
        // The angles travelled, for the splits; one circle needs none.
        let travel = std::cell::OnceCell::new();
        let travel = || travel.get_or_init(|| split::Travel::new(self.m, centre, ccw));
        for (cuts, strategy) in [
            (&[][..], Strategy::Circle),
            (&SEMICIRCLE_CUTS[..], Strategy::Semicircle),
            (&QUADRANT_CUTS[..], Strategy::Quadrant),
        ] {
            // A split that cuts nowhere new is a fit already tried.
            let pieces = if cuts.is_empty() { split::one_piece(self.m) } else { travel().cut_indices(cuts) };
            if tried.contains(&pieces) {
                continue;
            }
            if let Ok(fitted) = self.circles_at(centre, ccw, &pieces, strategy) {
                // Nothing takes fewer than one segment, and a tie keeps the earlier fit (every
                // fit `circles_at` gives meets the tolerance).
                if fitted.segments.len() == 1 {
                    return fitted;
                }
                self.keep_cheaper(&mut best, fitted);
            }
            tried.push(pieces);
        }
        self.keep_cheaper(&mut best, self.arcs());
        self.keep_cheaper(&mut best, self.densify());
        // Arcs always meet the tolerance (a line to the next point always passes); this is
        // the guard for points that are not numbers.
        best.unwrap_or_else(|| self.densify())
    }

    fn keep_cheaper(&self, best: &mut Option<Fitted>, candidate: Fitted) {
        let passes = candidate.max_deviation_mm <= self.tolerance;
        if passes && best.as_ref().is_none_or(|b| candidate.segments.len() < b.segments.len()) {
            *best = Some(candidate);
        }
    }
}

#[cfg(test)]
mod tests;
