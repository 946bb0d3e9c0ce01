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

use crate::toolpath::Xz;

fn v(p: Xz) -> Vector2<f64> {
    Vector2::new(p.z, p.x)
}

fn p(v: Vector2<f64>) -> Xz {
    Xz::new(v.y, v.x)
}

/// The angle of `point` about `centre` (radians, from +Z toward +X).
pub fn angle(point: Xz, centre: Xz) -> f64 {
    (point.x - centre.x).atan2(point.z - centre.z)
}

/// The point at `angle` on the circle of `radius` about `centre`.
pub fn on_circle(centre: Xz, radius: f64, angle: f64) -> Xz {
    Xz::new(centre.x + radius * angle.sin(), centre.z + radius * angle.cos())
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

/// [`sweep`] when the angles of `start` (`a0`) and `end` (`a1`) about the centre are known.
pub fn sweep_from_angles(start: Xz, end: Xz, a0: f64, a1: f64, ccw: bool) -> f64 {
    let raw = if ccw { a1 - a0 } else { a0 - a1 };
    let mut s = raw.rem_euclid(TAU);
    // A chord shorter than a nanometre is a full circle, not an empty arc.
    if s < 1e-12 || (start.distance(end) < 1e-9 && s > TAU - 1e-9) {
        s = TAU;
    }
    s
}

pub fn arc_length(start: Xz, end: Xz, centre: Xz, ccw: bool) -> f64 {
    start.distance(centre) * sweep(start, end, centre, ccw)
}

/// The points where an arc is furthest along ±X and ±Z (inside its sweep), for limit checks.
pub fn arc_extremes(start: Xz, end: Xz, centre: Xz, ccw: bool) -> Vec<Xz> {
    let radius = start.distance(centre);
    let a0 = angle(start, centre);
    let total = sweep(start, end, centre, ccw);
    let mut out = Vec::new();
    for k in 0..4 {
        let target = k as f64 * PI / 2.0;
        let delta = if ccw { (target - a0).rem_euclid(TAU) } else { (a0 - target).rem_euclid(TAU) };
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
    let delta = if ccw { (a - a0).rem_euclid(TAU) } else { (a0 - a).rem_euclid(TAU) };
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
    centre: Xz,
    ccw: bool,
    /// The angle it sweeps ([`sweep`]).
    total: f64,
}

impl Sector {
    pub fn new(start: Xz, end: Xz, centre: Xz, ccw: bool) -> Sector {
        Sector {
            sides: SweepSides::new(start, end, centre, ccw),
            start,
            centre,
            ccw,
            total: sweep(start, end, centre, ccw),
        }
    }

    /// The angle the sector sweeps, radians.
    pub fn total(&self) -> f64 {
        self.total
    }

    /// Whether `point` lies in the sector, as [`angle_within`] decides it.
    pub fn contains(&self, point: Xz) -> bool {
        // Away from half and whole turns the sweep's size is certain, and the cross products
        // then answer for points all round the circle.
        const MARGIN: f64 = 1e-6;
        let answer = if self.total < PI - MARGIN {
            self.sides.inside_given_half(point, true)
        } else if self.total > PI + MARGIN && self.total < TAU - MARGIN {
            self.sides.inside_given_half(point, false)
        } else {
            self.sides.inside(point)
        };
        answer.unwrap_or_else(|| {
            let (a0, a) = (angle(self.start, self.centre), angle(point, self.centre));
            let delta = if self.ccw { (a - a0).rem_euclid(TAU) } else { (a0 - a).rem_euclid(TAU) };
            delta <= self.total + 1e-12
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
/// u₀ × v taken in the arc's sense is |u₀||v| times the sine of the angle from u₀ to v. Both
/// u₀ × v > 0 and v × u₁ > 0 put v less than half a turn past the start and less than half a
/// turn short of the end, which is inside the sweep whatever its size. Both u₁ × v > 0 and
/// v × u₀ > 0 put it inside the rest of the turn, outside the sweep, where the sweep is
/// clear of none and of a full turn (`sweep` makes a full circle of an arc whose ends
/// nearly meet). Each sine must exceed [`CLEAR_OF_ENDS`], so rounding cannot turn the
/// answer; a point nearer an end, or a half-turn away from one, is left to the angles.
#[derive(Debug, Clone, Copy)]
pub struct SweepSides {
    centre: Xz,
    /// u₀ and u₁.
    start: Xz,
    end: Xz,
    /// 1 counter-clockwise, −1 clockwise.
    sense: f64,
    /// CLEAR_OF_ENDS² |u₀|² and CLEAR_OF_ENDS² |u₁|², to compare squared cross products with.
    start_limit: f64,
    end_limit: f64,
    /// The sweep is clear of none and of a full turn.
    proper: bool,
}

impl SweepSides {
    pub fn new(start: Xz, end: Xz, centre: Xz, ccw: bool) -> SweepSides {
        let start = Xz::new(start.x - centre.x, start.z - centre.z);
        let end = Xz::new(end.x - centre.x, end.z - centre.z);
        let clear2 = CLEAR_OF_ENDS * CLEAR_OF_ENDS;
        let mut sides = SweepSides {
            centre,
            start,
            end,
            sense: if ccw { 1.0 } else { -1.0 },
            start_limit: clear2 * (start.x * start.x + start.z * start.z),
            end_limit: clear2 * (end.x * end.x + end.z * end.z),
            proper: false,
        };
        let (ahead, behind) = (sides.turn(start, end), sides.turn(end, start));
        let limit = sides.start_limit * (end.x * end.x + end.z * end.z);
        sides.proper =
            Self::clear(ahead, limit) || Self::clear(behind, limit) || start.x * end.x + start.z * end.z < 0.0;
        sides
    }

    /// The cross product a × b in the arc's sense: positive where b lies less than half a
    /// turn ahead of a.
    fn turn(&self, a: Xz, b: Xz) -> f64 {
        self.sense * (b.x * a.z - b.z * a.x)
    }

    /// Whether a cross product is positive by more than its limit (squared).
    fn clear(cross: f64, limit: f64) -> bool {
        cross > 0.0 && cross * cross > limit
    }

    /// `Some(true)` where `p` lies clearly inside the sweep, `Some(false)` clearly outside,
    /// `None` where only the angles can tell (or the arc has no extent to tell it by).
    pub fn inside(&self, p: Xz) -> Option<bool> {
        let (from_start, to_end) = self.turns(p)?;
        if from_start.clear_ahead() && to_end.clear_ahead() {
            return Some(true);
        }
        if self.proper && to_end.clear_behind() && from_start.clear_behind() {
            return Some(false);
        }
        None
    }

    /// [`SweepSides::inside`] for a sweep known to be less than half a turn (`Some(true)`)
    /// or more (`Some(false)`), which also answers for the points more than half a turn
    /// from an end: with less than half a turn, a point clearly behind the start or clearly
    /// past the end is outside; with more, a point clearly ahead of the start or clearly
    /// short of the end is inside.
    pub fn inside_given_half(&self, p: Xz, less_than_half: bool) -> Option<bool> {
        let (from_start, to_end) = self.turns(p)?;
        let both_ahead = from_start.clear_ahead() && to_end.clear_ahead();
        let both_behind = from_start.clear_behind() && to_end.clear_behind();
        let one_ahead = from_start.clear_ahead() || to_end.clear_ahead();
        let one_behind = from_start.clear_behind() || to_end.clear_behind();
        match less_than_half {
            true if both_ahead => Some(true),
            true if one_behind => Some(false),
            false if both_behind => Some(false),
            false if one_ahead => Some(true),
            _ => None,
        }
    }

    /// The turns from the start to `p` and from `p` to the end, with their limits; `None`
    /// where they cannot be told (a point at the centre, an arc without extent, overflow).
    fn turns(&self, p: Xz) -> Option<(Turn, Turn)> {
        let v = Xz::new(p.x - self.centre.x, p.z - self.centre.z);
        let length2 = v.x * v.x + v.z * v.z;
        if !(length2 > 0.0 && length2.is_finite() && self.start_limit > 0.0 && self.end_limit > 0.0) {
            return None;
        }
        let (start_limit, end_limit) = (self.start_limit * length2, self.end_limit * length2);
        if !(start_limit.is_finite() && end_limit.is_finite()) {
            return None;
        }
        Some((
            Turn { cross: self.turn(self.start, v), limit: start_limit },
            Turn { cross: self.turn(v, self.end), limit: end_limit },
        ))
    }
}

/// A cross product in an arc's sense and the square it must exceed to tell its sign.
#[derive(Debug, Clone, Copy)]
struct Turn {
    cross: f64,
    limit: f64,
}

impl Turn {
    /// Clearly less than half a turn ahead.
    fn clear_ahead(self) -> bool {
        SweepSides::clear(self.cross, self.limit)
    }

    /// Clearly less than half a turn behind.
    fn clear_behind(self) -> bool {
        SweepSides::clear(-self.cross, self.limit)
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
