//! `scale_x {ppm}`, `scale_z {ppm}`: the named slide travels `ppm` parts per million too
//! far (ball-screw lead error, screw growth): `dx = x · ppm · 1e-6`, zero on the spindle
//! axis; `dz = z · ppm · 1e-6`, zero at the work zero.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::control::TablePart;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR, MICRON, Search, beyond};
use crate::error_model::spacing::{ArcTerms, Spacing};
use crate::toolpath::Xz;

use super::ParametricEffect;
use super::axis::{Axis, X, Z};

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scale<A: Axis> {
    /// Parts per million of the travel from zero.
    pub ppm: f64,
    /// The slide that travels too far.
    #[serde(skip)]
    pub axis: A,
}

/// `scale_x`.
pub type ScaleX = Scale<X>;
/// `scale_z`.
pub type ScaleZ = Scale<Z>;

/// Plausible `ppm`: within ±10,000 (1 % of the travel). Ball-screw lead errors and
/// thermal growth of the screw are tens to hundreds of ppm.
pub const PPM: Range = Range::magnitude(10_000.0, "ppm");

impl<A: Axis> ParametricEffect for Scale<A> {
    fn check(&self) -> Result<(), Invalid> {
        PPM.check_key("ppm", self.ppm)
    }

    fn displacement(&self, s: &Sample) -> Xz {
        A::along(A::of(s.at) * self.ppm * 1e-6)
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
        MICRON / A::extent(extents) * 1e6
    }

    fn fitted(linear: [f64; MAX_LINEAR], _searched: f64) -> Self {
        Scale { ppm: linear[0], axis: A::default() }
    }

    fn control_table(&self) -> TablePart {
        // A function of the axis' own position alone.
        TablePart::Pitch(A::SLIDE)
    }

    fn out_of_bounds(&self, _extents: &Extents) -> Option<String> {
        beyond(self.ppm, 500.0, "ppm")
    }
}
