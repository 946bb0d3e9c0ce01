//! The provenance comment: what made a compensated program, written into it.
//!
//! A compensated program is the nominal one with the machine's errors taken out; run through
//! `compensate` again, the errors are taken out twice and the part is worse. So `compensate`
//! writes one comment block after the program's name line, in the program's own comment style,
//! that names the tool, the model and the settings it was compensated with:
//!
//! ```text
//! (TURNPASS 0.1.0 COMPENSATED, MODEL TEST LATHE, SHA256 1A2B3C4D5E6F, TOLERANCE 0.0005 MM, STRATEGY AUTO, START 30 MIN)
//! ```
//!
//! (`STRATEGY DENSIFY, STEP 0.5 MM` when densify was given a step; `TABLE 4F…` after the
//! model's digest when the program was compensated for a machine with a control table
//! loaded, `--with-table`: the first digits of that table's SHA-256.) The model is named by
//! its `[machine] name` or its file name, and by the first [`SHA256_DIGITS`] hex digits of
//! the SHA-256 of its content ([`model_sha256`]). [`marks`] finds such comments in a parsed
//! program, [`refusal`] is the diagnostic `compensate` refuses a marked program with, and
//! `verify` reads the start time and the model's digest from the mark.
//!
//! The comment is upper case unless the program's own comments use lower-case letters
//! (older controls reject lower case even in comments); the model's name keeps only
//! characters every control takes in a comment. Reading is case-insensitive, and a field
//! a later version adds is skipped.

use sha2::{Digest, Sha256};

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::Dialect;
use crate::printer::Edits;
use crate::source::Span;
use crate::syntax::{Program, WordKind};

use super::fit::Strategy;

#[cfg(test)]
mod tests;

/// The version of turnpass that writes the comment.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// How many hex digits of the model's SHA-256 the comment carries: 48 bits, enough that two
/// models of one shop never share them by chance, short enough to read aloud.
pub const SHA256_DIGITS: usize = 12;

/// The longest model name written, in characters; a longer one is cut after a whole word
/// (the digest names the model; the name is for the reader).
const NAME_MAX: usize = 48;

/// What a compensated program was made with.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Provenance {
    /// The version of turnpass.
    pub version: String,
    /// The model's `[machine] name`, or its file name.
    pub model: String,
    /// The first [`SHA256_DIGITS`] hex digits of the model's SHA-256, lower case.
    pub model_sha256: String,
    /// The first [`SHA256_DIGITS`] hex digits of the SHA-256 of the control table the machine
    /// runs with (`--with-table`: its file and the files it names), lower case; none for a
    /// machine without.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub table_sha256: Option<String>,
    pub tolerance_mm: f64,
    #[serde(serialize_with = "strategy_name")]
    pub strategy: Strategy,
    /// Densify's step, when one was given.
    pub step_mm: Option<f64>,
    /// Minutes since the machine started when the program starts (thermal effects).
    pub start_min: f64,
    /// The dialect the program was read and written in, where its text alone would read as
    /// the other (`printer::mark`); none otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dialect: Option<Dialect>,
}

fn strategy_name<S: serde::Serializer>(strategy: &Strategy, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(strategy.name())
}

/// The SHA-256 of a model, in lower-case hex: the model file's text, then each table file it
/// reads, in order (each after its length, so that no two lists of texts hash alike). A
/// table is part of the model: a remeasured slide changes the digest.
pub fn model_sha256<'a>(model_text: &[u8], tables: impl IntoIterator<Item = &'a [u8]>) -> String {
    let mut hasher = Sha256::new();
    hasher.update(model_text);
    for table in tables {
        hasher.update((table.len() as u64).to_le_bytes());
        hasher.update(table);
    }
    hasher.finalize().iter().map(|byte| format!("{byte:02x}")).collect()
}

