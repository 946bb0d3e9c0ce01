//! A machine model file read as TOML with the place of every key and value, so that what is
//! wrong in it is reported at the table and key that hold it, as a diagnostic like a
//! program's (file:line:column, a label on the text, a hint with the nearest valid name).
//!
//! Values are read through serde from the spanned tree (`toml::de::DeTable`), a table at a
//! time; serde's errors carry the span of the key or value at fault, and the tree tells
//! which table that is. Values are checked against their ranges after they are read
//! (`crate::bounds`): a refused value's path in the tree gives its place.

use serde::de::DeserializeOwned;
use toml::Spanned;
use toml::de::{DeTable, DeValue, ValueDeserializer};

use crate::bounds::{Invalid, Key, Reason};
use crate::diagnostic::{Diagnostic, DiagnosticKind, ModelProblem};
use crate::source::{LineIndex, Span};

/// What is wrong with a model file: its diagnostics, and a one-line summary of them with
/// their lines and columns for messages that show no source (the language server's).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{summary}")]
pub struct Problems {
    pub diagnostics: Vec<Diagnostic>,
    summary: String,
}

impl Problems {
    pub fn new(text: &str, diagnostics: Vec<Diagnostic>) -> Problems {
        let lines = LineIndex::new(text.as_bytes());
        let summary = diagnostics
            .iter()
            .map(|d| {
                let (line, column) = lines.position(d.span.start.min(text.len() as u32));
                format!("line {line}, column {column}: {}", d.message())
            })
            .collect::<Vec<_>>()
            .join("; ");
        Problems { diagnostics, summary }
    }
}

/// One step of a path into a document: a key of a table, or an element of an array.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Step {
    Key(String),
    Index(usize),
}

impl From<Key> for Step {
    fn from(key: Key) -> Step {
        match key {
            Key::Name(name) => Step::Key(name.to_string()),
            Key::Index(index) => Step::Index(index),
        }
    }
}

impl From<&str> for Step {
    fn from(key: &str) -> Step {
        Step::Key(key.to_string())
    }
}

impl From<usize> for Step {
    fn from(index: usize) -> Step {
        Step::Index(index)
    }
}

/// A model file's TOML, every key and value with its span.
pub struct Document<'t> {
    root: Spanned<DeTable<'t>>,
}

/// A byte range of the text as a `Span` (model files are far below 4 GiB; a larger one is
/// refused by its TOML reader first).
pub fn span(range: std::ops::Range<usize>) -> Span {
    let clamp = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
    Span::new(clamp(range.start), clamp(range.end))
}

fn error(problem: ModelProblem, at: Span) -> Diagnostic {
    Diagnostic::error(DiagnosticKind::ModelFile(Box::new(problem)), at)
}

/// The value of `key` in `table`.
fn entry<'a, 't>(
    table: &'a DeTable<'t>,
    key: &str,
) -> Option<(&'a Spanned<toml::de::DeString<'t>>, &'a Spanned<DeValue<'t>>)> {
    table.iter().find(|(k, _)| k.get_ref().as_ref() == key)
}

impl<'t> Document<'t> {
    /// Read `text`; a TOML syntax error is the diagnostic.
    pub fn parse(text: &'t str) -> Result<Document<'t>, Diagnostic> {
        match DeTable::parse(text) {
            Ok(root) => Ok(Document { root }),
            Err(e) => {
                let at = e.span().map_or(Span::new(0, 0), span);
                Err(error(ModelProblem::Syntax { message: e.message().trim().to_string() }, at))
            }
        }
    }

    /// The value at `path`.
    pub fn get(&self, path: &[Step]) -> Option<&Spanned<DeValue<'t>>> {
        let (first, rest) = path.split_first()?;
        let Step::Key(key) = first else { return None };
        let mut value = entry(self.root.get_ref(), key)?.1;
        for step in rest {
            value = match (step, value.get_ref()) {
                (Step::Key(key), DeValue::Table(table)) => entry(table, key)?.1,
                (Step::Index(index), DeValue::Array(array)) => array.get(*index)?,
                _ => return None,
            };
        }
        Some(value)
    }

    /// The keys of the top-level table, with their spans.
    pub fn top_keys(&self) -> Vec<(String, Span)> {
        self.root.get_ref().iter().map(|(k, _)| (k.get_ref().to_string(), span(k.span()))).collect()
    }

    /// The span of the value at `path`, or of the nearest table above it that exists.
    pub fn span_of(&self, path: &[Step]) -> Span {
        (0..=path.len()).rev().find_map(|n| self.get(&path[..n]).map(|v| span(v.span()))).unwrap_or(Span::new(0, 0))
    }

    /// The value at `path` read as a `T`; `None` when the file has no such value.
    pub fn read<T: DeserializeOwned>(&self, path: &[Step]) -> Result<Option<T>, Diagnostic> {
        match self.get(path) {
            Some(value) => self.read_value(value.clone()).map(Some),
            None => Ok(None),
        }
    }

