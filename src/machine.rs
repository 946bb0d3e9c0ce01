//! Machine settings: the `[machine]` table of a machine model file.
//!
//! The G-code system and the decimal-point rule are properties of the machine, never
//! guessed from a program, so they come from here (or from the command line).
//! This module parses text; finding and reading the file is the binary's job.

use serde::Deserialize;

use crate::dialect::{DecimalInput, Dialect, GCodeSystem};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    Mm,
    Inch,
}

/// The `[machine]` table. Every field is optional; the caller supplies what is missing from
/// the command line or the documented defaults.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MachineSettings {
    pub name: Option<String>,
    pub dialect: Option<Dialect>,
    pub gcode_system: Option<GCodeSystem>,
    pub decimal_input: Option<DecimalInput>,
    /// Units of a program that does not select them.
    pub units: Option<Units>,
    pub diameter_programming: Option<bool>,
    /// Least input increment in the machine's units (0.001 mm, 0.0001 in).
    pub least_increment: Option<f64>,
    /// The reference position `G28` returns to, in the machine's units with X as the
    /// machine programs it (a diameter on diameter-programmed lathes).
    pub home: Option<AxisPair>,
    /// Travel limits of the tool reference point, same convention as `home`.
    pub travel: Option<Travel>,
    /// Rapid traverse rate of each axis, machine units per minute.
    pub rapid_rate: Option<AxisPair>,
    /// The spindle's top speed, rpm; constant surface speed never exceeds it.
    pub max_spindle_rpm: Option<f64>,
    /// The block-delete switch: `true` skips blocks that start with `/`.
    pub block_delete: Option<bool>,
    /// The lead of each axis' ball screw, mm (a property of the screw, so in millimetres
    /// whatever the machine's units): the period of its cyclic error (`diagnose`).
    pub ball_screw_pitch_mm: Option<ScrewPitch>,
    /// The tool table.
    #[serde(default)]
    pub tool: Vec<ToolSettings>,
}

/// An X and a Z value.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisPair {
    pub x: f64,
    pub z: f64,
}

/// The ball-screw lead of each axis, mm; either may be unknown.
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScrewPitch {
    pub x: Option<f64>,
    pub z: Option<f64>,
}

#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Travel {
    pub x_min: f64,
    pub x_max: f64,
    pub z_min: f64,
    pub z_max: f64,
}

/// One tool of the table: `[[machine.tool]]`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolSettings {
    /// Turret station (`T04xx` selects station 4).
    pub station: u32,
    /// Offset number; the station's number when absent (`T0404`).
    pub offset: Option<u32>,
    /// Geometry offset, machine units, X as programmed.
    #[serde(default)]
    pub x: f64,
    #[serde(default)]
    pub z: f64,
    /// Nose radius, machine units.
    #[serde(default)]
    pub nose_radius: f64,
    /// Imaginary tip direction 0-9 (3 for an outside turning tool cutting toward the chuck).
    #[serde(default)]
    pub tip: u8,
    /// Minor cutting edge angle, degrees, for the roughness estimate (eq. 9.1 of the thesis).
    pub minor_edge_angle: Option<f64>,
}

/// A machine model file. Only `[machine]` is read here; the error-model tables that later
/// passes add are left to them.
#[derive(Debug, Clone, Default, Deserialize)]
pub struct ModelFile {
    #[serde(default)]
    pub machine: MachineSettings,
}

#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct SettingsError(String);

impl ModelFile {
    pub fn from_toml(text: &str) -> Result<ModelFile, SettingsError> {
        toml::from_str(text).map_err(|e| SettingsError(e.to_string()))
    }
}

impl MachineSettings {
    /// Decimal places of the least increment: 3 for 0.001, 4 for 0.0001.
    pub fn increment_places(&self) -> u8 {
        let increment = self.least_increment.unwrap_or(match self.units {
            Some(Units::Inch) => 0.0001,
            _ => 0.001,
        });
        increment_places(increment)
    }
}

/// The decimal places of a least increment in program units (3 for 0.001): how many times
/// it is scaled by ten before it is whole (at most nine).
pub fn increment_places(increment: f64) -> u8 {
    let mut places = 0u8;
    let mut scaled = increment;
    while places < 9 && (scaled - scaled.round()).abs() > 1e-9 {
        scaled *= 10.0;
        places += 1;
    }
    places
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn machine_table_reads_and_rejects_typos() {
        let file =
            ModelFile::from_toml("[machine]\ndialect = \"fanuc\"\ngcode_system = \"B\"\nleast_increment = 0.0001\n")
                .unwrap();
        assert_eq!(file.machine.gcode_system, Some(GCodeSystem::B));
        assert_eq!(file.machine.increment_places(), 4);
        assert!(ModelFile::from_toml("[machine]\ngcode_sytem = \"B\"\n").is_err());
    }
}
