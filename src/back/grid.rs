//! The least-increment grid a program's coordinates live on, and the words of an arc on it.
//!
//! A control accepts coordinates in whole least increments of its program units: 0.001 mm
//! or 0.0001 in, of the diameter on a diameter-programmed lathe (so the radius grid is half
//! the increment). This is where a length of the IR (mm, X as a radius) goes back to the
//! program's frame, the inverse of `semantic/frame.rs`: every coordinate the back end writes,
//! for `expand` and for compensation alike, is counted here. A point is rounded on the grid
//! from its exact value, never from a rounded neighbour, so rounding errors do not add up
//! along a path; incremental words are differences of rounded absolutes for the same reason.
//!
//! Values are kept as integer counts of the increment (`i64` mantissas with the
//! increment's decimal places), so comparisons and differences are exact.

use std::f64::consts::PI;

use crate::dialect::AddressKind;
use crate::geometry::{self, SweepSides};
use crate::semantic::{CoordinateMark, Frame};
use crate::syntax::Number;
use crate::toolpath::Xz;

/// The grid of one stretch of program (a frame and a `G50` shift).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    pub frame: Frame,
    /// Toolpath frame minus program coordinates, mm.
    pub shift: Xz,
    /// Decimal places of the increment in program units.
    pub places: u8,
}

/// A point as the program writes it: `X` (diameter or radius, as programmed) and `Z`, in
/// increments.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct GridPoint {
    pub x: i64,
    pub z: i64,
}

impl Grid {
    /// The grid of the coordinates in force from `mark` on.
    pub fn new(mark: &CoordinateMark) -> Grid {
        Grid::of(mark.frame, mark.shift)
    }

    /// The grid of `frame`'s increment, with the program's coordinates shifted by `shift`
    /// (`G50 X Z`).
    pub fn of(frame: Frame, shift: Xz) -> Grid {
        Grid { frame, shift, places: places(frame.increment) }
    }

    fn scale(&self) -> f64 {
        // Exact in f64 for the at most nine places an increment has.
        10f64.powi(i32::from(self.places))
    }

    /// A value in program units to a count of increments.
    pub fn count(&self, value: f64) -> i64 {
        nearest_whole(value * self.scale())
    }

    /// The count of a literal word's value (`Frame::literal`; `kind`, the word's address kind,
    /// is asked for only where it decides). A literal written with a point and the grid's
    /// decimal places is its own count: the value's two roundings through f64 (the mantissa
    /// over a power of ten, and back) stray by less than a quarter of an increment below
    /// `EXACT_LITERAL_COUNTS`, so the nearest whole count is the mantissa (proptested in
    /// `tests`). Nearly every coordinate word of a long program is such a literal.
    pub fn literal_count(&self, number: Number, kind: impl FnOnce() -> Option<AddressKind>) -> i64 {
        const EXACT_LITERAL_COUNTS: u64 = 1 << 50;
        if number.has_point() && number.scale == self.places && number.mantissa.unsigned_abs() < EXACT_LITERAL_COUNTS {
            number.mantissa
        } else {
            self.count(self.frame.literal(number, kind(), false))
        }
    }

    /// A count of increments as a number to write.
    pub fn number(&self, count: i64) -> Number {
        Number::new(count, self.places, true)
    }

    /// A point of the toolpath frame (mm, X radius), rounded onto the grid.
    pub fn point(&self, p: Xz) -> GridPoint {
        GridPoint {
            x: self.count(self.frame.x_program(p.x - self.shift.x)),
            z: self.count(self.frame.program(p.z - self.shift.z)),
        }
    }

    /// A grid point back in the toolpath frame.
    pub fn to_mm(self, g: GridPoint) -> Xz {
        let scale = self.scale();
        Xz::new(self.frame.x_mm(g.x as f64 / scale) + self.shift.x, self.frame.mm(g.z as f64 / scale) + self.shift.z)
    }

    /// `p` rounded onto the grid, in the toolpath frame.
    pub fn round(&self, p: Xz) -> Xz {
        self.to_mm(self.point(p))
    }

    /// A length (a radius, an `I`/`K` offset; never a diameter) in mm as a count.
    pub fn length(&self, mm: f64) -> i64 {
        self.count(self.frame.program(mm))
    }

    /// A count of a length back in mm.
    pub fn length_mm(&self, count: i64) -> f64 {
        self.frame.mm(count as f64 / self.scale())
    }

    /// The increment in mm (of X as programmed: the diameter on a diameter machine).
    pub fn increment_mm(&self) -> f64 {
        self.frame.mm(self.frame.increment)
    }
}

/// The decimal places of an increment in program units (`machine::increment_places`), told
/// at once for the increments controls use: every move asks for its grid, and the count
/// takes a loop of library roundings, which shows in `compensate`'s instruction count.
fn places(increment: f64) -> u8 {
    match increment {
        0.001 => 3,
        0.0001 => 4,
        0.01 => 2,
        _ => crate::machine::increment_places(increment),
    }
}

