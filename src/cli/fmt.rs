//! `turnpass fmt`: a program printed back, losslessly or in canonical form.
//!
//! A program with errors is not printed (exit 1, nothing written, to a file or to standard
//! output), as for every command that writes a program: a formatter's output goes on to a
//! control or an editor buffer, and a damaged program must not travel with it.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use turnpass::printer::{self, CanonicalOptions, Edits};
use turnpass::syntax;

use super::common::{
    CliError, ReadArgs, check_output, display_name, note_machine_defaults, read_program_bytes, report, resolve,
    write_output,
};
use super::streams;

#[derive(Args)]
pub struct FmtArgs {
    /// Program file; `-` reads standard input.
    file: PathBuf,
    /// Output file (default: standard output; `-` is standard output). A program with
    /// errors is written nowhere (exit 1).
    #[arg(short, long, value_name = "OUT")]
    output: Option<PathBuf>,
    /// Write nothing; exit 1 if the output would differ from the input.
    #[arg(long)]
    check: bool,
    /// Rewrite every block in the normal form instead of printing losslessly.
    #[arg(long)]
    canonical: bool,
    #[command(flatten)]
    read: ReadArgs,
}

pub fn fmt(args: FmtArgs) -> Result<ExitCode, CliError> {
    check_output(args.output.as_deref().filter(|_| !args.check))?;
    let resolved = resolve(&args.read, &args.file)?;
    let bytes = read_program_bytes(&args.file)?;
    note_machine_defaults(&resolved, None, None);
    let name = display_name(&args.file);
    let parsed = syntax::parse(&bytes, &resolved.options);
    report(&name, &bytes, &parsed.diagnostics);
    if parsed.has_errors() {
        streams::err_line(format_args!("fmt: {name} has errors; nothing is written"));
        return Ok(ExitCode::from(1));
    }
    let output = if args.canonical {
        let options =
            CanonicalOptions { decimal_input: resolved.decimal_input, increment_places: resolved.increment_places };
        printer::print_canonical(&parsed.program, &options)
    } else {
        printer::print(&parsed.program, &Edits::new())
    };
    if args.check {
        if output != bytes {
            streams::err_line(format_args!("{name}: would change"));
            return Ok(ExitCode::from(1));
        }
        return Ok(ExitCode::SUCCESS);
    }
    write_output(args.output.as_deref(), &output)?;
    Ok(ExitCode::SUCCESS)
}
