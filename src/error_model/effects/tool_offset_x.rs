//! `tool_offset_x {dx}`: the tool sits `dx` (mm, radius) off its setting in X, everywhere: a
//! tool setting error. Its signature is the same size error on every diameter.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolOffsetX {
    /// mm, radius.
    pub dx: f64,
}

/// Plausible `dx`: within ±10 mm. A tool set further off than that is a wrong offset
/// number or a crash, not an error a model compensates.
pub const DX: Range = Range::magnitude(10.0, "mm");

impl ToolOffsetX {
    /// The parameters against their plausible ranges (checked when a model file is read).
    pub fn check(&self) -> Result<(), Invalid> {
        DX.check_key("dx", self.dx)
    }

    pub fn displacement(&self, _s: &Sample) -> Xz {
        Xz::new(self.dx, 0.0)
    }
}
