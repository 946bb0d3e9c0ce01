//! `straightness_x {coeffs}`: the Z slide does not run straight; moving along Z carries
//! the tool off in X by a bow, `dx = Σ coeffs[k] · z^(k+2)`. The polynomial starts at the
//! square: a constant is `tool_offset_x` and a slope is `squareness`.

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::error_model::spacing::{Spacing, step_for_curvature};
use crate::toolpath::Xz;

use super::{bow, bow_curvature};

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

    /// The bow's second derivative, `Σ |coeffs[k]|·(k+2)(k+1)·|z|^k`, is largest at the
    /// farthest Z the program reaches (`reach_z`, mm).
    pub fn spacing(&self, allowance: f64, reach_z: f64) -> Spacing {
        Spacing::mm(step_for_curvature(bow_curvature(&self.coeffs, reach_z), allowance))
    }
}
