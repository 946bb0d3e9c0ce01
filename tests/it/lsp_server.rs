//! The server never panics, whatever the documents and edits, and what it publishes after
//! any sequence of incremental edits is what a full parse of the text gives.
//!
//! The server runs in process (`Server` with a host that has no files) and gets random
//! messages: documents from the round-trip family, changes with ranges anywhere (past the
//! end of a line or of the text, reversed, inside a surrogate pair), hovers, definitions,
//! symbols and formatting at random places. A model of the editor applies each change to
//! its own copy of the text with its own reading of the protocol's positions.

use std::path::{Path, PathBuf};

use lsp_server::{Message, Notification, Request, RequestId};
use proptest::prelude::*;
use serde_json::{Value, json};
use turnpass::dialect::{DialectChoice, GCodeSystem};
use turnpass::lsp::server::{Host, Server};
use turnpass::syntax::{ParseOptions, parse};

use crate::roundtrip::{line, program};

struct NoFiles;

impl Host for NoFiles {
    fn model_file(&self, _: Option<&Path>, _: Option<&Path>) -> Option<(PathBuf, Result<String, String>)> {
        None
    }
}

#[derive(Debug, Clone)]
enum Action {
    Change { from: (u32, u32), to: (u32, u32), text: String },
    Full(String),
    Hover(u32, u32),
    Definition(u32, u32),
    Symbols,
    Formatting,
}

fn text() -> impl Strategy<Value = String> {
    prop_oneof![
        3 => line().prop_map(|l| String::from_utf8_lossy(&l).into_owned()),
        2 => prop::sample::select(vec!["\n", "\r\n", "\r", "°", "𝑥", "%\n", "$ X=1\n", "N0207 G81\n", "G85 N0207 D2\n", ""])
            .prop_map(str::to_string),
    ]
}

fn position() -> impl Strategy<Value = (u32, u32)> {
    (prop_oneof![4 => 0u32..30, 1 => Just(u32::MAX)], prop_oneof![4 => 0u32..40, 1 => Just(u32::MAX)])
}

fn action() -> impl Strategy<Value = Action> {
    prop_oneof![
        8 => (position(), position(), text()).prop_map(|(from, to, text)| Action::Change { from, to, text }),
        1 => program().prop_map(|p| Action::Full(String::from_utf8_lossy(&p).into_owned())),
        2 => position().prop_map(|(l, c)| Action::Hover(l, c)),
        2 => position().prop_map(|(l, c)| Action::Definition(l, c)),
        1 => Just(Action::Symbols),
        1 => Just(Action::Formatting),
    ]
}

/// The editor's reading of a position: a line past the last is the end of the text, a
/// column past the end of its line is the line's end, a column inside a surrogate pair is
/// the start of its character.
fn offset(text: &str, (line, column): (u32, u32)) -> usize {
    let mut start = 0;
    for _ in 0..line {
        match text[start..].find(['\n', '\r']) {
            Some(at) => {
                let at = start + at;
                start = if text[at..].starts_with("\r\n") { at + 2 } else { at + 1 };
            }
            None => return text.len(),
        }
    }
    let end = text[start..].find(['\n', '\r']).map_or(text.len(), |at| start + at);
    let mut units = 0u64;
    for (at, c) in text[start..end].char_indices() {
        if units + c.len_utf16() as u64 > column as u64 {
            return start + at;
        }
        units += c.len_utf16() as u64;
    }
    end
}

fn notification(method: &str, params: Value) -> Message {
    Message::Notification(Notification::new(method.to_string(), params))
}

fn request(id: i32, method: &str, params: Value) -> Message {
    Message::Request(Request::new(RequestId::from(id), method.to_string(), params))
}

