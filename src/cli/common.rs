//! What every command shares: the reading options, settings and model lookup, lowering,
//! diagnostics on standard error, and output written atomically or to standard output.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, ValueEnum};

use turnpass::diagnose::measured::MeasuredError;
use turnpass::diagnostic::render::{RenderSource, render_terminal};
use turnpass::diagnostic::{Diagnostic, DiagnosticKind, SHOWN_DIAGNOSTICS, Severity};
use turnpass::dialect::{Control, DecimalInput, DialectChoice, GCodeSystem};
use turnpass::error_model::ErrorModel;
use turnpass::error_model::model_file::{ModelError, ModelSpec};
use turnpass::machine::{MachineSettings, ModelFile, StockSettings};
use turnpass::parallel::Tuning;
use turnpass::part::PartCheck;
use turnpass::pipeline::{self, Analysed, Lowering, Ready};
use turnpass::semantic::{self, LowerOptions};
use turnpass::source::escape_controls;
use turnpass::syntax::{self, ParseOptions};

pub use super::error::CliError;
use super::streams;

#[derive(Args, Clone)]
pub struct RunArgs {
    /// The block-delete switch: `on` skips blocks starting with `/` (default: the machine
    /// settings, else off).
    #[arg(long, value_enum)]
    pub block_delete: Option<Switch>,
}

/// The bar a run starts from (`check`, `simulate`).
#[derive(Args, Clone)]
pub struct StockArgs {
    /// The bar the program starts from, for this run, over the model file's [stock]:
    /// `diameter=D,length=L` with optional `front=Z` (0) and `bore=B`, in the machine's units,
    /// diameters as diameters. Without either, the smallest bar holding every cut's start is
    /// assumed, and crashes into it are notes.
    #[arg(long, value_name = "diameter=D,length=L[,front=Z][,bore=B]", value_parser = StockSettings::parse)]
    pub stock: Option<StockSettings>,
}

impl StockArgs {
    /// The part model's stock: the flag's, else the model file's, else assumed.
    pub fn check(&self, resolved: &Resolved) -> PartCheck {
        PartCheck { stock: self.stock.or(resolved.stock) }
    }
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum Switch {
    On,
    Off,
}

#[derive(Args, Clone)]
pub struct ReadArgs {
    /// Dialect to read: auto (decide from the text), osp or fanuc.
    #[arg(long, value_parser = parse_dialect)]
    pub dialect: Option<DialectChoice>,
    /// Fanuc G-code system of the machine (A, B or C); a machine setting, never guessed.
    #[arg(long, value_parser = parse_system)]
    pub gcode_system: Option<GCodeSystem>,
    /// The Fanuc-compatible control (fanuc, haas or denford): its own drilling cycles,
    /// lower-case letters; a machine setting, never guessed.
    #[arg(long, value_parser = parse_control)]
    pub control: Option<Control>,
    /// How numbers without a decimal point read on this machine.
    #[arg(long, value_enum)]
    pub decimal_input: Option<DecimalInputArg>,
    /// Machine model file (TOML): its [machine] table holds the settings above, its
    /// [model], [[axis_table]] and [[effect]] tables the error model.
    #[arg(long, value_name = "FILE")]
    pub model: Option<PathBuf>,
    /// The value of a common variable the machine keeps (`--var '#501=350'`, `--var V12=4`),
    /// over the settings' `[machine] variables`; repeatable.
    #[arg(long = "var", value_name = "NAME=VALUE", value_parser = parse_variable)]
    pub variables: Vec<(String, f64)>,
}

/// `NAME=VALUE` of `--var`.
fn parse_variable(text: &str) -> Result<(String, f64), String> {
    let (name, value) = text.split_once('=').ok_or_else(|| format!("`{text}` is not NAME=VALUE"))?;
    let value: f64 = value.trim().parse().map_err(|_| format!("`{value}` is not a number"))?;
    if !value.is_finite() {
        return Err(format!("`{value}` is not a finite number"));
    }
    Ok((name.trim().to_string(), value))
}

#[derive(Clone, Copy, ValueEnum)]
pub enum DecimalInputArg {
    Calculator,
    Increment,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum Format {
    Human,
    Json,
}

/// A slide, on the command line.
#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum AxisArg {
    X,
    Z,
}

impl AxisArg {
    pub fn axis(self) -> turnpass::error_model::model_file::Axis {
        match self {
            AxisArg::X => turnpass::error_model::model_file::Axis::X,
            AxisArg::Z => turnpass::error_model::model_file::Axis::Z,
        }
    }
}

/// An SVG file to write: a name whose extension says another format (`part.png`) is
/// refused, since the file would hold SVG whatever its name says.
pub fn svg_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    match path.extension() {
        Some(extension) if !extension.eq_ignore_ascii_case("svg") => Err(format!(
            "`{s}` names a .{} file, and turnpass draws SVG only: give a name ending in .svg",
            extension.to_string_lossy()
        )),
        _ => Ok(path),
    }
}

