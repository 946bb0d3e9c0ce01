//! `thermal_z {amp, tau_min}`: first-order warm-up growth in Z (eq. 5.1 of the thesis),
//! `dz = amp · (1 − e^(−t/τ))`, t in minutes since the machine started.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::spacing::{Spacing, step_for_curvature};
use crate::toolpath::Xz;

use super::warm_up;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThermalZ {
    /// Growth at thermal equilibrium, mm.
    pub amp: f64,
    /// Time constant, minutes.
    pub tau_min: f64,
}

/// Plausible `amp`: within ±1 mm (spindles and slides grow by micrometres to tens of
/// micrometres).
pub const AMP: Range = Range::magnitude(1.0, "mm");
/// Plausible `tau_min`: from 0.1 to 100,000 minutes. Machine warm-ups take tens of
/// minutes to hours; the sampling step follows `amp/τ²`, so τ must be more than nothing.
pub const TAU_MIN: Range = Range::closed(0.1, 100_000.0, "min");

impl ThermalZ {
    /// The parameters against their plausible ranges (checked when a model file is read).
    pub fn check(&self) -> Result<(), Invalid> {
        AMP.check_key("amp", self.amp)?;
        TAU_MIN.check_key("tau_min", self.tau_min)
    }

    pub fn displacement(&self, s: &Sample) -> Xz {
        self.at_time(s.t_min)
    }

    /// The growth at `t_min` minutes since the machine started.
    pub fn at_time(&self, t_min: f64) -> Xz {
        Xz::new(0.0, warm_up(self.amp, self.tau_min, t_min))
    }

    /// The warm-up curve bends most at the start: `amp/τ²` per minute², whatever the path.
    pub fn spacing(&self, allowance: f64) -> Spacing {
        Spacing::minutes(step_for_curvature(self.amp / (self.tau_min * self.tau_min), allowance))
    }
}