/// Let the server publish, running its semantic passes in place; the last publish.
fn settle(server: &mut Server<NoFiles>) -> Option<Value> {
    let (mut messages, jobs) = server.idle();
    for job in jobs {
        messages.extend(server.finished(job.run()));
    }
    messages.into_iter().rev().find_map(|m| match m {
        Message::Notification(n) if n.method == "textDocument/publishDiagnostics" => Some(n.params),
        _ => None,
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn the_server_follows_any_edits_without_panicking(
        source in program(),
        actions in prop::collection::vec(action(), 1..16),
    ) {
        let uri = "file:///work/part.nc";
        let (mut server, _, _) = Server::initialize(NoFiles, json!({ "capabilities": {} }));
        let mut text = String::from_utf8_lossy(&source).into_owned();
        let item = json!({ "uri": uri, "languageId": "gcode", "version": 1, "text": text });
        server.handle(notification("textDocument/didOpen", json!({ "textDocument": item })));
        let options = ParseOptions { dialect: DialectChoice::Auto, gcode_system: GCodeSystem::A, machine_kind: None, control: Default::default() };
        for (index, action) in actions.into_iter().enumerate() {
            let version = index as i32 + 2;
            let document = json!({ "uri": uri });
            let at = |(line, character): (u32, u32)| json!({ "line": line, "character": character });
            let replies = match action {
                Action::Change { from, to, text: inserted } => {
                    let start = offset(&text, from);
                    let end = offset(&text, to).max(start);
                    text.replace_range(start..end, &inserted);
                    let change = json!({ "range": { "start": at(from), "end": at(to) }, "text": inserted });
                    let params = json!({ "textDocument": { "uri": uri, "version": version }, "contentChanges": [change] });
                    server.handle(notification("textDocument/didChange", params))
                }
                Action::Full(new) => {
                    text = new;
                    let params = json!({ "textDocument": { "uri": uri, "version": version }, "contentChanges": [{ "text": text }] });
                    server.handle(notification("textDocument/didChange", params))
                }
                Action::Hover(line, character) => server.handle(request(
                    version, "textDocument/hover", json!({ "textDocument": document, "position": at((line, character)) }))),
                Action::Definition(line, character) => server.handle(request(
                    version, "textDocument/definition", json!({ "textDocument": document, "position": at((line, character)) }))),
                Action::Symbols => server.handle(request(version, "textDocument/documentSymbol", json!({ "textDocument": document }))),
                Action::Formatting => server.handle(request(
                    version, "textDocument/formatting", json!({ "textDocument": document, "options": { "tabSize": 4, "insertSpaces": true } }))),
            };
            for reply in replies {
                if let Message::Response(response) = reply {
                    prop_assert!(response.response_result.is_ok(), "{:?}", response);
                }
            }
            if let Some(published) = settle(&mut server) {
                let full = parse(text.as_bytes(), &options);
                let expected: Vec<(String, u32, u32)> =
                    full.diagnostics.iter().map(|d| (d.code().to_string(), d.span.start, d.span.end)).collect();
                let got: Vec<(String, u32, u32)> = published["diagnostics"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .filter(|d| d["data"]["pass"] == "syntax")
                    .map(|d| {
                        let offset = |end: &str| d["data"]["offset"][end].as_u64().unwrap() as u32;
                        (d["code"].as_str().unwrap().to_string(), offset("start"), offset("end"))
                    })
                    .collect();
                prop_assert_eq!(got, expected, "{:?}", text);
            }
        }
        let closed = server.handle(notification("textDocument/didClose", json!({ "textDocument": { "uri": uri } })));
        prop_assert_eq!(closed.len(), 1, "the diagnostics are cleared");
    }
}

/// The codes and byte offsets of a publish, each marked with its pass.
fn published(messages: &[Message]) -> Vec<Vec<(String, String, u64)>> {
    messages
        .iter()
        .filter_map(|m| match m {
            Message::Notification(n) if n.method == "textDocument/publishDiagnostics" => Some(&n.params),
            _ => None,
        })
        .map(|params| {
            params["diagnostics"]
                .as_array()
                .unwrap()
                .iter()
                .map(|d| {
                    let pass = d["data"]["pass"].as_str().unwrap().to_string();
                    (pass, d["code"].as_str().unwrap().to_string(), d["data"]["offset"]["start"].as_u64().unwrap())
                })
                .collect()
        })
        .collect()
}

/// Above `semanticInlineLimit` the semantic pass runs as a job on its own: the parse's
/// diagnostics are published at once with the previous semantic ones moved across the
/// edits, a result for a version the editor has left is dropped, and the next one is
/// published when it comes.
#[test]
fn large_programs_get_their_semantic_diagnostics_from_a_job() {
    let uri = "file:///work/big.nc";
    let init = json!({ "capabilities": {}, "initializationOptions": { "semanticInlineLimit": 0, "dialect": "fanuc" } });
    let (mut server, _, messages) = Server::initialize(NoFiles, init);
    assert!(messages.is_empty(), "{messages:?}");
    let text = "G00 X60. Z2.\nG71 U2. R0.5\nG71 P10 Q21 U0.4 W0.1 F0.25\nN10 G01 X20.\nN20 X60.\n";
    let missing = text.find("Q21").unwrap() as u64;
    let item = json!({ "uri": uri, "languageId": "gcode", "version": 1, "text": text });
    server.handle(notification("textDocument/didOpen", json!({ "textDocument": item })));

    // Version 1: the parse's diagnostics now (none), the job's when it is done.
    let (messages, jobs) = server.idle();
    assert_eq!(published(&messages), vec![vec![]]);
    assert_eq!(jobs.len(), 1);
    assert!(!jobs[0].inline);
    let first = server.finished(jobs[0].run());
    let semantic = published(&first);
    assert_eq!(semantic.len(), 1);
    assert!(semantic[0].contains(&("semantic".to_string(), "missing-sequence".to_string(), missing)), "{semantic:?}");

    // Version 2: a line typed at the top moves the semantic diagnostics in the publish at
    // once; the job for version 2 is overtaken by version 3 and its result dropped.
    let change = |version: i32, text: &str| {
        let range = json!({ "start": { "line": 0, "character": 0 }, "end": { "line": 0, "character": 0 } });
        let params = json!({ "textDocument": { "uri": uri, "version": version }, "contentChanges": [{ "range": range, "text": text }] });
        notification("textDocument/didChange", params)
    };
    server.handle(change(2, "G97 S500\n"));
    let (messages, jobs) = server.idle();
    let interim = published(&messages);
    assert!(interim[0].contains(&("semantic".to_string(), "missing-sequence".to_string(), missing + 9)), "{interim:?}");
    server.handle(change(3, "M03\n"));
    assert!(server.finished(jobs[0].run()).is_empty(), "a result for version 2 is not published at version 3");
    let (messages, jobs) = server.idle();
    assert!(jobs.len() == 1 && published(&messages).len() == 1);
    let last = published(&server.finished(jobs[0].run()));
    assert!(last[0].contains(&("semantic".to_string(), "missing-sequence".to_string(), missing + 13)), "{last:?}");
}

/// A document closed and opened again starts its versions anew: a semantic job started for
/// the first opening must not be published for the second, even when the version numbers
/// are the same.
#[test]
fn a_result_for_a_closed_document_is_not_published_after_it_is_reopened() {
    let uri = "file:///work/reopened.nc";
    let init = json!({ "capabilities": {}, "initializationOptions": { "semanticInlineLimit": 0, "dialect": "fanuc" } });
    let (mut server, _, _) = Server::initialize(NoFiles, init);
    let open = |text: &str| {
        let item = json!({ "uri": uri, "languageId": "gcode", "version": 1, "text": text });
        notification("textDocument/didOpen", json!({ "textDocument": item }))
    };
    let broken = "G00 X60. Z2.\nG71 U2. R0.5\nG71 P10 Q21 U0.4 W0.1 F0.25\nN10 G01 X20.\nN20 X60.\n";
    server.handle(open(broken));
    let (_, first_jobs) = server.idle();
    assert_eq!(first_jobs.len(), 1);
    server.handle(notification("textDocument/didClose", json!({ "textDocument": { "uri": uri } })));

    // Opened again at version 1 with the Q target fixed: the first opening's result, which
    // reports the missing N21, is dropped, and the new job's is published.
    let fixed = broken.replace("Q21", "Q20");
    server.handle(open(&fixed));
    let (_, jobs) = server.idle();
    assert_eq!(jobs.len(), 1);
    assert!(server.finished(first_jobs[0].run()).is_empty(), "a result for the closed document is dropped");
    let published = published(&server.finished(jobs[0].run()));
    assert_eq!(published.len(), 1);
    assert!(!published[0].is_empty(), "the fixed program still starts from an unknown position");
    assert!(published[0].iter().all(|(_, code, _)| code != "missing-sequence"), "{published:?}");
}
