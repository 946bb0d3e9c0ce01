use super::*;
use crate::diagnose::measured::{BallBarRow, ProfilePoint};
use crate::diagnose::test_support::{BALL_BAR, DOME, nominal};
use crate::error_model::effects::*;

fn trace(step_deg: f64) -> Vec<BallBarRow> {
    let mut rows = Vec::new();
    for direction in [Direction::Ccw, Direction::Cw] {
        let mut travel = step_deg;
        while travel <= 360.0 + 1e-9 {
            let angle = direction.sign() * travel;
            rows.push(BallBarRow {
                angle_deg: angle.rem_euclid(360.0),
                deviation_mm: 0.0,
                direction,
                line: rows.len() + 2,
            });
            travel += step_deg;
        }
    }
    rows
}

fn model(effects: Vec<Effect>) -> ErrorModel {
    ErrorModel { tables: None, effects, start_min: 0.0, control: None }
}

#[test]
fn a_ball_bar_reads_the_squareness_oval_at_every_angle() {
    let nominal = nominal(BALL_BAR);
    let forward = Forward::new(&nominal, &Measured::BallBar(trace(1.0))).unwrap();
    assert_eq!(forward.len(), 720);
    assert_eq!(forward.groups.len(), 1, "one bar set-up for both runs");
    let alpha = 50e-6;
    let simulated = forward.simulate(&model(vec![Effect::Squareness(Squareness { urad: 50.0 })]));
    for (p, reading) in forward.points.iter().zip(&simulated.readings) {
        let theta = p.angle_deg.unwrap().to_radians();
        // dx = z α with z = −50 + 50 cos θ; radially, dx sin θ to first order.
        let z = -50.0 + 50.0 * theta.cos();
        let expected = ((50.0 * theta.sin() + z * alpha).powi(2) + (50.0 * theta.cos()).powi(2)).sqrt() - 50.0;
        assert!((reading - expected).abs() < 1e-12, "{theta}: {reading} vs {expected}");
    }
    for (p, state) in forward.points.iter().zip(&simulated.states) {
        assert!(state.at.distance(p.nominal) < 1e-9, "{:?} vs {:?}", state.at, p.nominal);
    }
}

#[test]
fn servo_mismatch_flips_with_the_direction_and_backlash_steps_at_the_reversals() {
    let nominal = nominal(BALL_BAR);
    let forward = Forward::new(&nominal, &Measured::BallBar(trace(1.0))).unwrap();
    let simulated = forward.simulate(&model(vec![Effect::ServoMismatch(ServoMismatch { dt_ms: 0.06 })]));
    // dx = −vx dt, vx = ±F cos θ: radially ∓(F dt / 2) sin 2θ, to first order (the
    // displacement is 1 µm, so the second-order term is 1e-8 mm).
    let amplitude = 1000.0 / 60_000.0 * 0.06 / 2.0;
    for (p, reading) in forward.points.iter().zip(&simulated.readings) {
        let theta = p.angle_deg.unwrap().to_radians();
        let expected = -p.direction.unwrap().sign() * amplitude * (2.0 * theta).sin();
        assert!((reading - expected).abs() < 2e-8, "{theta}: {reading} vs {expected}");
    }
    let b = 0.004;
    let simulated = forward.simulate(&model(vec![Effect::BacklashX(BacklashX { b, axis: X })]));
    // CCW from the top: X falls from 90° to 270° (slide above its command by b/2) and
    // rises elsewhere; away from the reversals the reading is ∓ b/2 · sin θ.
    for (p, reading) in forward.points.iter().zip(&simulated.readings) {
        let degrees = p.angle_deg.unwrap();
        if p.direction == Some(Direction::Ccw) && (100.0..260.0).contains(&degrees) {
            let expected = b / 2.0 * degrees.to_radians().sin();
            assert!((reading - expected).abs() < 1e-6, "{degrees}: {reading} vs {expected}");
        }
    }
}

