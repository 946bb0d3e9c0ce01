//! Where a reversing slide's command reaches the far side of its play along a move: the
//! knee of a backlash take-up, in closed form.
//!
//! Between two points measured along a move each axis moves one way (an arc's extremes in X
//! and Z are samples), so the command's coordinate on that axis crosses a given value once.
//! On a line the coordinate is linear in the move's parameter; on an arc it is the centre's
//! plus the radius times the sine (X) or cosine (Z) of the angle, linear in the parameter,
//! so the crossing is an arcsine (an arccosine for Z) brought into the stretch's angles.

use crate::toolpath::Motion;

/// The axis a take-up is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    X,
    Z,
}

/// What `crossing` needs of a move: a line from `start` to `end`, or an arc about `centre`
/// of `radius` from `start_angle` through `sweep` (radians, positive) in its own sense.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Path {
    pub motion: Motion,
    pub start: crate::toolpath::Xz,
    pub end: crate::toolpath::Xz,
    pub centre: crate::toolpath::Xz,
    pub radius: f64,
    pub start_angle: f64,
    pub sweep: f64,
}

impl Path {
    /// The command's coordinate on `axis` at parameter `t` (as `sampling::sample_view_at`
    /// places the point).
    pub fn coordinate(&self, axis: Axis, t: f64) -> f64 {
        let t = t.clamp(0.0, 1.0);
        match self.motion {
            Motion::Cw | Motion::Ccw => {
                let angle = self.angle_at(t);
                match axis {
                    Axis::X => self.centre.x + self.radius * angle.sin(),
                    Axis::Z => self.centre.z + self.radius * angle.cos(),
                }
            }
            _ => match axis {
                Axis::X => self.start.x + (self.end.x - self.start.x) * t,
                Axis::Z => self.start.z + (self.end.z - self.start.z) * t,
            },
        }
    }

    fn sign(&self) -> f64 {
        if self.motion == Motion::Ccw { 1.0 } else { -1.0 }
    }

    fn angle_at(&self, t: f64) -> f64 {
        self.start_angle + self.sign() * self.sweep * t
    }
}

/// The parameter in `[from, to]` where the coordinate on `axis` reaches `edge`, the
/// coordinate moving one way across the stretch; `None` where it does not cross there (or
/// the move has no extent). The answer is the exact crossing up to rounding: the caller
/// checks which side of the edge the point it makes of it lies on.
pub fn crossing(path: &Path, axis: Axis, edge: f64, from: f64, to: f64) -> Option<f64> {
    // A stretch running back, or not a number, has no crossing.
    if from.partial_cmp(&to).is_none_or(|order| order.is_gt()) {
        return None;
    }
    let t = match path.motion {
        Motion::Cw | Motion::Ccw => {
            if !(path.radius > 0.0 && path.sweep > 0.0) {
                return None;
            }
            // sin(angle) = v for X, cos(angle) = v for Z.
            let offset = match axis {
                Axis::X => edge - path.centre.x,
                Axis::Z => edge - path.centre.z,
            };
            let v = (offset / path.radius).clamp(-1.0, 1.0);
            let (low, high) = (path.angle_at(from), path.angle_at(to));
            let (low, high) = (low.min(high), low.max(high));
            let middle = (low + high) / 2.0;
            let roots = match axis {
                Axis::X => [v.asin(), std::f64::consts::PI - v.asin()],
                Axis::Z => [v.acos(), -v.acos()],
            };
            // Each root's turn nearest the stretch; the stretch is less than half a turn
            // (an axis moves one way along it), so at most one lies in it.
            let slack = 1e-9 * (1.0 + high - low);
            let angle = roots
                .into_iter()
                .map(|root| root + std::f64::consts::TAU * ((middle - root) / std::f64::consts::TAU).round())
                .filter(|angle| *angle >= low - slack && *angle <= high + slack)
                .min_by(|a, b| (a - middle).abs().total_cmp(&(b - middle).abs()))?;
            (angle - path.start_angle) / (path.sign() * path.sweep)
        }
        _ => {
            let (a, b) = match axis {
                Axis::X => (path.start.x, path.end.x),
                Axis::Z => (path.start.z, path.end.z),
            };
            if a == b {
                return None;
            }
            (edge - a) / (b - a)
        }
    };
    t.is_finite().then(|| t.clamp(from, to))
}

/// The reference of `crossing`: halving `[from, to]` 48 times, as the take-up's knee was
/// found before it was solved for. The first point found past the edge (`past`).
#[cfg(test)]
pub fn crossing_by_halving(path: &Path, axis: Axis, edge: f64, direction: f64, from: f64, to: f64) -> Option<f64> {
    let past = |t: f64| (path.coordinate(axis, t) - edge) * direction >= 0.0;
    if past(from) || !past(to) {
        return None;
    }
    let (mut low, mut high) = (from, to);
    for _ in 0..48 {
        let middle = (low + high) / 2.0;
        if past(middle) { high = middle } else { low = middle }
    }
    Some(high)
}

