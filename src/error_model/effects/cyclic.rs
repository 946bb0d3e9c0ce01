//! `cyclic_x {amp, pitch, phase}`, `cyclic_z {amp, pitch, phase}`: the periodic lead error
//! of the named slide's ball screw, `dx = amp · sin(2πx/pitch + phase)` (or `dz` of `z`),
//! locked to the slide position (not to time). The thesis machine's Z screw has an
//! 11.94 mm pitch.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::control::TablePart;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR, MICRON, beyond};
use crate::error_model::spacing::{ArcTerms, Spacing, step_for_curvature};
use crate::toolpath::Xz;

use super::axis::{Axis, X, Z};
use super::{ParametricEffect, amplitude_phase};

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Cyclic<A: Axis> {
    /// Amplitude, mm.
    pub amp: f64,
    /// Period, mm of travel (the screw's lead).
    pub pitch: f64,
    /// Phase at zero, radians.
    pub phase: f64,
    /// The slide whose screw has the error.
    #[serde(skip)]
    pub axis: A,
}

/// `cyclic_x`.
pub type CyclicX = Cyclic<X>;
/// `cyclic_z`.
pub type CyclicZ = Cyclic<Z>;

/// Plausible `amp`: within ±1 mm (screws' cyclic errors are micrometres).
pub const AMP: Range = Range::magnitude(1.0, "mm");
/// Plausible `pitch`: from 0.1 to 1,000 mm, the leads of ball screws
/// (and their fractions, for harmonics).
pub const PITCH: Range = crate::machine::SCREW_PITCH;
/// Plausible `phase`: within ±100 rad (any angle is a phase; a larger number is a
/// misread value, and its sine loses its precision).
pub const PHASE: Range = Range::magnitude(100.0, "rad");

impl<A: Axis> ParametricEffect for Cyclic<A> {
    fn check(&self) -> Result<(), Invalid> {
        AMP.check_key("amp", self.amp)?;
        PITCH.check_key("pitch", self.pitch)?;
        PHASE.check_key("phase", self.phase)
    }

    fn displacement(&self, s: &Sample) -> Xz {
        A::along(self.amp * (std::f64::consts::TAU * A::of(s.at) / self.pitch + self.phase).sin())
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
        // `amp·sin` curves by at most `amp·(2π/pitch)²` per mm² of travel along the screw,
        // and a move's travel along it is never longer than the move.
        let wavenumber = std::f64::consts::TAU / self.pitch;
        Spacing::mm(step_for_curvature(self.amp * wavenumber * wavenumber, allowance))
    }

    fn arc_terms(&self, _reach: Xz) -> ArcTerms {
        ArcTerms::gradient(self.amp * std::f64::consts::TAU / self.pitch)
    }

    const FIT: Fit = Fit::linear(&["sin", "cos"], A::PITCH);

    fn probe(_extents: &Extents) -> f64 {
        MICRON
    }

    fn fitted(linear: [f64; MAX_LINEAR], searched: f64) -> Self {
        let (amp, phase) = amplitude_phase(linear[0], linear[1]);
        Cyclic { amp, pitch: searched, phase, axis: A::default() }
    }

    fn control_table(&self) -> TablePart {
        // A function of the axis' own position alone, as the screw's lead error it is.
        TablePart::Pitch(A::SLIDE)
    }

    fn out_of_bounds(&self, _extents: &Extents) -> Option<String> {
        beyond(self.amp, 0.05, "amp (mm)").or_else(|| beyond(self.pitch, 100.0, "pitch (mm)"))
    }
}
