use proptest::prelude::*;

use super::*;

fn infeed(mode: InfeedMode, pattern: InfeedPattern, d: f64, h: f64, u: Option<f64>) -> Infeed {
    Infeed { mode, pattern, first_depth: d, height: h, allowance: u }
}

fn depths(plan: &Plan) -> Vec<f64> {
    plan.passes.iter().map(|p| p.depth).collect()
}

fn close(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
}

#[test]
fn pattern_1_cuts_d_per_pass_then_the_rest_then_the_allowance() {
    // H 1.8, U 0.2: rough to 1.6 in steps of 0.5 → 0.5, 1.0, 1.5, 1.6, then 1.8.
    let plan = plan(&infeed(InfeedMode::OneFlank, InfeedPattern::ConstantDepth, 0.5, 1.8, Some(0.2))).unwrap();
    assert!(close(&depths(&plan), &[0.5, 1.0, 1.5, 1.6, 1.8]), "{:?}", depths(&plan));
    assert!(plan.passes.last().unwrap().finishing);
    assert!(plan.passes.iter().all(|p| p.flank == 1.0));
}

#[test]
fn pattern_2_cuts_equal_areas() {
    // D 0.6, H 1.8, no allowance: 0.6·√n below 1.8 for n = 1..8 (0.6·3 = 1.8 is the ninth).
    let plan = plan(&infeed(InfeedMode::OtherFlank, InfeedPattern::ConstantArea, 0.6, 1.8, None)).unwrap();
    let expected: Vec<f64> = (1..=9).map(|n| 0.6 * (n as f64).sqrt()).collect();
    assert!(close(&depths(&plan), &expected), "{:?}", depths(&plan));
    assert!(plan.passes.iter().all(|p| p.flank == -1.0 && !p.finishing));
}

#[test]
fn pattern_3_zigzag_puts_odd_passes_halfway() {
    // D 1, H 2, U 0.3: even passes at 1, √2, 1.7 (clamped); odd passes halfway; finish at 2.
    // D² = 1 ≥ H² − (H − U)² = 4 − 2.89 = 1.11 fails, so the plan says it approximated.
    let plan = plan(&infeed(InfeedMode::Zigzag, InfeedPattern::Pattern3, 1.0, 2.0, Some(0.3))).unwrap();
    let r2 = 2f64.sqrt();
    let expected = [0.5, 1.0, (1.0 + r2) / 2.0, r2, (r2 + 1.7) / 2.0, 1.7, 2.0];
    assert!(close(&depths(&plan), &expected), "{:?}", depths(&plan));
    let flanks: Vec<f64> = plan.passes.iter().map(|p| p.flank).collect();
    assert_eq!(flanks, [1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0]);
    assert!(plan.approximated);
    let documented = plan_of(1.2, 2.0, Some(0.3));
    assert!(!documented.approximated);
}

fn plan_of(d: f64, h: f64, u: Option<f64>) -> Plan {
    plan(&infeed(InfeedMode::OneFlank, InfeedPattern::Pattern3, d, h, u)).unwrap()
}

#[test]
fn the_control_rejects_what_the_manual_forbids() {
    let e = |pattern, d, h, u| plan(&infeed(InfeedMode::OneFlank, pattern, d, h, u)).err();
    assert_eq!(
        e(InfeedPattern::ConstantDepth, 0.5, 0.6, Some(0.2)),
        Some(InfeedError::RoughDepthBelowFirstCut { rough_depth: 0.6 - 0.2 })
    );
    assert_eq!(e(InfeedPattern::ConstantArea, 0.5, 0.6, Some(0.7)), Some(InfeedError::AllowanceOverHeight));
    assert_eq!(e(InfeedPattern::Pattern3, 0.5, 0.6, Some(0.7)), Some(InfeedError::AllowanceOverHeight));
    assert_eq!(e(InfeedPattern::ConstantArea, 0.0, 0.6, None), Some(InfeedError::FirstDepthNotPositive));
    assert_eq!(e(InfeedPattern::ConstantArea, 0.5, 0.0, None), Some(InfeedError::HeightNotPositive));
    assert!(matches!(e(InfeedPattern::ConstantArea, 0.001, 10.0, None), Some(InfeedError::TooManyPasses { .. })));
    // Pattern 2 accepts a first depth deeper than the thread: one pass at H − U, then H.
    let plan = plan(&infeed(InfeedMode::OneFlank, InfeedPattern::ConstantArea, 2.0, 0.6, Some(0.1))).unwrap();
    assert!(close(&depths(&plan), &[0.5, 0.6]));
}

