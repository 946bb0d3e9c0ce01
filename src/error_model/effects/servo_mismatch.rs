//! `servo_mismatch {dt_ms}`: the X loop lags the Z loop by `dt_ms` milliseconds, so X
//! trails its command by its velocity times the lag: `dx = −vx · dt` (vx in mm/min). On a
//! ball bar it is a 45° oval that flips with the direction and grows with the feed.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::control::TablePart;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR, MICRON, Search, beyond};
use crate::error_model::spacing::{ArcTerms, Spacing};
use crate::toolpath::Xz;

use super::ParametricEffect;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ServoMismatch {
    /// Lag of X behind Z, milliseconds.
    pub dt_ms: f64,
}

/// Plausible `dt_ms`: within ±1,000 ms. Loop lags are milliseconds; a second is no
/// servo loop a lathe cuts with.
pub const DT_MS: Range = Range::magnitude(1_000.0, "ms");

impl ParametricEffect for ServoMismatch {
    fn check(&self) -> Result<(), Invalid> {
        DT_MS.check_key("dt_ms", self.dt_ms)
    }

    fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(-s.velocity.x / 60_000.0 * self.dt_ms, 0.0)
    }

    fn play(&self) -> Xz {
        Xz::new(0.0, 0.0)
    }

    const OF_TIME: bool = false;

    fn at_time(&self, _t_min: f64) -> Option<Xz> {
        None
    }

    const WEARS: bool = false;

    fn spacing(&self, _allowance: f64, _reach: Xz) -> Spacing {
        // Constant at a line's constant velocity.
        Spacing::ANY
    }

    fn arc_terms(&self, _reach: Xz) -> ArcTerms {
        // The lag turns with the velocity.
        ArcTerms { lag_min: self.dt_ms.abs() / 60_000.0, ..ArcTerms::default() }
    }

    const FIT: Fit = Fit::linear(&["dt_ms"], Search::None);

    fn probe(extents: &Extents) -> f64 {
        MICRON / extents.speed * 60_000.0
    }

    fn fitted(linear: [f64; MAX_LINEAR], _searched: f64) -> Self {
        ServoMismatch { dt_ms: linear[0] }
    }

    fn control_table(&self) -> TablePart {
        TablePart::Program("a function of the velocity")
    }

    fn out_of_bounds(&self, _extents: &Extents) -> Option<String> {
        beyond(self.dt_ms, 50.0, "dt (ms)")
    }
}
