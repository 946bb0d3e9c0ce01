//! `turnpass compensate`: one program as a filter (`-` in, standard output out) or to a
//! file, or many into `--out-dir` in parallel (`batch.rs`).
//!
//! A program is written only when it compensates cleanly: a program with errors, one the
//! safety checks refuse, or one that carries a provenance comment (compensated already;
//! `--force` to compensate it anyway) writes nothing and exits 1. A program whose edits the
//! check before writing finds worse than the program as written, or past the bound the
//! program as written meets, is written as it came (exit 0). What is written carries a
//! provenance comment of its own (`compensation::provenance`). An output that would replace
//! an input is refused before any work, unless `--force`. The `--report json` goes to
//! standard output, which then holds the report alone, or into `--report-file`; when the
//! program itself goes to standard output the report needs that file (one stream each).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::builder::{PossibleValuesParser, TypedValueParser};
use clap::{Args, ValueEnum};

use turnpass::compensation::deviation::Figures;
use turnpass::compensation::fit::{FitOptions, Strategy};
use turnpass::compensation::provenance::{self, Provenance};
use turnpass::compensation::verify::{self, Measure, PartFrom};
use turnpass::compensation::{
    CompensateOptions, CycleForm, Judged, OTHER_NOT_AS_WRITTEN, Outcome, PROFILE_COPIED, PROFILE_NOT_COPIED,
    PROFILE_NOT_IN_PLACE, PROFILE_TAKE_UP, SINGLE_NOT_IN_PLACE, THREAD_NOT_IN_PLACE, compensate_program,
};
use turnpass::diagnostic::{Diagnostic, DiagnosticKind};
use turnpass::error_model::ErrorModel;
use turnpass::machine::StockSettings;
use turnpass::part::clearance::Clearance;
use turnpass::pipeline::Ready;
use turnpass::printer;
use turnpass::semantic::Machine;
use turnpass::semantic::nose_radius::ToolTable;
use turnpass::source::Span;

use super::common::{
    CliError, ReadArgs, Resolved, RunArgs, StockArgs, check_output, display_name, is_stdout, model_name, model_sha256,
    model_source, pipeline_settings, read_program, ready_or_diagnostics, rendered, required_error_model, write_output,
};
use super::numbers::{self, within};
use super::streams;
use super::table::{WithTable, split_summary, with_table};

#[derive(Args)]
pub struct CompensateArgs {
    /// Program files; `-` reads standard input (the compensated program then goes to
    /// standard output).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Output file for one program (default: standard output; `-` is standard output).
    #[arg(short, long, value_name = "OUT", conflicts_with = "out_dir")]
    pub output: Option<PathBuf>,
    /// Write each compensated program into DIR under its own file name; programs are
    /// compensated in parallel.
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,
    /// Write over an input program (`-o` naming it, or `--out-dir` its own folder), and
    /// compensate a program that carries a provenance comment (a compensated program).
    #[arg(long)]
    pub force: bool,
    #[command(flatten)]
    pub fit: FitArgs,
    /// Refuse to write a program whose predicted deviation from the nominal part, as
    /// `verify` measures it, exceeds MM (default: verify's, twice the least increment).
    #[arg(long, allow_negative_numbers = true, value_name = "MM", value_parser = within(numbers::MAX_DEVIATION_MM))]
    pub max_deviation: Option<f64>,
    /// Also write a report: per edited block the corrections, fitted arcs, predicted
    /// residual and SSQ before and after; on standard output, which then holds the report
    /// alone, or into --report-file.
    #[arg(long, value_enum, value_name = "FORMAT")]
    pub report: Option<ReportFormat>,
    /// Write the report into FILE instead of standard output (needed when the program
    /// itself goes to standard output).
    #[arg(long, value_name = "FILE", requires = "report")]
    pub report_file: Option<PathBuf>,
    #[command(flatten)]
    pub read: ReadArgs,
    #[command(flatten)]
    pub run: RunArgs,
    /// The bar the part is cut from, for the check of what is written (as `verify --stock`).
    #[command(flatten)]
    pub stock: StockArgs,
    /// Check what is written pass by pass, as `verify --passes` measures it, instead of on the
    /// finished part (every pass, roughing and thread infeed included, held to the bound).
    #[arg(long)]
    pub passes: bool,
    /// Also say, for each program, where the machine settings and the model come from.
    #[arg(long, short)]
    pub verbose: bool,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum ReportFormat {
    Json,
}

/// How moves are re-expressed and checked (shared with `plot`).
#[derive(Args, Clone)]
pub struct FitArgs {
    /// How a compensated move is written: the cheapest form that meets the tolerance
    /// (auto), one circle per arc, circles per half or quarter, adaptive arcs, or G01 lines.
    #[arg(long, default_value = "auto", value_parser = strategy_parser())]
    pub strategy: Strategy,
    /// Every commanded point lies this close to the written path, mm (default: half the
    /// least increment).
    #[arg(long, allow_negative_numbers = true, value_name = "MM", value_parser = within(numbers::TOLERANCE_MM))]
    pub tolerance: Option<f64>,
    /// Only with --strategy densify: one G01 every MM of path (default: as few as the
    /// tolerance allows).
    #[arg(long, allow_negative_numbers = true, value_name = "MM", value_parser = within(numbers::STEP_MM))]
    pub step: Option<f64>,
    /// Refuse the program when the model moves any point by more than MM.
    #[arg(
        long,
        allow_negative_numbers = true,
        value_name = "MM",
        default_value_t = 0.1,
        value_parser = within(numbers::MAX_SHIFT_MM),
    )]
    pub max_shift: f64,
    /// Expand every canned cycle, not only those whose motion changes.
    #[arg(long)]
    pub expand_cycles: bool,
    /// Minutes since the machine started when the program starts (thermal effects;
    /// default: the model's `start_min`).
    #[arg(long, allow_negative_numbers = true, value_name = "MIN", value_parser = within(numbers::MINUTES))]
    pub start_min: Option<f64>,
    /// The machine runs with this control table loaded (as `turnpass table` writes it: a
    /// LinuxCNC INI file, a Fanuc tape): compensate only what the table leaves.
    #[arg(long, value_name = "FILE")]
    pub with_table: Option<PathBuf>,
}

