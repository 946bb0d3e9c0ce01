use super::*;
use crate::compensation::fit::circle::tests::Noise;
use crate::geometry::on_circle;

/// 0.001 mm on the diameter and on Z: 0.0005 mm in X as a radius.
const GRID: Grid = Grid { x_mm: 0.0005, z_mm: 0.001 };

fn on_grid(value: f64, step: f64) -> bool {
    ((value / step) - (value / step).round()).abs() < 1e-6
}

#[test]
fn ten_thousand_segments_do_not_drift() {
    // A wandering path of lines and arcs whose exact ends are nowhere near the grid.
    let mut noise = Noise(99);
    let mut segments = Vec::new();
    let mut exact = Xz::new(12.34567, -3.21098);
    let start = exact;
    for i in 0..10_000 {
        let end = Xz::new(exact.x + 0.0123 + 0.01 * noise.next(), exact.z - 0.0371 + 0.02 * noise.next());
        segments.push(if i % 3 == 0 {
            // The arc of radius 1 through both ends, turning left.
            let centre = geometry::centre_from_radius(exact, end, 1.0, true, 0.0).unwrap();
            Segment::Arc { end, centre, ccw: true }
        } else {
            Segment::Line { end }
        });
        exact = end;
    }
    let form = ArcForm::Centre { grid: GRID, tolerance_mm: 0.001 };
    let q = quantize(start, &segments, &[], GRID, form);
    assert_eq!(q.segments.len(), segments.len());
    assert!(q.failures.is_empty(), "{:?}", q.failures.first());
    // Every end is within half an increment of its exact place: none has drifted.
    for (rounded, exact) in q.segments.iter().zip(&segments) {
        let (r, e) = (rounded.end(), exact.end());
        assert!((r.x - e.x).abs() <= GRID.x_mm / 2.0 + 1e-12 && (r.z - e.z).abs() <= GRID.z_mm / 2.0 + 1e-12);
        assert!(on_grid(r.x, GRID.x_mm) && on_grid(r.z, GRID.z_mm));
    }
    // The last end is the exact end rounded, so differences of these absolutes (U, W) sum
    // back to it.
    assert_eq!(q.segments.last().unwrap().end(), GRID.round(exact));
    // Rounding each increment instead would have walked away: the test can tell.
    let mut walked = q.start;
    let mut from = start;
    for s in &segments {
        let step = Xz::new(s.end().x - from.x, s.end().z - from.z);
        walked = Xz::new(walked.x + round_to(step.x, GRID.x_mm), walked.z + round_to(step.z, GRID.z_mm));
        from = s.end();
    }
    assert!((walked.x - exact.x).abs() > GRID.x_mm || (walked.z - exact.z).abs() > GRID.z_mm, "{walked:?} {exact:?}");
}

#[test]
fn centre_form_arcs_keep_both_ends_on_one_radius_within_the_control_tolerance() {
    let centre = Xz::new(0.00513, 0.00571);
    let from = on_circle(centre, 25.39581, 90.1f64.to_radians());
    let end = on_circle(centre, 25.39581, 0.3f64.to_radians());
    let points: Vec<Xz> =
        (1..=100).map(|i| on_circle(centre, 25.39581, (90.1 - 0.898 * f64::from(i)).to_radians())).collect();
    let arc = [Segment::Arc { end, centre, ccw: false }];
    let q = quantize(from, &arc, &points, GRID, ArcForm::Centre { grid: GRID, tolerance_mm: 0.001 });
    assert!(q.failures.is_empty());
    let Segment::Arc { end: e, centre: c, ccw: false } = q.segments[0] else { panic!("{:?}", q.segments) };
    assert!((q.start.distance(c) - e.distance(c)).abs() <= 0.001);
    // The offset I K from the rounded start is on the grid.
    assert!(on_grid(c.x - q.start.x, GRID.x_mm) && on_grid(c.z - q.start.z, GRID.z_mm));
    // Rounding cost at most about an increment.
    assert!(q.max_deviation_mm < 0.0015, "{}", q.max_deviation_mm);
    // A control that takes no mismatch at all: no grid centre will do, and it is reported.
    let strict = quantize(from, &arc, &points, GRID, ArcForm::Centre { grid: GRID, tolerance_mm: 0.0 });
    assert!(matches!(strict.failures[..], [ArcFailure { index: 0, problem: ArcProblem::RadiusMismatch { .. } }]));
    assert_eq!(strict.segments[0], Segment::Line { end: e });
}

#[test]
fn radius_form_arcs_are_circles_with_a_radius_on_the_grid_and_keep_their_side() {
    let centre = Xz::new(3.0003, -7.00007);
    for (from_deg, to_deg, ccw) in [(10.0, 80.0, true), (10.0, 260.0, true), (200.0, -20.0, false)] {
        let from = on_circle(centre, 5.43217, f64::to_radians(from_deg));
        let end = on_circle(centre, 5.43217, f64::to_radians(to_deg));
        let q =
            quantize(from, &[Segment::Arc { end, centre, ccw }], &[], GRID, ArcForm::Radius { increment_mm: 0.001 });
        let Segment::Arc { end: e, centre: c, ccw: same } = q.segments[0] else { panic!("{:?}", q.segments) };
        assert_eq!(same, ccw);
        let radius = q.start.distance(c);
        assert!((radius - e.distance(c)).abs() < 1e-9 && on_grid(radius, 0.001), "{radius}");
        let exact_sweep = geometry::sweep(from, end, centre, ccw);
        assert_eq!(geometry::sweep(q.start, e, c, ccw) > PI, exact_sweep > PI);
        assert!(c.distance(centre) < 0.003, "{c:?}");
    }
}

#[test]
fn arcs_that_vanish_or_cannot_be_written_become_lines_and_are_reported() {
    // A 0.2 µm arc rounds to nothing: a control would run a full circle.
    let from = Xz::new(1.0001, 2.0001);
    let tiny = Segment::Arc { end: Xz::new(1.0002, 2.0002), centre: Xz::new(1.0, 2.5), ccw: true };
    let q = quantize(from, &[tiny], &[], GRID, ArcForm::Centre { grid: GRID, tolerance_mm: 0.001 });
    assert_eq!(q.failures, vec![ArcFailure { index: 0, problem: ArcProblem::Vanished }]);
    assert!(matches!(q.segments[0], Segment::Line { .. }));
    // A full circle: written with I K, refused with R.
    let start = Xz::new(10.0, 0.0);
    let full = Segment::Arc { end: start, centre: Xz::new(0.0, 0.0), ccw: true };
    let by_centre = quantize(start, &[full], &[], GRID, ArcForm::Centre { grid: GRID, tolerance_mm: 0.001 });
    assert!(by_centre.failures.is_empty() && matches!(by_centre.segments[0], Segment::Arc { .. }));
    let by_radius = quantize(start, &[full], &[], GRID, ArcForm::Radius { increment_mm: 0.001 });
    assert_eq!(by_radius.failures, vec![ArcFailure { index: 0, problem: ArcProblem::FullCircleByRadius }]);
}
