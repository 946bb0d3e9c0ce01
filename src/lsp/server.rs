//! The protocol state machine: open documents, their settings, what to publish.
//!
//! [`Server`] turns each incoming message into outgoing ones and reads nothing itself: the
//! settings files come through a [`Host`], and the loop that owns the connection
//! (`stdio.rs`) decides where a semantic pass runs. That keeps every path of the server
//! testable without a process or a file system (the property test drives it with random
//! messages).
//!
//! **When diagnostics are published.** Edits mark a document; when no message is waiting,
//! the loop calls [`Server::idle`], which publishes each marked document once, for its
//! latest version (a burst of keystrokes costs one publish). A program up to
//! `semanticInlineLimit` bytes (by default `parallel::Tuning::lsp_inline_bytes`, 256 KiB,
//! where the pass takes a few milliseconds) gets its semantic diagnostics in that same
//! publish. A larger one is published at once with its parse diagnostics and the previous
//! semantic diagnostics moved across the edits, and again when the semantic pass, run on
//! another thread, has finished with that version.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use lsp_server::{ErrorCode, Message, Notification, Request, Response};
use lsp_types::notification::{self as notify, Notification as _};
use lsp_types::request::{self as req, Request as _};
use lsp_types::{
    DidChangeTextDocumentParams, DidCloseTextDocumentParams, DidOpenTextDocumentParams, DidSaveTextDocumentParams,
    DocumentFormattingParams, DocumentSymbolParams, DocumentSymbolResponse, GotoDefinitionParams,
    GotoDefinitionResponse, HoverParams, HoverProviderCapability, InitializeResult, Location, LogMessageParams,
    MessageType, OneOf, PositionEncodingKind, PublishDiagnosticsParams, ServerCapabilities, ServerInfo,
    ShowMessageParams, TextDocumentSyncCapability, TextDocumentSyncKind, Uri,
};

use crate::diagnostic::Diagnostic;

use super::analysis::{self, SemanticDiagnostics, SemanticJob};
use super::document::{Document, LinePosition};
use super::settings::{InitOptions, Settings};
use super::{definition, format, hover, symbols};

/// Where the server gets what lives outside the protocol: the settings files.
pub trait Host {
    /// The model file for the program at `program` (`None` for a document that is no file):
    /// `model` when the client named one, else the nearest `turnpass.toml` in the program's
    /// directory or above it. Returns its path and its text, or why it could not be read;
    /// `None` when there is no such file.
    fn model_file(&self, program: Option<&Path>, model: Option<&Path>) -> Option<(PathBuf, Result<String, String>)>;
}

/// A semantic pass to run for one version of a document.
#[derive(Debug)]
pub struct Job {
    pub uri: Uri,
    /// Which opening of the document (a document closed and opened again starts its
    /// versions anew) and which version of it.
    pub generation: u64,
    pub version: i32,
    pub work: SemanticJob,
    /// Run it now and hand the result to [`Server::finished`] before reading the next
    /// message; otherwise run it on another thread.
    pub inline: bool,
}

/// What a [`Job`] found.
#[derive(Debug)]
pub struct JobResult {
    pub uri: Uri,
    pub generation: u64,
    pub version: i32,
    pub diagnostics: Vec<Diagnostic>,
}

impl Job {
    pub fn run(&self) -> JobResult {
        JobResult {
            uri: self.uri.clone(),
            generation: self.generation,
            version: self.version,
            diagnostics: self.work.run(),
        }
    }
}

struct Open {
    document: Document,
    generation: u64,
    version: i32,
    settings: Settings,
    /// The semantic diagnostics of `semantic_version`, moved across the edits since.
    semantic: SemanticDiagnostics,
    semantic_version: Option<i32>,
    /// Edited since the last publish.
    dirty: bool,
    /// A semantic pass is running on another thread.
    running: bool,
}

pub struct Server<H: Host> {
    host: H,
    init: InitOptions,
    documents: HashMap<Uri, Open>,
    inline_limit: usize,
    /// How many diagnostics a publish holds at most (`maxDiagnostics`; 0 there is no limit).
    max_diagnostics: usize,
    shut_down: bool,
    /// Documents opened so far.
    openings: u64,
}

