//! Editor sessions with `turnpass lsp` as a subprocess, driven by `tests/cases/lsp/`.
//!
//! A case is a program and a `<name>.toml` of steps (incremental changes, hovers,
//! definitions, symbols, formatting). The transcript, a snapshot under `snapshots/lsp/`,
//! shows every published diagnostic with its range drawn under the line it points at, and
//! every answer. Positions are the protocol's: 0-based lines, UTF-16 columns; the test
//! converts them with its own code, not the server's.

use std::fmt::Write as _;
use std::path::Path;

use serde::Deserialize;
use serde_json::{Value, json};

use crate::lsp_client::{Client, file_uri};
use crate::support::{repo, with_snapshots};

#[derive(Deserialize)]
struct Session {
    #[serde(default)]
    init: toml::Table,
    #[serde(default)]
    step: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Step {
    change: Option<Vec<Change>>,
    hover: Option<[u32; 2]>,
    definition: Option<[u32; 2]>,
    #[serde(default)]
    symbols: bool,
    #[serde(default)]
    formatting: bool,
}

#[derive(Deserialize)]
struct Change {
    from: [u32; 2],
    to: [u32; 2],
    text: String,
}

#[test]
fn editor_sessions() {
    let dir = repo().join("tests/cases/lsp");
    let mut cases: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    cases.sort();
    assert!(!cases.is_empty());
    for case in cases {
        let name = case.file_stem().unwrap().to_string_lossy().into_owned();
        let program = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .find(|p| p.file_stem() == case.file_stem() && p.extension().is_some_and(|e| e != "toml"))
            .unwrap_or_else(|| panic!("{name}: no program beside the session"));
        let session: Session = toml::from_str(&std::fs::read_to_string(&case).unwrap()).unwrap();
        let transcript = run(&program, &session);
        with_snapshots("lsp", || insta::assert_snapshot!(name, transcript));
    }
}

fn run(program: &Path, session: &Session) -> String {
    let uri = file_uri(program);
    let mut text = std::fs::read_to_string(program).unwrap();
    let mut client = Client::start(serde_json::to_value(&session.init).unwrap());
    let mut out = String::new();
    let mut version = 1;
    client.notify(
        "textDocument/didOpen",
        json!({ "textDocument": { "uri": uri, "languageId": "gcode", "version": version, "text": text } }),
    );
    let file_name = program.file_name().unwrap().to_string_lossy();
    let _ = writeln!(out, "open {file_name}");
    diagnostics(&mut out, &text, &client.diagnostics(&uri, version));
    // The log, sent before the diagnostics, with the document's URI (a path on this
    // machine) written as its file name.
    for log in client.log_messages() {
        let message = log["params"]["message"].as_str().unwrap().replace(&uri, &file_name);
        let kind = ["error", "warning", "info", "log"].get(log["params"]["type"].as_u64().unwrap() as usize - 1);
        let _ = writeln!(out, "  log ({}): {message}", kind.unwrap());
    }
    let document = json!({ "uri": uri });
    for step in &session.step {
        if let Some(changes) = &step.change {
            version += 1;
            let mut content = Vec::new();
            for change in changes {
                let _ = writeln!(out, "\nchange {:?}-{:?} to {:?}", change.from, change.to, change.text);
                let (start, end) = (offset(&text, change.from), offset(&text, change.to));
                text.replace_range(start..end, &change.text);
                content.push(json!({ "range": range(change.from, change.to), "text": change.text }));
            }
            let params = json!({ "textDocument": { "uri": uri, "version": version }, "contentChanges": content });
            client.notify("textDocument/didChange", params);
            diagnostics(&mut out, &text, &client.diagnostics(&uri, version));
        }
        if let Some(at) = step.hover {
            let result =
                client.request("textDocument/hover", json!({ "textDocument": document, "position": position(at) }));
            let _ = writeln!(out, "\nhover {at:?} `{}`", word_at(&text, at));
            match result.get("contents") {
                Some(contents) => {
                    let _ = writeln!(out, "  range {}", show_range(&result["range"]));
                    for line in contents["value"].as_str().unwrap().lines() {
                        let _ = writeln!(out, "  | {line}");
                    }
                }
                None => out.push_str("  (nothing)\n"),
            }
        }
        if let Some(at) = step.definition {
            let result = client
                .request("textDocument/definition", json!({ "textDocument": document, "position": position(at) }));
            let _ = writeln!(out, "\ndefinition {at:?} `{}`", word_at(&text, at));
            let locations = match result {
                Value::Null => Vec::new(),
                Value::Array(list) => list,
                single => vec![single],
            };
            for location in &locations {
                assert_eq!(location["uri"], uri);
                let line = location["range"]["start"]["line"].as_u64().unwrap() as usize;
                let _ = writeln!(out, "  → {} `{}`", show_range(&location["range"]), lines(&text)[line]);
            }
            if locations.is_empty() {
                out.push_str("  (nothing)\n");
            }
        }
        if step.symbols {
            let result = client.request("textDocument/documentSymbol", json!({ "textDocument": document }));
            out.push_str("\nsymbols\n");
            symbols(&mut out, &result, 1);
        }
        if step.formatting {
            let params = json!({ "textDocument": document, "options": { "tabSize": 4, "insertSpaces": true } });
            let result = client.request("textDocument/formatting", params);
            out.push_str("\nformatting\n");
            for edit in result.as_array().unwrap() {
                let _ = writeln!(out, "  {} →", show_range(&edit["range"]));
                for line in edit["newText"].as_str().unwrap().split('\n') {
                    let _ = writeln!(out, "  | {line}");
                }
            }
        }
    }
    let status = client.stop();
    assert!(status.success(), "exit after shutdown: {status}");
    out.push_str("\nshutdown, exit: 0\n");
    out
}

/// Each diagnostic with its range drawn under the line it starts on.
fn diagnostics(out: &mut String, text: &str, list: &[Value]) {
    let _ = writeln!(out, "  {} diagnostic{}", list.len(), if list.len() == 1 { "" } else { "s" });
    let lines = lines(text);
    for d in list {
        let severity = match d["severity"].as_u64() {
            Some(1) => "error",
            Some(2) => "warning",
            Some(3) => "info",
            _ => "hint",
        };
        assert_eq!(d["source"], "turnpass");
        let _ = writeln!(
            out,
            "  {} {severity}[{}] ({}): {}",
            show_range(&d["range"]),
            d["code"].as_str().unwrap(),
            d["data"]["pass"].as_str().unwrap(),
            d["message"].as_str().unwrap()
        );
        let start = &d["range"]["start"];
        let end = &d["range"]["end"];
        let line = start["line"].as_u64().unwrap() as usize;
        if let Some(source) = lines.get(line) {
            let from = start["character"].as_u64().unwrap() as usize;
            let to = if end["line"] == start["line"] { end["character"].as_u64().unwrap() as usize } else { from + 1 };
            // Columns are UTF-16 units; the drawing counts characters by their units.
            let mut marker = String::new();
            let mut unit = 0;
            for c in source.chars() {
                let width = c.len_utf16();
                marker.push(if unit >= from && unit < to { '^' } else { ' ' });
                unit += width;
            }
            if to > unit {
                marker.push('^');
            }
            let _ = writeln!(out, "      | {source}\n      | {}", marker.trim_end());
        }
        for related in d["relatedInformation"].as_array().into_iter().flatten() {
            let _ = writeln!(
                out,
                "      + {} {}",
                show_range(&related["location"]["range"]),
                related["message"].as_str().unwrap()
            );
        }
    }
}

fn symbols(out: &mut String, list: &Value, depth: usize) {
    for symbol in list.as_array().into_iter().flatten() {
        let _ = writeln!(
            out,
            "{}{} (kind {}) {} name {}: {}",
            "  ".repeat(depth),
            symbol["name"].as_str().unwrap(),
            symbol["kind"],
            show_range(&symbol["range"]),
            show_range(&symbol["selectionRange"]),
            symbol["detail"].as_str().unwrap_or("")
        );
        symbols(out, &symbol["children"], depth + 1);
    }
}

fn lines(text: &str) -> Vec<&str> {
    text.split('\n').collect()
}

/// The byte offset of a protocol position (UTF-16 column) in `text` (LF line ends).
fn offset(text: &str, [line, column]: [u32; 2]) -> usize {
    let start: usize = lines(text).iter().take(line as usize).map(|l| l.len() + 1).sum();
    let mut units = 0;
    for (at, c) in lines(text)[line as usize].char_indices() {
        if units >= column as usize {
            return start + at;
        }
        units += c.len_utf16();
    }
    start + lines(text)[line as usize].len()
}

/// The blank-separated token under a position, for the transcript.
fn word_at(text: &str, at: [u32; 2]) -> &str {
    let line_start = offset(text, [at[0], 0]);
    let line = lines(text)[at[0] as usize];
    let cursor = offset(text, at) - line_start;
    let start = line[..cursor].rfind(' ').map_or(0, |p| p + 1);
    let end = line[cursor..].find(' ').map_or(line.len(), |p| cursor + p);
    &line[start..end]
}

fn position([line, character]: [u32; 2]) -> Value {
    json!({ "line": line, "character": character })
}

fn range(from: [u32; 2], to: [u32; 2]) -> Value {
    json!({ "start": position(from), "end": position(to) })
}

fn show_range(range: &Value) -> String {
    let point = |p: &Value| format!("{}:{}", p["line"], p["character"]);
    format!("{}-{}", point(&range["start"]), point(&range["end"]))
}
