//! `turnpass check`: the errors in programs, as a compiler's check finds them: the parse,
//! then the semantic pass and the toolpath's validation that `simulate` runs, so that a
//! program `check` passes is one `simulate`, `expand` and the language server accept
//! (`--syntax-only` stops after the parse).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use turnpass::diagnostic::render::{RenderSource, render_terminal, to_json};
use turnpass::source::LineIndex;
use turnpass::syntax::{self, Statement};

use super::common::{
    CliError, Format, ReadArgs, RunArgs, StockArgs, analyse, display_name, model_source, note_machine_defaults,
    pipeline_settings, plural, read_input, resolve,
};
use super::streams;

#[derive(Args)]
pub struct CheckArgs {
    /// Program files; `-` reads standard input.
    #[arg(required = true)]
    files: Vec<PathBuf>,
    #[command(flatten)]
    read: ReadArgs,
    #[command(flatten)]
    run: RunArgs,
    #[command(flatten)]
    stock: StockArgs,
    /// Check the syntax only: the parse, without the semantic pass (P/Q targets, arcs,
    /// profiles, feeds) and the toolpath's checks.
    #[arg(long)]
    syntax_only: bool,
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
    let color = streams::stdout_color();
    for path in &args.files {
        let resolved = resolve(&args.read, path)?;
        let bytes = read_input(path)?;
        let part = args.stock.check(&resolved);
        note_machine_defaults(
            &resolved,
            (!args.syntax_only).then_some(&args.run),
            (!args.syntax_only).then_some(part.stock.is_some()),
        );
        let name = display_name(path);
        // A file that is not text gets one diagnostic, not a parse that echoes its bytes.
        if let Some(not_text) = turnpass::source::not_text(&bytes) {
            any_errors = true;
            let shown = not_text.shown(&bytes);
            let render = RenderSource::new(&name, &shown);
            let diagnostics = [not_text.diagnostic()];
            match args.format {
                Format::Json => json.extend(to_json(&render, &diagnostics)),
                Format::Human => {
                    let mut text = render_terminal(&render, &diagnostics, color);
                    text.extend_from_slice(format!("{name}: not a text program; not read\n").as_bytes());
                    streams::out(text)?;
                }
            }
            continue;
        }
        let (parsed, mut diagnostics) = if args.syntax_only {
            let parsed = syntax::parse(&bytes, &resolved.options);
            let diagnostics = parsed.diagnostics.clone();
            (parsed, diagnostics)
        } else {
            let analysed = analyse(&bytes, &pipeline_settings(&resolved, &args.run, true).with_part(part));
            (analysed.parsed, analysed.diagnostics)
        };
        if let Some(warning) = parsed.program.nothing_to_run() {
            diagnostics.insert(0, warning);
        }
        let errors = diagnostics.iter().filter(|d| d.is_error()).count();
        any_errors |= errors > 0;
        let render = RenderSource::new(&name, &bytes);
        match args.format {
            Format::Json => json.extend(to_json(&render, &diagnostics)),
            Format::Human => {
                let mut text = render_terminal(&render, &diagnostics, color);
                if args.verbose {
                    let lines = LineIndex::new(&bytes);
                    text.extend_from_slice(format!("{name}:\n").as_bytes());
                    text.extend_from_slice(format!("{}\n", model_source(&args.read, &resolved)).as_bytes());
                    text.extend_from_slice(parsed.detection.explain(&lines).as_bytes());
                    text.extend_from_slice(summary_of_statements(&parsed.program).as_bytes());
                }
                let warnings = diagnostics.len() - errors;
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
                streams::out(text)?;
            }
        }
    }
    if args.format == Format::Json {
        let text = serde_json::to_string_pretty(&json).unwrap_or_else(|_| "[]".to_string());
        streams::out(text + "\n")?;
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
