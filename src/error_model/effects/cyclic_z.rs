//! `cyclic_z {amp, pitch, phase}`: the periodic lead error of the Z ball screw,
//! `dz = amp · sin(2πz/pitch + phase)` (the thesis machine's screw has an 11.94 mm pitch).

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::spacing::{Spacing, step_for_curvature};
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CyclicZ {
    /// Amplitude, mm.
    pub amp: f64,
    /// Period, mm of travel (the screw's lead).
    pub pitch: f64,
    /// Phase at zero, radians.
    pub phase: f64,
}

/// Plausible `amp`: within ±1 mm (screws' cyclic errors are micrometres).
pub const AMP: Range = Range::magnitude(1.0, "mm");
/// Plausible `pitch`: from 0.1 to 1,000 mm, the leads of ball screws
/// (and their fractions, for harmonics).
pub const PITCH: Range = Range::closed(0.1, 1_000.0, "mm");
/// Plausible `phase`: within ±100 rad (any angle is a phase; a larger number is a
/// misread value, and its sine loses its precision).
pub const PHASE: Range = Range::magnitude(100.0, "rad");

impl CyclicZ {
    /// The parameters against their plausible ranges (checked when a model file is read).
    pub fn check(&self) -> Result<(), Invalid> {
        AMP.check_key("amp", self.amp)?;
        PITCH.check_key("pitch", self.pitch)?;
        PHASE.check_key("phase", self.phase)
    }

    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(0.0, self.amp * (std::f64::consts::TAU * s.at.z / self.pitch + self.phase).sin())
    }

    /// `amp·sin` curves by at most `amp·(2π/pitch)²` per mm² of travel along the screw,
    /// and a move's travel along it is never longer than the move.
    pub fn spacing(&self, allowance: f64) -> Spacing {
        let wavenumber = std::f64::consts::TAU / self.pitch;
        Spacing::mm(step_for_curvature(self.amp * wavenumber * wavenumber, allowance))
    }
}
