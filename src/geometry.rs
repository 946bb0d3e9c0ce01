//! Plane geometry in the toolpath frame (X radius, Z axial, mm), with nalgebra.
//!
//! **Arc sense.** Seen from +Y (the ZX plane of `G18`, Z to the right and X up), `G02` turns
//! clockwise and `G03` counter-clockwise. With the angle of a point about a centre measured
//! as `atan2(x − cx, z − cz)`, `G03` is the direction of increasing angle.
//!
//! ```txt
//!   X ▲        G03 (ccw): angle grows
//!     │   ╭─╮
//!     │  ╱   ╲
//!     └──────────▶ Z
//! ```

use std::f64::consts::{PI, TAU};

use nalgebra::{Matrix2, Vector2};
use smallvec::SmallVec;

/// A point in the toolpath frame: `x` is the radius, `z` the axial position, both in mm.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Xz {
    pub x: f64,
    pub z: f64,
}

impl Xz {
    pub const fn new(x: f64, z: f64) -> Xz {
        Xz { x, z }
    }

    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.z.is_finite()
    }

    pub fn distance(self, other: Xz) -> f64 {
        // Not `hypot`: lathe coordinates are far from overflow, and the plain square root
        // is several times faster on the hot path of every move.
        self.distance_squared(other).sqrt()
    }

    /// The square of `distance`, for comparisons that need no root (`compensation/squares.rs`).
    pub fn distance_squared(self, other: Xz) -> f64 {
        let (dx, dz) = (self.x - other.x, self.z - other.z);
        dx * dx + dz * dz
    }
}

fn v(p: Xz) -> Vector2<f64> {
    Vector2::new(p.z, p.x)
}

fn p(v: Vector2<f64>) -> Xz {
    Xz::new(v.y, v.x)
}

/// The greatest whole number not above `x` (`f64::floor`), by truncation: the build's
/// baseline x86-64 has no rounding instruction, so `f64::floor` is a call into a software
/// routine, and the part model asks it for every ray range and every arc's crossing.
/// Numbers of 2⁵² and above, infinities and NaN are their own floor.
pub fn floor(x: f64) -> f64 {
    if x.is_nan() || x.abs() >= 4_503_599_627_370_496.0 {
        return x;
    }
    let truncated = x as i64 as f64;
    if truncated > x { truncated - 1.0 } else { truncated }
}

/// The least whole number not below `x` (`f64::ceil`), as [`floor`] does it.
pub fn ceil(x: f64) -> f64 {
    -floor(-x)
}

/// The angle of `point` about `centre` (radians, from +Z toward +X).
pub fn angle(point: Xz, centre: Xz) -> f64 {
    (point.x - centre.x).atan2(point.z - centre.z)
}

/// The point at `angle` on the circle of `radius` about `centre`.
pub fn on_circle(centre: Xz, radius: f64, angle: f64) -> Xz {
    Xz::new(centre.x + radius * angle.sin(), centre.z + radius * angle.cos())
}

/// `x.rem_euclid(TAU)`: an angle (a difference of two, as a rule) brought into [0, 2π).
/// Where |x| < 2π, as every difference of two angles is, the remainder of the division is
/// `x` itself, which spares the library call the remainder is on this target.
pub fn rem_turn(x: f64) -> f64 {
    if x.abs() < TAU { if x < 0.0 { x + TAU } else { x } } else { x.rem_euclid(TAU) }
}

/// The swept angle from `start` to `end` about `centre`, positive, in `(0, 2π]`: an arc whose
/// end meets its start is a full circle.
pub fn sweep(start: Xz, end: Xz, centre: Xz, ccw: bool) -> f64 {
    sweep_from_angles(start, end, angle(start, centre), angle(end, centre), ccw)
}

/// [`sweep`] given the start's angle `a0` (`angle(start, centre)`), which callers that need
/// it too have measured already.
pub fn sweep_from(a0: f64, start: Xz, end: Xz, centre: Xz, ccw: bool) -> f64 {
    sweep_from_angles(start, end, a0, angle(end, centre), ccw)
}

