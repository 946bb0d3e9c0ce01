use super::*;

#[test]
fn densify_keeps_one_line_for_straight_points_and_splits_a_bend() {
    let straight: Vec<Xz> = (1..=10).map(|i| Xz::new(10.0, -f64::from(i))).collect();
    let m = MovePoints { start: Xz::new(10.0, 0.0), points: &straight, nominal: NominalShape::Line };
    assert_eq!(densify(&m, 0.001, None), vec![Segment::Line { end: Xz::new(10.0, -10.0) }]);
    // A 5 µm bump in the middle: the chord from the start to the end misses it.
    let mut bent = straight.clone();
    bent[4].x += 0.005;
    let lines = densify(&MovePoints { points: &bent, ..m }, 0.001, None);
    assert!(lines.len() >= 2);
    let mut from = m.start;
    for s in &lines {
        from = s.end();
    }
    assert_eq!(from, Xz::new(10.0, -10.0));
    // Every point lies within the tolerance of the written lines.
    let mut a = m.start;
    let mut k = 0;
    for s in &lines {
        let b = s.end();
        while k < bent.len() && bent[k] != b {
            assert!(distance_to_chord(bent[k], a, b) <= 0.001);
            k += 1;
        }
        k += 1;
        a = b;
    }
}

#[test]
fn densify_at_a_step_writes_one_line_per_step() {
    let points: Vec<Xz> = (1..=100).map(|i| Xz::new(0.0, f64::from(i) * 0.254)).collect();
    let m = MovePoints { start: Xz::new(0.0, 0.0), points: &points, nominal: NominalShape::Line };
    let lines = densify(&m, 0.001, Some(2.54));
    assert_eq!(lines.len(), 10);
    assert!((lines[0].end().z - 2.54).abs() < 1e-9);
}

#[test]
fn densify_along_a_small_arc_holds_its_lines_to_the_arc_between_the_samples() {
    // A 1.6 mm fillet sampled every 0.254 mm: a line from one sample to the next cuts
    // 0.254² / (8 · 1.6) = 5 µm inside the arc, ten times the tolerance, and no sample lies
    // between them to show it.
    let (centre, radius) = (Xz::new(20.0, -30.0), 1.6);
    let step = 0.254 / radius;
    let points: Vec<Xz> = (1..=12).map(|i| crate::geometry::on_circle(centre, radius, f64::from(i) * step)).collect();
    let m = MovePoints {
        start: crate::geometry::on_circle(centre, radius, 0.0),
        points: &points,
        nominal: NominalShape::Arc { centre, ccw: true, radius },
    };
    for step_mm in [None, Some(0.508)] {
        let lines = densify(&m, TOLERANCE, step_mm);
        assert_eq!(lines.last().map(Segment::end), points.last().copied());
        // The arc, finely, stays within the tolerance of the lines.
        let worst = (0..=1200)
            .map(|k| crate::geometry::on_circle(centre, radius, 12.0 * step * f64::from(k) / 1200.0))
            .map(|p| max_deviation(m.start, &lines, &[p]))
            .fold(0.0, f64::max);
        assert!(worst <= TOLERANCE, "{step_mm:?}: {worst}");
    }
    // What `fit_move` reports for densify is measured on the arc between the samples too.
    let fitted = fit_move(&m, &FitOptions { strategy: Strategy::Densify, tolerance_mm: TOLERANCE, step_mm: None });
    assert!(fitted.max_deviation_mm <= TOLERANCE && fitted.segments.len() > 3 * points.len());
}

// ---------------------------------------------------------------------------------------
// The strategies on synthetic compensated arcs.
// ---------------------------------------------------------------------------------------

use crate::geometry::{self, on_circle};
use proptest::prelude::{ProptestConfig, prop_assert, prop_assert_eq, prop_oneof, proptest};
use proptest::strategy::Strategy as _;

const TOLERANCE: f64 = 0.0005;

/// The error terms a compensated arc carries, mm.
#[derive(Debug, Clone, Copy, Default)]
struct Errors {
    /// Radius error.
    radius: f64,
    /// Centre offset.
    centre: Xz,
    /// A Z backlash play: the path jumps by it where Z reverses (0° and 180°).
    backlash_z: f64,
    /// An oval, `amplitude · cos 2θ` on the radius.
    oval: f64,
    /// A third harmonic, `amplitude · cos 3θ` on the radius.
    third: f64,
}

