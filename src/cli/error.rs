//! The error that ends a command's run, with its exit code and what standard error shows.

/// An error that ends the run: exit code 2, except [`CliError::Rejected`] (1).
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    #[error("cannot read {path}: {source}")]
    Read { path: String, source: std::io::Error },
    /// An input larger than the input limit (`--max-input-mb`), unread past it.
    #[error(
        "{path} is larger than {limit_mib} MiB, the most turnpass reads of an input; give --max-input-mb N to \
         read up to N MiB (at most 4095)"
    )]
    TooLarge { path: String, limit_mib: u64 },
    #[error("cannot write {path}: {source}")]
    Write { path: String, source: std::io::Error },
    /// A model file that does not read, or holds values out of range: its diagnostics,
    /// rendered as a program's are, printed as they are.
    #[error("{0}")]
    Diagnosed(String),
    #[error("{0}")]
    Usage(String),
    /// The language server's connection failed (the client broke the protocol or went away).
    #[error("language server: {0}")]
    Protocol(String),
    /// A data file that is not UTF-8 text, at its first byte that is not.
    #[error("{path}:{line}:{column}: not UTF-8 text (byte 0x{byte:02X}); save the file as UTF-8 or ASCII")]
    NotUtf8 { path: String, line: usize, column: usize, byte: u8 },
    /// The program was refused before any work (it is not text): its diagnostics, rendered.
    /// Exit code 1, as for any program with errors.
    #[error("{}", String::from_utf8_lossy(.0))]
    Rejected(Vec<u8>),
    /// A measurement or log whose content is wrong (it does not fit the program, a fit of
    /// it fails): exit code 1, as for a program with errors.
    #[error("{0}")]
    Data(String),
}

impl CliError {
    pub fn exit_code(&self) -> u8 {
        match self {
            // The data's own faults, as a program's errors are.
            CliError::Rejected(_) | CliError::Data(_) | CliError::NotUtf8 { .. } => 1,
            _ => 2,
        }
    }

    /// What standard error shows: `error: …` and a line break, or the rendered diagnostics.
    pub fn message(&self) -> Vec<u8> {
        match self {
            CliError::Rejected(text) => text.clone(),
            CliError::Diagnosed(text) => text.clone().into_bytes(),
            other => format!("error: {}\n", turnpass::source::escape_controls(&other.to_string())).into_bytes(),
        }
    }
}
