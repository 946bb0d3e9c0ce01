//! `backlash_z {b}`: lost motion (play) `b` in the Z drive: the slide lags its command by
//! half the play against the direction it was last pushed in, `dz = ∓b/2`; see
//! `backlash_x.rs`.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::toolpath::Xz;

use super::backlash_share as share;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BacklashZ {
    /// Total play, mm (radius for X).
    pub b: f64,
}

/// Plausible `b`: within ±1 mm. Drives have micrometres to tenths of a millimetre of
/// play; a negative `b` is an over-compensating control.
pub const B: Range = Range::magnitude(1.0, "mm");

impl BacklashZ {
    /// The parameters against their plausible ranges (checked when a model file is read).
    pub fn check(&self) -> Result<(), Invalid> {
        B.check_key("b", self.b)
    }

    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(0.0, share(self.b, s.play.z, s.backlash.z, s.direction.z))
    }
}
