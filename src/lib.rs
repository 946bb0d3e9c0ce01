//! turnpass: a compiler pass for CNC lathe programs in the Okuma OSP and Fanuc-compatible
//! dialects.
//!
//! ```txt
//!            ┌──────────── pipeline::analyse ─────────────┐
//! bytes ─▶ syntax ─▶ semantic ─▶ toolpath::validate ─▶ Validated<Lowered>
//!            │  Program (typed AST, spans)                 │
//!            │                                             ▼
//!            │            expand · simulation · compensation (error_model) · diagnose
//!            │                                             │ edits to the AST (back end)
//!            │                                             ▼
//!            ├──────────────────────────────────────────▶ printer ─▶ bytes
//!            └─ diagnostics ─▶ diagnostic::render (codespan, JSON, plain)
//! ```
//!
//! `pipeline` is the façade: it parses, lowers and validates, and the passes after it take
//! only the validated program. `parallel` is the one module that starts threads.
//!
//! The library does no I/O: the binary (`main.rs`, `cli.rs`) reads and writes files, and
//! `clippy.toml` bans file-system and environment calls here.

#![deny(clippy::disallowed_methods)]

pub mod back;
pub mod bounds;
pub mod compensation;
pub mod control_table;
pub mod diagnose;
pub mod diagnostic;
pub mod dialect;
pub mod error_model;
pub mod expand;
pub mod geometry;
pub mod lsp;
pub mod machine;
pub mod measurement_file;
mod memory;
pub mod parallel;
pub mod part;
pub mod pipeline;
pub mod plot;
pub mod printer;
pub mod report;
pub mod semantic;
pub mod simulation;
pub mod source;
pub mod syntax;
pub mod toml_spans;
pub mod toolpath;
