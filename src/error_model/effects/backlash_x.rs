//! `backlash_x {b}`: lost motion (play) `b` in the X drive. The slide lags its command by
//! half the play, against the direction it was last pushed in: `dx = −b/2` after a move in
//! +X, `+b/2` after a move in −X. The offset persists while the axis rests and changes by
//! `b` across a reversal, during which the slide stands still (the tracker's play
//! operator, `state.rs`). A negative `b` is an over-compensating control.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::toolpath::Xz;

use super::backlash_share as share;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BacklashX {
    /// Total play, mm (radius for X).
    pub b: f64,
}

/// Plausible `b`: within ±1 mm. Drives have micrometres to tenths of a millimetre of
/// play; a negative `b` is an over-compensating control.
pub const B: Range = Range::magnitude(1.0, "mm");

impl BacklashX {
    /// The parameters against their plausible ranges (checked when a model file is read).
    pub fn check(&self) -> Result<(), Invalid> {
        B.check_key("b", self.b)
    }

    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(share(self.b, s.play.x, s.backlash.x, s.direction.x), 0.0)
    }
}
