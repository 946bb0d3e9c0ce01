//! The effect catalogue as candidates. Each `[[effect]]` kind's own file says how it is
//! fitted (`error_model::effects::ParametricEffect`): which of its parameters enter linearly
//! (fitted as columns), which one does not (searched), how large a probe gives a clean
//! column, how to build the effect from fitted values, and the physical bounds a fitted
//! value must respect. This module makes the columns' effects of them and the search grids.
//!
//! A column is the change in the simulated measurement when the effect is added to the
//! model with a small probe value of one linear parameter, divided by the probe (so it is
//! the derivative of the readings by that parameter). Probes are sized to move the tool by
//! about a micrometre, where the readings are linear in the displacement to 1e-8 mm.
//!
//! Parameters that do not enter linearly: the thermal time constant τ and the decay length
//! of a reversal spike (searched on a logarithmic grid, then refined), and the ball-screw
//! pitch of a cyclic error (the machine settings' pitch when given, else searched). A cyclic
//! error's amplitude and phase are fitted as the sine and cosine columns,
//! `amp·sin(u + φ) = amp cos φ · sin u + amp sin φ · cos u`. Backlash enters linearly in the
//! model but not in the readings (the play holds the slide still across a reversal): its
//! column is refined at the fitted value (a secant).

use crate::error_model::Effect;
use crate::error_model::effects::EffectKind;
use crate::error_model::fitting::MAX_LINEAR;
pub use crate::error_model::fitting::{Extents, Search};

/// What the measured points cover: the span of x and of z (mm), and their first and last
/// time (minutes since the machine started).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reach {
    pub x: f64,
    pub z: f64,
    pub time: (f64, f64),
}

impl Reach {
    pub fn of(states: &[crate::error_model::Sample], kept: &[bool]) -> Reach {
        let span = |f: &dyn Fn(&crate::error_model::Sample) -> f64| {
            let (lo, hi) = states
                .iter()
                .zip(kept)
                .filter(|(_, k)| **k)
                .map(|(s, _)| f(s))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
            if hi >= lo { (lo, hi) } else { (0.0, 0.0) }
        };
        let (x, z) = (span(&|s| s.at.x), span(&|s| s.at.z));
        Reach { x: x.1 - x.0, z: z.1 - z.0, time: span(&|s| s.t_min) }
    }

    /// Minutes from the first point to the last.
    pub fn time_span(&self) -> f64 {
        self.time.1 - self.time.0
    }
}

/// One kind of effect as a candidate: how it is fitted (its file's
/// `ParametricEffect::FIT`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shape {
    pub kind: EffectKind,
    /// The linear parameters' names (for a cyclic error, its sine and cosine parts).
    pub linear: &'static [&'static str],
    pub search: Search,
    /// The readings depend on the parameter through the play (backlash).
    pub secant: bool,
}

/// The shapes of the catalogue, in `effects::NAMES` order.
pub const SHAPES: [Shape; EffectKind::ALL.len()] = {
    let mut shapes = [Shape::of(EffectKind::ALL[0]); EffectKind::ALL.len()];
    let mut i = 1;
    while i < shapes.len() {
        shapes[i] = Shape::of(EffectKind::ALL[i]);
        i += 1;
    }
    shapes
};

impl Shape {
    /// The shape of `kind`.
    pub const fn of(kind: EffectKind) -> Shape {
        let fit = kind.fit();
        Shape { kind, linear: fit.linear, search: fit.search, secant: fit.secant }
    }

