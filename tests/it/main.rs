//! The one integration-test binary (see ARCHITECTURE.md, "Tests are data").
//!
//! Cases live under `tests/cases/`, expected output under `snapshots/`; every test that
//! parses checks the span invariants of `support::check_spans`.

#![allow(clippy::disallowed_methods, clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod arc_times;
mod canonical;
mod check_agrees;
mod cli;
mod closed_loop;
mod compensate;
mod compensate_cycles;
mod control_table;
mod corpus;
mod corpus_semantic;
mod cycles;
mod diagnose;
mod differential;
mod exit_codes;
mod lap;
mod linuxcnc_table;
mod lsp_check;
mod lsp_client;
mod lsp_incremental;
mod lsp_nvim;
mod lsp_protocol;
mod lsp_server;
mod lsp_session;
mod measured_layouts;
mod model_file_docs;
mod moves;
mod nose_radius;
mod outputs;
mod parse;
mod part;
mod plots;
mod print;
mod provenance;
mod readme;
mod report_browser;
mod robustness;
mod roundtrip;
mod simulate;
mod stock_removal;
mod support;
mod synth_surface;
mod thesis;
mod thesis_compensation;
mod trust;
