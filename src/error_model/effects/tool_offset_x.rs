//! `tool_offset_x {dx}`: the tool sits `dx` (mm, radius) off its setting in X, everywhere: a
//! tool setting error. Its signature is the same size error on every diameter.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR, MICRON, Search, beyond};
use crate::error_model::spacing::{ArcTerms, Spacing};
use crate::toolpath::Xz;

use super::ParametricEffect;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolOffsetX {
    /// mm, radius.
    pub dx: f64,
}

/// Plausible `dx`: within ±10 mm. A tool set further off than that is a wrong offset
/// number or a crash, not an error a model compensates.
pub const DX: Range = Range::magnitude(10.0, "mm");

impl ParametricEffect for ToolOffsetX {
    fn check(&self) -> Result<(), Invalid> {
        DX.check_key("dx", self.dx)
    }

    fn displacement(&self, _s: &Sample) -> Xz {
        Xz::new(self.dx, 0.0)
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
        // Constant: one sample at each end of a move follows it.
        Spacing::ANY
    }

    fn arc_terms(&self, _reach: Xz) -> ArcTerms {
        // Constant: nothing turns with the arc.
        ArcTerms::default()
    }

    const FIT: Fit = Fit::linear(&["dx"], Search::None);

    fn probe(_extents: &Extents) -> f64 {
        MICRON
    }

    fn fitted(linear: [f64; MAX_LINEAR], _searched: f64) -> Self {
        ToolOffsetX { dx: linear[0] }
    }

    fn out_of_bounds(&self, _extents: &Extents) -> Option<String> {
        beyond(self.dx, 0.5, "dx (mm)")
    }
}
