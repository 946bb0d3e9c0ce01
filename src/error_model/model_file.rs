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
//! A file that does not read is a list of diagnostics on its text (`crate::toml_spans`),
//! each at the table and key that hold the error: an unknown key or effect with the nearest
//! valid name, a value of the wrong type, a number outside its plausible range (every
//! number is checked when it is read). A table's own problems are diagnostics on the table
//! file (a misspelt column at its header cell) or, for an inline table, on the model file.
//!
//! Reading a table's file is the caller's job (the library does no I/O): `build` takes a
//! function from the file name to its text, or to the reason it cannot be read (which
//! should say the path it tried).

use std::fmt;

use serde::Deserialize;
use toml::Spanned;
use toml::de::DeValue;

use super::ErrorModel;
use super::effects::{self, Effect};
use super::htm::AxisTables;
use super::interferometer::{self, SlideTable};
use crate::bounds::{Invalid, Range};
use crate::diagnostic::{Diagnostic, DiagnosticKind, ModelProblem};
use crate::machine::MachineSettings;
use crate::measurement_file::DataError;
use crate::source::Span;
use crate::toml_spans::{self, Document, Problems, Step};

/// The tables a model file may have at its top level.
pub const TABLES: [&str; 5] = ["machine", "stock", "model", "axis_table", "effect"];

#[derive(Debug, Clone, Default)]
pub struct ModelSpec {
    /// The machine settings (`crate::machine`), read and checked with the rest.
    pub machine: MachineSettings,
    pub model: ModelSection,
    pub axis_table: Vec<AxisTableSpec>,
    pub effect: Vec<Effect>,
    /// Where each effect's `[[effect]]` is in the file.
    pub effect_spans: Vec<Span>,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSection {
    /// Within `START_MIN`.
    #[serde(default)]
    pub start_min: f64,
    /// Within `ABBE_Y_MM`.
    #[serde(default)]
    pub abbe_y_mm: f64,
}

/// Plausible start times, minutes since the machine started: from 0 (a program before the
/// start has no warm-up to read) to 1,000,000 (about two years of running). The
/// command line's `--start-min` and `--parts` take the same range.
pub const START_MIN: Range = Range::closed(0.0, 1_000_000.0, "min");

/// Plausible Abbe offsets of the tool point along Y: within ±1,000 mm.
pub const ABBE_Y_MM: Range = Range::magnitude(1_000.0, "mm");

impl ModelSection {
    /// The values against their plausible ranges.
    pub fn check(&self) -> Vec<Invalid> {
        [START_MIN.check_key("start_min", self.start_min), ABBE_Y_MM.check_key("abbe_y_mm", self.abbe_y_mm)]
            .into_iter()
            .filter_map(Result::err)
            .collect()
    }
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisTableSpec {
    pub axis: Axis,
    /// The table's file, relative to the model file's folder; its span is the value's in
    /// the model file.
    #[serde(default)]
    pub file: Option<Spanned<String>>,
    #[serde(default)]
    pub csv: Option<Spanned<String>>,
    /// Whether the control's pitch-error compensation was on while the table was taken (the
    /// table then holds what that compensation leaves), or off (the slide's whole error);
    /// `None` when the table does not say.
    #[serde(default)]
    pub pitch_error_compensation: Option<Switch>,
    /// Likewise the control's backlash compensation, which decides what the table's
    /// reversal holds.
    #[serde(default)]
    pub backlash_compensation: Option<Switch>,
    /// The `[[axis_table]]` in the model file.
    #[serde(skip)]
    pub span: Span,
    /// Where the text of `csv` starts in the model file, when the string is written
    /// without escapes (so that a place in the table is a place in the file).
    #[serde(skip)]
    pub inline_start: Option<u32>,
}

/// A compensation of the control, on or off.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Switch {
    On,
    Off,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    X,
    Z,
}

impl Axis {
    pub fn letter(self) -> char {
        match self {
            Axis::X => 'X',
            Axis::Z => 'Z',
        }
    }
}

/// A model that does not build: problems in the model file's text, or in a table file it
/// names.
#[derive(Debug, Clone, PartialEq)]
pub enum ModelError {
    /// The file does not read.
    File(Problems),
    /// A problem of the model's tables, on the model file's text.
    Model(Box<Diagnostic>),
    /// A table file that does not read: its name as the model writes it, its text and the
    /// diagnostic on that text.
    TableFile { file: String, text: String, diagnostic: Box<Diagnostic> },
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ModelError::File(problems) => write!(f, "{problems}"),
            ModelError::Model(diagnostic) => f.write_str(&diagnostic.message()),
            ModelError::TableFile { file, text, diagnostic } => {
                write!(f, "{file}: {}", Problems::new(text, vec![(**diagnostic).clone()]))
            }
        }
    }
}