/// `x.round() as i64` (the nearest whole number, halves away from zero), without the library
/// call `round` is on this target: every grid point takes two, and the call also keeps the
/// measures that count on the grid from being inlined. Below 2⁵² in size, the truncation
/// toward zero and the fraction it leaves are both exact in f64, and the fraction decides;
/// from 2⁵² on every f64 is whole already, and those, the infinities and NaN take `round`
/// itself. The fraction is added as two flags rather than chosen by branches: its side is as
/// good as random from point to point.
fn nearest_whole(x: f64) -> i64 {
    const WHOLE_FROM: f64 = 4_503_599_627_370_496.0;
    if x.abs() < WHOLE_FROM {
        let whole = x as i64;
        let fraction = x - whole as f64;
        whole + i64::from(fraction >= 0.5) - i64::from(fraction <= -0.5)
    } else {
        x.round() as i64
    }
}

/// How an arc is written on the grid (see [`Grid::arc_words`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArcWords {
    /// `R` (OSP `L`): the signed radius in increments, negative beyond half a turn.
    Radius(i64),
    /// `I K`: the centre's offset from the rounded start, in increments.
    Centre { i: i64, k: i64 },
    /// No arc the control would run stays near it (its rounded ends coincide and it sweeps
    /// no more than half a turn): the move is a straight one to its rounded end.
    Line,
}

impl Grid {
    /// The words of the arc from `from` to `end` about `centre` (exact points, toolpath
    /// frame), in the form `prefer_radius` asks for when that form holds the arc.
    ///
    /// A control finds an `R` arc's centre from the rounded ends and the rounded radius, on
    /// the chord's perpendicular bisector at the height √(R² − (c/2)²) over the chord. Near
    /// half a turn that height is small and changes fast with the chord and the radius: a
    /// half-increment rounding of either moves the centre by many increments, and past half
    /// a turn the radius may no longer reach across the rounded chord at all (metrology.md
    /// §5.3: prefer the centre form there). An `I K` arc's centre is rounded by at most half
    /// an increment per axis, whatever the sweep. So the radius form is kept where the arc
    /// the control would run from it stays within half an increment of the exact arc, or
    /// no further than the centre form's, and where the rounded radius exceeds half the
    /// rounded chord by at least an increment; else the arc is written by its centre. (At
    /// exactly half a turn the radius is half the chord: whether a control then runs the
    /// half circle or stops with "radius too small" turns on its own arithmetic.) A full
    /// circle has only the centre form.
    pub fn arc_words(&self, from: Xz, end: Xz, centre: Xz, ccw: bool, prefer_radius: bool) -> ArcWords {
        self.arc_words_straying(from, end, centre, ccw, prefer_radius, f64::INFINITY).0
    }

    /// [`Grid::arc_words`], and whether the arc the control runs for them strays from the
    /// exact arc by more than `limit` (as [`Grid::arc_gap`] measures it; an arc written as
    /// [`ArcWords::Line`] strays infinitely), which the choice has bounded already.
    pub fn arc_words_straying(
        &self,
        from: Xz,
        end: Xz,
        centre: Xz,
        ccw: bool,
        prefer_radius: bool,
        limit: f64,
    ) -> (ArcWords, bool) {
        let (start, stop) = (self.point(from), self.point(end));
        let exact = ArcSpan::new(from, end, centre, ccw);
        // Rounded ends that meet make the control run a full circle: what an arc of more
        // than half a turn short of one by less than an increment should be, and nothing
        // near a shorter one.
        let full = start == stop;
        if full && exact.sweep() <= PI {
            return (ArcWords::Line, true);
        }
        // The rounded ends in mm, which every stray's arc runs between.
        let (at, to) = (self.to_mm(start), self.to_mm(stop));
        // Most arcs keep the radius form: the centre's words are counted only where asked for.
        let by_centre = || ArcWords::Centre { i: self.length(centre.x - at.x), k: self.length(centre.z - at.z) };
        // Each stray runs the control's arc; it is bounded only where the choice needs it,
        // and measured only where the bounds do not decide (the choice is the same as
        // measuring both every time).
        let stray = |words| Stray::new(self, &exact, at, to, words, ccw);
        let centre_stray = std::cell::OnceCell::new();
        let centre_stray = || centre_stray.get_or_init(|| stray(by_centre()));
        let line = (ArcWords::Line, true);
        if full {
            let by_centre_stray = centre_stray();
            return if by_centre_stray.is_finite() { (by_centre(), !by_centre_stray.at_most(limit)) } else { line };
        }
        let radius = exact.radius;
        let beyond_half_turn = exact.sides.beyond_half_turn().unwrap_or_else(|| exact.sweep() > PI + 1e-9);
        let signed = if beyond_half_turn { -radius } else { radius };
        let count = self.length(signed);
        let by_radius = ArcWords::Radius(count);
        if prefer_radius {
            let radius_stray = stray(by_radius);
            let increment = self.increment_mm();
            let reaches = self.length_mm(count).abs() - at.distance(to) / 2.0 >= increment - 1e-12;
            let radius_holds =
                reaches && (radius_stray.at_most(increment / 2.0) || radius_stray.at_most_as_far_as(centre_stray()));
            if radius_holds {
                return (by_radius, !radius_stray.at_most(limit));
            }
            return if centre_stray().is_finite() {
                (by_centre(), !centre_stray().at_most(limit))
            } else if radius_stray.is_finite() {
                (by_radius, !radius_stray.at_most(limit))
            } else {
                line
            };
        }
        if centre_stray().is_finite() {
            return (by_centre(), !centre_stray().at_most(limit));
        }
        let radius_stray = stray(by_radius);
        if radius_stray.is_finite() { (by_radius, !radius_stray.at_most(limit)) } else { line }
    }

