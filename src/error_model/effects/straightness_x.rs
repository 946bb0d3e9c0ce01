//! `straightness_x {coeffs}`: the Z slide does not run straight; moving along Z carries
//! the tool off in X by a bow, `dx = Σ coeffs[k] · z^(k+2)`. The polynomial starts at the
//! square: a constant is `tool_offset_x` and a slope is `squareness`.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Key, Range, Reason};
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

/// Plausible coefficients: at most six (a bow up to the seventh power of the position),
/// each within `coefficient_range`.
pub const TERMS: usize = 6;

/// The plausible range of `coeffs[k]`: a term that bends the path by at most 1 mm at
/// 100 mm from the origin, `|coeffs[k]| · 100^(k+2) ≤ 1` (slides bow by micrometres over
/// their travel).
pub fn coefficient_range(k: usize) -> Range {
    Range::magnitude(100f64.powi(-(k as i32 + 2)), "")
}

impl StraightnessX {
    /// The coefficients against their plausible ranges (checked when a model file is read):
    /// at most `TERMS` of them, each within `coefficient_range`.
    pub fn check(&self) -> Result<(), Invalid> {
        if self.coeffs.len() > TERMS {
            return Err(Invalid { path: vec![Key::Name("coeffs")], reason: Reason::Rule("at most six coefficients") });
        }
        for (k, &c) in self.coeffs.iter().enumerate() {
            coefficient_range(k).check(c).map_err(|e| Invalid {
                path: vec![Key::Name("coeffs"), Key::Index(k)],
                reason: Reason::OutOfRange(e),
            })?;
        }
        Ok(())
    }

    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(bow(&self.coeffs, s.at.z), 0.0)
    }

    /// The bow's second derivative, `Σ |coeffs[k]|·(k+2)(k+1)·|z|^k`, is largest at the
    /// farthest Z the program reaches (`reach_z`, mm).
    pub fn spacing(&self, allowance: f64, reach_z: f64) -> Spacing {
        Spacing::mm(step_for_curvature(bow_curvature(&self.coeffs, reach_z), allowance))
    }
}