impl std::error::Error for ModelError {}

/// An axis table read from its source.
pub struct ReadTable<'a> {
    pub spec: &'a AxisTableSpec,
    pub table: SlideTable,
    /// Its file's name, or "inline csv".
    pub source_name: String,
    /// Its CSV text.
    pub text: String,
}

impl ModelSpec {
    /// A model file's text read and checked; the error holds every problem found.
    pub fn read(text: &str) -> Result<ModelSpec, Problems> {
        let document = Document::parse(text).map_err(|d| Problems::new(text, vec![d]))?;
        let mut problems = Vec::new();
        for (key, at) in document.top_keys() {
            if !TABLES.contains(&key.as_str()) {
                problems.push(document.unknown_key(&[], &key, at, &TABLES));
            }
        }
        let machine = MachineSettings::read(&document).unwrap_or_else(|found| {
            problems.extend(found);
            MachineSettings::default()
        });
        if let Err(found) = crate::machine::StockSettings::read(&document) {
            problems.extend(found);
        }
        let model_path = [Step::from("model")];
        let model: ModelSection = read_or_note(&document, &model_path, &mut problems).unwrap_or_default();
        problems.extend(model.check().iter().map(|bad| document.invalid(&model_path, bad)));
        let mut axis_table: Vec<AxisTableSpec> =
            read_or_note(&document, &[Step::from("axis_table")], &mut problems).unwrap_or_default();
        for (index, table) in axis_table.iter_mut().enumerate() {
            table.span = document.span_of(&[Step::from("axis_table"), Step::Index(index)]);
            table.inline_start = table.csv.as_ref().and_then(|csv| unescaped_start(text, csv));
        }
        let (effect, effect_spans) = read_effects(&document, &mut problems);
        if problems.is_empty() {
            Ok(ModelSpec { machine, model, axis_table, effect, effect_spans })
        } else {
            problems.sort_by_key(|d| d.span.start);
            Err(Problems::new(text, problems))
        }
    }

    /// [`ModelSpec::read`] with the error as a [`ModelError`].
    pub fn from_toml(text: &str) -> Result<ModelSpec, ModelError> {
        ModelSpec::read(text).map_err(ModelError::File)
    }

    /// The error model, reading each table's `file` through `read`.
    pub fn build(&self, read: impl FnMut(&str) -> Result<String, String>) -> Result<ErrorModel, ModelError> {
        self.build_with_warnings(read).map(|(model, _)| model)
    }

    /// [`ModelSpec::build`], with the warnings of the model: an error it holds twice, in a
    /// table and an effect (`counted_twice`), on the model file's text.
    pub fn build_with_warnings(
        &self,
        read: impl FnMut(&str) -> Result<String, String>,
    ) -> Result<(ErrorModel, Vec<Diagnostic>), ModelError> {
        let read_tables = self.read_tables(read)?;
        let warnings = super::counted_twice::counted_twice(self, &read_tables);
        let mut tables: Option<AxisTables> = None;
        for ReadTable { spec, table, .. } in read_tables {
            let all =
                tables.get_or_insert_with(|| AxisTables { abbe_y_mm: self.model.abbe_y_mm, ..Default::default() });
            match spec.axis {
                Axis::X => all.x = table,
                Axis::Z => all.z = table,
            }
        }
        let model = ErrorModel { tables, effects: self.effect.clone(), start_min: self.model.start_min, control: None };
        Ok((model, warnings))
    }

