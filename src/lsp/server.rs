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
    CodeAction, CodeActionKind, CodeActionOptions, CodeActionOrCommand, CodeActionParams, CodeActionProviderCapability,
    CompletionOptions, CompletionParams, CompletionResponse, DidChangeTextDocumentParams, DidCloseTextDocumentParams,
    DidOpenTextDocumentParams, DidSaveTextDocumentParams, DocumentFormattingParams, DocumentSymbolParams,
    DocumentSymbolResponse, FoldingRangeParams, FoldingRangeProviderCapability, GotoDefinitionParams,
    GotoDefinitionResponse, HoverParams, HoverProviderCapability, InitializeResult, InlayHintParams, Location,
    LogMessageParams, MessageType, OneOf, PositionEncodingKind, PrepareRenameResponse, PublishDiagnosticsParams,
    ReferenceParams, RenameOptions, RenameParams, SemanticTokens, SemanticTokensFullOptions, SemanticTokensOptions,
    SemanticTokensParams, SemanticTokensRangeParams, SemanticTokensRangeResult, SemanticTokensResult,
    SemanticTokensServerCapabilities, ServerCapabilities, ServerInfo, ShowMessageParams, SignatureHelpOptions,
    SignatureHelpParams, TextDocumentPositionParams, TextDocumentSyncCapability, TextDocumentSyncKind, Uri,
};

use crate::diagnostic::Diagnostic;

use super::analysis::{self, SemanticDiagnostics, SemanticJob};
use super::document::{Document, LinePosition};
use super::settings::{InitOptions, Settings};
use super::{actions, completion, definition, folding, format, hover, inlay, rename, semantic_tokens, symbols};

/// Where the server gets what lives outside the protocol: the settings files.
pub trait Host {
    /// The model file for the program at `program` (`None` for a document that is no file):
    /// `model` when the client named one, else the nearest `turnpass.toml` in the program's
    /// directory or above it. Returns its path and its text, or why it could not be read;
    /// `None` when there is no such file.
    fn model_file(&self, program: Option<&Path>, model: Option<&Path>) -> Option<(PathBuf, Result<String, String>)>;

    /// The program files in the folder of the program at `program` (itself excepted), for
    /// a definition of a program the file does not hold (`CALL OSUB`, `M98 P1000`).
    fn programs_beside(&self, _program: &Path) -> Vec<PathBuf> {
        Vec::new()
    }

    /// The text of a program file, `None` when it cannot be read (or is too large to be a
    /// subprogram worth reading for a definition).
    fn read_program(&self, _path: &Path) -> Option<Vec<u8>> {
        None
    }
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
    /// Where the last edit was: a publish capped at `maxDiagnostics` shows the ones nearest
    /// it (`None` until the first edit: the first ones).
    focus: Option<usize>,
    /// The version last published.
    published: Option<i32>,
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
    /// What the client said it supports.
    client: Client,
}

/// The client's capabilities the answers depend on.
#[derive(Debug, Clone, Default)]
struct Client {
    /// Hover in plain text: the client prefers it (eglot), or does not list Markdown.
    plain_hover: bool,
    /// The client resolves a code action's edit when it applies it (`codeAction/resolve`).
    resolves_actions: bool,
}

