//! A minimal Language Server Protocol client: it starts `turnpass lsp` as a subprocess and
//! speaks JSON-RPC to it over its standard input and output, as an editor does.

use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, Command, ExitStatus, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::Duration;

use serde_json::{Value, json};

/// How long any answer may take before the test fails: a debug build on a busy machine runs
/// the part model some 40 times slower than a release build, and the 0.001 mm G71 of
/// `tests/cases/bounded/` (320,000 moves, 71 million ray visits) takes 1.8 s in release and
/// 72 s in debug on an idle machine.
const PATIENCE: Duration = Duration::from_secs(300);

pub struct Client {
    child: Child,
    stdin: ChildStdin,
    incoming: Receiver<Value>,
    next_id: i64,
    /// Notifications received while waiting for something else.
    pub notifications: Vec<Value>,
    /// What the server answered to `initialize`.
    pub capabilities: Value,
}

impl Client {
    /// Start the server and complete the `initialize` handshake.
    pub fn start(initialization_options: Value) -> Client {
        Client::start_with(initialization_options, json!({}))
    }

    /// [`Client::start`] for a client that announces `capabilities`.
    pub fn start_with(initialization_options: Value, capabilities: Value) -> Client {
        let mut child = Command::new(env!("CARGO_BIN_EXE_turnpass"))
            .arg("lsp")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .unwrap();
        let stdin = child.stdin.take().unwrap();
        let stdout = child.stdout.take().unwrap();
        let (sender, incoming) = channel();
        std::thread::spawn(move || {
            let mut reader = BufReader::new(stdout);
            while let Some(message) = read_message(&mut reader) {
                if sender.send(message).is_err() {
                    break;
                }
            }
        });
        let mut client =
            Client { child, stdin, incoming, next_id: 0, notifications: Vec::new(), capabilities: Value::Null };
        let params = json!({
            "processId": null,
            "rootUri": null,
            "capabilities": capabilities,
            "initializationOptions": initialization_options,
        });
        let result = client.request("initialize", params);
        assert_eq!(result["capabilities"]["textDocumentSync"], json!(2), "incremental sync");
        client.capabilities = result["capabilities"].clone();
        client.notify("initialized", json!({}));
        client
    }

    pub fn notify(&mut self, method: &str, params: Value) {
        self.send(&json!({ "jsonrpc": "2.0", "method": method, "params": params }));
    }

    /// Send a request and wait for its response; returns its result.
    pub fn request(&mut self, method: &str, params: Value) -> Value {
        match self.try_request(method, params) {
            Ok(result) => result,
            Err(error) => panic!("{method}: {error}"),
        }
    }

    /// Send a request and wait for its response: its result, or its error.
    pub fn try_request(&mut self, method: &str, params: Value) -> Result<Value, Value> {
        self.next_id += 1;
        let id = self.next_id;
        self.send(&json!({ "jsonrpc": "2.0", "id": id, "method": method, "params": params }));
        loop {
            let message = self.receive(&format!("the response to {method}"));
            if message.get("id") == Some(&json!(id)) {
                return match message.get("error") {
                    Some(error) => Err(error.clone()),
                    None => Ok(message["result"].clone()),
                };
            }
            self.notifications.push(message);
        }
    }

    /// Wait for the diagnostics published for `uri` at `version`.
    pub fn diagnostics(&mut self, uri: &str, version: i64) -> Vec<Value> {
        let matches = |m: &Value| {
            m["method"] == "textDocument/publishDiagnostics"
                && m["params"]["uri"] == uri
                && m["params"]["version"] == json!(version)
        };
        if let Some(at) = self.notifications.iter().position(matches) {
            return self.notifications.remove(at)["params"]["diagnostics"].as_array().unwrap().clone();
        }
        loop {
            let message = self.receive(&format!("diagnostics for {uri} version {version}"));
            if matches(&message) {
                return message["params"]["diagnostics"].as_array().unwrap().clone();
            }
            self.notifications.push(message);
        }
    }

    /// The `window/logMessage` notifications received so far, taken out of the queue.
    pub fn log_messages(&mut self) -> Vec<Value> {
        let (logs, others) =
            std::mem::take(&mut self.notifications).into_iter().partition(|m| m["method"] == "window/logMessage");
        self.notifications = others;
        logs
    }

    /// `shutdown`, then `exit`; the server's exit status.
    pub fn stop(mut self) -> ExitStatus {
        assert_eq!(self.request("shutdown", Value::Null), Value::Null);
        self.notify("exit", Value::Null);
        let status = self.child.wait().unwrap();
        assert!(
            !self.notifications.iter().any(|m| m["method"] == "window/showMessage"),
            "the server complained: {:?}",
            self.notifications
        );
        status
    }

    fn send(&mut self, message: &Value) {
        let body = serde_json::to_vec(message).unwrap();
        write!(self.stdin, "Content-Length: {}\r\n\r\n", body.len()).unwrap();
        self.stdin.write_all(&body).unwrap();
        self.stdin.flush().unwrap();
    }

    fn receive(&mut self, what: &str) -> Value {
        match self.incoming.recv_timeout(PATIENCE) {
            Ok(message) => message,
            Err(error) => panic!("waiting for {what}: {error}; got so far {:?}", self.notifications),
        }
    }
}

fn read_message(reader: &mut impl BufRead) -> Option<Value> {
    let mut length = None;
    loop {
        let mut line = String::new();
        if reader.read_line(&mut line).ok()? == 0 {
            return None;
        }
        let line = line.trim_end();
        if line.is_empty() {
            break;
        }
        if let Some(value) = line.strip_prefix("Content-Length:") {
            length = value.trim().parse::<usize>().ok();
        }
    }
    let mut body = vec![0; length?];
    reader.read_exact(&mut body).ok()?;
    serde_json::from_slice(&body).ok()
}

/// A `file:` URI for a path (the test paths need no percent-encoding but spaces).
pub fn file_uri(path: &std::path::Path) -> String {
    format!("file://{}", path.display().to_string().replace(' ', "%20"))
}
