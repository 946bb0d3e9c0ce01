//! `backlash_z {b}`: lost motion (play) `b` in the Z drive: the slide lags its command by
//! half the play against the direction it was last pushed in, `dz = ∓b/2`; see
//! `backlash_x.rs`.

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::toolpath::Xz;

use super::backlash_share as share;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BacklashZ {
    /// Total play, mm (radius for X).
    pub b: f64,
}

impl BacklashZ {
    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(0.0, share(self.b, s.play.z, s.backlash.z, s.direction.z))
    }
}