impl Client {
    fn from_json(capabilities: Option<&serde_json::Value>) -> Client {
        let Some(capabilities) = capabilities else { return Client::default() };
        let document = &capabilities["textDocument"];
        let formats: Vec<&str> = document["hover"]["contentFormat"]
            .as_array()
            .map(|list| list.iter().filter_map(|f| f.as_str()).collect())
            .unwrap_or_default();
        // The client's order is its preference; a client that names none takes Markdown.
        let plain_hover = formats.first().is_some_and(|f| *f == "plaintext")
            || (!formats.is_empty() && !formats.contains(&"markdown"));
        let resolves_actions = document["codeAction"]["resolveSupport"]["properties"]
            .as_array()
            .is_some_and(|list| list.iter().any(|p| p == "edit"));
        Client { plain_hover, resolves_actions }
    }
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
        let client = Client::from_json(params.get("capabilities"));
        let server = Server {
            host,
            init,
            documents: HashMap::new(),
            inline_limit,
            max_diagnostics,
            shut_down: false,
            openings: 0,
            client,
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
                hover::hover(&open.document, offset, &open.settings.machine, server.client.plain_hover)
            }),
            req::GotoDefinition::METHOD => self.answer(request, |server, params: GotoDefinitionParams| {
                let at = &params.text_document_position_params;
                let uri = &at.text_document.uri;
                let open = server.documents.get(uri)?;
                let mut locations: Vec<Location> =
                    match definition::definition(&open.document, offset(&open.document, at.position)) {
                        definition::Definition::Here(targets) => targets
                            .into_iter()
                            .map(|span| Location { uri: uri.clone(), range: open.document.range(span) })
                            .collect(),
                        definition::Definition::Program(key) => {
                            server.program_elsewhere(uri, &key).into_iter().collect()
                        }
                    };
                match locations.len() {
                    0 => None,
                    1 => locations.pop().map(GotoDefinitionResponse::Scalar),
                    _ => Some(GotoDefinitionResponse::Array(locations)),
                }
            }),
            req::References::METHOD => self.answer(request, |server, params: ReferenceParams| {
                let at = &params.text_document_position;
                let uri = &at.text_document.uri;
                let open = server.documents.get(uri)?;
                let offset = offset(&open.document, at.position);
                let spans = rename::references(&open.document, offset, params.context.include_declaration);
                Some(
                    spans
                        .into_iter()
                        .map(|span| Location { uri: uri.clone(), range: open.document.range(span) })
                        .collect::<Vec<_>>(),
                )
            }),
            req::PrepareRenameRequest::METHOD => self.answer(request, |server, params: TextDocumentPositionParams| {
                let open = server.documents.get(&params.text_document.uri)?;
                let (span, placeholder) = rename::prepare(&open.document, offset(&open.document, params.position))?;
                Some(PrepareRenameResponse::RangeWithPlaceholder { range: open.document.range(span), placeholder })
            }),
            req::Rename::METHOD => {
                let params: Result<RenameParams, _> = serde_json::from_value(request.params.clone());
                match params {
                    Err(e) => Err((ErrorCode::InvalidParams, format!("{}: {e}", request.method))),
                    Ok(params) => {
                        let at = &params.text_document_position;
                        let uri = &at.text_document.uri;
                        match self.documents.get(uri) {
                            None => Ok(serde_json::Value::Null),
                            Some(open) => match rename::rename(
                                &open.document,
                                offset(&open.document, at.position),
                                &params.new_name,
                            ) {
                                Ok(edits) => serde_json::to_value(actions::edit(&open.document, uri, edits))
                                    .map_err(|e| (ErrorCode::InternalError, e.to_string())),
                                Err(why) => Err((ErrorCode::InvalidParams, why)),
                            },
                        }
                    }
                }
            }
            req::Completion::METHOD => self.answer(request, |server, params: CompletionParams| {
                let at = &params.text_document_position;
                let open = server.documents.get(&at.text_document.uri)?;
                let offset = offset(&open.document, at.position);
                Some(CompletionResponse::Array(completion::completion(&open.document, offset, &open.settings.machine)))
            }),
            req::SignatureHelpRequest::METHOD => self.answer(request, |server, params: SignatureHelpParams| {
                let at = &params.text_document_position_params;
                let open = server.documents.get(&at.text_document.uri)?;
                let offset = offset(&open.document, at.position);
                completion::signature_help(&open.document, offset, &open.settings.machine)
            }),
            req::SemanticTokensFullRequest::METHOD => self.answer(request, |server, params: SemanticTokensParams| {
                let open = server.documents.get(&params.text_document.uri)?;
                let end = open.document.len().min(semantic_tokens::FULL_LIMIT);
                let data = semantic_tokens::tokens(&open.document, 0..end);
                Some(SemanticTokensResult::Tokens(SemanticTokens { result_id: None, data }))
            }),
            req::SemanticTokensRangeRequest::METHOD => {
                self.answer(request, |server, params: SemanticTokensRangeParams| {
                    let open = server.documents.get(&params.text_document.uri)?;
                    let start = offset(&open.document, params.range.start);
                    let end = offset(&open.document, params.range.end).max(start);
                    let data = semantic_tokens::tokens(&open.document, start..end);
                    Some(SemanticTokensRangeResult::Tokens(SemanticTokens { result_id: None, data }))
                })
            }
            req::FoldingRangeRequest::METHOD => self.answer(request, |server, params: FoldingRangeParams| {
                let open = server.documents.get(&params.text_document.uri)?;
                Some(folding::folding_ranges(&open.document))
            }),
            req::InlayHintRequest::METHOD => self.answer(request, |server, params: InlayHintParams| {
                let open = server.documents.get(&params.text_document.uri)?;
                let start = offset(&open.document, params.range.start);
                let end = offset(&open.document, params.range.end).max(start);
                Some(inlay::inlay_hints(&open.document, start..end, &open.settings.machine))
            }),
            req::CodeActionRequest::METHOD => self.answer(request, |server, params: CodeActionParams| {
                let uri = &params.text_document.uri;
                let open = server.documents.get(uri)?;
                let wants = |kind: &CodeActionKind| {
                    params
                        .context
                        .only
                        .as_ref()
                        .is_none_or(|only| only.iter().any(|o| kind.as_str().starts_with(o.as_str())))
                };
                let start = offset(&open.document, params.range.start);
                let end = offset(&open.document, params.range.end).max(start);
                let mut found: Vec<CodeActionOrCommand> = Vec::new();
                if wants(&CodeActionKind::QUICKFIX) {
                    found.extend(
                        actions::quick_fixes(&open.document, uri, &open.semantic, start..end)
                            .into_iter()
                            .map(CodeActionOrCommand::CodeAction),
                    );
                }
                if wants(&CodeActionKind::REFACTOR_REWRITE) {
                    let resolved = !server.client.resolves_actions;
                    found.extend(
                        actions::renumbering(&open.document, uri, resolved).map(CodeActionOrCommand::CodeAction),
                    );
                }
                Some(found)
            }),
            req::CodeActionResolveRequest::METHOD => self.answer(request, |server, action: CodeAction| {
                let uri: Uri = serde_json::from_value(action.data.as_ref()?.get("renumber")?.clone()).ok()?;
                let open = server.documents.get(&uri)?;
                actions::renumbering(&open.document, &uri, true)
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

    /// The block that names program `key` in a program file beside the document at `uri`
    /// (an open document's text, else the file's): files named for the program first.
    fn program_elsewhere(&self, uri: &Uri, key: &str) -> Option<Location> {
        let path = file_path(uri)?;
        let open = self.documents.get(uri)?;
        let mut candidates = self.host.programs_beside(&path);
        // `OSUB.SSB`, `O1000.nc`, `1000.nc` first: where a control's file of that program is.
        let named = |p: &PathBuf| {
            let stem = p.file_stem().map(|s| s.to_string_lossy().to_ascii_uppercase()).unwrap_or_default();
            let stem = stem.strip_prefix('O').unwrap_or(&stem).to_string();
            let key = key.to_ascii_uppercase();
            stem == key || stem.trim_start_matches('0') == key.trim_start_matches('0')
        };
        candidates.sort_by_key(|p| !named(p));
        for candidate in candidates {
            let candidate_uri = file_uri(&candidate)?;
            let text = match self.documents.get(&candidate_uri) {
                Some(other) => other.document.text(),
                None => match self.host.read_program(&candidate) {
                    Some(text) => text,
                    None => continue,
                },
            };
            let document = Document::new(text, open.settings.parse);
            if document.config().dialect != open.document.config().dialect {
                continue;
            }
            if let Some(span) = definition::program(&document, key) {
                return Some(Location { uri: candidate_uri, range: document.range(span) });
            }
        }
        None
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
            notify::DidChangeConfiguration::METHOD => {
                // Settings the client sends replace its initializationOptions; a file's
                // settings are read again either way.
                let mut messages = Vec::new();
                match params.get("settings").and_then(InitOptions::from_settings) {
                    Some(Ok(options)) => self.set_options(options),
                    Some(Err(problem)) => messages.push(show_message(MessageType::WARNING, problem)),
                    None => {}
                }
                messages.extend(self.refresh_settings());
                messages
            }
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
                crate::semantic::settings_in_force(&settings.machine, Some(settings.stock.is_some()))
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
            focus: None,
            published: None,
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
                    open.document.replace(start..end, change.text.as_bytes());
                    open.semantic.move_across_edit(start..end, change.text.as_bytes());
                    open.focus = Some(start);
                }
                None => {
                    open.document.set_text(change.text.into_bytes());
                    open.semantic.clear();
                    open.focus = None;
                }
            }
        }
    }

    /// Take new client options (`workspace/didChangeConfiguration`).
    fn set_options(&mut self, init: InitOptions) {
        self.inline_limit = init.semantic_inline_limit.unwrap_or(crate::parallel::tuning().lsp_inline_bytes);
        self.max_diagnostics = match init.max_diagnostics {
            None => analysis::DEFAULT_MAX_DIAGNOSTICS,
            Some(0) => usize::MAX,
            Some(limit) => limit,
        };
        self.init = init;
        for open in self.documents.values_mut() {
            open.dirty = true;
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
        for (uri, open) in self.documents.iter_mut() {
            if !open.dirty {
                continue;
            }
            open.dirty = false;
            if open.semantic_version != Some(open.version) && !open.running {
                let inline = open.document.len() <= self.inline_limit;
                let work = SemanticJob::new(open.document.snapshot(), &open.settings.machine, open.settings.stock);
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
        // The diagnostics moved across the edits are what this version already showed: a
        // pass that finds the same (most keystrokes) is not published twice.
        let unchanged = open.published == Some(result.version) && open.semantic.same_as(&result.diagnostics);
        open.semantic_version = Some(result.version);
        if unchanged {
            return Vec::new();
        }
        open.semantic = SemanticDiagnostics::new(result.diagnostics);
        vec![publish_open(&result.uri, open, self.max_diagnostics)]
    }
}

fn publish_open(uri: &Uri, open: &mut Open, limit: usize) -> Message {
    open.published = Some(open.version);
    let diagnostics = analysis::publishable(&open.document, uri, &open.semantic, limit, open.focus);
    publish(uri.clone(), diagnostics, Some(open.version))
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
            references_provider: Some(OneOf::Left(true)),
            completion_provider: Some(CompletionOptions::default()),
            signature_help_provider: Some(SignatureHelpOptions {
                trigger_characters: Some(vec![" ".to_string()]),
                retrigger_characters: None,
                work_done_progress_options: Default::default(),
            }),
            semantic_tokens_provider: Some(SemanticTokensServerCapabilities::SemanticTokensOptions(
                SemanticTokensOptions {
                    legend: semantic_tokens::legend(),
                    range: Some(true),
                    full: Some(SemanticTokensFullOptions::Bool(true)),
                    work_done_progress_options: Default::default(),
                },
            )),
            folding_range_provider: Some(FoldingRangeProviderCapability::Simple(true)),
            inlay_hint_provider: Some(OneOf::Left(true)),
            rename_provider: Some(OneOf::Right(RenameOptions {
                prepare_provider: Some(true),
                work_done_progress_options: Default::default(),
            })),
            code_action_provider: Some(CodeActionProviderCapability::Options(CodeActionOptions {
                code_action_kinds: Some(vec![CodeActionKind::QUICKFIX, CodeActionKind::REFACTOR_REWRITE]),
                resolve_provider: Some(true),
                work_done_progress_options: Default::default(),
            })),
            ..ServerCapabilities::default()
        },
        server_info: Some(ServerInfo {
            name: "turnpass".to_string(),
            version: Some(env!("CARGO_PKG_VERSION").to_string()),
        }),
    }
}

/// The `file:` URI of a path, percent-encoded.
pub fn file_uri(path: &Path) -> Option<Uri> {
    let text = path.to_str()?;
    let mut encoded = String::from("file://");
    for byte in text.bytes() {
        if byte.is_ascii_alphanumeric() || b"/-._~".contains(&byte) {
            encoded.push(byte as char);
        } else {
            encoded.push_str(&format!("%{byte:02X}"));
        }
    }
    encoded.parse().ok()
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
