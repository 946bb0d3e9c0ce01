//! `turnpass diagnose PROGRAM --model M --measured DATA.csv`: where the model and a
//! measurement disagree, which effect is missing, and the gap closing as it is added; and
//! `turnpass synth PROGRAM --model TRUTH --kind …`: a measurement made from a truth model.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, ValueEnum};

use turnpass::diagnose::forward::Nominal;
use turnpass::diagnose::measured::{self, Kind, KindName};
use turnpass::diagnose::synth::{SynthOptions, finest_step_deg, synth, to_csv};
use turnpass::diagnose::{Options, diagnose, model_text, report};
use turnpass::error_model::ErrorModel;
use turnpass::error_model::model_file::{ModelError, with_table_files};
use turnpass::measurement_file::DataError;
use turnpass::pipeline::Ready;
use turnpass::source::Span;

use super::common::{
    AxisArg, CliError, Format, ReadArgs, Resolved, RunArgs, StockArgs, check_output, data_invalid, data_misfit,
    display_name, folder_of, model_problems, model_spec, read_data_text, read_program, read_table, ready,
    ready_with_part, required_error_model, write_file, write_output,
};
use super::numbers::{self, within};
use super::streams;

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum KindArg {
    Ballbar,
    Profile,
    /// An interferometer table (ISO 230-2 CSV) of the slide --axis names.
    Table,
}

impl KindArg {
    fn name(self) -> KindName {
        match self {
            KindArg::Ballbar => KindName::BallBar,
            KindArg::Profile => KindName::Profile,
            KindArg::Table => KindName::Table,
        }
    }

    fn kind(self, axis: Option<AxisArg>) -> Result<Kind, CliError> {
        Ok(match self {
            KindArg::Ballbar => Kind::BallBar,
            KindArg::Profile => Kind::Profile,
            KindArg::Table => match axis {
                Some(axis) => Kind::Table(axis.axis()),
                None => {
                    return Err(CliError::Usage(
                        "an interferometer table needs --axis x|z: the slide it measured".into(),
                    ));
                }
            },
        })
    }
}

#[derive(Args)]
pub struct DiagnoseArgs {
    /// The program the measurement was made on: the ball bar test, or the part.
    pub file: PathBuf,
    /// The measurement (CSV): a ball bar trace, a CMM profile or an interferometer table, in
    /// turnpass's own layout or as instrument software exports it (docs/measurements.md).
    #[arg(long, value_name = "DATA.csv")]
    pub measured: PathBuf,
    /// What the measurement is (default: told by its header). For an interferometer table
    /// (`--kind table --axis x|z`) the program plays no part beyond finding the model.
    #[arg(long, value_enum)]
    pub kind: Option<KindArg>,
    /// The slide an interferometer table measured (default: the table's own `axis:` line).
    #[arg(long, value_enum)]
    pub axis: Option<AxisArg>,
    /// Write the model file with the effects found appended as [[effect]] tables.
    #[arg(long, value_name = "OUT.toml")]
    pub write_model: Option<PathBuf>,
    #[arg(long, value_enum, default_value = "human")]
    pub format: Format,
    /// Draw the residual before and after (SVG): polar for a ball bar, along the surface
    /// for a CMM profile.
    #[arg(long, value_name = "report.svg", value_parser = super::common::svg_path)]
    pub plot: Option<PathBuf>,
    /// Minutes since the machine started when the program started (default: the model's
    /// `start_min`; a CMM file's `start_min` column gives each part's own).
    #[arg(long, allow_negative_numbers = true, value_name = "MIN", value_parser = within(numbers::MINUTES))]
    pub start_min: Option<f64>,
    /// Stop after this many effects.
    #[arg(long, default_value_t = 6)]
    pub max_iterations: usize,
    #[command(flatten)]
    pub read: ReadArgs,
    #[command(flatten)]
    pub run: RunArgs,
}