impl Provenance {
    /// The comment's text, between its delimiters, in upper case when `upper`.
    pub fn text(&self, upper: bool) -> String {
        let model = printable_name(&self.model);
        let model = if upper { model.to_ascii_uppercase() } else { model };
        let table =
            self.table_sha256.as_ref().map_or_else(String::new, |t| format!(", TABLE {}", t.to_ascii_uppercase()));
        let mut text = format!(
            "TURNPASS {} COMPENSATED, MODEL {model}, SHA256 {}{table}, TOLERANCE {} MM, STRATEGY {}",
            self.version,
            self.model_sha256.to_ascii_uppercase(),
            short(self.tolerance_mm, 6),
            self.strategy.name().to_ascii_uppercase(),
        );
        if let Some(step) = self.step_mm {
            text.push_str(&format!(", STEP {} MM", short(step, 6)));
        }
        text.push_str(&format!(", START {} MIN", short(self.start_min, 3)));
        if let Some(dialect) = self.dialect {
            text.push_str(&format!(", {}", crate::printer::mark::dialect_field(dialect)));
        }
        text
    }

    /// Whether a model whose SHA-256 (hex, any length from [`SHA256_DIGITS`] up) is `sha256`
    /// is the model this program was compensated with.
    pub fn same_model(&self, sha256: &str) -> bool {
        let ours = self.model_sha256.as_bytes();
        sha256.len() >= ours.len() && sha256.as_bytes()[..ours.len()].eq_ignore_ascii_case(ours)
    }

    /// Read a comment's text (its delimiters removed): `None` when it is not a provenance
    /// comment, `Some(Err(why))` when it is one that does not read.
    pub fn parse(text: &str) -> Option<Result<Provenance, String>> {
        let mut fields = text.split(',').map(str::trim);
        let version = {
            let first: Vec<&str> = fields.next()?.split_whitespace().collect();
            match first.as_slice() {
                [tool, version, what]
                    if tool.eq_ignore_ascii_case("turnpass") && what.eq_ignore_ascii_case("compensated") =>
                {
                    (*version).to_string()
                }
                _ => return None,
            }
        };
        Some(read_fields(version, fields))
    }
}

/// The fields after `TURNPASS version COMPENSATED`.
fn read_fields<'a>(version: String, fields: impl Iterator<Item = &'a str>) -> Result<Provenance, String> {
    let (mut model, mut sha256, mut tolerance, mut strategy, mut step, mut start, mut dialect) =
        (None, None, None, None, None, None, None);
    let mut table = None;
    for field in fields {
        let (key, value) = field.split_once(' ').map_or((field, ""), |(k, v)| (k, v.trim()));
        let number = |unit: &str| -> Result<f64, String> {
            let digits = value
                .len()
                .checked_sub(unit.len())
                .and_then(|n| value[n..].eq_ignore_ascii_case(unit).then(|| value[..n].trim()));
            digits
                .and_then(|d| d.parse::<f64>().ok())
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("{key} `{value}` is not a number of {}", unit.trim().to_ascii_lowercase()))
        };
        match key.to_ascii_uppercase().as_str() {
            "MODEL" => model = Some(value.to_string()),
            "SHA256" => {
                if value.len() < SHA256_DIGITS || !value.bytes().all(|b| b.is_ascii_hexdigit()) {
                    return Err(format!("SHA256 `{value}` is not {SHA256_DIGITS} or more hex digits"));
                }
                sha256 = Some(value.to_ascii_lowercase());
            }
            "TABLE" => {
                if value.len() < SHA256_DIGITS || !value.bytes().all(|b| b.is_ascii_hexdigit()) {
                    return Err(format!("TABLE `{value}` is not {SHA256_DIGITS} or more hex digits"));
                }
                table = Some(value.to_ascii_lowercase());
            }
            "TOLERANCE" => tolerance = Some(number(" MM")?),
            "STRATEGY" => {
                strategy =
                    Some(Strategy::from_name(value).ok_or_else(|| format!("STRATEGY `{value}` is not a strategy"))?)
            }
            "STEP" => step = Some(number(" MM")?),
            "START" => start = Some(number(" MIN")?),
            "DIALECT" => {
                dialect = Some(match value.to_ascii_uppercase().as_str() {
                    "OSP" => Dialect::Osp,
                    "FANUC" => Dialect::Fanuc,
                    _ => return Err(format!("DIALECT `{value}` is not OSP or FANUC")),
                })
            }
            // A field a later version writes.
            _ => {}
        }
    }
    let missing = |name: &str| format!("it has no {name} field");
    Ok(Provenance {
        version,
        model: model.ok_or_else(|| missing("MODEL"))?,
        model_sha256: sha256.ok_or_else(|| missing("SHA256"))?,
        table_sha256: table,
        tolerance_mm: tolerance.ok_or_else(|| missing("TOLERANCE"))?,
        strategy: strategy.ok_or_else(|| missing("STRATEGY"))?,
        step_mm: step,
        start_min: start.ok_or_else(|| missing("START"))?,
        dialect,
    })
}

