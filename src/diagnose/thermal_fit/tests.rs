use super::*;
use crate::diagnose::noise::Noise;

/// A curve's gain, time constant (minutes) and offset.
type Curve = (f64, f64, f64);

/// The thesis' fits (eq. 5.3–5.6), by element: its warm-up and its cool-down curve, in the
/// table's order.
fn thesis_fits() -> Vec<(&'static str, Curve, Curve)> {
    let table = include_str!("../../../tests/cases/thesis/thermal_fits.csv");
    let mut curves: Vec<(&str, &str, Curve)> = Vec::new();
    for line in table.lines().filter(|l| !l.starts_with('#') && !l.starts_with("element,")) {
        let fields: Vec<&str> = line.split(',').collect();
        let number = |i: usize| fields[i].parse::<f64>().unwrap();
        curves.push((fields[0], fields[1], (number(2), number(3), number(4))));
    }
    let fits: Vec<_> = curves
        .chunks(2)
        .map(|pair| {
            let [(element, "warm", warm), (other, "cool", cool)] = pair else { panic!("warm then cool: {pair:?}") };
            assert_eq!(element, other);
            (*element, *warm, *cool)
        })
        .collect();
    assert_eq!(fits.len(), 2, "the spindle and the Z slide");
    fits
}

/// Four hours of warm-up then four of cool-down, one sample a second as the thesis
/// recorded, with noise.
fn synthesise(warm: Curve, cool: Curve, sigma: f64, seed: u64) -> (Vec<f64>, Vec<f64>) {
    let mut noise = Noise::new(seed);
    let (mut t, mut y) = (Vec::new(), Vec::new());
    for second in 0..=240 * 60 {
        let m = f64::from(second) / 60.0;
        t.push(m);
        y.push(warm.0 * (1.0 - (-m / warm.1).exp()) + warm.2 + noise.normal(sigma));
    }
    for second in 1..=240 * 60 {
        let m = f64::from(second) / 60.0;
        t.push(240.0 + m);
        y.push(cool.0 * (-m / cool.1).exp() + cool.2 + noise.normal(sigma));
    }
    (t, y)
}

#[test]
fn recovers_the_thesis_time_constants_within_five_percent_from_noisy_logs() {
    for (name, warm, cool) in thesis_fits() {
        for seed in [1, 7, 42] {
            let (t, y) = synthesise(warm, cool, 0.15, seed);
            let fit = fit_log(&t, &y).unwrap();
            assert_eq!(fit.split, Split::Fitted, "{name}: {:?}", fit.no_cool_down);
            // The thesis' two curves of the Z slide do not meet at the switch (70.19 and
            // 70.29 °F), so its log is back at the warm-up's level two minutes after it.
            assert!((fit.split_min - 240.0).abs() <= 4.0, "{name}: split at {}", fit.split_min);
            assert!((fit.warm.tau_min / warm.1 - 1.0).abs() < 0.05, "{name} warm τ {} vs {}", fit.warm.tau_min, warm.1);
            let c = fit.cool.unwrap();
            assert!((c.tau_min / cool.1 - 1.0).abs() < 0.05, "{name} cool τ {} vs {}", c.tau_min, cool.1);
            assert!((c.tau_min - cool.1).abs() < 3.0 * c.tau_sigma, "{name} cool τ {} ± {}", c.tau_min, c.tau_sigma);
            // The stated uncertainty covers the error (three standard errors).
            assert!((fit.warm.tau_min - warm.1).abs() < 4.0 * fit.warm.tau_sigma, "{name}: σ {}", fit.warm.tau_sigma);
            assert!((fit.warm.rms - 0.15).abs() < 0.05);
        }
    }
}

#[test]
fn an_exact_curve_is_fitted_exactly() {
    let (_, (gain, tau, offset), _) = thesis_fits()[0];
    let t: Vec<f64> = (0..200).map(f64::from).collect();
    let y: Vec<f64> = t.iter().map(|&m| gain * (1.0 - (-m / tau).exp()) + offset).collect();
    let fit = fit_phase(Phase::Warm, &t, &y).unwrap();
    assert!((fit.tau_min - tau).abs() < 1e-4 && (fit.gain - gain).abs() < 1e-5 && (fit.offset - offset).abs() < 1e-5);
}

