//! Command-line interface: arguments, files, settings lookup, output and exit codes.
//!
//! Exit codes (one rule for every command, README "Exit codes"): 0 the command did what
//! was asked (no `error` printed), 1 the input cannot give it (the program has errors or no
//! block to run, an OSP machining-centre program given to a command that runs it, `fmt
//! --check` found changes, `compensate` refused, `verify` found a violation, a measurement
//! does not read), 2 usage or I/O error. A run that exits 1 writes no program, table or
//! plot, to a file or to standard output. Output files are written to a temporary file
//! beside the target, synced and renamed, so a failed run never leaves a partial file;
//! devices, FIFOs and standard output are written directly. One module per command under
//! `cli/`; `common.rs` holds what they share; `streams.rs` is the one place that writes to
//! standard output and error.

// Every write to a standard stream goes through `streams`, which treats a closed pipe as
// the end of the output; the print macros would panic on it instead.
#![deny(clippy::print_stdout, clippy::print_stderr)]

mod batch;
mod check;
mod common;
mod compensate;
mod diagnose;
mod error;
mod fmt;
mod lsp;
mod model;
mod numbers;
mod plot;
mod report;
mod simulate;
mod streams;
mod table;
mod thermal;
mod verify;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

const EXAMPLES: &str = "\
Examples:
  turnpass check examples/programs/thesis-o2005-arc.nc
  turnpass check --format json part.nc other.MIN
  turnpass check --verbose --dialect auto part.nc
  turnpass fmt part.nc -o part.nc            (lossless: untouched blocks stay byte-identical)
  turnpass fmt --canonical --check part.nc   (exit 1 if the program is not in normal form)
  cat part.nc | turnpass check -
  turnpass compensate part.nc --model machine.toml -o part-comp.nc
  cat part.nc | turnpass compensate - > part-comp.nc     (model from turnpass.toml)
  turnpass compensate *.nc --out-dir compensated/ --report json
  turnpass verify part.nc part-comp.nc --model machine.toml
  turnpass plot part.nc --model machine.toml -o part.svg
  turnpass report part.nc part-comp.nc --model machine.toml -o report.html
  turnpass model report machine.toml
  turnpass table machine.toml --control linuxcnc -o lathe-comp.ini   (and lathe-comp-x.comp, lathe-comp-z.comp)
  turnpass compensate part.nc --model machine.toml --with-table lathe-comp.ini -o part-comp.nc
  turnpass diagnose part.nc --model machine.toml --measured cmm.csv --write-model machine-new.toml --plot gap.svg
  turnpass synth ballbar.nc --model truth.toml --kind ballbar --noise 0.0002 --seed 7 -o trace.csv
  turnpass fit-thermal spindle-log.csv --write-model machine.toml --axis z
  turnpass lsp                               (language server on standard input and output, for editors)

Machine settings come from --model FILE, or from a turnpass.toml found in the program's
directory or above it ([machine] table: dialect, gcode_system, decimal_input, units,
least_increment; [model], [[axis_table]] and [[effect]] tables: the error model).

Exit codes: 0 ok, 1 the input cannot give what was asked (the program has errors or nothing
to run, compensate refused it, verify found a violation, a measurement does not read),
2 usage or I/O error. With exit 1 no program, table or plot is written, to a file or to
standard output: only the diagnostics (check's output) or the findings (verify's).
Every input is read to at most 256 MiB (--max-input-mb raises it).
report writes its page whatever verify finds (exit 0, the verdict on the page).
A closed standard output (`| head`) ends the output quietly; the exit code is the run's.";

#[derive(Parser)]
#[command(name = "turnpass", version, about = "A compiler pass for Okuma OSP and Fanuc-compatible lathe programs", after_help = EXAMPLES)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// When to colour diagnostics: auto (on a terminal, unless NO_COLOR is set and not
    /// empty), always or never.
    #[arg(long, global = true, value_enum, value_name = "WHEN", default_value = "auto")]
    color: streams::ColorChoice,
    /// The largest input read, in MiB (a program, model, axis table, measurement or log;
    /// standard input too): a larger one is refused, exit 2. At most 4095.
    #[arg(
        long,
        global = true,
        value_name = "MIB",
        default_value_t = turnpass::source::DEFAULT_INPUT_LIMIT_MIB,
        value_parser = clap::value_parser!(u64).range(1..=turnpass::source::MAX_INPUT_LIMIT_MIB),
    )]
    max_input_mb: u64,
}

