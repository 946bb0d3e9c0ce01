//! The words of the diagnostics of machine model files and their axis tables: what is wrong
//! with a table, a key or a value, said with the table and key that hold it (the label
//! points at the text, `toml_spans` finds it).

use std::borrow::Cow;

use super::Words;
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
    /// A key whose name says it is in the other system of units (`dx_dia` in an effect,
    /// which is in mm with X as a radius): `said` is what its name says ("a diameter"),
    /// `instead` the key meant, when there is one.
    WrongUnits { key: String, table: String, said: &'static str, instead: Option<String> },
    /// The same error in a slide table and an effect (`error_model::counted_twice`): `what`
    /// ("play", "scale") of the `axis` slide, what the table holds and what the effect adds;
    /// `switch` is the `[[axis_table]]` key that says whether the control's compensation of
    /// it was on while the table was taken, `measured_with` its value.
    CountedTwice {
        axis: char,
        what: &'static str,
        table: String,
        effect: String,
        switch: &'static str,
        measured_with: Option<crate::error_model::model_file::Switch>,
    },
    /// An axis table's file cannot be read; `reason` is the reader's, with the path it tried.
    TableUnreadable { axis: char, reason: String },
    /// An axis table with both or neither of `file` and `csv`.
    TableSource { axis: char },
    /// A second table for a slide that has one.
    DuplicateTable { axis: char },
    /// A column of an axis table that the table's reader cannot place; `hint` says what would.
    UnknownColumn { axis: char, column: String, hint: Option<String> },
    /// An axis table that does not read: what is wrong, the label on the text, and what
    /// would put it right.
    TableInvalid { axis: char, message: String, label: &'static str, hint: Option<String> },
}

/// `known` as a list in backticks.
fn list<S: AsRef<str>>(known: &[S]) -> String {
    known.iter().map(|k| format!("`{}`", k.as_ref())).collect::<Vec<_>>().join(", ")
}

/// "did you mean `x`? " before the list of what there is.
fn guess(suggestion: Option<&str>, what: &str, known: String) -> Option<Cow<'static, str>> {
    let list = if known.is_empty() { format!("there are no {what}") } else { format!("the {what} are {known}") };
    Some(match suggestion {
        Some(s) => format!("did you mean `{s}`? {list}").into(),
        None => list.into(),
    })
}

