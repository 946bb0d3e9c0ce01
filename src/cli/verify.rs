//! `turnpass verify ORIGINAL COMPENSATED`: the compensated program predicted on the model
//! against the original's nominal part, and its non-motion words against the original's.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use std::sync::atomic::{AtomicUsize, Ordering};
use turnpass::compensation::provenance::{Provenance, marks};

use turnpass::compensation::verify::{
    self, CutWords, Deviation, Held, Measure, Measured, PartDeviation, PartFrom, Side, WordCheck, check_feeds,
    check_words, deviation_each, deviation_of, part_deviation_watched,
};
use turnpass::error_model::ErrorModel;
use turnpass::pipeline::Ready;
use turnpass::semantic::Machine;
use turnpass::semantic::nose_radius::ToolTable;
use turnpass::source::{LineIndex, escape_controls};
use turnpass::toolpath::Xz;

use super::common::{
    CliError, Format, ReadArgs, Resolved, RunArgs, StockArgs, display_name, model_sha256, model_source, read_program,
    read_program_bytes, ready, rendered, required_error_model, write_output,
};
use super::numbers::{self, within};
use super::streams;
use super::table::{WithTable, split_summary, with_table};

#[derive(Args)]
pub struct VerifyArgs {
    /// The program as written for the part.
    pub original: PathBuf,
    /// The compensated program.
    pub compensated: PathBuf,
    #[command(flatten)]
    pub checks: CheckArgs,
    #[arg(long, value_enum, default_value = "human")]
    pub format: Format,
    #[command(flatten)]
    pub read: ReadArgs,
    #[command(flatten)]
    pub run: RunArgs,
    /// Also say where the machine settings and the model come from.
    #[arg(long, short)]
    pub verbose: bool,
}

/// What `verify` checks against, shared with `report`.
#[derive(Args)]
pub struct CheckArgs {
    /// Fail when the predicted deviation from the nominal part exceeds MM (default: twice
    /// the least increment).
    #[arg(long, allow_negative_numbers = true, value_name = "MM", value_parser = within(numbers::MAX_DEVIATION_MM))]
    pub max_deviation: Option<f64>,
    /// Minutes since the machine started when the program starts (thermal effects; default:
    /// the compensated program's provenance comment, else the model's `start_min`).
    #[arg(long, value_name = "MIN")]
    pub start_min: Option<f64>,
    /// Verify on the model given even when it is not the one the compensated program's
    /// provenance comment names (its SHA-256 differs, or its control table); without this
    /// that is a violation.
    #[arg(long)]
    pub allow_other_model: bool,
    /// The machine runs with this control table loaded (as `turnpass table` writes it): check
    /// the program on the machine with the table.
    #[arg(long, value_name = "FILE")]
    pub with_table: Option<PathBuf>,
    /// Measure every pass against the original's nominal path, pass by pass, instead of the
    /// finished part (a roughing pass then counts as much as the finishing one).
    #[arg(long)]
    pub passes: bool,
    /// The bar the parts are cut from (the finished-part measure; `report` draws it under
    /// the path plot: else the model file's [stock], else the smallest bar holding every
    /// cut's start, drawn as assumed).
    #[command(flatten)]
    pub stock: StockArgs,
}

