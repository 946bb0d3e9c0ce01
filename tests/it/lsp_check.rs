//! `turnpass check --format json` and `turnpass lsp` report the same diagnostics, the
//! parse's and the semantic pass's: the same codes, messages (the server's with the hint
//! on a second line), severities, hints and related labels, and the same ranges (the
//! JSON's byte offsets are the server's `data.offset`; its 1-based line is the server's
//! 0-based line plus one; the server's UTF-16 columns are those of the same bytes, a start
//! rounded down and an end rounded up to whole characters).
//!
//! Every program under `tests/cases/` and `examples/programs/` that is UTF-8 (an editor
//! sends text, so a Shift-JIS file reaches the server re-encoded) goes through both;
//! check's warning on a program with no block to run is its own (see below).

use std::path::PathBuf;
use std::process::Command;

use serde_json::{Value, json};

use crate::lsp_client::{Client, file_uri};
use crate::support::repo;

fn programs() -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut pending = vec![repo().join("tests/cases"), repo().join("examples/programs")];
    while let Some(dir) = pending.pop() {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                pending.push(path);
            } else if path.extension().is_some_and(|e| ["nc", "min", "ssb", "sub", "NC", "MIN"].iter().any(|x| e == *x))
                && std::str::from_utf8(&std::fs::read(&path).unwrap()).is_ok()
            {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// UTF-16 units of `line[..offset]`, an offset inside a character counting it when `up`.
fn units(line: &str, offset: usize, up: bool) -> u64 {
    line.char_indices()
        .take_while(|(at, c)| if up { *at < offset } else { at + c.len_utf8() <= offset })
        .map(|(_, c)| c.len_utf16() as u64)
        .sum()
}

#[test]
fn check_json_and_the_server_agree() {
    let files = programs();
    assert!(files.len() > 40, "{} programs", files.len());
    let output = Command::new(env!("CARGO_BIN_EXE_turnpass"))
        .args(["check", "--format", "json"])
        .args(&files)
        .current_dir(repo())
        .output()
        .unwrap();
    let json: Vec<Value> = serde_json::from_slice(&output.stdout).unwrap();
    // Every diagnostic, as check lists them all: the server's default shows the first 200.
    let mut client = Client::start(json!({ "maxDiagnostics": 0 }));
    let (mut compared, mut semantic) = (0, 0);
    for path in &files {
        let text = std::fs::read_to_string(path).unwrap();
        let uri = file_uri(path);
        let item = json!({ "uri": uri, "languageId": "gcode", "version": 1, "text": text });
        client.notify("textDocument/didOpen", json!({ "textDocument": item }));
        let published = client.diagnostics(&uri, 1);
        client.notify("textDocument/didClose", json!({ "textDocument": { "uri": uri } }));
        let name = path.display().to_string();
        // `empty-program` and `program-cut` are check's findings about the whole file, not a
        // parse diagnostic: the server leaves an empty buffer quiet, as an editor's new file
        // is, and a buffer that ends in the middle of a block, as one being typed does.
        let mut expected: Vec<&Value> = json
            .iter()
            .filter(|d| d["file"] == name && d["code"] != "empty-program" && d["code"] != "program-cut")
            .collect();
        semantic += published.iter().filter(|d| d["data"]["pass"] == "semantic").count();
        // Both in the order of their spans, then codes and messages (the server merges the
        // two passes' lists; check sorts one list).
        let key = |offset: &Value, d: &Value| {
            (offset["start"].as_u64(), offset["end"].as_u64(), d["code"].to_string(), d["message"].to_string())
        };
        let mut all: Vec<&Value> = published.iter().collect();
        // The server's message without its hint line, as check's message is.
        let first_line =
            |d: &Value| json!({ "code": d["code"], "message": d["message"].as_str().unwrap().lines().next() });
        all.sort_by_key(|d| key(&d["data"]["offset"], &first_line(d)));
        expected.sort_by_key(|d| {
            key(&json!({ "start": d["range"]["start"]["offset"], "end": d["range"]["end"]["offset"] }), d)
        });
        assert_eq!(all.len(), expected.len(), "{name}: {published:#?}\n{expected:#?}");
        let line_starts: Vec<usize> =
            std::iter::once(0).chain(text.match_indices('\n').map(|(at, _)| at + 1)).collect();
        for (lsp, check) in all.iter().zip(&expected) {
            let context = format!("{name}: {lsp:#}\n{check:#}");
            assert_eq!(lsp["code"], check["code"], "{context}");
            // The server's message is check's, its hint on a second line and how many more
            // times the run found it (`repeats`) on a line of its own.
            let mut message = check["message"].as_str().unwrap().to_string();
            if let Some(hint) = check["hint"].as_str() {
                message.push_str(&format!("\nhint: {hint}"));
            }
            if let Some(repeats) = check["repeats"].as_u64() {
                let s = if repeats == 1 { "" } else { "s" };
                message.push_str(&format!(
                    "\nfound {repeats} more time{s} as the run comes back to this place; shown once"
                ));
            }
            let message = json!(message);
            assert_eq!(lsp["message"], message, "{context}");
            let severity = match check["severity"].as_str().unwrap() {
                "error" => 1,
                "warning" => 2,
                _ => 3,
            };
            assert_eq!(lsp["severity"], json!(severity), "{context}");
            assert_eq!(lsp["data"]["label"], check["label"], "{context}");
            assert_eq!(lsp["data"]["hint"], check["hint"], "{context}");
            for (end, up) in [("start", false), ("end", true)] {
                let offset = check["range"][end]["offset"].as_u64().unwrap() as usize;
                assert_eq!(lsp["data"]["offset"][end], json!(offset), "{context}");
                let line = check["range"][end]["line"].as_u64().unwrap() - 1;
                assert_eq!(lsp["range"][end]["line"], json!(line), "{context}");
                let start = line_starts[line as usize];
                let text_line = text[start..].split(['\n', '\r']).next().unwrap();
                let character = units(text_line, offset - start, up);
                assert_eq!(lsp["range"][end]["character"], json!(character), "{context}");
                if text_line.is_ascii() {
                    assert_eq!(character + 1, check["range"][end]["column"].as_u64().unwrap(), "{context}");
                }
            }
            let related: Vec<Value> =
                check["related"].as_array().unwrap().iter().map(|r| r["message"].clone()).collect();
            let server: Vec<Value> = lsp["relatedInformation"]
                .as_array()
                .map(|list| list.iter().map(|r| r["message"].clone()).collect())
                .unwrap_or_default();
            assert_eq!(server, related, "{context}");
            compared += 1;
        }
    }
    assert!(client.stop().success());
    // Enough of both kinds that the comparison means something.
    assert!(compared > 100 && semantic > 10, "{compared} diagnostics compared, {semantic} semantic ones");
}
