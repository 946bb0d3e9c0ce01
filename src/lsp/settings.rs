//! How the server reads a program: dialect, G-code system and machine settings.
//!
//! As on the command line: the `[machine]` table of the nearest `turnpass.toml` above the
//! program (or of the `model` file the client names), and options the client gives at
//! initialisation override it as command-line flags would. The client may also give a
//! `machine` table, used when no file is found. Reading files is the server's I/O layer's
//! job; this module only decides from text and values.

use serde::Deserialize;

use crate::dialect::{DecimalInput, DialectChoice, GCodeSystem};
use crate::machine::{MachineSettings, ModelFile, StockSettings};
use crate::printer::CanonicalOptions;
use crate::syntax::ParseOptions;

/// `initializationOptions`, all optional:
///
/// ```json
/// { "dialect": "osp", "gcodeSystem": "B", "decimalInput": "increment",
///   "model": "/path/to/machine.toml", "machine": { "units": "mm" },
///   "semanticInlineLimit": 262144, "maxDiagnostics": 200 }
/// ```
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct InitOptions {
    /// `auto`, `osp` or `fanuc`.
    pub dialect: Option<String>,
    /// `A`, `B` or `C`.
    pub gcode_system: Option<String>,
    /// `calculator` or `increment`.
    pub decimal_input: Option<String>,
    /// A model file to read instead of looking for `turnpass.toml`.
    pub model: Option<String>,
    /// Machine settings for programs with no `turnpass.toml` above them.
    pub machine: Option<MachineSettings>,
    /// Programs up to this many bytes get their semantic diagnostics in the same publish as
    /// their parse diagnostics; larger ones get them from a worker thread, later.
    pub semantic_inline_limit: Option<usize>,
    /// How many diagnostics a publish holds at most, the rest summed up in a note; 0 is no
    /// limit.
    pub max_diagnostics: Option<usize>,
}

/// Everything a document is read and checked with.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    pub parse: ParseOptions,
    pub machine: MachineSettings,
    /// The model file's `[stock]`, for the part model.
    pub stock: Option<StockSettings>,
    pub canonical: CanonicalOptions,
}

impl InitOptions {
    /// Read the client's options; the message says what is wrong with them. No options may
    /// come as `null`, `{}` or `[]` (clients whose configuration language has no empty map
    /// send an empty list).
    pub fn from_json(value: Option<serde_json::Value>) -> Result<InitOptions, String> {
        match value {
            None | Some(serde_json::Value::Null) => Ok(InitOptions::default()),
            Some(serde_json::Value::Array(list)) if list.is_empty() => Ok(InitOptions::default()),
            Some(value) => serde_json::from_value(value).map_err(|e| format!("initializationOptions: {e}")),
        }
    }

    /// The options in `workspace/didChangeConfiguration`'s settings: under `turnpass` (as
    /// VS Code sends a section), or the settings themselves; `None` when they hold none.
    pub fn from_settings(settings: &serde_json::Value) -> Option<Result<InitOptions, String>> {
        let options = settings.get("turnpass").unwrap_or(settings);
        match options {
            serde_json::Value::Object(map) if !map.is_empty() => {
                Some(serde_json::from_value(options.clone()).map_err(|e| format!("settings: {e}")))
            }
            _ => None,
        }
    }

    /// The settings for a program, from the text of its model file (`turnpass.toml`) if
    /// one was found. Problems (a file that does not read, an unknown dialect name) leave
    /// the defaults in place and are returned as messages for the user.
    pub fn settings(&self, model_file: Option<&str>) -> (Settings, Vec<String>) {
        let mut problems = Vec::new();
        let mut stock = None;
        let from_file = model_file.and_then(|text| match ModelFile::from_toml(text) {
            Ok(file) => {
                stock = file.stock;
                Some(file.machine)
            }
            Err(error) => {
                problems.push(format!("machine settings: {error}"));
                None
            }
        });
        let settings = from_file.or_else(|| self.machine.clone()).unwrap_or_default();
        // Values in either case: editors' settings are written by hand (`"OSP"`, `"b"`).
        let dialect = self
            .dialect
            .as_deref()
            .and_then(|d| d.to_ascii_lowercase().parse::<DialectChoice>().map_err(|e| problems.push(e)).ok());
        let gcode_system = self
            .gcode_system
            .as_deref()
            .and_then(|s| s.to_ascii_uppercase().parse::<GCodeSystem>().map_err(|e| problems.push(e)).ok());
        let decimal = self.decimal_input.as_deref().and_then(|d| {
            serde_json::from_value::<DecimalInput>(serde_json::Value::String(d.to_ascii_lowercase()))
                .map_err(|_| problems.push(format!("unknown decimal input `{d}` (expected calculator or increment)")))
                .ok()
        });
        let dialect = dialect.or(settings.dialect.map(DialectChoice::Fixed)).unwrap_or(DialectChoice::Auto);
        let gcode_system = gcode_system.or(settings.gcode_system).unwrap_or_default();
        let control = settings.control.unwrap_or_default();
        // Kept unset when neither gives it: the semantic pass says where that matters.
        let given_decimal_input = decimal.or(settings.decimal_input);
        let decimal_input = given_decimal_input.unwrap_or_default();
        // The settings in force, the client's options included.
        let machine = MachineSettings {
            dialect: match dialect {
                DialectChoice::Fixed(dialect) => Some(dialect),
                DialectChoice::Auto => None,
            },
            gcode_system: Some(gcode_system),
            control: Some(control),
            decimal_input: given_decimal_input,
            ..settings
        };
        let canonical = CanonicalOptions { decimal_input, increment_places: machine.increment_places() };
        let parse = ParseOptions { dialect, gcode_system, machine_kind: None, control };
        (Settings { parse, machine, stock, canonical }, problems)
    }
}