#[derive(Args)]
pub struct SynthArgs {
    /// The program to measure: a ball bar test (full circles) or a part.
    pub file: PathBuf,
    /// The measurement to make.
    #[arg(long, value_enum)]
    pub kind: KindArg,
    /// The slide of an interferometer table.
    #[arg(long, value_enum)]
    pub axis: Option<AxisArg>,
    /// Interferometer table: the targets, mm along the slide (comma-separated; default
    /// every 5 mm from 0 to 100).
    #[arg(
        long,
        allow_negative_numbers = true,
        value_name = "MM,MM,…",
        value_delimiter = ',',
        value_parser = within(numbers::TARGET_MM),
    )]
    pub targets: Vec<f64>,
    /// Standard deviation of the gauge's noise, mm.
    #[arg(
        long,
        allow_negative_numbers = true,
        value_name = "MM",
        default_value_t = 0.0,
        value_parser = within(numbers::NOISE_MM),
    )]
    pub noise: f64,
    /// Seed of the noise: the same seed gives the same file.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Ball bar: degrees of travel between rows.
    #[arg(
        long,
        allow_negative_numbers = true,
        value_name = "DEG",
        default_value_t = 1.0,
        value_parser = within(numbers::STEP_DEG),
    )]
    pub step_deg: f64,
    /// CMM: mm along the surface between points.
    #[arg(
        long,
        allow_negative_numbers = true,
        value_name = "MM",
        default_value_t = 0.5,
        value_parser = within(numbers::SPACING_MM),
    )]
    pub spacing: f64,
    /// How many readings are probe glitches (chosen by the seed), each off by --glitch-mm.
    #[arg(long, default_value_t = 0)]
    pub glitches: usize,
    /// The size of a glitch, mm (either sign).
    #[arg(
        long,
        allow_negative_numbers = true,
        value_name = "MM",
        default_value_t = 0.025,
        value_parser = within(numbers::GLITCH_MM),
    )]
    pub glitch_mm: f64,
    /// CMM: several parts, started at these minutes since machine start (comma-separated).
    #[arg(
        long,
        allow_negative_numbers = true,
        value_name = "MIN,MIN,…",
        value_delimiter = ',',
        value_parser = within(numbers::MINUTES),
    )]
    pub parts: Vec<f64>,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "DATA.csv")]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub read: ReadArgs,
    #[command(flatten)]
    pub run: RunArgs,
    /// CMM: the bar the part is cut from (or the model file's [stock]): points are then
    /// sampled only where the finished part's surface is, not where a later groove or thread
    /// cut the finished profile away or a lead-in runs in front of the bar.
    #[command(flatten)]
    pub stock: StockArgs,
}

/// The program, its model and its nominal path; `Err` with the exit code when the program
/// is not ready (its diagnostics already on standard error).
fn prepare(
    file: &Path,
    read: &ReadArgs,
    run: &RunArgs,
    command: &str,
    start_min: Option<f64>,
    stock: Option<&StockArgs>,
) -> Result<Result<(Nominal, ErrorModel, Resolved), ExitCode>, CliError> {
    let (bytes, resolved) = read_program(file, read)?;
    let mut model = required_error_model(&resolved, command)?;
    if let Some(start) = start_min {
        model.start_min = start;
    }
    let name = display_name(file);
    let mut messages = Vec::new();
    // On a bar that is only assumed the part is a guess, and a point it would drop may be on
    // the real part: without a stock the profile is sampled on the finishing moves alone.
    let part = stock.map(|stock| stock.check(&resolved)).filter(|part| part.stock.is_some());
    let ready = match part {
        Some(part) => ready_with_part(&name, &bytes, (&resolved, run), part, command, &mut messages),
        None => ready(&name, &bytes, &resolved, run, command, &mut messages),
    };
    let result = match ready {
        Ok(Ready { parsed, lowered, machine, part }) => {
            let mut nominal = Nominal::new(&parsed.program, &lowered, &machine);
            nominal.part = part.and_then(|run| run.part);
            nominal.screw_pitch = resolved.settings.ball_screw_pitch_mm.unwrap_or_default();
            Ok((nominal, model, resolved))
        }
        Err(text) => {
            messages = text;
            Err(ExitCode::from(1))
        }
    };
    streams::err(messages);
    Ok(result)
}

