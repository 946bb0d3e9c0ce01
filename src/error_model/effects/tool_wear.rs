//! `tool_wear {um_per_m}`: the tool wears back in proportion to the length it has cut,
//! `dx = um_per_m · 1e-3 · L` (L in metres since the tool was set): diameters drift with
//! cut length and reset at a tool change.

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
pub struct ToolWear {
    /// Micrometres of radius per metre of cut.
    pub um_per_m: f64,
}

/// Plausible `um_per_m`: within ±1,000 µm per metre of cut. An insert that loses a
/// millimetre per metre is gone after a few parts.
pub const UM_PER_M: Range = Range::magnitude(1_000.0, "µm/m");

impl ParametricEffect for ToolWear {
    fn check(&self) -> Result<(), Invalid> {
        UM_PER_M.check_key("um_per_m", self.um_per_m)
    }

    fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(self.um_per_m * 1e-3 * s.cut_length_m, 0.0)
    }

    fn play(&self) -> Xz {
        Xz::new(0.0, 0.0)
    }

    const OF_TIME: bool = false;

    fn at_time(&self, _t_min: f64) -> Option<Xz> {
        None
    }

    const WEARS: bool = true;

    fn spacing(&self, _allowance: f64, _reach: Xz) -> Spacing {
        // Linear in the length cut.
        Spacing::ANY
    }

    fn arc_terms(&self, _reach: Xz) -> ArcTerms {
        // A function of the length cut: nothing turns with the arc.
        ArcTerms::default()
    }

    const FIT: Fit = Fit::linear(&["um_per_m"], Search::None);

    fn probe(extents: &Extents) -> f64 {
        MICRON / (extents.cut_m * 1e-3)
    }

    fn fitted(linear: [f64; MAX_LINEAR], _searched: f64) -> Self {
        ToolWear { um_per_m: linear[0] }
    }

    fn control_table(&self) -> TablePart {
        TablePart::Program("a function of the length the tool has cut")
    }

    fn out_of_bounds(&self, _extents: &Extents) -> Option<String> {
        beyond(self.um_per_m, 500.0, "µm/m")
    }
}
