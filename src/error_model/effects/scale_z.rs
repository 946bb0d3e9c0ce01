//! `scale_z {ppm}`: the Z slide travels `ppm` parts per million too far (ball-screw lead
//! error, screw growth): `dz = z · ppm · 1e-6`, zero at the work zero.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScaleZ {
    /// Parts per million of the travel from zero.
    pub ppm: f64,
}

/// Plausible `ppm`: within ±10,000 (1 % of the travel). Ball-screw lead errors and
/// thermal growth of the screw are tens to hundreds of ppm.
pub const PPM: Range = Range::magnitude(10_000.0, "ppm");

impl ScaleZ {
    /// The parameters against their plausible ranges (checked when a model file is read).
    pub fn check(&self) -> Result<(), Invalid> {
        PPM.check_key("ppm", self.ppm)
    }

    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(0.0, s.at.z * self.ppm * 1e-6)
    }
}
