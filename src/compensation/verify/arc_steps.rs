//! How finely the measure samples an arc: no finer than the bound below needs for the
//! distance it measures to follow the straight interpolation between samples.
//!
//! **The bound.** Take a step of `h` radians along an arc of radius `R` (the measured
//! program's own move, about its centre `c`), and the circle of the original's arc it is
//! measured against (centre `c₀`, radius `R₀`). The predicted point is `P(θ) = c + R·u(θ) +
//! D(θ)`, `u` the unit radial, `D` the model's displacement, and its distance from the
//! circle is `f(θ) = |P(θ) − c₀| − R₀`. The model is sampled so that `D` departs from its
//! chord `L` between the step's ends by at most the allowance `A` (`error_model/spacing.rs`),
//! and a distance is 1-Lipschitz, so `f` is within `A` of `f̃(θ) = |R·u(θ) + V(θ)| − R₀`
//! with `V = L + c − c₀`, linear in θ, and equal to it at the ends. Write `ρ = |Y|`,
//! `Y = R·u + V`: `Y' = R·t + v` (`t` the unit tangent, `v = V'` constant), `Y'' = −R·u`, and
//!
//! ```txt
//! ρ'' = (Y''·Y + |Y'|²)/ρ − (Y'·Y)²/ρ³
//!     = (−R·u·V + 2R·t·v + |v|²)/ρ − (R·t·V + R·u·v + v·V)²/ρ³,
//! ```
//!
//! so with `|V| ≤ m < R` (then `ρ ≥ R − m`) and `|v| ≤ w`,
//!
//! ```txt
//! |f̃''| ≤ K = (R·m + 2R·w + w²)/(R − m) + (R·m + R·w + w·m)²/(R − m)³.
//! ```
//!
//! The straight interpolation of `f̃` misses it by at most `h²·K/8` (and meets it at the
//! ends), so that of `f` misses `f` by at most `A + h²·K/8`. Cut into `k` equal pieces, a
//! piece's chord of `D` has a slope within `2kA/h` of the whole step's, so `w` becomes
//! `(|ΔD| + 2kA)/h`, with `ΔD` the change of `D` over the step. The step is cut into the
//! fewest pieces that bring `h²·K/(8k²)` within `A`: the distance then follows its
//! interpolation within `2A` on an arc, as within `A` on a line (where `u` does not turn).
//!
//! `m` bounds `|V|` over the step: the larger of `|D + c − c₀|` at the ends, plus `A`. The
//! play a reversing slide takes up is no part of `L` (it changes only inside a take-up,
//! whose knee the measure samples): it is left out of `ΔD`, and where it changes inside the
//! step `m` grows by its change, which bounds how far it strays from its interpolation. Where the measured program is the original
//! the circle is its own (`c = c₀`); for the compensated one, it is the arc of the original
//! its previous point was matched to. Round a corner, or where that is no arc, the distance
//! is not to one circle: the step keeps at most `FALLBACK_RADIANS`.

/// The largest step where the bound does not apply (the measured point's circle is not
/// known, or `m` is not below `R`), radians: a 64th of a turn, where a displacement of
/// 40 µm turns away from the interpolation by about the allowance of a 1 µm grid.
pub const FALLBACK_RADIANS: f64 = std::f64::consts::PI / 32.0;

/// The finest piece of an arc the bound asks for, radians: finer helps nothing a
/// measurement can show, and a bound near zero would otherwise ask for unboundedly many.
const FINEST_RADIANS: f64 = 1e-3;

/// What the bound needs to know of one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// The angle of the step, radians, and the radius of the measured arc, mm.
    pub radians: f64,
    pub radius: f64,
    /// `m`: a bound of the displacement from the reference circle's centre offset, mm.
    pub largest: f64,
    /// `|ΔD|`: the change of the displacement (without the play) over the step, mm.
    pub change: f64,
    /// `A`: the model's allowance, which the interpolation may use again, mm.
    pub allowance: f64,
}

/// `K` of the module documentation, for `m = largest`, `w = slope`, `R = radius`; `None`
/// where `m` is not below `R`.
pub fn curvature(radius: f64, largest: f64, slope: f64) -> Option<f64> {
    let (r, m, w) = (radius, largest, slope);
    if !(m >= 0.0 && w >= 0.0 && r > m) {
        return None;
    }
    let gap = r - m;
    let k = (r * m + 2.0 * r * w + w * w) / gap + (r * m + r * w + w * m).powi(2) / gap.powi(3);
    k.is_finite().then_some(k)
}

