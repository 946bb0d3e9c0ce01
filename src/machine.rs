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
        let mut places = 0u8;
        let mut scaled = increment;
        while places < 9 && (scaled - scaled.round()).abs() > 1e-9 {
            scaled *= 10.0;
            places += 1;
        }
        places
    }
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