fn strategy_parser() -> impl TypedValueParser<Value = Strategy> {
    PossibleValuesParser::new(Strategy::ALL.map(Strategy::name))
        .map(|name| Strategy::from_name(&name).unwrap_or_default())
}

impl FitArgs {
    /// Refuse options that do not go together: `--step` is the length of each line
    /// `--strategy densify` writes, and the other strategies choose their own segments, so
    /// with them it would only change how closely the path is sampled, which no option
    /// promises.
    pub fn check(&self) -> Result<(), CliError> {
        if self.step.is_some() && self.strategy != Strategy::Densify {
            let name = self.strategy.name();
            return Err(CliError::Usage(format!(
                "--step is the length of each G01 that --strategy densify writes, and --strategy {name} chooses \
                 its own segments: give --strategy densify with --step, or leave --step out"
            )));
        }
        Ok(())
    }

    /// Refuse a `--step` finer than what a program on `machine` can write: its lines' ends
    /// would fall on the same increments, making lines of no length by the million, and the
    /// work and memory would follow the option instead of the program.
    pub fn check_step(&self, machine: &Machine) -> Result<(), CliError> {
        let finest = machine.finest_increment_mm();
        match self.step {
            Some(step) if step < finest * (1.0 - 1e-9) => Err(CliError::Usage(format!(
                "--step {step} mm is finer than the least increment a program can write on this machine \
                 ({finest} mm): lines that short would end on the same increments; give --step {finest} or more"
            ))),
            _ => Ok(()),
        }
    }

    pub fn options(&self, machine: &Machine) -> CompensateOptions {
        let half_increment = machine.increment * machine.scale() / 2.0;
        CompensateOptions {
            fit: FitOptions {
                strategy: self.strategy,
                tolerance_mm: self.tolerance.unwrap_or(half_increment),
                step_mm: self.step,
            },
            max_shift_mm: self.max_shift,
            expand_cycles: self.expand_cycles,
            profiles_in_place: true,
            profiles_copied: true,
            threads_in_place: true,
            singles_in_place: true,
            others_as_written: true,
            thread_pieces_every_pass: false,
            paths: false,
            block_reports: true,
        }
    }

    /// The error model of the program's model file, started at `--start-min` when given, on
    /// a machine with `--with-table` loaded when given (and that table, with the words for
    /// standard error of what goes where).
    pub fn error_model(
        &self,
        resolved: &Resolved,
        command: &str,
    ) -> Result<(ErrorModel, Option<(WithTable, String)>), CliError> {
        let mut model = required_error_model(resolved, command)?;
        if let Some(start) = self.start_min {
            model.start_min = start;
        }
        match &self.with_table {
            Some(path) => {
                let (combined, with) = with_table(path, &resolved.settings, &model, command)?;
                let mut text = format!("{command}: {}\n", split_summary(&model, &with));
                if let Some(why) = with.loaded.unverified {
                    text.push_str(&format!("{command}: warning: unverified: {why}\n"));
                }
                Ok((combined, Some((with, text))))
            }
            None => Ok((model, None)),
        }
    }

    /// Compensate a ready program with `model`; `paths` keeps every sample's paths (for
    /// `plot`), `block_reports` reports every edited block (for `--report json`).
    pub fn compensate(&self, program: &Ready<'_>, model: &ErrorModel, paths: bool, block_reports: bool) -> Outcome {
        let options = CompensateOptions { paths, block_reports, ..self.options(&program.machine) };
        compensate_program(
            &program.parsed.program,
            &program.lowered,
            &program.machine,
            model,
            &options,
            Judged::EveryFeed,
        )
    }

    /// `compensate` for writing: every edited block reported with `block_reports`, the
    /// profiles of cycles and the words of thread cycles compensated in place, or not, and
    /// the moves that need no correction left as written, or not (`in_place`; the feed moves
    /// that keep clear of the finished part, `clearance`, only where the check measures the
    /// part); every thread pass held to the bound where the check is `measure`d pass by pass.
    fn compensate_cycles(
        &self,
        program: &Ready<'_>,
        model: &ErrorModel,
        (block_reports, measure, clearance): (bool, Measure, Option<&Clearance>),
        in_place: InPlace,
    ) -> Outcome {
        let options = CompensateOptions {
            paths: false,
            block_reports,
            thread_pieces_every_pass: measure == Measure::Passes,
            profiles_in_place: in_place.profiles,
            profiles_copied: in_place.copies,
            threads_in_place: in_place.threads,
            singles_in_place: in_place.singles,
            others_as_written: in_place.others,
            ..self.options(&program.machine)
        };
        let judged = match (in_place.air, measure, clearance) {
            (LeftAsWritten::Feeds, Measure::Part, Some(clearance)) => Judged::Shaping(clearance),
            (LeftAsWritten::Feeds | LeftAsWritten::Rapids, ..) => Judged::EveryFeed,
            (LeftAsWritten::None, ..) => Judged::Every,
        };
        compensate_program(&program.parsed.program, &program.lowered, &program.machine, model, &options, judged)
    }
}

/// The blocks of `program` that `cycle_lines` names for `cycles` (each call and the ends of
/// its profile), with their spans: what it needs of the AST, taken before the AST goes.
fn cycle_blocks(
    program: &turnpass::syntax::Program<'_>,
    cycles: &[turnpass::compensation::CycleOutcome],
) -> Vec<(usize, Span)> {
    let mut blocks: Vec<usize> = Vec::new();
    for cycle in cycles {
        blocks.push(cycle.block);
        if let CycleForm::ProfileEdited { profile, .. } | CycleForm::ProfileCopied { profile, .. } = &cycle.form {
            blocks.extend(profile.first().into_iter().chain(profile.last()));
        }
    }
    blocks.sort_unstable();
    blocks.dedup();
    blocks.into_iter().filter(|&b| b < program.blocks().len()).map(|b| (b, program.block(b).span)).collect()
}

