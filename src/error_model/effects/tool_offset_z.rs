//! `tool_offset_z {dz}`: the tool sits `dz` (mm) off its setting in Z, everywhere: a tool
//! setting or datum error that shifts every face by the same amount.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolOffsetZ {
    /// mm.
    pub dz: f64,
}

/// Plausible `dz`: within ±10 mm. A tool set further off than that is a wrong offset
/// number or a crash, not an error a model compensates.
pub const DZ: Range = Range::magnitude(10.0, "mm");

impl ToolOffsetZ {
    /// The parameters against their plausible ranges (checked when a model file is read).
    pub fn check(&self) -> Result<(), Invalid> {
        DZ.check_key("dz", self.dz)
    }

    pub fn displacement(&self, _s: &Sample) -> Xz {
        Xz::new(0.0, self.dz)
    }
}
