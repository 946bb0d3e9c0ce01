//! The server's manners on the wire, driven by `tests/cases/lsp/protocol/*.toml`: frames as
//! a hostile or a dying client writes them, and what the server answers, byte-exact.
//!
//! A case is a list of steps, each one thing written to the server's standard input:
//!
//! - `body = '…'`: a frame with this body and its correct `Content-Length`;
//! - `raw = '…'`: these bytes as they are, header and all;
//! - `nested = N`: a frame whose body is `[` N times and `]` N times;
//! - `request = { method = …, params = … }`, `notify = { … }`: a message, framed;
//! - `close = true`: close the input.
//!
//! In `body` and `raw`, `\r`, `\n` and `\xNN` stand for CR, LF and the byte NN (so that a
//! case can hold bytes that are not UTF-8). Unless `handshake = false`, the session starts
//! with `initialize` and `initialized`.
//!
//! After each step the test sends a probe (a request for a method no server has) and
//! records everything the server writes until the probe's answer, the end of its output
//! (then its exit code), or [`PATIENCE`] of silence (then the server is wedged: the case
//! says so and the server is killed). Every session ends by closing the input: a server
//! still running [`PATIENCE`] after that lingers, and the transcript says so.

use std::fmt::Write as _;
use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::Duration;

use serde::Deserialize;
use serde_json::{Value, json};

use crate::support::{repo, with_snapshots};

/// How long the server may stay silent before it counts as wedged.
const PATIENCE: Duration = Duration::from_secs(10);

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Case {
    #[serde(default = "yes")]
    handshake: bool,
    #[serde(default)]
    init: toml::Table,
    #[serde(default)]
    step: Vec<Step>,
}

