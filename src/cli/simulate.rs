//! `turnpass expand` and `turnpass simulate`: the cycles written out, and the toolpath.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, ValueEnum};

use turnpass::printer;
use turnpass::semantic::{self, Machine};
use turnpass::simulation;
use turnpass::syntax;

use super::common::{
    CliError, Lowering, ReadArgs, RunArgs, announce_settings, check_output, display_name, lower_and_validate,
    lower_options, model_file_name, not_lowered, read_program, report, write_output,
};

#[derive(Args)]
pub struct ExpandArgs {
    /// Program file; `-` reads standard input.
    file: PathBuf,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "OUT")]
    output: Option<PathBuf>,
    #[command(flatten)]
    read: ReadArgs,
    #[command(flatten)]
    run: RunArgs,
    /// Also say where the machine settings come from.
    #[arg(long, short)]
    verbose: bool,
}

#[derive(Args)]
pub struct SimulateArgs {
    /// Program file; `-` reads standard input.
    file: PathBuf,
    #[arg(long, value_enum, default_value = "csv")]
    format: SimulateFormat,
    #[command(flatten)]
    read: ReadArgs,
    #[command(flatten)]
    run: RunArgs,
    /// Also say where the machine settings come from.
    #[arg(long, short)]
    verbose: bool,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum SimulateFormat {
    Csv,
    Json,
}

pub fn expand(args: ExpandArgs) -> Result<ExitCode, CliError> {
    check_output(args.output.as_deref())?;
    let (bytes, resolved) = read_program(&args.file, &args.read)?;
    let name = display_name(&args.file);
    announce_settings("expand", &name, (&args.read, &args.run), &resolved, args.verbose);
    let parsed = syntax::parse(&bytes, &resolved.options);
    if !semantic::lowers(&parsed.program) {
        return Ok(not_lowered("expand", &name, &bytes, &parsed));
    }
    let machine = Machine::from_settings(&resolved.settings);
    let lowered = semantic::lower(&parsed.program, &machine, &lower_options(&args.run, &resolved.settings, false));
    let mut diagnostics = parsed.diagnostics.clone();
    diagnostics.extend(lowered.diagnostics.iter().cloned());
    diagnostics.sort_by_key(|d| d.span.start);
    report(&name, &bytes, &diagnostics);
    let errors = diagnostics.iter().any(|d| d.is_error());
    if errors {
        // A program that does not lower cleanly is not expanded: no partial output.
        return Ok(ExitCode::from(1));
    }
    let (edits, notes) = turnpass::expand::expansion_edits(&parsed.program, &lowered);
    report(&name, &bytes, &notes);
    let output = printer::print(&parsed.program, &edits);
    write_output(args.output.as_deref(), &output)?;
    Ok(ExitCode::SUCCESS)
}

pub fn simulate(args: SimulateArgs) -> Result<ExitCode, CliError> {
    let (bytes, resolved) = read_program(&args.file, &args.read)?;
    let name = display_name(&args.file);
    announce_settings("simulate", &name, (&args.read, &args.run), &resolved, args.verbose);
    let parsed = syntax::parse(&bytes, &resolved.options);
    if !semantic::lowers(&parsed.program) {
        return Ok(not_lowered("simulate", &name, &bytes, &parsed));
    }
    let Lowering { lowered, machine, diagnostics } = lower_and_validate(&parsed, &resolved, &args.run);
    report(&name, &bytes, &diagnostics);
    let Ok(lowered) = lowered else { return Ok(ExitCode::from(1)) };
    let valid = lowered.valid();
    let rows = simulation::rows(&parsed.program, &valid);
    let summary = simulation::summary(&parsed.program, &lowered, &valid, &machine);
    let output = match args.format {
        SimulateFormat::Csv => {
            let mut text = simulation::csv(&rows).map_err(|e| CliError::Write {
                path: "<stdout>".into(),
                source: std::io::Error::other(e.to_string()),
            })?;
            // The summary goes to standard error so that standard output stays one CSV table.
            let _ = writeln!(std::io::stderr(), "{}", summary_text(&summary));
            text.shrink_to_fit();
            text
        }
        SimulateFormat::Json => {
            // `model_file` is null when the machine defaults are in force.
            let value =
                serde_json::json!({ "model_file": model_file_name(&resolved), "moves": rows, "summary": summary });
            let mut text = serde_json::to_vec_pretty(&value).unwrap_or_default();
            text.push(b'\n');
            text
        }
    };
    std::io::stdout()
        .lock()
        .write_all(&output)
        .map_err(|source| CliError::Write { path: "<stdout>".into(), source })?;
    Ok(if diagnostics.iter().any(|d| d.is_error()) { ExitCode::from(1) } else { ExitCode::SUCCESS })
}

fn summary_text(summary: &simulation::Summary) -> String {
    let mut out = format!(
        "cycle time {:.1} s, cutting time {:.1} s, path {:.1} mm ({:.1} mm cutting), {} moves",
        summary.cycle_time_s, summary.cutting_time_s, summary.path_length_mm, summary.cutting_length_mm, summary.moves
    );
    if summary.rapid_rate_assumed {
        out.push_str(" (rapid rate not in the machine settings: 10 m/min assumed)");
    }
    for pass in &summary.finishing_passes {
        match pass.roughness_mm {
            Some(rt) => out.push_str(&format!(
                "\nfinishing pass at line {}: tool {}, {:.4} mm/rev, nose {:.3} mm, Rt {:.2} µm ({})",
                pass.line,
                pass.tool,
                pass.feed_per_rev_mm,
                pass.nose_radius_mm,
                rt * 1000.0,
                pass.formula
            )),
            None => out.push_str(&format!(
                "\nfinishing pass at line {}: tool {}, {:.4} mm/rev, no nose radius in the tool table",
                pass.line, pass.tool, pass.feed_per_rev_mm
            )),
        }
    }
    out
}
