use super::*;
use crate::compensation::fit::max_deviation;
use crate::geometry::on_circle;

/// A G01 polyline through points of an S: a quarter G03 of radius 10, a tangent line of
/// 10 mm, a quarter G02 of radius 5, every `chord` mm, rounded to 0.001 mm as a CAM post
/// writes it.
fn polyline(chord: f64) -> (Xz, Vec<Xz>) {
    let mut out = Vec::new();
    let round = |p: Xz| Xz::new((p.x * 1000.0).round() / 1000.0, (p.z * 1000.0).round() / 1000.0);
    // G03 about (0, 0) from −90° (x −10, z 0) to 0° (x 0, z 10).
    let n = (10.0 * std::f64::consts::FRAC_PI_2 / chord).ceil() as usize;
    for i in 1..=n {
        out.push(round(on_circle(Xz::new(0.0, 0.0), 10.0, (-90.0 + 90.0 * i as f64 / n as f64).to_radians())));
    }
    // A line along +X from (0, 10) to (10, 10).
    let n = (10.0 / chord).ceil() as usize;
    for i in 1..=n {
        out.push(round(Xz::new(10.0 * i as f64 / n as f64, 10.0)));
    }
    // G02 about (10, 15) from 180° (x 10, z 10) to 90° (x 15, z 15).
    let n = (5.0 * std::f64::consts::FRAC_PI_2 / chord).ceil() as usize;
    for i in 1..=n {
        out.push(round(on_circle(Xz::new(10.0, 15.0), 5.0, (180.0 - 90.0 * i as f64 / n as f64).to_radians())));
    }
    (Xz::new(-10.0, 0.0), out)
}

#[test]
fn a_polyline_sampled_from_arcs_gives_the_arcs_back() {
    let (start, points) = polyline(0.2);
    let m = MovePoints { start, points: &points, nominal: NominalShape::Line };
    let pieces = fit(&m, 0.0025);
    assert_eq!(pieces.segments.last().map(Segment::end), points.last().copied());
    let measured = max_deviation(start, &pieces.segments, &points);
    assert!(measured <= 0.0025 && pieces.max_deviation_mm >= measured - 1e-12, "{measured}");
    // The three shapes, give or take a piece where a join rounds across two of them.
    assert!((3..=6).contains(&pieces.segments.len()), "{:#?}", pieces.segments);
    let arcs: Vec<(Xz, bool)> = pieces
        .segments
        .iter()
        .filter_map(|s| match *s {
            Segment::Arc { centre, ccw, .. } => Some((centre, ccw)),
            Segment::Line { .. } => None,
        })
        .collect();
    assert!(arcs.iter().any(|&(c, ccw)| ccw && c.distance(Xz::new(0.0, 0.0)) < 0.01), "{arcs:?}");
    assert!(arcs.iter().any(|&(c, ccw)| !ccw && c.distance(Xz::new(10.0, 15.0)) < 0.01), "{arcs:?}");
}

#[test]
fn the_chord_test_refuses_an_arc_that_only_meets_the_points() {
    // Every 30° of a radius of 10: each chord sags 0.34 mm inside the circle.
    let points: Vec<Xz> =
        (1..=7).map(|i| on_circle(Xz::new(0.0, 0.0), 10.0, (30.0 * f64::from(i)).to_radians())).collect();
    let start = Xz::new(0.0, 10.0);
    // As a G01 polyline the path is the chords: the circle through the points is 0.34 mm off
    // them, so only lines pass.
    let polyline = MovePoints { start, points: &points, nominal: NominalShape::Line };
    let pieces = fit(&polyline, 0.01);
    assert!(pieces.segments.iter().all(|s| matches!(s, Segment::Line { .. })), "{:?}", pieces.segments);
    assert_eq!(pieces.segments.len(), 7);
    // Sampled from a nominal arc, the path between the points is that arc's bulge, and
    // the circle follows it: 210° in two arcs of at most half a turn each.
    let nominal =
        NominalShape::Arc { centre: Xz::new(0.0, 0.0), ccw: true, radius: polyline.start.distance(Xz::new(0.0, 0.0)) };
    let sampled = MovePoints { nominal, ..polyline };
    let pieces = fit(&sampled, 0.01);
    assert!(pieces.segments.iter().all(|s| matches!(s, Segment::Arc { .. })), "{:?}", pieces.segments);
    assert_eq!(pieces.segments.len(), 2);
    assert!(pieces.max_deviation_mm < 1e-9);
}

#[test]
fn no_arc_sweeps_more_than_half_a_turn_or_is_too_flat_for_a_control() {
    let centre = Xz::new(0.0, 0.0);
    let points: Vec<Xz> = (1..=360).map(|i| on_circle(centre, 20.0, f64::from(i).to_radians())).collect();
    let m = MovePoints {
        start: Xz::new(0.0, 20.0),
        points: &points,
        nominal: NominalShape::Arc { centre, ccw: true, radius: 20.0 },
    };
    let pieces = fit(&m, 0.0005);
    let mut from = m.start;
    for s in &pieces.segments {
        if let Segment::Arc { end, centre, ccw } = *s {
            assert!(geometry::sweep(from, end, centre, ccw) <= PI + 1e-9);
        }
        from = s.end();
    }
    assert!(pieces.segments.len() >= 2);
    // A 2 µm bow over 200 mm would want a radius of 2,500 m: it is written as lines.
    let bow: Vec<Xz> = (1..=400)
        .map(|i| {
            let z = -0.5 * f64::from(i);
            Xz::new(10.0 + 0.002 * (std::f64::consts::PI * z / 200.0).sin().abs(), z)
        })
        .collect();
    let m = MovePoints { start: Xz::new(10.0, 0.0), points: &bow, nominal: NominalShape::Line };
    let pieces = fit(&m, 0.0005);
    let mut from = m.start;
    for s in &pieces.segments {
        if let Segment::Arc { centre, .. } = *s {
            assert!(from.distance(centre) <= pinned::MAX_RADIUS_MM, "{s:?}");
        }
        from = s.end();
    }
    assert!(max_deviation(m.start, &pieces.segments, &bow) <= 0.0005);
}

#[test]
fn one_point_after_a_step_on_a_small_arc_follows_the_arc_not_its_chord() {
    // After a backlash step the rest of a move may be one sample 0.254 mm on along a
    // 4.7 mm arc: the chord to it cuts 1.7 µm inside the arc between them, more than the
    // tolerance, and no point shows it. The piece follows the nominal curvature instead.
    let (centre, radius) = (Xz::new(70.0, -50.0), 4.7);
    let start = on_circle(centre, radius, 1.0);
    let end = on_circle(centre, radius, 1.0 - 0.254 / radius);
    let m = MovePoints { start, points: &[end], nominal: NominalShape::Arc { centre, ccw: false, radius } };
    let pieces = fit(&m, 0.0005);
    let [Segment::Arc { end: written, centre: fitted, ccw: false }] = pieces.segments[..] else {
        panic!("{:?}", pieces.segments)
    };
    assert_eq!(written, end);
    assert!(fitted.distance(centre) < 1e-9, "{fitted:?}");
    // Along a nominal line the path between points is their chord: a line it stays.
    let m = MovePoints { start, points: &[end], nominal: NominalShape::Line };
    assert_eq!(fit(&m, 0.0005).segments, vec![Segment::Line { end }]);
}