impl ModelProblem {
    /// The code, message, label and hint of this problem, one arm per kind.
    pub fn words(&self) -> Words {
        match self {
            ModelProblem::Syntax { message } => Words {
                code: "model-syntax",
                message: format!("the model file is not valid TOML: {message}").into(),
                label: "not TOML".into(),
                hint: None,
            },
            ModelProblem::UnknownKey { key, table, known, suggestion } => Words {
                code: "model-unknown-key",
                message: format!("{table} has no key `{key}`").into(),
                label: "unknown key".into(),
                hint: guess(suggestion.as_deref(), "keys", list(known)),
            },
            ModelProblem::UnknownName { key, table, found, known, suggestion } => Words {
                code: "model-unknown-name",
                message: format!("`{key}` in {table} is `{found}`, which is none of the names it takes").into(),
                label: "unknown name".into(),
                hint: guess(suggestion.as_deref(), "names", list(known)),
            },
            ModelProblem::MissingKey { key, table } => Words {
                code: "model-missing-key",
                message: format!("{table} has no `{key}`, which it needs").into(),
                label: format!("no `{key}` in this table").into(),
                hint: Some(format!("add `{key} = …` to the table").into()),
            },
            ModelProblem::WrongValue { key, table, detail } => Words {
                code: "model-wrong-value",
                message: format!("`{key}` in {table}: {detail}").into(),
                label: "this value".into(),
                hint: None,
            },
            ModelProblem::OutOfRange { key, table, error } if error.value.is_finite() => Words {
                code: "model-out-of-range",
                message: format!("`{key}` in {table} is {}: it must be {}", show(error.value), error.range).into(),
                label: "out of range".into(),
                hint: None,
            },
            ModelProblem::OutOfRange { key, table, error } => Words {
                code: "model-out-of-range",
                message: format!(
                    "`{key}` in {table} is {}, not a finite number: it must be {}",
                    error.value, error.range
                )
                .into(),
                label: "not a finite number".into(),
                hint: None,
            },
            ModelProblem::BrokenRule { key, table, rule } => Words {
                code: "model-broken-rule",
                message: format!("`{key}` in {table}: {rule}").into(),
                label: "this value".into(),
                hint: None,
            },
            ModelProblem::WrongUnits { key, table, said, instead } => Words {
                code: "model-wrong-units",
                message: format!("`{key}` in {table} gives {said}: {}", crate::machine::UNITS_RULE).into(),
                label: (*said).into(),
                hint: Some(
                    match instead {
                        Some(instead) => format!(
                            "write `{instead}` in millimetres, X as a radius (a diameter's change is twice the \
                             radius's)"
                        ),
                        None => "an effect has no unit of its own: its lengths are millimetres, X a radius".to_string(),
                    }
                    .into(),
                ),
            },
            ModelProblem::CountedTwice { axis, what, table, effect, switch, measured_with } => Words {
                code: "model-counted-twice",
                message: format!(
                    "the {axis} slide's {what} is counted twice: its table holds {table}, and {effect}; the model \
                     adds both, so compensation would take it out twice"
                )
                .into(),
                label: format!("this table holds the {what}").into(),
                hint: Some(
                    match measured_with {
                        Some(crate::error_model::model_file::Switch::On) => format!(
                            "the table was taken with the control's {} on, so it holds the {what} that compensation \
                             leaves, as the machine runs: keep it there and remove the effect",
                            switch.replace('_', " ")
                        ),
                        Some(crate::error_model::model_file::Switch::Off) => format!(
                            "the table was taken with the control's {} off, so it holds the slide's whole {what}: \
                             keep one of the two, and neither if the control compensates it as it runs",
                            switch.replace('_', " ")
                        ),
                        None => format!(
                            "keep the {what} in one place; and say how the table was taken: `{switch} = \"on\"` \
                             (it holds what the control's compensation leaves) or `\"off\"` in its [[axis_table]]"
                        ),
                    }
                    .into(),
                ),
            },
            ModelProblem::TableUnreadable { axis, reason } => Words {
                code: "model-table-unreadable",
                message: format!("cannot read the {axis} slide's table: {reason}").into(),
                label: "the table named here".into(),
                hint: Some("a table's `file` is read relative to the model file's folder".into()),
            },
            ModelProblem::TableSource { axis } => Words {
                code: "model-table-source",
                message: format!(
                    "the {axis} slide's [[axis_table]] needs either `file` or `csv` (one of them, not both)"
                )
                .into(),
                label: "this table".into(),
                hint: None,
            },
            ModelProblem::DuplicateTable { axis } => Words {
                code: "model-duplicate-table",
                message: format!("a second table for the {axis} slide").into(),
                label: "second table".into(),
                hint: Some("give each slide one [[axis_table]]".into()),
            },
            ModelProblem::UnknownColumn { axis, column, hint } => Words {
                code: "table-unknown-column",
                message: format!("unknown column `{column}` in the {axis} slide's table").into(),
                label: "unknown column".into(),
                hint: hint.clone().map(Cow::Owned),
            },
            ModelProblem::TableInvalid { axis, message, label, hint } => Words {
                code: "table-invalid",
                message: format!("the {axis} slide's table: {message}").into(),
                label: (*label).into(),
                hint: hint.clone().map(Cow::Owned),
            },
        }
    }

    pub fn code(&self) -> &'static str {
        self.words().code
    }

    pub fn message(&self) -> String {
        self.words().message.into_owned()
    }

    pub fn label(&self) -> String {
        self.words().label.into_owned()
    }

    pub fn hint(&self) -> Option<String> {
        self.words().hint.map(Cow::into_owned)
    }
}