pub fn verify(args: VerifyArgs) -> Result<ExitCode, CliError> {
    // Both programs run on the machine the original's settings name.
    let (original_bytes, resolved) = read_program(&args.original, &args.read)?;
    let compensated_bytes = read_program_bytes(&args.compensated)?;
    let mut model = required_error_model(&resolved, "verify")?;
    let (original_name, compensated_name) = (display_name(&args.original), display_name(&args.compensated));
    let mut messages = Vec::new();
    if args.verbose {
        messages.extend_from_slice(format!("verify: {}\n", model_source(&args.read, &resolved)).as_bytes());
    }
    // Each program is held for the checks as soon as it is ready, its AST and full moves let
    // go; the longer text first, so that the peak is the longer program analysed, not both.
    let hold = |name: &str, bytes: &[u8], said: &mut Vec<u8>| {
        ready(name, bytes, &resolved, &args.run, "verify", said).map(Checkable::of)
    };
    let (mut original_said, mut compensated_said) = (Vec::new(), Vec::new());
    let (original, compensated) = if compensated_bytes.len() > original_bytes.len() {
        let compensated = hold(&compensated_name, &compensated_bytes, &mut compensated_said);
        (hold(&original_name, &original_bytes, &mut original_said), compensated)
    } else {
        let original = hold(&original_name, &original_bytes, &mut original_said);
        (original, hold(&compensated_name, &compensated_bytes, &mut compensated_said))
    };
    messages.append(&mut original_said);
    messages.append(&mut compensated_said);
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
    let progress = Progress::new(streams::stderr_is_terminal(), [&original, &compensated]);
    let checked = checked(
        (&original, &compensated),
        (&original_name, &compensated_name, &original_bytes, &compensated_bytes),
        &resolved,
        &mut model,
        &args.checks,
        Watch::Progress(&|side, measured| progress.measured(side, measured)),
    );
    let checked = match checked {
        Ok(checked) => checked,
        Err(error) => {
            streams::err(messages);
            return Err(error);
        }
    };
    progress.finish();
    if let Some((_, summary)) = &checked.table {
        messages.extend_from_slice(format!("verify: {summary}\n").as_bytes());
    }
    for warning in &checked.warnings {
        messages.extend_from_slice(format!("verify: warning: {}\n", escape_controls(warning)).as_bytes());
    }
    streams::err(messages);
    let Checked { provenance, start, model_sha256, figures, measure, part, words, limit, violations, table, .. } =
        checked;
    let machine = &original.machine;
    // Each text's lines are indexed once, when a line is first asked for: a report names a
    // line for every feature, and a long program's index takes a pass over its text.
    let (original_lines, compensated_lines) = (std::cell::OnceCell::new(), std::cell::OnceCell::new());
    let original_line = |span: turnpass::source::Span| {
        original_lines.get_or_init(|| LineIndex::new(&original_bytes)).position(span.start).0
    };
    let compensated_line = |by: Option<usize>| {
        by.filter(|&k| k < compensated.held.path.len()).map(|k| {
            let lines = compensated_lines.get_or_init(|| LineIndex::new(&compensated_bytes));
            lines.position(compensated.held.path.source(k).start).0
        })
    };
    let feature_line =
        |block: turnpass::source::Span| (block != turnpass::source::Span::SYNTHETIC).then(|| original_line(block));
    let text = match args.format {
        Format::Json => {
            let value = serde_json::json!({
                "original": original_name,
                "compensated": compensated_name,
                "measure": measure,
                "deviation": figures,
                "start_min": start.minutes,
                "start_min_from": start.from,
                "provenance": provenance.as_ref().and_then(|p| p.as_ref().ok()),
                "model_sha256": model_sha256,
                "max_deviation_mm": limit,
                "words_checked": words.checked,
                "violations": violations,
            });
            let mut value = value;
            if let (Some(part), Some(object)) = (&part, value.as_object_mut()) {
                let probe = |p: &turnpass::compensation::verify::Probe| {
                    let x = if machine.diameter_programming { 2.0 * p.at.x } else { p.at.x } / machine.scale();
                    serde_json::json!({
                        "x": x,
                        "z": p.at.z / machine.scale(),
                        "deviation_mm": p.signed_mm,
                        "cut_by_line": compensated_line(p.cut_by),
                    })
                };
                let features: Vec<serde_json::Value> = part
                    .features
                    .iter()
                    .map(|f| {
                        serde_json::json!({
                            "line": feature_line(f.block),
                            "figures": f.figures,
                            "worst": probe(&f.worst),
                        })
                    })
                    .collect();
                let threads: Vec<serde_json::Value> = part
                    .threads
                    .iter()
                    .map(|t| {
                        let mut value = serde_json::json!(t);
                        if let Some(object) = value.as_object_mut() {
                            object.insert("line".into(), serde_json::json!(original_line(t.block)));
                            object.insert("last_line".into(), serde_json::json!(original_line(t.last_block)));
                        }
                        value
                    })
                    .collect();
                object.insert(
                    "part".to_string(),
                    serde_json::json!({
                        "stock": {
                            "diameter_mm": 2.0 * part.stock.outer,
                            "bore_mm": 2.0 * part.stock.bore,
                            "front_mm": part.stock.front,
                            "back_mm": part.stock.back,
                            "assumed": part.stock.assumed,
                        },
                        "ray_spacing_mm": part.spacing_mm,
                        "unprobed_mm": part.unprobed_mm,
                        "features": features,
                        "deepest_gouge": part.gouge.as_ref().map(probe),
                        "threads": threads,
                    }),
                );
            }
            if let (Some((table, _)), Some(object)) = (&table, value.as_object_mut()) {
                object.insert(
                    "control_table".to_string(),
                    serde_json::json!({
                        "file": table.path.display().to_string(),
                        "control": table.loaded.control.name(),
                        "sha256": table.sha256,
                        "unverified": table.loaded.unverified,
                    }),
                );
            }
            serde_json::to_string_pretty(&value).unwrap_or_default() + "\n"
        }
        Format::Human => {
            let row = |label: &str, f: &turnpass::compensation::deviation::Figures| {
                format!("  {label:<16} {:>10.5} {:>10.5} {:>10.5} {:>8}\n", f.max_mm, f.rms_mm, f.ssq_mm, f.points)
            };
            let mut text = match &provenance {
                Some(Ok(made)) => format!(
                    "compensated by turnpass {} for the model `{}` (sha256 {}), tolerance {} mm, strategy {}\n",
                    made.version,
                    made.model,
                    made.model_sha256.to_ascii_lowercase(),
                    made.tolerance_mm,
                    made.strategy.name()
                ),
                Some(Err(_)) => "compensated by turnpass (its provenance comment does not read)\n".to_string(),
                None => format!("{compensated_name} carries no provenance comment\n"),
            };
            text.push_str(&format!("start time: {} min ({})\n", start.minutes, start.from));
            text.push_str(&format!(
                "measure: {}{}\n",
                measure.describe(),
                match measure {
                    Measure::Part => " (--passes: pass by pass)",
                    Measure::Passes => " (--passes)",
                }
            ));
            if let Some(part) = &part {
                let stock = &part.stock;
                text.push_str(&format!(
                    "stock: bar Ø{:.3} mm{}, Z{:.3} to Z{:.3}{}; rays {:.4} mm apart\n",
                    2.0 * stock.outer,
                    if stock.bore > 0.0 { format!(" bored Ø{:.3} mm", 2.0 * stock.bore) } else { String::new() },
                    stock.front,
                    stock.back,
                    if stock.assumed { " (assumed: the smallest bar holding every cut's start)" } else { "" },
                    part.spacing_mm,
                ));
            }
            text.push_str(&format!("predicted deviation from the nominal part of {original_name}, mm:\n"));
            text.push_str(&format!("  {:<16} {:>10} {:>10} {:>10} {:>8}\n", "", "max", "RMS", "SSQ", "points"));
            text.push_str(&row("as programmed", &figures.before));
            text.push_str(&row("compensated", &figures.after));
            let improvement = turnpass::compensation::deviation::improvement_text(figures.improvement_percent);
            text.push_str(&format!("  RMS improvement: {improvement}\n"));
            if let Some(lead) = &figures.lead {
                text.push_str(&format!(
                    "thread lead over each pass's length (the tool after each whole spindle turn along the axis \
                     from the helix of the programmed lead, placed to fit best), largest error, mm: as programmed {:.5}, compensated {:.5} ({} pass{})\n",
                    lead.before_mm,
                    lead.after_mm,
                    lead.passes,
                    if lead.passes == 1 { "" } else { "es" },
                ));
            }
            if let Some(part) = &part {
                text.push_str(&format!(
                    "the compensated part by surface feature (the line of {original_name} that cuts it), mm \
                     (+ material left, - removed inside the nominal part):\n"
                ));
                text.push_str(&format!(
                    "  {:<8} {:>10} {:>10}  {:<36} {}\n",
                    "line", "max", "RMS", "worst at", "cut by line"
                ));
                for f in &part.features {
                    let line = feature_line(f.block).map_or_else(|| "stock".to_string(), |l| l.to_string());
                    let by = compensated_line(f.worst.cut_by).map_or_else(|| "-".to_string(), |l| l.to_string());
                    let at = format!("{} ({:+.5})", place(machine, f.worst.at), f.worst.signed_mm);
                    text.push_str(&format!(
                        "  {line:<8} {:>10.5} {:>10.5}  {at:<36} {by}\n",
                        f.figures.max_mm, f.figures.rms_mm
                    ));
                }
                if part.unprobed_mm > 0.0 {
                    text.push_str(&format!(
                        "not probed: {:.3} mm of the nominal surface, at an edge of the actual part that the probe \
                         along the normal passes\n",
                        part.unprobed_mm
                    ));
                }
                match &part.gouge {
                    Some(g) => text.push_str(&format!(
                        "deepest gouge: {:.5} mm inside the nominal part at {}{}\n",
                        -g.signed_mm,
                        place(machine, g.at),
                        compensated_line(g.cut_by)
                            .map_or_else(String::new, |l| format!(", cut by {compensated_name} line {l}"))
                    )),
                    None => text.push_str("deepest gouge: none (no material removed inside the nominal part)\n"),
                }
                for t in &part.threads {
                    let form = |f: &Option<turnpass::compensation::verify::ThreadForm>| match f {
                        Some(f) => format!(
                            "pitch diameter {:.5} ({:+.5}), lead {}",
                            f.pitch_diameter_mm,
                            f.pitch_diameter_mm - t.nominal.pitch_diameter_mm,
                            match (f.lead_mm, t.nominal.lead_mm) {
                                (Some(l), Some(n)) => format!("{l:.6} ({:+.6})", l - n),
                                (Some(l), None) => format!("{l:.6}"),
                                _ => "not measured".to_string(),
                            }
                        ),
                        None => "not measured".to_string(),
                    };
                    text.push_str(&format!(
                        "thread of lines {}-{} (lead {:.6} mm, measured over {} leads), mm: nominal pitch diameter {:.5}, lead {}\n  as programmed: {}\n  compensated:   {}\n",
                        original_line(t.block),
                        original_line(t.last_block),
                        t.programmed_lead_mm,
                        t.leads,
                        t.nominal.pitch_diameter_mm,
                        t.nominal.lead_mm.map_or_else(|| "not measured".to_string(), |l| format!("{l:.6}")),
                        form(&t.before),
                        form(&t.after),
                    ));
                }
            }
            text.push_str(&format!(
                "words: {} M, T, S, comment and block-delete words kept in order; feed and spindle words of every \
                 cut checked\n",
                words.checked
            ));
            for violation in &violations {
                text.push_str(&format!("violation: {violation}\n"));
            }
            if violations.is_empty() {
                text.push_str("ok\n");
            }
            // It quotes the programs' words and names: shown escaped.
            turnpass::source::escape_controls(&text).into_owned()
        }
    };
    write_output(None, text.as_bytes())?;
    Ok(if violations.is_empty() { ExitCode::SUCCESS } else { ExitCode::from(1) })
}

