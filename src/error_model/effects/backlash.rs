//! `backlash_x {b}`, `backlash_z {b}`: lost motion (play) `b` in the drive of the named
//! slide. The slide lags its command by half the play, against the direction it was last
//! pushed in: `−b/2` along the axis after a move in +, `+b/2` after a move in −. The offset
//! persists while the axis rests and changes by `b` across a reversal, during which the
//! slide stands still (the tracker's play operator, `state.rs`). A negative `b` is an
//! over-compensating control.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::control::TablePart;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR, MICRON, Search};
use crate::error_model::spacing::{ArcTerms, Spacing};
use crate::toolpath::Xz;

use super::axis::{Axis, X, Z};
use super::{ParametricEffect, backlash_share as share};

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Backlash<A: Axis> {
    /// Total play, mm (radius for X).
    pub b: f64,
    /// The slide whose drive has the play.
    #[serde(skip)]
    pub axis: A,
}

/// `backlash_x`.
pub type BacklashX = Backlash<X>;
/// `backlash_z`.
pub type BacklashZ = Backlash<Z>;

/// Plausible `b`: within ±1 mm. Drives have micrometres to tenths of a millimetre of
/// play; a negative `b` is an over-compensating control.
pub const B: Range = Range::magnitude(1.0, "mm");

impl<A: Axis> ParametricEffect for Backlash<A> {
    fn check(&self) -> Result<(), Invalid> {
        B.check_key("b", self.b)
    }

    fn displacement(&self, s: &Sample) -> Xz {
        A::along(share(self.b, A::of(s.play), A::of(s.backlash), A::sign(s.direction)))
    }

    fn play(&self) -> Xz {
        if self.b > 0.0 { A::along(self.b) } else { Xz::new(0.0, 0.0) }
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
        Backlash { b: linear[0], axis: A::default() }
    }

    fn control_table(&self) -> TablePart {
        TablePart::Backlash(A::SLIDE, self.b)
    }

    fn out_of_bounds(&self, _extents: &Extents) -> Option<String> {
        // A negative play is an over-compensating control: possible, but small.
        let b = self.b;
        (!b.is_finite() || !(-0.02..=0.2).contains(&b)).then(|| format!("b {b:.4} mm outside −0.02…0.2"))
    }
}
