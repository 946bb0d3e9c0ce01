//! The parametric effects of the model's `[[effect]]` tables, one file each. Every effect
//! is a displacement of the tool (actual − commanded, mm, X as a radius) as a function of a
//! `Sample`; `kind` in the table names it and the other keys are its parameters, exactly:
//!
//! ```toml
//! [[effect]]
//! kind = "backlash_x"
//! b = 0.004
//! ```
//!
//! An effect's file holds every fact of it, as its parameters' `ParametricEffect`: the
//! ranges a model file may give, the displacement, the play, whether it is a function of
//! time or of the cut length, how closely a move and an arc are sampled for it, and how
//! `diagnose` fits it (shape, probe, the bounds of a fitted value). A cause that acts on
//! either slide is one file and one type over its axis (`backlash.rs`, `Backlash<A>`;
//! `axis.rs`), which gives one effect per axis. The list below the trait (`effects!`)
//! names each file and, in it, each effect by its name in a model file and its type: the
//! `Effect` enum, `EffectKind`, `NAMES` and every dispatch of `Effect` come from it, each
//! an exhaustive match, so a new effect is its file and a line of that list.

use serde::{Deserialize, Deserializer, Serialize};

use crate::bounds::Invalid;
use crate::error_model::Sample;
use crate::error_model::control::TablePart;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR};
use crate::error_model::spacing::{ArcTerms, Spacing};
use crate::toolpath::Xz;

/// Every fact of one parametric effect, implemented by its parameters in its own file. No
/// item has a default: a new effect states each one, and the compiler asks for any it
/// lacks.
pub trait ParametricEffect: Sized {
    /// The parameters against the ranges a model file may give (checked when it is read;
    /// the path of a refused value is relative to the effect's table). They refuse what no
    /// machine has (a misread unit, a typing error), and are wider than `out_of_bounds`.
    fn check(&self) -> Result<(), Invalid>;

    /// The displacement of the tool at `s`: actual − commanded, mm, X as a radius.
    fn displacement(&self, s: &Sample) -> Xz;

    /// The play this effect puts in each axis' drive, mm (the tracker's play operator,
    /// `state.rs`).
    fn play(&self) -> Xz;

    /// Whether the displacement is a function of time alone (a warm-up), which the model
    /// evaluates once per sample time (`at_time`).
    const OF_TIME: bool;

    /// The displacement at `t_min` minutes since the machine started, as `displacement`
    /// gives it at a sample of that time, for an effect of time alone (`OF_TIME`); `None`
    /// for any other.
    fn at_time(&self, t_min: f64) -> Option<Xz>;

    /// Whether the displacement depends on the length the tool has cut: the trackers follow
    /// it only for a model with such an effect.
    const WEARS: bool;

    /// How closely a move must be sampled for the straight interpolation between samples
    /// to follow this effect within `allowance` mm (`spacing.rs`); `reach` is the farthest
    /// the program goes from the origin in each axis (mm, X as a radius).
    fn spacing(&self, allowance: f64, reach: Xz) -> Spacing;

    /// What makes this effect's correction turn around an arc (`spacing::ArcTerms`);
    /// `reach` as for `spacing`.
    fn arc_terms(&self, reach: Xz) -> ArcTerms;

    /// How `diagnose` fits this effect (`fitting::Fit`).
    const FIT: Fit;

    /// The probe value of each linear parameter: about a micrometre (`fitting::MICRON`) of
    /// displacement over the measurement's `extents`.
    fn probe(extents: &Extents) -> f64;

    /// The effect with linear parameters `linear` (in the order of `FIT.linear`, the rest
    /// zero) and searched parameter `searched` (NaN for none).
    fn fitted(linear: [f64; MAX_LINEAR], searched: f64) -> Self;

    /// What a control's own axis compensation (its pitch-error table and backlash
    /// compensation, functions of each axis' own commanded position and direction) carries
    /// of this effect; the program carries the rest (`control.rs`).
    fn control_table(&self) -> TablePart;