#[test]
fn bad_logs_are_refused() {
    assert!(matches!(fit_log(&[0.0, 1.0], &[1.0, 2.0]), Err(ThermalFitError::TooFewSamples(_))));
    let t = [0.0, 1.0, 2.0, 2.0, 4.0, 5.0, 6.0, 7.0];
    assert!(matches!(fit_log(&t, &[0.0; 8]), Err(ThermalFitError::TimesNotIncreasing(4))));
    let t: Vec<f64> = (0..20).map(f64::from).collect();
    assert!(fit_phase(Phase::Warm, &t, &[5.0; 20]).is_err());
}

#[test]
fn a_known_switch_off_time_splits_the_log_there() {
    let (_, warm, cool) = thesis_fits()[0];
    let (t, y) = synthesise(warm, cool, 0.15, 3);
    let fit = fit_log_split(&t, &y, Some(240.0)).unwrap();
    assert!((fit.split_min - 240.0).abs() < 0.02, "{}", fit.split_min);
    let c = fit.cool.unwrap();
    assert!((c.tau_min / cool.1 - 1.0).abs() < 0.03, "cool τ {}", c.tau_min);
}

/// A log as `fit-thermal` reads it: `t_min,value` rows after a header.
fn read_log(text: &str) -> (Vec<f64>, Vec<f64>) {
    text.lines()
        .skip(1)
        .map(|line| {
            let (t, y) = line.split_once(',').unwrap();
            (t.parse::<f64>().unwrap(), y.parse::<f64>().unwrap())
        })
        .unzip()
}

/// The bundled log (`examples/data/z-growth-log.csv`, `cargo run --example thermal_log`):
/// the split found by fitting lies within two minutes of the switch-off at 240, and each
/// fitted τ within three of its standard errors of the curve the log was made from.
#[test]
fn the_bundled_log_is_split_where_the_heat_stopped() {
    let (t, y) = read_log(include_str!("../../../examples/data/z-growth-log.csv"));
    let fit = fit_log(&t, &y).unwrap();
    assert_eq!(fit.split, Split::Fitted);
    assert!((fit.split_min - 240.0).abs() <= 2.0, "split at {}", fit.split_min);
    assert!((fit.warm.tau_min - 54.59).abs() < 3.0 * fit.warm.tau_sigma, "warm τ {:?}", fit.warm);
    let cool = fit.cool.unwrap();
    assert!((cool.tau_min - 81.97).abs() < 3.0 * cool.tau_sigma, "cool τ {} ± {}", cool.tau_min, cool.tau_sigma);
}

/// The thesis' Z slide curves (eq. 5.5–5.6; `cargo run --example thermal_log -- z-slide`),
/// each phase with its own gain and offset as the thesis fits them.
#[test]
fn the_thesis_z_slide_log_is_split_where_the_heat_stopped() {
    let (t, y) = read_log(include_str!("../../../tests/cases/diagnose/thermal/z-slide.csv"));
    let fit = fit_log(&t, &y).unwrap();
    assert!((fit.split_min - 240.0).abs() <= 2.0, "split at {}", fit.split_min);
    assert!((fit.warm.tau_min - 92.59).abs() < 3.0 * fit.warm.tau_sigma, "warm τ {:?}", fit.warm);
    let cool = fit.cool.unwrap();
    assert!((cool.tau_min - 95.24).abs() < 3.0 * cool.tau_sigma, "cool τ {} ± {}", cool.tau_min, cool.tau_sigma);
}

/// Six hours of warm-up and no cool-down (`cargo run --example thermal_log --
/// warm-up-only`): no cool-down is made up from the plateau's noise, and the warm-up curve
/// is fitted to the whole log.
#[test]
fn a_log_without_a_cool_down_has_none() {
    let (t, y) = read_log(include_str!("../../../tests/cases/diagnose/thermal/warm-up-only.csv"));
    let fit = fit_log(&t, &y).unwrap();
    assert_eq!((fit.split, fit.cool), (Split::None, None), "{:?}", fit.cool);
    assert!(fit.no_cool_down.is_some());
    assert_eq!(fit.warm.samples, t.len());
    assert!((fit.warm.tau_min - 54.59).abs() < 3.0 * fit.warm.tau_sigma, "warm τ {:?}", fit.warm);
}
