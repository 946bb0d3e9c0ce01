//! The axis an effect of one axis acts on. A cause that acts on either slide (a backlash, a
//! scale error, a screw's cyclic error, …) is one implementation over its axis,
//! `Backlash<A: Axis>`; `backlash_x` and `backlash_z` in a model file are that cause on
//! [`X`] and on [`Z`]. The axis is a type, not a value: each effect of the `effects!` list
//! stays one type with its own facts (a fit's searched pitch is that of its own screw), and
//! the code of an effect is the same for both axes.

use std::fmt::Debug;

use crate::error_model::fitting::{Extents, Search};
use crate::error_model::model_file::Axis as Slide;
use crate::error_model::state::Signs;
use crate::toolpath::Xz;

/// One of the lathe's two slides, as a type.
pub trait Axis: Copy + Default + PartialEq + Debug + Send + Sync + 'static {
    /// The axis the other slide moves along (straightness: the bow of this axis along the
    /// other's travel).
    type Other: Axis;

    /// The axis' letter as the model file writes it in an effect's name.
    const LETTER: char;

    /// The slide, as a value (`model_file::Axis`).
    const SLIDE: Slide;

    /// The searched parameter of a cyclic error of this axis' screw (`diagnose`).
    const PITCH: Search;

    /// The name of a tool offset's parameter along this axis (`dx`, `dz`), alone in a
    /// list as the field names of a table are given to serde.
    const OFFSET_KEY: &'static [&'static str];

    /// This axis' coordinate of `p`.
    fn of(p: Xz) -> f64;

    /// This axis' direction in `signs`.
    fn sign(signs: Signs) -> i8;

    /// A displacement of `amount` along this axis.
    fn along(amount: f64) -> Xz;

    /// How far a measurement reaches along this axis (`Extents`).
    fn extent(extents: &Extents) -> f64;
}

/// The X slide (radius, across the spindle axis).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct X;

/// The Z slide (along the spindle axis).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct Z;

impl Axis for X {
    type Other = Z;
    const LETTER: char = 'x';
    const SLIDE: Slide = Slide::X;
    const PITCH: Search = Search::PitchX;
    const OFFSET_KEY: &'static [&'static str] = &["dx"];

    #[inline(always)]
    fn of(p: Xz) -> f64 {
        p.x
    }

    #[inline(always)]
    fn sign(signs: Signs) -> i8 {
        signs.x
    }

    #[inline(always)]
    fn along(amount: f64) -> Xz {
        Xz::new(amount, 0.0)
    }

    fn extent(extents: &Extents) -> f64 {
        extents.x
    }
}

impl Axis for Z {
    type Other = X;
    const LETTER: char = 'z';
    const SLIDE: Slide = Slide::Z;
    const PITCH: Search = Search::PitchZ;
    const OFFSET_KEY: &'static [&'static str] = &["dz"];

    #[inline(always)]
    fn of(p: Xz) -> f64 {
        p.z
    }

    #[inline(always)]
    fn sign(signs: Signs) -> i8 {
        signs.z
    }

    #[inline(always)]
    fn along(amount: f64) -> Xz {
        Xz::new(0.0, amount)
    }

    fn extent(extents: &Extents) -> f64 {
        extents.z
    }
}
