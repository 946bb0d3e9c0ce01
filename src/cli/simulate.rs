//! `turnpass expand` and `turnpass simulate`: the cycles written out, and the toolpath.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, ValueEnum};

use turnpass::expand::Unwritable;
use turnpass::pipeline::{Analysed, Lowering};
use turnpass::printer;
use turnpass::simulation;

use super::common::{
    CliError, ReadArgs, RunArgs, StockArgs, analyse, announce_settings, check_output, display_name, model_file_name,
    not_lowered, pipeline_settings, plural, read_program, report, write_output,
};
use super::streams;

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
    #[command(flatten)]
    stock: StockArgs,
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
    announce_settings("expand", &name, (&args.read, &args.run), &resolved, args.verbose, None);
    // Without nose-radius compensation: the blocks `expand` prints stay under the program's
    // own `G41`/`G42`.
    let analysed = analyse(&bytes, &pipeline_settings(&resolved, &args.run, false));
    if let Some(code) = cannot_run("expand", &name, &bytes, &analysed) {
        return Ok(code);
    }
    report(&name, &bytes, &analysed.diagnostics);
    let errors = analysed.error_count();
    // A program that does not lower cleanly, or whose toolpath is not valid, is not
    // expanded: no partial output.
    let Ok(ready) = analysed.ready() else {
        streams::err_line(format_args!("expand: {name} has {errors} error{}; nothing is written", plural(errors)));
        return Ok(ExitCode::from(1));
    };
    let (mut edits, notes) = turnpass::expand::expansion_edits(ready.program(), &ready.lowered);
    report(&name, &bytes, &notes);
    let mut output = printer::print(ready.program(), &edits);
    // Where the text alone would read as the other dialect, a comment names its own.
    if let Some(dialect) = printer::mark::dialect_to_name(ready.program(), &output) {
        printer::mark::insert_dialect_mark(ready.program(), &mut edits, dialect);
        output = printer::print(ready.program(), &edits);
    }
    // What is about to be written is read back and run as the control reads the original.
    let mut reading = pipeline_settings(&resolved, &args.run, false);
    reading.parse = printer::read_back_options(ready.program());
    match turnpass::expand::check_written(&ready.lowered, &output, &reading) {
        Ok(()) => {}
        Err(Unwritable::Errors(errors)) => {
            report(&format!("{name} (expanded)"), &output, &errors);
            streams::err_line(format_args!(
                "expand: {name}: the expanded program does not read back and run cleanly; nothing is written"
            ));
            return Ok(ExitCode::from(1));
        }
        Err(Unwritable::OtherCuts { original, written }) => {
            streams::err_line(format_args!(
                "expand: {name}: the expanded program would make {written} cutting moves where the program makes \
                 {original}; nothing is written (a defect of turnpass: please report it with the program)"
            ));
            return Ok(ExitCode::from(1));
        }
        Err(Unwritable::OtherCut { index, by_mm }) => {
            streams::err_line(format_args!(
                "expand: {name}: the expanded program's cutting move {index} ends {by_mm:.4} mm from the program's, or \
                 threads otherwise; nothing is written (a defect of turnpass: please report it with the program)"
            ));
            return Ok(ExitCode::from(1));
        }
    }
    write_output(args.output.as_deref(), &output)?;
    Ok(ExitCode::SUCCESS)
}

