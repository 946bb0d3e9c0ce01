//! `backlash_z {b}`: lost motion in the Z drive, `dz = ±b/2` by the sign of the last
//! non-zero Z motion; it persists while the axis rests and steps by `b` where Z reverses.

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BacklashZ {
    /// Total play, mm (radius for X).
    pub b: f64,
}

impl BacklashZ {
    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(0.0, f64::from(s.direction.z) * self.b / 2.0)
    }
}
