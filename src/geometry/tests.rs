use super::*;

fn close(a: Xz, b: Xz) -> bool {
    a.distance(b) < 1e-9
}

#[test]
fn g03_from_the_face_centre_to_the_diameter_is_a_convex_quarter() {
    // The thesis' `G3X2.5Z-1.25R1.2498` from X0 Z0 (diameters): radius 1.25 about Z-1.25.
    let start = Xz::new(0.0, 0.0);
    let end = Xz::new(1.25, -1.25);
    let centre = centre_from_radius(start, end, 1.25, true, 1e-6).unwrap();
    assert!(close(centre, Xz::new(0.0, -1.25)), "{centre:?}");
    assert!((sweep(start, end, centre, true) - PI / 2.0).abs() < 1e-12);
    assert!((sweep(start, end, centre, false) - 3.0 * PI / 2.0).abs() < 1e-12);
    assert!((arc_length(start, end, centre, true) - 1.25 * PI / 2.0).abs() < 1e-12);
}

#[test]
fn negative_radius_takes_the_long_way_and_short_radius_cannot_reach() {
    let start = Xz::new(0.0, 0.0);
    let end = Xz::new(1.0, -1.0);
    let minor = centre_from_radius(start, end, 1.0, true, 1e-6).unwrap();
    let major = centre_from_radius(start, end, -1.0, true, 1e-6).unwrap();
    assert!(sweep(start, end, minor, true) < PI);
    assert!(sweep(start, end, major, true) > PI);
    assert!(centre_from_radius(start, end, 0.5, true, 1e-6).is_none());
}

#[test]
fn full_circle_sweeps_two_pi() {
    let p = Xz::new(10.0, 0.0);
    assert!((sweep(p, p, Xz::new(0.0, 0.0), true) - TAU).abs() < 1e-12);
    assert_eq!(arc_extremes(p, p, Xz::new(0.0, 0.0), true).len(), 3);
}

#[test]
fn intersections() {
    let hit = line_line(Xz::new(0.0, 0.0), Xz::new(2.0, 2.0), Xz::new(2.0, 0.0), Xz::new(0.0, 2.0)).unwrap();
    assert!(close(hit, Xz::new(1.0, 1.0)));
    assert!(line_line(Xz::new(0.0, 0.0), Xz::new(1.0, 0.0), Xz::new(0.0, 1.0), Xz::new(1.0, 1.0)).is_none());
    let ts = line_circle(Xz::new(0.0, -5.0), Xz::new(0.0, 5.0), Xz::new(0.0, 0.0), 2.0);
    assert_eq!(ts.len(), 2);
    assert!((ts[0] - 0.3).abs() < 1e-12 && (ts[1] - 0.7).abs() < 1e-12);
    let points = circle_circle(Xz::new(0.0, 0.0), 1.0, Xz::new(0.0, 1.0), 1.0);
    assert_eq!(points.len(), 2);
    assert!(points.iter().all(|q| (q.z - 0.5).abs() < 1e-12));
}

#[test]
fn left_normal_of_a_cut_toward_the_chuck_points_to_larger_x() {
    // Turning an outside diameter toward -Z: the tool's left (G41) is +X.
    let n = left_normal(Xz::new(10.0, 0.0), Xz::new(10.0, -5.0));
    assert!(close(n, Xz::new(-1.0, 0.0)) || close(n, Xz::new(1.0, 0.0)));
    assert!(n.x.abs() > 0.99);
}

mod sector {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// `Sector::contains` decides as `angle_within` does, points next to the end rays
        /// included (there it asks the angles).
        #[test]
        fn decides_as_angle_within(
            a0 in -4.0f64..4.0, sweep_angle in 0.001f64..6.2, radius in 0.01f64..500.0,
            a in -4.0f64..4.0, distance in 0.0f64..3.0, ccw: bool, near_end: bool,
            cx in -200.0f64..200.0, cz in -200.0f64..200.0,
        ) {
            let centre = Xz::new(cx, cz);
            let a1 = if ccw { a0 + sweep_angle } else { a0 - sweep_angle };
            let (start, end) = (on_circle(centre, radius, a0), on_circle(centre, radius, a1));
            let a = if near_end { a1 + a * 1e-9 } else { a };
            let point = on_circle(centre, radius * distance, a);
            prop_assume!(distance > 1e-9);
            let sector = Sector::new(start, end, centre, ccw);
            prop_assert_eq!(sector.contains(point), angle_within(point, start, end, centre, ccw));
            // Measured up front or when asked, the angles are the same.
            let unmeasured = Sector::unmeasured(start, end, centre, ccw);
            prop_assert_eq!(unmeasured.contains(point), sector.contains(point));
            prop_assert_eq!(sector.total().to_bits(), sweep(start, end, centre, ccw).to_bits());
            prop_assert_eq!(unmeasured.total().to_bits(), sector.total().to_bits());
            prop_assert_eq!(unmeasured.start_angle().to_bits(), angle(start, centre).to_bits());
            prop_assert_eq!(sector.start_angle().to_bits(), angle(start, centre).to_bits());
        }
    }

    #[test]
    fn a_full_circle_contains_every_direction_and_a_half_circle_its_end_rays() {
        let centre = Xz::new(1.0, 2.0);
        let at = |x: f64, z: f64| Xz::new(centre.x + x, centre.z + z);
        let start = at(0.0, 5.0);
        let full = Sector::new(start, start, centre, true);
        for k in 0..16 {
            let a = f64::from(k) * TAU / 16.0;
            assert!(full.contains(at(a.sin(), a.cos())));
        }
        // G03 from +Z to −Z about the centre sweeps through +X.
        let half = Sector::new(start, at(0.0, -5.0), centre, true);
        assert!(half.contains(at(0.0, 1.0)) && half.contains(at(0.0, -1.0)));
        assert!(half.contains(at(1.0, 0.0)) && !half.contains(at(-1.0, 0.0)));
        let half_cw = Sector::new(start, at(0.0, -5.0), centre, false);
        assert!(half_cw.contains(at(-1.0, 0.0)) && !half_cw.contains(at(1.0, 0.0)));
    }
}

