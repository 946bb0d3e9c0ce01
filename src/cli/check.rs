//! `turnpass check`: the errors in programs.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use turnpass::diagnostic::render::{RenderSource, render_terminal, to_json};
use turnpass::source::LineIndex;
use turnpass::syntax::{self, Statement};

use super::common::{
    CliError, Format, ReadArgs, display_name, model_source, note_machine_defaults, plural, read_input, resolve,
};

#[derive(Args)]
pub struct CheckArgs {
    /// Program files; `-` reads standard input.
    #[arg(required = true)]
    files: Vec<PathBuf>,
    #[command(flatten)]
    read: ReadArgs,
    #[arg(long, value_enum, default_value = "human")]
    format: Format,
    /// Also say where the machine settings come from, which dialect was chosen and why, and
    /// what the program holds.
    #[arg(long, short)]
    verbose: bool,
}

pub fn check(args: CheckArgs) -> Result<ExitCode, CliError> {
    let mut any_errors = false;
    let mut json = Vec::new();
    let color = std::io::stdout().is_terminal();
    let mut stdout = std::io::stdout().lock();
    for path in &args.files {
        let resolved = resolve(&args.read, path)?;
        let bytes = read_input(path)?;
        note_machine_defaults(&resolved, None);
        let name = display_name(path);
        let parsed = syntax::parse(&bytes, &resolved.options);
        any_errors |= parsed.has_errors();
        let render = RenderSource::new(&name, &bytes);
        match args.format {
            Format::Json => json.extend(to_json(&render, &parsed.diagnostics)),
            Format::Human => {
                let mut text = render_terminal(&render, &parsed.diagnostics, color);
                if args.verbose {
                    let lines = LineIndex::new(&bytes);
                    text.extend_from_slice(format!("{name}:\n").as_bytes());
                    text.extend_from_slice(format!("{}\n", model_source(&args.read, &resolved)).as_bytes());
                    text.extend_from_slice(parsed.detection.explain(&lines).as_bytes());
                    text.extend_from_slice(summary_of_statements(&parsed.program).as_bytes());
                }
                let errors = parsed.error_count();
                let warnings = parsed.diagnostics.len() - errors;
                text.extend_from_slice(
                    format!(
                        "{name}: {} blocks, {errors} error{}, {warnings} warning{} or note{}\n",
                        parsed.program.blocks().len(),
                        plural(errors),
                        plural(warnings),
                        plural(warnings)
                    )
                    .as_bytes(),
                );
                stdout.write_all(&text).map_err(|source| CliError::Write { path: "<stdout>".into(), source })?;
            }
        }
    }
    if args.format == Format::Json {
        let text = serde_json::to_string_pretty(&json).unwrap_or_else(|_| "[]".to_string());
        writeln!(stdout, "{text}").map_err(|source| CliError::Write { path: "<stdout>".into(), source })?;
    }
    Ok(if any_errors { ExitCode::from(1) } else { ExitCode::SUCCESS })
}

fn summary_of_statements(program: &syntax::Program<'_>) -> String {
    let mut counts: Vec<(&'static str, usize)> = Vec::new();
    for block in program.blocks() {
        let name = match block.statement {
            Statement::Motion => "motion",
            Statement::Cycle(_) => "cycle",
            Statement::LapCall(_) => "LAP call",
            Statement::LapMarker(_) => "LAP contour marker",
            Statement::Dwell(_) => "dwell",
            Statement::OneShot(_) => "one-shot command",
            Statement::ToolCall => "tool call",
            Statement::Spindle => "spindle",
            Statement::Control => "control",
            Statement::Assignment => "assignment",
            Statement::Invalid => "invalid",
            _ => continue,
        };
        match counts.iter_mut().find(|(n, _)| *n == name) {
            Some((_, c)) => *c += 1,
            None => counts.push((name, 1)),
        }
    }
    let parts: Vec<String> = counts.iter().map(|(n, c)| format!("{c} {n}")).collect();
    format!("  blocks: {}\n", parts.join(", "))
}