fn parse_dialect(s: &str) -> Result<DialectChoice, String> {
    s.parse()
}

fn parse_control(s: &str) -> Result<Control, String> {
    s.parse()
}

fn parse_system(s: &str) -> Result<GCodeSystem, String> {
    s.parse()
}

pub fn display_name(path: &Path) -> String {
    // A name is shown with its control characters escaped, as every text from outside is.
    if path == Path::new("-") {
        "<stdin>".to_string()
    } else {
        turnpass::source::escape_controls(&path.display().to_string()).into_owned()
    }
}

/// The largest input read, in mebibytes (`--max-input-mb`; `turnpass::source::DEFAULT_INPUT_LIMIT_MIB`).
static INPUT_LIMIT_MIB: std::sync::atomic::AtomicU64 =
    std::sync::atomic::AtomicU64::new(turnpass::source::DEFAULT_INPUT_LIMIT_MIB);

/// Set the largest input read, in mebibytes (once, from the command line).
pub fn set_input_limit_mib(mib: u64) {
    INPUT_LIMIT_MIB.store(mib, std::sync::atomic::Ordering::Relaxed);
}

/// An input's bytes: the file `path`, or standard input for `-`. Every input goes through
/// here (programs, models, axis tables, measurements, logs), so none is read past the input
/// limit: a regular file larger than it is refused from its size, unread, and a stream
/// (standard input, a device, a FIFO) once it has given that much (exit 2).
pub fn read_input(path: &Path) -> Result<Vec<u8>, CliError> {
    let mib = INPUT_LIMIT_MIB.load(std::sync::atomic::Ordering::Relaxed);
    let limit = mib << 20;
    let name = display_name(path);
    let read_error = |source| CliError::Read { path: name.clone(), source };
    let read = if path == Path::new("-") {
        turnpass::source::read_at_most(std::io::stdin().lock(), limit)
    } else {
        let file = std::fs::File::open(path).map_err(read_error)?;
        if file.metadata().is_ok_and(|meta| meta.is_file() && meta.len() > limit) {
            Ok(None)
        } else {
            turnpass::source::read_at_most(file, limit)
        }
    };
    match read.map_err(read_error)? {
        Some(bytes) => Ok(bytes),
        None => Err(CliError::TooLarge { path: name, limit_mib: mib }),
    }
}

/// An input that must be UTF-8 text (a model file): [`read_input`], then the text.
pub fn read_input_text(path: &Path) -> Result<String, CliError> {
    String::from_utf8(read_input(path)?).map_err(|_| CliError::Read {
        path: display_name(path),
        source: std::io::Error::new(std::io::ErrorKind::InvalidData, "stream did not contain valid UTF-8"),
    })
}

/// A program file's bytes, refused (exit 1, one diagnostic) when the file is not text
/// (`turnpass::source::not_text`), so that a binary file is never parsed.
pub fn read_program_bytes(path: &Path) -> Result<Vec<u8>, CliError> {
    let bytes = read_input(path)?;
    let Some(not_text) = turnpass::source::not_text(&bytes) else { return Ok(bytes) };
    let name = display_name(path);
    // Rendered from the bytes before the first control byte: none of the rest is echoed.
    let mut text = rendered(&name, &not_text.shown(&bytes), &[not_text.diagnostic()]);
    text.extend_from_slice(format!("{name}: not a text program; not read\n").as_bytes());
    Err(CliError::Rejected(text))
}

/// A data file (CSV) as UTF-8 text; a byte that is not is reported at its line and column.
pub fn read_data_text(path: &Path) -> Result<String, CliError> {
    let bytes = read_input(path)?;
    String::from_utf8(bytes).map_err(|error| {
        let bytes = error.as_bytes();
        let at = error.utf8_error().valid_up_to();
        let (line, column) = turnpass::source::LineIndex::new(bytes).position(at as u32);
        CliError::NotUtf8 { path: display_name(path), line, column, byte: bytes[at] }
    })
}

/// A measurement or log that does not read: the problem at its file, line and column,
/// rendered as a program's diagnostics are, and a line saying what `command` did not do
/// (exit 1: it is the data's fault, as errors of a program are).
pub fn data_invalid(name: &str, text: &str, error: MeasuredError, command: &str) -> CliError {
    data_refused(name, text, error, command, "does not read")
}

/// [`data_invalid`] for a measurement that reads and does not fit the program (a point off
/// the part, a trace the other way round from the program's circle).
pub fn data_misfit(name: &str, text: &str, error: MeasuredError, command: &str) -> CliError {
    data_refused(name, text, error, command, "does not fit the program")
}

