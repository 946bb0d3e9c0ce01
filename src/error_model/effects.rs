//! The parametric effects of the model's `[[effect]]` tables, one file each. Every effect
//! is a displacement of the tool (actual − commanded, mm, X as a radius) as a function of a
//! `Sample`; `kind` in the table names it and the other keys are its parameters, exactly:
//!
//! ```toml
//! [[effect]]
//! kind = "backlash_x"
//! b = 0.004
//! ```

pub mod backlash_x;
pub mod backlash_z;
pub mod cyclic_x;
pub mod cyclic_z;
pub mod nose_radius;
pub mod reversal_spike_x;
pub mod reversal_spike_z;
pub mod scale_x;
pub mod scale_z;
pub mod servo_mismatch;
pub mod squareness;
pub mod straightness_x;
pub mod straightness_z;
pub mod thermal_x;
pub mod thermal_z;
pub mod tool_offset_x;
pub mod tool_offset_z;
pub mod tool_wear;

pub use backlash_x::BacklashX;
pub use backlash_z::BacklashZ;
pub use cyclic_x::CyclicX;
pub use cyclic_z::CyclicZ;
pub use nose_radius::NoseRadius;
pub use reversal_spike_x::ReversalSpikeX;
pub use reversal_spike_z::ReversalSpikeZ;
pub use scale_x::ScaleX;
pub use scale_z::ScaleZ;
pub use servo_mismatch::ServoMismatch;
pub use squareness::Squareness;
pub use straightness_x::StraightnessX;
pub use straightness_z::StraightnessZ;
pub use thermal_x::ThermalX;
pub use thermal_z::ThermalZ;
pub use tool_offset_x::ToolOffsetX;
pub use tool_offset_z::ToolOffsetZ;
pub use tool_wear::ToolWear;

use serde::{Deserialize, Deserializer, Serialize};

use crate::bounds::Invalid;
use crate::error_model::Sample;
use crate::error_model::spacing::{ArcTerms, Spacing};
use crate::toolpath::Xz;

/// One parametric effect. It is written with its name as `kind` beside its parameters
/// (`Serialize`); a model file's `[[effect]]` is read by that name, `Effect::deserialize_kind`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Effect {
    ToolOffsetX(ToolOffsetX),
    ToolOffsetZ(ToolOffsetZ),
    ScaleX(ScaleX),
    ScaleZ(ScaleZ),
    Squareness(Squareness),
    BacklashX(BacklashX),
    BacklashZ(BacklashZ),
    CyclicX(CyclicX),
    CyclicZ(CyclicZ),
    ServoMismatch(ServoMismatch),
    ThermalX(ThermalX),
    ThermalZ(ThermalZ),
    ToolWear(ToolWear),
    ReversalSpikeX(ReversalSpikeX),
    ReversalSpikeZ(ReversalSpikeZ),
    StraightnessX(StraightnessX),
    StraightnessZ(StraightnessZ),
    NoseRadius(NoseRadius),
}

/// Every effect name, in catalogue order.
pub const NAMES: [&str; 18] = [
    "tool_offset_x",
    "tool_offset_z",
    "scale_x",
    "scale_z",
    "squareness",
    "backlash_x",
    "backlash_z",
    "cyclic_x",
    "cyclic_z",
    "servo_mismatch",
    "thermal_x",
    "thermal_z",
    "tool_wear",
    "reversal_spike_x",
    "reversal_spike_z",
    "straightness_x",
    "straightness_z",
    "nose_radius",
];

