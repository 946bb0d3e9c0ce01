//! `tool_offset_z {dz}`: the tool sits `dz` (mm) off its setting in Z, everywhere: a tool
//! setting or datum error that shifts every face by the same amount.

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolOffsetZ {
    /// mm.
    pub dz: f64,
}

impl ToolOffsetZ {
    pub fn displacement(&self, _s: &Sample) -> Xz {
        Xz::new(0.0, self.dz)
    }
}