    /// The effect's name as the model file writes it.
    pub fn name(&self) -> &'static str {
        self.kind.name()
    }

    /// The probe value of each linear parameter: about a micrometre of displacement.
    pub fn probes(&self, e: &Extents) -> Vec<f64> {
        let one = self.kind.probe(e);
        vec![one; self.linear.len()]
    }

    /// The effect with linear parameters `linear` and searched parameter `searched`.
    pub fn build(&self, linear: &[f64], searched: f64) -> Effect {
        let mut values = [0.0; MAX_LINEAR];
        for (value, given) in values.iter_mut().zip(linear) {
            *value = *given;
        }
        self.kind.fitted(values, searched)
    }

    /// The fitted values of an effect of this kind (the inverse of `build`): its linear
    /// parameters as the fit names them (a cyclic error's sine and cosine parts from its
    /// amplitude and phase) and its searched one (NaN for none). `None` when the effect
    /// holds more than the fit does (a straightness with higher terms), which building it
    /// back from these values would lose.
    pub fn values_of(&self, effect: &Effect) -> Option<(Vec<f64>, f64)> {
        if effect.kind() != self.kind {
            return None;
        }
        let serde_json::Value::Object(fields) = serde_json::to_value(effect).ok()? else { return None };
        let number = |name: &str| fields.get(name).and_then(serde_json::Value::as_f64);
        let mut linear = Vec::with_capacity(self.linear.len());
        for name in self.linear {
            let value = match *name {
                // amp·sin(u + φ) = amp cos φ · sin u + amp sin φ · cos u
                "sin" => number("amp")? * number("phase")?.cos(),
                "cos" => number("amp")? * number("phase")?.sin(),
                other => match other.strip_suffix("[0]") {
                    Some(array) => match fields.get(array)?.as_array()?.as_slice() {
                        [only] => only.as_f64()?,
                        _ => return None,
                    },
                    None => number(other)?,
                },
            };
            linear.push(value);
        }
        let searched = match self.search.parameter() {
            Some(name) => number(name)?,
            None => f64::NAN,
        };
        // Built back, it must be the same effect (to rounding).
        let back = serde_json::to_value(self.build(&linear, searched)).ok()?;
        let original = serde_json::to_value(effect).ok()?;
        let same = |a: &serde_json::Value, b: &serde_json::Value| match (a.as_f64(), b.as_f64()) {
            (Some(x), Some(y)) => (x - y).abs() <= 1e-9 * x.abs().max(y.abs()).max(1e-12),
            _ => a == b,
        };
        let agree = match (&back, &original) {
            (serde_json::Value::Object(a), serde_json::Value::Object(b)) => {
                a.len() == b.len()
                    && a.iter().all(|(key, x)| {
                        b.get(key).is_some_and(|y| match (x, y) {
                            (serde_json::Value::Array(p), serde_json::Value::Array(q)) => {
                                p.len() == q.len() && p.iter().zip(q).all(|(p, q)| same(p, q))
                            }
                            // A phase is the same angle a turn apart.
                            _ if key == "phase" => {
                                let d = x.as_f64().unwrap_or(0.0) - y.as_f64().unwrap_or(0.0);
                                (d / std::f64::consts::TAU - (d / std::f64::consts::TAU).round()).abs() < 1e-9
                            }
                            _ => same(x, y),
                        })
                    })
            }
            _ => false,
        };
        agree.then_some((linear, searched))
    }

    /// The effect with only linear parameter `index` at `value` (the others zero), for a
    /// column. A cyclic error's cosine part is the sine at a quarter-turn phase.
    pub fn unit(&self, index: usize, value: f64, searched: f64) -> Effect {
        let mut linear = vec![0.0; self.linear.len()];
        if let Some(slot) = linear.get_mut(index) {
            *slot = value;
        }
        self.build(&linear, searched)
    }

    /// The search range and grid of the searched parameter, from the reach of the
    /// measurement: `(low, high, points)`; the grid is logarithmic (τ, decay) or uniform in
    /// frequency (pitch). `None` for no search.
    pub fn search_range(&self, reach: &Reach) -> Option<(f64, f64, usize)> {
        match self.search {
            Search::None => None,
            // From a twentieth of the time the data span (at least a minute): a shorter τ
            // is a step that the set-up or an offset makes as well. Ten points a decade up
            // to the catalogue's 1000 minutes.
            Search::Tau => {
                let low = (reach.time_span() / 20.0).max(1.0);
                (low < 1000.0).then(|| (low, 1000.0, ((1000f64 / low).log10() * 10.0).ceil().max(1.0) as usize + 1))
            }
            Search::Decay => Some((0.02, 20.0, 31)),
            Search::PitchX | Search::PitchZ => {
                let span = if self.search == Search::PitchX { reach.x } else { reach.z };
                // At least two whole periods on the path, between 3 and 50 mm (ball-screw
                // leads, and their halves for a second harmonic);
                // the grid in frequency is fine enough that the phase drifts by a quarter
                // turn over the path between neighbours (the golden-section refinement
                // finds the peak between them).
                let longest = (span / 2.0).min(50.0);
                let shortest = 3.0;
                if longest <= shortest {
                    return None;
                }
                let points = ((1.0 / shortest - 1.0 / longest) * span / 0.25).ceil().clamp(8.0, 1000.0) as usize;
                Some((shortest, longest, points))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error_model::effects::NAMES;

    #[test]
    fn every_kind_of_the_catalogue_is_a_candidate_and_builds_itself() {
        let names: Vec<&str> = SHAPES.iter().map(Shape::name).collect();
        assert_eq!(names, NAMES);
        for shape in &SHAPES {
            let effect = shape.build(&vec![0.001; shape.linear.len()], 11.94);
            assert_eq!(effect.kind(), shape.kind);
        }
        // The sine and cosine parts make amplitude and phase.
        let Effect::CyclicZ(c) = Shape::of(EffectKind::CyclicZ).build(&[0.003, 0.004], 11.94) else { panic!() };
        assert!((c.amp - 0.005).abs() < 1e-15 && (c.phase - (0.004f64).atan2(0.003)).abs() < 1e-15);
    }
}