#[derive(Subcommand)]
enum Command {
    /// Report the errors in programs (file:line:column, labelled, with hints).
    Check(check::CheckArgs),
    /// Print a program back: losslessly, or in canonical form.
    Fmt(fmt::FmtArgs),
    /// Print the program with every cycle replaced by the moves it performs.
    Expand(simulate::ExpandArgs),
    /// Print the toolpath the machine moves, and a summary (times, length, roughness).
    Simulate(simulate::SimulateArgs),
    /// Write the program that makes the modelled machine cut the nominal part.
    Compensate(compensate::CompensateArgs),
    /// Predict a compensated program on the model and check it kept every other word.
    Verify(verify::VerifyArgs),
    /// Draw the nominal, actual and compensated paths (SVG), or a ball-bar polar plot.
    Plot(plot::PlotArgs),
    /// One HTML page for a job: verify's figures and verdict, the plots, the edited blocks.
    Report(report::ReportArgs),
    /// Find where a measurement and the model disagree, name the missing effect, add it.
    Diagnose(diagnose::DiagnoseArgs),
    /// Make a measurement (ball bar trace, CMM profile or interferometer table) from a truth model, with noise.
    Synth(diagnose::SynthArgs),
    /// Fit the first-order warm-up and cool-down curves of a thermal log.
    FitThermal(thermal::FitThermalArgs),
    /// Write the control's pitch-error and backlash tables for a model (LinuxCNC, Fanuc, Okuma).
    Table(table::TableArgs),
    /// Serve the Language Server Protocol on standard input and output (for editors).
    Lsp,
    /// Machine models.
    Model {
        #[command(subcommand)]
        command: model::ModelCommand,
    },
}

pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(error) => return usage_error(&error),
    };
    streams::set_color(cli.color);
    common::set_input_limit_mib(cli.max_input_mb);
    if let Err(error) = common::tune_from_environment() {
        streams::err(error.message());
        return ExitCode::from(error.exit_code());
    }
    let result = match cli.command {
        Command::Check(args) => check::check(args),
        Command::Fmt(args) => fmt::fmt(args),
        Command::Expand(args) => simulate::expand(args),
        Command::Simulate(args) => simulate::simulate(args),
        Command::Compensate(args) => compensate::check_arguments(&args)
            .and_then(|()| if args.out_dir.is_some() { batch::run(&args) } else { compensate::compensate(args) }),
        Command::Verify(args) => verify::verify(args),
        Command::Plot(args) => plot::plot(args),
        Command::Report(args) => report::report(args),
        Command::Diagnose(args) => diagnose::run(args),
        Command::Synth(args) => diagnose::run_synth(args),
        Command::FitThermal(args) => thermal::run(args),
        Command::Table(args) => table::run(args),
        Command::Lsp => lsp::run(),
        Command::Model { command } => model::run(command),
    };
    match result {
        Ok(code) => code,
        Err(error) => {
            streams::err(error.message());
            ExitCode::from(error.exit_code())
        }
    }
}

/// Help, the version, or a command line clap refuses: printed through `streams` (help on
/// standard output, an error on standard error), coloured as `--color` says when the
/// command line got as far as giving it.
fn usage_error(error: &clap::Error) -> ExitCode {
    let choice = color_on_command_line().unwrap_or_default();
    streams::set_color(choice);
    let rendered = error.render();
    if error.use_stderr() {
        let text = if streams::stderr_color() { rendered.ansi().to_string() } else { rendered.to_string() };
        streams::err(text);
    } else {
        let text = if streams::stdout_color() { rendered.ansi().to_string() } else { rendered.to_string() };
        // Help on a closed pipe is no error; any other failure has nowhere to go but exit 2.
        if streams::out(text).is_err() {
            return ExitCode::from(2);
        }
    }
    ExitCode::from(u8::try_from(error.exit_code()).unwrap_or(2))
}

/// The `--color` value of a command line that clap did not accept as a whole.
fn color_on_command_line() -> Option<streams::ColorChoice> {
    use clap::ValueEnum;
    let mut args = std::env::args_os().skip(1).take_while(|arg| arg != "--");
    let mut value = None;
    while let Some(arg) = args.next() {
        let arg = arg.to_string_lossy().into_owned();
        if arg == "--color" {
            value = args.next().map(|v| v.to_string_lossy().into_owned());
        } else if let Some(v) = arg.strip_prefix("--color=") {
            value = Some(v.to_string());
        }
    }
    value.and_then(|v| streams::ColorChoice::from_str(&v, true).ok())
}