/// The move of a compensated arc about `centre` from `from_deg` through `sweep_deg`
/// (positive: G03), sampled at `n` steps; the first sample is the move's start.
fn compensated_arc(centre: Xz, radius: f64, from_deg: f64, sweep_deg: f64, n: usize, e: Errors) -> (Xz, Vec<Xz>) {
    let ccw = sweep_deg > 0.0;
    let point = |i: usize| {
        let theta = (from_deg + sweep_deg * i as f64 / n as f64).to_radians();
        let r = radius + e.radius + e.oval * (2.0 * theta).cos() + e.third * (3.0 * theta).cos();
        let p = on_circle(Xz::new(centre.x + e.centre.x, centre.z + e.centre.z), r, theta);
        // Going G03, Z falls while sin θ > 0; the command leads the slide by half the play
        // in the direction it moves.
        let z_direction = if ccw { -theta.sin().signum() } else { theta.sin().signum() };
        Xz::new(p.x, p.z + z_direction * e.backlash_z / 2.0)
    };
    (point(0), (1..=n).map(point).collect())
}

fn arc_move<'a>(start: Xz, points: &'a [Xz], centre: Xz, radius: f64, sweep_deg: f64) -> MovePoints<'a> {
    MovePoints { start, points, nominal: NominalShape::Arc { centre, ccw: sweep_deg > 0.0, radius } }
}

fn options(strategy: Strategy) -> FitOptions {
    FitOptions { strategy, tolerance_mm: TOLERANCE, step_mm: None }
}

/// What every re-expression must satisfy: it ends exactly on the last point, its arcs are
/// circles (both ends at one radius), and every point lies within the tolerance of it, as
/// measured independently of the strategy's own bookkeeping.
fn check(m: &MovePoints<'_>, fitted: &Fitted) {
    assert_eq!(fitted.segments.last().map(Segment::end), m.points.last().copied(), "the move ends on its last point");
    let mut from = m.start;
    for s in &fitted.segments {
        if let Segment::Arc { end, centre, .. } = *s {
            let (r0, r1) = (from.distance(centre), end.distance(centre));
            assert!((r0 - r1).abs() <= 1e-9 * r0.max(1.0), "arc radii {r0} and {r1}");
        }
        from = s.end();
    }
    let deviation = max_deviation(m.start, &fitted.segments, m.points);
    assert!(deviation <= TOLERANCE + 1e-12, "{:?}: deviation {deviation}", fitted.strategy_used);
    assert!(fitted.max_deviation_mm >= deviation - 1e-12, "the reported deviation is at least the measured one");
}

fn count(fitted: &Fitted) -> (usize, usize) {
    let arcs = fitted.segments.iter().filter(|s| matches!(s, Segment::Arc { .. })).count();
    (arcs, fitted.segments.len() - arcs)
}

#[test]
fn circle_absorbs_a_radius_error_and_a_centre_offset_exactly() {
    // The thesis' Table 7 quarter, G02 from (x 25.4, z 0) to (x 0, z 25.4) about the origin.
    let errors = Errors { radius: -0.0042, centre: Xz::new(0.0051, 0.0057), ..Errors::default() };
    let (start, points) = compensated_arc(Xz::new(0.0, 0.0), 25.4, 90.0, -90.0, 100, errors);
    let m = arc_move(start, &points, Xz::new(0.0, 0.0), 25.4, -90.0);
    let fitted = fit_move(&m, &options(Strategy::Circle));
    check(&m, &fitted);
    assert_eq!(fitted.strategy_used, Strategy::Circle);
    assert!(fitted.max_deviation_mm < 1e-9);
    let [Segment::Arc { centre, ccw: false, .. }] = fitted.segments[..] else { panic!("{:?}", fitted.segments) };
    assert!(centre.distance(Xz::new(0.0051, 0.0057)) < 1e-9, "{centre:?}");
    assert!((start.distance(centre) - 25.3958).abs() < 1e-9);
    // Auto keeps the one circle.
    let auto = fit_move(&m, &options(Strategy::Auto));
    assert_eq!((auto.strategy_used, auto.segments.len()), (Strategy::Circle, 1));
}

