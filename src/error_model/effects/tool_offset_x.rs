//! `tool_offset_x {dx}`: the tool sits `dx` (mm, radius) off its setting in X, everywhere: a
//! tool setting error. Its signature is the same size error on every diameter.

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolOffsetX {
    /// mm, radius.
    pub dx: f64,
}

impl ToolOffsetX {
    pub fn displacement(&self, _s: &Sample) -> Xz {
        Xz::new(self.dx, 0.0)
    }
}
