//! The effect catalogue as candidates: for each `[[effect]]` kind of the error model, which
//! of its parameters enter linearly (fitted as columns), which one does not (searched), how
//! large a probe gives a clean column, how to build the effect from fitted values, and the
//! physical bounds a fitted value must respect.
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

use crate::error_model::effects::*;
use crate::error_model::{Effect, Sample};

/// A parameter that is searched rather than fitted as a column.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Search {
    None,
    /// Thermal time constant, minutes.
    Tau,
    /// Reversal-spike decay length, mm.
    Decay,
    /// Ball-screw pitch, mm, of the X or the Z screw.
    PitchX,
    PitchZ,
}

/// How one kind of effect is fitted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shape {
    pub kind: &'static str,
    /// The linear parameters' names (for a cyclic error, its sine and cosine parts).
    pub linear: &'static [&'static str],
    pub search: Search,
    /// The readings depend on the parameter through the play (backlash).
    pub secant: bool,
}

/// The shapes of the catalogue, in `effects::NAMES` order.
pub const SHAPES: [Shape; 18] = [
    shape("tool_offset_x", &["dx"], Search::None),
    shape("tool_offset_z", &["dz"], Search::None),
    shape("scale_x", &["ppm"], Search::None),
    shape("scale_z", &["ppm"], Search::None),
    shape("squareness", &["urad"], Search::None),
    Shape { kind: "backlash_x", linear: &["b"], search: Search::None, secant: true },
    Shape { kind: "backlash_z", linear: &["b"], search: Search::None, secant: true },
    shape("cyclic_x", &["sin", "cos"], Search::PitchX),
    shape("cyclic_z", &["sin", "cos"], Search::PitchZ),
    shape("servo_mismatch", &["dt_ms"], Search::None),
    shape("thermal_x", &["amp"], Search::Tau),
    shape("thermal_z", &["amp"], Search::Tau),
    shape("tool_wear", &["um_per_m"], Search::None),
    shape("reversal_spike_x", &["h"], Search::Decay),
    shape("reversal_spike_z", &["h"], Search::Decay),
    shape("straightness_x", &["coeffs[0]"], Search::None),
    shape("straightness_z", &["coeffs[0]"], Search::None),
    shape("nose_radius", &["dr"], Search::None),
];

const fn shape(kind: &'static str, linear: &'static [&'static str], search: Search) -> Shape {
    Shape { kind, linear, search, secant: false }
}

pub fn shape_of(kind: &str) -> Option<&'static Shape> {
    SHAPES.iter().find(|s| s.kind == kind)
}

/// The reach of a measurement: the largest |x|, |z|, speed and cut length at its points,
/// for sizing probes and bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extents {
    pub x: f64,
    pub z: f64,
    pub speed: f64,
    pub cut_m: f64,
}

impl Extents {
    pub fn of(states: &[Sample]) -> Extents {
        let max = |f: &dyn Fn(&Sample) -> f64| states.iter().map(f).fold(0.0, f64::max);
        Extents {
            x: max(&|s| s.at.x.abs()).max(1.0),
            z: max(&|s| s.at.z.abs()).max(1.0),
            speed: max(&|s| s.velocity.x.hypot(s.velocity.z)).max(1.0),
            cut_m: max(&|s| s.cut_length_m).max(1e-3),
        }
    }
}

/// A micrometre, mm: the displacement a probe aims at.
const MICRON: f64 = 1e-3;

impl Shape {
    /// The probe value of each linear parameter: about a micrometre of displacement.
    pub fn probes(&self, e: &Extents) -> Vec<f64> {
        let one = match self.kind {
            "scale_x" => MICRON / e.x * 1e6,
            "scale_z" => MICRON / e.z * 1e6,
            "squareness" => MICRON / e.z * 1e6,
            "servo_mismatch" => MICRON / e.speed * 60_000.0,
            "tool_wear" => MICRON / (e.cut_m * 1e-3),
            "straightness_x" => MICRON / (e.z * e.z),
            "straightness_z" => MICRON / (e.x * e.x),
            "backlash_x" | "backlash_z" => 2.0 * MICRON,
            _ => MICRON,
        };
        vec![one; self.linear.len()]
    }