impl<H: Host> Server<H> {
    /// A server for a client's `initialize` parameters, the result to answer with, and
    /// messages for the user about options it could not read.
    pub fn initialize(host: H, params: serde_json::Value) -> (Server<H>, InitializeResult, Vec<Message>) {
        let options = params.get("initializationOptions").cloned();
        let mut messages = Vec::new();
        let init = InitOptions::from_json(options).unwrap_or_else(|problem| {
            messages.push(show_message(MessageType::WARNING, problem));
            InitOptions::default()
        });
        let inline_limit = init.semantic_inline_limit.unwrap_or(crate::parallel::tuning().lsp_inline_bytes);
        let max_diagnostics = match init.max_diagnostics {
            None => analysis::DEFAULT_MAX_DIAGNOSTICS,
            Some(0) => usize::MAX,
            Some(limit) => limit,
        };
        let server = Server {
            host,
            init,
            documents: HashMap::new(),
            inline_limit,
            max_diagnostics,
            shut_down: false,
            openings: 0,
        };
        (server, initialize_result(), messages)
    }

    /// Whether `shutdown` was received (the process then exits with 0 on `exit`).
    pub fn is_shut_down(&self) -> bool {
        self.shut_down
    }

    pub fn handle(&mut self, message: Message) -> Vec<Message> {
        match message {
            Message::Request(request) => vec![Message::Response(self.request(request))],
            Message::Notification(notification) => self.notification(notification),
            Message::Response(_) => Vec::new(),
        }
    }

    fn request(&mut self, request: Request) -> Response {
        let id = request.id.clone();
        if self.shut_down {
            return Response::new_err(id, ErrorCode::InvalidRequest as i32, "the server is shut down".to_string());
        }
        let result = match request.method.as_str() {
            req::Shutdown::METHOD => {
                self.shut_down = true;
                Ok(serde_json::Value::Null)
            }
            req::HoverRequest::METHOD => self.answer(request, |server, params: HoverParams| {
                let at = &params.text_document_position_params;
                let open = server.documents.get(&at.text_document.uri)?;
                let offset = offset(&open.document, at.position);
                hover::hover(&open.document, offset, &open.settings.machine)
            }),
            req::GotoDefinition::METHOD => self.answer(request, |server, params: GotoDefinitionParams| {
                let at = &params.text_document_position_params;
                let open = server.documents.get(&at.text_document.uri)?;
                let targets = definition::definition(&open.document, offset(&open.document, at.position));
                let uri = &at.text_document.uri;
                let mut locations: Vec<Location> = targets
                    .into_iter()
                    .map(|span| Location { uri: uri.clone(), range: open.document.range(span) })
                    .collect();
                match locations.len() {
                    0 => None,
                    1 => locations.pop().map(GotoDefinitionResponse::Scalar),
                    _ => Some(GotoDefinitionResponse::Array(locations)),
                }
            }),
            req::DocumentSymbolRequest::METHOD => self.answer(request, |server, params: DocumentSymbolParams| {
                let open = server.documents.get(&params.text_document.uri)?;
                Some(DocumentSymbolResponse::Nested(symbols::symbols(&open.document)))
            }),
            req::Formatting::METHOD => self.answer(request, |server, params: DocumentFormattingParams| {
                let open = server.documents.get(&params.text_document.uri)?;
                Some(format::formatting(&open.document, &open.settings.canonical))
            }),
            _ => Err((ErrorCode::MethodNotFound, format!("turnpass does not handle `{}`", request.method))),
        };
        match result {
            Ok(value) => Response::new_ok(id, value),
            Err((code, message)) => Response::new_err(id, code as i32, message),
        }
    }

    /// Decode a request's parameters, answer, and encode the answer (`null` for `None`).
    fn answer<P, R>(
        &mut self,
        request: Request,
        answer: impl FnOnce(&mut Self, P) -> Option<R>,
    ) -> Result<serde_json::Value, (ErrorCode, String)>
    where
        P: serde::de::DeserializeOwned,
        R: serde::Serialize,
    {
        let params: P = serde_json::from_value(request.params)
            .map_err(|e| (ErrorCode::InvalidParams, format!("{}: {e}", request.method)))?;
        serde_json::to_value(answer(self, params)).map_err(|e| (ErrorCode::InternalError, e.to_string()))
    }

