//! The two dialects and the machine settings that change how a program reads.
//!
//! Dialect facts are data: `grammar/osp.toml` and `grammar/fanuc.toml` hold the code tables,
//! address rules, keywords and cycle word schemas; [`tables`] compiles them once into lookup
//! structures the parser and the semantic pass share.

pub(crate) mod address;
pub mod detect;
pub(crate) mod roles;
pub(crate) mod tables;

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

pub use roles::IntegerUnit;
pub use tables::{
    Address, AddressKind, Code, DrillPeck, DrillRetract, DrillingFacts, FeedAndSpeed, Form, GFunction, GInfo, GKind,
    KeywordInfo, KeywordKind, ModalGroup, Role, Schema, SchemaId, Tables,
};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Dialect {
    /// Okuma OSP lathe (OSP-P200L / P300L, OSP7000L).
    Osp,
    /// Fanuc-compatible lathe form (Fanuc, Haas, Okuma-Howa on Fanuc controls).
    Fanuc,
}

impl Dialect {
    pub fn name(self) -> &'static str {
        match self {
            Dialect::Osp => "Okuma OSP",
            Dialect::Fanuc => "Fanuc",
        }
    }

    pub fn cli_name(self) -> &'static str {
        match self {
            Dialect::Osp => "osp",
            Dialect::Fanuc => "fanuc",
        }
    }
}

impl fmt::Display for Dialect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The dialect to read a program in, or `Auto` to decide from the text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DialectChoice {
    Auto,
    Fixed(Dialect),
}

impl FromStr for DialectChoice {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "auto" => Ok(DialectChoice::Auto),
            "osp" | "okuma" => Ok(DialectChoice::Fixed(Dialect::Osp)),
            "fanuc" => Ok(DialectChoice::Fixed(Dialect::Fanuc)),
            other => Err(format!("unknown dialect `{other}` (expected auto, osp or fanuc)")),
        }
    }
}

/// Fanuc lathe G-code system. A is the lathe default; B and C use G92 for the spindle clamp
/// and G90/G91 for absolute/incremental, and C renumbers the multiple repetitive cycles.
/// It is a machine setting, never guessed from the text.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum GCodeSystem {
    #[default]
    A,
    B,
    C,
}

impl FromStr for GCodeSystem {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "A" | "a" => Ok(GCodeSystem::A),
            "B" | "b" => Ok(GCodeSystem::B),
            "C" | "c" => Ok(GCodeSystem::C),
            other => Err(format!("unknown G-code system `{other}` (expected A, B or C)")),
        }
    }
}

/// The Fanuc-compatible control a Fanuc-form program runs on, where controls differ in
/// what a program may say (`[control.*]` and the `control` lists of `grammar/fanuc.toml`):
/// Haas lathes drill with `G81`-`G89` of their own; Haas and Denford read lower-case
/// letters. A machine setting, never guessed from the text; OSP programs ignore it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Control {
    #[default]
    Fanuc,
    Haas,
    Denford,
}

impl Control {
    pub const ALL: [Control; 3] = [Control::Fanuc, Control::Haas, Control::Denford];

    pub fn name(self) -> &'static str {
        match self {
            Control::Fanuc => "fanuc",
            Control::Haas => "haas",
            Control::Denford => "denford",
        }
    }
}

impl FromStr for Control {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Control::ALL
            .into_iter()
            .find(|c| c.name() == s.to_ascii_lowercase())
            .ok_or_else(|| format!("unknown control `{s}` (expected fanuc, haas or denford)"))
    }
}

/// What an OSP program was written for. Machining-centre programs share the lexical rules
/// but not the lathe cycles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MachineKind {
    Lathe,
    MachiningCentre,
}

/// How numbers without a decimal point are read: on a calculator-type control `X105` is
/// 105 mm; on a least-increment control it is 105 increments (0.105 mm at 0.001 mm).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum DecimalInput {
    #[default]
    Calculator,
    Increment,
}

/// Everything the parser needs to know to read a program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DialectConfig {
    pub dialect: Dialect,
    pub gcode_system: GCodeSystem,
    pub machine_kind: MachineKind,
    /// The Fanuc-compatible control (always `Fanuc` for an OSP program).
    pub control: Control,
}

impl DialectConfig {
    pub fn new(dialect: Dialect, gcode_system: GCodeSystem, machine_kind: MachineKind) -> DialectConfig {
        DialectConfig { dialect, gcode_system, machine_kind, control: Control::Fanuc }
    }

    /// The configuration on `control` (a Fanuc-form program's; OSP ignores it).
    pub fn with_control(self, control: Control) -> DialectConfig {
        let control = if self.dialect == Dialect::Fanuc { control } else { Control::Fanuc };
        DialectConfig { control, ..self }
    }

    pub fn tables(&self) -> &'static Tables {
        tables::tables(*self)
    }
}
