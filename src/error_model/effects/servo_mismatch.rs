//! `servo_mismatch {dt_ms}`: the X loop lags the Z loop by `dt_ms` milliseconds, so X
//! trails its command by its velocity times the lag: `dx = −vx · dt` (vx in mm/min). On a
//! ball bar it is a 45° oval that flips with the direction and grows with the feed.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ServoMismatch {
    /// Lag of X behind Z, milliseconds.
    pub dt_ms: f64,
}

/// Plausible `dt_ms`: within ±1,000 ms. Loop lags are milliseconds; a second is no
/// servo loop a lathe cuts with.
pub const DT_MS: Range = Range::magnitude(1_000.0, "ms");

impl ServoMismatch {
    /// The parameters against their plausible ranges (checked when a model file is read).
    pub fn check(&self) -> Result<(), Invalid> {
        DT_MS.check_key("dt_ms", self.dt_ms)
    }

    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(-s.velocity.x / 60_000.0 * self.dt_ms, 0.0)
    }
}
