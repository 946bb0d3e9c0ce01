//! `cyclic_x {amp, pitch, phase}`: the periodic lead error of the X ball screw,
//! `dx = amp · sin(2πx/pitch + phase)`, locked to the slide position (not to time).

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CyclicX {
    /// Amplitude, mm.
    pub amp: f64,
    /// Period, mm of travel (the screw's lead).
    pub pitch: f64,
    /// Phase at zero, radians.
    pub phase: f64,
}

impl CyclicX {
    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(self.amp * (std::f64::consts::TAU * s.at.x / self.pitch + self.phase).sin(), 0.0)
    }
}