#[test]
fn semicircle_absorbs_a_backlash_step_that_defeats_one_circle() {
    let errors = Errors { radius: 0.003, centre: Xz::new(-0.002, 0.004), backlash_z: 0.004, ..Errors::default() };
    // A quarter across 0°, where Z reverses; 301 steps put no sample on 0° itself. The
    // step is written as a straight line between the samples either side of it, held to
    // the arc's bulge between them: 0.068 µm at these 0.3° steps (at 2° it would be 3 µm,
    // and the step could not be written within the tolerance).
    let (start, points) = compensated_arc(Xz::new(10.0, -30.0), 20.0, -45.0, 90.0, 301, errors);
    let m = arc_move(start, &points, Xz::new(10.0, -30.0), 20.0, 90.0);

    let circle = fit_move(&m, &options(Strategy::Circle));
    check(&m, &circle);
    let rejected = circle.rejected.expect("one circle cannot take a 4 µm step");
    assert!(rejected.strategy == Strategy::Circle && rejected.deviation_mm > TOLERANCE);
    assert_eq!(circle.strategy_used, Strategy::Densify);

    let halves = fit_move(&m, &options(Strategy::Semicircle));
    check(&m, &halves);
    assert_eq!(halves.strategy_used, Strategy::Semicircle);
    assert!(halves.max_deviation_mm < 1e-9, "{}", halves.max_deviation_mm);
    // An arc to the reversal, the step, an arc from it.
    let [Segment::Arc { centre: before, .. }, Segment::Line { .. }, Segment::Arc { centre: after, .. }] =
        halves.segments[..]
    else {
        panic!("{:?}", halves.segments)
    };
    // Each half is the circle shifted by half the play in Z, the way it was going.
    let expected = Xz::new(10.0 - 0.002, -30.0 + 0.004);
    assert!(before.distance(Xz::new(expected.x, expected.z + 0.002)) < 1e-9, "{before:?}");
    assert!(after.distance(Xz::new(expected.x, expected.z - 0.002)) < 1e-9, "{after:?}");

    let auto = fit_move(&m, &options(Strategy::Auto));
    check(&m, &auto);
    assert_eq!((auto.strategy_used, auto.segments.len()), (Strategy::Semicircle, 3));
}

#[test]
fn a_step_whose_straight_line_would_cut_inside_the_arc_is_not_written() {
    // The same quarter sampled every 2°: the samples either side of the reversal are 0.7 mm
    // apart, and a straight step between them cuts inside the arc by 3 µm. Semicircle
    // cannot write the step within the tolerance, says so, and the move is densified.
    let errors = Errors { radius: 0.003, centre: Xz::new(-0.002, 0.004), backlash_z: 0.004, ..Errors::default() };
    let (start, points) = compensated_arc(Xz::new(10.0, -30.0), 20.0, -45.0, 90.0, 45, errors);
    let m = arc_move(start, &points, Xz::new(10.0, -30.0), 20.0, 90.0);
    let halves = fit_move(&m, &options(Strategy::Semicircle));
    check(&m, &halves);
    let rejected = halves.rejected.expect("the step cannot be written straight");
    assert_eq!(rejected.strategy, Strategy::Semicircle);
    assert!(rejected.deviation_mm > 0.003 && rejected.deviation_mm < 0.0031, "{}", rejected.deviation_mm);
    assert_eq!(halves.strategy_used, Strategy::Densify);
}

#[test]
fn quadrant_approximates_an_oval_that_defeats_one_circle_and_two_halves() {
    // A full circle with a 2 µm oval: one circle leaves 2 µm, a half 0.7 µm, a quarter 0.34 µm.
    let errors = Errors { radius: 0.002, centre: Xz::new(0.0153, 0.0930), oval: 0.002, ..Errors::default() };
    let (start, points) = compensated_arc(Xz::new(0.0, 0.0), 100.0, 0.0, 360.0, 720, errors);
    let m = arc_move(start, &points, Xz::new(0.0, 0.0), 100.0, 360.0);
    for strategy in [Strategy::Circle, Strategy::Semicircle] {
        let fitted = fit_move(&m, &options(strategy));
        check(&m, &fitted);
        assert!(fitted.rejected.is_some_and(|r| r.deviation_mm > TOLERANCE), "{strategy:?}");
    }
    let quarters = fit_move(&m, &options(Strategy::Quadrant));
    check(&m, &quarters);
    assert_eq!((quarters.strategy_used, count(&quarters)), (Strategy::Quadrant, (4, 0)));
    assert!(quarters.max_deviation_mm > 0.1 * TOLERANCE, "an approximation, not an exact fit");
    let auto = fit_move(&m, &options(Strategy::Auto));
    check(&m, &auto);
    assert_eq!((auto.strategy_used, auto.segments.len()), (Strategy::Quadrant, 4));
}