    /// The centre the control takes for an arc written with `words` from `start` to `stop`
    /// (grid points), in the toolpath frame: as the semantic pass reads the block back.
    pub fn arc_centre(&self, start: GridPoint, stop: GridPoint, words: ArcWords, ccw: bool) -> Option<Xz> {
        self.arc_centre_between(self.to_mm(start), self.to_mm(stop), words, ccw)
    }

    /// [`Grid::arc_centre`] given the grid points in mm (`Grid::to_mm`), for callers that have
    /// them already.
    fn arc_centre_between(&self, from: Xz, to: Xz, words: ArcWords, ccw: bool) -> Option<Xz> {
        match words {
            ArcWords::Radius(count) => {
                geometry::centre_from_radius(from, to, self.length_mm(count), ccw, geometry::ARC_RADIUS_REACH_MM)
            }
            ArcWords::Centre { i, k } => {
                let centre = Xz::new(from.x + self.length_mm(i), from.z + self.length_mm(k));
                geometry::centre_from_offsets(from, to, centre).ok()
            }
            ArcWords::Line => None,
        }
    }

    /// How far the arc the control runs for `words`, written for the arc from `from` to
    /// `end` about `centre` (exact), strays from that arc (infinite when it runs none).
    #[cfg(test)]
    pub fn arc_gap(&self, from: Xz, end: Xz, centre: Xz, ccw: bool, words: ArcWords) -> f64 {
        let (start, stop) = (self.to_mm(self.point(from)), self.to_mm(self.point(end)));
        // Every point measured, as the bounded choices (`Stray`) are held to.
        let exact = ArcSpan::new(from, end, centre, ccw);
        let run = self.arc_centre_between(start, stop, words, ccw).map(|c| ArcSpan::new(start, stop, c, ccw));
        run.map_or(f64::INFINITY, |run| exact.gap(&run))
    }
}

/// How far the arc the control runs for some words strays from the exact arc: bounded
/// without angles first (`ArcSpan::gap_bounds`), measured (`ArcSpan::gap`) only where a
/// comparison falls between the bounds.
struct Stray<'a> {
    exact: &'a ArcSpan,
    /// The arc the control runs, `None` where it runs none (the stray is infinite).
    run: Option<ArcSpan>,
    low: f64,
    high: f64,
    /// The upper bound on each point's distance (`GapBounds::points`), for `measured` to
    /// skip the points that cannot hold the largest.
    points: [f64; GAP_POINTS],
    measured: std::cell::OnceCell<f64>,
}

impl<'a> Stray<'a> {
    /// The stray of the arc the control runs for `words` between the rounded ends `start` and
    /// `stop` (grid points in mm).
    fn new(grid: &Grid, exact: &'a ArcSpan, start: Xz, stop: Xz, words: ArcWords, ccw: bool) -> Self {
        let run = grid.arc_centre_between(start, stop, words, ccw).map(|c| ArcSpan::new(start, stop, c, ccw));
        let bounds = match &run {
            Some(run) => exact.gap_bounds(run).unwrap_or(GapBounds::NONE),
            None => GapBounds { low: f64::INFINITY, high: f64::INFINITY, points: [f64::INFINITY; GAP_POINTS] },
        };
        let GapBounds { low, high, points } = bounds;
        Stray { exact, run, low, high, points, measured: std::cell::OnceCell::new() }
    }

    /// The stray itself (infinite where the control runs no arc). A point whose distance is
    /// bounded below `low` cannot be the farthest (some point `gap` measures is at least
    /// `low` away), so it is not measured: the largest is the same.
    fn measured(&self) -> f64 {
        *self.measured.get_or_init(|| {
            self.run.as_ref().map_or(f64::INFINITY, |run| self.exact.gap_above(run, &self.points, self.low))
        })
    }

