//! `squareness {urad}`: the X slide is not square to the spindle axis: moving along Z
//! carries the tool off in X, `dx = z · urad · 1e-6`. A faced surface comes out conical and
//! a ball bar shows a 45° oval of the same sign in both directions.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::control::TablePart;
use crate::error_model::model_file::Axis;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR, MICRON, Search, beyond};
use crate::error_model::spacing::{ArcTerms, Spacing};
use crate::toolpath::Xz;

use super::ParametricEffect;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Squareness {
    /// Out-of-squareness, microradians (positive: X grows with Z).
    pub urad: f64,
}

/// Plausible `urad`: within ±10,000 µrad (0.57°). Slides are square to tens of
/// microradians; more is a crash or a misread unit.
pub const URAD: Range = Range::magnitude(10_000.0, "µrad");

impl ParametricEffect for Squareness {
    fn check(&self) -> Result<(), Invalid> {
        URAD.check_key("urad", self.urad)
    }

    fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(s.at.z * self.urad * 1e-6, 0.0)
    }

    fn play(&self) -> Xz {
        Xz::new(0.0, 0.0)
    }

    const OF_TIME: bool = false;

    fn at_time(&self, _t_min: f64) -> Option<Xz> {
        None
    }

    const WEARS: bool = false;

    fn spacing(&self, _allowance: f64, _reach: Xz) -> Spacing {
        // Affine in the position along a straight move: one sample at each end follows it.
        Spacing::ANY
    }

    fn arc_terms(&self, _reach: Xz) -> ArcTerms {
        ArcTerms::gradient(self.urad * 1e-6)
    }

    const FIT: Fit = Fit::linear(&["urad"], Search::None);

    fn probe(extents: &Extents) -> f64 {
        MICRON / extents.z * 1e6
    }

    fn fitted(linear: [f64; MAX_LINEAR], _searched: f64) -> Self {
        Squareness { urad: linear[0] }
    }

    fn control_table(&self) -> TablePart {
        // X as a function of Z's position.
        TablePart::CrossAxis(Axis::X)
    }

    fn out_of_bounds(&self, _extents: &Extents) -> Option<String> {
        beyond(self.urad, 1000.0, "µrad")
    }
}
