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
        /// `Sector::contains` decides as `angle_within` does, for every point not within
        /// a millionth of a radian of the arc's end rays (where either answer measures the
        /// same distance, and the two may differ by the last bits of an angle).
        #[test]
        fn decides_as_angle_within(
            a0 in -4.0f64..4.0, sweep_angle in 0.001f64..6.2, radius in 0.01f64..500.0,
            a in -4.0f64..4.0, distance in 0.0f64..3.0, ccw: bool,
            cx in -200.0f64..200.0, cz in -200.0f64..200.0,
        ) {
            let centre = Xz::new(cx, cz);
            let a1 = if ccw { a0 + sweep_angle } else { a0 - sweep_angle };
            let (start, end) = (on_circle(centre, radius, a0), on_circle(centre, radius, a1));
            let point = on_circle(centre, radius * distance, a);
            let near = |ray: f64| (a - ray).rem_euclid(TAU).min((ray - a).rem_euclid(TAU)) < 1e-6;
            prop_assume!(!near(a0) && !near(a1) && distance > 1e-9);
            let sector = Sector::new(start, end, centre, ccw);
            let offset = Xz::new(point.x - centre.x, point.z - centre.z);
            prop_assert_eq!(sector.contains(offset), angle_within(point, start, end, centre, ccw));
        }
    }

    #[test]
    fn a_full_circle_contains_every_direction_and_a_half_circle_its_end_rays() {
        let centre = Xz::new(1.0, 2.0);
        let start = Xz::new(1.0, 7.0);
        let full = Sector::new(start, start, centre, true);
        for k in 0..16 {
            let a = f64::from(k) * TAU / 16.0;
            assert!(full.contains(Xz::new(a.sin(), a.cos())));
        }
        // G03 from +Z to −Z about the centre sweeps through +X.
        let half = Sector::new(start, Xz::new(1.0, -3.0), centre, true);
        assert!(half.contains(Xz::new(0.0, 1.0)) && half.contains(Xz::new(0.0, -1.0)));
        assert!(half.contains(Xz::new(1.0, 0.0)) && !half.contains(Xz::new(-1.0, 0.0)));
        let half_cw = Sector::new(start, Xz::new(1.0, -3.0), centre, false);
        assert!(half_cw.contains(Xz::new(-1.0, 0.0)) && !half_cw.contains(Xz::new(1.0, 0.0)));
    }
}
