//! `turnpass plot FILE -o OUT.svg`: the program compensated in memory, and its nominal,
//! actual and compensated paths drawn with the error magnified, or with `--polar` the
//! radial deviation of a full-circle (ball-bar) program, or with `--part` the finished part
//! each cuts on the model, probed as `verify` probes it.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use turnpass::compensation::verify::{self, Measure};
use turnpass::diagnostic::{Diagnostic, Severity};
use turnpass::printer;
use turnpass::semantic::nose_radius::ToolTable;

use super::common::{
    CliError, ReadArgs, RunArgs, StockArgs, check_output, display_name, model_source, pipeline_settings, read_program,
    ready_with_part, rendered, svg_path, write_file,
};
use super::compensate::FitArgs;
use super::streams;

#[derive(Args)]
pub struct PlotArgs {
    /// Program file; `-` reads standard input.
    pub file: PathBuf,
    /// The SVG file to write (its name ends in `.svg`).
    #[arg(short, long, value_name = "OUT.svg", value_parser = svg_path)]
    pub output: PathBuf,
    /// Magnify the deviations along the surface normal this many times (a number above 0;
    /// default: the round factor that draws the largest at a thirtieth of the part).
    #[arg(long, value_parser = magnification)]
    pub magnify: Option<f64>,
    /// A ball-bar polar plot: radial deviation against angle, each direction.
    #[arg(long)]
    pub polar: bool,
    /// The finished part instead of the paths: the deviation of the part the program cuts on
    /// the model and of the part its compensation cuts, probed along the nominal surface's
    /// outward normal as `verify` probes them, over the half-section.
    #[arg(long, conflicts_with = "polar")]
    pub part: bool,
    #[command(flatten)]
    pub fit: FitArgs,
    #[command(flatten)]
    pub read: ReadArgs,
    #[command(flatten)]
    pub run: RunArgs,
    /// The bar under the path plot's half-section (else the model file's [stock], else the
    /// smallest bar holding every cut's start, drawn as assumed).
    #[command(flatten)]
    pub stock: StockArgs,
    /// Also say where the machine settings and the model come from.
    #[arg(long, short)]
    pub verbose: bool,
}

pub fn plot(args: PlotArgs) -> Result<ExitCode, CliError> {
    check_output(Some(&args.output))?;
    args.fit.check()?;
    let (bytes, resolved) = read_program(&args.file, &args.read)?;
    args.fit.check_step(&turnpass::semantic::Machine::from_settings(&resolved.settings))?;
    let (model, table) = args.fit.error_model(&resolved, "plot")?;
    if let Some((_, said)) = &table {
        streams::err(said);
    }
    let name = display_name(&args.file);
    let mut messages = Vec::new();
    if args.verbose {
        messages.extend_from_slice(format!("plot: {name}: {}\n", model_source(&args.read, &resolved)).as_bytes());
    }
    let part = args.stock.check(&resolved);
    let program = match ready_with_part(&name, &bytes, (&resolved, &args.run), part, "plot", &mut messages) {
        Ok(program) => program,
        Err(text) => {
            streams::err(text);
            return Ok(ExitCode::from(1));
        }
    };
    let outcome = args.fit.compensate(&program, &model, true, false);
    // A path that needs more samples than a plot holds is kept nowhere: nothing to draw.
    if outcome.refused() && outcome.paths.samples.is_empty() {
        messages.extend(rendered(&name, &bytes, &outcome.diagnostics));
        messages.extend_from_slice(format!("plot: {name}: nothing is drawn\n").as_bytes());
        streams::err(messages);
        return Ok(ExitCode::from(1));
    }
    // The plot shows what compensation would do even where `compensate` would refuse: its
    // refusals are warnings here, for the plot is drawn (an error is printed only by a run that
    // exits 1 and writes nothing).
    let refused = outcome.diagnostics.iter().filter(|d| d.is_error()).count();
    let shown: Vec<Diagnostic> = outcome
        .diagnostics
        .iter()
        .map(|d| Diagnostic { severity: d.severity.min(Severity::Warning), ..d.clone() })
        .collect();
    messages.extend(rendered(&name, &bytes, &shown));
    if refused > 0 {
        messages.extend_from_slice(
            format!(
                "plot: {name}: compensate refuses this program ({refused} warning{} above); the plot shows the \
                 compensation it refuses\n",
                super::common::plural(refused)
            )
            .as_bytes(),
        );
    }
    streams::err(messages);
    let toolpath = program.valid();
    let [before, after] = turnpass::plot::points_of(toolpath, &outcome.paths);
    let svg = if args.polar {
        turnpass::plot::polar_svg(&name, toolpath, &before, &after).map(|svg| (svg, None))
    } else if args.part {
        // The compensation printed and read back, both parts cut and probed: the check
        // `compensate` makes before writing, on the same stock.
        let written = printer::print(&program.parsed.program, &outcome.edits);
        let mut reading = pipeline_settings(&resolved, &args.run, true);
        reading.parse = printer::read_back_options(&program.parsed.program);
        let tools = ToolTable::from_machine(&program.machine);
        let words = verify::Words::of(&program.parsed.program, &program.lowered.expansions);
        let original = verify::Held::from_toolpath(words, toolpath, &tools);
        let checked = verify::check_written(
            || Ok(original),
            &written,
            &reading,
            &tools,
            (&model, Measure::Part, verify::PartFrom { stock: part.stock.as_ref(), finished: None }),
        );
        let measured = match checked.map(|written| written.part) {
            Ok(Some(measured)) => measured,
            Ok(None) => {
                streams::err_line(format_args!("plot: {name}: the part was not measured: nothing is drawn"));
                return Ok(ExitCode::from(1));
            }
            Err(diagnostics) => {
                let mut text = rendered(&name, &bytes, &diagnostics);
                text.extend_from_slice(
                    format!("plot: {name}: the compensation does not read back: nothing is drawn\n").as_bytes(),
                );
                streams::err(text);
                return Ok(ExitCode::from(1));
            }
        };
        if let Some(stopped) = measured.incomplete() {
            streams::err(rendered(&name, &bytes, &[Diagnostic { severity: Severity::Warning, ..stopped }]));
        }
        let section = program.part.as_ref().and_then(|run| run.part.as_ref());
        turnpass::plot::part_svg(&name, toolpath, (&measured.points, measured.spacing_mm), args.magnify, section)
            .map(|drawn| (drawn.svg, Some(drawn.magnify)))
    } else {
        let part = program.part.as_ref().and_then(|run| run.part.as_ref());
        turnpass::plot::path_svg(&name, toolpath, (&before, &after), args.magnify, part)
            .map(|drawn| (drawn.svg, Some(drawn.magnify)))
    };
    match svg {
        Ok((svg, magnify)) => {
            write_file(&args.output, svg.as_bytes())?;
            let magnified = magnify.map_or_else(String::new, |k| format!(" (deviations magnified ×{k})"));
            streams::err_line(format_args!("plot: {name}: wrote {}{magnified}", args.output.display()));
            Ok(ExitCode::SUCCESS)
        }
        Err(error) => {
            streams::err_line(format_args!("plot: {name}: {error}"));
            Ok(ExitCode::from(1))
        }
    }
}

pub(super) fn magnification(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("`{s}` is not a magnification: give a number above 0, such as 10")),
    }
}