    /// Why a fitted effect is not a physical one, if it is not: the bounds of what
    /// `diagnose` reports as found, over the measurement's `extents`. They are tighter than
    /// `check`'s: they bound what a machine in service shows, where `check` refuses only
    /// what no machine has.
    fn out_of_bounds(&self, extents: &Extents) -> Option<String>;
}

/// The `Effect` enum, `EffectKind`, `NAMES` and the dispatch of every fact, from the list of
/// effects: each `file { name: Type, … }`, the file a module of this directory and each
/// `name` an effect's name in a model file, `Type` its parameters (a cause over its axis
/// names one effect per axis).
macro_rules! effects {
    ($($file:ident { $($name:ident: $Type:ident),+ $(,)? }),+ $(,)?) => {
        $(
            pub mod $file;
            pub use $file::{$($Type),+};
        )+
        effects!(@list $($($name: $Type),+),+);
    };
    (@list $($name:ident: $Type:ident),+) => {

        /// One parametric effect with its parameters. It is written as its parameters
        /// (`Serialize`; its name is `name`); a model file's `[[effect]]` is read by its
        /// `kind`, `Effect::deserialize_kind`.
        #[derive(Debug, Clone, PartialEq, Serialize)]
        #[serde(untagged)]
        pub enum Effect {
            $($Type($Type)),+
        }

        /// Which effect, without its parameters.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum EffectKind {
            $($Type),+
        }

        /// Every effect name, in catalogue order.
        pub const NAMES: [&str; EffectKind::ALL.len()] = [$(stringify!($name)),+];

        impl EffectKind {
            /// Every kind, in catalogue order.
            pub const ALL: [EffectKind; [$(stringify!($name)),+].len()] = [$(EffectKind::$Type),+];

            /// The effect's name as the model file writes it.
            pub const fn name(self) -> &'static str {
                match self {
                    $(EffectKind::$Type => stringify!($name)),+
                }
            }

            /// How `diagnose` fits this kind.
            pub const fn fit(self) -> Fit {
                match self {
                    $(EffectKind::$Type => <$Type as ParametricEffect>::FIT),+
                }
            }

            /// The probe value of each of its linear parameters (`ParametricEffect::probe`).
            pub fn probe(self, extents: &Extents) -> f64 {
                match self {
                    $(EffectKind::$Type => $Type::probe(extents)),+
                }
            }

            /// The effect of this kind with the fitted values (`ParametricEffect::fitted`).
            pub fn fitted(self, linear: [f64; MAX_LINEAR], searched: f64) -> Effect {
                match self {
                    $(EffectKind::$Type => Effect::$Type($Type::fitted(linear, searched))),+
                }
            }
        }

        // No fit has more linear parameters than `fitted` takes.
        $(const _: () = assert!(<$Type as ParametricEffect>::FIT.linear.len() <= MAX_LINEAR);)+

        impl Effect {
            /// The effect named `kind` (a name of `NAMES`), its parameters read from
            /// `parameters` (the table without its `kind`); `None` for a name no effect has.
            /// The model file reads each `[[effect]]` table through this rather than through
            /// a tag on the enum, which would buffer the table and lose the place of an
            /// error in it.
            pub fn deserialize_kind<'de, D: Deserializer<'de>>(
                kind: &str,
                parameters: D,
            ) -> Option<Result<Effect, D::Error>> {
                match kind {
                    $(stringify!($name) => Some($Type::deserialize(parameters).map(Effect::$Type)),)+
                    _ => None,
                }
            }

            /// Which effect this is.
            pub fn kind(&self) -> EffectKind {
                match self {
                    $(Effect::$Type(_) => EffectKind::$Type),+
                }
            }

            /// The effect's name as the model file writes it.
            pub fn name(&self) -> &'static str {
                self.kind().name()
            }

            /// `ParametricEffect::check`.
            pub fn check(&self) -> Result<(), Invalid> {
                match self {
                    $(Effect::$Type(e) => e.check()),+
                }
            }

            /// `ParametricEffect::play`.
            pub fn play(&self) -> Xz {
                match self {
                    $(Effect::$Type(e) => e.play()),+
                }
            }

            // Inlined into the model's sum (`ErrorModel::displacement_timed`), which
            // evaluates every effect several times per sample: a call clobbers every
            // floating-point register the sum and its caller hold, which cost more than
            // most effects' arithmetic.
            /// `ParametricEffect::displacement`.
            #[inline(always)]
            pub fn displacement(&self, s: &Sample) -> Xz {
                match self {
                    $(Effect::$Type(e) => e.displacement(s)),+
                }
            }

            /// `ParametricEffect::at_time`.
            pub fn at_time(&self, t_min: f64) -> Option<Xz> {
                match self {
                    $(Effect::$Type(e) => e.at_time(t_min)),+
                }
            }

            /// Whether the term is a function of time alone (`ParametricEffect::OF_TIME`).
            pub fn is_of_time(&self) -> bool {
                match self {
                    $(Effect::$Type(_) => $Type::OF_TIME),+
                }
            }

            /// Whether the term depends on the length cut (`ParametricEffect::WEARS`).
            pub fn wears(&self) -> bool {
                match self {
                    $(Effect::$Type(_) => $Type::WEARS),+
                }
            }

            /// `ParametricEffect::spacing`.
            pub fn spacing(&self, allowance: f64, reach: Xz) -> Spacing {
                match self {
                    $(Effect::$Type(e) => e.spacing(allowance, reach)),+
                }
            }

            /// `ParametricEffect::arc_terms`.
            pub fn arc_terms(&self, reach: Xz) -> ArcTerms {
                match self {
                    $(Effect::$Type(e) => e.arc_terms(reach)),+
                }
            }

            /// `ParametricEffect::control_table`.
            pub fn control_table(&self) -> TablePart {
                match self {
                    $(Effect::$Type(e) => e.control_table()),+
                }
            }

            /// `ParametricEffect::out_of_bounds`.
            pub fn out_of_bounds(&self, extents: &Extents) -> Option<String> {
                match self {
                    $(Effect::$Type(e) => e.out_of_bounds(extents)),+
                }
            }
        }
    };
}

