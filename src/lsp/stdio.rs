//! The server's I/O layer: the stdio connection, the message loop, the worker threads of
//! the semantic pass, and the file system (finding and reading `turnpass.toml`).
//!
//! This is the only module of the language server that touches files or standard streams,
//! as `main.rs`/`cli.rs` are for the other commands; `clippy.toml` bans those calls in the
//! library and the lint is allowed here alone.
//!
//! **Never wedged.** One thread reads frames (`frame.rs`) and hands each to the loop, with
//! the end of the input as an event of its own: when the editor dies or closes the pipe
//! without `exit`, the loop ends and the process exits (1 without `shutdown`). A frame that
//! is no message is answered with a JSON-RPC error and the loop goes on; a header that does
//! not read is answered with a parse error and ends the connection (exit 2), because the
//! next frame cannot be found.

#![allow(clippy::disallowed_methods)]

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::mpsc;

use lsp_server::{ErrorCode, Message, Request, RequestId, Response};
use lsp_types::request::{Initialize, Request as _};

use super::frame::{self, Frame};
use super::server::{Host, JobResult, Server};

/// Reads settings and programs from the file system.
struct Files;

impl Host for Files {
    fn model_file(&self, program: Option<&Path>, model: Option<&Path>) -> Option<(PathBuf, Result<String, String>)> {
        let path = match model {
            Some(model) => model.to_path_buf(),
            None => {
                let directory = std::fs::canonicalize(program?).ok()?.parent()?.to_path_buf();
                directory.ancestors().map(|d| d.join("turnpass.toml")).find(|p| p.is_file())?
            }
        };
        let text = read_settings(&path);
        Some((path, text))
    }

    fn programs_beside(&self, program: &Path) -> Vec<PathBuf> {
        let Some(folder) = program.parent() else { return Vec::new() };
        let Ok(entries) = std::fs::read_dir(folder) else { return Vec::new() };
        let mut found: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p != program && is_program_file(p))
            .take(MAX_PROGRAMS_BESIDE)
            .collect();
        found.sort();
        found
    }

    fn read_program(&self, path: &Path) -> Option<Vec<u8>> {
        let size = std::fs::metadata(path).ok()?.len();
        if size > MAX_PROGRAM_BESIDE_BYTES {
            return None;
        }
        std::fs::read(path).ok()
    }
}

/// A settings or model file's text, read no further than the command line's input limit
/// (`source::DEFAULT_INPUT_LIMIT_MIB`): a `/dev/zero` named as the model is an error, not
/// a server that reads until memory runs out.
fn read_settings(path: &Path) -> Result<String, String> {
    let limit = crate::source::DEFAULT_INPUT_LIMIT_MIB << 20;
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    match crate::source::read_at_most(file, limit) {
        Ok(Some(bytes)) => String::from_utf8(bytes).map_err(|_| "stream did not contain valid UTF-8".to_string()),
        Ok(None) => Err(format!(
            "larger than {} MiB, the most turnpass reads of an input",
            crate::source::DEFAULT_INPUT_LIMIT_MIB
        )),
        Err(e) => Err(e.to_string()),
    }
}

/// How many files of a folder a definition looks through for a subprogram, and the largest
/// it reads: a definition must answer while the user waits.
const MAX_PROGRAMS_BESIDE: usize = 500;
const MAX_PROGRAM_BESIDE_BYTES: u64 = 4 << 20;

/// A file with the extension of a lathe program (as `examples/editors/` attach the server
/// to): `.min`, `.nc`, `.ssb`, `.sub`, in any case.
fn is_program_file(path: &Path) -> bool {
    let extension = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    matches!(extension.as_deref(), Some("min" | "nc" | "ssb" | "sub")) && path.is_file()
}

/// What the loop waits for: a frame from the client, or a finished semantic pass.
enum Event {
    Frame(Frame),
    Finished(JobResult),
}

/// How a session ended.
type Ended = Result<bool, String>;

/// Serve one client over standard input and output until it says `exit` or its input
/// ends. Returns whether the client shut the server down first (the exit code is 0 then, 1
/// otherwise); an error when the connection failed (a frame that cannot be read, an output
/// that cannot be written).
pub fn run_stdio() -> Ended {
    let (events, queue) = mpsc::channel::<Event>();
    let reader = events.clone();
    crate::parallel::detach(move || {
        let stdin = std::io::stdin();
        let mut input = stdin.lock();
        loop {
            let frame = frame::read(&mut input);
            let last = match &frame {
                Frame::End | Frame::Broken(_) => true,
                Frame::Message(Message::Notification(n)) => n.method == "exit",
                _ => false,
            };
            if reader.send(Event::Frame(frame)).is_err() || last {
                break;
            }
        }
    });
    let stdout = std::io::stdout();
    let mut output = stdout.lock();
    serve(&mut output, &events, &queue)
}

