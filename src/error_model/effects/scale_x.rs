//! `scale_x {ppm}`: the X slide travels `ppm` parts per million too far (ball-screw lead
//! error, screw growth): `dx = x · ppm · 1e-6`, zero on the spindle axis.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR, MICRON, Search, beyond};
use crate::error_model::spacing::{ArcTerms, Spacing};
use crate::toolpath::Xz;

use super::ParametricEffect;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScaleX {
    /// Parts per million of the travel from zero.
    pub ppm: f64,
}

/// Plausible `ppm`: within ±10,000 (1 % of the travel). Ball-screw lead errors and
/// thermal growth of the screw are tens to hundreds of ppm.
pub const PPM: Range = Range::magnitude(10_000.0, "ppm");

impl ParametricEffect for ScaleX {
    fn check(&self) -> Result<(), Invalid> {
        PPM.check_key("ppm", self.ppm)
    }

    fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(s.at.x * self.ppm * 1e-6, 0.0)
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
        ArcTerms::gradient(self.ppm * 1e-6)
    }

    const FIT: Fit = Fit::linear(&["ppm"], Search::None);

    fn probe(extents: &Extents) -> f64 {
        MICRON / extents.x * 1e6
    }

    fn fitted(linear: [f64; MAX_LINEAR], _searched: f64) -> Self {
        ScaleX { ppm: linear[0] }
    }

    fn out_of_bounds(&self, _extents: &Extents) -> Option<String> {
        beyond(self.ppm, 500.0, "ppm")
    }
}