impl Effect {
    /// The effect named `kind` (a name of `NAMES`), its parameters read from `parameters`
    /// (the table without its `kind`); `None` for a name no effect has. The model file reads
    /// each `[[effect]]` table through this rather than through the enum's `kind` tag, which
    /// would buffer the table and lose the place of an error in it.
    pub fn deserialize_kind<'de, D: Deserializer<'de>>(kind: &str, parameters: D) -> Option<Result<Effect, D::Error>> {
        fn read<'de, T: Deserialize<'de>, D: Deserializer<'de>>(
            parameters: D,
            effect: fn(T) -> Effect,
        ) -> Option<Result<Effect, D::Error>> {
            Some(T::deserialize(parameters).map(effect))
        }
        match kind {
            "tool_offset_x" => read(parameters, Effect::ToolOffsetX),
            "tool_offset_z" => read(parameters, Effect::ToolOffsetZ),
            "scale_x" => read(parameters, Effect::ScaleX),
            "scale_z" => read(parameters, Effect::ScaleZ),
            "squareness" => read(parameters, Effect::Squareness),
            "backlash_x" => read(parameters, Effect::BacklashX),
            "backlash_z" => read(parameters, Effect::BacklashZ),
            "cyclic_x" => read(parameters, Effect::CyclicX),
            "cyclic_z" => read(parameters, Effect::CyclicZ),
            "servo_mismatch" => read(parameters, Effect::ServoMismatch),
            "thermal_x" => read(parameters, Effect::ThermalX),
            "thermal_z" => read(parameters, Effect::ThermalZ),
            "tool_wear" => read(parameters, Effect::ToolWear),
            "reversal_spike_x" => read(parameters, Effect::ReversalSpikeX),
            "reversal_spike_z" => read(parameters, Effect::ReversalSpikeZ),
            "straightness_x" => read(parameters, Effect::StraightnessX),
            "straightness_z" => read(parameters, Effect::StraightnessZ),
            "nose_radius" => read(parameters, Effect::NoseRadius),
            _ => None,
        }
    }

    /// The parameters against the plausible ranges each effect's file gives; the path of a
    /// refused value is relative to the effect's table.
    pub fn check(&self) -> Result<(), Invalid> {
        match self {
            Effect::ToolOffsetX(e) => e.check(),
            Effect::ToolOffsetZ(e) => e.check(),
            Effect::ScaleX(e) => e.check(),
            Effect::ScaleZ(e) => e.check(),
            Effect::Squareness(e) => e.check(),
            Effect::BacklashX(e) => e.check(),
            Effect::BacklashZ(e) => e.check(),
            Effect::CyclicX(e) => e.check(),
            Effect::CyclicZ(e) => e.check(),
            Effect::ServoMismatch(e) => e.check(),
            Effect::ThermalX(e) => e.check(),
            Effect::ThermalZ(e) => e.check(),
            Effect::ToolWear(e) => e.check(),
            Effect::ReversalSpikeX(e) => e.check(),
            Effect::ReversalSpikeZ(e) => e.check(),
            Effect::StraightnessX(e) => e.check(),
            Effect::StraightnessZ(e) => e.check(),
            Effect::NoseRadius(e) => e.check(),
        }
    }

    /// The play this effect puts in each axis' drive, mm.
    pub fn play(&self) -> Xz {
        match self {
            Effect::BacklashX(e) if e.b > 0.0 => Xz::new(e.b, 0.0),
            Effect::BacklashZ(e) if e.b > 0.0 => Xz::new(0.0, e.b),
            _ => Xz::new(0.0, 0.0),
        }
    }

    // Inlined into the model's sum (`ErrorModel::displacement_timed`), which evaluates every
    // effect several times per sample: a call clobbers every floating-point register the
    // sum and its caller hold, which cost more than most effects' arithmetic.
    #[inline(always)]
    pub fn displacement(&self, s: &Sample) -> Xz {
        match self {
            Effect::ToolOffsetX(e) => e.displacement(s),
            Effect::ToolOffsetZ(e) => e.displacement(s),
            Effect::ScaleX(e) => e.displacement(s),
            Effect::ScaleZ(e) => e.displacement(s),
            Effect::Squareness(e) => e.displacement(s),
            Effect::BacklashX(e) => e.displacement(s),
            Effect::BacklashZ(e) => e.displacement(s),
            Effect::CyclicX(e) => e.displacement(s),
            Effect::CyclicZ(e) => e.displacement(s),
            Effect::ServoMismatch(e) => e.displacement(s),
            Effect::ThermalX(e) => e.displacement(s),
            Effect::ThermalZ(e) => e.displacement(s),
            Effect::ToolWear(e) => e.displacement(s),
            Effect::ReversalSpikeX(e) => e.displacement(s),
            Effect::ReversalSpikeZ(e) => e.displacement(s),
            Effect::StraightnessX(e) => e.displacement(s),
            Effect::StraightnessZ(e) => e.displacement(s),
            Effect::NoseRadius(e) => e.displacement(s),
        }
    }

    /// The displacement of a term that is a function of time alone (warm-up) at `t_min`,
    /// as `displacement` gives it at a sample of that time; `None` for any other term.
    pub fn at_time(&self, t_min: f64) -> Option<Xz> {
        match self {
            Effect::ThermalX(e) => Some(e.at_time(t_min)),
            Effect::ThermalZ(e) => Some(e.at_time(t_min)),
            _ => None,
        }
    }

    /// Whether the term is a function of time alone (`at_time`).
    pub fn is_of_time(&self) -> bool {
        matches!(self, Effect::ThermalX(_) | Effect::ThermalZ(_))
    }

    /// How closely a move must be sampled for the straight interpolation between samples
    /// to follow this effect within `allowance` mm (`spacing.rs`); `reach` is the farthest
    /// the program goes from the origin in each axis (mm, X as a radius).
    pub fn spacing(&self, allowance: f64, reach: Xz) -> Spacing {
        match self {
            Effect::CyclicX(e) => e.spacing(allowance),
            Effect::CyclicZ(e) => e.spacing(allowance),
            Effect::ThermalX(e) => e.spacing(allowance),
            Effect::ThermalZ(e) => e.spacing(allowance),
            Effect::ReversalSpikeX(e) => e.spacing(allowance),
            Effect::ReversalSpikeZ(e) => e.spacing(allowance),
            Effect::StraightnessX(e) => e.spacing(allowance, reach.z),
            Effect::StraightnessZ(e) => e.spacing(allowance, reach.x),
            // Constant or affine in the position along a straight move: offsets, scale and
            // squareness; backlash, which changes only where an axis reverses (at a line's
            // ends, and at the samples `sampling.rs` puts at an arc's extremes); servo lag
            // and the nose radius, constant at a line's constant velocity and normal; wear,
            // linear in the length cut.
            Effect::ToolOffsetX(_)
            | Effect::ToolOffsetZ(_)
            | Effect::ScaleX(_)
            | Effect::ScaleZ(_)
            | Effect::Squareness(_)
            | Effect::BacklashX(_)
            | Effect::BacklashZ(_)
            | Effect::ServoMismatch(_)
            | Effect::ToolWear(_)
            | Effect::NoseRadius(_) => Spacing::ANY,
        }
    }

    /// What makes this effect's correction turn around an arc (`spacing::ArcTerms`); `reach`
    /// as for `spacing`.
    pub fn arc_terms(&self, reach: Xz) -> ArcTerms {
        let gradient = |gradient: f64| ArcTerms { gradient: gradient.abs(), ..ArcTerms::default() };
        match self {
            Effect::ScaleX(e) => gradient(e.ppm * 1e-6),
            Effect::ScaleZ(e) => gradient(e.ppm * 1e-6),
            Effect::Squareness(e) => gradient(e.urad * 1e-6),
            Effect::CyclicX(e) => gradient(e.amp * std::f64::consts::TAU / e.pitch),
            Effect::CyclicZ(e) => gradient(e.amp * std::f64::consts::TAU / e.pitch),
            Effect::StraightnessX(e) => gradient(bow_slope(&e.coeffs, reach.z)),
            Effect::StraightnessZ(e) => gradient(bow_slope(&e.coeffs, reach.x)),
            Effect::ServoMismatch(e) => ArcTerms { lag_min: e.dt_ms.abs() / 60_000.0, ..ArcTerms::default() },
            Effect::NoseRadius(e) => ArcTerms { nose_mm: e.dr.abs(), ..ArcTerms::default() },
            // Constant (offsets), a step where an axis reverses (backlash, sampled there), a
            // function of time (warm-up), of the length cut (wear) or of the travel since a
            // reversal (spikes, in `spacing`): nothing that turns with the arc.
            Effect::ToolOffsetX(_)
            | Effect::ToolOffsetZ(_)
            | Effect::BacklashX(_)
            | Effect::BacklashZ(_)
            | Effect::ThermalX(_)
            | Effect::ThermalZ(_)
            | Effect::ToolWear(_)
            | Effect::ReversalSpikeX(_)
            | Effect::ReversalSpikeZ(_) => ArcTerms::default(),
        }
    }

    /// The effect's name as the model file writes it.
    pub fn name(&self) -> &'static str {
        match self {
            Effect::ToolOffsetX(_) => "tool_offset_x",
            Effect::ToolOffsetZ(_) => "tool_offset_z",
            Effect::ScaleX(_) => "scale_x",
            Effect::ScaleZ(_) => "scale_z",
            Effect::Squareness(_) => "squareness",
            Effect::BacklashX(_) => "backlash_x",
            Effect::BacklashZ(_) => "backlash_z",
            Effect::CyclicX(_) => "cyclic_x",
            Effect::CyclicZ(_) => "cyclic_z",
            Effect::ServoMismatch(_) => "servo_mismatch",
            Effect::ThermalX(_) => "thermal_x",
            Effect::ThermalZ(_) => "thermal_z",
            Effect::ToolWear(_) => "tool_wear",
            Effect::ReversalSpikeX(_) => "reversal_spike_x",
            Effect::ReversalSpikeZ(_) => "reversal_spike_z",
            Effect::StraightnessX(_) => "straightness_x",
            Effect::StraightnessZ(_) => "straightness_z",
            Effect::NoseRadius(_) => "nose_radius",
        }
    }
}

