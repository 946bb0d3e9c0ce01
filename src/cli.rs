//! Command-line interface: arguments, files, settings lookup, output and exit codes.
//!
//! Exit codes: 0 ok, 1 the program has errors (or `fmt --check` found changes), 2 usage or
//! I/O error. Output files are written to a temporary file beside the target and renamed,
//! so a failed run never leaves a partial file.

use std::io::{IsTerminal, Read, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand, ValueEnum};

use turnpass::diagnostic::render::{RenderSource, render_terminal, to_json};
use turnpass::dialect::{DecimalInput, DialectChoice, GCodeSystem};
use turnpass::machine::{MachineSettings, ModelFile};
use turnpass::printer::{self, CanonicalOptions, Edits};
use turnpass::semantic::{self, LowerOptions, Machine};
use turnpass::simulation;
use turnpass::source::LineIndex;
use turnpass::syntax::{self, ParseOptions, Statement};

const EXAMPLES: &str = "\
Examples:
  turnpass check examples/programs/thesis-o2005-arc.nc
  turnpass check --format json part.nc other.MIN
  turnpass check --verbose --dialect auto part.nc
  turnpass fmt part.nc -o part.nc            (lossless: untouched blocks stay byte-identical)
  turnpass fmt --canonical --check part.nc   (exit 1 if the program is not in normal form)
  cat part.nc | turnpass check -

Machine settings come from --model FILE, or from a turnpass.toml found in the program's
directory or above it ([machine] table: dialect, gcode_system, decimal_input, units,
least_increment).

Exit codes: 0 ok, 1 the program has errors, 2 usage or I/O error.";

#[derive(Parser)]
#[command(name = "turnpass", version, about = "A compiler pass for Okuma OSP and Fanuc-compatible lathe programs", after_help = EXAMPLES)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Report the errors in programs (file:line:column, labelled, with hints).
    Check(CheckArgs),
    /// Print a program back: losslessly, or in canonical form.
    Fmt(FmtArgs),
    /// Print the program with every cycle replaced by the moves it performs.
    Expand(ExpandArgs),
    /// Print the toolpath the machine moves, and a summary (times, length, roughness).
    Simulate(SimulateArgs),
    /// Serve the Language Server Protocol on standard input and output (for editors).
    Lsp,
}

#[derive(Args)]
struct ExpandArgs {
    /// Program file; `-` reads standard input.
    file: PathBuf,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "OUT")]
    output: Option<PathBuf>,
    #[command(flatten)]
    read: ReadArgs,
    #[command(flatten)]
    run: RunArgs,
}

#[derive(Args)]
struct SimulateArgs {
    /// Program file; `-` reads standard input.
    file: PathBuf,
    #[arg(long, value_enum, default_value = "csv")]
    format: SimulateFormat,
    #[command(flatten)]
    read: ReadArgs,
    #[command(flatten)]
    run: RunArgs,
}