/// What `verify` found: the figures, the words, the provenance and the violations.
pub struct Checked {
    pub provenance: Option<Result<Provenance, String>>,
    pub start: Start,
    /// The SHA-256 of the model given, in full.
    pub model_sha256: String,
    pub figures: Deviation,
    /// Which measure the figures are.
    pub measure: Measure,
    /// The finished-part measure's findings (none with `--passes`).
    pub part: Option<PartDeviation>,
    pub words: WordCheck,
    /// The largest deviation allowed, mm.
    pub limit: f64,
    pub violations: Vec<String>,
    pub warnings: Vec<String>,
    /// The control table the machine runs with (`--with-table`), and what goes where with it.
    pub table: Option<(WithTable, String)>,
}

/// How `checked` hands out the points it measures.
pub enum Watch<'a> {
    /// Every point, each program in path order (the report's plots): one thread.
    Each(&'a mut dyn FnMut(Side, Measured)),
    /// How far the measure has come: both programs at once, on two threads.
    Progress(&'a (dyn Fn(Side, &Measured) + Sync)),
}

/// A progress bar of the measure on standard error while it is a terminal: the share of each
/// program's moves measured, redrawn when the whole percentage changes.
struct Progress {
    shown: bool,
    moves: [usize; 2],
    reached: [AtomicUsize; 2],
    percent: AtomicUsize,
}

impl Progress {
    fn new(shown: bool, programs: [&Checkable; 2]) -> Progress {
        Progress {
            shown,
            moves: programs.map(|p| p.held.path.len().max(1)),
            reached: [AtomicUsize::new(0), AtomicUsize::new(0)],
            percent: AtomicUsize::new(0),
        }
    }

    fn measured(&self, side: Side, measured: &Measured) {
        if !self.shown {
            return;
        }
        let k = usize::from(side == Side::Compensated);
        self.reached[k].fetch_max(measured.sample.move_index + 1, Ordering::Relaxed);
        let share = |k: usize| self.reached[k].load(Ordering::Relaxed) as f64 / self.moves[k] as f64;
        let percent = ((share(0) + share(1)) * 50.0).floor() as usize;
        if self.percent.fetch_max(percent, Ordering::Relaxed) < percent {
            streams::progress(percent as f64 / 100.0, &format!("{percent} % of the paths measured"));
        }
    }

    fn finish(&self) {
        if self.shown {
            streams::progress_clear();
        }
    }
}

/// `verify`'s checks of `compensated` against `original` on `model` (its start minute set
/// as they decide), every measured point also handed out as `watch` says. A move that needs
/// more samples than a measure holds (`verify::oversampled`, the bound `compensate` and
/// `plot` refuse by) is refused before any is measured: exit 1, its diagnostics rendered.
pub fn checked(
    (original, compensated): (&Checkable, &Checkable),
    (original_name, compensated_name, original_bytes, compensated_bytes): (&str, &str, &[u8], &[u8]),
    resolved: &Resolved,
    model: &mut ErrorModel,
    checks: &CheckArgs,
    watch: Watch<'_>,
) -> Result<Checked, CliError> {
    let model_sha256 = model_sha256(resolved)?;
    let provenance = compensated_with(&original.marks, &compensated.marks);
    let mut warnings = Vec::new();
    let table = match &checks.with_table {
        Some(path) => {
            let (combined, with) = with_table(path, &resolved.settings, model, "verify")?;
            warnings.extend(with.loaded.unverified.map(|why| format!("unverified: {why}")));
            let summary = split_summary(model, &with);
            *model = combined;
            Some((with, summary))
        }
        None => None,
    };
    let start = match (checks.start_min, &provenance) {
        (Some(minutes), _) => Start { minutes, from: "--start-min" },
        (None, Some(Ok(made))) => Start { minutes: made.start_min, from: "the provenance comment" },
        (None, _) => Start { minutes: model.start_min, from: "the model's start_min" },
    };
    model.start_min = start.minutes;
    let mut violations = Vec::new();
    let mut warn = |text: String| warnings.push(text);
    if !original.marks.is_empty() && provenance.is_none() {
        warn(format!(
            "{original_name} carries a provenance comment: it is a compensated program, not the nominal one \
             (give the nominal program first, the compensated one second)"
        ));
    }
    match &provenance {
        Some(Ok(made)) => {
            if let Some(minutes) = checks.start_min.filter(|&m| m != made.start_min) {
                warn(format!(
                    "{compensated_name} was compensated for a start at {} min; verifying at {minutes} min (--start-min)",
                    made.start_min
                ));
            }
            if !made.same_model(&model_sha256) {
                let model_file =
                    resolved.model.as_ref().map_or_else(String::new, |(path, _)| path.display().to_string());
                let text = format!(
                    "{compensated_name} was compensated for the model `{}` (sha256 {}), but the model given, \
                     {model_file}, is another (sha256 {model_sha256})",
                    made.model,
                    made.model_sha256.to_ascii_lowercase(),
                );
                if checks.allow_other_model {
                    warn(format!("{text}; verifying on the model given (--allow-other-model)"));
                } else {
                    violations.push(format!("{text}: give the model it was compensated for, or --allow-other-model"));
                }
            }
            let given = table.as_ref().map(|(t, _)| t.sha256.as_str());
            if let Some(text) = other_table(compensated_name, made.table_sha256.as_deref(), given) {
                if checks.allow_other_model {
                    warn(format!("{text}; verifying as given (--allow-other-model)"));
                } else {
                    violations.push(format!("{text}, or --allow-other-model"));
                }
            }
        }
        Some(Err(why)) => warn(format!(
            "the provenance comment of {compensated_name} does not read ({why}): its start time and model are not \
             checked"
        )),
        None => {}
    }
    let machine = &original.machine;
    let (original_path, compensated_path) = (&original.held.path, &compensated.held.path);
    let sampling = verify::sampling(model, machine.increment * machine.scale(), &[original_path, compensated_path]);
    let mut refusal = Vec::new();
    for (name, bytes, path) in
        [(original_name, original_bytes, original_path), (compensated_name, compensated_bytes, compensated_path)]
    {
        refusal.extend(rendered(name, bytes, &verify::oversampled(path, &sampling)));
    }
    if !refusal.is_empty() {
        refusal.extend_from_slice(b"a move needs more samples than a measure holds: nothing is measured or written\n");
        return Err(CliError::Rejected(refusal));
    }
    let mut measure = if checks.passes { Measure::Passes } else { Measure::Part };
    let (figures, part) = match (measure, watch) {
        (Measure::Passes, Watch::Each(each)) => {
            (deviation_each(original_path, compensated_path, model, &sampling, each), None)
        }
        (Measure::Passes, Watch::Progress(watch)) => {
            (deviation_of(original_path, compensated_path, model, &sampling, watch), None)
        }
        (Measure::Part, watch) => {
            // The plots draw the predicted path: its points are measured pass by pass.
            let mut passes = None;
            let progress: &(dyn Fn(Side, &Measured) + Sync) = match watch {
                Watch::Progress(watch) => watch,
                Watch::Each(each) => {
                    passes = Some(deviation_each(original_path, compensated_path, model, &sampling, each));
                    &|_, _| {}
                }
            };
            let stock = checks.stock.check(resolved).stock;
            let part = part_deviation_watched(
                (original_path, compensated_path),
                model,
                &sampling,
                (machine, PartFrom { stock: stock.as_ref(), finished: None }),
                progress,
            );
            if part.probed_nothing() {
                // As `compensate`'s check does (`verify::check_written`).
                warnings.push(
                    "the finished part has no surface point to probe (no move cuts the bar, or none leaves a \
                     surface the probe reaches): the passes are measured instead, as --passes measures them; give \
                     the bar with --stock if it is another"
                        .to_string(),
                );
                measure = Measure::Passes;
                // The plots' points are the pass measure already: its figures are not measured again.
                let figures = passes
                    .unwrap_or_else(|| deviation_of(original_path, compensated_path, model, &sampling, &|_, _| {}));
                (figures, None)
            } else {
                (part.deviation, Some(part))
            }
        }
    };
    let words = check_words(&original.held.words, &compensated.held.words);
    if let Some(change) = check_feeds(&original.held.feeds, &compensated.held.feeds) {
        let line = LineIndex::new(original_bytes).position(change.source.start).0;
        violations.push(format!(
            "{compensated_name} cuts with {} where {original_name} cuts with {} (its line {line} on)",
            cut_words(change.compensated),
            cut_words(change.original)
        ));
    }
    let limit = checks.max_deviation.unwrap_or_else(|| verify::default_bound_mm(machine));
    if let Some(missing) = &words.missing {
        let line = LineIndex::new(original_bytes).position(missing.span.start).0;
        violations.push(format!(
            "{compensated_name} lost `{}` ({original_name} line {line}), or has it out of order",
            missing.text
        ));
    }
    if let Some(lead) = &figures.lead {
        if lead.passes_differ {
            violations.push(format!("{compensated_name} cuts another number of thread passes than {original_name}"));
        }
        // On the part, a lead error is the flanks' deviation, which the part's figures judge
        // (an axial shift moves a 60° flank by cos 30° of it); pass by pass the points slide
        // along the thread and only the lead measure sees it.
        if lead.after_mm > limit && part.is_none() {
            let line = lead
                .worst_move
                .filter(|&m| m < original_path.len())
                .map_or(0, |m| LineIndex::new(original_bytes).position(original_path.source(m).start).0);
            violations.push(format!(
                "the predicted lead of the thread {compensated_name} cuts for line {line} of {original_name} errs by \
                 {:.5} mm over the thread's length, more than {limit:.5} mm",
                lead.after_mm
            ));
        }
    }
    match &part {
        Some(part) => violations.extend(part_violations(part, (original, compensated), (original_bytes, compensated_bytes), (original_name, compensated_name), limit)),
        None if figures.after.max_mm > limit => violations.push(format!(
            "the predicted deviation of {compensated_name} from the nominal part reaches {:.5} mm, more than {limit:.5} mm",
            figures.after.max_mm
        )),
        None => {}
    }
    Ok(Checked { provenance, start, model_sha256, figures, measure, part, words, limit, violations, warnings, table })
}

/// The finished-part measure's violations: a deviation past `limit` (where, on which
/// feature, cut by which block, a gouge named so), and a measure that stopped short.
fn part_violations(
    part: &PartDeviation,
    (original, compensated): (&Checkable, &Checkable),
    (original_bytes, compensated_bytes): (&[u8], &[u8]),
    (original_name, compensated_name): (&str, &str),
    limit: f64,
) -> Vec<String> {
    let mut out = Vec::new();
    let machine = &original.machine;
    if let Some((side, block)) = part.stopped {
        let (name, bytes) = if side == Side::Original {
            (original_name, original_bytes)
        } else {
            (compensated_name, compensated_bytes)
        };
        let line = LineIndex::new(bytes).position(block.start).0;
        out.push(format!(
            "the part model stopped at its bound on work at {name} line {line}: the finished part is measured only \
             up to there (--passes measures pass by pass)"
        ));
    }
    // Past the limit by the figure printed, the one compensate's check before writing takes.
    let worst = part.features.iter().max_by(|a, b| a.worst.signed_mm.abs().total_cmp(&b.worst.signed_mm.abs()));
    if let Some(feature) = worst.filter(|_| part.deviation.after.max_mm > limit) {
        let probe = feature.worst;
        let what = if probe.signed_mm < 0.0 {
            "removes material inside the nominal part (a gouge)"
        } else {
            "leaves material outside the nominal part"
        };
        out.push(format!(
            "the finished part of {compensated_name} {what} by {:.5} mm, more than {limit:.5} mm, at {} on the \
             surface {}{}",
            probe.signed_mm.abs(),
            place(machine, probe.at),
            surface_of(feature.block, original_bytes, original_name),
            cut_by(probe.cut_by, compensated, compensated_bytes, compensated_name),
        ));
    }
    out
}

/// Where a point is, as the program writes it (X a diameter where the machine is programmed
/// in diameters), in program units.
fn place(machine: &Machine, at: Xz) -> String {
    let x = if machine.diameter_programming { 2.0 * at.x } else { at.x };
    format!("X{:.4} Z{:.4}", x / machine.scale(), at.z / machine.scale())
}

/// The surface a block of the original cuts, in words.
fn surface_of(block: turnpass::source::Span, bytes: &[u8], name: &str) -> String {
    if block == turnpass::source::Span::SYNTHETIC {
        "of the stock".to_string()
    } else {
        format!("{name} line {} cuts", LineIndex::new(bytes).position(block.start).0)
    }
}

/// Which block of the compensated program cut a point, in words.
fn cut_by(by: Option<usize>, compensated: &Checkable, bytes: &[u8], name: &str) -> String {
    let path = &compensated.held.path;
    match by.filter(|&k| k < path.len()) {
        Some(k) => format!(", cut there by {name} line {}", LineIndex::new(bytes).position(path.source(k).start).0),
        None => String::new(),
    }
}

/// Why the control table a program was compensated for (`made`, the first digits of its
/// SHA-256) is not the one `verify` is given (`given`), in words; none when they agree.
fn other_table(compensated_name: &str, made: Option<&str>, given: Option<&str>) -> Option<String> {
    match (made, given) {
        (None, None) => None,
        (Some(made), Some(given)) if given.len() >= made.len() && given[..made.len()].eq_ignore_ascii_case(made) => {
            None
        }
        (Some(made), None) => Some(format!(
            "{compensated_name} was compensated for a machine with the control table {made} loaded, and no table is \
             given: give it with --with-table"
        )),
        (None, Some(given)) => Some(format!(
            "{compensated_name} was compensated for a machine without a control table, and the table {given} is \
             given: leave out --with-table"
        )),
        (Some(made), Some(given)) => Some(format!(
            "{compensated_name} was compensated for the control table {made}, and the one given is another \
             ({given}): give the table it was compensated for"
        )),
    }
}

/// A cut's feed and spindle words as a user reads them.
fn cut_words(words: Option<CutWords>) -> String {
    match words {
        None => "no cut".into(),
        Some(CutWords { feed, per_revolution, speed, threading }) => {
            let per = if threading {
                "lead"
            } else if per_revolution {
                "per revolution"
            } else {
                "per minute"
            };
            format!("F{feed} ({per}), S{speed}")
        }
    }
}

/// The minute the run starts at, and what said so.
pub struct Start {
    pub minutes: f64,
    pub from: &'static str,
}

/// What `compensated` says it was compensated with: its first provenance comment that is
/// not one of `original`'s (an original compensated with `--force` keeps its own, and the
/// new one may read the same, so they are matched one for one).
fn compensated_with(original: &Marks, compensated: &Marks) -> Option<Result<Provenance, String>> {
    let mut theirs: Vec<&[u8]> = original.iter().map(|(text, _)| text.as_slice()).collect();
    let new = compensated.iter().find(|(text, _)| match theirs.iter().position(|t| *t == text.as_slice()) {
        Some(at) => {
            theirs.swap_remove(at);
            false
        }
        None => true,
    });
    new.map(|(_, provenance)| provenance.clone())
}

/// A program's provenance comments: each one's text and what it says.
type Marks = Vec<(Vec<u8>, Result<Provenance, String>)>;

/// A program as `checked` reads it: held (`verify::Held`: compact, its words and feeds
/// taken), with its provenance comments and the machine it runs on.
pub struct Checkable {
    pub held: Held,
    marks: Marks,
    pub machine: Machine,
}

impl Checkable {
    /// `program` held, its AST and full moves let go.
    pub fn of(program: Ready<'_>) -> Checkable {
        let marks = marks_of(&program.parsed.program);
        let machine = program.machine.clone();
        let tools = ToolTable::from_machine(&machine);
        Checkable { held: Held::of(program, &tools), marks, machine }
    }

    /// `program` held as `of` holds it, keeping `program` (for a command that draws it).
    pub fn of_kept(program: &Ready<'_>) -> Checkable {
        let tools = ToolTable::from_machine(&program.machine);
        let words = verify::Words::of(&program.parsed.program, &program.lowered.expansions);
        Checkable {
            held: Held::from_toolpath(words, program.valid(), &tools),
            marks: marks_of(&program.parsed.program),
            machine: program.machine.clone(),
        }
    }
}

/// The provenance comments of `program`.
fn marks_of(program: &turnpass::syntax::Program<'_>) -> Marks {
    marks(program).into_iter().map(|mark| (program.text(mark.span).to_vec(), mark.provenance)).collect()
}
