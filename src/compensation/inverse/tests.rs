use super::*;
use crate::compensation::test_support::lower_program;
use crate::error_model::effects::*;
use crate::error_model::sampling::sample_toolpath;
use crate::semantic::Machine;
use crate::semantic::nose_radius::ToolTable;
use crate::toolpath::Toolpath;

const PROGRAM: &str = "\
G21 G99
G97 S1000 M03
G00 X40. Z2.
G01 Z-20. F0.2
X50. Z-25.
G02 X60. Z-30. R5.
G01 Z-40.
X40.
Z-20.
G00 X100. Z50.
M30
";

fn toolpath() -> (Toolpath, Machine) {
    let (lowered, machine) = lower_program(PROGRAM);
    (lowered.into_inner().toolpath, machine)
}

fn model(effects: Vec<Effect>) -> ErrorModel {
    ErrorModel { tables: None, effects, start_min: 0.0, control: None }
}

#[test]
fn a_constant_offset_is_mirrored_in_one_step() {
    let (path, machine) = toolpath();
    let samples = sample_toolpath(&path, &ToolTable::from_machine(&machine), 0.5);
    let m = model(vec![
        Effect::ToolOffsetX(ToolOffsetX { d: 0.01, axis: X }),
        Effect::ToolOffsetZ(ToolOffsetZ { d: -0.004, axis: Z }),
    ]);
    let result = compensate_samples(&samples, path.start, &m, &InverseOptions::default());
    assert_eq!(result.iterations, 1);
    assert!(result.max_residual_mm < 1e-12);
    for (s, c) in samples.iter().zip(&result.commanded) {
        assert!((c.x - (s.nominal.x - 0.01)).abs() < 1e-12 && (c.z - (s.nominal.z + 0.004)).abs() < 1e-12);
    }
}

#[test]
fn direction_dependent_and_position_dependent_errors_converge_below_the_tolerance() {
    let (path, machine) = toolpath();
    let samples = sample_toolpath(&path, &ToolTable::from_machine(&machine), 0.25);
    let m = model(vec![
        Effect::BacklashX(BacklashX { b: 0.006, axis: X }),
        Effect::BacklashZ(BacklashZ { b: 0.004, axis: Z }),
        Effect::ScaleZ(ScaleZ { ppm: 80.0, axis: Z }),
        Effect::CyclicZ(CyclicZ { amp: 0.002, pitch: 11.94, phase: 0.3, axis: Z }),
        Effect::Squareness(Squareness { urad: 30.0 }),
    ]);
    let options = InverseOptions { tolerance_mm: 1e-6, dead_band_mm: 1e-6, ..InverseOptions::default() };
    let result = compensate_samples(&samples, path.start, &m, &options);
    assert!(result.max_residual_mm <= 1e-6, "{} after {}", result.max_residual_mm, result.iterations);
    assert!(result.iterations <= 5, "{}", result.iterations);
    // The uncompensated path was off by micrometres; the compensated one is not.
    let before = samples.iter().zip(&result.uncompensated).map(|(s, a)| s.nominal.distance(*a)).fold(0.0, f64::max);
    assert!(before > 0.002, "{before}");
    // Re-predicting the commanded path from scratch gives the same answer.
    let again = predict(&samples, &result.commanded, path.start, &m);
    assert_eq!(again, result.predicted);
}

#[test]
fn rapids_are_sampled_at_their_end_and_dwells_not_at_all() {
    let (path, machine) = toolpath();
    let samples = sample_toolpath(&path, &ToolTable::from_machine(&machine), 1.0);
    for (k, m) in path.moves.iter().enumerate() {
        let of_move: Vec<_> = samples.iter().filter(|s| s.move_index == k).collect();
        match m.motion {
            crate::toolpath::Motion::Rapid => assert_eq!(of_move.len(), 1),
            crate::toolpath::Motion::Dwell => assert!(of_move.is_empty()),
            _ => {
                assert!(of_move.len() >= 2);
                let last = of_move.last().unwrap();
                assert_eq!(last.nominal, m.end);
                assert_eq!(last.param, 1.0);
            }
        }
    }
}

#[test]
fn terms_of_time_given_once_per_sample_solve_and_predict_as_evaluated_at_each_command() {
    let (path, machine) = toolpath();
    let samples = sample_toolpath(&path, &ToolTable::from_machine(&machine), 0.25);
    let m = ErrorModel {
        start_min: 20.0,
        ..model(vec![
            Effect::BacklashX(BacklashX { b: 0.004, axis: X }),
            Effect::ThermalX(ThermalX { amp: -0.003, tau_min: 12.0, axis: X }),
            Effect::ScaleZ(ScaleZ { ppm: 30.0, axis: Z }),
            Effect::ThermalZ(ThermalZ { amp: 0.008, tau_min: 54.59, axis: Z }),
        ])
    };
    let mut terms = Vec::new();
    time_terms(&samples, &m, &mut terms);
    assert_eq!(terms.len(), 2 * samples.len());
    let solved = |terms: &[Xz]| {
        let mut inverse = Inverse::new(path.start, &m, &InverseOptions::default());
        let (mut commanded, mut predicted) = (Vec::new(), Vec::new());
        inverse.solve(&samples, terms, (&mut commanded, &mut Vec::new()), Some(&mut predicted));
        (commanded, predicted, inverse.iterations)
    };
    let (with_terms, without) = (solved(&terms), solved(&[]));
    assert_eq!(with_terms, without);
    assert!(with_terms.2 >= 2, "{}", with_terms.2);
    let predicted = |terms: &[Xz], nominal: bool| {
        let mut out = Vec::new();
        let mut predictor = Predictor::new(path.start, &m);
        if nominal {
            predictor.predict_nominal(&samples, terms, &mut out);
        } else {
            predictor.predict(&samples, terms, &with_terms.0, &mut out);
        }
        out
    };
    assert_eq!(predicted(&terms, false), with_terms.1);
    assert_eq!(predicted(&terms, true), predicted(&[], true));
    let nominal: Vec<Xz> = samples.iter().map(|s| s.nominal).collect();
    assert_eq!(predicted(&terms, true), predict(&samples, &nominal, path.start, &m));
}

#[test]
fn the_largest_residual_is_the_root_of_the_largest_square() {
    let (path, machine) = toolpath();
    let samples = sample_toolpath(&path, &ToolTable::from_machine(&machine), 0.25);
    let m =
        model(vec![Effect::BacklashX(BacklashX { b: 0.006, axis: X }), Effect::ScaleZ(ScaleZ { ppm: 80.0, axis: Z })]);
    let options = InverseOptions { max_iterations: 1, ..InverseOptions::default() };
    let result = compensate_samples(&samples, path.start, &m, &options);
    let largest = samples.iter().zip(&result.predicted).map(|(s, &a)| s.nominal.distance(a)).fold(0.0, f64::max);
    assert!(largest > 0.0);
    assert_eq!(result.max_residual_mm.to_bits(), largest.to_bits());
}
