//! CMM points on the finished surface.
//!
//! The finished surface is the contour of the finishing passes (the programmed contour,
//! which the nose touches; the tool reference point runs offset from it under `G41`/`G42`).
//! Each point is matched to the closest point of that contour; where passes overlap (a
//! finishing cycle run again by a second tool), the last pass over the place made the
//! surface. A program with no finishing pass is matched against all its cuts.
//!
//! The matched contour point `q` with its normal `n` (from the part toward the tool) gives
//! the measured reading `(p − q) · n`, and the place on the tool reference path: the nose
//! centre is `q + r n` and the reference point `r · tip` from it.

use super::{Forward, ForwardError, Nominal, Place, Point, Projection, SetupTerms, param_on, split_and_sample};
use crate::diagnose::measured::{Kind, ProfilePoint};
use crate::error_model::sampling::surface_normal;
use crate::geometry;
use crate::semantic::nose_radius::tip_vector;
use crate::toolpath::{Compensation, Motion, Xz};

/// Passes closer than this (mm) over the same place are the same surface: the later one
/// finished it.
const SAME_SURFACE_MM: f64 = 1e-4;

/// A CMM point farther than this (mm) from every finished surface is not on this part.
pub const MAX_DISTANCE_MM: f64 = 1.0;

/// One finishing move's contour.
#[derive(Debug, Clone, Copy)]
struct Surface {
    index: usize,
    start: Xz,
    end: Xz,
    /// Arcs: the contour's centre and direction.
    arc: Option<(Xz, bool)>,
    /// The nose radius and tip vector the reference point is offset by (zero without
    /// compensation).
    nose: f64,
    tip: Xz,
}

impl Surface {
    /// The closest point to `p`, its distance and the tangent of travel there.
    fn closest(&self, p: Xz) -> (Xz, f64, Xz) {
        match self.arc {
            None => {
                let q = {
                    let (dx, dz) = (self.end.x - self.start.x, self.end.z - self.start.z);
                    let length2 = dx * dx + dz * dz;
                    let t = (((p.x - self.start.x) * dx + (p.z - self.start.z) * dz) / length2).clamp(0.0, 1.0);
                    Xz::new(self.start.x + dx * t, self.start.z + dz * t)
                };
                (q, q.distance(p), geometry::direction(self.start, self.end))
            }
            Some((centre, ccw)) => {
                let radius = self.start.distance(centre);
                let q = if geometry::angle_within(p, self.start, self.end, centre, ccw) {
                    geometry::on_circle(centre, radius, geometry::angle(p, centre))
                } else if p.distance(self.start) <= p.distance(self.end) {
                    self.start
                } else {
                    self.end
                };
                let a = geometry::angle(q, centre);
                let sign = if ccw { 1.0 } else { -1.0 };
                (q, q.distance(p), Xz::new(sign * a.cos(), -sign * a.sin()))
            }
        }
    }
}

fn surfaces(nominal: &Nominal, purpose: Use) -> Vec<Surface> {
    let path = &nominal.toolpath;
    let make = |index: usize| -> Option<Surface> {
        let m = path.moves.get(index)?;
        if !m.cutting || !matches!(m.motion, Motion::Feed | Motion::Cw | Motion::Ccw) {
            return None;
        }
        let start = if index == 0 { path.start } else { path.moves[index - 1].contour };
        let (radius, tip) = nominal.tools.lookup(m.tool, m.offset);
        let (nose, tip) = if m.compensation != Compensation::Off && radius > 0.0 {
            (radius, tip_vector(tip))
        } else {
            (0.0, Xz::default())
        };
        let arc = m
            .is_arc()
            .then(|| (Xz::new(m.centre.x - nose * tip.x, m.centre.z - nose * tip.z), m.motion == Motion::Ccw));
        (start.distance(m.contour) > 1e-9).then_some(Surface { index, start, end: m.contour, arc, nose, tip })
    };
    let finishing: Vec<Surface> = nominal.finishing.iter().flat_map(|r| r.clone()).filter_map(make).collect();
    if !finishing.is_empty() {
        return finishing;
    }
    // No finishing pass: every cut is a surface. Only where the surface is sampled, the move
    // that brings the tool from the air to a run of cuts is left out (see `approaches`).
    let approaches = if purpose == Use::Sampling { approaches(path) } else { Vec::new() };
    (0..path.moves.len()).filter(|i| !approaches.contains(i)).filter_map(make).collect()
}

/// What the surfaces are for: matching measured points (every surface a point may be on), or
/// sampling points for `synth` (only where the part surely is).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Use {
    Matching,
    Sampling,
}

/// The approaches of a program with no finishing pass: in each run of two or more cuts
/// that starts after a rapid (or at the start), the first one. A rapid ends in the air, so
/// that move starts in the air and ends where the next cut goes on: the lead-in to the
/// contour (`G01 Z0` from `Z2`). Where a run's first cut is itself part of the contour (a
/// turning cut started in front of the part), nothing in the program says where the
/// material begins along it, so it is left out of the sampling as well.
fn approaches(path: &crate::toolpath::Toolpath) -> Vec<usize> {
    let cut =
        |i: usize| path.moves[i].cutting && matches!(path.moves[i].motion, Motion::Feed | Motion::Cw | Motion::Ccw);
    (0..path.moves.len())
        .filter(|&i| cut(i) && (i == 0 || !cut(i - 1)) && i + 1 < path.moves.len() && cut(i + 1))
        .collect()
}