fn serve(output: &mut impl Write, events: &mpsc::Sender<Event>, queue: &mpsc::Receiver<Event>) -> Ended {
    let mut server: Option<Server<Files>> = None;
    loop {
        let event = match queue.try_recv() {
            Ok(event) => event,
            Err(_) => {
                // Nothing is waiting: the moment to publish.
                if let Some(server) = server.as_mut() {
                    idle(server, output, events)?;
                }
                match queue.recv() {
                    Ok(event) => event,
                    Err(_) => return Ok(false),
                }
            }
        };
        match event {
            Event::Finished(result) => {
                if let Some(server) = server.as_mut() {
                    send(output, server.finished(result))?;
                }
            }
            Event::Frame(Frame::End) => return Ok(server.is_some_and(|s| s.is_shut_down())),
            Event::Frame(Frame::Broken(problem)) => {
                let message = format!("{problem}; the next frame cannot be found, the connection ends");
                send_error(output, None, ErrorCode::ParseError, &message)?;
                return Err(message);
            }
            Event::Frame(Frame::Invalid { id, code, message }) => send_error(output, id, code, &message)?,
            Event::Frame(Frame::Message(Message::Notification(n))) if n.method == "exit" => {
                return Ok(server.is_some_and(|s| s.is_shut_down()));
            }
            Event::Frame(Frame::Message(message)) => match server.as_mut() {
                Some(server) => match message {
                    Message::Request(request) if request.method == Initialize::METHOD => {
                        let error = "the server is initialized already";
                        send_error(output, Some(request.id), ErrorCode::InvalidRequest, error)?;
                    }
                    message => send(output, server.handle(message))?,
                },
                None => server = handshake(output, message)?,
            },
        }
    }
}

/// Before `initialize`: start the server on it, refuse any other request, drop
/// notifications (the protocol's rules).
fn handshake(output: &mut impl Write, message: Message) -> Result<Option<Server<Files>>, String> {
    match message {
        Message::Request(Request { id, method, params }) if method == Initialize::METHOD => {
            let (server, result, messages) = Server::initialize(Files, params);
            let result = serde_json::to_value(result).map_err(|e| e.to_string())?;
            send(output, vec![Message::Response(Response::new_ok(id, result))])?;
            send(output, messages)?;
            Ok(Some(server))
        }
        Message::Request(request) => {
            let problem = "the server is not initialized: send `initialize` first";
            send_error(output, Some(request.id), ErrorCode::ServerNotInitialized, problem)?;
            Ok(None)
        }
        Message::Notification(_) | Message::Response(_) => Ok(None),
    }
}

/// Publish what the edits changed and start the semantic passes they need.
fn idle(server: &mut Server<Files>, output: &mut impl Write, events: &mpsc::Sender<Event>) -> Result<(), String> {
    let (messages, jobs) = server.idle();
    send(output, messages)?;
    for job in jobs {
        if job.inline {
            send(output, server.finished(job.run()))?;
        } else {
            let events = events.clone();
            crate::parallel::detach(move || {
                let _ = events.send(Event::Finished(job.run()));
            });
        }
    }
    Ok(())
}

fn send(output: &mut impl Write, messages: Vec<Message>) -> Result<(), String> {
    messages.into_iter().try_for_each(|m| m.write(output).map_err(|e| format!("cannot write to the client: {e}")))
}

/// A JSON-RPC error, to a request or (`id` unknown) to no one in particular: `"id": null`,
/// which `lsp_server::Response` cannot hold.
fn send_error(output: &mut impl Write, id: Option<RequestId>, code: ErrorCode, message: &str) -> Result<(), String> {
    let body = serde_json::json!({
        "jsonrpc": "2.0",
        "id": id,
        "error": { "code": code as i32, "message": format!("turnpass: {message}") },
    });
    let text = body.to_string();
    write!(output, "Content-Length: {}\r\n\r\n{text}", text.len())
        .and_then(|()| output.flush())
        .map_err(|e| format!("cannot write to the client: {e}"))
}
