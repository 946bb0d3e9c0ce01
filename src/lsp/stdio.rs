//! The server's I/O layer: the stdio connection, the message loop, the worker threads of
//! the semantic pass, and the file system (finding and reading `turnpass.toml`).
//!
//! This is the only module of the language server that touches files or standard streams,
//! as `main.rs`/`cli.rs` are for the other commands; `clippy.toml` bans those calls in the
//! library and the lint is allowed here alone.

#![allow(clippy::disallowed_methods)]

use std::path::{Path, PathBuf};
use std::sync::mpsc;

use lsp_server::{Connection, Message};

use super::server::{Host, JobResult, Server};

/// Reads settings files from the file system.
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
        let text = std::fs::read_to_string(&path).map_err(|e| e.to_string());
        Some((path, text))
    }
}

/// What the loop waits for: a message from the client, or a finished semantic pass.
enum Event {
    Message(Message),
    Finished(JobResult),
}

/// Serve one client over standard input and output until it says `exit`. Returns whether
/// the client shut the server down first (the exit code is 0 then, 1 otherwise).
pub fn run_stdio() -> Result<bool, String> {
    let (connection, threads) = Connection::stdio();
    let clean = serve(&connection)?;
    drop(connection);
    threads.join().map_err(|e| e.to_string())?;
    Ok(clean)
}

fn serve(connection: &Connection) -> Result<bool, String> {
    let (id, params) = connection.initialize_start().map_err(|e| e.to_string())?;
    let (mut server, result, messages) = Server::initialize(Files, params);
    let result = serde_json::to_value(result).map_err(|e| e.to_string())?;
    connection.initialize_finish(id, result).map_err(|e| e.to_string())?;
    let send = |messages: Vec<Message>| -> Result<(), String> {
        messages.into_iter().try_for_each(|m| connection.sender.send(m).map_err(|e| e.to_string()))
    };
    send(messages)?;

    // One queue for client messages and finished passes, so that the loop can tell when
    // nothing is waiting (the moment to publish).
    let (events, queue) = mpsc::channel::<Event>();
    let receiver = connection.receiver.clone();
    let forward = events.clone();
    crate::parallel::detach(move || {
        for message in receiver {
            if forward.send(Event::Message(message)).is_err() {
                break;
            }
        }
    });
    loop {
        let event = match queue.try_recv() {
            Ok(event) => event,
            Err(mpsc::TryRecvError::Empty) => {
                let (messages, jobs) = server.idle();
                send(messages)?;
                for job in jobs {
                    if job.inline {
                        send(server.finished(job.run()))?;
                    } else {
                        let events = events.clone();
                        crate::parallel::detach(move || {
                            let _ = events.send(Event::Finished(job.run()));
                        });
                    }
                }
                match queue.recv() {
                    Ok(event) => event,
                    Err(_) => return Ok(false),
                }
            }
            Err(mpsc::TryRecvError::Disconnected) => return Ok(false),
        };
        match event {
            Event::Message(Message::Notification(n)) if n.method == "exit" => return Ok(server.is_shut_down()),
            Event::Message(message) => send(server.handle(message))?,
            Event::Finished(result) => send(server.finished(result))?,
        }
    }
}
