use super::*;
use crate::semantic::cycles::canonical::{Canon, Element};

/// The `g85-longitudinal.nc` case in the canonical frame: A = r31 Z2, the contour X30 Z-20,
/// X40 Z-30, Z-50, X60 offset by U0.4 W0.1.
fn frame(start: Uv) -> RoughFrame {
    let points = [(15.2, 2.1), (15.2, -19.9), (20.2, -29.9), (20.2, -49.9), (30.2, -49.9)];
    let elements = points
        .windows(2)
        .map(|w| Element {
            start: Uv { u: w[0].0, v: w[0].1 },
            end: Uv { u: w[1].0, v: w[1].1 },
            arc: None,
            source: crate::source::Span::SYNTHETIC,
        })
        .collect();
    RoughFrame {
        canon: Canon { swap: false, mirror_u: false, mirror_v: false },
        start,
        contour_start: Uv { u: 15.2, v: 2.1 },
        allowance: Xz::new(0.2, 0.1),
        elements,
    }
}

#[test]
fn passes_start_on_the_infeed_line_and_stop_at_the_offset_contour() {
    let passes = plan(&frame(Uv { u: 31.0, v: 2.0 }), 4.0, 0.3, &Conditions::default()).unwrap();
    let expected = [(27.0, -49.9), (23.0, -49.9), (19.0, -27.5)];
    assert_eq!(passes.len(), expected.len());
    for (pass, (level, v_out)) in passes.iter().zip(expected) {
        assert!((pass.level - level).abs() < 1e-12);
        assert!((pass.v_in - (2.1 - 0.1 * (level - 15.2) / 15.8)).abs() < 1e-12, "{pass:?}");
        assert!((pass.v_out - v_out).abs() < 1e-9, "{pass:?}");
        assert_eq!(pass.feed, 0.3);
    }
}

#[test]
fn a_start_inside_the_allowance_is_refused() {
    let result = plan(&frame(Uv { u: 15.1, v: 2.0 }), 4.0, 0.3, &Conditions::default());
    assert_eq!(result, Err(DiagnosticKind::LapStartInsideContour));
}

#[test]
fn a_start_that_is_not_a_number_plans_nothing() {
    let passes = plan(&frame(Uv { u: f64::NAN, v: 2.0 }), 4.0, 0.3, &Conditions::default()).unwrap();
    assert!(passes.is_empty());
}

#[test]
fn conditions_apply_from_the_point_on_and_b_wins() {
    let conditions = Conditions {
        a: Some(Change { at: 35.0, depth: Some(2.0), feed: Some(0.25) }),
        b: Some(Change { at: 25.0, depth: Some(1.0), feed: None }),
    };
    assert_eq!(conditions.in_force(40.0, 4.0, 0.3), (4.0, 0.3));
    assert_eq!(conditions.in_force(35.0, 4.0, 0.3), (2.0, 0.25));
    assert_eq!(conditions.in_force(30.0, 4.0, 0.3), (2.0, 0.25));
    // B without a feed keeps the one in force, A's.
    assert_eq!(conditions.in_force(25.0, 4.0, 0.3), (1.0, 0.25));
    assert_eq!(conditions.in_force(10.0, 4.0, 0.3), (1.0, 0.25));
}
