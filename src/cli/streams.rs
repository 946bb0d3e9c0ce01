//! Standard output and standard error: every write of the command line goes through here,
//! and so does the choice of colour.
//!
//! A reader that goes away (`turnpass simulate part.nc | head -1`) is not an error of the
//! run: a write that finds the pipe closed marks the stream closed, later writes to it are
//! dropped, and the run goes on to its own exit code, so that code says the same whether or
//! not anyone read the output (as ripgrep does, the run ends quietly; unlike a C tool, it is
//! not killed by SIGPIPE, which would leave a half-written temporary file behind). Any other
//! failure to write standard output (a full disk under `> out.nc`, or no standard output at
//! all, `>&-`) is an I/O error, exit 2. Standard error has nowhere to report its own
//! failures, so they are dropped.

use std::io::{IsTerminal, Write};
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};

use clap::ValueEnum;

use super::error::CliError;

/// `--color`: when diagnostics and messages are coloured.
#[derive(Clone, Copy, Debug, Default, ValueEnum, PartialEq, Eq)]
pub enum ColorChoice {
    // On a terminal, unless `NO_COLOR` is set to a non-empty value (no-color.org). Plain
    // comments: a doc comment on a variant would turn clap's help into its long form.
    #[default]
    Auto,
    Always,
    Never,
}

static COLOR: OnceLock<ColorChoice> = OnceLock::new();
static STDOUT_CLOSED: AtomicBool = AtomicBool::new(false);
static STDERR_CLOSED: AtomicBool = AtomicBool::new(false);
/// Standard output was not open when the process started (`turnpass simulate part.nc >&-`).
static STDOUT_UNOPENED: AtomicBool = AtomicBool::new(false);

/// Whether standard output is open, asked before the Rust runtime starts: the runtime puts
/// `/dev/null` on a standard stream that is not open, after which writing to it succeeds
/// and the output is silently lost. An output that has nowhere to go is an error instead.
/// (Standard error that is not open loses only messages, which have nowhere else to go.)
#[cfg(target_os = "linux")]
#[used]
#[unsafe(link_section = ".init_array")]
static NOTE_UNOPENED_STDOUT: extern "C" fn() = note_unopened_stdout;

#[cfg(target_os = "linux")]
extern "C" fn note_unopened_stdout() {
    // SAFETY: F_GETFD reads the descriptor's flags and changes nothing; it fails with EBADF
    // exactly when descriptor 1 is not open.
    if unsafe { libc::fcntl(libc::STDOUT_FILENO, libc::F_GETFD) } == -1 {
        STDOUT_UNOPENED.store(true, Ordering::Relaxed);
    }
}

/// Set the colour choice of the run (once, from the command line).
pub fn set_color(choice: ColorChoice) {
    let _ = COLOR.set(choice);
}

/// Whether `choice` colours a stream that is (or is not) a terminal, with `NO_COLOR` as
/// given: `--color` on the command line overrides the environment, as no-color.org asks.
pub fn wants_color(choice: ColorChoice, terminal: bool, no_color: Option<&std::ffi::OsStr>) -> bool {
    match choice {
        ColorChoice::Always => true,
        ColorChoice::Never => false,
        ColorChoice::Auto => terminal && no_color.is_none_or(|value| value.is_empty()),
    }
}

fn color(terminal: bool) -> bool {
    let choice = COLOR.get().copied().unwrap_or_default();
    wants_color(choice, terminal, std::env::var_os("NO_COLOR").as_deref())
}

/// Whether what is written to standard output is coloured.
pub fn stdout_color() -> bool {
    color(std::io::stdout().is_terminal())
}

/// Whether what is written to standard error is coloured.
pub fn stderr_color() -> bool {
    color(std::io::stderr().is_terminal())
}

/// Whether standard error is a terminal (for a progress bar, which only a person watches).
pub fn stderr_is_terminal() -> bool {
    std::io::stderr().is_terminal()
}