fn data_refused(name: &str, text: &str, error: MeasuredError, command: &str, why: &str) -> CliError {
    let kind = DiagnosticKind::DataInvalid { message: error.message, label: error.label, hint: error.hint };
    let mut out = rendered(name, text.as_bytes(), &[Diagnostic::error(kind, error.span)]);
    out.extend_from_slice(format!("{command}: {name} {why}; nothing is done\n").as_bytes());
    CliError::Rejected(out)
}

/// The model file for `program`: `--model`, else the nearest `turnpass.toml` above it.
fn model_path(read: &ReadArgs, program: &Path) -> Option<PathBuf> {
    if let Some(path) = &read.model {
        return Some(path.clone());
    }
    let start = if program == Path::new("-") {
        std::env::current_dir().ok()
    } else {
        std::fs::canonicalize(program).ok().and_then(|p| p.parent().map(Path::to_path_buf))
    };
    start.and_then(|dir| dir.ancestors().map(|d| d.join("turnpass.toml")).find(|p| p.is_file()))
}

/// A program's settings, and the model file they came from.
pub struct Resolved {
    pub options: ParseOptions,
    pub decimal_input: DecimalInput,
    pub increment_places: u8,
    pub settings: MachineSettings,
    /// The model file's `[stock]`, when it has one.
    pub stock: Option<StockSettings>,
    /// The model file and its text, when there is one.
    pub model: Option<(PathBuf, String)>,
}

pub fn resolve(read: &ReadArgs, program: &Path) -> Result<Resolved, CliError> {
    let model = match model_path(read, program) {
        Some(path) => {
            let text = read_input_text(&path)?;
            Some((path, text))
        }
        None => None,
    };
    let (mut settings, stock) = match &model {
        Some((path, text)) => {
            let file = ModelFile::from_toml(text)
                .map_err(|problems| model_problems(path, text, ModelError::File(problems)))?;
            (file.machine, file.stock)
        }
        None => (MachineSettings::default(), None),
    };
    settings.variables.extend(read.variables.iter().cloned());
    let dialect = read.dialect.or(settings.dialect.map(DialectChoice::Fixed)).unwrap_or(DialectChoice::Auto);
    let gcode_system = read.gcode_system.or(settings.gcode_system).unwrap_or_default();
    let control = read.control.or(settings.control).unwrap_or_default();
    // Kept unset when neither gives it: the semantic pass says where that matters.
    let given_decimal_input = match read.decimal_input {
        Some(DecimalInputArg::Calculator) => Some(DecimalInput::Calculator),
        Some(DecimalInputArg::Increment) => Some(DecimalInput::Increment),
        None => settings.decimal_input,
    };
    let decimal_input = given_decimal_input.unwrap_or_default();
    let fixed_dialect = match dialect {
        DialectChoice::Fixed(dialect) => Some(dialect),
        DialectChoice::Auto => None,
    };
    Ok(Resolved {
        options: ParseOptions { dialect, gcode_system, machine_kind: None, control },
        decimal_input,
        increment_places: settings.increment_places(),
        // The settings in force, the command line's included.
        settings: MachineSettings {
            dialect: fixed_dialect,
            gcode_system: Some(gcode_system),
            control: Some(control),
            decimal_input: given_decimal_input,
            ..settings
        },
        stock,
        model,
    })
}

/// The model file of `resolved` as a user would name it: relative to the current
/// directory when it lies below it (a found `turnpass.toml` is looked up from the
/// program's canonical path).
pub fn model_file_name(resolved: &Resolved) -> Option<String> {
    let (path, _) = resolved.model.as_ref()?;
    let cwd = std::env::current_dir().ok().and_then(|d| std::fs::canonicalize(d).ok());
    let shown = cwd.as_deref().and_then(|cwd| path.strip_prefix(cwd).ok()).unwrap_or(path);
    Some(shown.display().to_string())
}

/// Where `resolved`'s machine settings come from, for `--verbose`: the `--model` file, the
/// `turnpass.toml` found above the program, or none (the machine defaults).
pub fn model_source(read: &ReadArgs, resolved: &Resolved) -> String {
    match model_file_name(resolved).map(|name| escape_controls(&name).into_owned()) {
        Some(name) if read.model.is_some() => format!("model file {name} (--model)"),
        Some(name) => format!("model file {name} (the nearest turnpass.toml above the program)"),
        None => "no model file: machine defaults".to_string(),
    }
}

/// What a command that runs a program says about its settings before anything else on
/// standard error: the machine defaults note when no model file gives them, and with
/// `verbose` where they come from.
pub fn announce_settings(
    command: &str,
    name: &str,
    (read, run): (&ReadArgs, &RunArgs),
    resolved: &Resolved,
    verbose: bool,
    stock: Option<bool>,
) {
    note_machine_defaults(resolved, Some(run), stock);
    if verbose {
        streams::err_line(format_args!("{command}: {name}: {}", model_source(read, resolved)));
    }
}