/// One line per cycle call whose moves change: kept with its profile compensated in place
/// (the profile's lines), or expanded (and why); `blocks` holds the spans of the blocks it
/// names (`cycle_blocks`) in the text `bytes`.
fn cycle_lines(
    name: &str,
    blocks: &[(usize, Span)],
    bytes: &[u8],
    cycles: &[turnpass::compensation::CycleOutcome],
) -> Vec<u8> {
    let mut out = Vec::new();
    if cycles.iter().all(|c| matches!(c.form, CycleForm::Kept)) {
        return out;
    }
    let lines = turnpass::source::LineIndex::new(bytes);
    let span = |block: usize| blocks.binary_search_by_key(&block, |&(b, _)| b).map_or(Span::new(0, 0), |k| blocks[k].1);
    let line = |block: usize| lines.position(span(block).start).0;
    for cycle in cycles {
        let call = line(cycle.block);
        let text = String::from_utf8_lossy(span(cycle.block).text(bytes)).trim_end().to_string();
        let said = match &cycle.form {
            CycleForm::Kept => continue,
            CycleForm::LeftAsWritten => {
                "kept as written: the part it cuts, with the blocks around it compensated, is within the bound"
                    .to_string()
            }
            CycleForm::ProfileEdited { profile, lead } => {
                let first = profile.first().map_or(0, |&b| line(b));
                let last = profile.last().map_or(0, |&b| line(b));
                match lead {
                    None => format!("kept; its profile (lines {first}-{last}) is compensated in place"),
                    Some(lead) => format!(
                        "kept; its profile (lines {first}-{last}) is compensated in place, and its lead {}",
                        lead_said(lead)
                    ),
                }
            }
            CycleForm::WordsEdited { lead, single_pass, .. } => {
                // A single-pass call (`G92`, `G90`) is one pass, not always the last.
                let pass = if *single_pass { "its pass's" } else { "the final pass's" };
                match lead {
                    None => format!("kept; its words carry {pass} correction"),
                    Some(lead) => format!("kept; its words carry {pass} correction, and its lead {}", lead_said(lead)),
                }
            }
            CycleForm::RoughsOriginal => {
                "kept; it roughs the profile as written, its finishing cycle runs a compensated copy".to_string()
            }
            CycleForm::ProfileCopied { profile, copy: (first, last), reason } => {
                let from = profile.first().map_or(0, |&b| line(b));
                let to = profile.last().map_or(0, |&b| line(b));
                let names = if first == last { first.clone() } else { format!("{first}-{last}") };
                format!(
                    "runs a compensated copy of its profile (lines {from}-{to}), written as {names}, which the call \
                     now names; the roughing keeps the profile as written ({reason})"
                )
            }
            CycleForm::Expanded { reason, lead: None } => format!("expanded: {reason}"),
            CycleForm::Expanded { reason, lead: Some(lead) } => {
                format!("expanded: {reason}; its thread moves' lead {}", lead_said(lead))
            }
        };
        out.extend_from_slice(format!("compensate: {name}: line {call} `{text}`: {said}\n").as_bytes());
    }
    out
}

/// A thread lead written for the slide to cut the programmed one, and where no word of the
/// dialect holds it, how far the lead written runs off over the thread.
fn lead_said(lead: &turnpass::compensation::LeadChange) -> String {
    let mut said = format!(
        "`{}` is written `{}` ({:+} ppm), for the slide to cut the programmed lead",
        lead.from, lead.to, lead.change_ppm
    );
    if let Some(mm) = lead.unheld_mm {
        said.push_str(&format!(
            ", short of it by {mm:.4} mm over the thread: no lead word of this dialect takes the digits it needs"
        ));
    }
    said
}

/// What a refused program is compensated again with, to find what would meet the bound,
/// and what measures the program as written: the check, and the settings a written program
/// is read back with.
struct Trial<'a> {
    check: TrialCheck<'a>,
    reading: &'a turnpass::pipeline::Settings,
}

/// What every trial of one program checks against, whatever it reads the program back with.
#[derive(Clone, Copy)]
struct TrialCheck<'a> {
    model: &'a ErrorModel,
    tools: &'a ToolTable,
    measure: Measure,
    stock: Option<&'a StockSettings>,
    clearance: Option<&'a Clearance>,
}

impl Trial<'_> {
    /// Programs of more moves than this are not compensated again with every strategy.
    const MAX_MOVES: usize = 100_000;

    /// What the check's parts are cut from: the stock, and the finished part the clearance
    /// of the feed moves was measured on (the original's nominal part, cut once).
    fn part(&self) -> PartFrom<'_> {
        PartFrom { stock: self.check.stock, finished: self.check.clearance.map(Clearance::finished) }
    }

    /// The program as it came (`bytes`, which `original` holds again), measured as `verify`
    /// of it against itself measures it: beside the edits, where the bar assumed from both
    /// programs' cuts gives only the edits a surface to probe, it measures nothing, while
    /// verify of it alone finds no surface and measures its passes (`verify::check_written`).
    /// Its figures only where that verify passes it: within `bound`, its part measured whole
    /// and, measured pass by pass, its thread's lead within `bound`.
    fn as_written(
        &self,
        original: impl FnOnce() -> Result<verify::Held, Vec<Diagnostic>>,
        bytes: &[u8],
        bound: f64,
    ) -> Option<Figures> {
        let checked = verify::check_written(
            original,
            bytes,
            self.reading,
            self.check.tools,
            (self.check.model, self.check.measure, self.part()),
        )
        .ok()?;
        let stopped = checked.part.as_ref().is_some_and(|part| part.incomplete().is_some());
        let lead_off =
            checked.deviation.lead.as_ref().is_some_and(|lead| lead.after_mm > bound && checked.part.is_none());
        let figures = checked.deviation.after;
        (figures.max_mm <= bound && !stopped && !lead_off).then_some(figures)
    }

    /// The other strategy whose compensated program, read back and measured as the check
    /// before writing measures it, deviates least, with that deviation, mm; `None` for a
    /// long program (`MAX_MOVES`) or where no other strategy's program reads back.
    fn closest_strategy(&self, program: &Ready<'_>, fit: &FitArgs, in_place: InPlace) -> Option<(&'static str, f64)> {
        if program.valid().moves.len() > Self::MAX_MOVES {
            return None;
        }
        let words = verify::Words::of(&program.parsed.program, &program.lowered.expansions);
        let original = verify::Held::from_toolpath(words, program.valid(), self.check.tools);
        Strategy::ALL
            .into_iter()
            .filter(|&strategy| strategy != fit.strategy && (fit.step.is_none() || strategy == Strategy::Densify))
            .filter_map(|strategy| {
                let other = FitArgs { strategy, ..fit.clone() };
                let outcome = other.compensate_cycles(
                    program,
                    self.check.model,
                    (false, self.check.measure, self.check.clearance),
                    in_place,
                );
                if outcome.refused() {
                    return None;
                }
                let written = printer::print(&program.parsed.program, &outcome.edits);
                let checked = verify::check_written(
                    || Ok(original.clone()),
                    &written,
                    self.reading,
                    self.check.tools,
                    (self.check.model, self.check.measure, self.part()),
                )
                .ok()?;
                Some((strategy.name(), checked.deviation.after.max_mm))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }
}

/// Which cycles keep their calls with a correction in place: those sharing a profile with a
/// finishing cycle (the profile edited, or else copied for the finishing cycle), thread
/// cycles and single turning and facing cycles (their words edited); and whether the others
/// stay as written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct InPlace {
    profiles: bool,
    copies: bool,
    threads: bool,
    singles: bool,
    others: bool,
    /// The moves that need no correction left as written (`plan::Judged`).
    air: LeftAsWritten,
}