/// The angle of `start` about `centre` ([`angle`]) and the angle the arc from `start` to
/// `end` turns through ([`sweep`]), measured together for the callers that need both.
pub fn turn(start: Xz, end: Xz, centre: Xz, ccw: bool) -> (f64, f64) {
    let a0 = angle(start, centre);
    (a0, sweep_from(a0, start, end, centre, ccw))
}

/// [`sweep`] when the angles of `start` (`a0`) and `end` (`a1`) about the centre are known.
pub fn sweep_from_angles(start: Xz, end: Xz, a0: f64, a1: f64, ccw: bool) -> f64 {
    let raw = if ccw { a1 - a0 } else { a0 - a1 };
    let mut s = rem_turn(raw);
    // A chord shorter than a nanometre is a full circle, not an empty arc.
    if s < 1e-12 || (start.distance(end) < 1e-9 && s > TAU - 1e-9) {
        s = TAU;
    }
    s
}

pub fn arc_length(start: Xz, end: Xz, centre: Xz, ccw: bool) -> f64 {
    start.distance(centre) * sweep(start, end, centre, ccw)
}

/// The points where an arc is furthest along ±X and ±Z (inside its sweep), for limit checks
/// and bounding boxes.
pub fn arc_extremes(start: Xz, end: Xz, centre: Xz, ccw: bool) -> SmallVec<[Xz; 4]> {
    let (a0, total) = turn(start, end, centre, ccw);
    arc_extremes_from(centre, start.distance(centre), a0, total, ccw)
}

/// [`arc_extremes`] of the arc of `radius` about `centre` from the angle `a0`, turning by
/// `total` (`sweep`), which callers that need them too have measured already.
pub fn arc_extremes_from(centre: Xz, radius: f64, a0: f64, total: f64, ccw: bool) -> SmallVec<[Xz; 4]> {
    let mut out = SmallVec::new();
    for k in 0..4 {
        let target = k as f64 * PI / 2.0;
        let delta = if ccw { rem_turn(target - a0) } else { rem_turn(a0 - target) };
        if delta > 0.0 && delta < total {
            out.push(on_circle(centre, radius, target));
        }
    }
    out
}

/// The centre of the arc from `start` to `end` with radius `radius`: the shorter arc for a
/// positive radius, the longer for a negative one (the Fanuc `R` rule). `None` when the
/// radius cannot reach: shorter than half the chord by more than `tolerance`.
pub fn centre_from_radius(start: Xz, end: Xz, radius: f64, ccw: bool, tolerance: f64) -> Option<Xz> {
    let a = v(start);
    let b = v(end);
    let chord = b - a;
    let half = chord.norm() / 2.0;
    let r = radius.abs();
    if half < 1e-12 || r + tolerance < half {
        return None;
    }
    let h = (r * r - half * half).max(0.0).sqrt();
    let mid = (a + b) / 2.0;
    let unit = chord / chord.norm();
    // Perpendicular to the chord, to the left of the direction start → end in (z, x).
    let left = Vector2::new(-unit.y, unit.x);
    // A counter-clockwise minor arc has its centre to the left of the chord.
    let minor = radius > 0.0;
    let side = if ccw == minor { 1.0 } else { -1.0 };
    Some(p(mid + left * (h * side)))
}

/// The largest difference of an `I`/`K` arc's start and end radii the controls accept, mm.
pub const ARC_RADIUS_MISMATCH_MM: f64 = 0.02;

/// How far an `R`/`L` radius may fall short of half the chord and still be taken (as a
/// half circle), mm: rounding noise, not a programming error.
pub const ARC_RADIUS_REACH_MM: f64 = 1e-6;

/// The centre a control takes for an arc given by its centre offsets (`I K`) from `start`
/// to `end`: `centre` itself when both ends are equally far from it, else the point of the
/// chord's perpendicular bisector nearest it (the ends' radii differ after rounding, and
/// the arc must still run through both ends). `None` when the radii differ by more than
/// [`ARC_RADIUS_MISMATCH_MM`] (the control's alarm), with the two radii.
pub fn centre_from_offsets(start: Xz, end: Xz, centre: Xz) -> Result<Xz, (f64, f64)> {
    let (r0, r1) = (start.distance(centre), end.distance(centre));
    if (r0 - r1).abs() > ARC_RADIUS_MISMATCH_MM {
        return Err((r0, r1));
    }
    if (r0 - r1).abs() > 1e-9 && start.distance(end) > 1e-9 {
        let mid = Xz::new((start.x + end.x) / 2.0, (start.z + end.z) / 2.0);
        let normal = left_normal(start, end);
        let along = (centre.x - mid.x) * normal.x + (centre.z - mid.z) * normal.z;
        Ok(Xz::new(mid.x + normal.x * along, mid.z + normal.z * along))
    } else {
        Ok(centre)
    }
}

