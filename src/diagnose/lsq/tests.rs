use super::*;

#[test]
fn gamma_and_incomplete_beta_match_closed_forms() {
    assert!((ln_gamma(0.5) - std::f64::consts::PI.sqrt().ln()).abs() < 1e-12);
    assert!((ln_gamma(5.0) - 24f64.ln()).abs() < 1e-12);
    assert!((ln_gamma(0.1) - 2.252_712_651_734_206).abs() < 1e-10);
    for x in [0.01, 0.3, 0.5, 0.77, 0.99] {
        assert!((incomplete_beta(x, 1.0, 1.0) - x).abs() < 1e-12);
        assert!((incomplete_beta(x, 3.0, 1.0) - x.powi(3)).abs() < 1e-12);
        assert!((incomplete_beta(x, 1.0, 4.0) - (1.0 - (1.0 - x).powi(4))).abs() < 1e-12);
        // I_x(a, b) = 1 − I_{1−x}(b, a).
        assert!((incomplete_beta(x, 2.5, 7.0) + incomplete_beta(1.0 - x, 7.0, 2.5) - 1.0).abs() < 1e-12);
    }
}

#[test]
fn f_survival_matches_tabulated_critical_values() {
    // 5 % and 0.1 % points of F from the standard tables.
    for (f, d1, d2, p) in [(4.965, 1.0, 10.0, 0.05), (3.087, 2.0, 100.0, 0.05), (10.83, 1.0, 1e6, 0.001)] {
        let got = f_survival(f, d1, d2);
        assert!((got / p - 1.0).abs() < 0.01, "F({d1}, {d2}) at {f}: {got}");
    }
    assert_eq!(f_survival(0.0, 1.0, 10.0), 1.0);
}

#[test]
fn a_column_is_fitted_jointly_with_the_base_and_dependent_columns_are_dropped() {
    let n = 200;
    let t: Vec<f64> = (0..n).map(|i| i as f64 / n as f64).collect();
    let ones = vec![1.0; n];
    let slope = t.clone();
    let square: Vec<f64> = t.iter().map(|x| x * x).collect();
    let y: Vec<f64> = t.iter().map(|x| 2.0 + 3.0 * x - 5.0 * x * x).collect();
    let mut base = Base::new(&[ones.clone(), slope.clone()]);
    assert!(!base.push(&ones.iter().zip(&slope).map(|(a, b)| a - 2.0 * b).collect::<Vec<_>>()));
    assert_eq!(base.rank(), 2);
    let r = base.residual_of(&y);
    let fit = fit_columns(&base, &r, std::slice::from_ref(&square)).unwrap();
    assert!((fit.coefficients[0] + 5.0).abs() < 1e-9 && fit.rss < 1e-18);
    assert!(fit_columns(&base, &r, std::slice::from_ref(&slope)).is_none());
    let cov = covariance(&[ones, slope, square], 1.0).unwrap();
    assert!(cov[(2, 2)] > 0.0);
}
