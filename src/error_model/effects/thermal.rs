//! `thermal_x {amp, tau_min}`, `thermal_z {amp, tau_min}`: first-order warm-up growth along
//! the named axis (eq. 5.1 of the thesis), `amp · (1 − e^(−t/τ))`, t in minutes since the
//! machine started.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::control::TablePart;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR, MICRON, Search, beyond};
use crate::error_model::spacing::{ArcTerms, Spacing, step_for_curvature};
use crate::toolpath::Xz;

use super::axis::{Axis, X, Z};
use super::{ParametricEffect, warm_up};

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Thermal<A: Axis> {
    /// Growth at thermal equilibrium, mm.
    pub amp: f64,
    /// Time constant, minutes.
    pub tau_min: f64,
    /// The axis that grows.
    #[serde(skip)]
    pub axis: A,
}

/// `thermal_x`.
pub type ThermalX = Thermal<X>;
/// `thermal_z`.
pub type ThermalZ = Thermal<Z>;

/// Plausible `amp`: within ±1 mm (spindles and slides grow by micrometres to tens of
/// micrometres).
pub const AMP: Range = Range::magnitude(1.0, "mm");
/// Plausible `tau_min`: from 0.1 to 100,000 minutes. Machine warm-ups take tens of
/// minutes to hours; the sampling step follows `amp/τ²`, so τ must be more than nothing.
pub const TAU_MIN: Range = Range::closed(0.1, 100_000.0, "min");

impl<A: Axis> Thermal<A> {
    /// The growth at `t_min` minutes since the machine started.
    pub fn growth(&self, t_min: f64) -> Xz {
        A::along(warm_up(self.amp, self.tau_min, t_min))
    }
}

impl<A: Axis> ParametricEffect for Thermal<A> {
    fn check(&self) -> Result<(), Invalid> {
        AMP.check_key("amp", self.amp)?;
        TAU_MIN.check_key("tau_min", self.tau_min)
    }

    fn displacement(&self, s: &Sample) -> Xz {
        self.growth(s.t_min)
    }

    fn play(&self) -> Xz {
        Xz::new(0.0, 0.0)
    }

    const OF_TIME: bool = true;

    fn at_time(&self, t_min: f64) -> Option<Xz> {
        Some(self.growth(t_min))
    }

    const WEARS: bool = false;

    fn spacing(&self, allowance: f64, _reach: Xz) -> Spacing {
        // The warm-up curve bends most at the start: `amp/τ²` per minute², whatever the path.
        Spacing::minutes(step_for_curvature(self.amp / (self.tau_min * self.tau_min), allowance))
    }

    fn arc_terms(&self, _reach: Xz) -> ArcTerms {
        // A function of time: nothing turns with the arc.
        ArcTerms::default()
    }

    const FIT: Fit = Fit::linear(&["amp"], Search::Tau);

    fn probe(_extents: &Extents) -> f64 {
        MICRON
    }

    fn fitted(linear: [f64; MAX_LINEAR], searched: f64) -> Self {
        Thermal { amp: linear[0], tau_min: searched, axis: A::default() }
    }

    fn control_table(&self) -> TablePart {
        TablePart::Program("a function of the time since the machine started")
    }

    fn out_of_bounds(&self, _extents: &Extents) -> Option<String> {
        beyond(self.amp, 0.2, "amp (mm)").or_else(|| beyond(self.tau_min, 1000.0, "τ (min)"))
    }
}