/// Draw a progress bar `filled` (0 to 1) full with `label` beside it on standard error, over
/// the one drawn before.
pub fn progress(filled: f64, label: &str) {
    const WIDTH: usize = 30;
    let bars = ((WIDTH as f64 * filled.clamp(0.0, 1.0)) as usize).min(WIDTH);
    err(format!("\r[{}{}] {label}", "#".repeat(bars), " ".repeat(WIDTH - bars)));
}

/// Clear the progress bar's line.
pub fn progress_clear() {
    err("\r\x1b[K");
}

/// Write `bytes` to standard output and flush them: a closed pipe ends the output quietly,
/// any other failure is an I/O error.
pub fn out(bytes: impl AsRef<[u8]>) -> Result<(), CliError> {
    out_parts([bytes.as_ref()])
}

/// [`out`] of a text given as pieces that follow each other.
pub fn out_parts<'a>(parts: impl IntoIterator<Item = &'a [u8]>) -> Result<(), CliError> {
    write_stdout(parts).map_err(stdout_error)
}

/// A failure to write standard output, as the run reports it.
pub fn stdout_error(source: std::io::Error) -> CliError {
    CliError::Write { path: "<stdout>".into(), source }
}

/// Write and flush the pieces to standard output: a closed pipe marks the stream closed
/// (and later writes are dropped), any other failure is returned.
fn write_stdout<'a>(parts: impl IntoIterator<Item = &'a [u8]>) -> std::io::Result<()> {
    if STDOUT_UNOPENED.load(Ordering::Relaxed) {
        return Err(std::io::Error::new(
            std::io::ErrorKind::NotConnected,
            "standard output is not open (`>&-`): redirect it to a file, or to /dev/null to discard it",
        ));
    }
    if STDOUT_CLOSED.load(Ordering::Relaxed) {
        return Ok(());
    }
    let mut stdout = std::io::stdout().lock();
    let written = parts.into_iter().try_for_each(|part| stdout.write_all(part)).and_then(|()| stdout.flush());
    match written {
        Err(error) if error.kind() == std::io::ErrorKind::BrokenPipe => {
            STDOUT_CLOSED.store(true, Ordering::Relaxed);
            Ok(())
        }
        other => other,
    }
}

/// Standard output as a writer, for an output written as it is made (a table of millions
/// of rows is never held whole): buffered, with [`out`]'s rules. Flush it at the end; a
/// failure to write is an I/O error of the run ([`stdout_error`]).
pub struct Out {
    buffer: Vec<u8>,
}

impl Out {
    /// How much is gathered before it is written.
    const CHUNK: usize = 1 << 16;

    pub fn new() -> Out {
        Out { buffer: Vec::with_capacity(Self::CHUNK) }
    }
}

impl Write for Out {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.buffer.extend_from_slice(bytes);
        if self.buffer.len() >= Self::CHUNK {
            self.flush()?;
        }
        Ok(bytes.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        write_stdout([self.buffer.as_slice()])?;
        self.buffer.clear();
        Ok(())
    }
}

/// Write `bytes` to standard error; a failure to do so has nowhere to be reported.
pub fn err(bytes: impl AsRef<[u8]>) {
    if STDERR_CLOSED.load(Ordering::Relaxed) {
        return;
    }
    let mut stderr = std::io::stderr().lock();
    if let Err(error) = stderr.write_all(bytes.as_ref()).and_then(|()| stderr.flush())
        && error.kind() == std::io::ErrorKind::BrokenPipe
    {
        STDERR_CLOSED.store(true, Ordering::Relaxed);
    }
}

/// One line of text on standard error, its control characters escaped: a message quotes
/// names and words from outside (a file name, a comment), which must not drive the terminal.
pub fn err_line(text: impl std::fmt::Display) {
    err(format!("{}\n", turnpass::source::escape_controls(&text.to_string())));
}
