//! `tool_offset_x {dx}`, `tool_offset_z {dz}`: the tool sits `dx` (mm, radius) or `dz`
//! (mm) off its setting along the named axis, everywhere: a tool setting error (or, in Z,
//! a datum error). In X its signature is the same size error on every diameter; in Z it
//! shifts every face by the same amount.

use std::fmt;
use std::marker::PhantomData;

use serde::de::{self, DeserializeSeed, MapAccess, Visitor};
use serde::ser::SerializeStruct;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::error_model::control::TablePart;
use crate::error_model::fitting::{Extents, Fit, MAX_LINEAR, MICRON, Search, beyond};
use crate::error_model::spacing::{ArcTerms, Spacing};
use crate::toolpath::Xz;

use super::ParametricEffect;
use super::axis::{Axis, X, Z};

/// The offset's one parameter is named for its axis (`dx`, `dz`: `Axis::OFFSET_KEY`), so
/// it is read and written by hand below, as serde's derive would with
/// `deny_unknown_fields`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToolOffset<A: Axis> {
    /// The offset, mm (radius for X).
    pub d: f64,
    /// The axis it shifts the tool along.
    pub axis: A,
}

/// `tool_offset_x`.
pub type ToolOffsetX = ToolOffset<X>;
/// `tool_offset_z`.
pub type ToolOffsetZ = ToolOffset<Z>;

/// Plausible offsets: within ±10 mm. A tool set further off than that is a wrong offset
/// number or a crash, not an error a model compensates.
pub const D: Range = Range::magnitude(10.0, "mm");

impl<A: Axis> ToolOffset<A> {
    /// The parameter's name in a model file.
    fn key() -> &'static str {
        A::OFFSET_KEY[0]
    }
}

impl<A: Axis> ParametricEffect for ToolOffset<A> {
    fn check(&self) -> Result<(), Invalid> {
        D.check_key(Self::key(), self.d)
    }

    fn displacement(&self, _s: &Sample) -> Xz {
        A::along(self.d)
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
        // Constant: one sample at each end of a move follows it.
        Spacing::ANY
    }

    fn arc_terms(&self, _reach: Xz) -> ArcTerms {
        // Constant: nothing turns with the arc.
        ArcTerms::default()
    }

    const FIT: Fit = Fit::linear(A::OFFSET_KEY, Search::None);

    fn probe(_extents: &Extents) -> f64 {
        MICRON
    }

    fn fitted(linear: [f64; MAX_LINEAR], _searched: f64) -> Self {
        ToolOffset { d: linear[0], axis: A::default() }
    }

    fn control_table(&self) -> TablePart {
        TablePart::Program("a constant of the tool, which its offset holds, not an axis table")
    }

    fn out_of_bounds(&self, _extents: &Extents) -> Option<String> {
        let name = format!("{} (mm)", Self::key());
        beyond(self.d, 0.5, &name)
    }
}

impl<A: Axis> Serialize for ToolOffset<A> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut table = serializer.serialize_struct("ToolOffset", 1)?;
        table.serialize_field(Self::key(), &self.d)?;
        table.end()
    }
}

impl<'de, A: Axis> Deserialize<'de> for ToolOffset<A> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_struct("ToolOffset", A::OFFSET_KEY, Table(PhantomData))
    }
}

/// The table of a tool offset: its one key, once.
struct Table<A>(PhantomData<A>);

impl<'de, A: Axis> Visitor<'de> for Table<A> {
    type Value = ToolOffset<A>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "struct ToolOffset with `{}`", ToolOffset::<A>::key())
    }

    fn visit_map<M: MapAccess<'de>>(self, mut map: M) -> Result<Self::Value, M::Error> {
        let mut d = None;
        // The key is checked as it is read (`Key`), so that an error about it is the key's.
        while map.next_key_seed(Key::<A>(PhantomData))?.is_some() {
            if d.is_some() {
                return Err(de::Error::duplicate_field(ToolOffset::<A>::key()));
            }
            d = Some(map.next_value::<f64>()?);
        }
        let d = d.ok_or_else(|| de::Error::missing_field(ToolOffset::<A>::key()))?;
        Ok(ToolOffset { d, axis: A::default() })
    }
}

/// A key of the table: only the axis' offset key reads.
struct Key<A>(PhantomData<A>);

impl<'de, A: Axis> DeserializeSeed<'de> for Key<A> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<(), D::Error> {
        deserializer.deserialize_identifier(self)
    }
}

impl<'de, A: Axis> Visitor<'de> for Key<A> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("field identifier")
    }

    fn visit_str<E: de::Error>(self, key: &str) -> Result<(), E> {
        if key == ToolOffset::<A>::key() { Ok(()) } else { Err(E::unknown_field(key, A::OFFSET_KEY)) }
    }
}
