//! `scale_z {ppm}`: the Z slide travels `ppm` parts per million too far (ball-screw lead
//! error, screw growth): `dz = z · ppm · 1e-6`, zero at the work zero.

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScaleZ {
    /// Parts per million of the travel from zero.
    pub ppm: f64,
}

impl ScaleZ {
    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(0.0, s.at.z * self.ppm * 1e-6)
    }
}
