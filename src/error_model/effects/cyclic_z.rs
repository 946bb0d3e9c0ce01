//! `cyclic_z {amp, pitch, phase}`: the periodic lead error of the Z ball screw,
//! `dz = amp · sin(2πz/pitch + phase)` (the thesis machine's screw has an 11.94 mm pitch).

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CyclicZ {
    /// Amplitude, mm.
    pub amp: f64,
    /// Period, mm of travel (the screw's lead).
    pub pitch: f64,
    /// Phase at zero, radians.
    pub phase: f64,
}

impl CyclicZ {
    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(0.0, self.amp * (std::f64::consts::TAU * s.at.z / self.pitch + self.phase).sin())
    }
}