/// Say once per run, at the top of standard error, that no model file gives `resolved`'s
/// settings, which machine defaults are in force (the options given on the command line
/// included; `run` for a command that runs the program; `stock` for one that runs the part
/// model, whether a stock is given) and how to set them. Nothing when a model file gives them.
pub fn note_machine_defaults(resolved: &Resolved, run: Option<&RunArgs>, stock: Option<bool>) {
    static SAID: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
    if resolved.model.is_some() || SAID.swap(true, std::sync::atomic::Ordering::Relaxed) {
        return;
    }
    let mut settings = resolved.settings.clone();
    if let Some(run) = run {
        settings.block_delete = Some(lower_options(run, &settings, false).block_delete);
    }
    let mut text =
        String::from("note: no model file (no --model, no turnpass.toml found): machine settings in force:\n");
    let mut line = String::new();
    for word in semantic::settings_in_force(&settings, stock).split(' ') {
        if !line.is_empty() && line.len() + 1 + word.len() > 96 {
            text.push_str(&format!("  {line}\n"));
            line.clear();
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    text.push_str(&format!("  {line}\n"));
    text.push_str(
        "  = set them with --model FILE, or a [machine] table in a turnpass.toml in the program's directory or above\n",
    );
    streams::err(text);
}

/// The error model of a model file: `[model]`, `[[axis_table]]` (files read relative to
/// the model file's directory) and `[[effect]]`.
pub fn load_error_model(path: &Path, text: &str) -> Result<ErrorModel, CliError> {
    let (spec, dir) = model_spec(path, text)?;
    let (model, warnings) =
        spec.build_with_warnings(|file| read_table(&dir, file)).map_err(|e| model_problems(path, text, e))?;
    // An error the model holds twice is said where the model is read, by every command.
    streams::err(rendered(&path.display().to_string(), text.as_bytes(), &warnings));
    Ok(model)
}

/// A model file's spec and the directory its tables are read from.
pub fn model_spec(path: &Path, text: &str) -> Result<(ModelSpec, PathBuf), CliError> {
    let spec = ModelSpec::read(text).map_err(|problems| model_problems(path, text, ModelError::File(problems)))?;
    Ok((spec, folder_of(path).to_path_buf()))
}

/// The folder a file is in (`.` for a bare name).
pub fn folder_of(path: &Path) -> &Path {
    path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."))
}

/// A model's table file, read relative to the model file's folder `dir`; the error says
/// the path it tried.
pub fn read_table(dir: &Path, file: &str) -> Result<String, String> {
    let path = dir.join(file);
    read_input_text(&path).map_err(|error| match error {
        CliError::Read { source, .. } => format!("{}: {source}", path.display()),
        other => other.to_string(),
    })
}

/// The problems of the model file at `path` (its text `text`) rendered as diagnostics on it,
/// or on the table file they are in, as the error that ends the run.
pub fn model_problems(path: &Path, text: &str, error: ModelError) -> CliError {
    let name = path.display().to_string();
    let mut out = match &error {
        ModelError::File(problems) => rendered(&name, text.as_bytes(), &problems.diagnostics),
        ModelError::Model(diagnostic) => rendered(&name, text.as_bytes(), std::slice::from_ref(diagnostic)),
        ModelError::TableFile { file, text, diagnostic } => {
            let table = folder_of(path).join(file).display().to_string();
            rendered(&table, text.as_bytes(), std::slice::from_ref(diagnostic))
        }
    };
    out.extend_from_slice(format!("error: invalid machine model {}\n", escape_controls(&name)).as_bytes());
    CliError::Diagnosed(String::from_utf8_lossy(&out).into_owned())
}

/// The error model `resolved` names; a command that needs one fails without it.
pub fn required_error_model(resolved: &Resolved, command: &str) -> Result<ErrorModel, CliError> {
    match &resolved.model {
        Some((path, text)) => {
            let model = load_error_model(path, text)?;
            if model.is_empty() {
                // A settings-only file (a `turnpass.toml` beside the programs) is found as
                // readily as a measured model: say that this one moves nothing.
                streams::err_line(format_args!(
                    "note: {} has no error terms ([[axis_table]] or [[effect]]): {command} takes the machine as \
                     perfect; give --model FILE for a measured machine",
                    model_file_name(resolved).unwrap_or_else(|| path.display().to_string())
                ));
            }
            Ok(model)
        }
        None => Err(CliError::Usage(format!(
            "{command} needs a machine model: give --model FILE, or put a turnpass.toml in the program's \
             directory or above it"
        ))),
    }
}

/// The name a provenance comment gives the model of `resolved`: its `[machine] name`, else
/// its file name.
pub fn model_name(resolved: &Resolved) -> String {
    let file = resolved.model.as_ref().and_then(|(path, _)| path.file_name()).map(|n| n.to_string_lossy().into_owned());
    resolved.settings.name.clone().or(file).unwrap_or_default()
}

/// The first [`SHA256_DIGITS`](turnpass::compensation::provenance::SHA256_DIGITS) hex
/// digits of the SHA-256 of the model of `resolved`: its file and every table file it reads.
pub fn model_sha256(resolved: &Resolved) -> Result<String, CliError> {
    use turnpass::compensation::provenance::{SHA256_DIGITS, model_sha256};
    let Some((path, text)) = &resolved.model else { return Ok(String::new()) };
    let (spec, dir) = model_spec(path, text)?;
    let mut tables = Vec::new();
    for file in spec.axis_table.iter().filter_map(|table| table.file.as_ref().map(|file| file.get_ref().as_str())) {
        let table = dir.join(file);
        tables.push(read_input(&table)?);
    }
    let mut digest = model_sha256(text.as_bytes(), tables.iter().map(Vec::as_slice));
    digest.truncate(SHA256_DIGITS);
    Ok(digest)
}

/// A program's bytes and the settings it is read with.
pub fn read_program(path: &Path, read: &ReadArgs) -> Result<(Vec<u8>, Resolved), CliError> {
    let resolved = resolve(read, path)?;
    let bytes = read_program_bytes(path)?;
    Ok((bytes, resolved))
}

/// `TURNPASS_SERIAL=USE,…` (names of `turnpass::parallel::Tuning::USES`, or `all`): run
/// those uses of a second thread on one, to measure what each gives (README,
/// "Performance"). The output is the same either way.
pub fn tune_from_environment() -> Result<(), CliError> {
    let Ok(names) = std::env::var("TURNPASS_SERIAL") else { return Ok(()) };
    let mut tuning = Tuning::DEFAULT;
    for name in names.split(',').map(str::trim).filter(|n| !n.is_empty()) {
        tuning = tuning.with_serial(name).ok_or_else(|| {
            CliError::Usage(format!(
                "TURNPASS_SERIAL: no use of threads is named `{name}`; the uses are {} (or all)",
                Tuning::USES.join(", ")
            ))
        })?;
    }
    turnpass::parallel::set_tuning(tuning);
    Ok(())
}

pub fn lower_options(run: &RunArgs, settings: &MachineSettings, compensation: bool) -> LowerOptions {
    let block_delete = match run.block_delete {
        Some(Switch::On) => true,
        Some(Switch::Off) => false,
        None => settings.block_delete_switch(),
    };
    LowerOptions { nose_radius_compensation: compensation, ..LowerOptions::new(block_delete) }
}

/// Diagnostics rendered for standard error: the first [`SHOWN_DIAGNOSTICS`] of them, then a
/// line with how many more there are (a program read with the wrong settings can have one
/// on every block, megabytes of them).
pub fn rendered(name: &str, bytes: &[u8], diagnostics: &[Diagnostic]) -> Vec<u8> {
    if diagnostics.is_empty() {
        return Vec::new();
    }
    let render = RenderSource::new(name, bytes);
    let shown = &diagnostics[..diagnostics.len().min(SHOWN_DIAGNOSTICS)];
    let mut text = render_terminal(&render, shown, streams::stderr_color());
    let more = diagnostics.len() - shown.len();
    if more > 0 {
        let errors = diagnostics.iter().filter(|d| d.is_error()).count();
        let others = diagnostics.len() - errors;
        text.extend_from_slice(
            format!(
                "{name}: {more} more diagnostic{} not shown ({errors} error{} and {others} warning{} or note{} in \
                 all; `turnpass check` lists every one)\n",
                plural(more),
                plural(errors),
                plural(others),
                plural(others)
            )
            .as_bytes(),
        );
    }
    text
}

pub fn report(name: &str, bytes: &[u8], diagnostics: &[Diagnostic]) {
    streams::err(rendered(name, bytes, diagnostics));
}

pub fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// What `resolved` and `run` give the pipeline; `compensation` turns nose-radius
/// compensation on.
pub fn pipeline_settings(resolved: &Resolved, run: &RunArgs, compensation: bool) -> pipeline::Settings {
    pipeline::Settings::new(resolved.options, &resolved.settings, lower_options(run, &resolved.settings, compensation))
}

/// Parse, lower with nose-radius compensation and validate; `Err` holds the rendered
/// diagnostics and a line saying why when the program is not ready (errors, or not a lathe
/// program). Warnings of a ready program come back in `warnings`.
pub fn ready<'b>(
    name: &str,
    bytes: &'b [u8],
    resolved: &Resolved,
    run: &RunArgs,
    command: &str,
    warnings: &mut Vec<u8>,
) -> Result<Ready<'b>, Vec<u8>> {
    ready_or_diagnostics(name, bytes, resolved, run, command, warnings).map_err(|(text, _)| text)
}