/// Into how many equal pieces `step` is cut (see the module documentation); `None` where
/// the bound does not apply.
pub fn pieces(step: &Step) -> Option<usize> {
    let Step { radians: h, radius, largest, change, allowance } = *step;
    if !(h > 0.0 && allowance > 0.0 && h.is_finite()) {
        return None;
    }
    let most = (h / FINEST_RADIANS).ceil().max(1.0) as usize;
    for k in 1..=most {
        let pieces = k as f64;
        let slope = (change + 2.0 * pieces * allowance) / h;
        let bend = curvature(radius, largest, slope)?;
        if h * h * bend / (8.0 * pieces * pieces) <= allowance {
            return Some(k);
        }
    }
    Some(most)
}

/// Pieces for a step where the bound does not apply: at most `FALLBACK_RADIANS` each.
pub fn fallback_pieces(radians: f64) -> usize {
    if radians.is_finite() && radians > 0.0 { (radians / FALLBACK_RADIANS).ceil().max(1.0) as usize } else { 1 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::on_circle;
    use crate::toolpath::Xz;
    use proptest::prelude::*;

    proptest! {
        /// The distance from a circle of a point that runs round another circle with a
        /// displacement that is a chord plus a wobble within the allowance, sampled at the
        /// pieces the bound asks for, follows the straight interpolation between samples
        /// within twice the allowance (checked at many points of each piece).
        #[test]
        fn a_step_cut_as_the_bound_asks_is_followed_within_twice_the_allowance(
            radius in 0.2f64..80.0, a0 in -4.0f64..4.0, h in 0.01f64..0.4,
            d0x in -0.02f64..0.02, d0z in -0.02f64..0.02, d1x in -0.02f64..0.02, d1z in -0.02f64..0.02,
            cx in -0.01f64..0.01, cz in -0.01f64..0.01, dr in -0.01f64..0.01, wobble in 0.0f64..1.0,
            allowance in 1e-6f64..1e-4,
        ) {
            let centre = Xz::new(3.0, -7.0);
            let original = Xz::new(centre.x + cx, centre.z + cz);
            let r0 = radius + dr;
            let d = |s: f64| {
                // The chord of D, and a bend of it within the allowance, zero at the ends.
                let bend = wobble * allowance * (std::f64::consts::PI * s).sin() / std::f64::consts::SQRT_2;
                Xz::new(d0x + (d1x - d0x) * s + bend, d0z + (d1z - d0z) * s - bend)
            };
            let f = |s: f64| {
                let p = on_circle(centre, radius, a0 + h * s);
                let p = Xz::new(p.x + d(s).x, p.z + d(s).z);
                p.distance(original) - r0
            };
            let largest = Xz::new(d0x, d0z).distance(Xz::default()).max(Xz::new(d1x, d1z).distance(Xz::default()))
                + allowance
                + Xz::new(cx, cz).distance(Xz::default());
            let change = Xz::new(d1x - d0x, d1z - d0z).distance(Xz::default());
            let step = Step { radians: h, radius, largest, change, allowance };
            let Some(k) = pieces(&step) else { return Ok(()) };
            for piece in 0..k {
                let (s0, s1) = (piece as f64 / k as f64, (piece + 1) as f64 / k as f64);
                for i in 1..16 {
                    let s = s0 + (s1 - s0) * i as f64 / 16.0;
                    let between = f(s0) + (f(s1) - f(s0)) * (s - s0) / (s1 - s0);
                    let miss = (f(s) - between).abs();
                    prop_assert!(miss <= 2.0 * allowance * (1.0 + 1e-6) + 1e-12, "{k} pieces: missed by {miss}");
                }
            }
        }
    }

    #[test]
    fn a_large_displacement_or_a_long_step_asks_for_more_pieces() {
        let step = Step { radians: 0.39, radius: 5.0, largest: 0.012, change: 0.0, allowance: 5e-5 };
        let few = pieces(&step).expect("the bound applies");
        let more = pieces(&Step { largest: 0.04, ..step }).expect("the bound applies");
        assert!(few >= 2 && more > few, "{few} {more}");
        assert_eq!(pieces(&Step { radians: 0.05, largest: 0.001, ..step }), Some(1));
        assert_eq!(pieces(&Step { largest: 6.0, ..step }), None);
        assert_eq!(fallback_pieces(0.39), 4);
    }
}
