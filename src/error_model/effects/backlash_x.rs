//! `backlash_x {b}`: lost motion in the X drive. The slide lags by half the play behind
//! the direction it last moved in, `dx = ±b/2` by the sign of the last non-zero X motion;
//! the offset persists while the axis rests, and steps by `b` where X reverses.

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BacklashX {
    /// Total play, mm (radius for X).
    pub b: f64,
}

impl BacklashX {
    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(f64::from(s.direction.x) * self.b / 2.0, 0.0)
    }
}