    fn notification(&mut self, notification: Notification) -> Vec<Message> {
        let method = notification.method.clone();
        let params = notification.params;
        match method.as_str() {
            notify::DidOpenTextDocument::METHOD => match serde_json::from_value::<DidOpenTextDocumentParams>(params) {
                Ok(params) => self.open(params),
                Err(_) => Vec::new(),
            },
            notify::DidChangeTextDocument::METHOD => {
                if let Ok(params) = serde_json::from_value::<DidChangeTextDocumentParams>(params) {
                    self.change(params);
                }
                Vec::new()
            }
            notify::DidCloseTextDocument::METHOD => {
                match serde_json::from_value::<DidCloseTextDocumentParams>(params) {
                    Ok(params) if self.documents.remove(&params.text_document.uri).is_some() => {
                        vec![publish(params.text_document.uri, Vec::new(), None)]
                    }
                    _ => Vec::new(),
                }
            }
            notify::DidSaveTextDocument::METHOD => match serde_json::from_value::<DidSaveTextDocumentParams>(params) {
                // A saved settings file changes how every program reads.
                Ok(params) if file_path(&params.text_document.uri).is_some_and(|p| is_settings_file(&p)) => {
                    self.refresh_settings()
                }
                _ => Vec::new(),
            },
            notify::DidChangeConfiguration::METHOD => self.refresh_settings(),
            _ => Vec::new(),
        }
    }

    fn open(&mut self, params: DidOpenTextDocumentParams) -> Vec<Message> {
        let item = params.text_document;
        let (settings, problems, defaults) = self.settings_for(&item.uri);
        // Reading with the machine defaults is logged, not published: a clean program must
        // not look wrong in the editor because no settings file exists.
        let defaults = defaults.then(|| {
            let message = format!(
                "{}: no turnpass.toml in its directory or above it, and no `model` or `machine` in \
                 initializationOptions; machine settings in force: {}",
                item.uri.as_str(),
                crate::semantic::settings_in_force(&settings.machine)
            );
            log_message(MessageType::INFO, message)
        });
        let document = Document::new(item.text.into_bytes(), settings.parse);
        self.openings += 1;
        let open = Open {
            document,
            generation: self.openings,
            version: item.version,
            settings,
            semantic: SemanticDiagnostics::default(),
            semantic_version: None,
            dirty: true,
            running: false,
        };
        self.documents.insert(item.uri, open);
        defaults.into_iter().chain(problems.into_iter().map(|p| show_message(MessageType::WARNING, p))).collect()
    }

    fn change(&mut self, params: DidChangeTextDocumentParams) {
        let Some(open) = self.documents.get_mut(&params.text_document.uri) else { return };
        open.version = params.text_document.version;
        open.dirty = true;
        for change in params.content_changes {
            match change.range {
                Some(range) => {
                    let start = offset(&open.document, range.start);
                    let end = offset(&open.document, range.end).max(start);
                    let inserted = change.text.len();
                    open.document.replace(start..end, change.text.as_bytes());
                    open.semantic.move_across_edit(start..end, inserted);
                }
                None => {
                    open.document.set_text(change.text.into_bytes());
                    open.semantic.clear();
                }
            }
        }
    }

    /// Read every document's settings again (a settings file changed).
    fn refresh_settings(&mut self) -> Vec<Message> {
        let uris: Vec<Uri> = self.documents.keys().cloned().collect();
        let mut messages = Vec::new();
        for uri in uris {
            let (settings, problems, _) = self.settings_for(&uri);
            messages.extend(problems.into_iter().map(|p| show_message(MessageType::WARNING, p)));
            if let Some(open) = self.documents.get_mut(&uri)
                && open.settings != settings
            {
                open.document.set_options(settings.parse);
                open.settings = settings;
                open.semantic.clear();
                open.semantic_version = None;
                open.dirty = true;
            }
        }
        messages
    }

    /// The settings for the program at `uri`, the problems met reading them, and whether
    /// they are the machine defaults (no model file, no `machine` table from the client).
    fn settings_for(&self, uri: &Uri) -> (Settings, Vec<String>, bool) {
        let program = file_path(uri);
        let model = self.init.model.as_deref().map(Path::new);
        let mut problems = Vec::new();
        let file = self.host.model_file(program.as_deref(), model);
        let text = match &file {
            Some((path, Err(error))) => {
                problems.push(format!("cannot read {}: {error}", path.display()));
                None
            }
            Some((_, Ok(text))) => Some(text.as_str()),
            None => None,
        };
        let (settings, found) = self.init.settings(text);
        let source = file.as_ref().map_or("initializationOptions".to_string(), |(p, _)| p.display().to_string());
        problems.extend(found.into_iter().map(|p| format!("{source}: {p}")));
        let defaults = file.is_none() && self.init.machine.is_none();
        (settings, problems, defaults)
    }

