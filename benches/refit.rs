//! Arc refit throughput: input segments per second for the `arcs` strategy on a long `G01`
//! polyline sampled from arcs (the ArcWelder use case), with the median of interleaved runs
//! printed as `lower.rs` does.
//!
//! Run with `cargo bench --bench refit`. The input is generated here: 1,000,000 `G01`
//! segments (`TURNPASS_REFIT_SEGMENTS` overrides the count) through points on a chain of
//! tangent arcs (radius 2–60 mm, 15–150° each) and lines, 0.25–0.5 mm apart, rounded to
//! 0.001 mm as a CAM post writes them. It is refitted at ArcWelder's default resolution
//! (0.05 mm, ±0.025 mm) and at a tight 0.0025 mm, each result checked on a prefix against
//! the independent deviation measure.
//!
//! **Peer.** The issue quotes ArcWelder at about 260 k segments/s. ArcWelder ships as a C++
//! console program and an OctoPrint plugin built from source; no package of it was found on
//! a registry to run here (PyPI: `arcwelder`, `pyarcwelder`, `octoprint-arcwelder`; npm:
//! `arcwelder`, `arc-welder`; crates.io: `arcwelder`, `arc-welder`, `arc_welder` — none
//! exists), so this bench prints no peer figure and the 260 k/s is the issue's, not
//! measured here.

#![allow(clippy::disallowed_methods, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;

mod support;
use support::median_seconds;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use turnpass::compensation::fit::{MovePoints, NominalShape, fit_arcs, max_deviation};
use turnpass::toolpath::Xz;

/// A repeatable uniform number in [0, 1).
struct Random(u64);

impl Random {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn between(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.next()
    }
}

/// The start and `count` points of a polyline along tangent arcs and lines.
fn polyline(count: usize) -> (Xz, Vec<Xz>) {
    let mut random = Random(2024);
    let round = |v: f64| (v * 1000.0).round() / 1000.0;
    let start = Xz::new(40.0, 0.0);
    let mut at = start;
    // The heading, as an angle from +Z toward +X.
    let mut heading: f64 = std::f64::consts::PI;
    let mut points = Vec::with_capacity(count);
    while points.len() < count {
        let chord = random.between(0.25, 0.5);
        if random.next() < 0.15 {
            let length = random.between(1.0, 20.0);
            let n = (length / chord).ceil() as usize;
            let (dx, dz) = (heading.sin() * length / n as f64, heading.cos() * length / n as f64);
            for i in 1..=n {
                points.push(Xz::new(at.x + dx * i as f64, at.z + dz * i as f64));
            }
            at = Xz::new(at.x + dx * n as f64, at.z + dz * n as f64);
        } else {
            let radius = random.between(2.0, 60.0);
            let sweep = random.between(15.0, 150.0).to_radians();
            let turn = if random.next() < 0.5 { 1.0 } else { -1.0 };
            // The centre is to the left of travel for a left turn.
            let normal = heading + turn * std::f64::consts::FRAC_PI_2;
            let centre = Xz::new(at.x + radius * normal.sin(), at.z + radius * normal.cos());
            let from = (at.x - centre.x).atan2(at.z - centre.z);
            let step = 2.0 * (chord / (2.0 * radius)).asin();
            let n = (sweep / step).ceil() as usize;
            for i in 1..=n {
                let angle = from + turn * sweep * i as f64 / n as f64;
                points.push(Xz::new(centre.x + radius * angle.sin(), centre.z + radius * angle.cos()));
            }
            let end = from + turn * sweep;
            at = Xz::new(centre.x + radius * end.sin(), centre.z + radius * end.cos());
            heading += turn * sweep;
        }
    }
    points.truncate(count);
    let points = points.into_iter().map(|p| Xz::new(round(p.x), round(p.z))).collect();
    (start, points)
}

fn refit(c: &mut Criterion) {
    let count = std::env::var("TURNPASS_REFIT_SEGMENTS").ok().and_then(|v| v.parse().ok()).unwrap_or(1_000_000);
    let (start, points) = polyline(count);
    let m = MovePoints { start, points: &points, nominal: NominalShape::Line };

    println!();
    for tolerance in [0.025, 0.0025] {
        // The result is right before it is fast: a prefix, measured independently.
        let prefix = MovePoints { points: &points[..points.len().min(50_000)], ..m };
        let checked = fit_arcs(&prefix, tolerance);
        let measured = max_deviation(start, &checked.segments, prefix.points);
        assert!(measured <= tolerance, "deviation {measured} over {tolerance}");

        let pieces = fit_arcs(&m, tolerance);
        assert_eq!(pieces.segments.last().map(|s| s.end()), points.last().copied());
        let arcs = pieces.segments.iter().filter(|s| matches!(s, turnpass::compensation::Segment::Arc { .. })).count();
        let seconds = median_seconds(|| drop(black_box(fit_arcs(&m, tolerance))), 7);
        println!(
            "turnpass-bench: arc refit of {count} G01 segments at ±{tolerance} mm in {:.1} ms: {:.2} M segments/s \
             ({} arcs + {} lines out, max deviation {:.4} mm)",
            seconds * 1e3,
            count as f64 / seconds / 1e6,
            arcs,
            pieces.segments.len() - arcs,
            pieces.max_deviation_mm,
        );
    }
    println!("turnpass-bench: ArcWelder is not on a package registry; no peer figure\n");

    let mut group = c.benchmark_group("refit");
    group.sample_size(10);
    group.throughput(Throughput::Elements(count as u64));
    group.bench_function("arcs_g01_polyline_0.025mm", |b| b.iter(|| fit_arcs(&m, 0.025)));
    group.finish();
}

criterion_group!(benches, refit);
criterion_main!(benches);
