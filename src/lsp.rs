//! The language server's analysis: what `turnpass lsp` tells an editor about a program.
//!
//! Everything here is pure: a [`Document`] holds a program's text and keeps it parsed as
//! the editor changes it (re-parsing only the blocks an edit touches, see
//! `lsp/document.rs`); the other modules answer the protocol's questions from a document
//! (diagnostics, hover, symbols, definitions, formatting). The message loop in `server.rs`
//! ties them to the protocol and reads no file itself: it asks a [`server::Host`] for the
//! settings files. `stdio.rs` is the I/O layer: the stdio connection, the message loop, the
//! worker threads, and the host that reads `turnpass.toml`.

pub(crate) mod actions;
pub mod analysis;
mod assemble;
mod chunk;
pub(crate) mod completion;
pub(crate) mod definition;
pub(crate) mod document;
pub(crate) mod folding;
pub(crate) mod format;
mod frame;
pub(crate) mod hover;
pub(crate) mod inlay;
pub(crate) mod names;
pub(crate) mod position;
pub(crate) mod rename;
pub(crate) mod roles;
pub(crate) mod semantic_tokens;
pub mod server;
pub(crate) mod settings;
pub mod stdio;
pub(crate) mod symbols;

pub use document::{Document, LinePosition, Snapshot};