    fn at_most(&self, limit: f64) -> bool {
        if self.high <= limit {
            true
        } else if self.low > limit {
            false
        } else {
            self.measured() <= limit
        }
    }

    fn at_most_as_far_as(&self, other: &Stray<'_>) -> bool {
        if self.high <= other.low {
            true
        } else if self.low > other.high {
            false
        } else {
            self.measured() <= other.measured()
        }
    }

    fn is_finite(&self) -> bool {
        self.high.is_finite() || (self.low != f64::INFINITY && self.measured().is_finite())
    }
}

/// The shortest chord between unit directions, for `ArcSpan::gap_bounds` to find the
/// direction halfway between them from: nearer directions leave it too little of the
/// chord's length to divide by.
const SHORTEST_UNIT_CHORD: f64 = 1e-3;

/// The points `ArcSpan::gap` measures: the quarters of the sweep (its ends, its middle and
/// the middles of its halves), then the two where the centres line up.
const GAP_POINTS: usize = 7;

/// Bounds on [`ArcSpan::gap`] (`ArcSpan::gap_bounds`).
struct GapBounds {
    low: f64,
    high: f64,
    /// An upper bound on the distance of each of the `GAP_POINTS`, in their order (infinite
    /// where it is not bounded).
    points: [f64; GAP_POINTS],
}

impl GapBounds {
    /// No bounds at all.
    const NONE: GapBounds =
        GapBounds { low: f64::NEG_INFINITY, high: f64::INFINITY, points: [f64::INFINITY; GAP_POINTS] };
}

/// An arc by its start, centre, radius and sweep.
struct ArcSpan {
    start: Xz,
    end: Xz,
    centre: Xz,
    radius: f64,
    ccw: bool,
    sides: SweepSides,
    /// The start's angle and the sweep (`geometry::angle`, `geometry::sweep`), measured
    /// where they are first needed.
    angles: std::cell::OnceCell<(f64, f64)>,
}

impl ArcSpan {
    fn new(start: Xz, end: Xz, centre: Xz, ccw: bool) -> ArcSpan {
        let sides = SweepSides::new(start, end, centre, ccw);
        ArcSpan { start, end, centre, radius: start.distance(centre), ccw, sides, angles: std::cell::OnceCell::new() }
    }

    fn angles(&self) -> (f64, f64) {
        *self.angles.get_or_init(|| geometry::turn(self.start, self.end, self.centre, self.ccw))
    }

    fn sweep(&self) -> f64 {
        self.angles().1
    }

    /// The point at `fraction` of the sweep.
    fn at(&self, fraction: f64) -> Xz {
        let sign = if self.ccw { 1.0 } else { -1.0 };
        let (a0, sweep) = self.angles();
        geometry::on_circle(self.centre, self.radius, a0 + sign * sweep * fraction)
    }

    /// The distance from `p` to this arc.
    fn distance(&self, p: Xz) -> f64 {
        if self.inside(p) { self.off_circle(p) } else { self.to_ends(p) }
    }

    fn off_circle(&self, p: Xz) -> f64 {
        (p.distance(self.centre) - self.radius).abs()
    }

    fn to_ends(&self, p: Xz) -> f64 {
        p.distance(self.start).min(p.distance(self.end))
    }

    /// Whether `p` lies inside the sweep: by the cross products where they tell, by the
    /// angle where it is near an end.
    fn inside(&self, p: Xz) -> bool {
        self.sides.inside(p).unwrap_or_else(|| self.within_sweep(geometry::angle(p, self.centre)))
    }

    /// Whether the angle `a` lies inside the sweep.
    fn within_sweep(&self, a: f64) -> bool {
        let (a0, sweep) = self.angles();
        let delta = if self.ccw { geometry::rem_turn(a - a0) } else { geometry::rem_turn(a0 - a) };
        delta <= sweep
    }

    /// The largest distance of a point of `other` from this arc. The distance of a point of
    /// one circle from another circle is extreme where the two centres and the point line
    /// up, so `other` is measured there (where that lies on it), at its ends, and at its
    /// quarters (which catch an arc gone round the other way).
    #[cfg(test)]
    fn gap(&self, other: &ArcSpan) -> f64 {
        self.gap_above(other, &[f64::INFINITY; GAP_POINTS], f64::NEG_INFINITY)
    }

