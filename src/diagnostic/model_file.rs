//! The words of the diagnostics of machine model files and their axis tables: what is wrong
//! with a table, a key or a value, said with the table and key that hold it (the label
//! points at the text, `toml_spans` finds it).

use crate::bounds::{OutOfRange, show};

/// What is wrong with a model file or one of its axis tables. `table` names the table that
/// holds the key as the file writes it (`[machine]`, `[[effect]] 3 (squareness)`), `key` the
/// key (`coeffs[1]` for an element of an array).
#[derive(Debug, Clone, PartialEq)]
pub enum ModelProblem {
    /// The text is not TOML; `message` is the TOML reader's.
    Syntax { message: String },
    /// A key the table does not have.
    UnknownKey { key: String, table: String, known: Vec<String>, suggestion: Option<String> },
    /// A value that is none of the names the key takes (`units = "mmm"`, an effect's `kind`).
    UnknownName { key: String, table: String, found: String, known: Vec<String>, suggestion: Option<String> },
    /// A key the table needs.
    MissingKey { key: String, table: String },
    /// A value of the wrong type or form; `detail` is the reader's.
    WrongValue { key: String, table: String, detail: String },
    /// A number outside its plausible range, or not a finite number.
    OutOfRange { key: String, table: String, error: OutOfRange },
    /// A value that breaks a rule between values or on its form; `rule` says what it asks.
    BrokenRule { key: String, table: String, rule: &'static str },
    /// An axis table's file cannot be read; `reason` is the reader's, with the path it tried.
    TableUnreadable { axis: char, reason: String },
    /// An axis table with both or neither of `file` and `csv`.
    TableSource { axis: char },
    /// A second table for a slide that has one.
    DuplicateTable { axis: char },
    /// A column of an axis table with a name the format does not have.
    UnknownColumn { axis: char, column: String, known: Vec<&'static str>, suggestion: Option<&'static str> },
    /// An axis table that does not read; `message` says why.
    TableInvalid { axis: char, message: String },
}

/// `known` as a list in backticks.
fn list<S: AsRef<str>>(known: &[S]) -> String {
    known.iter().map(|k| format!("`{}`", k.as_ref())).collect::<Vec<_>>().join(", ")
}

/// "did you mean `x`? " before the list of what there is.
fn guess(suggestion: Option<&str>, what: &str, known: String) -> Option<String> {
    let list = if known.is_empty() { format!("there are no {what}") } else { format!("the {what} are {known}") };
    Some(match suggestion {
        Some(s) => format!("did you mean `{s}`? {list}"),
        None => list,
    })
}

impl ModelProblem {
    pub fn code(&self) -> &'static str {
        match self {
            ModelProblem::Syntax { .. } => "model-syntax",
            ModelProblem::UnknownKey { .. } => "model-unknown-key",
            ModelProblem::UnknownName { .. } => "model-unknown-name",
            ModelProblem::MissingKey { .. } => "model-missing-key",
            ModelProblem::WrongValue { .. } => "model-wrong-value",
            ModelProblem::OutOfRange { .. } => "model-out-of-range",
            ModelProblem::BrokenRule { .. } => "model-broken-rule",
            ModelProblem::TableUnreadable { .. } => "model-table-unreadable",
            ModelProblem::TableSource { .. } => "model-table-source",
            ModelProblem::DuplicateTable { .. } => "model-duplicate-table",
            ModelProblem::UnknownColumn { .. } => "table-unknown-column",
            ModelProblem::TableInvalid { .. } => "table-invalid",
        }
    }

    pub fn message(&self) -> String {
        match self {
            ModelProblem::Syntax { message } => format!("the model file is not valid TOML: {message}"),
            ModelProblem::UnknownKey { key, table, .. } => format!("{table} has no key `{key}`"),
            ModelProblem::UnknownName { key, table, found, .. } => {
                format!("`{key}` in {table} is `{found}`, which is none of the names it takes")
            }
            ModelProblem::MissingKey { key, table } => format!("{table} has no `{key}`, which it needs"),
            ModelProblem::WrongValue { key, table, detail } => format!("`{key}` in {table}: {detail}"),
            ModelProblem::OutOfRange { key, table, error } if error.value.is_finite() => {
                format!("`{key}` in {table} is {}: it must be {}", show(error.value), error.range)
            }
            ModelProblem::OutOfRange { key, table, error } => {
                format!("`{key}` in {table} is {}, not a finite number: it must be {}", error.value, error.range)
            }
            ModelProblem::BrokenRule { key, table, rule } => format!("`{key}` in {table}: {rule}"),
            ModelProblem::TableUnreadable { axis, reason } => format!("cannot read the {axis} slide's table: {reason}"),
            ModelProblem::TableSource { axis } => {
                format!("the {axis} slide's [[axis_table]] needs either `file` or `csv` (one of them, not both)")
            }
            ModelProblem::DuplicateTable { axis } => format!("a second table for the {axis} slide"),
            ModelProblem::UnknownColumn { axis, column, .. } => {
                format!("unknown column `{column}` in the {axis} slide's table")
            }
            ModelProblem::TableInvalid { axis, message } => format!("the {axis} slide's table: {message}"),
        }
    }

    pub fn label(&self) -> String {
        match self {
            ModelProblem::Syntax { .. } => "not TOML".to_string(),
            ModelProblem::UnknownKey { .. } => "unknown key".to_string(),
            ModelProblem::UnknownName { .. } => "unknown name".to_string(),
            ModelProblem::MissingKey { key, .. } => format!("no `{key}` in this table"),
            ModelProblem::WrongValue { .. } => "this value".to_string(),
            ModelProblem::OutOfRange { error, .. } if !error.value.is_finite() => "not a finite number".to_string(),
            ModelProblem::OutOfRange { .. } => "out of range".to_string(),
            ModelProblem::BrokenRule { .. } => "this value".to_string(),
            ModelProblem::TableUnreadable { .. } => "the table named here".to_string(),
            ModelProblem::TableSource { .. } => "this table".to_string(),
            ModelProblem::DuplicateTable { .. } => "second table".to_string(),
            ModelProblem::UnknownColumn { .. } => "unknown column".to_string(),
            ModelProblem::TableInvalid { .. } => "here".to_string(),
        }
    }

    pub fn hint(&self) -> Option<String> {
        match self {
            ModelProblem::UnknownKey { known, suggestion, .. } => guess(suggestion.as_deref(), "keys", list(known)),
            ModelProblem::UnknownName { known, suggestion, .. } => guess(suggestion.as_deref(), "names", list(known)),
            ModelProblem::MissingKey { key, .. } => Some(format!("add `{key} = …` to the table")),
            ModelProblem::TableUnreadable { .. } => {
                Some("a table's `file` is read relative to the model file's folder".to_string())
            }
            ModelProblem::DuplicateTable { .. } => Some("give each slide one [[axis_table]]".to_string()),
            ModelProblem::UnknownColumn { known, suggestion, .. } => guess(*suggestion, "columns", list(known)),
            ModelProblem::Syntax { .. }
            | ModelProblem::WrongValue { .. }
            | ModelProblem::OutOfRange { .. }
            | ModelProblem::BrokenRule { .. }
            | ModelProblem::TableSource { .. }
            | ModelProblem::TableInvalid { .. } => None,
        }
    }
}
