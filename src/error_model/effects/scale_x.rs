//! `scale_x {ppm}`: the X slide travels `ppm` parts per million too far (ball-screw lead
//! error, screw growth): `dx = x · ppm · 1e-6`, zero on the spindle axis.

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScaleX {
    /// Parts per million of the travel from zero.
    pub ppm: f64,
}

impl ScaleX {
    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(s.at.x * self.ppm * 1e-6, 0.0)
    }
}