/// Which moves that need no correction are left as written (`plan::Judged`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum LeftAsWritten {
    /// Rapids, and feed moves that keep clear of the finished part.
    Feeds,
    Rapids,
    None,
}

/// Why the check before writing turned down each way of keeping cycles that was tried.
#[derive(Debug, Clone, Default)]
struct Because {
    profiles: Option<String>,
    copies: Option<String>,
    threads: Option<String>,
    /// Why the single cycles' words are not compensated in place, and, where leaving them as
    /// written is tried next and misses too, why not that either.
    singles: Option<String>,
    others: Option<String>,
}

impl InPlace {
    /// What to try after `outcome` (compensated so) missed the check: the feed moves it left
    /// as written corrected if it left any, else the cycles it left as written expanded if
    /// it left any, else the single turning and facing cycles whose words it edited left as
    /// written if it edited one (then expanded, as cycles left as written), else the
    /// profiles copied for their finishing
    /// cycles if it edited one in place, else expanded if it copied one, else the threads
    /// expanded if it edited one, else the rapids it left as written corrected; `None` when
    /// nothing is left to try.
    fn without(self, outcome: &Outcome) -> Option<InPlace> {
        let any = |form: fn(&CycleForm) -> bool| outcome.cycles.iter().any(|c| form(&c.form));
        if self.air == LeftAsWritten::Feeds && outcome.left_alone.feeds > 0 {
            // Before any cycle is given up: a cycle kept is worth more to the machinist than
            // a roughing pass left as written.
            Some(InPlace { air: LeftAsWritten::Rapids, ..self })
        } else if self.others && any(|f| matches!(f, CycleForm::LeftAsWritten)) {
            // A cycle left with no correction at all is the likeliest to miss.
            Some(InPlace { others: false, ..self })
        } else if self.singles && any(|f| matches!(f, CycleForm::WordsEdited { thread: false, .. })) {
            // Before a profile or a thread is given up: a single cycle's words carry every
            // correction of its cut, but not of its move back out.
            Some(InPlace { singles: false, ..self })
        } else if self.profiles && any(|f| matches!(f, CycleForm::ProfileEdited { .. })) {
            Some(InPlace { profiles: false, ..self })
        } else if self.copies && any(|f| matches!(f, CycleForm::ProfileCopied { .. })) {
            Some(InPlace { copies: false, ..self })
        } else if self.threads && any(|f| matches!(f, CycleForm::WordsEdited { thread: true, .. })) {
            Some(InPlace { threads: false, ..self })
        } else if self.air != LeftAsWritten::None && outcome.left_alone.rapids + outcome.left_alone.feeds > 0 {
            // The rapids left as written are corrected last: the model's play may still need
            // an end in the air corrected.
            Some(InPlace { air: LeftAsWritten::None, ..self })
        } else {
            None
        }
    }

    /// Keep `why` as the reason of the cycles `next` expands.
    fn said(self, next: InPlace, why: String, because: &mut Because) {
        if self.profiles && !next.profiles {
            because.profiles = Some(format!("with its profile compensated in place and the cycles {why}"));
        }
        if self.copies && !next.copies {
            because.copies = Some(format!(
                "with the roughing on the profile as written, the finishing on a compensated copy and the cycles {why}"
            ));
        }
        if self.threads && !next.threads {
            because.threads = Some(format!("with its words compensated in place and the cycle {why}"));
        }
        if self.singles && !next.singles {
            because.singles =
                Some(format!("its moves change, and with its words compensated in place and the cycle {why}"));
        }
        if self.others && !next.others {
            because.others = Some(format!("its moves change, and with it left as written and the other cycles {why}"));
            // A single cycle whose words are given up is left as written in this trial, so
            // its reason says why that misses too.
            if !self.singles
                && let Some(singles) = &mut because.singles
            {
                singles.push_str(&format!("; with it left as written and the other cycles {why}"));
            }
        }
    }
}

/// Why a program is written as it came.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Unchanged {
    /// The edits would leave the predicted part worse than the program as written, by its
    /// largest and its RMS deviation alike.
    Worse,
    /// The edits would miss the bound, which the program as written meets.
    PastTheBound,
}