#[test]
fn arcs_and_densify_meet_the_tolerance_on_every_error_at_once() {
    let errors =
        Errors { radius: 0.005, centre: Xz::new(0.0051, 0.0057), backlash_z: 0.004, oval: 0.003, third: 0.002 };
    for (from, sweep, n) in [(-45.0, 90.0, 225), (135.0, -270.0, 675), (10.0, 350.0, 875)] {
        let (start, points) = compensated_arc(Xz::new(0.0, 0.0), 25.4, from, sweep, n, errors);
        let m = arc_move(start, &points, Xz::new(0.0, 0.0), 25.4, sweep);
        let arcs = fit_move(&m, &options(Strategy::Arcs));
        let lines = fit_move(&m, &options(Strategy::Densify));
        check(&m, &arcs);
        check(&m, &lines);
        assert_eq!((arcs.strategy_used, lines.strategy_used), (Strategy::Arcs, Strategy::Densify));
        assert!(
            arcs.segments.len() * 3 < lines.segments.len(),
            "arcs {} against lines {}",
            arcs.segments.len(),
            lines.segments.len()
        );
        let auto = fit_move(&m, &options(Strategy::Auto));
        check(&m, &auto);
        assert!(auto.segments.len() <= arcs.segments.len());
        // One circle cannot follow all that.
        assert!(fit_move(&m, &options(Strategy::Circle)).rejected.is_some());
    }
}

/// The direction of travel at the start and at the end of each segment.
fn directions(start: Xz, segments: &[Segment]) -> Vec<(Xz, Xz)> {
    let mut from = start;
    let mut out = Vec::new();
    for s in segments {
        out.push(match *s {
            Segment::Line { end } => (geometry::direction(from, end), geometry::direction(from, end)),
            Segment::Arc { end, centre, ccw } => {
                let along = |p: Xz| {
                    let r = geometry::direction(centre, p);
                    if ccw { Xz::new(r.z, -r.x) } else { Xz::new(-r.z, r.x) }
                };
                (along(from), along(end))
            }
        });
        from = s.end();
    }
    out
}

#[test]
fn arcs_join_smoothly_where_the_path_is_smooth() {
    let errors = Errors { radius: 0.005, oval: 0.003, third: 0.002, ..Errors::default() };
    let (start, points) = compensated_arc(Xz::new(0.0, 0.0), 25.4, 180.0, -180.0, 400, errors);
    let m = arc_move(start, &points, Xz::new(0.0, 0.0), 25.4, -180.0);
    let arcs = fit_move(&m, &options(Strategy::Arcs));
    check(&m, &arcs);
    assert!(arcs.segments.len() >= 3, "{}", arcs.segments.len());
    // Most joins are tangent to rounding; a corner piece is taken only where it covers a
    // third again as many points, and on a smooth path its corner is slight.
    let turns: Vec<f64> =
        directions(m.start, &arcs.segments).windows(2).map(|pair| pair[0].1.distance(pair[1].0)).collect();
    let tangent = turns.iter().filter(|&&turn| turn < 1e-9).count();
    assert!(2 * tangent >= turns.len(), "{turns:?}");
    assert!(turns.iter().all(|&turn| turn < 1e-3), "{turns:?}");
    // With a backlash step the path has a corner, and so do the arcs.
    let stepped = Errors { backlash_z: 0.004, ..errors };
    let (start, points) = compensated_arc(Xz::new(0.0, 0.0), 25.4, 45.0, -90.0, 201, stepped);
    let m = arc_move(start, &points, Xz::new(0.0, 0.0), 25.4, -90.0);
    let arcs = fit_move(&m, &options(Strategy::Arcs));
    check(&m, &arcs);
    let turns: Vec<f64> =
        directions(m.start, &arcs.segments).windows(2).map(|pair| pair[0].1.distance(pair[1].0)).collect();
    assert!(turns.iter().any(|&turn| turn > 1e-2), "the step is a corner: {turns:?}");
}