/// [`ready`] with the part model run on `part`'s stock (for a command that needs the
/// finished part).
pub fn ready_with_part<'b>(
    name: &str,
    bytes: &'b [u8],
    (resolved, run): (&Resolved, &RunArgs),
    part: PartCheck,
    command: &str,
    warnings: &mut Vec<u8>,
) -> Result<Ready<'b>, Vec<u8>> {
    let analysed = analyse(bytes, &pipeline_settings(resolved, run, true).with_part(part));
    ready_or_why(name, bytes, command, analysed, warnings).map_err(|(text, _)| text)
}

/// [`ready`], with the diagnostics of a program that is not ready beside their rendering
/// (for a report that lists why).
pub fn ready_or_diagnostics<'b>(
    name: &str,
    bytes: &'b [u8],
    resolved: &Resolved,
    run: &RunArgs,
    command: &str,
    warnings: &mut Vec<u8>,
) -> Result<Ready<'b>, (Vec<u8>, Vec<Diagnostic>)> {
    let analysed = analyse(bytes, &pipeline_settings(resolved, run, true));
    ready_or_why(name, bytes, command, analysed, warnings)
}

/// The ready program of `analysed`, or the rendered reason it is not.
fn ready_or_why<'b>(
    name: &str,
    bytes: &[u8],
    command: &str,
    analysed: Analysed<'b>,
    warnings: &mut Vec<u8>,
) -> Result<Ready<'b>, (Vec<u8>, Vec<Diagnostic>)> {
    if let Some(warning) = analysed.parsed.program.nothing_to_run() {
        let mut text = rendered(name, bytes, std::slice::from_ref(&warning));
        text.extend_from_slice(format!("{command}: {name} holds no block to run; nothing is written\n").as_bytes());
        // The refusal is the error here: the diagnostic itself is a warning.
        return Err((text, vec![Diagnostic { severity: Severity::Error, ..warning }]));
    }
    if matches!(analysed.lowering, Lowering::NotLowered) {
        let mut text = rendered(name, bytes, &analysed.diagnostics);
        text.extend_from_slice(
            format!(
                "{command}: {name} is an OSP machining-centre program; turnpass runs lathe programs only, so \
                 nothing is written (`turnpass check` checks its syntax)\n"
            )
            .as_bytes(),
        );
        return Err((text, analysed.diagnostics));
    }
    let text = rendered(name, bytes, &analysed.diagnostics);
    match analysed.ready() {
        Ok(ready) => {
            warnings.extend_from_slice(&text);
            Ok(ready)
        }
        Err(analysed) => {
            let mut text = text;
            text.extend_from_slice(format!("{command}: {name} has errors; nothing is written\n").as_bytes());
            Err((text, analysed.diagnostics))
        }
    }
}

