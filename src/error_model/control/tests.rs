use super::*;
use crate::error_model::effects::EffectKind;
use crate::error_model::effects::backlash::{BacklashX, BacklashZ};
use crate::error_model::effects::cyclic::CyclicZ;
use crate::error_model::effects::scale::ScaleX;
use crate::error_model::state::{Signs, Tracker};

fn along(axis: Axis, d: Xz) -> f64 {
    match axis {
        Axis::X => d.x,
        Axis::Z => d.z,
    }
}

/// Each effect's answer is true of its displacement: a pitch table's term is along its axis
/// and a function of that axis' position alone (not of the other axis, time, velocity,
/// direction, the cut, the tool); a cross-axis term is along its axis and does not move with
/// that axis' own position; a backlash is the effect's own play.
#[test]
fn every_effect_is_what_its_table_part_says() {
    let base = Sample {
        velocity: Xz::new(600.0, -300.0),
        t_min: 7.5,
        cut_length_m: 2.0,
        normal: Xz::new(0.6, 0.8),
        tip: Xz::new(1.0, 1.0),
        ..Sample::at_rest(Xz::new(20.0, -50.0), 0.0)
    };
    for kind in EffectKind::ALL {
        let effect = kind.fitted([0.002, 0.001], 30.0);
        let d = |s: &Sample| effect.displacement(s);
        match effect.control_table() {
            TablePart::Pitch(axis) => {
                let others = [
                    Sample {
                        at: Xz::new(
                            base.at.x + if axis == Axis::Z { 17.0 } else { 0.0 },
                            base.at.z + if axis == Axis::X { 17.0 } else { 0.0 },
                        ),
                        ..base
                    },
                    Sample { t_min: 500.0, velocity: Xz::new(-50.0, 20.0), cut_length_m: 9.0, ..base },
                    Sample { direction: Signs { x: -1, z: -1 }, since_reversal: Xz::new(0.1, 0.1), ..base },
                    Sample { normal: Xz::new(-1.0, 0.0), tip: Xz::new(0.0, 0.0), ..base },
                ];
                for other in others {
                    assert_eq!(
                        d(&other),
                        d(&base),
                        "{}: a pitch table's term moves with no more than its axis",
                        kind.name()
                    );
                }
                let across = match axis {
                    Axis::X => d(&base).z,
                    Axis::Z => d(&base).x,
                };
                assert_eq!(across, 0.0, "{}", kind.name());
                assert_ne!(along(axis, d(&base)), 0.0, "{}: the fitted effect moves something", kind.name());
            }
            TablePart::CrossAxis(axis) => {
                let own = match axis {
                    Axis::X => Sample { at: Xz::new(base.at.x + 17.0, base.at.z), ..base },
                    Axis::Z => Sample { at: Xz::new(base.at.x, base.at.z + 17.0), ..base },
                };
                assert_eq!(d(&own), d(&base), "{}: a cross-axis term does not move with its own axis", kind.name());
                let across = match axis {
                    Axis::X => d(&base).z,
                    Axis::Z => d(&base).x,
                };
                assert_eq!(across, 0.0, "{}", kind.name());
            }
            TablePart::Backlash(axis, b) => {
                assert_eq!(along(axis, effect.play()), b, "{}", kind.name());
            }
            TablePart::Program(why) => assert!(!why.is_empty(), "{}", kind.name()),
        }
    }
}

#[test]
fn a_table_runs_linearly_or_by_steps_between_its_nodes() {
    let points = [(0.0, 0.001, -0.001), (10.0, 0.003, 0.001), (20.0, 0.002, 0.0)];
    let linear = AxisCompensation::new(&points, Between::Linear, 0.004);
    assert_eq!(linear.correction(-5.0, 1), 0.001);
    assert!((linear.correction(5.0, 1) - 0.002).abs() < 1e-15);
    assert!((linear.correction(15.0, -1) - 0.0005).abs() < 1e-15);
    assert_eq!(linear.correction(25.0, -1), 0.0);
    assert!((linear.total(5.0, 1) - 0.004).abs() < 1e-15);
    assert!((linear.total(5.0, -1) + 0.002).abs() < 1e-15);
    let steps = AxisCompensation::new(&points, Between::Steps, 0.0);
    assert_eq!(steps.correction(-5.0, 1), 0.001);
    assert_eq!(steps.correction(9.999, 1), 0.001);
    assert_eq!(steps.correction(10.0, 1), 0.003);
    assert_eq!(steps.correction(19.0, -1), 0.001);
    assert_eq!(steps.correction(30.0, 1), 0.002);
}