    /// [`ArcSpan::gap`], measuring only the points whose distance's upper bound `highs` (one
    /// per point of `GAP_POINTS`) is not below `floor`, a distance that some point it
    /// measures has at least: the others cannot change the largest.
    fn gap_above(&self, other: &ArcSpan, highs: &[f64; GAP_POINTS], floor: f64) -> f64 {
        let [h0, h1, h2, h3, h4, towards, opposite] = *highs;
        // A bound that is not a number bounds nothing.
        let measured = |high: f64| high >= floor || high.is_nan();
        let mut worst: f64 = 0.0;
        for (f, high) in [(0.0, h0), (0.25, h1), (0.5, h2), (0.75, h3), (1.0, h4)] {
            if measured(high) {
                worst = worst.max(self.distance(other.at(f)));
            }
        }
        if self.centre.distance(other.centre) > 0.0 && (measured(towards) || measured(opposite)) {
            let away = geometry::angle(self.centre, other.centre);
            for (a, high) in [(away, towards), (away + PI, opposite)] {
                if measured(high) && other.within_sweep(a) {
                    worst = worst.max(self.distance(geometry::on_circle(other.centre, other.radius, a)));
                }
            }
        }
        if worst.is_nan() { f64::INFINITY } else { worst }
    }

    /// Bounds on [`ArcSpan::gap`] that take no angles, or `None` where they cannot be had
    /// so (`other` sweeps nearly nothing or a full turn, a point lies too near an end).
    ///
    /// `gap` measures points of `other` that it finds by angles: its quarters, by its start
    /// angle and sweep, and the points where the centres line up, by the angle between the
    /// centres. The same points follow from unit vectors alone: the direction halfway
    /// between two, less than a turn apart in the arc's sense, is their difference turned a
    /// quarter turn against that sense, and the centres' line is their difference. The two
    /// ways differ by the rounding of a few operations on the coordinates (some 1e-14 of
    /// their size), and by that divided by the chords the halving divides by; `slack`
    /// allows a thousand times that. Each point's distance then lies within `slack` of the
    /// one `gap` measures, where the point lies clearly on one side of this arc's ends for
    /// everything within `slack` of it (`SweepSides::inside_within`); a point of the
    /// centres' line that may or may not lie on `other` raises only the upper bound.
    fn gap_bounds(&self, other: &ArcSpan) -> Option<GapBounds> {
        let (centre, radius) = (other.centre, other.radius);
        let unit = |p: Xz| {
            let length = p.distance(centre);
            Xz::new((p.x - centre.x) / length, (p.z - centre.z) / length)
        };
        let sense = if other.ccw { 1.0 } else { -1.0 };
        let halfway = |a: Xz, b: Xz| {
            let chord = b.distance(a);
            (chord >= SHORTEST_UNIT_CHORD).then(|| Xz::new(-sense * (b.z - a.z) / chord, sense * (b.x - a.x) / chord))
        };
        let (first, last) = (unit(other.start), unit(other.end));
        let chord = last.distance(first);
        let middle = halfway(first, last)?;
        let quarters = [first, halfway(first, middle)?, middle, halfway(middle, last)?, last];
        let scale =
            1.0 + self.centre.x.abs() + self.centre.z.abs() + self.radius + centre.x.abs() + centre.z.abs() + radius;
        let slack = 1e-11 * scale + 1e-13 * radius / (chord * chord);
        let on = |u: Xz| Xz::new(centre.x + radius * u.x, centre.z + radius * u.z);
        let (mut low, mut high) = (0.0_f64, 0.0_f64);
        let mut points = [f64::INFINITY; GAP_POINTS];
        for (u, point) in quarters.into_iter().zip(&mut points) {
            let d = self.distance_within(on(u), slack)?;
            (low, high) = (low.max(d - slack), high.max(d + slack));
            *point = d + slack;
        }
        let between = self.centre.distance(centre);
        if between > 0.0 {
            let away = Xz::new((self.centre.x - centre.x) / between, (self.centre.z - centre.z) / between);
            let lined_up = points.get_mut(5..).unwrap_or_default();
            for (u, point) in [away, Xz::new(-away.x, -away.z)].into_iter().zip(lined_up) {
                let on_other = other.sides.inside(Xz::new(centre.x + u.x, centre.z + u.z));
                // A point clearly off `other` is not measured by `gap` either; it keeps no
                // bound, so `gap_above` decides it by the angles as `gap` does.
                if on_other == Some(false) {
                    continue;
                }
                let d = self.distance_within(on(u), slack)?;
                high = high.max(d + slack);
                *point = d + slack;
                if on_other == Some(true) {
                    low = low.max(d - slack);
                }
            }
        }
        (low.is_finite() && high.is_finite()).then_some(GapBounds { low, high, points })
    }