#[test]
fn a_line_stays_a_line_or_takes_the_fewest_segments() {
    // A Z move with a 30 ppm scale error: still straight.
    let straight: Vec<Xz> = (1..=200).map(|i| Xz::new(20.0, -0.25 * f64::from(i) * (1.0 + 30e-6))).collect();
    let m = MovePoints { start: Xz::new(20.0, 0.0), points: &straight, nominal: NominalShape::Line };
    for strategy in [Strategy::Auto, Strategy::Circle, Strategy::Arcs, Strategy::Densify] {
        let fitted = fit_move(&m, &options(strategy));
        assert_eq!((fitted.strategy_used, fitted.segments.len()), (Strategy::Densify, 1), "{strategy:?}");
    }
    // A cyclic lead error of 3 µm and 10 mm pitch: lines must follow it.
    let wavy: Vec<Xz> = (1..=200)
        .map(|i| {
            let z = -0.25 * f64::from(i);
            Xz::new(20.0 + 0.003 * (std::f64::consts::TAU * z / 10.0).sin(), z)
        })
        .collect();
    let m = MovePoints { points: &wavy, ..m };
    let lines = fit_move(&m, &options(Strategy::Densify));
    let arcs = fit_move(&m, &options(Strategy::Arcs));
    let auto = fit_move(&m, &options(Strategy::Auto));
    let circle = fit_move(&m, &options(Strategy::Circle));
    for fitted in [&lines, &arcs, &auto, &circle] {
        check(&m, fitted);
    }
    assert_eq!(circle.strategy_used, Strategy::Densify);
    assert!(circle.rejected.is_none(), "densify is what circle does with a line");
    assert!(arcs.segments.len() < lines.segments.len(), "arcs {} lines {}", arcs.segments.len(), lines.segments.len());
    assert_eq!((auto.strategy_used, auto.segments.len()), (Strategy::Arcs, arcs.segments.len()));
}

#[test]
fn densify_at_a_step_still_keeps_the_tolerance() {
    // The thesis' O2012 turn: 2.54 mm steps over samples every 0.254 mm, with a bump that
    // a 2.54 mm chord would cut through.
    let points: Vec<Xz> = (1..=100)
        .map(|i| {
            let z = -0.254 * f64::from(i);
            Xz::new(10.0 + if i == 45 { 0.002 } else { 0.0 }, z)
        })
        .collect();
    let m = MovePoints { start: Xz::new(10.0, 0.0), points: &points, nominal: NominalShape::Line };
    let fitted =
        fit_move(&m, &FitOptions { strategy: Strategy::Densify, tolerance_mm: TOLERANCE, step_mm: Some(2.54) });
    check(&m, &fitted);
    // Nine whole steps, and the one with the bump cut at it.
    assert!(fitted.segments.len() > 10 && fitted.segments.len() <= 13, "{}", fitted.segments.len());
}

#[test]
fn degenerate_moves_do_not_panic() {
    let nothing = MovePoints { start: Xz::new(0.0, 0.0), points: &[], nominal: NominalShape::Line };
    assert!(reexpress(&nothing, &options(Strategy::Auto)).is_empty());
    let same = [Xz::new(1.0, 1.0); 5];
    let bad = [Xz::new(1.0, 1.0), Xz::new(f64::NAN, 2.0), Xz::new(3.0, f64::INFINITY), Xz::new(4.0, 4.0)];
    for points in [&same[..], &bad[..], &[Xz::new(2.0, 2.0)][..]] {
        for nominal in [
            NominalShape::Line,
            NominalShape::Arc { centre: Xz::new(1.0, 0.0), ccw: true, radius: 1.0 },
            // A centre on the start (radius zero), and one that is not a number.
            NominalShape::Arc { centre: Xz::new(1.0, 1.0), ccw: false, radius: 0.0 },
            NominalShape::Arc { centre: Xz::new(f64::NAN, 0.0), ccw: true, radius: f64::NAN },
        ] {
            for strategy in [
                Strategy::Auto,
                Strategy::Circle,
                Strategy::Semicircle,
                Strategy::Quadrant,
                Strategy::Arcs,
                Strategy::Densify,
            ] {
                let m = MovePoints { start: Xz::new(1.0, 1.0), points, nominal };
                let segments = reexpress(&m, &options(strategy));
                let last = *points.last().unwrap();
                let end = segments.last().unwrap().end();
                assert!(end == last || (end.x.is_nan() && last.x.is_nan()) || end.z.is_infinite(), "{strategy:?}");
            }
        }
    }
}