/// Whether `p` lies inside the sweep as the arc gauges measure it, by the angles.
fn inside_by_angles(p: Xz, start: Xz, end: Xz, centre: Xz, ccw: bool) -> bool {
    let (a0, a) = (angle(start, centre), angle(p, centre));
    let delta = if ccw { (a - a0).rem_euclid(TAU) } else { (a0 - a).rem_euclid(TAU) };
    delta <= sweep(start, end, centre, ccw)
}

#[test]
fn sweep_sides_place_points_as_the_angles_do_and_leave_the_ends_to_them() {
    let centre = Xz::new(20.0, -30.0);
    let on = |degrees: f64| on_circle(centre, 5.0, degrees.to_radians());
    // A quarter from 10° to 100° counter-clockwise: 55° is inside, 200° outside; both ways
    // round, the clockwise arc is the rest of the turn.
    let sides = SweepSides::new(on(10.0), on(100.0), centre, true);
    assert_eq!((sides.inside(on(55.0)), sides.inside(on(200.0))), (Some(true), Some(false)));
    let sides = SweepSides::new(on(10.0), on(100.0), centre, false);
    assert_eq!((sides.inside(on(55.0)), sides.inside(on(200.0))), (Some(false), Some(true)));
    // Within a nanoradian of an end, only the angles can tell.
    let sides = SweepSides::new(on(10.0), on(100.0), centre, true);
    assert_eq!(sides.inside(on(10.0 + 1e-9_f64.to_degrees())), None);
    // An arc whose ends meet may be a full circle (`sweep`): nothing is outside it.
    let sides = SweepSides::new(on(10.0), on(10.0), centre, true);
    assert_eq!(sides.inside(on(200.0)), None);
}

proptest::proptest! {
    #[test]
    fn sweep_sides_agree_with_the_angles_wherever_they_answer(
        from in -4.0f64..4.0, span in -7.0f64..7.0, at in -4.0f64..4.0, off in -0.01f64..0.01,
        near in proptest::bool::ANY, ccw in proptest::bool::ANY,
    ) {
        let centre = Xz::new(31.7, -12.3);
        let start = on_circle(centre, 7.5, from);
        let end = on_circle(centre, 7.5 + off, from + span);
        // Points anywhere, and points within a few micro-radians of the ends.
        let a = if near { from + span + at * 1e-6 } else { at };
        let p = on_circle(centre, 7.5 - off, a);
        if let Some(inside) = SweepSides::new(start, end, centre, ccw).inside(p) {
            proptest::prop_assert_eq!(inside, inside_by_angles(p, start, end, centre, ccw));
        }
    }
}

proptest::proptest! {
    #[test]
    fn rem_turn_is_rem_euclid_by_a_turn(x in -20.0f64..20.0, exactly in 0usize..5) {
        let x = [x, TAU, -TAU, 0.0, -0.0][exactly.min(4)];
        proptest::prop_assert_eq!(rem_turn(x).to_bits(), x.rem_euclid(TAU).to_bits());
    }
}

use proptest::prelude::Strategy as _;

proptest::proptest! {
    /// The part model's floor and ceiling agree with the standard library's everywhere,
    /// whole numbers, halves and the ends of the range included.
    #[test]
    fn floor_and_ceil_agree_with_the_standard_library(
        x in proptest::prop_oneof![
            proptest::num::f64::ANY,
            -1e6f64..1e6,
            (-1_000_000i64..1_000_000).prop_map(|k| k as f64),
            (-1_000_000i64..1_000_000).prop_map(|k| k as f64 + 0.5),
            (-1_000_000i64..1_000_000).prop_map(|k| k as f64 * 4.5e9),
        ]
    ) {
        let same = |a: f64, b: f64| a == b || (a.is_nan() && b.is_nan());
        proptest::prop_assert!(same(floor(x), x.floor()), "floor({x}) = {} not {}", floor(x), x.floor());
        proptest::prop_assert!(same(ceil(x), x.ceil()), "ceil({x}) = {} not {}", ceil(x), x.ceil());
    }
}
