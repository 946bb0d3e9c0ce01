//! `turnpass report ORIGINAL COMPENSATED --model M -o report.html`: `verify`'s checks, its
//! figures and verdict, the plots and the edited blocks on one self-contained HTML page.
//!
//! The page is written whenever both programs run, whatever `verify` finds: a report of a
//! failed check is the one a shop engineer needs to send. Its verdict is on the page and on
//! standard error, and the exit code is 0; `verify` is the gate. A program with errors is
//! exit 1 and writes nothing, as every other command.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use turnpass::compensation::verify::{Measured, Side};
use turnpass::plot::PathPoint;
use turnpass::report::{ModelFile, Page, Plot, ProgramFile};

use super::common::{
    CliError, ReadArgs, RunArgs, check_output, display_name, model_name, model_source, read_program,
    read_program_bytes, ready, ready_with_part, required_error_model, write_file,
};
use super::streams;
use super::verify::{CheckArgs, Checkable, Checked, Watch, checked};

#[derive(Args)]
pub struct ReportArgs {
    /// The program as written for the part.
    pub original: PathBuf,
    /// The compensated program.
    pub compensated: PathBuf,
    /// The HTML file to write (its name ends in `.html` or `.htm`).
    #[arg(short, long, value_name = "OUT.html", value_parser = html_path)]
    pub output: PathBuf,
    /// Magnify the deviations of the path and part plots this many times (default: the round
    /// factor that draws the largest at a thirtieth of the part).
    #[arg(long, value_parser = super::plot::magnification)]
    pub magnify: Option<f64>,
    #[command(flatten)]
    pub checks: CheckArgs,
    #[command(flatten)]
    pub read: ReadArgs,
    #[command(flatten)]
    pub run: RunArgs,
    /// Also say where the machine settings and the model come from.
    #[arg(long, short)]
    pub verbose: bool,
}

/// The most points of each program the plots are drawn from; a longer program's are taken
/// at even intervals of its samples.
const PLOTTED_POINTS: usize = 20_000;

pub fn report(args: ReportArgs) -> Result<ExitCode, CliError> {
    check_output(Some(&args.output))?;
    let (original_bytes, resolved) = read_program(&args.original, &args.read)?;
    let compensated_bytes = read_program_bytes(&args.compensated)?;
    let mut model = required_error_model(&resolved, "report")?;
    let (original_name, compensated_name) = (display_name(&args.original), display_name(&args.compensated));
    let mut messages = Vec::new();
    if args.verbose {
        messages.extend_from_slice(format!("report: {}\n", model_source(&args.read, &resolved)).as_bytes());
    }
    // The bar the part measure cuts from is the one drawn under the path plot.
    let part = args.checks.stock.check(&resolved);
    let original =
        ready_with_part(&original_name, &original_bytes, (&resolved, &args.run), part, "report", &mut messages);
    let compensated = ready(&compensated_name, &compensated_bytes, &resolved, &args.run, "report", &mut messages);
    let (original, compensated) = match (original, compensated) {
        (Ok(o), Ok(c)) => (o, c),
        (o, c) => {
            for text in [o.err(), c.err()].into_iter().flatten() {
                messages.extend(text);
            }
            streams::err(messages);
            return Ok(ExitCode::from(1));
        }
    };
    let toolpath = original.valid();
    let stride = stride_for(&toolpath);
    let toolpaths = [original.valid(), compensated.valid()];
    let mut points = [Collector::new(stride), Collector::new(stride)];
    let checkable = (Checkable::of_kept(&original), Checkable::of_kept(&compensated));
    let checked = checked(
        (&checkable.0, &checkable.1),
        (&original_name, &compensated_name, &original_bytes, &compensated_bytes),
        &resolved,
        &mut model,
        &args.checks,
        Watch::Each(&mut |side, measured| {
            let k = usize::from(side == Side::Compensated);
            points[k].add(&measured, &toolpaths[k]);
        }),
    );
    let checked = match checked {
        Ok(checked) => checked,
        Err(error) => {
            streams::err(messages);
            return Err(error);
        }
    };
    for warning in &checked.warnings {
        messages
            .extend_from_slice(format!("report: warning: {}\n", turnpass::source::escape_controls(warning)).as_bytes());
    }
    let [before, after] = points.map(|c| c.points);
    let title = format!("{original_name} → {compensated_name}");
    let part = original.part.as_ref().and_then(|run| run.part.as_ref());
    let path = turnpass::plot::path_svg(&title, toolpath, (&before, &after), args.magnify, part);
    let mut plots = vec![Plot {
        id: "plot-path",
        caption: match &path {
            Ok(drawn) => format!(
                "The nominal part at true scale; the deviation of the predicted path (pass by pass, every cutting \
                 point) along the surface normal, as programmed and compensated, magnified ×{}; under it the same \
                 in µm along the cut.",
                drawn.magnify
            ),
            Err(_) => "The path plot".to_string(),
        },
        svg: path.map(|drawn| drawn.svg).map_err(|e| e.to_string()),
    }];
    // The finished part, where the part measure ran: the figure of what verify judges.
    if let Some(measured) = &checked.part {
        let figure =
            turnpass::plot::part_svg(&title, toolpath, (&measured.points, measured.spacing_mm), args.magnify, part);
        plots.push(Plot {
            id: "plot-part",
            caption: match &figure {
                Ok(drawn) => format!(
                    "The finished part at true scale, on its stock: the deviation of the part each program cuts on \
                     the model (as programmed and compensated), measured along the nominal surface's outward normal \
                     at {} points, magnified ×{}; under it the same in µm along the surface.",
                    measured.points.len(),
                    drawn.magnify
                ),
                Err(_) => "The part plot".to_string(),
            },
            svg: figure.map(|drawn| drawn.svg).map_err(|e| e.to_string()),
        });
    }
    match turnpass::plot::polar_svg(&title, toolpath, &before, &after) {
        Ok(svg) => plots.push(Plot {
            id: "plot-polar",
            caption: "The full circle as a ball bar would trace it: radial deviation of the predicted path (pass by \
                      pass) against the angle, each direction, as programmed and compensated, with the ISO 230-4 \
                      figures."
                .to_string(),
            svg: Ok(svg),
        }),
        Err(turnpass::plot::PlotError::NoFullCircle) => {}
        Err(e) => plots.push(Plot { id: "plot-polar", caption: "The polar plot".to_string(), svg: Err(e.to_string()) }),
    }
    let Checked {
        provenance, start, model_sha256, figures, measure, words, limit, violations, warnings, table, ..
    } = checked;
    if let Some((_, summary)) = &table {
        streams::err_line(format_args!("report: {summary}"));
    }
    let compensated_with = match &provenance {
        Some(Ok(made)) => format!(
            "turnpass {} for the model `{}` (sha256 {}…), tolerance {} mm, strategy {}",
            made.version,
            made.model,
            made.model_sha256.to_ascii_lowercase(),
            made.tolerance_mm,
            made.strategy.name()
        ),
        Some(Err(why)) => format!("a provenance comment that does not read ({why})"),
        None => format!("{compensated_name} carries no provenance comment"),
    };
    // Checked on the machine with a control table loaded: the page says so where it says
    // what the program was compensated for.
    let compensated_with = match &table {
        Some((_, summary)) => format!("{compensated_with}; checked as {summary}"),
        None => compensated_with,
    };
    let model_file = resolved.model.as_ref().map_or_else(String::new, |(path, _)| path.display().to_string());
    let page = turnpass::report::html(&Page {
        version: env!("CARGO_PKG_VERSION"),
        original: ProgramFile { name: &original_name, bytes: &original_bytes },
        compensated: ProgramFile { name: &compensated_name, bytes: &compensated_bytes },
        model: ModelFile { file: &model_file, name: &model_name(&resolved), sha256: &model_sha256 },
        compensated_with,
        start: format!("{} min ({})", start.minutes, start.from),
        deviation: &figures,
        measure,
        limit_mm: limit,
        words_checked: words.checked,
        violations: &violations,
        warnings: &warnings,
        plots,
    });
    streams::err(messages);
    write_file(&args.output, page.as_bytes())?;
    let verdict = if violations.is_empty() {
        "verify: ok".to_string()
    } else {
        let plural = if violations.len() == 1 { "" } else { "s" };
        let mut text = format!("verify: {} violation{plural} (on the page)", violations.len());
        for violation in &violations {
            text.push_str(&format!("\nreport: violation: {violation}"));
        }
        text
    };
    streams::err_line(format_args!("report: wrote {}; {verdict}", args.output.display()));
    Ok(ExitCode::SUCCESS)
}