/// Points on the finished surface every `spacing` mm along each finishing move, at least
/// half a spacing from its ends, each on the surface the program finishes last there: for
/// synthesising a CMM profile.
pub(crate) fn surface_points(nominal: &Nominal, spacing: f64) -> Vec<Xz> {
    let surfaces = surfaces(nominal, Use::Sampling);
    let spacing = if spacing.is_finite() && spacing > 0.0 { spacing } else { 0.5 };
    let mut out = Vec::new();
    for (k, s) in surfaces.iter().enumerate() {
        let (length, at): (f64, Box<dyn Fn(f64) -> Xz>) = match s.arc {
            None => {
                let (start, end) = (s.start, s.end);
                (
                    start.distance(end),
                    Box::new(move |d: f64| {
                        let t = d / start.distance(end);
                        Xz::new(start.x + (end.x - start.x) * t, start.z + (end.z - start.z) * t)
                    }),
                )
            }
            Some((centre, ccw)) => {
                let radius = s.start.distance(centre);
                let a0 = geometry::angle(s.start, centre);
                let sign = if ccw { 1.0 } else { -1.0 };
                (
                    geometry::arc_length(s.start, s.end, centre, ccw),
                    Box::new(move |d: f64| geometry::on_circle(centre, radius, a0 + sign * d / radius)),
                )
            }
        };
        let count = ((length - spacing) / spacing).floor();
        if count < 0.0 {
            continue;
        }
        let first = (length - count * spacing) / 2.0;
        for i in 0..=count as usize {
            let p = at(first + spacing * i as f64);
            // Kept only where this move made the surface: no later pass over the same place
            // and no other surface closer.
            let nearest = surfaces.iter().map(|o| o.closest(p).1).fold(f64::INFINITY, f64::min);
            let owner = surfaces.iter().rposition(|o| o.closest(p).1 <= nearest + SAME_SURFACE_MM);
            if owner == Some(k) && p.x >= 0.0 {
                out.push(p);
            }
        }
    }
    out
}

pub(super) fn forward(nominal: &Nominal, points: &[ProfilePoint]) -> Result<Forward, ForwardError> {
    let surfaces = surfaces(nominal, Use::Matching);
    if surfaces.is_empty() {
        return Err(ForwardError::NoCuts);
    }
    let path = &nominal.toolpath;

    // Parts, in the order they were machined: by start time where given, else as listed.
    let mut parts: Vec<(Option<String>, Option<f64>)> = Vec::new();
    for p in points {
        if !parts.iter().any(|(label, _)| *label == p.part) {
            parts.push((p.part.clone(), p.start_min));
        }
    }
    if parts.iter().all(|(_, t)| t.is_some()) {
        parts.sort_by(|a, b| a.1.unwrap_or(0.0).total_cmp(&b.1.unwrap_or(0.0)));
    }

    let mut matched = Vec::with_capacity(points.len());
    for p in points {
        let at = Xz::new(p.x_mm, p.z_mm);
        let found: Vec<(Surface, Xz, f64, Xz)> = surfaces
            .iter()
            .map(|s| {
                let (q, d, tangent) = s.closest(at);
                (*s, q, d, tangent)
            })
            .collect();
        let nearest = found.iter().map(|f| f.2).fold(f64::INFINITY, f64::min);
        if nearest > MAX_DISTANCE_MM {
            // A diameter read as a radius: the point halved lies on the part.
            let halved = Xz::new(p.x_mm / 2.0, p.z_mm);
            let distance = surfaces.iter().map(|s| s.closest(halved).1).fold(f64::INFINITY, f64::min);
            let halved = (distance <= MAX_DISTANCE_MM / 10.0).then_some(distance);
            return Err(ForwardError::NotOnPart { line: p.line, x: p.x_mm, z: p.z_mm, distance: nearest, halved });
        }
        let Some(&(surface, q, _, tangent)) = found.iter().rev().find(|f| f.2 <= nearest + SAME_SURFACE_MM) else {
            return Err(ForwardError::NoCuts);
        };
        let m = &path.moves[surface.index];
        let (_, tip_code) = nominal.tools.lookup(m.tool, m.offset);
        let mut normal = surface_normal(tangent, m, tip_vector(tip_code));
        if normal.x == 0.0 && normal.z == 0.0 {
            normal = Xz::new(tangent.z, -tangent.x);
        }
        let reference =
            Xz::new(q.x + surface.nose * (normal.x + surface.tip.x), q.z + surface.nose * (normal.z + surface.tip.z));
        let run = parts.iter().position(|(label, _)| *label == p.part).unwrap_or(0);
        let measured = (at.x - q.x) * normal.x + (at.z - q.z) * normal.z;
        matched.push((
            Place { index: surface.index, param: param_on(path, surface.index, reference) },
            run,
            q,
            normal,
            measured,
        ));
    }

    let places: Vec<Place> = matched.iter().map(|m| m.0).collect();
    let (samples, sample_of) = split_and_sample(path, &nominal.tools, &places);
    let points = matched
        .iter()
        .zip(sample_of)
        .map(|(&(place, run, q, normal, measured), sample)| Point {
            run,
            sample,
            projection: Projection::Normal { nominal: samples.get(sample).map_or(q, |s| s.nominal), normal },
            measured,
            line: nominal.move_lines.get(place.index).copied().unwrap_or(0),
            nominal: q,
            angle_deg: None,
            direction: None,
            group: run,
        })
        .collect();
    let groups: Vec<String> = parts
        .iter()
        .map(|(label, start)| {
            let name = label.as_ref().map_or("the part".to_string(), |l| format!("part {l}"));
            match start {
                Some(t) => format!("{name} (started at {t} min)"),
                None => name,
            }
        })
        .collect();
    Ok(Forward {
        kind: Kind::Profile,
        samples,
        start: path.start,
        runs: parts.iter().map(|(_, t)| *t).collect(),
        duration_s: path.duration(),
        points,
        setup: vec![SetupTerms::DatumShift; groups.len()],
        groups,
    })
}
