//! Rename a sequence name with every word that refers to it, and renumber a Fanuc
//! program's sequence numbers, references following.
//!
//! Both edit only the name after the letter (`20` of `N20` and of `P20`), and refuse what
//! would change which block a word names: a new name another block has, a name that is
//! not one in this dialect, renumbering a program where one number names several blocks.

use crate::dialect::Dialect;
use crate::dialect::tables::SequenceStyle;
use crate::source::Span;

use super::document::Document;
use super::names::{self, Name, Use};

/// The name under the cursor that rename would change, and its text.
pub fn prepare(document: &Document, offset: usize) -> Option<(Span, String)> {
    let name = names::at(document, offset)?;
    let text = String::from_utf8_lossy(&document.text_of(name.name)).into_owned();
    Some((name.name, text))
}

/// The edits that rename the name at `offset` (the definitions and every reference with its
/// key) to `new_name` (with or without its `N`), or why not.
pub fn rename(document: &Document, offset: usize, new_name: &str) -> Result<Vec<(Span, String)>, String> {
    let Some(name) = names::at(document, offset) else {
        return Err(
            "no sequence name here: rename works on `N…` names and the `P`, `Q`, `GOTO` and LAP words that name them"
                .to_string(),
        );
    };
    let config = document.config();
    let lexical = &config.tables().lexical;
    let given = new_name.trim();
    let new = given.strip_prefix('N').unwrap_or(given);
    let valid = !new.is_empty()
        && new.len() <= lexical.sequence_max
        && match lexical.sequence {
            SequenceStyle::Numeric => new.bytes().all(|c| c.is_ascii_digit()),
            SequenceStyle::Osp => new.bytes().all(|c| c.is_ascii_digit() || c.is_ascii_uppercase()),
        };
    if !valid {
        let what = match lexical.sequence {
            SequenceStyle::Numeric => "digits",
            SequenceStyle::Osp => "upper-case letters and digits",
        };
        return Err(format!("`{given}` is no sequence name here: `N` and up to {} {what}", lexical.sequence_max));
    }
    let new_key = key_of(config.dialect, new);
    let all = names::all(document);
    if new_key != name.key && all.iter().any(|n| n.use_ == Use::Definition && n.key == new_key) {
        return Err(format!("`N{new}` names another block already"));
    }
    // Profile and jump words take numbers: an OSP name with letters cannot be one.
    let numeric = new.bytes().all(|c| c.is_ascii_digit());
    let same: Vec<&Name> = all.iter().filter(|n| n.key == name.key).collect();
    if !numeric && same.iter().any(|n| n.name == n.word) {
        return Err(format!("`N{new}` has letters; `GOTO` with a number needs a number"));
    }
    Ok(same.into_iter().map(|n| (n.name, new.to_string())).collect())
}

/// Every word that shares the name at `offset`: definitions (when `declarations`) and
/// references.
pub fn references(document: &Document, offset: usize, declarations: bool) -> Vec<Span> {
    let Some(name) = names::at(document, offset) else { return Vec::new() };
    names::all(document)
        .into_iter()
        .filter(|n| n.key == name.key && (declarations || n.use_ != Use::Definition))
        .map(|n| n.word)
        .collect()
}

/// The edits that renumber a Fanuc program's sequence numbers N10, N20, … in order, with
/// every `P`, `Q`, `GOTO` and `M99 P` that names one; `None` when there is nothing to
/// renumber (an OSP program, whose names are names, or no `N` at all); why not, when a
/// number names several blocks.
pub fn renumber(document: &Document) -> Option<Result<Vec<(Span, String)>, String>> {
    let config = document.config();
    if config.dialect != Dialect::Fanuc {
        return None;
    }
    let all = names::all(document);
    let definitions: Vec<&Name> = all.iter().filter(|n| n.use_ == Use::Definition).collect();
    if definitions.is_empty() {
        return None;
    }
    let mut new_of = std::collections::HashMap::new();
    let max = 10u64.pow(config.tables().lexical.sequence_max as u32) - 1;
    let step = if definitions.len() as u64 * 10 <= max { 10 } else { 1 };
    if definitions.len() as u64 * step > max {
        return Some(Err(format!("{} numbered blocks do not fit numbers up to {max}", definitions.len())));
    }
    for (index, definition) in definitions.iter().enumerate() {
        let number = (index as u64 + 1) * step;
        if new_of.insert(definition.key.clone(), number).is_some() {
            return Some(Err(format!(
                "N{} names several blocks; a `P`, `Q` or `GOTO` naming it would name another after renumbering",
                definition.key
            )));
        }
    }
    let edits = all
        .iter()
        .filter_map(|n| new_of.get(&n.key).map(|number| (n.name, number.to_string())))
        .filter(|(span, text)| document.text_of(*span) != text.as_bytes())
        .collect();
    Some(Ok(edits))
}

fn key_of(dialect: Dialect, name: &str) -> String {
    let number = name.parse::<u32>().ok();
    crate::semantic::labels::key(
        dialect,
        format!("N{name}").as_bytes(),
        number.filter(|_| name.bytes().all(|c| c.is_ascii_digit())),
    )
}