/// `pipeline::analyse` for a file: a text cut in the middle of a block
/// (`Lowered::cut_off`) is an error, so that nothing made from part of a program looks
/// whole, and `check` says so as every command that runs it does. (An editor's buffer,
/// often in this state as it is typed, is not refused: the language server does not
/// come here.)
pub fn analyse<'b>(bytes: &'b [u8], settings: &pipeline::Settings) -> Analysed<'b> {
    let mut analysed = pipeline::analyse(bytes, settings);
    if let Some(span) = analysed.lowered().and_then(|lowered| lowered.cut_off) {
        analysed.diagnostics.push(Diagnostic::error(DiagnosticKind::ProgramCut, span));
        analysed.diagnostics.sort_by_key(|d| d.span.start);
    }
    analysed
}

/// A program the semantic pass does not lower (an OSP machining-centre program): its parse
/// diagnostics, a line saying why nothing is printed, and exit code 1, as every command that
/// runs a program gives for one it cannot run (`check` checks its syntax, exit 0).
pub fn not_lowered(command: &str, name: &str, bytes: &[u8], parsed: &syntax::Parsed<'_>) -> ExitCode {
    report(name, bytes, &parsed.diagnostics);
    streams::err_line(format_args!(
        "{command}: {name} is an OSP machining-centre program; turnpass runs lathe programs only, so nothing is \
         printed (`turnpass check` checks its syntax)"
    ));
    ExitCode::from(1)
}

/// Write to `output` as [`write_file`] does, or to standard output for none or `-`.
pub fn write_output(output: Option<&Path>, bytes: &[u8]) -> Result<(), CliError> {
    match output {
        Some(path) => write_file(path, bytes),
        None => streams::out(bytes),
    }
}

