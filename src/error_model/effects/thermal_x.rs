//! `thermal_x {amp, tau_min}`: first-order warm-up growth in X (eq. 5.1 of the thesis),
//! `dx = amp · (1 − e^(−t/τ))`, t in minutes since the machine started.

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::error_model::spacing::{Spacing, step_for_curvature};
use crate::toolpath::Xz;

use super::warm_up;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThermalX {
    /// Growth at thermal equilibrium, mm.
    pub amp: f64,
    /// Time constant, minutes.
    pub tau_min: f64,
}

impl ThermalX {
    pub fn displacement(&self, s: &Sample) -> Xz {
        self.at_time(s.t_min)
    }

    /// The growth at `t_min` minutes since the machine started.
    pub fn at_time(&self, t_min: f64) -> Xz {
        Xz::new(warm_up(self.amp, self.tau_min, t_min), 0.0)
    }

    /// The warm-up curve bends most at the start: `amp/τ²` per minute², whatever the path.
    pub fn spacing(&self, allowance: f64) -> Spacing {
        Spacing::minutes(step_for_curvature(self.amp / (self.tau_min * self.tau_min), allowance))
    }
}