    /// `value` (a part of this document) read as a `T`.
    pub fn read_value<T: DeserializeOwned>(&self, value: Spanned<DeValue<'t>>) -> Result<T, Diagnostic> {
        T::deserialize(ValueDeserializer::from(value)).map_err(|e| self.diagnostic_of(&e))
    }

    /// [`Document::read_value`] through a function of a deserializer (an effect read by its
    /// kind).
    pub fn read_with<T>(
        &self,
        value: Spanned<DeValue<'t>>,
        read: impl FnOnce(ValueDeserializer<'t>) -> Result<T, toml::de::Error>,
    ) -> Result<T, Diagnostic> {
        read(ValueDeserializer::from(value)).map_err(|e| self.diagnostic_of(&e))
    }

    /// The diagnostic of a value refused by its range or a rule; `outer` is the path of the
    /// table that checked it.
    pub fn invalid(&self, outer: &[Step], invalid: &Invalid) -> Diagnostic {
        let mut path = outer.to_vec();
        path.extend(invalid.path.iter().copied().map(Step::from));
        let (table, key) = self.split(&path);
        let at = self.span_of(&path);
        match invalid.reason {
            Reason::OutOfRange(error) => self::error(ModelProblem::OutOfRange { key, table, error }, at),
            Reason::Rule(rule) => self::error(ModelProblem::BrokenRule { key, table, rule }, at),
        }
    }

    /// A key of the table at `table` that the reader does not know, at its span.
    pub fn unknown_key(&self, table: &[Step], key: &str, at: Span, known: &[&str]) -> Diagnostic {
        let problem = ModelProblem::UnknownKey {
            key: key.to_string(),
            table: self.table_name(table),
            known: known.iter().map(|k| k.to_string()).collect(),
            suggestion: nearest(key, known.iter().copied()).map(str::to_string),
        };
        error(problem, at)
    }

    /// A value of `key` (at `path`) that is none of the names in `known`.
    pub fn unknown_name(&self, path: &[Step], found: &str, known: &[&str]) -> Diagnostic {
        let (table, key) = self.split(path);
        let problem = ModelProblem::UnknownName {
            key,
            table,
            found: found.to_string(),
            known: known.iter().map(|k| k.to_string()).collect(),
            suggestion: nearest(found, known.iter().copied()).map(str::to_string),
        };
        error(problem, self.span_of(path))
    }

    /// The value at `path` is not of the form the reader wants; `detail` says what it wants.
    pub fn wrong_value(&self, path: &[Step], detail: &str) -> Diagnostic {
        let (table, key) = self.split(path);
        error(ModelProblem::WrongValue { key, table, detail: detail.to_string() }, self.span_of(path))
    }

    /// A key the table at `table` needs.
    pub fn missing_key(&self, table: &[Step], key: &str) -> Diagnostic {
        let problem = ModelProblem::MissingKey { key: key.to_string(), table: self.table_name(table) };
        error(problem, self.span_of(table))
    }

    /// How the file names the table at `path`: `[machine]`, `[machine.home]`,
    /// `[[effect]] 3 (squareness)` (1-based, with the effect's kind or the table's axis).
    pub fn table_name(&self, path: &[Step]) -> String {
        self.table_name_tagged(path, true)
    }

    /// [`Document::table_name`], with the kind or axis in brackets only when `tagged`.
    fn table_name_tagged(&self, path: &[Step], tagged: bool) -> String {
        if path.is_empty() {
            return "the model file".to_string();
        }
        let mut names = Vec::new();
        for (i, step) in path.iter().enumerate() {
            match step {
                Step::Key(key) => names.push(key.clone()),
                Step::Index(index) if i + 1 == path.len() => {
                    let tag = ["kind", "axis"].iter().find_map(|key| {
                        let mut tagged = path.to_vec();
                        tagged.push(Step::Key(key.to_string()));
                        self.get(&tagged).and_then(|v| v.get_ref().as_str().map(str::to_string))
                    });
                    let tag = tag.filter(|_| tagged).map_or(String::new(), |t| format!(" ({t})"));
                    return format!("[[{}]] {}{tag}", names.join("."), index + 1);
                }
                Step::Index(index) => {
                    let last = names.pop().unwrap_or_default();
                    names.push(format!("{last}[{index}]"));
                }
            }
        }
        format!("[{}]", names.join("."))
    }

    /// `path` split into the table that holds its key and the key as text (`coeffs[1]` for
    /// an element of an array).
    fn split(&self, path: &[Step]) -> (String, String) {
        let table_len = (0..path.len())
            .rev()
            .find(|&n| n == 0 || self.get(&path[..n]).is_some_and(|v| matches!(v.get_ref(), DeValue::Table(_))))
            .unwrap_or(0);
        let mut key = String::new();
        for step in &path[table_len..] {
            match step {
                Step::Key(name) if key.is_empty() => key.push_str(name),
                Step::Key(name) => {
                    key.push('.');
                    key.push_str(name);
                }
                Step::Index(index) => key.push_str(&format!("[{index}]")),
            }
        }
        // A table is not named by its tag when the tag is the key in question.
        let tagged = !matches!(path.get(table_len), Some(Step::Key(k)) if k == "kind" || k == "axis");
        (self.table_name_tagged(&path[..table_len], tagged), key)
    }

    /// The path of the deepest key or value whose text holds `at`.
    fn path_at(&self, at: std::ops::Range<usize>) -> Vec<Step> {
        type Range = std::ops::Range<usize>;
        fn within(outer: &Range, inner: &Range) -> bool {
            outer.start <= inner.start && inner.end <= outer.end
        }
        fn walk_table(table: &DeTable<'_>, at: &Range, path: &mut Vec<Step>, best: &mut Vec<Step>) {
            for (key, child) in table.iter() {
                visit(Step::Key(key.get_ref().to_string()), Some(key.span()), child, at, path, best);
            }
        }
        fn visit(
            step: Step,
            key: Option<Range>,
            child: &Spanned<DeValue<'_>>,
            at: &Range,
            path: &mut Vec<Step>,
            best: &mut Vec<Step>,
        ) {
            path.push(step);
            if (key.is_some_and(|k| within(&k, at)) || within(&child.span(), at)) && path.len() > best.len() {
                *best = path.clone();
            }
            match child.get_ref() {
                DeValue::Table(table) => walk_table(table, at, path, best),
                DeValue::Array(array) => {
                    for (index, element) in array.iter().enumerate() {
                        visit(Step::Index(index), None, element, at, path, best);
                    }
                }
                _ => {}
            }
            path.pop();
        }
        let mut best = Vec::new();
        walk_table(self.root.get_ref(), &at, &mut Vec::new(), &mut best);
        best
    }

    /// The diagnostic of a serde error met reading a part of this document.
    fn diagnostic_of(&self, e: &toml::de::Error) -> Diagnostic {
        let range = e.span().unwrap_or(0..0);
        let at = span(range.clone());
        let path = self.path_at(range);
        let message = e.message().trim();
        if let Some((found, known)) = named_and_expected(message, "unknown field `") {
            // The error is at the key, so the path ends with it.
            let table = &path[..path.len().saturating_sub(1)];
            let known: Vec<&str> = known.iter().map(String::as_str).collect();
            return self.unknown_key(table, &found, at, &known);
        }
        if let Some((found, known)) = named_and_expected(message, "unknown variant `") {
            let known: Vec<&str> = known.iter().map(String::as_str).collect();
            return self.unknown_name(&path, &found, &known);
        }
        if let Some(key) = message.strip_prefix("missing field `").and_then(|rest| rest.strip_suffix('`')) {
            return self.missing_key(&path, key);
        }
        let (table, key) = self.split(&path);
        // serde names Rust's types; the file's reader knows numbers and whole numbers.
        let detail = message
            .replace("expected f64", "expected a number")
            .replace("expected u8", "expected a whole number")
            .replace("expected u32", "expected a whole number");
        error(ModelProblem::WrongValue { key, table, detail }, at)
    }
}

/// The name and the list of valid names in serde's messages for an unknown field or variant
/// ("unknown field `uradd`, expected `urad`", "…, expected one of `a`, `b`", "…, there are no
/// fields").
fn named_and_expected(message: &str, prefix: &str) -> Option<(String, Vec<String>)> {
    let rest = message.strip_prefix(prefix)?;
    let (found, expected) = rest.split_once('`')?;
    let known = expected.split('`').skip(1).step_by(2).map(str::to_string).collect();
    Some((found.to_string(), known))
}

/// The name of `known` nearest to `found`, if one is near enough to be the one meant (a
/// typo, a wrong unit suffix, a different case).
pub fn nearest<'a>(found: &str, known: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let found = found.to_lowercase();
    known
        .into_iter()
        .map(|name| (strsim::jaro_winkler(&found, &name.to_lowercase()), name))
        .filter(|(score, _)| *score >= 0.8)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, name)| name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn serde_messages_give_the_name_and_the_valid_names() {
        assert_eq!(
            named_and_expected("unknown field `uradd`, expected `urad`", "unknown field `"),
            Some(("uradd".to_string(), vec!["urad".to_string()]))
        );
        assert_eq!(
            named_and_expected("unknown variant `mmm`, expected `mm` or `inch`", "unknown variant `"),
            Some(("mmm".to_string(), vec!["mm".to_string(), "inch".to_string()]))
        );
        assert_eq!(
            named_and_expected("unknown field `b`, there are no fields", "unknown field `"),
            Some(("b".to_string(), vec![]))
        );
    }

    #[test]
    fn the_nearest_name_is_a_likely_typo_or_none() {
        let columns = ["target_mm", "direction", "linear_mm", "straightness_mm", "angular_deg"];
        assert_eq!(nearest("linear_um", columns), Some("linear_mm"));
        assert_eq!(nearest("Direction", columns), Some("direction"));
        assert_eq!(nearest("temperature", columns), None);
        assert_eq!(nearest("squarenes", crate::error_model::effects::NAMES), Some("squareness"));
        assert_eq!(nearest("backlash_q", crate::error_model::effects::NAMES).map(|n| &n[..9]), Some("backlash_"));
    }
}
