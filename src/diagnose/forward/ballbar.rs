//! Ball bar traces on the program's test circles.
//!
//! The test circles are the program's full circles (`G02`/`G03` with `I K` that end where
//! they start). The trace's rows follow the program: each run of rows in one direction
//! lies on the next test circle, and a new circle begins where the travel from the
//! circle's start angle wraps round (a second circle run the same way) or the direction
//! changes. A row's place on its circle is the travel from the circle's start in the
//! direction of motion.
//!
//! A ball bar cuts nothing: the moves are taken as not cutting, so the tool's wear and the
//! surface normal play no part.

use std::f64::consts::{PI, TAU};

use super::{Forward, ForwardError, Nominal, Place, Point, Projection, SetupTerms, split_and_sample};
use crate::diagnose::measured::{BallBarRow, Direction, Kind};
use crate::geometry;
use crate::toolpath::{Motion, Xz};

/// A full circle of the program.
#[derive(Debug, Clone, Copy)]
struct Circle {
    index: usize,
    centre: Xz,
    radius: f64,
    ccw: bool,
    /// The angle the circle starts (and ends) at.
    start_angle: f64,
    line: usize,
}

impl Circle {
    /// The travel from the circle's start to `angle` in its direction, in `[0, 2π)`.
    fn travel(&self, angle: f64) -> f64 {
        let raw = if self.ccw { angle - self.start_angle } else { self.start_angle - angle };
        let travel = raw.rem_euclid(TAU);
        // An angle a rounding short of the start is the start.
        if TAU - travel < 1e-9 || travel < 1e-12 { 0.0 } else { travel }
    }

    fn direction(&self) -> Direction {
        if self.ccw { Direction::Ccw } else { Direction::Cw }
    }
}

/// The program's test circles, in order: each one's direction and start angle (degrees
/// from +Z toward +X), for synthesising a trace.
pub(crate) fn test_circles(nominal: &Nominal) -> Vec<(Direction, f64)> {
    circles(nominal).iter().map(|c| (c.direction(), c.start_angle.to_degrees())).collect()
}

/// The radius of the smallest test circle of the program, mm.
pub(crate) fn smallest_radius(nominal: &Nominal) -> Option<f64> {
    circles(nominal).iter().map(|c| c.radius).reduce(f64::min)
}

fn circles(nominal: &Nominal) -> Vec<Circle> {
    let path = &nominal.toolpath;
    path.moves
        .iter()
        .enumerate()
        .filter_map(|(index, m)| {
            let start = path.start_of(index);
            (m.is_arc() && start.distance(m.end) < 1e-6).then(|| Circle {
                index,
                centre: m.centre,
                radius: start.distance(m.centre),
                ccw: m.motion == Motion::Ccw,
                start_angle: geometry::angle(start, m.centre),
                line: nominal.move_lines.get(index).copied().unwrap_or(0),
            })
        })
        .collect()
}

pub(super) fn forward(nominal: &Nominal, rows: &[BallBarRow]) -> Result<Forward, ForwardError> {
    let circles = circles(nominal);
    if circles.is_empty() {
        return Err(ForwardError::NoTestCircle);
    }
    // Rows to circles, in order.
    let mut current: Option<usize> = None;
    let mut last_travel = 0.0;
    let mut on_circle = Vec::with_capacity(rows.len());
    for row in rows {
        let angle = row.angle_deg.to_radians();
        // Back at the start angle after most of a turn: the end of the circle (which is
        // also where the next one would start; the place is the same).
        let closing = current.is_some_and(|k| {
            let c = &circles[k];
            c.direction() == row.direction && c.travel(angle) == 0.0 && last_travel > PI
        });
        if closing {
            last_travel = TAU;
            on_circle.push((current.unwrap_or(0), TAU));
            continue;
        }
        let same = current.is_some_and(|k| {
            let c = &circles[k];
            c.direction() == row.direction && c.travel(angle) > last_travel - PI
        });
        if !same {
            let next = current.map_or(0, |k| k + 1);
            let Some(circle) = circles.get(next) else {
                return Err(ForwardError::NoCircleLeft {
                    line: row.line,
                    found: row.direction.name(),
                    circles: circles.len(),
                });
            };
            if circle.direction() != row.direction {
                return Err(ForwardError::DirectionMismatch {
                    line: row.line,
                    found: row.direction.name(),
                    expected: circle.direction().name(),
                    circle_line: circle.line,
                });
            }
            current = Some(next);
        }
        let k = current.unwrap_or(0);
        last_travel = circles[k].travel(angle);
        on_circle.push((k, last_travel));
    }

    // One set-up (centring and length) per distinct circle: the same bar on the same
    // centre keeps its set-up over all its runs.
    let mut groups: Vec<(Xz, f64)> = Vec::new();
    let mut group_of = Vec::with_capacity(circles.len());
    for c in &circles {
        let found =
            groups.iter().position(|(centre, r)| centre.distance(c.centre) < 1e-6 && (r - c.radius).abs() < 1e-6);
        group_of.push(found.unwrap_or_else(|| {
            groups.push((c.centre, c.radius));
            groups.len() - 1
        }));
    }

    let mut path = nominal.toolpath.clone();
    for m in &mut path.moves {
        m.cutting = false;
    }
    let places: Vec<Place> =
        on_circle.iter().map(|&(k, travel)| Place { index: circles[k].index, param: travel / TAU }).collect();
    let (samples, sample_of) = split_and_sample(&path, &nominal.tools, &places);
    let points = rows
        .iter()
        .zip(&on_circle)
        .zip(sample_of)
        .map(|((row, &(k, _)), sample)| {
            let c = &circles[k];
            Point {
                run: 0,
                sample,
                projection: Projection::Radial { centre: c.centre, radius: c.radius },
                measured: row.deviation_mm,
                line: c.line,
                nominal: geometry::on_circle(c.centre, c.radius, row.angle_deg.to_radians()),
                angle_deg: Some(row.angle_deg),
                direction: Some(row.direction),
                group: group_of[k],
            }
        })
        .collect();
    let groups: Vec<String> =
        groups.iter().map(|(centre, r)| format!("circle R{r:.3} about x {:.3} z {:.3}", centre.x, centre.z)).collect();
    Ok(Forward {
        kind: Kind::BallBar,
        samples,
        start: path.start,
        runs: vec![None],
        duration_s: path.duration(),
        points,
        setup: vec![SetupTerms::LengthAndCentring; groups.len()],
        groups,
    })
}