pub fn run(args: DiagnoseArgs) -> Result<ExitCode, CliError> {
    check_output(args.write_model.as_deref())?;
    check_output(args.plot.as_deref())?;
    if args.plot.is_some() && args.kind == Some(KindArg::Table) {
        return Err(CliError::Usage(format!("--plot: {NO_TABLE_PLOT}")));
    }
    let (nominal, model, resolved) = match prepare(&args.file, &args.read, &args.run, "diagnose", args.start_min, None)?
    {
        Ok(ready) => ready,
        Err(code) => return Ok(code),
    };
    let data_name = display_name(&args.measured);
    let text = read_data_text(&args.measured)?;
    let kind = args.kind.map(KindArg::name);
    let axis = args.axis.map(AxisArg::axis);
    let measured = measured::read_as(&text, kind, axis).map_err(|e| data_invalid(&data_name, &text, e, "diagnose"))?;
    let options = Options { max_iterations: args.max_iterations };
    let diagnosis = diagnose(&nominal, &measured, &model, &options).map_err(|e| match e.line() {
        // A row that does not fit the program: a diagnostic at its line.
        Some(line) => {
            let lines = turnpass::source::LineIndex::new(text.as_bytes());
            let start = if line >= 1 && line <= lines.line_count() { lines.line_start(line - 1) } else { 0 };
            let end = text[start as usize..].find(['\n', '\r']).map_or(text.len(), |n| start as usize + n) as u32;
            let mut error = DataError::new(line, Span::new(start, end), "this point", e.message());
            error.hint = e.hint();
            data_misfit(&data_name, &text, error, "diagnose")
        }
        None => CliError::Data(format!("{data_name}: {e}")),
    })?;
    let out = match args.format {
        Format::Human => turnpass::source::escape_controls(&report::human(&diagnosis)).into_owned(),
        Format::Json => serde_json::to_string_pretty(&report::json(&diagnosis)).unwrap_or_default() + "\n",
    };
    write_output(None, out.as_bytes())?;
    // Every output asked for is made, and checked, before any is written: a run that fails
    // on the second writes neither.
    let model_file = match &args.write_model {
        Some(path) => {
            let original = model_text_for(&resolved, path)?;
            let written = model_text::with_found_effects(&original, &diagnosis, &data_name)
                .map_err(|why| CliError::Usage(format!("{}: not written: {why}", path.display())))?;
            // The written model must load where it is written, tables and found effects alike.
            let (spec, dir) = model_spec(path, &written)?;
            spec.build(|file| read_table(&dir, file)).map_err(|e| model_problems(path, &written, e))?;
            Some((path, written))
        }
        None => None,
    };
    let plot = match &args.plot {
        Some(path) => match turnpass::plot::residuals::residuals_svg(&display_name(&args.file), &diagnosis) {
            Ok(svg) => Some((path, svg)),
            Err(error) => {
                let nothing = if model_file.is_some() { "; nothing is written" } else { "" };
                streams::err_line(format_args!("diagnose: no plot: {error}{nothing}"));
                return Ok(ExitCode::from(1));
            }
        },
        None => None,
    };
    if let Some((path, written)) = model_file {
        write_file(path, written.as_bytes())?;
        let plural = super::common::plural;
        let mut what = vec![format!("{} effect{} added", diagnosis.added.len(), plural(diagnosis.added.len()))];
        if !diagnosis.updated.is_empty() {
            let count = diagnosis.updated.len();
            what.push(format!("{count} stale value{} updated", plural(count)));
        }
        if let Some(table) = diagnosis.unexplained.as_ref().and_then(|u| u.table.as_ref()) {
            what.push(format!("the residual as the {} slide's {} table", table.axis.letter(), table.quantity.column()));
        }
        streams::err_line(format_args!("diagnose: wrote {} ({})", path.display(), what.join(", ")));
    }
    if let Some((path, svg)) = plot {
        write_file(path, svg.as_bytes())?;
        streams::err_line(format_args!("diagnose: wrote {}", path.display()));
    }
    Ok(ExitCode::SUCCESS)
}

/// Why `--plot` draws nothing for an interferometer table.
const NO_TABLE_PLOT: &str =
    "no plot is drawn for an interferometer table (`turnpass model report` gives its figures); leave out --plot";

