//! The error-model part of a machine model file (`--model machine.toml`), beside the
//! `[machine]` settings (`crate::machine`):
//!
//! ```toml
//! [model]
//! start_min = 30.0          # minutes since machine start when the program starts
//! abbe_y_mm = 0.0           # tool point's offset along Y from the slides' measuring line
//!
//! [[axis_table]]            # ISO 230-2 style table of one slide (`interferometer.rs`)
//! axis = "x"
//! file = "x-slide.csv"      # relative to the model file; or `csv = """…"""` inline
//!
//! [[effect]]                # parametric effects (`effects/`)
//! kind = "backlash_x"
//! b = 0.004
//! ```
//!
//! Reading a table's file is the caller's job (the library does no I/O): `build` takes a
//! function from the file name to its text.

use serde::Deserialize;

use super::ErrorModel;
use super::effects::Effect;
use super::htm::AxisTables;
use super::interferometer::{self, TableError};

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSpec {
    /// The machine settings, read by `crate::machine`.
    #[serde(default)]
    pub machine: Option<toml::Table>,
    #[serde(default)]
    pub model: ModelSection,
    #[serde(default)]
    pub axis_table: Vec<AxisTableSpec>,
    #[serde(default)]
    pub effect: Vec<Effect>,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSection {
    #[serde(default)]
    pub start_min: f64,
    #[serde(default)]
    pub abbe_y_mm: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisTableSpec {
    pub axis: Axis,
    #[serde(default)]
    pub file: Option<String>,
    #[serde(default)]
    pub csv: Option<String>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    X,
    Z,
}

#[derive(Debug, thiserror::Error)]
pub enum ModelError {
    #[error("{0}")]
    Toml(String),
    #[error("axis table {index} ({axis:?}): give either `file` or `csv`")]
    TableSource { index: usize, axis: Axis },
    #[error("axis table {index} ({axis:?}), {source_name}: {error}")]
    Table { index: usize, axis: Axis, source_name: String, error: TableError },
    #[error("axis table {index} ({axis:?}): cannot read `{file}`: {message}")]
    Read { index: usize, axis: Axis, file: String, message: String },
    #[error("two tables for the {0:?} slide")]
    DuplicateAxis(Axis),
}

impl ModelSpec {
    pub fn from_toml(text: &str) -> Result<ModelSpec, ModelError> {
        toml::from_str(text).map_err(|e| ModelError::Toml(e.to_string()))
    }

    /// The error model, reading each table's `file` through `read`.
    pub fn build(&self, mut read: impl FnMut(&str) -> Result<String, String>) -> Result<ErrorModel, ModelError> {
        let mut tables: Option<AxisTables> = None;
        let mut seen = Vec::new();
        for (index, spec) in self.axis_table.iter().enumerate() {
            if seen.contains(&spec.axis) {
                return Err(ModelError::DuplicateAxis(spec.axis));
            }
            seen.push(spec.axis);
            let (text, source_name) = self.table_text(index, &mut read)?;
            let table = interferometer::parse(&text).map_err(|error| ModelError::Table {
                index,
                axis: spec.axis,
                source_name,
                error,
            })?;
            let all =
                tables.get_or_insert_with(|| AxisTables { abbe_y_mm: self.model.abbe_y_mm, ..Default::default() });
            match spec.axis {
                Axis::X => all.x = table,
                Axis::Z => all.z = table,
            }
        }
        Ok(ErrorModel { tables, effects: self.effect.clone(), start_min: self.model.start_min })
    }

    /// The CSV text of axis table `index` and a name for it (its file, or "inline csv").
    pub fn table_text(
        &self,
        index: usize,
        mut read: impl FnMut(&str) -> Result<String, String>,
    ) -> Result<(String, String), ModelError> {
        let Some(spec) = self.axis_table.get(index) else {
            return Err(ModelError::Toml(format!("no axis table {index}")));
        };
        match (&spec.file, &spec.csv) {
            (Some(file), None) => {
                let text = read(file).map_err(|message| ModelError::Read {
                    index,
                    axis: spec.axis,
                    file: file.clone(),
                    message,
                })?;
                Ok((text, file.clone()))
            }
            (None, Some(csv)) => Ok((csv.clone(), "inline csv".to_string())),
            _ => Err(ModelError::TableSource { index, axis: spec.axis }),
        }
    }
}
