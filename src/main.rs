//! The `turnpass` binary: command-line parsing, files and exit codes around the library.

// The binary is where I/O belongs; the library bans it through clippy.toml.
#![allow(clippy::disallowed_methods)]

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