#[test]
fn the_response_of_a_term_without_play_is_the_simulated_change() {
    let nominal = nominal(BALL_BAR);
    let forward = Forward::new(&nominal, &Measured::BallBar(trace(2.0))).unwrap();
    let known = model(vec![
        Effect::BacklashZ(BacklashZ { b: 0.003, axis: Z }),
        Effect::ThermalX(ThermalX { amp: 0.01, tau_min: 20.0, axis: X }),
    ]);
    let base = forward.simulate(&known);
    for effect in [
        Effect::CyclicZ(CyclicZ { amp: 0.002, pitch: 11.94, phase: 0.4, axis: Z }),
        Effect::ReversalSpikeX(ReversalSpikeX { h: 0.003, decay_mm: 2.0, axis: X }),
        Effect::ServoMismatch(ServoMismatch { dt_ms: 3.0 }),
        Effect::BacklashX(BacklashX { b: 0.005, axis: X }),
    ] {
        let fast = forward.response(&known, &base, &effect);
        let mut with = known.clone();
        with.effects.push(effect.clone());
        let full = forward.simulate(&with);
        for ((f, a), b) in fast.iter().zip(&full.readings).zip(&base.readings) {
            assert!((f - (a - b)).abs() < 1e-12, "{}: {f} vs {}", effect.name(), a - b);
        }
    }
}

#[test]
fn a_trace_that_does_not_follow_the_program_is_refused_with_its_line() {
    let path = nominal(BALL_BAR);
    let mut rows = trace(90.0);
    rows.swap(0, 5);
    let message = Forward::new(&path, &Measured::BallBar(rows)).unwrap_err().to_string();
    assert!(message.starts_with("line 7: a cw trace, but the program's next test circle (line 5) is ccw"), "{message}");
    let mut rows = trace(90.0);
    rows.extend(trace(90.0));
    let message = Forward::new(&path, &Measured::BallBar(rows)).unwrap_err().to_string();
    assert!(message.contains("no test circle left"), "{message}");
    let message = Forward::new(&nominal(DOME), &Measured::BallBar(trace(90.0))).unwrap_err().to_string();
    assert!(message.contains("no test circle"), "{message}");
}

fn dome_points() -> Vec<ProfilePoint> {
    let mut points = Vec::new();
    let mut push = |x: f64, z: f64| {
        points.push(ProfilePoint { x_mm: x, z_mm: z, part: None, start_min: None, line: points.len() + 2 })
    };
    for k in 1..20 {
        let a = f64::from(k) * 4.5_f64.to_radians();
        push(20.0 * a.sin(), -20.0 + 20.0 * a.cos());
    }
    for k in 1..10 {
        push(20.0, -20.0 - 2.0 * f64::from(k));
    }
    for k in 1..5 {
        push(20.0 + 2.0 * f64::from(k), -40.0);
    }
    points
}

#[test]
fn cmm_points_meet_the_finishing_contour_and_read_the_normal_deviation() {
    let nominal = nominal(DOME);
    let points = dome_points();
    let forward = Forward::new(&nominal, &Measured::Profile(points.clone())).unwrap();
    assert_eq!(forward.len(), points.len());
    for p in &forward.points {
        assert!(p.measured.abs() < 1e-9, "{}", p.measured);
        assert!([6, 7, 8].contains(&p.line), "{}", p.line);
    }
    // A tool 3 µm out in X: the dome reads 3 µm · sin(angle), the cylinder 3 µm, the
    // shoulder nothing.
    let simulated = forward.simulate(&model(vec![Effect::ToolOffsetX(ToolOffsetX { d: 0.003, axis: X })]));
    for (p, reading) in forward.points.iter().zip(&simulated.readings) {
        let Projection::Normal { normal, .. } = p.projection else { panic!("not a normal") };
        assert!((reading - 0.003 * normal.x).abs() < 1e-12);
    }
    let cylinder = &forward.points[20];
    let Projection::Normal { normal, nominal: reference } = cylinder.projection else { panic!() };
    assert!((normal.x - 1.0).abs() < 1e-12, "{normal:?}");
    // The tool reference point of a tip-3 tool on a diameter: 0.8 mm out and... the
    // imaginary tip is the nose centre less (r, r): on x 20 it is at x 20.
    assert!((reference.x - 20.0).abs() < 1e-9, "{reference:?}");
    // A larger nose moves the dome and nothing else.
    let simulated = forward.simulate(&model(vec![Effect::NoseRadius(NoseRadius { dr: 0.01 })]));
    for (p, reading) in forward.points.iter().zip(&simulated.readings) {
        let Projection::Normal { normal, .. } = p.projection else { panic!() };
        let expected = -0.01 * (1.0 - normal.x - normal.z);
        assert!((reading - expected).abs() < 1e-9, "{:?}: {reading} vs {expected}", p.nominal);
    }
    // A point far from the part.
    let mut far = points;
    far.push(ProfilePoint { x_mm: 5.0, z_mm: -30.0, part: None, start_min: None, line: 99 });
    let message = Forward::new(&nominal, &Measured::Profile(far)).unwrap_err().to_string();
    assert!(message.starts_with("line 99: the point x 5.0000 z -30.0000 is"), "{message}");
}
