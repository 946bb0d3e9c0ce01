//! The words in which an effect says how the discrepancy workflow (`crate::diagnose`) fits
//! it: its shape (`Fit`: which parameters enter linearly, which one is searched), and the
//! reach of a measurement (`Extents`) that sizes its probes and its bounds. Each effect's
//! file gives its own (`effects::ParametricEffect`); `diagnose/candidates.rs` turns them
//! into columns.

use crate::error_model::Sample;

/// How one kind of effect is fitted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fit {
    /// The linear parameters' names, at most two (for a cyclic error, its sine and cosine
    /// parts).
    pub linear: &'static [&'static str],
    pub search: Search,
    /// The readings depend on the parameter through the play (backlash): its column is
    /// taken again at the fitted value.
    pub secant: bool,
}

impl Fit {
    /// A fit of `linear` and `search`, whose readings are linear in the linear parameters.
    pub const fn linear(linear: &'static [&'static str], search: Search) -> Fit {
        Fit { linear, search, secant: false }
    }
}

/// The most linear parameters a fit has (`Fit::linear`).
pub const MAX_LINEAR: usize = 2;

/// A parameter that is searched rather than fitted as a column.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Search {
    None,
    /// Thermal time constant, minutes.
    Tau,
    /// Reversal-spike decay length, mm.
    Decay,
    /// Ball-screw pitch, mm, of the X or the Z screw.
    PitchX,
    PitchZ,
}

impl Search {
    /// The searched parameter's name in a model file; `None` for no search.
    pub fn parameter(self) -> Option<&'static str> {
        match self {
            Search::None => None,
            Search::Tau => Some("tau_min"),
            Search::Decay => Some("decay_mm"),
            Search::PitchX | Search::PitchZ => Some("pitch"),
        }
    }
}

/// The reach of a measurement: the largest |x|, |z|, speed and cut length at its points,
/// for sizing probes and bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extents {
    pub x: f64,
    pub z: f64,
    pub speed: f64,
    pub cut_m: f64,
}

impl Extents {
    pub fn of(states: &[Sample]) -> Extents {
        let max = |f: &dyn Fn(&Sample) -> f64| states.iter().map(f).fold(0.0, f64::max);
        Extents {
            x: max(&|s| s.at.x.abs()).max(1.0),
            z: max(&|s| s.at.z.abs()).max(1.0),
            speed: max(&|s| s.velocity.x.hypot(s.velocity.z)).max(1.0),
            cut_m: max(&|s| s.cut_length_m).max(1e-3),
        }
    }
}

/// A micrometre, mm: the displacement a probe aims at.
pub const MICRON: f64 = 1e-3;

/// Why a fitted value is beyond `±limit`, if it is (or is not a finite number): `what`
/// names it with its unit.
pub fn beyond(value: f64, limit: f64, what: &str) -> Option<String> {
    (!value.is_finite() || value.abs() > limit).then(|| format!("{what} {value:.4e} beyond ±{limit}"))
}
