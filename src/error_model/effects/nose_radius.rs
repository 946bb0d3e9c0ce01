//! `nose_radius {dr}`: the tool's nose radius is `dr` larger than the tool table says. The
//! tool is set on its imaginary tip, so the nose centre sits `dr` further back along the tip
//! direction and the cut point moves by `−dr · (tip + n)`, n the surface normal: nothing on
//! a diameter or a face, `0.414 · dr` off the surface on a 45° chamfer.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::control::TablePart;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR, MICRON, Search, beyond};
use crate::error_model::spacing::{ArcTerms, Spacing};
use crate::toolpath::Xz;

use super::ParametricEffect;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NoseRadius {
    /// Nose radius error, mm.
    pub dr: f64,
}

/// Plausible `dr`: within ±1 mm. Nose radii are 0.1 to 2.4 mm, and an error is a
/// fraction of one.
pub const DR: Range = Range::magnitude(1.0, "mm");

impl ParametricEffect for NoseRadius {
    fn check(&self) -> Result<(), Invalid> {
        DR.check_key("dr", self.dr)
    }

    fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(-self.dr * (s.tip.x + s.normal.x), -self.dr * (s.tip.z + s.normal.z))
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
        // Constant at a line's constant normal.
        Spacing::ANY
    }

    fn arc_terms(&self, _reach: Xz) -> ArcTerms {
        // The error turns with the surface normal.
        ArcTerms { nose_mm: self.dr.abs(), ..ArcTerms::default() }
    }

    const FIT: Fit = Fit::linear(&["dr"], Search::None);

    fn probe(_extents: &Extents) -> f64 {
        MICRON
    }

    fn fitted(linear: [f64; MAX_LINEAR], _searched: f64) -> Self {
        NoseRadius { dr: linear[0] }
    }

    fn control_table(&self) -> TablePart {
        TablePart::Program("a function of the tool's nose and the surface being cut")
    }

    fn out_of_bounds(&self, _extents: &Extents) -> Option<String> {
        beyond(self.dr, 0.4, "dr (mm)")
    }
}
