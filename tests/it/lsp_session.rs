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
#[serde(deny_unknown_fields)]
struct Session {
    #[serde(default)]
    init: toml::Table,
    /// The client's capabilities (`initialize`'s `capabilities`).
    #[serde(default)]
    capabilities: toml::Table,
    /// The program, relative to `tests/cases/lsp/`, when it is not the one beside the case.
    program: Option<String>,
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
    /// List the code actions for the range from this position to itself…
    actions: Option<[u32; 2]>,
    /// … and apply the one whose title starts with this, as the editor does.
    apply: Option<String>,
    completion: Option<[u32; 2]>,
    signature: Option<[u32; 2]>,
    #[serde(default)]
    tokens: bool,
    #[serde(default)]
    folding: bool,
    references: Option<[u32; 2]>,
    rename: Option<Rename>,
    #[serde(default)]
    inlay: bool,
    /// `workspace/didChangeConfiguration` with these settings.
    settings: Option<toml::Value>,
}

#[derive(Deserialize)]
struct Rename {
    at: [u32; 2],
    to: String,
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
    let cases = crate::support::case_files(&dir, "toml");
    assert!(!cases.is_empty());
    let mut failed = Vec::new();
    for case in cases {
        let name = case.file_stem().unwrap().to_string_lossy().into_owned();
        let session: Session =
            toml::from_str(&std::fs::read_to_string(&case).unwrap()).unwrap_or_else(|e| panic!("{name}: {e}"));
        let program = match &session.program {
            Some(program) => dir.join(program),
            None => std::fs::read_dir(&dir)
                .unwrap()
                .map(|e| e.unwrap().path())
                .find(|p| p.file_stem() == case.file_stem() && p.extension().is_some_and(|e| e != "toml"))
                .unwrap_or_else(|| panic!("{name}: no program beside the session")),
        };
        // Every case runs, and the failures are named together.
        let outcome = std::panic::catch_unwind(|| {
            let transcript = run(&program, &session);
            with_snapshots("lsp", || insta::assert_snapshot!(name.clone(), transcript));
        });
        if outcome.is_err() {
            failed.push(name);
        }
    }
    assert!(failed.is_empty(), "sessions that failed: {failed:?}");
}

