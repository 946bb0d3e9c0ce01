//! How far points lie from a written path, and ArcWelder's chord test.
//!
//! [`max_deviation`] is the one measure every strategy is held to: the distance from each
//! compensated point to the nearest point of the written lines and arcs. An arc whose two
//! end radii differ (after rounding to the grid) is taken as the control runs it, a spiral
//! whose radius changes in proportion to the angle swept.
//!
//! Points alone do not pin an arc down between them, so an arc is also held to the path
//! between consecutive points ([`chord_deviation`], ArcWelder's rule): where the points come
//! from a polyline, the largest gap between the arc and each chord, at the foot of the
//! perpendicular from the centre; where they were sampled along a nominal arc, the path
//! between two samples is that arc's bulge, not the chord, so the arc is held to the chord's
//! midpoint pushed out by the nominal sagitta. (Held to the bare chord, a 2 mm fillet
//! sampled every 0.254 mm would fail by its own 4 µm sag, and no arc could ever be written
//! for it.)

use std::cell::OnceCell;

use smallvec::SmallVec;

use super::{Segment, distance_to_chord};
use crate::geometry::{self, SweepSides};
use crate::toolpath::Xz;

/// The distance from `p` to `segment`, drawn from `from`.
pub fn distance_to_segment(p: Xz, from: Xz, segment: &Segment) -> f64 {
    match *segment {
        Segment::Line { end } => distance_to_chord(p, from, end),
        Segment::Arc { end, centre, ccw } => ArcGauge::new(from, end, centre, ccw).distance(p),
    }
}

/// The largest distance from `points` to the one segment `segment` drawn from `from`.
pub fn segment_deviation(from: Xz, segment: &Segment, points: &[Xz]) -> f64 {
    let worst = match *segment {
        Segment::Line { end } => points.iter().map(|&p| distance_to_chord(p, from, end)).fold(0.0, f64::max),
        Segment::Arc { end, centre, ccw } => ArcGauge::new(from, end, centre, ccw).largest_distance(points),
    };
    if points.iter().all(|p| p.is_finite()) && !worst.is_nan() { worst } else { f64::INFINITY }
}

/// `distance_to_segment` for one segment, its constants computed once.
enum Gauge {
    Line { from: Xz, end: Xz },
    Arc(ArcGauge),
}

impl Gauge {
    fn new(from: Xz, segment: &Segment) -> Gauge {
        match *segment {
            Segment::Line { end } => Gauge::Line { from, end },
            Segment::Arc { end, centre, ccw } => Gauge::Arc(ArcGauge::new(from, end, centre, ccw)),
        }
    }

    fn distance(&self, p: Xz) -> f64 {
        match self {
            Gauge::Line { from, end } => distance_to_chord(p, *from, *end),
            Gauge::Arc(gauge) => gauge.distance(p),
        }
    }
}

/// An arc's constants, computed once for the many points measured against it.
struct ArcGauge {
    from: Xz,
    end: Xz,
    centre: Xz,
    ccw: bool,
    r0: f64,
    r1: f64,
    sides: SweepSides,
    /// The end radii are so close that the radius between them rounds to `r0` wherever it
    /// is taken (`r0 + (r1 − r0)·t` for t in [0, 1] lies between `r0` and `r0 + (r1 − r0)`,
    /// both rounded, and those are equal): a point inside the sweep then needs no angle.
    one_radius: bool,
    /// The start's angle and the sweep, measured where a point first needs them.
    angles: OnceCell<(f64, f64)>,
}

impl ArcGauge {
    fn new(from: Xz, end: Xz, centre: Xz, ccw: bool) -> ArcGauge {
        let (r0, r1) = (from.distance(centre), end.distance(centre));
        ArcGauge {
            from,
            end,
            centre,
            ccw,
            r0,
            r1,
            sides: SweepSides::new(from, end, centre, ccw),
            one_radius: r0 + (r1 - r0) == r0,
            angles: OnceCell::new(),
        }
    }

    /// The start's angle and the sweep (`geometry::sweep`).
    fn angles(&self) -> (f64, f64) {
        *self.angles.get_or_init(|| geometry::turn(self.from, self.end, self.centre, self.ccw))
    }

    fn distance(&self, p: Xz) -> f64 {
        let to_ends = p.distance(self.from).min(p.distance(self.end));
        // At an end (the last point is one), every way of measuring gives that nought.
        if to_ends == 0.0 || self.r0 <= 0.0 || self.r1 <= 0.0 {
            return to_ends;
        }
        match self.sides.inside(p) {
            Some(false) => return to_ends,
            Some(true) if self.one_radius => return (p.distance(self.centre) - self.r0).abs().min(to_ends),
            _ => {}
        }
        let (a0, total) = self.angles();
        let a = geometry::angle(p, self.centre);
        let swept = if self.ccw { geometry::rem_turn(a - a0) } else { geometry::rem_turn(a0 - a) };
        if swept > total {
            return to_ends;
        }
        let radius = self.r0 + (self.r1 - self.r0) * (swept / total);
        (p.distance(self.centre) - radius).abs().min(to_ends)
    }

