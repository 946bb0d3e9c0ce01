//! `reversal_spike_x {h, decay_mm}`, `reversal_spike_z {h, decay_mm}`: after the named
//! axis reverses, friction holds the slide back for a moment: `h · d · e^(−s/decay)` along
//! it, with d the new direction of the axis and s its travel since the reversal.
//! One-sided, decaying with travel, at the axis' reversal points.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::control::TablePart;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR, MICRON, Search, beyond};
use crate::error_model::spacing::{ArcTerms, Spacing, step_for_curvature};
use crate::toolpath::Xz;

use super::axis::{Axis, X, Z};
use super::{ParametricEffect, spike};

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReversalSpike<A: Axis> {
    /// Height at the reversal, mm.
    pub h: f64,
    /// Travel over which it falls by e, mm.
    pub decay_mm: f64,
    /// The axis that reverses.
    #[serde(skip)]
    pub axis: A,
}

/// `reversal_spike_x`.
pub type ReversalSpikeX = ReversalSpike<X>;
/// `reversal_spike_z`.
pub type ReversalSpikeZ = ReversalSpike<Z>;

/// Plausible `h`: within ±1 mm (friction spikes are micrometres).
pub const H: Range = Range::magnitude(1.0, "mm");
/// Plausible `decay_mm`: from 0.001 to 1,000 mm of travel; the sampling step follows
/// `h/decay²`, so the decay must be more than nothing.
pub const DECAY_MM: Range = Range::closed(0.001, 1_000.0, "mm");

impl<A: Axis> ParametricEffect for ReversalSpike<A> {
    fn check(&self) -> Result<(), Invalid> {
        H.check_key("h", self.h)?;
        DECAY_MM.check_key("decay_mm", self.decay_mm)
    }

    fn displacement(&self, s: &Sample) -> Xz {
        A::along(spike(self.h, self.decay_mm, A::sign(s.direction), A::of(s.since_reversal)))
    }

    fn play(&self) -> Xz {
        Xz::new(0.0, 0.0)
    }

    const OF_TIME: bool = false;

    fn at_time(&self, _t_min: f64) -> Option<Xz> {
        None
    }

    const WEARS: bool = false;

    fn spacing(&self, allowance: f64, _reach: Xz) -> Spacing {
        // The spike's decay bends most at the reversal: `h/decay²` per mm² of travel.
        Spacing::mm(step_for_curvature(self.h / (self.decay_mm * self.decay_mm), allowance))
    }

    fn arc_terms(&self, _reach: Xz) -> ArcTerms {
        // A function of the travel since a reversal, which `spacing` bounds: nothing turns
        // with the arc.
        ArcTerms::default()
    }

    const FIT: Fit = Fit::linear(&["h"], Search::Decay);

    fn probe(_extents: &Extents) -> f64 {
        MICRON
    }

    fn fitted(linear: [f64; MAX_LINEAR], searched: f64) -> Self {
        ReversalSpike { h: linear[0], decay_mm: searched, axis: A::default() }
    }

    fn control_table(&self) -> TablePart {
        TablePart::Program("a function of the travel since the axis reversed")
    }

    fn out_of_bounds(&self, _extents: &Extents) -> Option<String> {
        beyond(self.h, 0.05, "h (mm)")
    }
}