/// Write `bytes` to `path` as what it names takes them: a regular file (or a new one) is
/// replaced atomically ([`write_atomically`]); a character device or a FIFO is written
/// directly, since there is no file to replace and nothing to protect (a temporary file
/// renamed over `/dev/null` would replace the device); `-` and the names of standard output
/// (`/dev/stdout`, `/dev/fd/1`, `/proc/self/fd/1`) are standard output itself, so that
/// `>> app.nc` appends. Anything else is refused ([`output_target`]).
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    match output_target(path)? {
        OutputTarget::Stdout => streams::out(bytes),
        OutputTarget::File => write_atomically(path, bytes),
        OutputTarget::Direct => write_directly(path, bytes),
    }
}

/// How an output is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum OutputTarget {
    /// Standard output.
    Stdout,
    /// A regular file, or one to make: a temporary file beside it, renamed over it.
    File,
    /// A character device or a FIFO: opened and written.
    Direct,
}

/// Whether `path` names standard output: `-`, or a name the system gives descriptor 1.
pub fn is_stdout(path: &Path) -> bool {
    [Path::new("-"), Path::new("/dev/stdout"), Path::new("/dev/fd/1"), Path::new("/proc/self/fd/1")].contains(&path)
}

/// What `path` names as an output, found without opening it (opening a FIFO for reading
/// or writing waits for the other end): see [`write_file`]. Refused: a folder, a block
/// device or socket, and a descriptor of this process other than standard output (a file
/// reopened through `/dev/stderr` or `/dev/fd/N` is written from its start, over what it
/// held).
fn output_target(path: &Path) -> Result<OutputTarget, CliError> {
    if is_stdout(path) {
        return Ok(OutputTarget::Stdout);
    }
    let refused = |why: String| CliError::Write {
        path: path.display().to_string(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidInput, why),
    };
    let descriptor = ["/dev/fd/", "/proc/self/fd/", "/dev/stderr", "/dev/stdin"]
        .iter()
        .any(|prefix| path.to_str().is_some_and(|p| p.starts_with(prefix)));
    if descriptor {
        return Err(refused(
            "it names a descriptor of this process; write to standard output (-o - or /dev/stdout) or to a file"
                .to_string(),
        ));
    }
    let kind = match std::fs::metadata(path) {
        Ok(meta) => meta.file_type(),
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => return Ok(OutputTarget::File),
        // A folder on the way that cannot be read is found when the file is written.
        Err(_) => return Ok(OutputTarget::File),
    };
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_char_device() || kind.is_fifo() {
            return Ok(OutputTarget::Direct);
        }
        if kind.is_block_device() || kind.is_socket() {
            let what = if kind.is_socket() { "a socket" } else { "a block device" };
            return Err(refused(format!(
                "it is {what}; turnpass writes to files, character devices, FIFOs and standard output"
            )));
        }
    }
    if kind.is_dir() {
        return Err(refused("it is a directory; give a file name".to_string()));
    }
    Ok(OutputTarget::File)
}

/// Write `bytes` into the device or FIFO `path`: opened for writing (a FIFO waits for its
/// reader, as any writer does), neither made nor truncated.
fn write_directly(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    let error = |source| CliError::Write { path: path.display().to_string(), source };
    let mut file = std::fs::OpenOptions::new().write(true).open(path).map_err(error)?;
    file.write_all(bytes).and_then(|()| file.flush()).map_err(error)
}

/// Check, before any work, that `output` can be written: what it names can take an output
/// ([`output_target`]), and for a file the folder it goes into exists, so a long run never
/// ends in "cannot write". `None` and `-` are standard output. Every command that writes a
/// file asks this first.
pub fn check_output(output: Option<&Path>) -> Result<(), CliError> {
    let Some(path) = output else { return Ok(()) };
    if output_target(path)? != OutputTarget::File {
        return Ok(());
    }
    let error = |message: String| CliError::Write {
        path: path.display().to_string(),
        source: std::io::Error::new(std::io::ErrorKind::NotFound, message),
    };
    let target = link_target(path).map_err(|source| CliError::Write { path: path.display().to_string(), source })?;
    let dir = folder_of(&target);
    if !dir.is_dir() {
        return Err(error(format!("the directory {} does not exist", dir.display())));
    }
    if target.is_dir() {
        return Err(error("it is a directory; give a file name".to_string()));
    }
    Ok(())
}

/// Check, before any work, that `dir` (an `--out-dir`) is a folder that exists.
pub fn check_output_dir(dir: &Path) -> Result<(), CliError> {
    if dir.is_dir() { Ok(()) } else { Err(CliError::Usage(format!("--out-dir {}: no such directory", dir.display()))) }
}