    /// Every axis table read from its source, in the file's order, each slide once.
    pub fn read_tables(
        &self,
        mut read: impl FnMut(&str) -> Result<String, String>,
    ) -> Result<Vec<ReadTable<'_>>, ModelError> {
        let model_error = |problem: ModelProblem, at: Span| {
            ModelError::Model(Box::new(Diagnostic::error(DiagnosticKind::ModelFile(Box::new(problem)), at)))
        };
        let mut out: Vec<ReadTable<'_>> = Vec::new();
        for spec in &self.axis_table {
            let axis = spec.axis.letter();
            if out.iter().any(|t| t.spec.axis == spec.axis) {
                return Err(model_error(ModelProblem::DuplicateTable { axis }, spec.span));
            }
            let (file, source_name, text) = match (&spec.file, &spec.csv) {
                (Some(file), None) => {
                    let at = toml_spans::span(file.span());
                    let text = read(file.get_ref())
                        .map_err(|reason| model_error(ModelProblem::TableUnreadable { axis, reason }, at))?;
                    let read = interferometer::read_file(&text).map_err(|error| ModelError::TableFile {
                        file: file.get_ref().clone(),
                        diagnostic: Box::new(table_diagnostic(axis, &error, error.span)),
                        text: text.clone(),
                    })?;
                    (read, file.get_ref().clone(), text)
                }
                (None, Some(csv)) => {
                    let read = interferometer::read_file(csv.get_ref()).map_err(|error| {
                        let at = match spec.inline_start {
                            Some(start) => Span::new(start + error.span.start, start + error.span.end),
                            None => toml_spans::span(csv.span()),
                        };
                        ModelError::Model(Box::new(table_diagnostic(axis, &error, at)))
                    })?;
                    (read, "inline csv".to_string(), csv.get_ref().clone())
                }
                _ => return Err(model_error(ModelProblem::TableSource { axis }, spec.span)),
            };
            // A table file that says which slide it measured says it of this one.
            if let Some((said, _, _)) = file.axis
                && said != axis.to_ascii_lowercase()
            {
                let message = format!("the table's preamble says it measured the {} slide", said.to_ascii_uppercase());
                let hint = Some(format!("give it `axis = \"{said}\"`, or the {axis} slide's own table"));
                let problem = ModelProblem::TableInvalid { axis, message, label: "this table", hint };
                return Err(model_error(problem, spec.span));
            }
            let table = file.table;
            out.push(ReadTable { spec, table, source_name, text });
        }
        Ok(out)
    }
}

/// A model inside another TOML document (a test case's inline model) is read as a model file
/// of its own, written out again: the lines its problems name are those of that text.
impl<'de> Deserialize<'de> for ModelSpec {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<ModelSpec, D::Error> {
        let table = toml::Table::deserialize(deserializer)?;
        let text = toml::to_string(&table).map_err(serde::de::Error::custom)?;
        ModelSpec::read(&text).map_err(serde::de::Error::custom)
    }
}

/// `text`, a model file, with the `file` of each axis table replaced by what `rename` gives
/// for it (`None` keeps it); every other byte stays as written.
pub fn with_table_files(text: &str, mut rename: impl FnMut(&str) -> Option<String>) -> Result<String, Problems> {
    let spec = ModelSpec::read(text)?;
    let mut edits: Vec<(std::ops::Range<usize>, String)> = spec
        .axis_table
        .iter()
        .filter_map(|table| table.file.as_ref())
        .filter_map(|file| rename(file.get_ref()).map(|name| (file.span(), toml::Value::String(name).to_string())))
        .collect();
    edits.sort_by_key(|(range, _)| std::cmp::Reverse(range.start));
    let mut out = text.to_string();
    for (range, name) in edits {
        out.replace_range(range, &name);
    }
    Ok(out)
}

/// The value at `path` read as a `T`, or its diagnostic noted in `problems`.
fn read_or_note<T: serde::de::DeserializeOwned>(
    document: &Document<'_>,
    path: &[Step],
    problems: &mut Vec<Diagnostic>,
) -> Option<T> {
    document.read(path).unwrap_or_else(|d| {
        problems.push(d);
        None
    })
}