#[derive(Args)]
struct RunArgs {
    /// The block-delete switch: `on` skips blocks starting with `/` (default: the machine
    /// settings, else off).
    #[arg(long, value_enum)]
    block_delete: Option<Switch>,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum Switch {
    On,
    Off,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum SimulateFormat {
    Csv,
    Json,
}

#[derive(Args)]
struct ReadArgs {
    /// Dialect to read: auto (decide from the text), osp or fanuc.
    #[arg(long, value_parser = parse_dialect)]
    dialect: Option<DialectChoice>,
    /// Fanuc G-code system of the machine (A, B or C); a machine setting, never guessed.
    #[arg(long, value_parser = parse_system)]
    gcode_system: Option<GCodeSystem>,
    /// How numbers without a decimal point read on this machine.
    #[arg(long, value_enum)]
    decimal_input: Option<DecimalInputArg>,
    /// Machine model file (TOML); its [machine] table holds the settings above.
    #[arg(long, value_name = "FILE")]
    model: Option<PathBuf>,
}

#[derive(Clone, Copy, ValueEnum)]
enum DecimalInputArg {
    Calculator,
    Increment,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum Format {
    Human,
    Json,
}

#[derive(Args)]
struct CheckArgs {
    /// Program files; `-` reads standard input.
    #[arg(required = true)]
    files: Vec<PathBuf>,
    #[command(flatten)]
    read: ReadArgs,
    #[arg(long, value_enum, default_value = "human")]
    format: Format,
    /// Also say which dialect was chosen and why, and what the program holds.
    #[arg(long, short)]
    verbose: bool,
}

#[derive(Args)]
struct FmtArgs {
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

fn parse_dialect(s: &str) -> Result<DialectChoice, String> {
    s.parse()
}

fn parse_system(s: &str) -> Result<GCodeSystem, String> {
    s.parse()
}

/// An error that ends the run with exit code 2.
#[derive(Debug, thiserror::Error)]
enum CliError {
    #[error("cannot read {path}: {source}")]
    Read { path: String, source: std::io::Error },
    #[error("cannot write {path}: {source}")]
    Write { path: String, source: std::io::Error },
    #[error("invalid machine settings in {path}: {message}")]
    Settings { path: String, message: String },
}

pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Check(args) => check(args),
        Command::Fmt(args) => fmt(args),
        Command::Expand(args) => expand(args),
        Command::Simulate(args) => simulate(args),
        Command::Lsp => match turnpass::lsp::stdio::run_stdio() {
            Ok(clean) => Ok(if clean { ExitCode::SUCCESS } else { ExitCode::from(1) }),
            Err(message) => Err(CliError::Write { path: "<stdout>".into(), source: std::io::Error::other(message) }),
        },
    };
    match result {
        Ok(code) => code,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::from(2)
        }
    }
}

fn display_name(path: &Path) -> String {
    if path == Path::new("-") { "<stdin>".to_string() } else { path.display().to_string() }
}

fn read_input(path: &Path) -> Result<Vec<u8>, CliError> {
    if path == Path::new("-") {
        let mut bytes = Vec::new();
        std::io::stdin().read_to_end(&mut bytes).map_err(|source| CliError::Read { path: "<stdin>".into(), source })?;
        return Ok(bytes);
    }
    std::fs::read(path).map_err(|source| CliError::Read { path: path.display().to_string(), source })
}

/// The machine settings for `program`: `--model`, else the nearest `turnpass.toml` above it.
fn machine_settings(read: &ReadArgs, program: &Path) -> Result<MachineSettings, CliError> {
    let path = match &read.model {
        Some(path) => Some(path.clone()),
        None => {
            let start = if program == Path::new("-") {
                std::env::current_dir().ok()
            } else {
                std::fs::canonicalize(program).ok().and_then(|p| p.parent().map(Path::to_path_buf))
            };
            start.and_then(|dir| dir.ancestors().map(|d| d.join("turnpass.toml")).find(|p| p.is_file()))
        }
    };
    let Some(path) = path else { return Ok(MachineSettings::default()) };
    let text =
        std::fs::read_to_string(&path).map_err(|source| CliError::Read { path: path.display().to_string(), source })?;
    let file = ModelFile::from_toml(&text)
        .map_err(|e| CliError::Settings { path: path.display().to_string(), message: e.to_string() })?;
    Ok(file.machine)
}

struct Resolved {
    options: ParseOptions,
    decimal_input: DecimalInput,
    increment_places: u8,
    settings: MachineSettings,
}

fn resolve(read: &ReadArgs, program: &Path) -> Result<Resolved, CliError> {
    let settings = machine_settings(read, program)?;
    let dialect = read.dialect.or(settings.dialect.map(DialectChoice::Fixed)).unwrap_or(DialectChoice::Auto);
    let gcode_system = read.gcode_system.or(settings.gcode_system).unwrap_or_default();
    let decimal_input = match read.decimal_input {
        Some(DecimalInputArg::Calculator) => DecimalInput::Calculator,
        Some(DecimalInputArg::Increment) => DecimalInput::Increment,
        None => settings.decimal_input.unwrap_or_default(),
    };
    Ok(Resolved {
        options: ParseOptions { dialect, gcode_system, machine_kind: None },
        decimal_input,
        increment_places: settings.increment_places(),
        settings: MachineSettings { decimal_input: Some(decimal_input), ..settings },
    })
}

fn check(args: CheckArgs) -> Result<ExitCode, CliError> {
    let mut any_errors = false;
    let mut json = Vec::new();
    let color = std::io::stdout().is_terminal();
    let mut stdout = std::io::stdout().lock();
    for path in &args.files {
        let resolved = resolve(&args.read, path)?;
        let bytes = read_input(path)?;
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

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
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

fn fmt(args: FmtArgs) -> Result<ExitCode, CliError> {
    let resolved = resolve(&args.read, &args.file)?;
    let bytes = read_input(&args.file)?;
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
    match &args.output {
        Some(path) if path != Path::new("-") => write_atomically(path, &output)?,
        _ => std::io::stdout()
            .lock()
            .write_all(&output)
            .map_err(|source| CliError::Write { path: "<stdout>".into(), source })?,
    }
    Ok(if parsed.has_errors() { ExitCode::from(1) } else { ExitCode::SUCCESS })
}

/// A program's bytes and the settings it is read with.
fn read_program(path: &Path, read: &ReadArgs) -> Result<(Vec<u8>, Resolved), CliError> {
    let resolved = resolve(read, path)?;
    let bytes = read_input(path)?;
    Ok((bytes, resolved))
}

fn lower_options(run: &RunArgs, settings: &MachineSettings, compensation: bool) -> LowerOptions {
    let block_delete = match run.block_delete {
        Some(Switch::On) => true,
        Some(Switch::Off) => false,
        None => settings.block_delete.unwrap_or(false),
    };
    LowerOptions { nose_radius_compensation: compensation, ..LowerOptions::new(block_delete) }
}

fn report(name: &str, bytes: &[u8], diagnostics: &[turnpass::diagnostic::Diagnostic]) {
    if diagnostics.is_empty() {
        return;
    }
    let render = RenderSource::new(name, bytes);
    let text = render_terminal(&render, diagnostics, std::io::stderr().is_terminal());
    let _ = std::io::stderr().write_all(&text);
}

fn expand(args: ExpandArgs) -> Result<ExitCode, CliError> {
    let (bytes, resolved) = read_program(&args.file, &args.read)?;
    let name = display_name(&args.file);
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
    match &args.output {
        Some(path) if path != Path::new("-") => write_atomically(path, &output)?,
        _ => std::io::stdout()
            .lock()
            .write_all(&output)
            .map_err(|source| CliError::Write { path: "<stdout>".into(), source })?,
    }
    Ok(ExitCode::SUCCESS)
}

fn simulate(args: SimulateArgs) -> Result<ExitCode, CliError> {
    let (bytes, resolved) = read_program(&args.file, &args.read)?;
    let name = display_name(&args.file);
    let parsed = syntax::parse(&bytes, &resolved.options);
    if !semantic::lowers(&parsed.program) {
        return Ok(not_lowered("simulate", &name, &bytes, &parsed));
    }
    let machine = Machine::from_settings(&resolved.settings);
    let lowered = semantic::lower(&parsed.program, &machine, &lower_options(&args.run, &resolved.settings, true));
    let mut diagnostics = parsed.diagnostics.clone();
    diagnostics.extend(lowered.diagnostics.iter().cloned());
    let valid = match turnpass::toolpath::validate(lowered.toolpath.clone(), machine.limits) {
        Ok(valid) => Some(valid),
        Err(problems) => {
            diagnostics.extend(problems);
            None
        }
    };
    diagnostics.sort_by_key(|d| d.span.start);
    report(&name, &bytes, &diagnostics);
    let Some(valid) = valid else { return Ok(ExitCode::from(1)) };
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
            let value = serde_json::json!({ "moves": rows, "summary": summary });
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

/// A program the semantic pass does not lower (an OSP machining-centre program): its parse
/// diagnostics, a line saying why nothing is printed, and the exit code of its syntax check.
fn not_lowered(command: &str, name: &str, bytes: &[u8], parsed: &syntax::Parsed<'_>) -> ExitCode {
    report(name, bytes, &parsed.diagnostics);
    let _ = writeln!(
        std::io::stderr(),
        "{command}: {name} is an OSP machining-centre program; turnpass simulates and expands lathe \
         programs only, so nothing is printed (its syntax was checked)"
    );
    if parsed.has_errors() { ExitCode::from(1) } else { ExitCode::SUCCESS }
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

/// Write `bytes` to `path` through a temporary file in the same directory and a rename, so
/// readers see the old file or the whole new one, never a part.
fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    let error = |source| CliError::Write { path: path.display().to_string(), source };
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    if !dir.is_dir() {
        let message = format!("the directory {} does not exist", dir.display());
        return Err(error(std::io::Error::new(std::io::ErrorKind::NotFound, message)));
    }
    let mut temp = tempfile::NamedTempFile::new_in(dir).map_err(error)?;
    temp.write_all(bytes).map_err(error)?;
    temp.flush().map_err(error)?;
    temp.persist(path).map_err(|e| error(e.error))?;
    Ok(())
}
