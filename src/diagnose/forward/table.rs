//! Interferometer tables (ISO 230-2): one slide measured at its targets, each approached
//! upward and then downward, the other slide standing still.
//!
//! The test is simulated as ISO 230-2's linear test cycle: from an overrun below the first
//! target, up through every target to an overrun beyond the last, then down through every
//! target back to the start, the slide at rest at each target when it is read. The other
//! axis stands at zero. A table has no times, so thermal effects read at the model's start.
//!
//! The positioning deviation reads along the slide's axis, its straightness across it.
//! Set-up: the laser's zero for positioning; zero and alignment (a slope) for straightness,
//! which is why a squareness never shows in one straightness run.

use super::{Forward, Point, Projection, SetupTerms};
use crate::diagnose::measured::{Axis, Kind};
use crate::error_model::interferometer::{Profile, SlideTable};
use crate::error_model::sampling::PathSample;
use crate::toolpath::Xz;

/// Travel beyond the end targets before the slide turns back, mm.
const OVERRUN_MM: f64 = 2.0;

pub(super) fn forward(axis: Axis, table: &SlideTable) -> Forward {
    let along_x = axis == Axis::X;
    let at = |position: f64| if along_x { Xz::new(position, 0.0) } else { Xz::new(0.0, position) };
    let (along, across) =
        if along_x { (Xz::new(1.0, 0.0), Xz::new(0.0, 1.0)) } else { (Xz::new(0.0, 1.0), Xz::new(1.0, 0.0)) };
    let quantities: Vec<(&Profile, Xz, SetupTerms, &str)> = [
        (&table.linear, along, SetupTerms::Zero, "positioning (laser zero removed)"),
        (
            &table.straightness,
            across,
            SetupTerms::ZeroAndSlope { along_x },
            "straightness (zero and alignment removed)",
        ),
    ]
    .into_iter()
    .filter_map(|(p, direction, terms, name)| p.as_ref().map(|p| (p, direction, terms, name)))
    .collect();

    let mut targets: Vec<f64> = quantities.iter().flat_map(|q| q.0.targets.iter().copied()).collect();
    targets.sort_by(f64::total_cmp);
    targets.dedup();
    let (first, last) = (targets.first().copied().unwrap_or(0.0), targets.last().copied().unwrap_or(0.0));
    let sample = |position: f64| PathSample {
        move_index: 0,
        param: 1.0,
        nominal: at(position),
        covers_mm: 0.0,
        t_s: 0.0,
        velocity: Xz::default(),
        tool: 0,
        cutting: false,
        normal: Xz::default(),
        tip: Xz::default(),
    };
    // Up through the targets, the overrun, down through them, back to the start.
    let mut samples: Vec<PathSample> = targets.iter().map(|&t| sample(t)).collect();
    samples.push(sample(last + OVERRUN_MM));
    samples.extend(targets.iter().rev().map(|&t| sample(t)));
    samples.push(sample(first - OVERRUN_MM));
    let n = targets.len();
    let up_sample = |k: usize| k;
    let down_sample = |k: usize| n + 1 + (n - 1 - k);

    let mut points = Vec::new();
    for (group, (profile, direction, _, _)) in quantities.iter().enumerate() {
        for (i, &target) in profile.targets.iter().enumerate() {
            let Some(k) = targets.iter().position(|&t| t == target) else { continue };
            let reads = [
                (profile.up_measured.get(i) == Some(&true), profile.up.get(i), up_sample(k)),
                (profile.down_measured.get(i) == Some(&true), profile.down.get(i), down_sample(k)),
            ];
            for (measured, value, sample) in reads {
                let Some(&value) = value.filter(|_| measured) else { continue };
                points.push(Point {
                    run: 0,
                    sample,
                    projection: Projection::Normal { nominal: at(target), normal: *direction },
                    measured: value,
                    line: 0,
                    nominal: at(target),
                    angle_deg: None,
                    direction: None,
                    group,
                });
            }
        }
    }
    let slide = if along_x { "X slide" } else { "Z slide" };
    Forward {
        kind: Kind::Table(axis),
        samples,
        start: at(first - OVERRUN_MM),
        runs: vec![None],
        duration_s: 0.0,
        points,
        groups: quantities.iter().map(|q| format!("{slide} {}", q.3)).collect(),
        setup: quantities.iter().map(|q| q.2).collect(),
    }
}
