//! `squareness {urad}`: the X slide is not square to the spindle axis: moving along Z
//! carries the tool off in X, `dx = z · urad · 1e-6`. A faced surface comes out conical and
//! a ball bar shows a 45° oval of the same sign in both directions.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Squareness {
    /// Out-of-squareness, microradians (positive: X grows with Z).
    pub urad: f64,
}

/// Plausible `urad`: within ±10,000 µrad (0.57°). Slides are square to tens of
/// microradians; more is a crash or a misread unit.
pub const URAD: Range = Range::magnitude(10_000.0, "µrad");

impl Squareness {
    /// The parameters against their plausible ranges (checked when a model file is read).
    pub fn check(&self) -> Result<(), Invalid> {
        URAD.check_key("urad", self.urad)
    }

    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(s.at.z * self.urad * 1e-6, 0.0)
    }
}