    /// Bounds on `distance(p)` that need no angle: the distance itself where the point's side
    /// of the ends (`SweepSides`) tells it and the radius needs no interpolating, else the
    /// distances with the radius of either end, between which the interpolated radius lies
    /// (`r0 + (r1 − r0)·t` only grows or only shrinks with t, rounding included, and so does
    /// the distance on either side of it); where the side is not clear, the distance.
    fn bounds(&self, p: Xz) -> (f64, f64) {
        let to_ends = p.distance(self.from).min(p.distance(self.end));
        if to_ends == 0.0 || self.r0 <= 0.0 || self.r1 <= 0.0 {
            return (to_ends, to_ends);
        }
        match self.sides.inside(p) {
            Some(false) => (to_ends, to_ends),
            Some(true) => {
                let d = p.distance(self.centre);
                let (a, b) = (d - self.r0, d - (self.r0 + (self.r1 - self.r0)));
                let high = a.abs().max(b.abs());
                let low = if (a >= 0.0) == (b >= 0.0) { a.abs().min(b.abs()) } else { 0.0 };
                (low.min(to_ends), high.min(to_ends))
            }
            None => {
                let d = self.distance(p);
                (d, d)
            }
        }
    }

    /// The largest `distance` of `points`, as `fold(0, max)` of them gives it: from bounds
    /// first, measuring the angle only of the points whose upper bound reaches the largest
    /// lower bound, among which the largest distance must be.
    fn largest_distance(&self, points: &[Xz]) -> f64 {
        let bounds: SmallVec<[(f64, f64); 16]> = points.iter().map(|&p| self.bounds(p)).collect();
        let floor = bounds.iter().fold(0.0, |floor, &(low, _)| f64::max(floor, low));
        let candidates = points.iter().zip(&bounds).filter(|&(_, &(_, high))| high >= floor);
        candidates.map(|(&p, &(low, high))| if low == high { low } else { self.distance(p) }).fold(0.0, f64::max)
    }
}

/// The box around a segment (its ends and, for an arc, its extreme points), to skip the
/// segments that cannot be nearer than the best found.
#[derive(Clone, Copy)]
struct Bounds {
    low: Xz,
    high: Xz,
}

impl Bounds {
    fn of(from: Xz, segment: &Segment) -> Bounds {
        let mut b = Bounds { low: from, high: from };
        b.include(segment.end());
        if let Segment::Arc { end, centre, ccw } = *segment {
            // A spiral bulges at most by the difference of its radii beyond the circle.
            let slack = (from.distance(centre) - end.distance(centre)).abs();
            for p in geometry::arc_extremes(from, end, centre, ccw) {
                b.include(Xz::new(p.x + slack, p.z + slack));
                b.include(Xz::new(p.x - slack, p.z - slack));
            }
        }
        b
    }

    fn include(&mut self, p: Xz) {
        self.low = Xz::new(self.low.x.min(p.x), self.low.z.min(p.z));
        self.high = Xz::new(self.high.x.max(p.x), self.high.z.max(p.z));
    }

    fn distance(&self, p: Xz) -> f64 {
        let dx = (self.low.x - p.x).max(p.x - self.high.x).max(0.0);
        let dz = (self.low.z - p.z).max(p.z - self.high.z).max(0.0);
        (dx * dx + dz * dz).sqrt()
    }
}

/// The largest distance from any of `points` to the path that starts at `start` and runs
/// through `segments`: 0 without points, infinite with points and no segments, NaN-free
/// (a non-finite point counts as infinitely far).
pub fn max_deviation(start: Xz, segments: &[Segment], points: &[Xz]) -> f64 {
    if points.is_empty() {
        return 0.0;
    }
    if segments.is_empty() {
        return f64::INFINITY;
    }
    // Each segment's gauge (`distance_to_segment` with its constants computed once) and box.
    // On the stack for the few segments most moves are written in.
    let mut gauges: SmallVec<[Gauge; 4]> = SmallVec::with_capacity(segments.len());
    let mut bounds: SmallVec<[Bounds; 4]> = SmallVec::with_capacity(segments.len());
    let mut from = start;
    for segment in segments {
        gauges.push(Gauge::new(from, segment));
        bounds.push(Bounds::of(from, segment));
        from = segment.end();
    }
    // Points follow the path, so the segment nearest the last point is the first guess for
    // the next; the boxes then rule out most of the others.
    let mut guess = 0;
    let mut worst: f64 = 0.0;
    for &p in points {
        if !p.is_finite() {
            return f64::INFINITY;
        }
        let mut best = gauges.get(guess).map_or(f64::INFINITY, |g| g.distance(p));
        for (index, (gauge, bound)) in gauges.iter().zip(&bounds).enumerate() {
            if index == guess || bound.distance(p) >= best {
                continue;
            }
            let d = gauge.distance(p);
            if d < best {
                best = d;
                guess = index;
            }
        }
        worst = worst.max(best);
    }
    if worst.is_nan() { f64::INFINITY } else { worst }
}