pub fn simulate(args: SimulateArgs) -> Result<ExitCode, CliError> {
    let (bytes, resolved) = read_program(&args.file, &args.read)?;
    let name = display_name(&args.file);
    let part = args.stock.check(&resolved);
    announce_settings("simulate", &name, (&args.read, &args.run), &resolved, args.verbose, Some(part.stock.is_some()));
    let analysed = analyse(&bytes, &pipeline_settings(&resolved, &args.run, true).with_part(part));
    if let Some(code) = cannot_run("simulate", &name, &bytes, &analysed) {
        return Ok(code);
    }
    report(&name, &bytes, &analysed.diagnostics);
    let errors = analysed.error_count();
    // The blocks in error would be skipped: the toolpath and its times would be of a run
    // the control does not make, so a program with errors gets no table and no summary.
    let Ok(ready) = analysed.ready() else {
        streams::err_line(format_args!("simulate: {name} has {errors} error{}; nothing is printed", plural(errors)));
        return Ok(ExitCode::from(1));
    };
    let rows = simulation::rows(ready.program(), ready.valid());
    let summary = simulation::summary(ready.program(), &ready.lowered, &ready.machine).with_part(ready.part.as_ref());
    // The rows are written as they are made: memory follows the moves, not the text.
    let mut out = streams::Out::new();
    match args.format {
        SimulateFormat::Csv => {
            // The summary goes to standard error so that standard output stays one CSV table.
            streams::err_line(summary_text(&summary));
            simulation::write_csv(rows, &mut out).map_err(|error| match error.into_kind() {
                csv::ErrorKind::Io(source) => streams::stdout_error(source),
                other => streams::stdout_error(std::io::Error::other(format!("{other:?}"))),
            })?;
        }
        SimulateFormat::Json => {
            /// The document's keys in alphabetical order, as the rows' and the summary's.
            #[derive(serde::Serialize)]
            struct Document<'a> {
                /// Null when the machine defaults are in force.
                model_file: Option<String>,
                moves: simulation::Rows<'a>,
                summary: serde_json::Value,
            }
            let summary = serde_json::to_value(&summary).unwrap_or_default();
            let document = Document { model_file: model_file_name(&resolved), moves: rows, summary };
            serde_json::to_writer_pretty(&mut out, &document).map_err(|error| {
                streams::stdout_error(error.io_error_kind().map_or_else(
                    || std::io::Error::other(error.to_string()),
                    |kind| std::io::Error::new(kind, error.to_string()),
                ))
            })?;
            out.write_all(b"\n").map_err(streams::stdout_error)?;
        }
    }
    out.flush().map_err(streams::stdout_error)?;
    Ok(ExitCode::SUCCESS)
}

/// The refusal (exit 1) of a program `command` cannot run, as every command that runs one
/// refuses it: one with no block to run (its diagnostics, that warning first) or an OSP
/// machining-centre program (`not_lowered`).
fn cannot_run(command: &str, name: &str, bytes: &[u8], analysed: &Analysed<'_>) -> Option<ExitCode> {
    if let Some(warning) = analysed.parsed.program.nothing_to_run() {
        let diagnostics: Vec<_> = std::iter::once(warning).chain(analysed.diagnostics.iter().cloned()).collect();
        report(name, bytes, &diagnostics);
        streams::err_line(format_args!("{command}: {name} holds no block to run; nothing is written"));
        return Some(ExitCode::from(1));
    }
    matches!(analysed.lowering, Lowering::NotLowered).then(|| not_lowered(command, name, bytes, &analysed.parsed))
}

fn summary_text(summary: &simulation::Summary) -> String {
    let mut out = format!(
        "cycle time {}, cutting time {}, path {:.1} mm ({:.1} mm cutting), {} moves",
        duration_text(summary.cycle_time_s),
        duration_text(summary.cutting_time_s),
        summary.path_length_mm,
        summary.cutting_length_mm,
        summary.moves
    );
    if summary.rapid_rate_assumed {
        out.push_str(" (rapid rate not in the machine settings: 10 m/min assumed)");
    }
    if let Some(part) = &summary.part {
        out.push_str(&format!(
            "\nstock: bar Ø{:.3}{} mm, front Z{:.3}, {:.3} mm long{}",
            part.stock_diameter_mm,
            if part.stock_bore_mm > 0.0 { format!(" bored Ø{:.3}", part.stock_bore_mm) } else { String::new() },
            part.stock_front_mm,
            part.stock_length_mm,
            if part.stock_assumed { " (assumed: the smallest bar holding every cut's start)" } else { "" }
        ));
        out.push_str(&format!(
            "\nair cutting: {} feed move{} {} nothing, {:.1} mm, {}",
            part.air_moves,
            plural(part.air_moves),
            if part.air_moves == 1 { "removes" } else { "remove" },
            part.air_length_mm,
            duration_text(part.air_time_s)
        ));
        if let Some(z) = part.parted_off_at_mm {
            out.push_str(&format!("\nparted off at Z{z:.3}: the part is the piece in front"));
        }
        if let Some(index) = part.stopped_at_move {
            out.push_str(&format!("\nthe part model stopped at move {} (its bound on work)", index + 1));
        }
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

/// A time as a machinist reads it: seconds under a minute (`42.5 s`), else hours, minutes
/// and seconds (`0:04:27.3`, `74:19:48.3`), to a tenth of a second.
fn duration_text(seconds: f64) -> String {
    let tenths = (seconds * 10.0).round();
    if !(tenths.is_finite() && tenths >= 0.0) {
        return format!("{seconds} s");
    }
    if tenths < 600.0 {
        return format!("{:.1} s", tenths / 10.0);
    }
    let tenths = tenths as u64;
    let (hours, rest) = (tenths / 36_000, tenths % 36_000);
    let (minutes, rest) = (rest / 600, rest % 600);
    format!("{hours}:{minutes:02}:{:02}.{}", rest / 10, rest % 10)
}