pub fn run_synth(args: SynthArgs) -> Result<ExitCode, CliError> {
    check_output(args.output.as_deref())?;
    let (nominal, truth, resolved) = match prepare(&args.file, &args.read, &args.run, "synth", None, Some(&args.stock))?
    {
        Ok(ready) => ready,
        Err(code) => return Ok(code),
    };
    // A step finer than the machine can move is refused: its rows would repeat positions,
    // and their number would follow the option.
    let finest = turnpass::semantic::Machine::from_settings(&resolved.settings).finest_increment_mm();
    match args.kind {
        KindArg::Ballbar => {
            let least = finest_step_deg(&nominal, finest).unwrap_or(0.0);
            if args.step_deg < least * (1.0 - 1e-9) {
                // The least step rounded up to two significant digits.
                let digits = (1.0 - least.log10().floor()).max(0.0) as usize;
                let scale = 10f64.powi(digits as i32);
                return Err(CliError::Usage(format!(
                    "--step-deg {} moves the tool less than the least increment ({finest} mm) round the program's \
                     smallest test circle: give --step-deg {:.digits$} or more",
                    args.step_deg,
                    (least * scale).ceil() / scale
                )));
            }
        }
        KindArg::Profile if args.spacing < finest * (1.0 - 1e-9) => {
            return Err(CliError::Usage(format!(
                "--spacing {} mm is finer than the least increment a program can write on this machine ({finest} \
                 mm): give --spacing {finest} or more",
                args.spacing
            )));
        }
        _ => {}
    }
    let defaults = SynthOptions::default();
    let options = SynthOptions {
        noise_mm: args.noise,
        seed: args.seed,
        step_deg: args.step_deg,
        spacing_mm: args.spacing,
        parts: if args.parts.is_empty() { vec![None] } else { args.parts.iter().map(|&t| Some(t)).collect() },
        targets: if args.targets.is_empty() { defaults.targets } else { args.targets.clone() },
        glitches: args.glitches,
        glitch_mm: args.glitch_mm,
    };
    let measured = synth(&nominal, &truth, args.kind.kind(args.axis)?, &options).map_err(|e| match e.hint() {
        Some(hint) => CliError::Usage(format!("{}: {e}\n  = hint: {hint}", display_name(&args.file))),
        None => CliError::Usage(format!("{}: {e}", display_name(&args.file))),
    })?;
    write_output(args.output.as_deref(), to_csv(&measured).as_bytes())?;
    if let Some(path) = &args.output {
        let rows = measured.rows();
        streams::err_line(format_args!("synth: wrote {} ({rows} row{})", path.display(), super::common::plural(rows)));
    }
    Ok(ExitCode::SUCCESS)
}

/// The working model's text for a model written to `output`: the `file` of each axis table
/// rewritten relative to `output`'s folder when that is not the model's own, so the written
/// model reads the same tables wherever it is written.
fn model_text_for(resolved: &Resolved, output: &Path) -> Result<String, CliError> {
    let Some((model_path, text)) = &resolved.model else { return Ok(String::new()) };
    let canonical = |dir: &Path| {
        std::fs::canonicalize(dir).map_err(|source| CliError::Write { path: output.display().to_string(), source })
    };
    let (from, to) = (canonical(folder_of(model_path))?, canonical(folder_of(output))?);
    if from == to {
        return Ok(text.clone());
    }
    with_table_files(text, |file| {
        let file = Path::new(file);
        if file.is_absolute() {
            return None;
        }
        let table = std::fs::canonicalize(from.join(file)).unwrap_or_else(|_| from.join(file));
        relative_path(&to, &table).to_str().map(str::to_string)
    })
    .map_err(|problems| model_problems(model_path, text, ModelError::File(problems)))
}

/// The path of `target` from the folder `from`, both absolute: up to their common folder,
/// then down.
fn relative_path(from: &Path, target: &Path) -> PathBuf {
    let common = from.components().zip(target.components()).take_while(|(a, b)| a == b).count();
    let mut path = PathBuf::new();
    for _ in from.components().skip(common) {
        path.push("..");
    }
    path.extend(target.components().skip(common));
    path
}
