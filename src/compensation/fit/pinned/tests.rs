use super::*;
use crate::compensation::fit::circle::tests::Noise;
use crate::geometry::on_circle;

fn arc(centre: Xz, radius: f64, from_deg: f64, sweep_deg: f64, n: usize) -> Vec<Xz> {
    (0..=n).map(|i| on_circle(centre, radius, (from_deg + sweep_deg * i as f64 / n as f64).to_radians())).collect()
}

fn close(a: Xz, b: Xz, within: f64) -> bool {
    a.distance(b) <= within
}

#[test]
fn the_offset_is_the_signed_orthogonal_distance_for_every_curvature() {
    let mut noise = Noise(5);
    let start = Xz::new(1.0, 2.0);
    let tangent = geometry::direction(Xz::new(0.0, 0.0), Xz::new(0.6, 0.8));
    for curvature in [0.5, 0.01, 1e-9, 0.0, -1e-9, -0.01, -0.5] {
        let bend = Bend { start, tangent, curvature };
        for _ in 0..50 {
            let q = Xz::new(start.x + 3.0 * noise.next(), start.z + 3.0 * noise.next());
            let expected = match bend.centre() {
                Some(centre) if curvature > 0.0 => q.distance(centre) - bend.radius(),
                Some(centre) => bend.radius() - q.distance(centre),
                // Right of travel is positive: minus the component along the left normal.
                None => -((q.x - start.x) * tangent.z - (q.z - start.z) * tangent.x),
            };
            // The reference subtracts two numbers of the size of the radius; δ does not.
            let tolerance = 1e-12 * (1.0 + expected.abs()) + 1e-15 * bend.radius().min(1e12);
            assert!((bend.offset(q) - expected).abs() <= tolerance, "κ {curvature}: {} vs {expected}", bend.offset(q));
            // The projection goes through the centre: a far centre costs its own rounding.
            assert!(bend.offset(bend.project(q)).abs() < 1e-9 + 1e-15 * bend.radius().min(1e12));
        }
    }
}

#[test]
fn through_ends_recovers_minor_major_and_clockwise_arcs() {
    for (centre, radius, from, sweep) in [
        (Xz::new(5.0, -3.0), 12.0, 20.0, 80.0),
        (Xz::new(0.0, 0.0), 25.4, 90.0, -90.0),
        (Xz::new(2.0, 1.0), 4.0, -30.0, 270.0),
    ] {
        let points = arc(centre, radius, from, sweep, 30);
        let (first, rest) = points.split_first().unwrap();
        let (last, interior) = rest.split_last().unwrap();
        let ccw = sweep > 0.0;
        for refine in [false, true] {
            let bend = through_ends(*first, *last, interior, Some(ccw), None, refine).unwrap();
            assert!(close(bend.centre().unwrap(), centre, 1e-9), "{:?} vs {centre:?}", bend.centre());
            assert!((bend.radius() - radius).abs() < 1e-9);
            assert_eq!(bend.segment_to(*last), Segment::Arc { end: *last, centre: bend.centre().unwrap(), ccw });
        }
        // Asked for the other sense, the circle is the same but the arc is the other way
        // round it, far from the points.
        let other = through_ends(*first, *last, interior, Some(!ccw), None, true).unwrap();
        assert_eq!(other.curvature > 0.0, !ccw);
        let segment = other.segment_to(*last);
        assert!(crate::compensation::fit::segment_deviation(*first, &segment, interior) > radius / 2.0);
    }
}

#[test]
fn through_ends_refined_is_the_orthogonal_optimum_with_its_ends_fixed() {
    let mut noise = Noise(21);
    let points: Vec<Xz> = arc(Xz::new(0.0051, 0.0057), 25.3958, 90.0, -90.0, 100)
        .into_iter()
        .map(|p| Xz::new(p.x + 0.002 * noise.next(), p.z + 0.002 * noise.next()))
        .collect();
    let (first, rest) = points.split_first().unwrap();
    let (last, interior) = rest.split_last().unwrap();
    let cost = |bend: &Bend| interior.iter().map(|&q| bend.offset(q).powi(2)).sum::<f64>();
    let algebraic = through_ends(*first, *last, interior, Some(false), None, false).unwrap();
    let best = through_ends(*first, *last, interior, Some(false), None, true).unwrap();
    assert!(cost(&best) <= cost(&algebraic));
    assert!(best.offset(*first).abs() < 1e-12 && best.offset(*last).abs() < 1e-9);
    let family =
        EndFamily { from: *first, chord: first.distance(*last), along: geometry::direction(*first, *last), interior };
    let alpha = (best.curvature * family.chord / 2.0).asin();
    assert!((family.bend(alpha).curvature - best.curvature).abs() < 1e-15);
    for step in [1e-8, 1e-6, 1e-4] {
        for sign in [-1.0, 1.0] {
            assert!(
                cost(&family.bend(alpha + sign * step)) > cost(&best),
                "a step of {} lowered the cost",
                sign * step
            );
        }
    }
}

#[test]
fn nearly_straight_points_give_a_line_and_no_interior_takes_the_hint() {
    let from = Xz::new(10.0, 0.0);
    let to = Xz::new(10.0, -50.0);
    let straight: Vec<Xz> = (1..50).map(|i| Xz::new(10.0, -f64::from(i))).collect();
    let bend = through_ends(from, to, &straight, None, None, true).unwrap();
    assert!(bend.curvature.abs() < 1e-12);
    assert_eq!(bend.segment_to(to), Segment::Line { end: to });
    let hinted = through_ends(from, to, &[], Some(true), Some(1.0 / 30.0), true).unwrap();
    assert!((hinted.radius() - 30.0).abs() < 1e-9 && hinted.curvature > 0.0);
    assert_eq!(through_ends(from, from, &straight, None, None, true), None);
}

#[test]
fn tangent_circles_fit_the_curvature_and_reach_the_end() {
    let centre = Xz::new(-3.0, 4.0);
    let points = arc(centre, 7.0, 10.0, 60.0, 20);
    let (start, rest) = points.split_first().unwrap();
    // Counter-clockwise at 10°: the tangent of increasing angle is (cos, −sin) in (x, z).
    let a = 10f64.to_radians();
    let tangent = Xz::new(a.cos(), -a.sin());
    let fitted = with_tangent(*start, tangent, rest);
    assert!((fitted.curvature - 1.0 / 7.0).abs() < 1e-12);
    assert!(close(fitted.centre().unwrap(), centre, 1e-9));
    let end = *rest.last().unwrap();
    let reaching = with_tangent_to(*start, tangent, end);
    assert!((reaching.curvature - 1.0 / 7.0).abs() < 1e-12);
    let exit = reaching.tangent_at(end);
    let b = 70f64.to_radians();
    assert!(close(exit, Xz::new(b.cos(), -b.sin()), 1e-12), "{exit:?}");
    // Clockwise the other way round.
    let back = with_tangent_to(end, Xz::new(-exit.x, -exit.z), *start);
    assert!((back.curvature + 1.0 / 7.0).abs() < 1e-12);
}

#[test]
fn a_full_circle_is_pinned_to_its_start() {
    let centre = Xz::new(0.0153, 0.0930);
    let mut points = arc(centre, 100.011, 90.0, 360.0, 72);
    let start = points.remove(0);
    let circle = through_point(start, &points).unwrap();
    assert!(close(circle.centre, centre, 1e-9));
    assert!((circle.radius - 100.011).abs() < 1e-9);
}