/// The machine with a table loaded, as `with_control` models it on the commands, against
/// the machine itself driven by the commands the control sends (each command moved by the
/// table's correction of the direction the command last moved in, as LinuxCNC does): the
/// same landing for every command, for a control that takes up all or more than the play
/// (its forward column above its reverse one by at least the play, as a table read from a
/// file is split: `control_table::axis_compensation`), across reversals larger and smaller
/// than the play; and for one that takes up less, the same landing once a reversal has
/// crossed the play.
#[test]
fn the_loaded_table_is_the_machine_driven_through_it() {
    let machine = ErrorModel {
        effects: vec![
            Effect::BacklashX(BacklashX { b: 0.006, axis: X }),
            Effect::BacklashZ(BacklashZ { b: 0.004, axis: Z }),
            Effect::ScaleX(ScaleX { ppm: 120.0, axis: X }),
            Effect::CyclicZ(CyclicZ { amp: 0.003, pitch: 7.0, phase: 0.4, axis: Z }),
        ],
        ..ErrorModel::default()
    };
    let table = |b_x: f64, b_z: f64| ControlCompensation {
        x: Some(AxisCompensation::new(
            &[(0.0, 0.0001, 0.0), (40.0, -0.0047, -0.0048), (80.0, -0.0095, -0.0096)],
            Between::Linear,
            b_x,
        )),
        z: Some(AxisCompensation::new(&[(-30.0, 0.001, 0.0), (0.0, -0.002, -0.002)], Between::Linear, b_z)),
    };
    // Reversals of 2 mm and of 1, 3 and 0.5 µm, inside the play.
    let mut path = vec![Xz::new(10.0, -5.0)];
    for (dx, dz) in [
        (30.0, -12.0),
        (-2.0, 0.001),
        (0.001, -0.003),
        (-0.0005, 0.0005),
        (25.0, -10.0),
        (-0.003, 8.0),
        (0.0, -0.001),
        (-20.0, 0.0),
    ] {
        let last = *path.last().unwrap();
        for k in 1..=10 {
            let t = f64::from(k) / 10.0;
            path.push(Xz::new(last.x + dx * t, last.z + dz * t));
        }
    }
    for (b_x, b_z) in [(0.006, 0.004), (0.008, 0.005), (0.004, 0.001)] {
        let takes_up_all = b_x >= 0.006 && b_z >= 0.004;
        let control = table(b_x, b_z);
        let loaded = machine.with_control(control.clone());
        let mut direction = Signs { x: 1, z: 1 };
        let drive = |p: Xz, d: Signs| {
            Xz::new(
                p.x + control.x.as_ref().unwrap().total(p.x, d.x),
                p.z + control.z.as_ref().unwrap().total(p.z, d.z),
            )
        };
        let mut real = Tracker::new(drive(path[0], direction), machine.play());
        let mut modelled = Tracker::new(path[0], loaded.play());
        let at = |t: &Tracker| t.sample(0.0, Xz::new(0.0, 0.0), 0, Xz::new(0.0, 0.0), Xz::new(0.0, 0.0));
        for pair in path.windows(2) {
            let (from, to) = (pair[0], pair[1]);
            if to.x != from.x {
                direction.x = if to.x > from.x { 1 } else { -1 };
            }
            if to.z != from.z {
                direction.z = if to.z > from.z { 1 } else { -1 };
            }
            real.advance(drive(to, direction), 0, false);
            modelled.advance(to, 0, false);
            let (lands, predicted) = (machine.actual(&at(&real)), loaded.actual(&at(&modelled)));
            // Less than the play taken up: inside the rest of it the machine takes up the
            // table's switched remainder later than the model, which switches it with the
            // slide; they agree again once the reversal crosses the play.
            let since = at(&real).since_reversal;
            if !takes_up_all && (since.x < 0.01 || since.z < 0.01) {
                continue;
            }
            // The terms of position are evaluated at the command with its pitch correction in
            // the model and with its backlash correction besides on the machine: the slope
            // of the cyclic error times half the play, nanometres.
            assert!(
                lands.distance(predicted) < 1e-5,
                "b_c = {b_x}, {b_z}: at {to:?} the machine lands at {lands:?}, the model says {predicted:?}"
            );
        }
    }
}