/// The program written as it came (`bytes`), and why: `before` the figures of the program
/// as written, as verify of it against itself finds them (`Trial::as_written`), `after`
/// those of the edits, as the check before writing found them. `outcome` is what the edits
/// were; its report, with `--report json`, is that of the program as written.
fn written_unchanged(
    name: &str,
    bytes: &[u8],
    (why, bound): (Unchanged, f64),
    (before, after): (Figures, Figures),
    outcome: &mut Outcome,
    mut messages: Vec<u8>,
    json: bool,
) -> FileResult {
    let because = match why {
        Unchanged::Worse => format!(
            "its edits would leave the predicted part worse than the program as written (RMS {:.5} -> {:.5} mm, \
             largest {:.5} -> {:.5} mm)",
            before.rms_mm, after.rms_mm, before.max_mm, after.max_mm,
        ),
        Unchanged::PastTheBound => format!(
            "compensated, it would miss the bound {bound:.5} mm (largest {:.5} mm, RMS {:.5} mm), which the program \
             as written already meets (largest {:.5} mm, RMS {:.5} mm)",
            after.max_mm, after.rms_mm, before.max_mm, before.rms_mm,
        ),
    };
    messages.extend_from_slice(
        format!(
            "compensate: {name}: written unchanged: {because}; predicted deviation (as verify measures it) RMS {:.5} \
             mm, largest {:.5} mm\n",
            before.rms_mm, before.max_mm,
        )
        .as_bytes(),
    );
    outcome.report.totals.before = before;
    let report = json.then(|| {
        let because = match why {
            Unchanged::Worse => "edits_worse",
            Unchanged::PastTheBound => "edits_past_the_bound",
        };
        serde_json::json!({
            "file": name,
            "report": outcome.report.unchanged(),
            "written_unchanged": { "because": because, "bound_mm": bound, "before": before, "after_edits": after },
        })
    });
    FileResult { code: 0, messages, output: Some(bytes.to_vec()), report, errors: Vec::new() }
}

/// What compensating one file gave.
pub struct FileResult {
    /// 0 written, 1 errors or refused, 2 I/O or model trouble.
    pub code: u8,
    /// For standard error: diagnostics and a summary line.
    pub messages: Vec<u8>,
    /// The compensated program (only with code 0).
    pub output: Option<Vec<u8>>,
    pub report: Option<serde_json::Value>,
    /// Why nothing is written (with a code other than 0): the errors, each as `check
    /// --format json` gives a diagnostic, or `{"message"}` for one that is not on a text.
    pub errors: Vec<serde_json::Value>,
}

impl FileResult {
    pub fn failed(code: u8, messages: Vec<u8>) -> FileResult {
        FileResult { code, messages, output: None, report: None, errors: Vec::new() }
    }

    /// A failure whose errors are `diagnostics` on the text `bytes`, named `name`.
    fn refused(code: u8, messages: Vec<u8>, name: &str, bytes: &[u8], diagnostics: &[Diagnostic]) -> FileResult {
        let mut result = FileResult::failed(code, messages);
        result.add_errors(name, bytes, diagnostics);
        result
    }

    /// The errors among `diagnostics` (on `bytes`, named `name`) as reasons of the failure.
    fn add_errors(&mut self, name: &str, bytes: &[u8], diagnostics: &[Diagnostic]) {
        let errors: Vec<Diagnostic> = diagnostics.iter().filter(|d| d.is_error()).cloned().collect();
        let source = turnpass::diagnostic::render::RenderSource::new(name, bytes);
        self.errors.extend(
            turnpass::diagnostic::render::to_json(&source, &errors)
                .iter()
                .filter_map(|json| serde_json::to_value(json).ok()),
        );
    }

    /// The entry of this program in a batch's `--report json`: its report, or why it failed.
    pub fn report_entry(&self, name: &str) -> serde_json::Value {
        match &self.report {
            Some(report) => report.clone(),
            None => {
                let mut errors = self.errors.clone();
                if errors.is_empty() {
                    // A failure that is no diagnostic (a file that cannot be read): its message.
                    let text = String::from_utf8_lossy(&self.messages);
                    let message = text.trim_end().trim_start_matches("error: ").to_string();
                    errors.push(serde_json::json!({ "message": message }));
                }
                serde_json::json!({ "file": name, "failed": { "exit_code": self.code, "errors": errors } })
            }
        }
    }
}

/// What holds for one program and for a batch alike: the fit's options, and a report that
/// does not share standard output with the program.
pub fn check_arguments(args: &CompensateArgs) -> Result<(), CliError> {
    args.fit.check()?;
    let program_to_stdout = args.out_dir.is_none() && args.output.as_deref().is_none_or(is_stdout);
    if args.report.is_some() && args.report_file.is_none() && program_to_stdout {
        return Err(CliError::Usage(
            "the compensated program goes to standard output, so the report needs a file of its own: give \
             --report-file FILE (or -o FILE for the program)"
                .to_string(),
        ));
    }
    Ok(())
}

/// One program compensated into `-o` or standard output (several go to `batch.rs`, which
/// builds on this file).
pub fn compensate(args: CompensateArgs) -> Result<ExitCode, CliError> {
    let [path] = args.files.as_slice() else {
        return Err(CliError::Usage("several programs need --out-dir DIR to write them into".to_string()));
    };
    check_output(args.output.as_deref())?;
    if let Some(output) = args.output.as_deref() {
        refuse_overwriting_input(&args.files, output, args.force)?;
    }
    let result = compensate_file(path, &args)?;
    streams::err(&result.messages);
    if let Some(output) = &result.output {
        write_output(args.output.as_deref(), output)?;
    }
    if let Some(report) = &result.report {
        write_report(&args, report)?;
    }
    Ok(ExitCode::from(result.code))
}

/// The report as JSON, into `--report-file` or on standard output.
pub fn write_report(args: &CompensateArgs, report: &impl serde::Serialize) -> Result<(), CliError> {
    let text = serde_json::to_string_pretty(report).unwrap_or_default() + "\n";
    write_output(args.report_file.as_deref(), text.as_bytes())
}

/// Refuse, unless `force`, to write `output` when it is one of the `inputs` (the same file,
/// through a link or by another path): the nominal program would be lost.
pub fn refuse_overwriting_input(inputs: &[PathBuf], output: &Path, force: bool) -> Result<(), CliError> {
    if force || is_stdout(output) {
        return Ok(());
    }
    let input = inputs.iter().filter(|input| *input != Path::new("-")).find(|input| same_file(input, output));
    match input {
        Some(input) => Err(CliError::Usage(format!(
            "compensate would write {} over the program {}, which it reads; write the compensated program \
             elsewhere (-o or --out-dir), or give --force to replace it",
            output.display(),
            input.display()
        ))),
        None => Ok(()),
    }
}

