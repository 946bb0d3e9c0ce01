//! `straightness_x {coeffs}`, `straightness_z {coeffs}`: the other slide does not run
//! straight; moving along it carries the tool off along the named axis by a bow. For
//! `straightness_x` the Z slide bows in X, `dx = Σ coeffs[k] · z^(k+2)`; for
//! `straightness_z` the X slide bows in Z, `dz = Σ coeffs[k] · x^(k+2)`. The polynomial
//! starts at the square: a constant is the tool offset along the axis and a slope is the
//! squareness of the slides, other effects.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Key, Range, Reason};
use crate::error_model::Sample;
use crate::error_model::control::TablePart;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR, MICRON, Search, beyond};
use crate::error_model::spacing::{ArcTerms, Spacing, step_for_curvature};
use crate::toolpath::Xz;

use super::axis::{Axis, X, Z};
use super::{ParametricEffect, bow, bow_curvature, bow_slope};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Straightness<A: Axis> {
    /// Coefficients of the square, cube, … of the position, mm^(1−k).
    pub coeffs: Vec<f64>,
    /// The axis the bow carries the tool along (the bow is a function of the other's
    /// position).
    #[serde(skip)]
    pub axis: A,
}

/// `straightness_x`.
pub type StraightnessX = Straightness<X>;
/// `straightness_z`.
pub type StraightnessZ = Straightness<Z>;

/// Plausible coefficients: at most six (a bow up to the seventh power of the position),
/// each within `coefficient_range`.
pub const TERMS: usize = 6;

/// The plausible range of `coeffs[k]`: a term that bends the path by at most 1 mm at
/// 100 mm from the origin, `|coeffs[k]| · 100^(k+2) ≤ 1` (slides bow by micrometres over
/// their travel).
pub fn coefficient_range(k: usize) -> Range {
    Range::magnitude(100f64.powi(-(k as i32 + 2)), "")
}

impl<A: Axis> ParametricEffect for Straightness<A> {
    fn check(&self) -> Result<(), Invalid> {
        if self.coeffs.len() > TERMS {
            return Err(Invalid { path: vec![Key::Name("coeffs")], reason: Reason::Rule("at most six coefficients") });
        }
        for (k, &c) in self.coeffs.iter().enumerate() {
            coefficient_range(k).check(c).map_err(|e| Invalid {
                path: vec![Key::Name("coeffs"), Key::Index(k)],
                reason: Reason::OutOfRange(e),
            })?;
        }
        Ok(())
    }

    fn displacement(&self, s: &Sample) -> Xz {
        A::along(bow(&self.coeffs, <A::Other as Axis>::of(s.at)))
    }

    fn play(&self) -> Xz {
        Xz::new(0.0, 0.0)
    }

    const OF_TIME: bool = false;

    fn at_time(&self, _t_min: f64) -> Option<Xz> {
        None
    }

    const WEARS: bool = false;

    fn spacing(&self, allowance: f64, reach: Xz) -> Spacing {
        // The bow's second derivative, `Σ |coeffs[k]|·(k+2)(k+1)·|p|^k` with p the other
        // axis' position, is largest at the farthest the program reaches along that axis
        // (`reach`, mm, X a radius).
        Spacing::mm(step_for_curvature(bow_curvature(&self.coeffs, <A::Other as Axis>::of(reach)), allowance))
    }

    fn arc_terms(&self, reach: Xz) -> ArcTerms {
        ArcTerms::gradient(bow_slope(&self.coeffs, <A::Other as Axis>::of(reach)))
    }

    const FIT: Fit = Fit::linear(&["coeffs[0]"], Search::None);

    fn probe(extents: &Extents) -> f64 {
        let along = <A::Other as Axis>::extent(extents);
        MICRON / (along * along)
    }

    fn fitted(linear: [f64; MAX_LINEAR], _searched: f64) -> Self {
        Straightness { coeffs: vec![linear[0]], axis: A::default() }
    }

    fn control_table(&self) -> TablePart {
        // A function of the other slide's position.
        TablePart::CrossAxis(A::SLIDE)
    }

    fn out_of_bounds(&self, extents: &Extents) -> Option<String> {
        // A bow of at most 0.1 mm over the measured reach.
        let along = <A::Other as Axis>::extent(extents);
        beyond(self.coeffs.first().copied().unwrap_or(0.0) * along * along, 0.1, "bow (mm)")
    }
}