fn yes() -> bool {
    true
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Step {
    body: Option<String>,
    raw: Option<String>,
    nested: Option<usize>,
    request: Option<Call>,
    notify: Option<Call>,
    #[serde(default)]
    close: bool,
}

#[derive(Deserialize)]
struct Call {
    method: String,
    #[serde(default)]
    params: Option<toml::Value>,
}

/// What the server wrote: a message, or the end of its output.
enum Output {
    Message(Value),
    /// Bytes that are no frame (the transcript shows them).
    Garbage(String),
    End,
}

struct Session {
    child: Child,
    stdin: Option<ChildStdin>,
    incoming: Receiver<Output>,
    next_id: i64,
    out: String,
    /// The server exited or was killed: nothing more to send or wait for.
    over: bool,
}

#[test]
fn protocol_sessions() {
    let dir = repo().join("tests/cases/lsp/protocol");
    let cases = crate::support::case_files(&dir, "toml");
    assert!(!cases.is_empty());
    // Each session waits on a process: run them side by side.
    let transcripts: Vec<(String, String)> = std::thread::scope(|scope| {
        let handles: Vec<_> = cases
            .iter()
            .map(|case| {
                scope.spawn(move || {
                    let name = case.file_stem().unwrap().to_string_lossy().into_owned();
                    let case: Case = toml::from_str(&std::fs::read_to_string(case).unwrap())
                        .unwrap_or_else(|e| panic!("{name}: {e}"));
                    (name, run(&case))
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    // Every case is compared, and the failures are named together.
    let mut failed = Vec::new();
    for (name, transcript) in transcripts {
        let outcome = std::panic::catch_unwind(|| {
            with_snapshots("lsp/protocol", || insta::assert_snapshot!(name.clone(), transcript));
        });
        if outcome.is_err() {
            failed.push(name);
        }
    }
    assert!(failed.is_empty(), "protocol cases that failed: {failed:?}");
}

fn run(case: &Case) -> String {
    let mut child = Command::new(env!("CARGO_BIN_EXE_turnpass"))
        .arg("lsp")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let stdin = child.stdin.take();
    let stdout = child.stdout.take().unwrap();
    let (sender, incoming) = channel();
    std::thread::spawn(move || {
        let mut reader = BufReader::new(stdout);
        loop {
            let output = read_output(&mut reader);
            let end = matches!(output, Output::End | Output::Garbage(_));
            if sender.send(output).is_err() || end {
                break;
            }
        }
    });
    let mut session = Session { child, stdin, incoming, next_id: 0, out: String::new(), over: false };
    if case.handshake {
        session.next_id += 1;
        let params = json!({ "processId": null, "rootUri": null, "capabilities": {},
                             "initializationOptions": serde_json::to_value(&case.init).unwrap() });
        session.write(&frame(
            &json!({ "jsonrpc": "2.0", "id": session.next_id, "method": "initialize", "params": params }),
        ));
        match session.incoming.recv_timeout(PATIENCE * 6) {
            Ok(Output::Message(m)) if m.get("result").is_some() => {}
            _ => panic!("no answer to initialize"),
        }
        session.write(&frame(&json!({ "jsonrpc": "2.0", "method": "initialized", "params": {} })));
        session.out.push_str("initialize, initialized\n");
    }
    for step in &case.step {
        if session.over {
            break;
        }
        session.step(step);
    }
    if !session.over {
        session.out.push_str("\nclose the input\n");
        session.stdin = None;
        session.drain(None);
    }
    let mut stderr = String::new();
    if let Some(mut err) = session.child.stderr.take() {
        let _ = err.read_to_string(&mut stderr);
    }
    for line in stderr.lines() {
        let _ = writeln!(session.out, "  stderr: {line}");
    }
    session.out
}

impl Session {
    fn step(&mut self, step: &Step) {
        if let Some(body) = &step.body {
            let _ = writeln!(self.out, "\nsend a frame with the body {}", shown(body));
            let body = bytes(body);
            let mut framed = format!("Content-Length: {}\r\n\r\n", body.len()).into_bytes();
            framed.extend(body);
            self.write(&framed);
        }
        if let Some(raw) = &step.raw {
            let _ = writeln!(self.out, "\nsend the bytes {}", shown(raw));
            self.write(&bytes(raw));
        }
        if let Some(depth) = step.nested {
            let _ = writeln!(self.out, "\nsend a frame whose body is {depth} `[` and {depth} `]`");
            let body = format!("{}{}", "[".repeat(depth), "]".repeat(depth));
            self.write(&frame_bytes(body.as_bytes()));
        }
        if let Some(call) = &step.request {
            self.next_id += 1;
            let params = call.params.as_ref().map_or(Value::Null, |p| serde_json::to_value(p).unwrap());
            let _ = writeln!(self.out, "\nrequest {} {}", call.method, params);
            self.write(&frame(
                &json!({ "jsonrpc": "2.0", "id": self.next_id, "method": call.method, "params": params }),
            ));
        }
        if let Some(call) = &step.notify {
            let params = call.params.as_ref().map_or(Value::Null, |p| serde_json::to_value(p).unwrap());
            let _ = writeln!(self.out, "\nnotify {} {}", call.method, params);
            self.write(&frame(&json!({ "jsonrpc": "2.0", "method": call.method, "params": params })));
        }
        if step.close {
            self.out.push_str("\nclose the input\n");
            self.stdin = None;
            self.drain(None);
            return;
        }
        let probe = format!("probe-{}", self.next_id);
        self.write(&frame(&json!({ "jsonrpc": "2.0", "id": probe, "method": "test/probe" })));
        self.drain(Some(&probe));
    }

    /// Write to the server; a server that has closed its input has exited or will (the
    /// transcript records that), so a broken pipe is not the test's failure.
    fn write(&mut self, bytes: &[u8]) {
        if let Some(stdin) = self.stdin.as_mut() {
            let _ = stdin.write_all(bytes).and_then(|()| stdin.flush());
        }
    }

    /// Record what the server writes until the probe's answer, the end of its output, or
    /// silence.
    fn drain(&mut self, probe: Option<&str>) {
        loop {
            match self.incoming.recv_timeout(PATIENCE) {
                Ok(Output::Message(message)) => {
                    if probe.is_some_and(|p| message["id"] == json!(p)) {
                        return;
                    }
                    self.out.push_str(&describe(&message));
                }
                Ok(Output::Garbage(text)) => {
                    let _ = writeln!(self.out, "  ← bytes that are no frame: {text}");
                    self.finish();
                    return;
                }
                Ok(Output::End) | Err(RecvTimeoutError::Disconnected) => {
                    self.finish();
                    return;
                }
                Err(RecvTimeoutError::Timeout) => {
                    let _ = writeln!(self.out, "  (silent for {} s: the server is wedged; killed)", PATIENCE.as_secs());
                    let _ = self.child.kill();
                    let _ = self.child.wait();
                    self.over = true;
                    return;
                }
            }
        }
    }

    /// The server's output ended: its exit code, if it exits in time.
    fn finish(&mut self) {
        self.over = true;
        let deadline = std::time::Instant::now() + PATIENCE;
        loop {
            if let Some(status) = self.child.try_wait().unwrap() {
                let _ =
                    writeln!(self.out, "  exit {}", status.code().map_or("by a signal".to_string(), |c| c.to_string()));
                return;
            }
            if std::time::Instant::now() > deadline {
                let _ = writeln!(self.out, "  (output closed, still running after {} s; killed)", PATIENCE.as_secs());
                let _ = self.child.kill();
                let _ = self.child.wait();
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

/// One received message as a transcript line: errors with their code and message, results
/// as JSON, notifications by method.
fn describe(message: &Value) -> String {
    if let Some(error) = message.get("error") {
        return format!(
            "  ← error {} (id {}): {}\n",
            error["code"],
            message["id"],
            error["message"].as_str().unwrap_or("")
        );
    }
    if let Some(result) = message.get("result") {
        if let Some(server) = result.get("serverInfo") {
            return format!("  ← result (id {}): the server's capabilities ({})\n", message["id"], server["name"]);
        }
        return format!("  ← result (id {}): {result}\n", message["id"]);
    }
    format!("  ← {} {}\n", message["method"].as_str().unwrap_or("?"), message["params"])
}

fn read_output(reader: &mut impl BufRead) -> Output {
    let mut length = None;
    loop {
        let mut line = String::new();
        match reader.read_line(&mut line) {
            Ok(0) | Err(_) => return Output::End,
            Ok(_) => {}
        }
        if !line.ends_with("\r\n") {
            return Output::Garbage(format!("{line:?}"));
        }
        let line = line.trim_end();
        if line.is_empty() {
            break;
        }
        match line.strip_prefix("Content-Length: ") {
            Some(value) => length = value.parse::<usize>().ok(),
            None => return Output::Garbage(format!("{line:?}")),
        }
    }
    let Some(length) = length else { return Output::Garbage("a frame with no Content-Length".into()) };
    let mut body = vec![0; length];
    if reader.read_exact(&mut body).is_err() {
        return Output::End;
    }
    match serde_json::from_slice(&body) {
        Ok(value) => Output::Message(value),
        Err(e) => Output::Garbage(format!("{e}: {:?}", String::from_utf8_lossy(&body))),
    }
}

fn frame(message: &Value) -> Vec<u8> {
    frame_bytes(&serde_json::to_vec(message).unwrap())
}

fn frame_bytes(body: &[u8]) -> Vec<u8> {
    let mut out = format!("Content-Length: {}\r\n\r\n", body.len()).into_bytes();
    out.extend_from_slice(body);
    out
}

/// The bytes a case's text stands for: `\r`, `\n`, `\xNN` decoded, the rest as UTF-8.
fn bytes(text: &str) -> Vec<u8> {
    let mut out = Vec::new();
    let mut rest = text.as_bytes();
    while let Some((&first, tail)) = rest.split_first() {
        rest = match (first, tail) {
            (b'\\', [b'r', after @ ..]) => {
                out.push(b'\r');
                after
            }
            (b'\\', [b'n', after @ ..]) => {
                out.push(b'\n');
                after
            }
            (b'\\', [b'x', high, low, after @ ..]) => {
                let hex = std::str::from_utf8(&[*high, *low]).unwrap().to_string();
                out.push(u8::from_str_radix(&hex, 16).unwrap());
                after
            }
            _ => {
                out.push(first);
                tail
            }
        };
    }
    out
}

/// A case's text for the transcript, at most 100 characters.
fn shown(text: &str) -> String {
    let mut shown: String = text.chars().take(100).collect();
    if text.chars().count() > 100 {
        shown.push('…');
    }
    format!("`{shown}`")
}
