//! `tool_wear {um_per_m}`: the tool wears back in proportion to the length it has cut,
//! `dx = um_per_m · 1e-3 · L` (L in metres since the tool was set): diameters drift with
//! cut length and reset at a tool change.

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolWear {
    /// Micrometres of radius per metre of cut.
    pub um_per_m: f64,
}

impl ToolWear {
    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(self.um_per_m * 1e-3 * s.cut_length_m, 0.0)
    }
}