/// `value` with at most `places` decimals and no trailing zeros (`0.0005`, `30`).
fn short(value: f64, places: usize) -> String {
    let text = format!("{value:.places$}");
    let text = if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.') } else { &text };
    if text == "-0" { "0".to_string() } else { text.to_string() }
}

/// A model name as a comment may hold it: letters, digits, blanks and `- . _ /`; anything
/// else (a parenthesis or `;` would end the comment, a comma would end the field) becomes a
/// blank; runs of blanks become one; whole words up to [`NAME_MAX`] characters, and `...`
/// where words were left out.
fn printable_name(name: &str) -> String {
    let kept: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() || matches!(c, '-' | '.' | '_' | '/') { c } else { ' ' })
        .collect();
    // Whole words, as many as fit (the first one cut if it alone is too long).
    let mut name = String::new();
    for word in kept.split_whitespace() {
        let blank = usize::from(!name.is_empty());
        if name.len() + blank + word.len() > NAME_MAX - 3 {
            if name.is_empty() {
                name = word.chars().take(NAME_MAX - 3).collect();
            }
            name.push_str("...");
            break;
        }
        if blank == 1 {
            name.push(' ');
        }
        name.push_str(word);
    }
    if name.is_empty() { "UNNAMED".to_string() } else { name }
}

/// A provenance comment found in a program.
#[derive(Debug, Clone, PartialEq)]
pub struct Mark {
    /// The comment, delimiters included.
    pub span: Span,
    /// What it says, or why it does not read.
    pub provenance: Result<Provenance, String>,
}

/// Read comment `text` (as written, delimiters included): `None` when it is not a
/// provenance comment.
fn read(text: &[u8]) -> Option<Result<Provenance, String>> {
    let body = crate::printer::mark::comment_body(text).trim_ascii_start();
    // Only a comment that starts with the tool's name is read further.
    if !body.get(..8).is_some_and(|head| head.eq_ignore_ascii_case(b"turnpass")) {
        return None;
    }
    Provenance::parse(&String::from_utf8_lossy(body))
}

/// Whether comment `text` (as written, delimiters included) is a provenance comment.
pub fn is_mark(text: &[u8]) -> bool {
    read(text).is_some()
}

/// Every provenance comment of `program`, in order.
pub fn marks(program: &Program<'_>) -> Vec<Mark> {
    let comments = program.blocks().iter().flat_map(|block| program.words_of(block));
    comments
        .filter(|word| matches!(word.kind, WordKind::Comment(_)))
        .filter_map(|word| read(program.text(word.span)).map(|provenance| Mark { span: word.span, provenance }))
        .collect()
}

/// The error `compensate` refuses a program with when it carries a provenance comment (it
/// is a compensated program already), on the first such comment.
pub fn refusal(program: &Program<'_>) -> Option<Diagnostic> {
    let mark = marks(program).into_iter().next()?;
    let model = mark.provenance.ok().map(|p| p.model);
    Some(Diagnostic::error(DiagnosticKind::AlreadyCompensated { model }, mark.span))
}

/// Record in `edits` the provenance comment block, after the program's name line
/// (`printer::mark::insert_after_name`), in the program's comment style.
pub fn insert(program: &Program<'_>, edits: &mut Edits, provenance: &Provenance) {
    crate::printer::mark::insert_after_name(program, edits, |upper| provenance.text(upper));
}
