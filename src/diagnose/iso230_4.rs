//! The figures of a circular test (ISO 230-4) from a ball bar trace: radial deviations
//! `d_i` at angles `θ_i`, from +Z toward +X about the programmed centre.
//!
//! * **G**, circular deviation, per direction: the radial width of the thinnest pair of
//!   concentric circles enclosing the path. We give it about the **minimum-zone centre**
//!   (the centre that makes the width least, which is what the standard's definition asks
//!   for), and beside it about the least-squares centre, which is always at least as wide.
//! * **G(b)**: the same for the CW and CCW paths together.
//! * **H**, circular hysteresis: the largest radial difference between the CW and CCW paths
//!   at the same angle (after removing their common least-squares centre).
//! * **F**: the radial deviation from the nominal radius, largest and smallest, about the
//!   least-squares centre (the bar's length is taken as calibrated).
//!
//! A centre offset `(e_x, e_z)` changes a radial deviation by `−e_x sin θ − e_z cos θ` to
//! first order (micrometres on tens of millimetres). The zone width is then a convex,
//! piecewise-linear function of the offset, minimised by nested ternary searches.

use serde::Serialize;

use super::measured::Direction;

/// The figures of one path (one direction, or both for G(b)).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Circular {
    /// Circular deviation about the minimum-zone centre, mm.
    pub g_mm: f64,
    /// The same about the least-squares centre, mm.
    pub g_lsq_mm: f64,
    /// Largest and smallest radial deviation from the nominal radius about the
    /// least-squares centre, mm.
    pub f_max_mm: f64,
    pub f_min_mm: f64,
}

/// The figures of a trace.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Figures {
    pub ccw: Option<Circular>,
    pub cw: Option<Circular>,
    /// G(b): both directions together (when the trace has both).
    pub both: Option<Circular>,
    /// H, mm (when the trace has both directions).
    pub hysteresis_mm: Option<f64>,
}

/// The figures of a trace of `deviations` at `angles_deg` run in `directions`.
pub fn figures(angles_deg: &[f64], deviations: &[f64], directions: &[Direction]) -> Figures {
    let pick = |want: Option<Direction>| -> (Vec<f64>, Vec<f64>) {
        let mut theta = Vec::new();
        let mut d = Vec::new();
        for ((a, v), dir) in angles_deg.iter().zip(deviations).zip(directions) {
            if want.is_none_or(|w| w == *dir) {
                theta.push(a.to_radians());
                d.push(*v);
            }
        }
        (theta, d)
    };
    let (ccw_t, ccw_d) = pick(Some(Direction::Ccw));
    let (cw_t, cw_d) = pick(Some(Direction::Cw));
    let ccw = circular(&ccw_t, &ccw_d);
    let cw = circular(&cw_t, &cw_d);
    let (both, hysteresis_mm) = if ccw.is_some() && cw.is_some() {
        let (all_t, all_d) = pick(None);
        (circular(&all_t, &all_d), hysteresis(&ccw_t, &ccw_d, &cw_t, &cw_d, &all_t, &all_d))
    } else {
        (None, None)
    };
    Figures { ccw, cw, both, hysteresis_mm }
}

fn circular(theta: &[f64], d: &[f64]) -> Option<Circular> {
    if theta.len() < 3 {
        return None;
    }
    let (ex, ez) = lsq_centre(theta, d)?;
    let about =
        |ex: f64, ez: f64| -> Vec<f64> { theta.iter().zip(d).map(|(t, v)| v - ex * t.sin() - ez * t.cos()).collect() };
    let lsq = about(ex, ez);
    let (f_min, f_max) = range(&lsq);
    Some(Circular { g_mm: min_zone(theta, d), g_lsq_mm: f_max - f_min, f_max_mm: f_max, f_min_mm: f_min })
}

fn range(values: &[f64]) -> (f64, f64) {
    values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(*v), hi.max(*v)))
}

/// The least-squares centre offset: `d ≈ r + e_x sin θ + e_z cos θ`.
fn lsq_centre(theta: &[f64], d: &[f64]) -> Option<(f64, f64)> {
    let columns =
        vec![vec![1.0; theta.len()], theta.iter().map(|t| t.sin()).collect(), theta.iter().map(|t| t.cos()).collect()];
    let (coefficients, _, _) = super::lsq::solve(&columns, d)?;
    Some((coefficients[1], coefficients[2]))
}

/// The least zone width over centre offsets.
fn min_zone(theta: &[f64], d: &[f64]) -> f64 {
    let (s, c): (Vec<f64>, Vec<f64>) = theta.iter().map(|t| (t.sin(), t.cos())).unzip();
    let width = |ex: f64, ez: f64| -> f64 {
        let (lo, hi) = d
            .iter()
            .zip(s.iter().zip(&c))
            .map(|(v, (s, c))| v - ex * s - ez * c)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
        hi - lo
    };
    let (lo, hi) = range(d);
    // No centre further off than the trace's own width can narrow it.
    let reach = (hi - lo).max(1e-9) * 2.0;
    let best_ez = |ex: f64| ternary(|ez| width(ex, ez), -reach, reach);
    let ex = ternary(|ex| width(ex, best_ez(ex)), -reach, reach);
    width(ex, best_ez(ex))
}

