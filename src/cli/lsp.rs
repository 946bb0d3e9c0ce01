//! `turnpass lsp`: the language server on standard input and output, for editors.
//!
//! The server itself is the library's `lsp` module; this only maps how the session ended
//! to an exit code, as the protocol asks: 0 when the client sent `shutdown` before `exit`,
//! 1 when it did not.

use std::process::ExitCode;

use super::common::CliError;

pub fn run() -> Result<ExitCode, CliError> {
    match turnpass::lsp::stdio::run_stdio() {
        Ok(true) => Ok(ExitCode::SUCCESS),
        Ok(false) => Ok(ExitCode::from(1)),
        Err(message) => Err(CliError::Protocol(message)),
    }
}
