//! Sampling a toolpath for the error model: points along every move with the state an
//! effect needs (time, velocity, tool, whether it cuts, the surface normal, the tip).
//!
//! Cutting moves (feeds and arcs) are sampled every `step` mm or closer; a rapid only at
//! its end, where the next cut starts (what the tool does between is not on the part);
//! a dwell not at all. The toolpath's start is the machine's position before the program
//! and is not a sample: nothing commands it.

use std::ops::Range;

use crate::geometry;
use crate::semantic::nose_radius::{ToolTable, tip_vector};
use crate::toolpath::{Compensation, Motion, Move, Toolpath, Xz};

/// One point of the nominal path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathSample {
    /// The move it lies on, and where along it (0 at the start, 1 at the end).
    pub move_index: usize,
    pub param: f64,
    /// The nominal tool reference point, mm, X as a radius.
    pub nominal: Xz,
    /// Seconds since the program started.
    pub t_s: f64,
    /// Commanded velocity, mm/min.
    pub velocity: Xz,
    pub tool: u16,
    pub cutting: bool,
    /// Unit normal from the part toward the tool (zero when not cutting).
    pub normal: Xz,
    /// The tool's tip direction (nose radii).
    pub tip: Xz,
}

/// Sample every move of `toolpath`; cutting moves at most `step` mm apart.
pub fn sample_toolpath(toolpath: &Toolpath, tools: &ToolTable, step: f64) -> Vec<PathSample> {
    let mut out = Vec::with_capacity(toolpath.moves.len() * 2);
    sample_moves(toolpath, 0..toolpath.moves.len(), tools, step, &mut out);
    out
}

/// Sample the moves `moves` of `toolpath` as `sample_toolpath` does, appending to `out`.
pub fn sample_moves(toolpath: &Toolpath, moves: Range<usize>, tools: &ToolTable, step: f64, out: &mut Vec<PathSample>) {
    let step = if step.is_finite() && step > 0.0 { step } else { 0.254 };
    let first = moves.start;
    for (index, m) in toolpath.moves.get(moves).unwrap_or_default().iter().enumerate() {
        let index = first + index;
        let start = toolpath.start_of(index);
        let (_, tip) = tools.lookup(m.tool, m.offset);
        let tip = tip_vector(tip);
        match m.motion {
            Motion::Dwell => {}
            Motion::Rapid => out.push(sample(index, m, 1.0, m.end, Xz::new(0.0, 0.0), false, tip)),
            Motion::Feed => {
                let length = start.distance(m.end);
                let n = (length / step).ceil().max(1.0) as usize;
                let direction = unit(Xz::new(m.end.x - start.x, m.end.z - start.z));
                let velocity = Xz::new(direction.x * m.feed, direction.z * m.feed);
                let normal = if m.cutting { surface_normal(direction, m, tip) } else { Xz::new(0.0, 0.0) };
                for i in 1..=n {
                    let t = i as f64 / n as f64;
                    let p = Xz::new(start.x + (m.end.x - start.x) * t, start.z + (m.end.z - start.z) * t);
                    out.push(PathSample { velocity, ..sample(index, m, t, p, normal, m.cutting, tip) });
                }
            }
            Motion::Cw | Motion::Ccw => {
                let ccw = m.motion == Motion::Ccw;
                let radius = start.distance(m.centre);
                let sweep = geometry::sweep(start, m.end, m.centre, ccw);
                let a0 = geometry::angle(start, m.centre);
                let sign = if ccw { 1.0 } else { -1.0 };
                let n = (radius * sweep / step).ceil().max(2.0) as usize;
                for i in 1..=n {
                    let t = i as f64 / n as f64;
                    let angle = a0 + sign * sweep * t;
                    let p = if i == n { m.end } else { geometry::on_circle(m.centre, radius, angle) };
                    // The tangent of increasing angle is (cos, −sin) in (x, z).
                    let tangent = Xz::new(sign * angle.cos(), -sign * angle.sin());
                    let velocity = Xz::new(tangent.x * m.feed, tangent.z * m.feed);
                    let normal = if m.cutting { surface_normal(tangent, m, tip) } else { Xz::new(0.0, 0.0) };
                    out.push(PathSample { velocity, ..sample(index, m, t, p, normal, m.cutting, tip) });
                }
            }
        }
    }
}

fn sample(index: usize, m: &Move, t: f64, p: Xz, normal: Xz, cutting: bool, tip: Xz) -> PathSample {
    PathSample {
        move_index: index,
        param: t,
        nominal: p,
        t_s: m.t_start + (m.t_end - m.t_start) * t,
        velocity: Xz::new(0.0, 0.0),
        tool: m.tool,
        cutting,
        normal,
        tip,
    }
}

fn unit(v: Xz) -> Xz {
    let length = (v.x * v.x + v.z * v.z).sqrt();
    if length > 0.0 { Xz::new(v.x / length, v.z / length) } else { Xz::new(0.0, 0.0) }
}

/// The normal of the cut surface, pointing to the tool: to the left of the direction of
/// travel under `G41`, to the right under `G42`; without compensation, the side the tool's
/// body is on (opposite its tip direction); none for a tool with no tip direction.
pub(crate) fn surface_normal(direction: Xz, m: &Move, tip: Xz) -> Xz {
    // The left normal of (x, z) travel, seen with Z to the right and X up.
    let left = Xz::new(direction.z, -direction.x);
    let right = Xz::new(-left.x, -left.z);
    match m.compensation {
        Compensation::Left => left,
        Compensation::Right => right,
        Compensation::Off => {
            let body = Xz::new(-tip.x, -tip.z);
            let side = left.x * body.x + left.z * body.z;
            if side > 1e-9 {
                left
            } else if side < -1e-9 {
                right
            } else {
                Xz::new(0.0, 0.0)
            }
        }
    }
}