/// Write `bytes` to `path` through a temporary file beside the file written and a rename,
/// so readers see the old file or the whole new one, never a part. The temporary file is
/// synced before the rename and the folder after it: without that, after a power cut the
/// new name can point at a file whose data never reached the disk (an empty program).
///
/// A new file gets the mode the umask leaves of `rw-rw-rw-`, as any tool's output does (a
/// DNC service running as another user must be able to read it); a file written over keeps
/// its mode; a symbolic link is written through to the file it names and stays a link.
fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    let error = |source| CliError::Write { path: path.display().to_string(), source };
    let target = link_target(path).map_err(error)?;
    let dir = folder_of(&target);
    if !dir.is_dir() {
        let message = format!("the directory {} does not exist", dir.display());
        return Err(error(std::io::Error::new(std::io::ErrorKind::NotFound, message)));
    }
    remove_stale_temporaries(dir);
    let mut temp = temporary_beside(dir, std::fs::metadata(&target).ok()).map_err(error)?;
    temp.write_all(bytes).map_err(error)?;
    temp.flush().map_err(error)?;
    temp.as_file().sync_all().map_err(error)?;
    temp.persist(&target).map_err(|e| error(e.error))?;
    // The rename is an entry of the folder: synced with it. The file is in place whatever
    // this finds, so a folder that cannot be synced (some file systems refuse) is no error.
    if let Ok(folder) = std::fs::File::open(dir) {
        let _ = folder.sync_all();
    }
    Ok(())
}

/// The file `path` names once every symbolic link in its last component is followed (the
/// file need not exist: a link may name a file about to be made). Links in the folders above
/// need no following, because a rename inside a linked folder lands in the real one.
fn link_target(path: &Path) -> std::io::Result<PathBuf> {
    // As many links as Linux follows before it gives ELOOP.
    const MAX_LINKS: usize = 40;
    let mut path = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match std::fs::symlink_metadata(&path) {
            Ok(meta) if meta.file_type().is_symlink() => {
                let to = std::fs::read_link(&path)?;
                // A relative link is relative to its own folder; `join` keeps an absolute one.
                path = match path.parent() {
                    Some(dir) => dir.join(to),
                    None => to,
                };
            }
            _ => return Ok(path),
        }
    }
    Err(std::io::Error::other("too many levels of symbolic links"))
}

/// How a temporary output file is named: `.turnpass-PID-XXXXXX.partial`, the process that
/// writes it and random letters. A run that is killed (SIGKILL, a power cut) leaves it behind;
/// its name says what it is, and the next run that writes into the folder removes it.
const TEMPORARY_PREFIX: &str = ".turnpass-";
const TEMPORARY_SUFFIX: &str = ".partial";

/// Remove the temporary files of runs that are no longer running from `dir`: those whose
/// process is gone. A file of a run still writing (another turnpass, at the same time) is
/// left alone. Failures are ignored: a leftover is untidy, not wrong.
fn remove_stale_temporaries(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name
            .to_str()
            .and_then(|n| n.strip_prefix(TEMPORARY_PREFIX))
            .filter(|n| n.ends_with(TEMPORARY_SUFFIX))
            .and_then(|n| n.split('-').next())
            .and_then(|pid| pid.parse::<u32>().ok())
        else {
            continue;
        };
        if pid != std::process::id() && !process_runs(pid) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Whether process `pid` runs (on Linux, `/proc` has it; elsewhere a process is taken to
/// run, and nothing is removed).
fn process_runs(pid: u32) -> bool {
    if cfg!(target_os = "linux") { Path::new("/proc").join(pid.to_string()).exists() } else { true }
}

/// A temporary file in `dir`, named as [`TEMPORARY_PREFIX`] says, that has the mode the file
/// it replaces has (`existing`), or, for a new file, the mode the umask gives: it is created
/// with `rw-rw-rw-`, which the system reduces by the umask, so the umask is never read or
/// changed (the batch writes from several threads at once).
#[cfg(unix)]
fn temporary_beside(dir: &Path, existing: Option<std::fs::Metadata>) -> std::io::Result<tempfile::NamedTempFile> {
    use std::os::unix::fs::PermissionsExt;
    let prefix = format!("{TEMPORARY_PREFIX}{}-", std::process::id());
    let temp = tempfile::Builder::new()
        .prefix(&prefix)
        .suffix(TEMPORARY_SUFFIX)
        .permissions(std::fs::Permissions::from_mode(0o666))
        .tempfile_in(dir)?;
    if let Some(existing) = existing {
        temp.as_file().set_permissions(existing.permissions())?;
    }
    Ok(temp)
}

#[cfg(not(unix))]
fn temporary_beside(dir: &Path, existing: Option<std::fs::Metadata>) -> std::io::Result<tempfile::NamedTempFile> {
    let prefix = format!("{TEMPORARY_PREFIX}{}-", std::process::id());
    let temp = tempfile::Builder::new().prefix(&prefix).suffix(TEMPORARY_SUFFIX).tempfile_in(dir)?;
    if let Some(existing) = existing {
        temp.as_file().set_permissions(existing.permissions())?;
    }
    Ok(temp)
}
