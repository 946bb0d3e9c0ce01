//! `straightness_z {coeffs}`: the X slide does not run straight; moving along X carries
//! the tool off in Z, `dz = Σ coeffs[k] · x^(k+2)` (the constant and slope terms are other
//! effects: `tool_offset_z` and the squareness of the slides).

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::error_model::spacing::{Spacing, step_for_curvature};
use crate::toolpath::Xz;

use super::{bow, bow_curvature};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StraightnessZ {
    /// Coefficients of the square, cube, … of the position, mm^(1−k).
    pub coeffs: Vec<f64>,
}

impl StraightnessZ {
    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(0.0, bow(&self.coeffs, s.at.x))
    }

    /// The bow's second derivative, `Σ |coeffs[k]|·(k+2)(k+1)·|x|^k`, is largest at the
    /// farthest X the program reaches (`reach_x`, mm, a radius).
    pub fn spacing(&self, allowance: f64, reach_x: f64) -> Spacing {
        Spacing::mm(step_for_curvature(bow_curvature(&self.coeffs, reach_x), allowance))
    }
}