/// The minimiser of a convex function on `[a, b]`.
fn ternary(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    for _ in 0..60 {
        let m1 = a + (b - a) / 3.0;
        let m2 = b - (b - a) / 3.0;
        if f(m1) <= f(m2) {
            b = m2;
        } else {
            a = m1;
        }
    }
    (a + b) / 2.0
}

/// The largest CCW − CW difference at the CCW angles, the CW trace interpolated in angle,
/// both about their common least-squares centre.
fn hysteresis(ccw_t: &[f64], ccw_d: &[f64], cw_t: &[f64], cw_d: &[f64], all_t: &[f64], all_d: &[f64]) -> Option<f64> {
    let (ex, ez) = lsq_centre(all_t, all_d)?;
    let centred = |t: f64, v: f64| v - ex * t.sin() - ez * t.cos();
    let tau = std::f64::consts::TAU;
    let mut cw: Vec<(f64, f64)> = cw_t.iter().zip(cw_d).map(|(t, v)| (t.rem_euclid(tau), centred(*t, *v))).collect();
    cw.sort_by(|a, b| a.0.total_cmp(&b.0));
    cw.dedup_by(|b, a| (b.0 - a.0).abs() < 1e-12);
    if cw.len() < 2 {
        return None;
    }
    let at = |t: f64| -> f64 {
        let t = t.rem_euclid(tau);
        let k = cw.partition_point(|p| p.0 <= t);
        let (a, b) = if k == 0 || k == cw.len() {
            let (last, first) = (cw[cw.len() - 1], cw[0]);
            (last, (first.0 + tau, first.1))
        } else {
            (cw[k - 1], cw[k])
        };
        let t = if t < a.0 { t + tau } else { t };
        let w = if b.0 > a.0 { (t - a.0) / (b.0 - a.0) } else { 0.0 };
        a.1 + (b.1 - a.1) * w
    };
    Some(ccw_t.iter().zip(ccw_d).map(|(t, v)| (centred(*t, *v) - at(*t)).abs()).fold(0.0, f64::max))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_offset_circle_has_no_circular_deviation_and_an_oval_has_its_width() {
        let n = 720;
        let angles: Vec<f64> = (0..n).map(|k| 360.0 * k as f64 / n as f64).collect();
        // A centre 5 µm off: F shows it removed, G is zero.
        let offset: Vec<f64> = angles.iter().map(|a| 0.005 * a.to_radians().sin() + 0.001).collect();
        let directions = vec![Direction::Ccw; n];
        let f = figures(&angles, &offset, &directions);
        let ccw = f.ccw.unwrap();
        assert!(ccw.g_mm < 1e-9 && ccw.g_lsq_mm < 1e-9, "{ccw:?}");
        assert!((ccw.f_max_mm - 0.001).abs() < 1e-9 && (ccw.f_min_mm - 0.001).abs() < 1e-9);
        assert!(f.cw.is_none() && f.both.is_none() && f.hysteresis_mm.is_none());
        // An oval of ±3 µm, and the CW run shifted 2 µm: G 6 µm each, G(b) 8 µm, H 2 µm.
        let mut all_angles = angles.clone();
        all_angles.extend(angles.iter().rev());
        let mut d: Vec<f64> = angles.iter().map(|a| 0.003 * (2.0 * a.to_radians()).sin()).collect();
        d.extend(angles.iter().rev().map(|a| 0.003 * (2.0 * a.to_radians()).sin() + 0.002));
        let mut directions = vec![Direction::Ccw; n];
        directions.extend(vec![Direction::Cw; n]);
        let f = figures(&all_angles, &d, &directions);
        assert!((f.ccw.unwrap().g_mm - 0.006).abs() < 1e-8, "{:?}", f.ccw);
        assert!((f.cw.unwrap().g_mm - 0.006).abs() < 1e-8);
        assert!((f.both.unwrap().g_mm - 0.008).abs() < 1e-8, "{:?}", f.both);
        assert!((f.hysteresis_mm.unwrap() - 0.002).abs() < 1e-8, "{:?}", f.hysteresis_mm);
    }

    #[test]
    fn the_minimum_zone_is_no_wider_than_the_least_squares_zone() {
        // A one-sided bump: least squares shifts the centre toward it, minimum zone less.
        let angles: Vec<f64> = (0..360).map(f64::from).collect();
        let d: Vec<f64> = angles.iter().map(|a| if (80.0..100.0).contains(a) { 0.004 } else { 0.0 }).collect();
        let c = circular(&angles.iter().map(|a| a.to_radians()).collect::<Vec<_>>(), &d).unwrap();
        assert!(c.g_mm <= c.g_lsq_mm + 1e-12 && c.g_mm < 0.004, "{c:?}");
    }
}