fn run(program: &Path, session: &Session) -> String {
    let program = &program.to_path_buf();
    let uri = file_uri(program);
    let mut text = std::fs::read_to_string(program).unwrap();
    let mut client = Client::start_with(
        serde_json::to_value(&session.init).unwrap(),
        serde_json::to_value(&session.capabilities).unwrap(),
    );
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
                    let _ = writeln!(
                        out,
                        "  range {} ({})",
                        show_range(&result["range"]),
                        contents["kind"].as_str().unwrap()
                    );
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
                let line = location["range"]["start"]["line"].as_u64().unwrap() as usize;
                if location["uri"] == uri {
                    let _ = writeln!(out, "  → {} `{}`", show_range(&location["range"]), lines(&text)[line]);
                } else {
                    // Another file, named relative to the program's folder.
                    let other = location["uri"].as_str().unwrap();
                    let folder = file_uri(program.parent().unwrap());
                    let relative = other.strip_prefix(&format!("{folder}/")).unwrap_or(other);
                    let path = program.parent().unwrap().join(relative);
                    let other_text = std::fs::read_to_string(path).unwrap();
                    let _ = writeln!(
                        out,
                        "  → {relative} {} `{}`",
                        show_range(&location["range"]),
                        lines(&other_text)[line]
                    );
                }
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
        if let Some(at) = step.actions {
            let here = range(at, at);
            let context = json!({ "diagnostics": [] });
            let params = json!({ "textDocument": document, "range": here, "context": context });
            let result = client.request("textDocument/codeAction", params);
            let _ = writeln!(out, "\nactions {at:?} `{}`", word_at(&text, at));
            let actions = result.as_array().cloned().unwrap_or_default();
            if actions.is_empty() {
                out.push_str("  (none)\n");
            }
            for action in &actions {
                let _ = writeln!(
                    out,
                    "  {} ({})",
                    action["title"].as_str().unwrap(),
                    action["kind"].as_str().unwrap_or("?")
                );
                if let Some(reason) = action["disabled"]["reason"].as_str() {
                    let _ = writeln!(out, "    disabled: {reason}");
                }
            }
            if let Some(prefix) = &step.apply {
                let mut action = actions
                    .iter()
                    .find(|a| a["title"].as_str().unwrap().starts_with(prefix.as_str()))
                    .unwrap_or_else(|| panic!("no action `{prefix}` at {at:?}"))
                    .clone();
                if action.get("edit").is_none() {
                    action = client.request("codeAction/resolve", action);
                }
                if let Some(reason) = action["disabled"]["reason"].as_str() {
                    let _ = writeln!(out, "  cannot apply `{}`: {reason}", action["title"].as_str().unwrap());
                } else {
                    let edits = action["edit"]["changes"][&uri].as_array().unwrap().clone();
                    let _ = writeln!(out, "  apply `{}`", action["title"].as_str().unwrap());
                    version += 1;
                    apply(&mut client, &mut out, &mut text, &uri, version, &edits);
                }
            }
        }
        if let Some(at) = step.completion {
            let params = json!({ "textDocument": document, "position": position(at) });
            let result = client.request("textDocument/completion", params);
            let _ = writeln!(out, "\ncompletion {at:?} after `{}`", before_cursor(&text, at));
            let items = match &result {
                Value::Array(items) => items.clone(),
                Value::Null => Vec::new(),
                list => list["items"].as_array().cloned().unwrap_or_default(),
            };
            if items.is_empty() {
                out.push_str("  (none)\n");
            }
            const SHOWN: usize = 40;
            for item in items.iter().take(SHOWN) {
                let detail = item["detail"].as_str().unwrap_or("");
                let insert = item["textEdit"]["newText"].as_str().or(item["insertText"].as_str());
                let insert = insert.map_or(String::new(), |t| format!(" inserts `{t}`"));
                let _ =
                    writeln!(out, "  {} (kind {}){insert}: {detail}", item["label"].as_str().unwrap(), item["kind"]);
            }
            if items.len() > SHOWN {
                let _ = writeln!(out, "  … {} more", items.len() - SHOWN);
            }
        }
        if let Some(at) = step.signature {
            let params = json!({ "textDocument": document, "position": position(at) });
            let result = client.request("textDocument/signatureHelp", params);
            let _ = writeln!(out, "\nsignature help {at:?} after `{}`", before_cursor(&text, at));
            match result.get("signatures") {
                Some(signatures) => {
                    let active = result["activeSignature"].as_u64().unwrap_or(0);
                    for (index, signature) in signatures.as_array().unwrap().iter().enumerate() {
                        let mark = if index as u64 == active { "*" } else { " " };
                        let _ = writeln!(out, " {mark}{}", signature["label"].as_str().unwrap());
                        if let Some(doc) =
                            signature["documentation"]["value"].as_str().or(signature["documentation"].as_str())
                        {
                            for line in doc.lines() {
                                let _ = writeln!(out, "    | {line}");
                            }
                        }
                        let parameter = signature["activeParameter"].as_u64().or(result["activeParameter"].as_u64());
                        if let Some(p) = parameter.filter(|_| index as u64 == active) {
                            let label = match &signature["parameters"][p as usize]["label"] {
                                Value::Array(offsets) => {
                                    // UTF-16 offsets into the signature's label.
                                    let units: Vec<u16> = signature["label"].as_str().unwrap().encode_utf16().collect();
                                    let at = |i: usize| offsets[i].as_u64().unwrap() as usize;
                                    String::from_utf16(&units[at(0)..at(1)]).unwrap()
                                }
                                label => label.as_str().unwrap().to_string(),
                            };
                            let _ = writeln!(out, "    active parameter: `{label}`");
                        }
                    }
                }
                None => out.push_str("  (nothing)\n"),
            }
        }
        if step.tokens {
            let result = client.request("textDocument/semanticTokens/full", json!({ "textDocument": document }));
            out.push_str("\nsemantic tokens\n");
            let legend = client.capabilities["semanticTokensProvider"]["legend"].clone();
            tokens(&mut out, &text, &result["data"], &legend);
        }
        if step.folding {
            let result = client.request("textDocument/foldingRange", json!({ "textDocument": document }));
            out.push_str("\nfolding ranges\n");
            for fold in result.as_array().unwrap() {
                let (start, end) =
                    (fold["startLine"].as_u64().unwrap() as usize, fold["endLine"].as_u64().unwrap() as usize);
                let kind = fold["kind"].as_str().map_or(String::new(), |k| format!(" ({k})"));
                let _ = writeln!(out, "  {start}-{end}{kind}: `{}` … `{}`", lines(&text)[start], lines(&text)[end]);
            }
        }
        if let Some(at) = step.references {
            let params = json!({ "textDocument": document, "position": position(at), "context": { "includeDeclaration": true } });
            let result = client.request("textDocument/references", params);
            let _ = writeln!(out, "\nreferences {at:?} `{}`", word_at(&text, at));
            for location in result.as_array().into_iter().flatten() {
                let line = location["range"]["start"]["line"].as_u64().unwrap() as usize;
                let _ = writeln!(out, "  {} `{}`", show_range(&location["range"]), lines(&text)[line]);
            }
            if result.as_array().is_none_or(|l| l.is_empty()) {
                out.push_str("  (none)\n");
            }
        }
        if let Some(rename) = &step.rename {
            let at = rename.at;
            let prepared = client
                .request("textDocument/prepareRename", json!({ "textDocument": document, "position": position(at) }));
            let _ = writeln!(out, "\nrename {at:?} `{}` to `{}`", word_at(&text, at), rename.to);
            let _ = writeln!(
                out,
                "  prepare: {}",
                if prepared.is_null() {
                    "null".to_string()
                } else {
                    format!(
                        "{} placeholder `{}`",
                        show_range(&prepared["range"]),
                        prepared["placeholder"].as_str().unwrap_or("")
                    )
                }
            );
            let params = json!({ "textDocument": document, "position": position(at), "newName": rename.to });
            match client.try_request("textDocument/rename", params) {
                Ok(result) => {
                    let edits = result["changes"][&uri].as_array().cloned().unwrap_or_default();
                    version += 1;
                    apply(&mut client, &mut out, &mut text, &uri, version, &edits);
                }
                Err(error) => {
                    let _ = writeln!(out, "  refused ({}): {}", error["code"], error["message"].as_str().unwrap());
                }
            }
        }
        if step.inlay {
            let end = [lines(&text).len() as u32, 0];
            let params = json!({ "textDocument": document, "range": range([0, 0], end) });
            let result = client.request("textDocument/inlayHint", params);
            out.push_str("\ninlay hints\n");
            for hint in result.as_array().into_iter().flatten() {
                let p = &hint["position"];
                let line = p["line"].as_u64().unwrap() as usize;
                let label = match &hint["label"] {
                    Value::String(label) => label.clone(),
                    parts => parts.as_array().unwrap().iter().map(|p| p["value"].as_str().unwrap()).collect(),
                };
                let _ = writeln!(out, "  {}:{} `{}` {label}", p["line"], p["character"], lines(&text)[line]);
            }
        }
        if let Some(settings) = &step.settings {
            let settings = serde_json::to_value(settings).unwrap();
            let _ = writeln!(out, "\nsettings {settings}");
            client.notify("workspace/didChangeConfiguration", json!({ "settings": settings }));
            // The re-read is published as a new publish of the same version.
            diagnostics(&mut out, &text, &client.diagnostics(&uri, version));
        }
    }
    let status = client.stop();
    assert!(status.success(), "exit after shutdown: {status}");
    out.push_str("\nshutdown, exit: 0\n");
    out
}