    /// The effect with linear parameters `linear` and searched parameter `searched`.
    pub fn build(&self, linear: &[f64], searched: f64) -> Effect {
        let a = linear.first().copied().unwrap_or(0.0);
        let b = linear.get(1).copied().unwrap_or(0.0);
        let cyclic = || (a.hypot(b), b.atan2(a));
        match self.kind {
            "tool_offset_x" => Effect::ToolOffsetX(ToolOffsetX { dx: a }),
            "tool_offset_z" => Effect::ToolOffsetZ(ToolOffsetZ { dz: a }),
            "scale_x" => Effect::ScaleX(ScaleX { ppm: a }),
            "scale_z" => Effect::ScaleZ(ScaleZ { ppm: a }),
            "squareness" => Effect::Squareness(Squareness { urad: a }),
            "backlash_x" => Effect::BacklashX(BacklashX { b: a }),
            "backlash_z" => Effect::BacklashZ(BacklashZ { b: a }),
            "cyclic_x" => {
                let (amp, phase) = cyclic();
                Effect::CyclicX(CyclicX { amp, pitch: searched, phase })
            }
            "cyclic_z" => {
                let (amp, phase) = cyclic();
                Effect::CyclicZ(CyclicZ { amp, pitch: searched, phase })
            }
            "servo_mismatch" => Effect::ServoMismatch(ServoMismatch { dt_ms: a }),
            "thermal_x" => Effect::ThermalX(ThermalX { amp: a, tau_min: searched }),
            "thermal_z" => Effect::ThermalZ(ThermalZ { amp: a, tau_min: searched }),
            "tool_wear" => Effect::ToolWear(ToolWear { um_per_m: a }),
            "reversal_spike_x" => Effect::ReversalSpikeX(ReversalSpikeX { h: a, decay_mm: searched }),
            "reversal_spike_z" => Effect::ReversalSpikeZ(ReversalSpikeZ { h: a, decay_mm: searched }),
            "straightness_x" => Effect::StraightnessX(StraightnessX { coeffs: vec![a] }),
            "straightness_z" => Effect::StraightnessZ(StraightnessZ { coeffs: vec![a] }),
            _ => Effect::NoseRadius(NoseRadius { dr: a }),
        }
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

    /// The search range and grid of the searched parameter, from the span of the axis
    /// positions the measurement covers:
    /// `(low, high, points)`; the grid is logarithmic (τ, decay) or uniform in frequency
    /// (pitch). `None` for no search.
    pub fn search_range(&self, span_x: f64, span_z: f64) -> Option<(f64, f64, usize)> {
        match self.search {
            Search::None => None,
            Search::Tau => Some((1.0, 1000.0, 31)),
            Search::Decay => Some((0.02, 20.0, 31)),
            Search::PitchX | Search::PitchZ => {
                let span = if self.search == Search::PitchX { span_x } else { span_z };
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

/// Why a fitted effect is not physical, if it is not: the bounds of the catalogue.
pub fn out_of_bounds(effect: &Effect, e: &Extents) -> Option<String> {
    let check = |value: f64, limit: f64, what: &str| -> Option<String> {
        (!value.is_finite() || value.abs() > limit).then(|| format!("{what} {value:.4e} beyond ±{limit}"))
    };
    match effect {
        Effect::ToolOffsetX(p) => check(p.dx, 0.5, "dx (mm)"),
        Effect::ToolOffsetZ(p) => check(p.dz, 0.5, "dz (mm)"),
        Effect::ScaleX(p) => check(p.ppm, 500.0, "ppm"),
        Effect::ScaleZ(p) => check(p.ppm, 500.0, "ppm"),
        Effect::Squareness(p) => check(p.urad, 1000.0, "µrad"),
        Effect::BacklashX(BacklashX { b }) | Effect::BacklashZ(BacklashZ { b }) => {
            // A negative play is an over-compensating control: possible, but small.
            (!b.is_finite() || *b > 0.2 || *b < -0.02).then(|| format!("b {b:.4} mm outside −0.02…0.2"))
        }
        Effect::CyclicX(CyclicX { amp, pitch, .. }) | Effect::CyclicZ(CyclicZ { amp, pitch, .. }) => {
            check(*amp, 0.05, "amp (mm)").or_else(|| check(*pitch, 100.0, "pitch (mm)"))
        }
        Effect::ServoMismatch(p) => check(p.dt_ms, 50.0, "dt (ms)"),
        Effect::ThermalX(ThermalX { amp, tau_min }) | Effect::ThermalZ(ThermalZ { amp, tau_min }) => {
            check(*amp, 0.2, "amp (mm)").or_else(|| check(*tau_min, 1000.0, "τ (min)"))
        }
        Effect::ToolWear(p) => check(p.um_per_m, 500.0, "µm/m"),
        Effect::ReversalSpikeX(ReversalSpikeX { h, .. }) | Effect::ReversalSpikeZ(ReversalSpikeZ { h, .. }) => {
            check(*h, 0.05, "h (mm)")
        }
        // A bow of at most 0.1 mm over the measured reach.
        Effect::StraightnessX(p) => check(p.coeffs.first().copied().unwrap_or(0.0) * e.z * e.z, 0.1, "bow (mm)"),
        Effect::StraightnessZ(p) => check(p.coeffs.first().copied().unwrap_or(0.0) * e.x * e.x, 0.1, "bow (mm)"),
        Effect::NoseRadius(p) => check(p.dr, 0.4, "dr (mm)"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error_model::effects::NAMES;

    #[test]
    fn every_kind_of_the_catalogue_is_a_candidate_and_builds_itself() {
        let names: Vec<&str> = SHAPES.iter().map(|s| s.kind).collect();
        assert_eq!(names, NAMES);
        for shape in &SHAPES {
            let effect = shape.build(&vec![0.001; shape.linear.len()], 11.94);
            assert_eq!(effect.name(), shape.kind);
        }
        // The sine and cosine parts make amplitude and phase.
        let Effect::CyclicZ(c) = shape_of("cyclic_z").unwrap().build(&[0.003, 0.004], 11.94) else { panic!() };
        assert!((c.amp - 0.005).abs() < 1e-15 && (c.phase - (0.004f64).atan2(0.003)).abs() < 1e-15);
    }
}