/// First-order warm-up growth: `amp · (1 − e^(−t/τ))`, nothing before the machine starts.
pub(crate) fn warm_up(amp: f64, tau_min: f64, t_min: f64) -> f64 {
    if t_min <= 0.0 || tau_min <= 0.0 {
        return if tau_min <= 0.0 && t_min > 0.0 { amp } else { 0.0 };
    }
    amp * (1.0 - (-t_min / tau_min).exp())
}

/// One backlash effect's part of the slide's position in the play: the tracker runs the
/// play operator with the total play of the axis, and each effect takes its share. A
/// negative `b` (an over-compensating control) is no play the tracker can run: it is the
/// same formula, `−d·b/2` with `d` the direction of the last motion, so the slide leads.
pub(crate) fn backlash_share(b: f64, play: f64, slide_offset: f64, direction: i8) -> f64 {
    if b > 0.0 { if play > 0.0 { slide_offset * b / play } else { 0.0 } } else { -f64::from(direction) * b / 2.0 }
}

/// A bound on the second derivative of `bow(coeffs, p)` for `|p| ≤ reach`:
/// `Σ |coeffs[k]|·(k+2)(k+1)·reach^k`.
pub(crate) fn bow_curvature(coeffs: &[f64], reach: f64) -> f64 {
    let reach = reach.abs();
    coeffs.iter().enumerate().map(|(k, c)| c.abs() * ((k + 2) * (k + 1)) as f64 * reach.powi(k as i32)).sum()
}

/// A bound on the slope of `bow(coeffs, p)` for `|p| ≤ reach`:
/// `Σ |coeffs[k]|·(k+2)·reach^(k+1)`.
pub(crate) fn bow_slope(coeffs: &[f64], reach: f64) -> f64 {
    let reach = reach.abs();
    coeffs.iter().enumerate().map(|(k, c)| c.abs() * (k + 2) as f64 * reach.powi(k as i32 + 1)).sum()
}

/// A reversal spike: `h · direction · e^(−s/decay)`.
pub(crate) fn spike(h: f64, decay_mm: f64, direction: i8, since_reversal: f64) -> f64 {
    if decay_mm <= 0.0 || !since_reversal.is_finite() {
        return 0.0;
    }
    h * f64::from(direction) * (-since_reversal / decay_mm).exp()
}

/// `Σ coeffs[k] · p^(k+2)`, by Horner's rule.
pub(crate) fn bow(coeffs: &[f64], p: f64) -> f64 {
    coeffs.iter().rev().fold(0.0, |acc, c| acc * p + c) * p * p
}