pub mod axis;
pub use axis::{X, Z};

effects! {
    tool_offset { tool_offset_x: ToolOffsetX, tool_offset_z: ToolOffsetZ },
    scale { scale_x: ScaleX, scale_z: ScaleZ },
    squareness { squareness: Squareness },
    backlash { backlash_x: BacklashX, backlash_z: BacklashZ },
    cyclic { cyclic_x: CyclicX, cyclic_z: CyclicZ },
    servo_mismatch { servo_mismatch: ServoMismatch },
    thermal { thermal_x: ThermalX, thermal_z: ThermalZ },
    tool_wear { tool_wear: ToolWear },
    reversal_spike { reversal_spike_x: ReversalSpikeX, reversal_spike_z: ReversalSpikeZ },
    straightness { straightness_x: StraightnessX, straightness_z: StraightnessZ },
    nose_radius { nose_radius: NoseRadius },
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

/// A cyclic error's amplitude and phase from its sine and cosine parts:
/// `amp·sin(u + φ) = amp cos φ · sin u + amp sin φ · cos u`.
pub(crate) fn amplitude_phase(sine: f64, cosine: f64) -> (f64, f64) {
    (sine.hypot(cosine), cosine.atan2(sine))
}

/// `Σ coeffs[k] · p^(k+2)`, by Horner's rule.
pub(crate) fn bow(coeffs: &[f64], p: f64) -> f64 {
    coeffs.iter().rev().fold(0.0, |acc, c| acc * p + c) * p * p
}
