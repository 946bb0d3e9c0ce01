//! `backlash_z {b}`: lost motion (play) `b` in the Z drive: the slide lags its command by
//! half the play against the direction it was last pushed in, `dz = ∓b/2`; see
//! `backlash_x.rs`.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR, MICRON, Search};
use crate::error_model::spacing::{ArcTerms, Spacing};
use crate::toolpath::Xz;

use super::{ParametricEffect, backlash_share as share};

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BacklashZ {
    /// Total play, mm (radius for X).
    pub b: f64,
}

/// Plausible `b`: within ±1 mm. Drives have micrometres to tenths of a millimetre of
/// play; a negative `b` is an over-compensating control.
pub const B: Range = Range::magnitude(1.0, "mm");

impl ParametricEffect for BacklashZ {
    fn check(&self) -> Result<(), Invalid> {
        B.check_key("b", self.b)
    }

    fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(0.0, share(self.b, s.play.z, s.backlash.z, s.direction.z))
    }

    fn play(&self) -> Xz {
        if self.b > 0.0 { Xz::new(0.0, self.b) } else { Xz::new(0.0, 0.0) }
    }

    const OF_TIME: bool = false;

    fn at_time(&self, _t_min: f64) -> Option<Xz> {
        None
    }

    const WEARS: bool = false;

    fn spacing(&self, _allowance: f64, _reach: Xz) -> Spacing {
        // It changes only where the axis reverses: at a line's ends, and at the samples
        // `sampling.rs` puts at an arc's extremes.
        Spacing::ANY
    }

    fn arc_terms(&self, _reach: Xz) -> ArcTerms {
        // A step where the axis reverses, sampled there: nothing turns with the arc.
        ArcTerms::default()
    }

    const FIT: Fit = Fit { linear: &["b"], search: Search::None, secant: true };

    fn probe(_extents: &Extents) -> f64 {
        2.0 * MICRON
    }

    fn fitted(linear: [f64; MAX_LINEAR], _searched: f64) -> Self {
        BacklashZ { b: linear[0] }
    }

    fn out_of_bounds(&self, _extents: &Extents) -> Option<String> {
        // A negative play is an over-compensating control: possible, but small.
        let b = self.b;
        (!b.is_finite() || !(-0.02..=0.2).contains(&b)).then(|| format!("b {b:.4} mm outside −0.02…0.2"))
    }
}