fn errors_strategy() -> impl proptest::strategy::Strategy<Value = Errors> {
    (-0.01..0.01f64, -0.01..0.01f64, -0.01..0.01f64, 0.0..0.006f64, -0.004..0.004f64, -0.003..0.003f64).prop_map(
        |(radius, cx, cz, backlash_z, oval, third)| Errors { radius, centre: Xz::new(cx, cz), backlash_z, oval, third },
    )
}

const ALL: [Strategy; 6] =
    [Strategy::Auto, Strategy::Circle, Strategy::Semicircle, Strategy::Quadrant, Strategy::Arcs, Strategy::Densify];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn every_strategy_ends_right_and_keeps_the_tolerance_on_arcs(
        radius in 1.0..120.0f64,
        from in -180.0..180.0f64,
        sweep in prop_oneof![-350.0..-5.0f64, 5.0..350.0f64],
        step in 0.1..1.0f64,
        errors in errors_strategy(),
    ) {
        let n = ((radius * sweep.abs().to_radians() / step).ceil() as usize).clamp(3, 3000);
        let centre = Xz::new(30.0, -20.0);
        let (start, points) = compensated_arc(centre, radius, from, sweep, n, errors);
        let m = arc_move(start, &points, centre, radius, sweep);
        for strategy in ALL {
            let fitted = fit_move(&m, &options(strategy));
            check(&m, &fitted);
            // A strategy that cannot meet the tolerance says so and falls back to densify.
            if let Some(rejected) = fitted.rejected {
                prop_assert_eq!(rejected.strategy, strategy);
                prop_assert_eq!(fitted.strategy_used, Strategy::Densify);
            }
        }
    }

    #[test]
    fn every_strategy_ends_right_and_keeps_the_tolerance_on_lines(
        angle in 0.0..std::f64::consts::TAU,
        length in 0.5..200.0f64,
        amplitude in 0.0..0.01f64,
        pitch in 2.0..50.0f64,
        step in 0.1..1.0f64,
    ) {
        let n = ((length / step).ceil() as usize).max(1);
        let (direction, across) = (Xz::new(angle.sin(), angle.cos()), Xz::new(angle.cos(), -angle.sin()));
        let start = Xz::new(40.0, -10.0);
        let points: Vec<Xz> = (1..=n)
            .map(|i| {
                let s = length * i as f64 / n as f64;
                let off = amplitude * (std::f64::consts::TAU * s / pitch).sin();
                Xz::new(start.x + direction.x * s + across.x * off, start.z + direction.z * s + across.z * off)
            })
            .collect();
        let m = MovePoints { start, points: &points, nominal: NominalShape::Line };
        for strategy in ALL {
            let fitted = fit_move(&m, &options(strategy));
            check(&m, &fitted);
            prop_assert!(fitted.rejected.is_none());
        }
    }
}

proptest! {
    /// `segment_deviation` measures most points by bounds and only the likeliest largest by
    /// its angle; the figure is the one measuring every point gives, to the bit.
    #[test]
    fn segment_deviation_is_the_largest_distance_of_any_point(
        from in -3.2f64..3.2, sweep in 0.01f64..6.2, radius in 0.5f64..40.0, drift in -1e-14f64..1e-14,
        ccw in proptest::bool::ANY, offsets in proptest::collection::vec((-0.3f64..1.3, -0.002f64..0.002), 1..12),
    ) {
        let centre = Xz::new(31.7, -12.3);
        let sense = if ccw { 1.0 } else { -1.0 };
        let start = on_circle(centre, radius, from);
        let end = on_circle(centre, radius + drift * radius, from + sense * sweep);
        let arc = Segment::Arc { end, centre, ccw };
        // Points along the arc and beyond its ends, off it by a few micrometres, and its end.
        let mut points: Vec<Xz> =
            offsets.iter().map(|&(t, off)| on_circle(centre, radius + off, from + sense * sweep * t)).collect();
        points.push(end);
        let each = points.iter().map(|&p| distance_to_segment(p, start, &arc)).fold(0.0, f64::max);
        prop_assert_eq!(segment_deviation(start, &arc, &points).to_bits(), each.to_bits());
    }
}
