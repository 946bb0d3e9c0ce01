//! The machine state an error depends on, sampled along a commanded path.
//!
//! Direction-dependent effects need each axis' last direction of motion and the travel
//! since it last reversed; wear needs the cut length of the tool; thermal effects the time.
//! A `Tracker` walks the commanded points in order and produces a `Sample` at each.
//! Before an axis has moved, its last direction is `+`: a machine starts from a reference
//! return, which on the lathes we model approaches in the positive direction.

use crate::toolpath::Xz;

/// Last direction of motion of each axis: `+1` or `-1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Signs {
    pub x: i8,
    pub z: i8,
}

/// Everything an effect may depend on at one commanded point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// The commanded tool reference point, mm, X as a radius.
    pub at: Xz,
    /// Minutes since the machine started.
    pub t_min: f64,
    /// Commanded velocity, mm/min (zero at rest).
    pub velocity: Xz,
    /// Each axis' last direction of motion (kept while it rests).
    pub direction: Signs,
    /// Travel of each axis since it last reversed, mm.
    pub since_reversal: Xz,
    /// Length the current tool has cut since it was set, m.
    pub cut_length_m: f64,
    /// Unit normal of the surface being cut, pointing from the part to the tool; zero when
    /// the move does not cut.
    pub normal: Xz,
    /// The tool's tip direction: imaginary tip − nose centre, in nose radii (`tip_vector`).
    pub tip: Xz,
}

impl Sample {
    /// A tool at rest at `at`, at time `t_min`, axes last moved in `+`.
    pub fn at_rest(at: Xz, t_min: f64) -> Sample {
        Sample {
            at,
            t_min,
            velocity: Xz::new(0.0, 0.0),
            direction: Signs { x: 1, z: 1 },
            since_reversal: Xz::new(f64::INFINITY, f64::INFINITY),
            cut_length_m: 0.0,
            normal: Xz::new(0.0, 0.0),
            tip: Xz::new(0.0, 0.0),
        }
    }
}

/// Moves below this (mm) do not change an axis' direction: rounding noise is no reversal.
const STILL_MM: f64 = 1e-9;

/// Follows the machine state along a commanded path.
#[derive(Debug, Clone)]
pub struct Tracker {
    at: Xz,
    direction: Signs,
    since_reversal: Xz,
    /// Cut length per tool (turret station), m: wear belongs to the tool, not the program.
    cut: Vec<(u16, f64)>,
}

impl Tracker {
    pub fn new(start: Xz) -> Tracker {
        Tracker {
            at: start,
            direction: Signs { x: 1, z: 1 },
            since_reversal: Xz::new(f64::INFINITY, f64::INFINITY),
            cut: Vec::new(),
        }
    }

    /// The commanded point the tracker stands at.
    pub fn position(&self) -> Xz {
        self.at
    }

    /// Move to `to`; `cutting` adds the travel to `tool`'s cut length.
    pub fn advance(&mut self, to: Xz, tool: u16, cutting: bool) {
        let (dx, dz) = (to.x - self.at.x, to.z - self.at.z);
        advance_axis(dx, &mut self.direction.x, &mut self.since_reversal.x);
        advance_axis(dz, &mut self.direction.z, &mut self.since_reversal.z);
        if cutting {
            let length_m = (dx * dx + dz * dz).sqrt() / 1000.0;
            match self.cut.iter_mut().find(|(t, _)| *t == tool) {
                Some((_, m)) => *m += length_m,
                None => self.cut.push((tool, length_m)),
            }
        }
        self.at = to;
    }

    /// The sample at the current point.
    pub fn sample(&self, t_min: f64, velocity: Xz, tool: u16, normal: Xz, tip: Xz) -> Sample {
        Sample {
            at: self.at,
            t_min,
            velocity,
            direction: self.direction,
            since_reversal: self.since_reversal,
            cut_length_m: self.cut.iter().find(|(t, _)| *t == tool).map_or(0.0, |(_, m)| *m),
            normal,
            tip,
        }
    }
}

fn advance_axis(delta: f64, direction: &mut i8, since: &mut f64) {
    if delta.abs() <= STILL_MM {
        return;
    }
    let sign = if delta > 0.0 { 1 } else { -1 };
    if sign == *direction {
        *since += delta.abs();
    } else {
        *direction = sign;
        *since = delta.abs();
    }
}
