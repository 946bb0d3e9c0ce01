//! `tool_wear {um_per_m}`: the tool wears back in proportion to the length it has cut,
//! `dx = um_per_m · 1e-3 · L` (L in metres since the tool was set): diameters drift with
//! cut length and reset at a tool change.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolWear {
    /// Micrometres of radius per metre of cut.
    pub um_per_m: f64,
}

/// Plausible `um_per_m`: within ±1,000 µm per metre of cut. An insert that loses a
/// millimetre per metre is gone after a few parts.
pub const UM_PER_M: Range = Range::magnitude(1_000.0, "µm/m");

impl ToolWear {
    /// The parameters against their plausible ranges (checked when a model file is read).
    pub fn check(&self) -> Result<(), Invalid> {
        UM_PER_M.check_key("um_per_m", self.um_per_m)
    }

    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(self.um_per_m * 1e-3 * s.cut_length_m, 0.0)
    }
}
