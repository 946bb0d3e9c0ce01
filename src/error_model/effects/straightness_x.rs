//! `straightness_x {coeffs}`: the Z slide does not run straight; moving along Z carries
//! the tool off in X by a bow, `dx = Σ coeffs[k] · z^(k+2)`. The polynomial starts at the
//! square: a constant is `tool_offset_x` and a slope is `squareness`.

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::toolpath::Xz;

use super::bow;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StraightnessX {
    /// Coefficients of the square, cube, … of the position, mm^(1−k).
    pub coeffs: Vec<f64>,
}

impl StraightnessX {
    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(bow(&self.coeffs, s.at.z), 0.0)
    }
}
