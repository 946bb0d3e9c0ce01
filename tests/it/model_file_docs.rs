//! The model file's reference (`docs/error-model.md`) against its reader: every key the
//! reader accepts in `[machine]`, its sub-tables and tool table, `[model]` and
//! `[[axis_table]]`, and every top-level table, is named in the section that documents it.
//! The keys are the reader's own, asked of it with a key it does not know (the diagnostic
//! lists the keys there are), so a key added to the reader and not to the reference fails
//! here.

use turnpass::diagnostic::{DiagnosticKind, ModelProblem};
use turnpass::error_model::model_file::{ModelSpec, TABLES};

use crate::support::repo;

/// The keys the reader accepts where `text` (a model file with an unknown key `__probe`)
/// has that key.
fn keys_where(text: &str) -> Vec<String> {
    let problems = ModelSpec::read(text).expect_err(text);
    problems
        .diagnostics
        .iter()
        .find_map(|d| match &d.kind {
            DiagnosticKind::ModelFile(problem) => match problem.as_ref() {
                ModelProblem::UnknownKey { key, known, .. } if key == "__probe" => Some(known.clone()),
                _ => None,
            },
            _ => None,
        })
        .unwrap_or_else(|| panic!("no unknown-key diagnostic for `__probe` in\n{text}\n{problems:?}"))
}

/// The text of the section of `docs` under the heading that starts with `heading`, up to the
/// next heading of its level (empty when there is none: every key of it is then missing).
fn section<'d>(docs: &'d str, heading: &str) -> &'d str {
    let Some(start) = docs.find(&format!("\n{heading}")).map(|at| at + 1) else { return "" };
    let rest = &docs[start..];
    let level = heading.chars().take_while(|&c| c == '#').count();
    let next = rest[1..]
        .match_indices('\n')
        .map(|(at, _)| at + 2)
        .find(|&at| {
            let line = &rest[at..];
            line.starts_with('#') && line.chars().take_while(|&c| c == '#').count() <= level
        })
        .unwrap_or(rest.len());
    &rest[..next]
}

/// The table row of `text` that documents `key` (`| \`key\` |`), if there is one.
fn row<'t>(text: &'t str, key: &str) -> Option<&'t str> {
    let cell = format!("| `{key}` |");
    text.lines().find(|line| line.starts_with(&cell))
}

#[test]
fn the_reference_names_every_key_the_reader_accepts() {
    let docs = std::fs::read_to_string(repo().join("docs/error-model.md")).unwrap();
    let mut missing = Vec::new();

    // Every table of a model file has a section of its own.
    let top = keys_where("__probe = 1\n");
    assert_eq!(top, TABLES.to_vec(), "the tables the reader accepts");
    for table in &top {
        let heading = ["## `[", table, "]`"].concat();
        let array_heading = ["## `[[", table, "]]`"].concat();
        if !docs.contains(&heading) && !docs.contains(&array_heading) {
            missing.push(format!("the table `{table}` has no section"));
        }
    }

    // `[machine]`: a row for each key; the keys of its sub-tables in their key's row.
    let machine = section(&docs, "## `[machine]`");
    for key in keys_where("[machine]\n__probe = 1\n") {
        if row(machine, &key).is_none() {
            missing.push(format!("[machine] `{key}` has no row"));
        }
    }
    for table in ["home", "travel", "rapid_rate", "ball_screw_pitch_mm"] {
        let keys = keys_where(&format!("[machine.{table}]\n__probe = 1\n"));
        let Some(row) = row(machine, table) else { continue };
        for key in keys {
            if !row.contains(&format!("`{key}`")) {
                missing.push(format!("[machine.{table}] `{key}` is not named in the row of `{table}`"));
            }
        }
    }
    let tools = section(machine, "`[[machine.tool]]`");
    for key in keys_where("[[machine.tool]]\n__probe = 1\n") {
        if row(tools, &key).is_none() {
            missing.push(format!("[[machine.tool]] `{key}` has no row"));
        }
    }

    // `[model]` and `[[axis_table]]`: each key named in its section.
    for (table, heading) in [("[model]", "## `[model]`"), ("[[axis_table]]", "## `[[axis_table]]`")] {
        let text = section(&docs, heading);
        for key in keys_where(&format!("{table}\n__probe = 1\n")) {
            if !text.contains(&format!("`{key}`")) && !text.contains(&format!("`{key} =")) {
                missing.push(format!("{table} `{key}` is not named in its section"));
            }
        }
    }
    assert!(missing.is_empty(), "docs/error-model.md:\n{}", missing.join("\n"));
}