/// Where the line through `a1`, `a2` meets the line through `b1`, `b2`; `None` if parallel.
pub fn line_line(a1: Xz, a2: Xz, b1: Xz, b2: Xz) -> Option<Xz> {
    let d1 = v(a2) - v(a1);
    let d2 = v(b2) - v(b1);
    let m = Matrix2::new(d1.x, -d2.x, d1.y, -d2.y);
    let rhs = v(b1) - v(a1);
    let t = m.try_inverse()? * rhs;
    Some(p(v(a1) + d1 * t.x))
}

/// Where the line through `a`, `b` meets the circle; parameters along `a → b` (0 at `a`,
/// 1 at `b`), in increasing order.
pub fn line_circle(a: Xz, b: Xz, centre: Xz, radius: f64) -> Vec<f64> {
    let d = v(b) - v(a);
    let f = v(a) - v(centre);
    let qa = d.dot(&d);
    if qa < 1e-24 {
        return Vec::new();
    }
    let qb = 2.0 * f.dot(&d);
    let qc = f.dot(&f) - radius * radius;
    let disc = qb * qb - 4.0 * qa * qc;
    if disc < 0.0 {
        return Vec::new();
    }
    let root = disc.sqrt();
    let t1 = (-qb - root) / (2.0 * qa);
    let t2 = (-qb + root) / (2.0 * qa);
    if root == 0.0 { vec![t1] } else { vec![t1, t2] }
}

/// Where two circles meet.
pub fn circle_circle(c1: Xz, r1: f64, c2: Xz, r2: f64) -> Vec<Xz> {
    let d = v(c2) - v(c1);
    let dist = d.norm();
    if dist < 1e-12 || dist > r1 + r2 + 1e-9 || dist < (r1 - r2).abs() - 1e-9 {
        return Vec::new();
    }
    let a = (r1 * r1 - r2 * r2 + dist * dist) / (2.0 * dist);
    let h = (r1 * r1 - a * a).max(0.0).sqrt();
    let unit = d / dist;
    let base = v(c1) + unit * a;
    let perp = Vector2::new(-unit.y, unit.x);
    if h < 1e-12 { vec![p(base)] } else { vec![p(base + perp * h), p(base - perp * h)] }
}

/// Whether the angle of `point` about `centre` lies inside the sweep of the arc.
pub fn angle_within(point: Xz, start: Xz, end: Xz, centre: Xz, ccw: bool) -> bool {
    let total = sweep(start, end, centre, ccw);
    let a0 = angle(start, centre);
    let a = angle(point, centre);
    let delta = if ccw { rem_turn(a - a0) } else { rem_turn(a0 - a) };
    delta <= total + 1e-12
}

/// An arc's angular extent about its centre, for testing many points against it:
/// [`angle_within`]'s answer, told by [`SweepSides`] without an arctangent wherever it is
/// clear, and by the angles only for a point next to an end ray (the measures ask it for
/// millions of samples, and `atan2` was the largest single cost of a compensation run).
#[derive(Debug, Clone, Copy)]
pub struct Sector {
    sides: SweepSides,
    start: Xz,
    end: Xz,
    centre: Xz,
    ccw: bool,
    /// The start's angle about the centre ([`angle`]) and the sweep ([`sweep`]), when they
    /// were measured up front (`new`).
    angles: Option<(f64, f64)>,
}

impl Sector {
    /// A sector whose angles are measured now, for one asked about many points.
    pub fn new(start: Xz, end: Xz, centre: Xz, ccw: bool) -> Sector {
        Sector { angles: Some(turn(start, end, centre, ccw)), ..Sector::unmeasured(start, end, centre, ccw) }
    }