    /// `distance` of every point within `slack` of `p` to within `slack`, where they all lie
    /// on one side of the ends.
    fn distance_within(&self, p: Xz, slack: f64) -> Option<f64> {
        let inside = self.sides.inside_within(p, slack)?;
        Some(if inside { self.off_circle(p) } else { self.to_ends(p) })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dialect::{DecimalInput, Dialect};
    use std::f64::consts::TAU;

    fn grid(inch: bool, diameter: bool) -> Grid {
        let frame = Frame {
            dialect: Dialect::Fanuc,
            inch,
            diameter,
            decimal_input: DecimalInput::Calculator,
            increment: if inch { 0.0001 } else { 0.001 },
        };
        Grid::new(&CoordinateMark { from_move: 0, frame, absolute: true, shift: Xz::default() })
    }

    #[test]
    fn diameter_grid_is_half_the_increment_in_radius() {
        let g = grid(false, true);
        // 10.00024 mm radius is a diameter of 20.00048: 20.000 on the grid, 10.000 back.
        assert_eq!(g.point(Xz::new(10.00024, 0.0)).x, 20_000);
        assert_eq!(g.point(Xz::new(10.00026, 0.0)).x, 20_001);
        assert!((g.round(Xz::new(10.00026, 0.0)).x - 10.0005).abs() < 1e-12);
    }

    /// The point at `degrees` (from +Z toward +X) on the circle about `centre`.
    fn on(centre: Xz, radius: f64, degrees: f64) -> Xz {
        geometry::on_circle(centre, radius, degrees.to_radians())
    }

    #[test]
    fn a_quarter_and_three_quarters_keep_their_radius() {
        let g = grid(false, false);
        // G02 X45 Z-15 R5 from X40 Z-10 (radius programming): centre X45 Z-10.
        let words = g.arc_words(Xz::new(40.0, -10.0), Xz::new(45.0, -15.0), Xz::new(45.0, -10.0), false, true);
        assert_eq!(words, ArcWords::Radius(5_000));
        // G03 X25 Z-48 R-3 from X22 Z-45: three quarters of a turn, a negative radius.
        let words = g.arc_words(Xz::new(22.0, -45.0), Xz::new(25.0, -48.0), Xz::new(25.0, -45.0), true, true);
        assert_eq!(words, ArcWords::Radius(-3_000));
        // A program that writes I K keeps I K.
        let words = g.arc_words(Xz::new(40.0, -10.0), Xz::new(45.0, -15.0), Xz::new(45.0, -10.0), false, false);
        assert_eq!(words, ArcWords::Centre { i: 5_000, k: 0 });
    }

    #[test]
    fn near_half_a_turn_the_centre_form_is_written_where_the_radius_would_move_the_centre() {
        let g = grid(false, false);
        let centre = Xz::new(30.1003, -24.9987);
        // Radii that round up (the control finds the centre far off the exact one) and
        // down (the rounded radius does not reach across the chord: an alarm).
        for radius in [4.9996, 5.0002] {
            for (sweep, ccw) in [(179.7, false), (179.9, true), (180.1, false), (180.4, true)] {
                let from = on(centre, radius, 3.1);
                let end = on(centre, radius, if ccw { 3.1 + sweep } else { 3.1 - sweep });
                let words = g.arc_words(from, end, centre, ccw, true);
                let ArcWords::Centre { .. } = words else { panic!("{radius} {sweep}°: {words:?}") };
                let signed = if sweep > 180.0 { -radius } else { radius };
                let by_radius = g.arc_gap(from, end, centre, ccw, ArcWords::Radius(g.length(signed)));
                let by_centre = g.arc_gap(from, end, centre, ccw, words);
                // Whether the choice strays further than a limit is what measuring it says, on
                // either side of it and at it.
                for limit in [0.0, by_centre * (1.0 - 1e-12), by_centre, g.increment_mm()] {
                    let straying = g.arc_words_straying(from, end, centre, ccw, true, limit);
                    assert_eq!(straying, (words, by_centre > limit));
                }
                // Rounded up, R puts the centre some 0.03–0.06 mm from where it is.
                assert!(by_radius > 0.02, "{radius} {sweep}°: R strays {by_radius}");
                // I K strays by its rounding only: the centre and the ends by half an
                // increment per axis.
                assert!(by_centre <= 0.0015, "{radius} {sweep}°: I K strays {by_centre}");
            }
        }
    }

    /// The choice of words as documented on [`Grid::arc_words`], every stray measured.
    fn measured_choice(g: &Grid, from: Xz, end: Xz, centre: Xz, ccw: bool, prefer_radius: bool) -> (ArcWords, f64) {
        let (start, stop) = (g.point(from), g.point(end));
        let sweep = geometry::sweep(from, end, centre, ccw);
        let line = (ArcWords::Line, f64::INFINITY);
        if start == stop && sweep <= PI {
            return line;
        }
        let at = g.to_mm(start);
        let by_centre = ArcWords::Centre { i: g.length(centre.x - at.x), k: g.length(centre.z - at.z) };
        let centre_gap = g.arc_gap(from, end, centre, ccw, by_centre);
        if start == stop {
            return if centre_gap.is_finite() { (by_centre, centre_gap) } else { line };
        }
        let radius = from.distance(centre);
        let count = g.length(if sweep > PI + 1e-9 { -radius } else { radius });
        let by_radius = ArcWords::Radius(count);
        let radius_gap = g.arc_gap(from, end, centre, ccw, by_radius);
        let increment = g.increment_mm();
        let reaches = g.length_mm(count).abs() - at.distance(g.to_mm(stop)) / 2.0 >= increment - 1e-12;
        if prefer_radius && reaches && (radius_gap <= increment / 2.0 || radius_gap <= centre_gap) {
            (by_radius, radius_gap)
        } else if centre_gap.is_finite() {
            (by_centre, centre_gap)
        } else if radius_gap.is_finite() {
            (by_radius, radius_gap)
        } else {
            line
        }
    }

    proptest::proptest! {
        /// Measuring only the points whose bounds reach the floor (`Stray::measured`) finds
        /// the largest distance bit for bit, for runs near the exact arc as the control's are
        /// (its ends and centre moved by up to `shift`) and far from it.
        #[test]
        fn a_gap_measured_above_its_floor_is_the_gap(
            cx in -80.0f64..80.0, cz in -200.0f64..10.0, radius in 0.3f64..60.0, from in -3.2f64..3.2,
            sweep in 0.001f64..(TAU - 0.001), ccw in proptest::bool::ANY, shift in 0.0f64..0.05,
            moves in proptest::collection::vec(-1.0f64..1.0, 6),
        ) {
            let centre = Xz::new(cx, cz);
            let sense = if ccw { 1.0 } else { -1.0 };
            let (a, b) = (geometry::on_circle(centre, radius, from), geometry::on_circle(centre, radius, from + sense * sweep));
            let moved = |p: Xz, k: usize| Xz::new(p.x + shift * moves[k], p.z + shift * moves[k + 1]);
            let exact = ArcSpan::new(a, b, centre, ccw);
            let run = ArcSpan::new(moved(a, 0), moved(b, 2), moved(centre, 4), ccw);
            if let Some(bounds) = exact.gap_bounds(&run) {
                let gap = exact.gap(&run);
                proptest::prop_assert!(bounds.low <= gap && gap <= bounds.high);
                proptest::prop_assert_eq!(exact.gap_above(&run, &bounds.points, bounds.low).to_bits(), gap.to_bits());
            }
        }
    }

    proptest::proptest! {
        /// The choice bounds the strays and measures one only where the bounds do not decide:
        /// it is the choice that measures them all, and so is whether it strays past a limit.
        #[test]
        fn bounded_strays_choose_as_measured_ones(
            cx in -80.0f64..80.0, cz in -200.0f64..10.0, radius in 0.3f64..60.0, from in -3.2f64..3.2,
            sweep in 0.001f64..(TAU - 0.001), near_half in -2e-3f64..2e-3, half in proptest::bool::ANY,
            ccw in proptest::bool::ANY, prefer_radius in proptest::bool::ANY, inch in proptest::bool::ANY,
            diameter in proptest::bool::ANY,
        ) {
            let g = grid(inch, diameter);
            let centre = Xz::new(cx, cz);
            let sweep = if half { PI + near_half } else { sweep };
            let sense = if ccw { 1.0 } else { -1.0 };
            let (a, b) = (geometry::on_circle(centre, radius, from), geometry::on_circle(centre, radius, from + sense * sweep));
            let (words, gap) = measured_choice(&g, a, b, centre, ccw, prefer_radius);
            proptest::prop_assert_eq!(g.arc_words(a, b, centre, ccw, prefer_radius), words);
            for limit in [0.0, g.increment_mm() / 2.0, g.increment_mm(), gap, gap * (1.0 - 1e-12), gap * (1.0 + 1e-12)] {
                let straying = g.arc_words_straying(a, b, centre, ccw, prefer_radius, limit);
                proptest::prop_assert_eq!(straying, (words, gap > limit), "limit {}", limit);
            }
        }
    }

    #[test]
    fn a_half_circle_on_the_grid_is_written_by_its_centre() {
        // Its radius is exactly half its chord: the R arc is exact, but whether a control
        // takes R = c/2 as a half circle or as "radius too small" is its own arithmetic's
        // call.
        let g = grid(false, false);
        let (from, end, centre) = (Xz::new(21.998, -45.001), Xz::new(27.998, -45.001), Xz::new(24.998, -45.001));
        assert_eq!(g.arc_words(from, end, centre, true, true), ArcWords::Centre { i: 3_000, k: 0 });
    }

    #[test]
    fn an_arc_whose_rounded_ends_meet_is_a_line_unless_it_is_nearly_a_full_circle() {
        let g = grid(false, false);
        // 0.3 µm of a 5 mm circle: both ends round to X25.000 Z-50.000.
        let centre = Xz::new(20.0, -50.0);
        let (from, end) = (on(centre, 5.0, 90.0 - 1e-6), on(centre, 5.0, 90.0 + 2.4e-6));
        assert_eq!(g.point(from), g.point(end));
        assert_eq!(g.arc_words(from, end, centre, true, true), ArcWords::Line);
        assert_eq!(g.arc_centre(g.point(from), g.point(end), ArcWords::Line, true), None);
        // The rest of the same circle, the long way round: the control runs the full circle
        // from I K, about the centre as rounded.
        let words = g.arc_words(from, end, centre, false, true);
        assert_eq!(words, ArcWords::Centre { i: -5_000, k: 0 });
        let run = g.arc_centre(g.point(from), g.point(end), words, false).unwrap();
        assert!(run.distance(centre) < 1e-9, "{run:?}");
    }

    #[test]
    fn the_centre_the_control_takes_from_offsets_is_on_the_rounded_chords_bisector() {
        let g = grid(false, false);
        // I5 K0 from X30 Z-20 to X35 Z-24.999: the end is 1 µm nearer the centre than the
        // start. The control moves the centre onto the chord's bisector, nearest the
        // written one, as the semantic pass reads the block.
        let (start, stop) = (GridPoint { x: 30_000, z: -20_000 }, GridPoint { x: 35_000, z: -24_999 });
        let run = g.arc_centre(start, stop, ArcWords::Centre { i: 5_000, k: 0 }, false).unwrap();
        let (a, b) = (g.to_mm(start), g.to_mm(stop));
        assert!((run.distance(a) - run.distance(b)).abs() < 1e-12);
        let moved = run.distance(Xz::new(35.0, -20.0));
        assert!(moved > 1e-4 && moved < 1e-3, "{run:?}");
    }

    #[test]
    fn the_usual_increments_have_the_places_they_count() {
        for increment in [0.001, 0.0001, 0.01, 0.005, 0.5, 1.0] {
            assert_eq!(places(increment), crate::machine::increment_places(increment), "{increment}");
        }
    }

    #[test]
    fn nearest_whole_is_round_as_a_count() {
        let halves =
            [0.5, -0.5, 1.5, -2.5, 0.499_999_999_999_999_94, -0.499_999_999_999_999_94, 4_503_599_627_370_495.5];
        let edges = [0.0, -0.0, 1e300, -1e300, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, 9.3e18, -9.3e18];
        for x in halves.into_iter().chain(edges) {
            assert_eq!(nearest_whole(x), x.round() as i64, "{x}");
        }
    }

    proptest::proptest! {
        #[test]
        fn nearest_whole_agrees_with_round(mantissa in -1e7f64..1e7, places in 0u8..10, half in proptest::bool::ANY) {
            let x = if half { mantissa.trunc() + 0.5 } else { mantissa * 10f64.powi(i32::from(places)) };
            proptest::prop_assert_eq!(nearest_whole(x), x.round() as i64);
        }
    }

    #[test]
    fn inch_grid_rounds_in_inches() {
        let g = grid(true, false);
        let p = g.point(Xz::new(25.4 * 1.00004, -25.4 * 0.00006));
        assert_eq!((p.x, p.z), (10_000, -1));
    }

    proptest::proptest! {
        /// A literal with the grid's decimal places counts as its mantissa: the same count
        /// as its value through f64, up to the bound the shortcut takes (and just under it).
        #[test]
        fn a_literal_on_the_grid_counts_as_its_value(
            places in 0u8..=9,
            mantissa in proptest::prop_oneof![
                -100_000_000i64..100_000_000,
                -(1i64 << 50) + 1..(1i64 << 50),
                ((1i64 << 50) - 1_000_000)..(1i64 << 50),
                (-(1i64 << 50) + 1)..(-(1i64 << 50) + 1_000_000),
            ],
            inch in proptest::bool::ANY,
            diameter in proptest::bool::ANY,
        ) {
            let g = Grid { places, ..grid(inch, diameter) };
            let number = Number::new(mantissa, places, true);
            let through_f64 = g.count(g.frame.literal(number, Some(AddressKind::Length), false));
            proptest::prop_assert_eq!(g.literal_count(number, || Some(AddressKind::Length)), through_f64);
            proptest::prop_assert_eq!(through_f64, mantissa);
        }
    }

    /// Literals the shortcut leaves to the f64 path: other decimal places, no point (a
    /// count of increments on such a Fanuc control), beyond the bound.
    #[test]
    fn other_literals_count_through_their_value() {
        let g = grid(false, false);
        assert_eq!(g.literal_count(Number::new(552, 1, true), || Some(AddressKind::Length)), 55_200);
        let increments = Grid { frame: Frame { decimal_input: DecimalInput::Increment, ..g.frame }, ..g };
        assert_eq!(increments.literal_count(Number::new(552, 0, false), || Some(AddressKind::Length)), 552);
        assert_eq!(g.literal_count(Number::new(552, 0, false), || Some(AddressKind::Length)), 552_000);
        let huge = (1i64 << 53) + 1;
        assert_eq!(g.literal_count(Number::new(huge, 3, true), || None), g.count(Number::new(huge, 3, true).to_f64()));
    }
}