/// The `[[effect]]` tables, each read by its `kind` so that an error is placed at its own
/// key, and checked against its parameters' ranges.
fn read_effects(document: &Document<'_>, problems: &mut Vec<Diagnostic>) -> (Vec<Effect>, Vec<Span>) {
    let Some(list) = document.get(&[Step::from("effect")]) else { return (Vec::new(), Vec::new()) };
    let DeValue::Array(tables) = list.get_ref() else {
        problems.push(document.wrong_value(&[Step::from("effect")], "write each effect as an [[effect]] table"));
        return (Vec::new(), Vec::new());
    };
    let mut out = Vec::new();
    let mut spans = Vec::new();
    for (index, table) in tables.iter().enumerate() {
        let at = [Step::from("effect"), Step::Index(index)];
        let DeValue::Table(entries) = table.get_ref() else {
            problems.push(document.wrong_value(&at, "write each effect as an [[effect]] table"));
            continue;
        };
        let kind_path = [Step::from("effect"), Step::Index(index), Step::from("kind")];
        let Some(kind) = document.get(&kind_path) else {
            problems.push(document.missing_key(&at, "kind"));
            continue;
        };
        let Some(kind) = kind.get_ref().as_str() else {
            problems.push(document.wrong_value(&kind_path, "the kind is the effect's name, a string"));
            continue;
        };
        if !effects::NAMES.contains(&kind) {
            problems.push(document.unknown_name(&kind_path, kind, &effects::NAMES));
            continue;
        }
        let parameters = entries.iter().filter(|(key, _)| key.get_ref() != "kind").map(|(k, v)| (k.clone(), v.clone()));
        let parameters = Spanned::new(table.span(), DeValue::Table(parameters.collect()));
        let effect = document.read_with(parameters, |d| {
            // Every name of `NAMES` is a kind `deserialize_kind` reads (tested in `effects`).
            Effect::deserialize_kind(kind, d).unwrap_or_else(|| Err(serde::de::Error::custom("unknown kind")))
        });
        match effect {
            Ok(effect) => match effect.check() {
                Ok(()) => {
                    out.push(effect);
                    spans.push(document.span_of(&at));
                }
                Err(bad) => problems.push(document.invalid(&at, &bad)),
            },
            Err(diagnostic) => problems.push(in_other_units(diagnostic)),
        }
    }
    (out, spans)
}

/// An unknown key of an effect whose name says it is in the other system of units (`dx_dia`,
/// `b_inch`, `units`): refused with the rule of units instead of as a misspelling.
fn in_other_units(diagnostic: Diagnostic) -> Diagnostic {
    let DiagnosticKind::ModelFile(problem) = &diagnostic.kind else { return diagnostic };
    let ModelProblem::UnknownKey { key, table, known, .. } = problem.as_ref() else { return diagnostic };
    let Some(said) = crate::machine::names_other_units(key) else { return diagnostic };
    // A unit the effect's own keys name (`tool_wear`'s `um_per_m`) is its unit: a misspelling.
    if known.iter().any(|k| crate::machine::names_other_units(k) == Some(said)) {
        return diagnostic;
    }
    // The key meant: the name without its unit (`dx` of `dx_dia`), if the effect has it.
    let stripped: String =
        key.split('_').filter(|word| crate::machine::names_other_units(word).is_none()).collect::<Vec<_>>().join("_");
    let instead = known.iter().find(|k| **k == stripped).cloned().or_else(|| {
        toml_spans::nearest(&stripped, known.iter().map(String::as_str))
            .filter(|_| !stripped.is_empty())
            .map(str::to_string)
    });
    let problem = ModelProblem::WrongUnits { key: key.clone(), table: table.clone(), said, instead };
    Diagnostic { kind: DiagnosticKind::ModelFile(Box::new(problem)), ..diagnostic }
}

/// The diagnostic of a table that does not read.
fn table_diagnostic(axis: char, error: &DataError, at: Span) -> Diagnostic {
    let problem = match &error.unknown_column {
        Some(column) => ModelProblem::UnknownColumn { axis, column: column.clone(), hint: error.hint.clone() },
        None => ModelProblem::TableInvalid {
            axis,
            message: error.message.clone(),
            label: error.label,
            hint: error.hint.clone(),
        },
    };
    Diagnostic::error(DiagnosticKind::ModelFile(Box::new(problem)), at)
}

/// Where the text of the string value `csv` starts in `text`, the model file, if the
/// string is written as its value is (no escapes): after its opening quotes, and after the
/// line break that follows the quotes of a multi-line string.
fn unescaped_start(text: &str, csv: &Spanned<String>) -> Option<u32> {
    let written = text.get(csv.span())?;
    let quotes = ["\"\"\"", "'''", "\"", "'"].into_iter().find(|q| written.starts_with(q))?;
    let mut start = quotes.len();
    if quotes.len() == 3 {
        start += ["\r\n", "\n"].into_iter().find(|b| written[start..].starts_with(b)).map_or(0, str::len);
    }
    let end = written.len().checked_sub(quotes.len())?;
    let content = written.get(start..end)?;
    (content == csv.get_ref()).then(|| (csv.span().start + start) as u32)
}
