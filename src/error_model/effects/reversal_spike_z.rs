//! `reversal_spike_z {h, decay_mm}`: after Z reverses, `dz = h · d · e^(−s/decay)` with d
//! the new direction of Z and s the Z travel since the reversal.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::spacing::{Spacing, step_for_curvature};
use crate::toolpath::Xz;

use super::spike;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReversalSpikeZ {
    /// Height at the reversal, mm.
    pub h: f64,
    /// Travel over which it falls by e, mm.
    pub decay_mm: f64,
}

/// Plausible `h`: within ±1 mm (friction spikes are micrometres).
pub const H: Range = Range::magnitude(1.0, "mm");
/// Plausible `decay_mm`: from 0.001 to 1,000 mm of travel; the sampling step follows
/// `h/decay²`, so the decay must be more than nothing.
pub const DECAY_MM: Range = Range::closed(0.001, 1_000.0, "mm");

impl ReversalSpikeZ {
    /// The parameters against their plausible ranges (checked when a model file is read).
    pub fn check(&self) -> Result<(), Invalid> {
        H.check_key("h", self.h)?;
        DECAY_MM.check_key("decay_mm", self.decay_mm)
    }

    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(0.0, spike(self.h, self.decay_mm, s.direction.z, s.since_reversal.z))
    }

    /// The spike's decay bends most at the reversal: `h/decay²` per mm² of travel.
    pub fn spacing(&self, allowance: f64) -> Spacing {
        Spacing::mm(step_for_curvature(self.h / (self.decay_mm * self.decay_mm), allowance))
    }
}