fn modes() -> impl Strategy<Value = InfeedMode> {
    prop_oneof![Just(InfeedMode::OneFlank), Just(InfeedMode::Zigzag), Just(InfeedMode::OtherFlank)]
}

fn patterns() -> impl Strategy<Value = InfeedPattern> {
    prop_oneof![Just(InfeedPattern::ConstantDepth), Just(InfeedPattern::ConstantArea), Just(InfeedPattern::Pattern3)]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// Depths increase strictly, no rough pass goes below `H − U`, and the last pass is at `H`.
    #[test]
    fn passes_deepen_up_to_the_thread_height(
        mode in modes(),
        pattern in patterns(),
        d in 0.01f64..2.0,
        h in 0.05f64..4.0,
        u in prop::option::of(0.0f64..1.0),
    ) {
        let infeed = infeed(mode, pattern, d, h, u);
        match plan(&infeed) {
            Ok(plan) => {
                let depths = depths(&plan);
                prop_assert!(!depths.is_empty());
                for pair in depths.windows(2) {
                    prop_assert!(pair[1] > pair[0], "{depths:?}");
                }
                let rough = h - u.unwrap_or(0.0);
                for pass in plan.passes.iter().filter(|p| !p.finishing) {
                    prop_assert!(pass.depth <= rough + 1e-9, "{depths:?} rough {rough}");
                }
                prop_assert!((depths[depths.len() - 1] - h).abs() < 1e-9, "{depths:?} h {h}");
                prop_assert_eq!(plan.passes.iter().filter(|p| p.finishing).count(), usize::from(u.is_some_and(|u| u > 0.0)));
                if mode == InfeedMode::Zigzag {
                    for pair in plan.passes.windows(2) {
                        prop_assert_eq!(pair[0].flank, -pair[1].flank);
                    }
                }
            }
            Err(InfeedError::RoughDepthBelowFirstCut { .. }) => {
                prop_assert_eq!(pattern, InfeedPattern::ConstantDepth);
                prop_assert!(h - u.unwrap_or(0.0) < d);
            }
            Err(InfeedError::AllowanceOverHeight) => prop_assert!(u.unwrap_or(0.0) > h),
            Err(InfeedError::TooManyPasses { passes }) => prop_assert!(passes > MAX_PASSES),
            Err(other) => prop_assert!(false, "unexpected {other:?}"),
        }
    }

    /// Pattern 2: every rough pass but the last (cut short at `H − U`) removes the area of the
    /// first, `D²` in the units of a groove whose area grows with its depth squared.
    #[test]
    fn pattern_2_passes_remove_equal_areas(
        mode in modes(),
        d in 0.05f64..1.0,
        h in 0.1f64..3.0,
        u in prop::option::of(0.0f64..0.5),
    ) {
        let Ok(plan) = plan(&infeed(mode, InfeedPattern::ConstantArea, d, h, u)) else { return Ok(()) };
        let rough: Vec<f64> = plan.passes.iter().filter(|p| !p.finishing).map(|p| p.depth).collect();
        let mut previous = 0.0;
        for (i, depth) in rough.iter().enumerate() {
            let area = depth * depth - previous * previous;
            if i + 1 < rough.len() {
                prop_assert!((area - d * d).abs() < 1e-9 * d * d.max(1.0) + 1e-12, "pass {i}: {area} vs {}", d * d);
            } else {
                prop_assert!(area <= d * d + 1e-9, "last rough pass {i}: {area} vs {}", d * d);
            }
            previous = *depth;
        }
    }

    /// Pattern 1: every rough pass but the last cuts exactly `D`.
    #[test]
    fn pattern_1_passes_cut_equal_depths(
        d in 0.05f64..1.0,
        h in 0.1f64..3.0,
        u in prop::option::of(0.0f64..0.5),
    ) {
        let Ok(plan) = plan(&infeed(InfeedMode::OneFlank, InfeedPattern::ConstantDepth, d, h, u)) else {
            return Ok(());
        };
        let rough: Vec<f64> = plan.passes.iter().filter(|p| !p.finishing).map(|p| p.depth).collect();
        let mut previous = 0.0;
        for (i, depth) in rough.iter().enumerate() {
            let cut = depth - previous;
            if i + 1 < rough.len() {
                prop_assert!((cut - d).abs() < 1e-9, "pass {i} cuts {cut}, D {d}");
            } else {
                prop_assert!(cut <= d + 1e-9);
            }
            previous = *depth;
        }
    }
}