    /// Publish what the edits since the last call changed, and the semantic passes to run.
    pub fn idle(&mut self) -> (Vec<Message>, Vec<Job>) {
        let mut messages = Vec::new();
        let mut jobs = Vec::new();
        for (uri, open) in &mut self.documents {
            if !open.dirty {
                continue;
            }
            open.dirty = false;
            if open.semantic_version != Some(open.version) && !open.running {
                let inline = open.document.len() <= self.inline_limit;
                let work = SemanticJob::new(open.document.snapshot(), &open.settings.machine);
                jobs.push(Job { uri: uri.clone(), generation: open.generation, version: open.version, work, inline });
                open.running = true;
                if inline {
                    // Published with the job's result, in `finished`.
                    continue;
                }
            }
            messages.push(publish_open(uri, open, self.max_diagnostics));
        }
        (messages, jobs)
    }

    /// Take a semantic pass's result: publish it if its version is still the document's,
    /// else mark the document so that the next idle moment runs the pass again.
    pub fn finished(&mut self, result: JobResult) -> Vec<Message> {
        let Some(open) = self.documents.get_mut(&result.uri) else { return Vec::new() };
        if open.generation != result.generation {
            return Vec::new();
        }
        open.running = false;
        if result.version != open.version {
            open.dirty = true;
            return Vec::new();
        }
        open.semantic = SemanticDiagnostics::new(result.diagnostics);
        open.semantic_version = Some(result.version);
        vec![publish_open(&result.uri, open, self.max_diagnostics)]
    }
}

fn publish_open(uri: &Uri, open: &Open, limit: usize) -> Message {
    publish(uri.clone(), analysis::publishable(&open.document, uri, &open.semantic, limit), Some(open.version))
}

fn publish(uri: Uri, diagnostics: Vec<lsp_types::Diagnostic>, version: Option<i32>) -> Message {
    let params = PublishDiagnosticsParams { uri, diagnostics, version };
    Message::Notification(Notification::new(notify::PublishDiagnostics::METHOD.to_string(), params))
}

fn show_message(kind: MessageType, message: String) -> Message {
    let params = ShowMessageParams { typ: kind, message: format!("turnpass: {message}") };
    Message::Notification(Notification::new(notify::ShowMessage::METHOD.to_string(), params))
}

fn log_message(kind: MessageType, message: String) -> Message {
    let params = LogMessageParams { typ: kind, message: format!("turnpass: {message}") };
    Message::Notification(Notification::new(notify::LogMessage::METHOD.to_string(), params))
}

fn offset(document: &Document, position: lsp_types::Position) -> usize {
    document.offset_of(LinePosition { line: position.line, column: position.character })
}

fn initialize_result() -> InitializeResult {
    InitializeResult {
        capabilities: ServerCapabilities {
            position_encoding: Some(PositionEncodingKind::UTF16),
            text_document_sync: Some(TextDocumentSyncCapability::Kind(TextDocumentSyncKind::INCREMENTAL)),
            hover_provider: Some(HoverProviderCapability::Simple(true)),
            definition_provider: Some(OneOf::Left(true)),
            document_symbol_provider: Some(OneOf::Left(true)),
            document_formatting_provider: Some(OneOf::Left(true)),
            ..ServerCapabilities::default()
        },
        server_info: Some(ServerInfo {
            name: "turnpass".to_string(),
            version: Some(env!("CARGO_PKG_VERSION").to_string()),
        }),
    }
}

/// The file a `file:` URI names, percent-decoded.
pub fn file_path(uri: &Uri) -> Option<PathBuf> {
    if !uri.scheme().is_some_and(|s| s.as_str().eq_ignore_ascii_case("file")) {
        return None;
    }
    let decoded = uri.path().as_estr().decode().into_string().ok()?;
    Some(PathBuf::from(decoded.into_owned()))
}

fn is_settings_file(path: &Path) -> bool {
    path.file_name().is_some_and(|n| n == "turnpass.toml")
}