/// [`max_deviation`] for segments that each end on one of `points`, in order (what
/// `densify` writes): each point measured against the segment that ends on it or after
/// it, in one pass. That bounds the distance to the whole path from above. Segments that
/// do not end on the points in order are measured by [`max_deviation`].
pub fn deviation_by_piece(start: Xz, segments: &[Segment], points: &[Xz]) -> f64 {
    let mut worst: f64 = 0.0;
    let mut from = start;
    let mut rest = points;
    for segment in segments {
        let end = segment.end();
        let Some(count) = rest.iter().position(|&p| p == end).map(|i| i + 1) else {
            return max_deviation(start, segments, points);
        };
        let (covered, after) = rest.split_at(count);
        worst = worst.max(segment_deviation(from, segment, covered));
        from = end;
        rest = after;
    }
    if rest.is_empty() { worst } else { max_deviation(start, segments, points) }
}

/// Where the points an arc is held to came from, for the chord test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Between {
    /// The path between consecutive points is the straight chord (a `G01` polyline, or
    /// samples of a nominal line).
    Chords,
    /// The points were sampled along a nominal arc of this centre and radius.
    Bulge { centre: Xz, radius: f64 },
}

/// The middle of the path between `a` and `b` sampled along a nominal arc (`centre`,
/// `radius`): their chord's midpoint pushed out by the nominal sagitta.
fn bulge_middle(a: Xz, b: Xz, centre: Xz, radius: f64) -> Xz {
    let middle = Xz::new((a.x + b.x) / 2.0, (a.z + b.z) / 2.0);
    let half = a.distance(b) / 2.0;
    let sagitta = if half < radius { radius - (radius * radius - half * half).sqrt() } else { 0.0 };
    let outward = geometry::direction(centre, middle);
    Xz::new(middle.x + outward.x * sagitta, middle.z + outward.z * sagitta)
}

/// The middles of the path between consecutive points of `from`, `points…` sampled along a
/// nominal arc (`centre`, `radius`), for holding a line to that path.
pub fn bulge_middles(from: Xz, points: &[Xz], centre: Xz, radius: f64) -> Vec<Xz> {
    let mut a = from;
    points
        .iter()
        .map(|&b| {
            let middle = bulge_middle(a, b, centre, radius);
            a = b;
            middle
        })
        .collect()
}

/// How far a line from `from` over `points` strays from the path between them where that
/// path is a nominal arc's bulge (`bulge_middles`); zero along a nominal line, where the
/// path between points is their chord.
pub fn line_bulge_deviation(from: Xz, line: &Segment, points: &[Xz], between: Between) -> f64 {
    let Between::Bulge { centre, radius } = between else { return 0.0 };
    segment_deviation(from, line, &bulge_middles(from, points, centre, radius))
}

/// The largest gap between the circle (`centre`, `radius`) and the path between
/// consecutive points of `from`, `points…` (see the module comment).
pub fn chord_deviation(from: Xz, points: &[Xz], centre: Xz, radius: f64, between: Between) -> f64 {
    let mut worst: f64 = 0.0;
    let mut a = from;
    for &b in points {
        let gap = match between {
            Between::Chords => {
                let (dx, dz) = (b.x - a.x, b.z - a.z);
                let length2 = dx * dx + dz * dz;
                let t = if length2 > 0.0 { ((centre.x - a.x) * dx + (centre.z - a.z) * dz) / length2 } else { 0.0 };
                if t > 0.0 && t < 1.0 {
                    (radius - Xz::new(a.x + dx * t, a.z + dz * t).distance(centre)).abs()
                } else {
                    0.0
                }
            }
            Between::Bulge { centre: nominal, radius: nominal_radius } => {
                (bulge_middle(a, b, nominal, nominal_radius).distance(centre) - radius).abs()
            }
        };
        worst = worst.max(gap);
        a = b;
    }
    if worst.is_nan() { f64::INFINITY } else { worst }
}