/// Apply an editor's text edits (ranges in the current text) as the editor does: to its
/// text, then as one `didChange` of the edits from the last to the first, so that each
/// range is still where it was; the diagnostics of the new version.
fn apply(client: &mut Client, out: &mut String, text: &mut String, uri: &str, version: i64, edits: &[Value]) {
    let mut edits: Vec<&Value> = edits.iter().collect();
    let at = |p: &Value| [p["line"].as_u64().unwrap() as u32, p["character"].as_u64().unwrap() as u32];
    edits.sort_by_key(|e| std::cmp::Reverse(at(&e["range"]["start"])));
    let mut content = Vec::new();
    for edit in &edits {
        let (from, to) = (at(&edit["range"]["start"]), at(&edit["range"]["end"]));
        let new_text = edit["newText"].as_str().unwrap();
        let _ = writeln!(out, "  edit {from:?}-{to:?} to {new_text:?}");
        let (start, end) = (offset(text, from), offset(text, to));
        text.replace_range(start..end, new_text);
        content.push(json!({ "range": range(from, to), "text": new_text }));
    }
    let params = json!({ "textDocument": { "uri": uri, "version": version }, "contentChanges": content });
    client.notify("textDocument/didChange", params);
    diagnostics(out, text, &client.diagnostics(uri, version));
}

/// The semantic tokens decoded (the protocol's relative encoding), each with its text.
fn tokens(out: &mut String, text: &str, data: &Value, legend: &Value) {
    let data: Vec<u64> = data.as_array().unwrap().iter().map(|v| v.as_u64().unwrap()).collect();
    let types = legend["tokenTypes"].as_array().unwrap();
    let modifiers = legend["tokenModifiers"].as_array().unwrap();
    let (mut line, mut start) = (0u64, 0u64);
    let lines = lines(text);
    for token in data.chunks(5) {
        let [delta_line, delta_start, length, kind, mods] = [token[0], token[1], token[2], token[3], token[4]];
        if delta_line > 0 {
            line += delta_line;
            start = delta_start;
        } else {
            start += delta_start;
        }
        let source = lines[line as usize];
        let from = offset(text, [line as u32, start as u32]) - offset(text, [line as u32, 0]);
        let to = offset(text, [line as u32, (start + length) as u32]) - offset(text, [line as u32, 0]);
        let names: Vec<&str> =
            (0..modifiers.len()).filter(|b| mods & (1 << b) != 0).map(|b| modifiers[b].as_str().unwrap()).collect();
        let names = if names.is_empty() { String::new() } else { format!(" [{}]", names.join(", ")) };
        let _ =
            writeln!(out, "  {line}:{start} `{}` {}{names}", &source[from..to], types[kind as usize].as_str().unwrap());
    }
}

/// The text of the line before a position, for the transcript.
fn before_cursor(text: &str, at: [u32; 2]) -> &str {
    &text[offset(text, [at[0], 0])..offset(text, at)]
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
            d["message"].as_str().unwrap().replace('\n', "\n      ")
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