    /// A sector whose start angle and sweep were measured already (as `new` measures them,
    /// `angle` and `sweep_from`), for one made afresh for each few points it is asked about.
    pub fn with_angles(start: Xz, end: Xz, centre: Xz, ccw: bool, start_angle: f64, total: f64) -> Sector {
        Sector { angles: Some((start_angle, total)), ..Sector::unmeasured(start, end, centre, ccw) }
    }

    /// A sector whose angles are measured only when a point next to an end ray needs them:
    /// for one asked about a few points that the cross products place, such as a rounded
    /// segment's (`quantised`), which would spend most of its cost on the two arctangents.
    pub fn unmeasured(start: Xz, end: Xz, centre: Xz, ccw: bool) -> Sector {
        Sector { sides: SweepSides::new(start, end, centre, ccw), start, end, centre, ccw, angles: None }
    }

    /// The start's angle about the centre and the sweep, as measured up front or now.
    fn angles(&self) -> (f64, f64) {
        self.angles.unwrap_or_else(|| turn(self.start, self.end, self.centre, self.ccw))
    }

    /// The angle the sector sweeps, radians ([`sweep`]).
    pub fn total(&self) -> f64 {
        self.angles().1
    }

    /// The angle of its start about its centre ([`angle`]).
    pub fn start_angle(&self) -> f64 {
        self.angles().0
    }

    /// Where the arc starts and ends, and its centre.
    pub fn start(&self) -> Xz {
        self.start
    }

    pub fn end(&self) -> Xz {
        self.end
    }

    pub fn centre(&self) -> Xz {
        self.centre
    }

    /// Whether `point` lies in the sector, as [`angle_within`] decides it.
    pub fn contains(&self, point: Xz) -> bool {
        let answer = self.sides.inside(point);
        answer.unwrap_or_else(|| {
            let ((a0, total), a) = (self.angles(), angle(point, self.centre));
            let delta = if self.ccw { (a - a0).rem_euclid(TAU) } else { (a0 - a).rem_euclid(TAU) };
            delta <= total + 1e-12
        })
    }
}

/// How far inside or outside an arc's sweep, as the sine of the angle from the nearer end, a
/// point must lie for [`SweepSides`] to place it: far more than the rounding of [`angle`] and
/// [`sweep`] (a few 1e-16 radians), far less than any point measured lies from an end.
const CLEAR_OF_ENDS: f64 = 1e-8;

/// Whether points lie inside an arc's sweep as [`angle`] and [`sweep`] measure it (the
/// angle from the start, in the arc's sense, at most the sweep), told by cross products
/// without an arctangent wherever the answer is clear.
///
/// With u₀, u₁ and v the start, the end and the point about the centre, the cross product
/// u₀ × v taken in the arc's sense is |u₀||v| times the sine of the angle from u₀ to v:
/// positive where v lies less than half a turn past u₀. A sweep of less than half a turn
/// holds the points less than half a turn past its start *and* short of its end; one of
/// more than half a turn holds those less than half a turn past its start *or* short of its
/// end; near half a turn, the first test still holds only points inside. The rest of the
/// turn, outside the sweep, is told the same way with the ends swapped, where the sweep is
/// clearly more than none and less than a full turn (`sweep` makes a full circle of an arc
/// whose ends nearly meet). Each sine must exceed [`CLEAR_OF_ENDS`], so rounding cannot
/// turn the answer; a point nearer an end, or half a turn from one, is left to the angles.
#[derive(Debug, Clone, Copy)]
pub struct SweepSides {
    centre: Xz,
    /// u₀ and u₁, and their lengths.
    start: Xz,
    end: Xz,
    start_length: f64,
    end_length: f64,
    /// 1 counter-clockwise, −1 clockwise.
    sense: f64,
    /// Whether the sweep is more than half a turn, where it clearly is or is not.
    beyond_half_turn: Option<bool>,
    /// Both ends lie some finite distance from the centre.
    measurable: bool,
}

/// A length is positive and finite (NaN is neither).
fn measurable(length: f64) -> bool {
    length > 0.0 && length < f64::INFINITY
}