/// Whether `a` and `b` name one file (through a link or by another path): the same device
/// and inode, as `stat` finds them. Nothing is opened: a FIFO opened to compare it would
/// wait for a writer. A path that does not exist (an output not made yet) is no input.
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        #[cfg(unix)]
        (Ok(a), Ok(b)) => {
            use std::os::unix::fs::MetadataExt;
            (a.dev(), a.ino()) == (b.dev(), b.ino())
        }
        #[cfg(not(unix))]
        (Ok(_), Ok(_)) => std::fs::canonicalize(a).ok().is_some_and(|a| std::fs::canonicalize(b).ok() == Some(a)),
        _ => false,
    }
}

/// Compensate one program; nothing is written here.
pub fn compensate_file(path: &Path, args: &CompensateArgs) -> Result<FileResult, CliError> {
    let (bytes, resolved) = read_program(path, &args.read)?;
    args.fit.check_step(&Machine::from_settings(&resolved.settings))?;
    let (model, table) = args.fit.error_model(&resolved, "compensate")?;
    let name = display_name(path);
    let mut messages = Vec::new();
    if let Some((_, said)) = &table {
        messages.extend_from_slice(said.as_bytes());
    }
    if args.verbose {
        messages.extend_from_slice(format!("compensate: {name}: {}\n", model_source(&args.read, &resolved)).as_bytes());
    }
    let program = match ready_or_diagnostics(&name, &bytes, &resolved, &args.run, "compensate", &mut messages) {
        Ok(ready) => ready,
        Err((text, diagnostics)) => return Ok(FileResult::refused(1, text, &name, &bytes, &diagnostics)),
    };
    // A program that carries a provenance comment was compensated already.
    if let Some(diagnostic) = provenance::refusal(&program.parsed.program).filter(|_| !args.force) {
        messages.extend(rendered(&name, &bytes, std::slice::from_ref(&diagnostic)));
        messages.extend_from_slice(format!("compensate: {name}: refused; nothing is written\n").as_bytes());
        return Ok(FileResult::refused(1, messages, &name, &bytes, &[diagnostic]));
    }
    // Cycles that share a profile with a finishing cycle stay calls, their profile
    // compensated in place; where the program so written misses the check, the finishing
    // cycle runs a compensated copy of the profile and the roughing the profile as written;
    // where that misses it too, they are expanded, and the report says why.
    let mut because = Because::default();
    let mut in_place =
        InPlace { profiles: true, copies: true, threads: true, singles: true, others: true, air: LeftAsWritten::Feeds };
    let stock = args.stock.check(&resolved).stock;
    let measure = if args.passes { Measure::Passes } else { Measure::Part };
    // The feed moves that cut no finished surface, on the part the check measures.
    let clearance = (measure == Measure::Part)
        .then(|| turnpass::part::clearance::clearance(program.valid(), &program.machine, stock.as_ref()))
        .flatten();
    let tools = ToolTable::from_machine(&program.machine);
    // The original is analysed again where it is needed after its AST and moves went
    // (before the read-back of what is about to be written): its text and settings are the
    // same, and so is what it reads as.
    let again =
        || ready_or_diagnostics(&name, &bytes, &resolved, &args.run, "compensate", &mut Vec::new()).map_err(|(_, d)| d);
    let machine = program.machine.clone();
    let mut kept = Some(program);
    // `--strategy auto` writes each move in its cheapest form; where those forms leave the
    // nose no room under G41/G42, the program is written in the other form that reads back
    // and meets the bound with the least deviation (`fell_back`).
    let mut fit = args.fit.clone();
    let mut fell_back: Option<String> = None;
    // Each try says its own warnings: only the last try's are kept (a cycle left as it is
    // is said once, not once for every way of keeping cycles that was tried).
    let said_before = messages.len();
    let check =
        TrialCheck { model: &model, tools: &tools, measure, stock: stock.as_ref(), clearance: clearance.as_ref() };
    let (mut outcome, written, cycle_blocks, reading) = loop {
        messages.truncate(said_before);
        let program = match kept.take().map_or_else(&again, Ok) {
            Ok(program) => program,
            Err(diagnostics) => {
                messages.extend(rendered(&name, &bytes, &diagnostics));
                return Ok(FileResult::refused(1, messages, &name, &bytes, &diagnostics));
            }
        };
        let mut outcome =
            fit.compensate_cycles(&program, &model, (args.report.is_some(), measure, clearance.as_ref()), in_place);
        if outcome.refused()
            && let Some(next) = in_place.without(&outcome)
        {
            let why = format!(
                "compensated in place, it cannot be written: {}",
                outcome.diagnostics.iter().find(|d| d.is_error()).map_or_else(String::new, Diagnostic::message)
            );
            in_place.said(next, why, &mut because);
            in_place = next;
            kept = Some(program);
            continue;
        }
        messages.extend(rendered(&name, &bytes, &outcome.diagnostics));
        if outcome.refused() {
            messages.extend_from_slice(format!("compensate: {name}: refused; nothing is written\n").as_bytes());
            return Ok(FileResult::refused(1, messages, &name, &bytes, &outcome.diagnostics));
        }
        let provenance = Provenance {
            version: provenance::VERSION.to_string(),
            model: model_name(&resolved),
            model_sha256: model_sha256(&resolved)?,
            table_sha256: table.as_ref().map(|(table, _)| table.sha256.clone()),
            tolerance_mm: args.fit.options(&program.machine).fit.tolerance_mm,
            strategy: fit.strategy,
            step_mm: args.fit.step,
            start_min: model.start_min,
            // Where the text alone would read as the other dialect, the comment names it.
            dialect: printer::mark::dialect_to_name(
                &program.parsed.program,
                &printer::print(&program.parsed.program, &outcome.edits),
            ),
        };
        provenance::insert(&program.parsed.program, &mut outcome.edits, &provenance);
        let written = printer::print(&program.parsed.program, &outcome.edits);
        // The edits are in the text now: they go before the read-back, which holds a second
        // program.
        drop(std::mem::take(&mut outcome.edits));
        drop(std::mem::take(&mut outcome.edited));
        // What is about to be written is read back and measured as `verify` measures it; its
        // figures are the ones reported, and a program that misses verify's bound is refused.
        // Read back as the original was read: with `--dialect auto`, the evidence of the
        // dialect may have been in the blocks an edit replaced.
        let mut reading = pipeline_settings(&resolved, &args.run, true);
        reading.parse = printer::read_back_options(&program.parsed.program);
        let trial = Trial { check, reading: &reading };
        let bound = args.max_deviation.unwrap_or_else(|| verify::default_bound_mm(&machine));
        let mut unreadable = FileResult::failed(1, Vec::new());
        // The original's AST and moves go before the read-back, which holds a second program;
        // the check holds the original again once the read-back is held (`check_written`).
        let blocks = cycle_blocks(&program.parsed.program, &outcome.cycles);
        let moves = program.valid().moves.len();
        drop(program);
        let refusal = match verify::check_written(
            || again().map(|program| verify::Held::of(program, &tools)),
            &written,
            &reading,
            &tools,
            (&model, measure, trial.part()),
        ) {
            Ok(verify::Written { deviation: figures, part, feed_change, lost, original }) => {
                let block = |k: usize| if k < original.path.len() { original.path.source(k) } else { Span::new(0, 0) };
                let totals = &mut outcome.report.totals;
                (totals.before, totals.after) = (figures.before, figures.after);
                totals.improvement_percent = figures.improvement_percent;
                let too_far = figures.worst.filter(|_| figures.after.max_mm > bound).map(|worst| {
                    let span = block(worst.original_move);
                    let tolerance_mm = args.fit.options(&machine).fit.tolerance_mm;
                    let deviation_mm = worst.deviation_mm;
                    let kind = DiagnosticKind::CompensationFailsCheck {
                        deviation_mm,
                        bound_mm: bound,
                        tolerance_mm,
                        other_strategy: None,
                    };
                    Diagnostic::error(kind, span)
                });
                // On the part the flanks' deviation judges the lead (`verify::checked`).
                let lead_off = figures.lead.filter(|lead| lead.after_mm > bound && part.is_none()).map(|lead| {
                    let span = lead.worst_move.map_or(Span::new(0, 0), block);
                    Diagnostic::error(
                        DiagnosticKind::ThreadLeadFailsCheck { lead_error_mm: lead.after_mm, bound_mm: bound },
                        span,
                    )
                });
                // A part model that stopped at its bound measured only part of the part.
                let stopped = part.as_ref().and_then(|part| part.incomplete());
                too_far
                    .or(stopped)
                    .or(lead_off)
                    .or_else(|| {
                        feed_change
                            .map(|change| Diagnostic::error(DiagnosticKind::CompensationChangesFeed, change.source))
                    })
                    .or_else(|| {
                        lost.map(|word| {
                            Diagnostic::error(DiagnosticKind::CompensationLosesWord { word: word.text }, word.span)
                        })
                    })
            }
            Err(problems) => {
                // Where in the text about to be written it does not read.
                unreadable.messages = rendered(&format!("{name} (compensated)"), &written, &problems);
                unreadable.add_errors(&format!("{name} (compensated)"), &written, &problems);
                let problem = problems.first().map_or_else(String::new, Diagnostic::message);
                // The original read cleanly, so a nose that does not fit is the moved contour's.
                let nose_has_no_room = !problems.is_empty()
                    && problems.iter().all(|d| matches!(d.kind, DiagnosticKind::NoseDoesNotFit { .. }));
                let kind = DiagnosticKind::CompensationUnreadable { problem, nose_has_no_room };
                Some(Diagnostic::error(kind, Span::new(0, 0)))
            }
        };
        if let Some(diagnostic) = refusal {
            if let Some(next) = in_place.without(&outcome) {
                // The roughing of a cycle kept with its profile edited, and the infeed passes of
                // a thread kept with its words edited, are not compensated, only moved with the
                // profile or the final pass: the finished part holds them to not gouging it.
                let lines = turnpass::source::LineIndex::new(&bytes);
                let line = lines.position(diagnostic.span.start).0;
                let why = match &diagnostic.kind {
                    DiagnosticKind::CompensationFailsCheck { deviation_mm, .. } => match measure {
                        Measure::Part => format!(
                            "kept, the part the program read back cuts is {deviation_mm:.5} mm off on the surface \
                             line {line} cuts, more than the bound {bound} mm (the check before writing measures the \
                             finished part: a roughing or thread infeed pass counts where it gouges it)"
                        ),
                        Measure::Passes => format!(
                            "kept, the program read back is {deviation_mm:.5} mm off at line {line}, more than the \
                             bound {bound} mm (--passes: the check before writing measures every pass, roughing and \
                             thread infeed passes among them)"
                        ),
                    },
                    DiagnosticKind::CompensationUnreadable { problem, .. } => {
                        format!("kept, the program read back does not run cleanly ({problem})")
                    }
                    _ => format!("kept, the program read back fails the check: {}", diagnostic.message()),
                };
                in_place.said(next, why, &mut because);
                in_place = next;
                continue;
            }
            if let DiagnosticKind::CompensationUnreadable { problem, nose_has_no_room: true } = &diagnostic.kind
                && fit.strategy == Strategy::Auto
                && fell_back.is_none()
                && moves <= Trial::MAX_MOVES
                && let Ok(program) = again()
                && let Some((other, _)) =
                    trial.closest_strategy(&program, &fit, in_place).filter(|&(_, deviation)| deviation <= bound)
                && let Some(strategy) = Strategy::from_name(other)
            {
                fell_back = Some(format!(
                    "compensate: {name}: --strategy auto: its cheapest forms leave the nose no room under \
                     G41/G42 ({problem}); written in the `{other}` form, which the nose can follow\n"
                ));
                fit.strategy = strategy;
                kept = Some(program);
                continue;
            }
            // A program whose edits miss the bound goes out as it came where the program as
            // written meets it, as verify of it against itself finds: there is nothing to
            // refuse.
            if let DiagnosticKind::CompensationFailsCheck { .. } = diagnostic.kind
                && let Some(before) =
                    trial.as_written(|| again().map(|program| verify::Held::of(program, &tools)), &bytes, bound)
            {
                let after = outcome.report.totals.after;
                let why = (Unchanged::PastTheBound, bound);
                let json = args.report.is_some();
                return Ok(written_unchanged(&name, &bytes, why, (before, after), &mut outcome, messages, json));
            }
            let mut diagnostic = diagnostic;
            if let DiagnosticKind::CompensationFailsCheck { other_strategy, .. } = &mut diagnostic.kind
                && moves <= Trial::MAX_MOVES
                && let Ok(program) = again()
            {
                *other_strategy = trial.closest_strategy(&program, &fit, in_place);
            }
            messages.append(&mut unreadable.messages);
            messages.extend(rendered(&name, &bytes, std::slice::from_ref(&diagnostic)));
            messages.extend_from_slice(format!("compensate: {name}: refused; nothing is written\n").as_bytes());
            unreadable.messages = messages;
            unreadable.add_errors(&name, &bytes, &[diagnostic]);
            return Ok(unreadable);
        }
        break (outcome, written, blocks, reading);
    };
    if let Some(said) = fell_back {
        messages.extend_from_slice(said.as_bytes());
    }
    let neither = match (&because.profiles, &because.copies) {
        (Some(a), Some(b)) => Some(format!("{a}; {b}")),
        (a, b) => a.clone().or_else(|| b.clone()),
    };
    let take_up = because.copies.as_ref().map(|copies| format!("{PROFILE_TAKE_UP}; {copies}"));
    for (constant, reason) in [
        (PROFILE_TAKE_UP, &take_up),
        (PROFILE_NOT_IN_PLACE, &because.profiles),
        (PROFILE_COPIED, &because.profiles),
        (PROFILE_NOT_COPIED, &neither),
        (THREAD_NOT_IN_PLACE, &because.threads),
        (SINGLE_NOT_IN_PLACE, &because.singles),
        (OTHER_NOT_AS_WRITTEN, &because.others),
    ] {
        let Some(reason) = reason else { continue };
        for cycle in &mut outcome.report.cycles {
            if cycle.reason.as_deref() == Some(constant) {
                cycle.reason = Some(reason.clone());
            }
        }
        for cycle in &mut outcome.cycles {
            if let CycleForm::Expanded { reason: why, .. } | CycleForm::ProfileCopied { reason: why, .. } =
                &mut cycle.form
                && why == constant
            {
                why.clone_from(reason);
            }
        }
    }
    // Edits that the check predicts leave the part worse than the program as it came, by its
    // largest and its RMS deviation alike (corrections the control's increments round the
    // wrong way), are not worth writing: the program goes out as it came, and says why. The
    // program as it came is measured as `verify` of it against itself measures it, the
    // figures it would be written with (`Trial::as_written`). It goes out only within the
    // bound and better than the edits by both figures.
    let after = outcome.report.totals.after;
    let bound = args.max_deviation.unwrap_or_else(|| verify::default_bound_mm(&machine));
    let trial = Trial { check, reading: &reading };
    let unchanged = (after.max_mm > outcome.report.totals.before.max_mm
        && after.rms_mm > outcome.report.totals.before.rms_mm)
        .then(|| trial.as_written(|| again().map(|program| verify::Held::of(program, &tools)), &bytes, bound))
        .flatten()
        .filter(|before| after.max_mm > before.max_mm && after.rms_mm > before.rms_mm);
    if let Some(before) = unchanged {
        let json = args.report.is_some();
        let why = (Unchanged::Worse, bound);
        return Ok(written_unchanged(&name, &bytes, why, (before, after), &mut outcome, messages, json));
    }
    let totals = &outcome.report.totals;
    messages.extend_from_slice(
        format!(
            "compensate: {name}: {} block{} edited, {} cycle{} expanded{}; largest correction {:.4} mm; \
             predicted deviation (as verify measures it) RMS {:.5} -> {:.5} mm, largest {:.5} -> {:.5} mm\n",
            totals.edited_blocks,
            super::common::plural(totals.edited_blocks),
            totals.expanded_cycles,
            super::common::plural(totals.expanded_cycles),
            match totals.profiles_copied {
                0 => String::new(),
                n => format!(", {n} profile{} copied for finishing", super::common::plural(n)),
            },
            totals.max_correction_mm,
            totals.before.rms_mm,
            totals.after.rms_mm,
            totals.before.max_mm,
            totals.after.max_mm,
        )
        .as_bytes(),
    );
    messages.extend(cycle_lines(&name, &cycle_blocks, &bytes, &outcome.cycles));
    if let feeds @ 1.. = outcome.left_alone.feeds {
        // Why a roughing pass by hand reads as the programmer wrote it.
        messages.extend_from_slice(
            format!(
                "compensate: {name}: {feeds} feed move{} left as written: the whole tool keeps {} mm clear of the \
                 finished part there (roughing that leaves its allowance, moves in the air)\n",
                super::common::plural(feeds),
                turnpass::part::clearance::CLEARANCE_MM,
            )
            .as_bytes(),
        );
    }
    let tolerance = args.fit.options(&machine).fit.tolerance_mm;
    if totals.inverse_residual_mm > tolerance {
        // The figures above are what the written program does; the tolerance asked for is
        // what the inverse could not reach.
        messages.extend_from_slice(
            format!(
                "compensate: {name}: note: the inverse stops {:.6} mm from the nominal path at its worst point, more \
                 than --tolerance {tolerance} mm: a slide is not reversed for less than half the least increment, \
                 and the inverse stops after {} steps\n",
                totals.inverse_residual_mm, totals.inverse_iterations,
            )
            .as_bytes(),
        );
    }
    let report = args.report.map(|_| serde_json::json!({ "file": name, "report": outcome.report }));
    Ok(FileResult { code: 0, messages, output: Some(written), report, errors: Vec::new() })
}