/// Every how many samples a point is kept for the plots.
fn stride_for(toolpath: &turnpass::toolpath::Toolpath) -> usize {
    let cut: f64 = (0..toolpath.moves.len())
        .filter(|&k| toolpath.moves[k].cutting)
        .map(|k| {
            let (start, m) = (toolpath.start_of(k), &toolpath.moves[k]);
            if m.is_arc() { std::f64::consts::TAU * start.distance(m.centre) } else { start.distance(m.end) }
        })
        .sum();
    let samples = cut / turnpass::compensation::program::SAMPLE_STEP_MM;
    ((samples / PLOTTED_POINTS as f64).ceil() as usize).max(1)
}

/// The points of one program kept for the plots.
struct Collector {
    stride: usize,
    seen: usize,
    /// The cutting length of the program up to the last point seen, mm.
    along_mm: f64,
    /// The sample index of the last point seen, and whether the cut broke since the last kept.
    last: Option<usize>,
    broken: bool,
    points: Vec<PathPoint>,
}

impl Collector {
    fn new(stride: usize) -> Collector {
        Collector { stride, seen: 0, along_mm: 0.0, last: None, broken: true, points: Vec::new() }
    }

    fn add(&mut self, m: &Measured, own: &turnpass::toolpath::Toolpath) {
        if self.last.is_none_or(|last| last + 1 != m.sample_index) {
            self.broken = true;
        }
        self.last = Some(m.sample_index);
        self.seen += 1;
        self.along_mm += m.sample.covers_mm;
        if !(self.seen - 1).is_multiple_of(self.stride) {
            return;
        }
        self.points.push(PathPoint {
            nominal: m.closest,
            move_index: m.original_move,
            motion: own.moves.get(m.sample.move_index).map_or(turnpass::toolpath::Motion::Feed, |own| own.motion),
            normal: m.sample.normal,
            travel: m.sample.velocity,
            predicted: m.predicted,
            along_mm: self.along_mm,
            joined: !self.broken,
        });
        self.broken = false;
    }
}

/// An HTML file to write: a name whose extension says another format is refused.
fn html_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    match path.extension() {
        Some(e) if !(e.eq_ignore_ascii_case("html") || e.eq_ignore_ascii_case("htm")) => Err(format!(
            "`{s}` names a .{} file, and the report is an HTML page: give a name ending in .html",
            e.to_string_lossy()
        )),
        _ => Ok(path),
    }
}