/// The knee of a take-up on `axis` along `path` between the parameters `from` and `to`: the
/// first point where the command is past `edge` in `direction` (+1 or −1), when it is not
/// at `from` and is at `to`; `crossing`, moved on to the first point past the edge where
/// rounding left it a hair short.
pub fn knee(path: &Path, axis: Axis, edge: f64, direction: f64, from: f64, to: f64) -> Option<f64> {
    let past = |t: f64| (path.coordinate(axis, t) - edge) * direction >= 0.0;
    if past(from) || !past(to) {
        return None;
    }
    let t = crossing(path, axis, edge, from, to).unwrap_or(from);
    if past(t) {
        return Some(t);
    }
    // Short of the edge by rounding (or no closed form): halve what is left.
    let (mut low, mut high) = (t, to);
    for _ in 0..64 {
        let middle = (low + high) / 2.0;
        if middle <= low || middle >= high {
            break;
        }
        if past(middle) { high = middle } else { low = middle }
    }
    Some(high)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::on_circle;
    use crate::toolpath::Xz;
    use proptest::prelude::*;

    /// A line from `a` to `b`.
    fn line(a: Xz, b: Xz) -> Path {
        Path {
            motion: Motion::Feed,
            start: a,
            end: b,
            centre: Xz::default(),
            radius: 0.0,
            start_angle: 0.0,
            sweep: 0.0,
        }
    }

    /// The knee found in closed form is the one halving finds, to far less than a nanometre
    /// along any move a lathe makes, and it lies past the edge.
    fn agrees(path: &Path, axis: Axis, fraction: f64, from: f64, to: f64) -> Result<(), TestCaseError> {
        let (a, b) = (path.coordinate(axis, from), path.coordinate(axis, to));
        prop_assume!((a - b).abs() > 1e-9);
        let direction = (b - a).signum();
        let edge = a + (b - a) * fraction;
        let halved = crossing_by_halving(path, axis, edge, direction, from, to);
        let solved = knee(path, axis, edge, direction, from, to);
        // Along the move the two are within a hair of the stretch (halving stops at 2⁻⁴⁸ of
        // it), a few roundings of the angle, and the rounding of the coordinate itself
        // carried back to the parameter: a few ulps of a coordinate far from zero, over how
        // fast the coordinate moves (a 0.01 mm move at Z−227 puts the knee's parameter
        // only to about 1e-11).
        let rate = (b - a).abs() / (to - from);
        let rounding = 8.0 * f64::EPSILON * a.abs().max(b.abs()).max(edge.abs()).max(1.0) / rate;
        let within = (to - from) * 1e-13 + 1e-12 + rounding;
        match (halved, solved) {
            (Some(h), Some(s)) => {
                prop_assert!((path.coordinate(axis, s) - edge) * direction >= 0.0, "{s} not past {edge}");
                // The closed form itself, not its halving where rounding left it short.
                let closed = crossing(path, axis, edge, from, to);
                prop_assert!(closed.is_some_and(|c| (h - c).abs() <= within), "{closed:?}, {h}");
                prop_assert!((h - s).abs() <= within, "halving {h}, solved {s}");
            }
            (None, None) => {}
            (h, s) => prop_assert!(false, "halving {h:?}, solved {s:?}"),
        }
        Ok(())
    }

    /// A short move far from zero, where the coordinate's rounding, not the closed form,
    /// sets how near the two knees are (1.1e-12 apart here, above a fixed 1e-12).
    #[test]
    fn a_knee_on_a_short_move_far_from_zero() {
        let path = line(Xz::new(0.0, -227.1157691587802), Xz::new(0.0, -227.1157691587802 + 0.012602762401475122));
        agrees(&path, Axis::Z, 0.6672282458126508, 0.0, 0.2092283446466154).unwrap();
    }

    proptest! {
        #[test]
        fn a_knee_on_a_line_is_where_halving_finds_it(
            x0 in -150.0f64..150.0, z0 in -300.0f64..10.0, dx in -20.0f64..20.0, dz in -20.0f64..20.0,
            from in 0.0f64..0.5, length in 0.0f64..0.5, fraction in 0.0f64..1.0, x_axis: bool,
        ) {
            let path = line(Xz::new(x0, z0), Xz::new(x0 + dx, z0 + dz));
            let axis = if x_axis { Axis::X } else { Axis::Z };
            agrees(&path, axis, fraction, from, from + length)?;
        }

        /// On an arc the stretch lies in one quarter of a turn (an axis moves one way along
        /// it: an arc's extremes are samples).
        #[test]
        fn a_knee_on_an_arc_is_where_halving_finds_it(
            cx in -150.0f64..150.0, cz in -300.0f64..10.0, radius in 0.05f64..200.0, quarter in 0i32..8,
            inside in 0.0f64..1.0, span in 0.0f64..1.0, before in 0.0f64..3.0, after in 0.0f64..3.0,
            fraction in 0.0f64..1.0, ccw: bool, x_axis: bool,
        ) {
            let quarter_turn = std::f64::consts::FRAC_PI_2;
            // The stretch, as angles, inside the quarter; the move sweeps on either side of it.
            let low = f64::from(quarter - 4) * quarter_turn + inside * quarter_turn * (1.0 - span);
            let high = low + span * quarter_turn * (1.0 - inside).max(0.0);
            let (first, last) = if ccw { (low, high) } else { (high, low) };
            let sweep = (high - low) + before + after;
            let sign = if ccw { 1.0 } else { -1.0 };
            let start_angle = first - sign * before;
            let centre = Xz::new(cx, cz);
            let path = Path {
                motion: if ccw { Motion::Ccw } else { Motion::Cw },
                start: on_circle(centre, radius, start_angle),
                end: on_circle(centre, radius, start_angle + sign * sweep),
                centre,
                radius,
                start_angle,
                sweep,
            };
            prop_assume!(sweep > 1e-6);
            let (from, to) = ((first - start_angle) * sign / sweep, (last - start_angle) * sign / sweep);
            let axis = if x_axis { Axis::X } else { Axis::Z };
            agrees(&path, axis, fraction, from, to)?;
        }
    }
}