impl SweepSides {
    pub fn new(start: Xz, end: Xz, centre: Xz, ccw: bool) -> SweepSides {
        let origin = Xz::new(0.0, 0.0);
        let start = Xz::new(start.x - centre.x, start.z - centre.z);
        let end = Xz::new(end.x - centre.x, end.z - centre.z);
        let mut sides = SweepSides {
            centre,
            start,
            end,
            start_length: start.distance(origin),
            end_length: end.distance(origin),
            sense: if ccw { 1.0 } else { -1.0 },
            beyond_half_turn: None,
            measurable: false,
        };
        sides.measurable = measurable(sides.start_length) && measurable(sides.end_length);
        let ahead = sides.turn(start, end);
        let limit = sides.start_length * sides.end_length * CLEAR_OF_ENDS;
        sides.beyond_half_turn = if !(limit > 0.0 && limit.is_finite()) {
            None
        } else if ahead > limit {
            Some(false)
        } else if ahead < -limit {
            Some(true)
        } else {
            None
        };
        sides
    }

    /// The cross product a × b in the arc's sense: positive where b lies less than half a
    /// turn ahead of a.
    fn turn(&self, a: Xz, b: Xz) -> f64 {
        self.sense * (b.x * a.z - b.z * a.x)
    }

    /// Whether the sweep is more than half a turn, where it clearly is or is not (the sine of
    /// the sweep beyond [`CLEAR_OF_ENDS`] either way); `None` near none, half or a full turn.
    pub fn beyond_half_turn(&self) -> Option<bool> {
        self.beyond_half_turn
    }

    /// `Some(true)` where `p` lies clearly inside the sweep, `Some(false)` clearly outside,
    /// `None` where only the angles can tell (or the arc has no extent to tell it by).
    pub fn inside(&self, p: Xz) -> Option<bool> {
        self.inside_within(p, 0.0)
    }

    /// [`SweepSides::inside`] for every point within `slack` of `p` alike: `Some` only where
    /// all of them lie clearly on the one side.
    ///
    /// A point w within `slack` of v moves u × w from u × v by at most |u|·slack and |w|
    /// from |v| by at most `slack`, so u × v > |u|·(CLEAR_OF_ENDS·|v| + 2·slack) keeps
    /// u × w > CLEAR_OF_ENDS·|u|·|w|.
    pub fn inside_within(&self, p: Xz, slack: f64) -> Option<bool> {
        let v = Xz::new(p.x - self.centre.x, p.z - self.centre.z);
        let length = v.distance(Xz::new(0.0, 0.0));
        if !(self.measurable && measurable(length) && slack >= 0.0) {
            return None;
        }
        let margin = CLEAR_OF_ENDS * length + 2.0 * slack;
        // Past the start and short of it, the same cross product's two signs; so for the end.
        let from_start = self.turn(self.start, v);
        let from_end = self.turn(self.end, v);
        let (start, end) = (self.start_length * margin, self.end_length * margin);
        let (past_start, short_of_start) = (from_start > start, -from_start > start);
        let (past_end, short_of_end) = (from_end > end, -from_end > end);
        match self.beyond_half_turn {
            Some(true) if past_start || short_of_end => Some(true),
            Some(true) if past_end && short_of_start => Some(false),
            Some(false) if past_start && short_of_end => Some(true),
            Some(false) if past_end || short_of_start => Some(false),
            // Near half a turn (nearer none or a full turn nothing is clearly outside).
            None if past_start && short_of_end => Some(true),
            None if past_end && short_of_start && self.start.x * self.end.x + self.start.z * self.end.z < 0.0 => {
                Some(false)
            }
            _ => None,
        }
    }
}

/// The unit direction from `a` to `b` (zero for coincident points).
pub fn direction(a: Xz, b: Xz) -> Xz {
    let d = v(b) - v(a);
    let n = d.norm();
    if n < 1e-15 { Xz::default() } else { p(d / n) }
}

/// The unit normal to the left of the direction `a → b`, in the (Z, X) view.
pub fn left_normal(a: Xz, b: Xz) -> Xz {
    let d = direction(a, b);
    Xz::new(d.z, -d.x)
}

#[cfg(test)]
mod tests;
