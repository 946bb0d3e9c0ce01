//! `turnpass fmt`: a program printed back, losslessly or in canonical form.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use turnpass::diagnostic::render::{RenderSource, render_terminal};
use turnpass::printer::{self, CanonicalOptions, Edits};
use turnpass::syntax;

use super::common::{
    CliError, ReadArgs, check_output, display_name, note_machine_defaults, read_input, resolve, write_output,
};

#[derive(Args)]
pub struct FmtArgs {
    /// Program file; `-` reads standard input.
    file: PathBuf,
    /// Output file (default: standard output; `-` is standard output).
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
    let bytes = read_input(&args.file)?;
    note_machine_defaults(&resolved, None);
    let name = display_name(&args.file);
    let parsed = syntax::parse(&bytes, &resolved.options);
    let output = if args.canonical {
        let options =
            CanonicalOptions { decimal_input: resolved.decimal_input, increment_places: resolved.increment_places };
        printer::print_canonical(&parsed.program, &options)
    } else {
        printer::print(&parsed.program, &Edits::new())
    };
    if !parsed.diagnostics.is_empty() {
        let render = RenderSource::new(&name, &bytes);
        let text = render_terminal(&render, &parsed.diagnostics, std::io::stderr().is_terminal());
        let _ = std::io::stderr().write_all(&text);
    }
    if args.check {
        if output != bytes {
            eprintln!("{name}: would change");
            return Ok(ExitCode::from(1));
        }
        return Ok(if parsed.has_errors() { ExitCode::from(1) } else { ExitCode::SUCCESS });
    }
    write_output(args.output.as_deref(), &output)?;
    Ok(if parsed.has_errors() { ExitCode::from(1) } else { ExitCode::SUCCESS })
}
