//! `turnpass compensate` as one library call: a lowered, validated program and a machine
//! model in, the edits that compensate it (or the reasons to refuse), the report, and the
//! paths `plot` draws, out.
//!
//! sample the nominal path → invert the model (`inverse.rs`) → plan each move's segments
//! (`plan.rs`) → check the corrections (`safety.rs`) → edit the blocks (`rewrite.rs`) →
//! predict the rounded program through the model and report (`quantised.rs`,
//! `report.rs`).

mod stream;

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::error_model::ErrorModel;
use crate::printer::Edits;
use crate::semantic::nose_radius::ToolTable;
use crate::semantic::{Lowered, Machine};
use crate::source::Span;
use crate::syntax::Program;
use crate::toolpath::{Validated, Xz};

use super::deviation::LocalPath;
use super::fit::FitOptions;
use super::plan::{Judged, LeftAlone, PlanOptions};
use super::report::{Report, ReportInput};
use super::rewrite;
use crate::error_model::sampling::{PathSample, Sampling};

pub use crate::error_model::sampling::SAMPLE_STEP_MM;

/// The share of the tolerance the straight interpolation between samples may use.
const INTERPOLATION_SHARE: f64 = 0.1;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompensateOptions {
    pub fit: FitOptions,
    /// Refuse a correction larger than this, mm.
    pub max_shift_mm: f64,
    /// Expand every cycle, not only those whose motion changes.
    pub expand_cycles: bool,
    /// Compensate a profile that a finishing cycle runs in place, keeping the cycles that
    /// share it, rather than expand them (`rewrite::CycleChoice`).
    pub profiles_in_place: bool,
    /// Where a profile is not compensated in place, give its finishing cycle a compensated
    /// copy and leave the roughing on the profile as written (`rewrite::CycleChoice`).
    pub profiles_copied: bool,
    /// Compensate a thread cycle's final pass in its own words rather than expand it.
    pub threads_in_place: bool,
    /// Compensate a single turning or facing cycle's cut in its own words rather than leave
    /// it as written or expand it (`rewrite::CycleChoice`).
    pub singles_in_place: bool,
    /// Leave as written a cycle whose correction neither its words nor a profile can carry,
    /// rather than expand it (`rewrite::CycleChoice`).
    pub others_as_written: bool,
    /// Write every thread pass whose lead error is not uniform along it as thread blocks of
    /// their own leads, not only the passes that shape the finished thread
    /// (`rewrite::thread_pieces`): `--passes` checks every pass.
    pub thread_pieces_every_pass: bool,
    /// Keep every sample's paths in `Outcome::paths` (for `plot`; a long program has
    /// millions of samples).
    pub paths: bool,
    /// Report every edited block (`Report::blocks`, for `--report json`); the totals are
    /// always reported.
    pub block_reports: bool,
}

/// What `compensate` produced.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub edits: Edits,
    /// Errors (refusals: write nothing), warnings and notes, in program order.
    pub diagnostics: Vec<Diagnostic>,
    pub report: Report,
    /// Empty unless `CompensateOptions::paths`.
    pub paths: Paths,
    /// The blocks edited (motion blocks and expanded cycle calls).
    pub edited: Vec<rewrite::EditedBlock>,
    /// What became of each cycle call.
    pub cycles: Vec<rewrite::CycleOutcome>,
    /// The moves left as written (`plan::Judged`).
    pub left_alone: LeftAlone,
}

/// The paths of the compensation, one point per sample, for plotting.
#[derive(Debug, Clone, Default)]
pub struct Paths {
    pub samples: Vec<PathSample>,
    /// Where the model puts the tool for the program as written.
    pub uncompensated: Vec<Xz>,
    /// … and for the compensated program, rounded as written.
    pub compensated: Vec<Xz>,
}

impl Outcome {
    pub fn refused(&self) -> bool {
        self.diagnostics.iter().any(Diagnostic::is_error)
    }
}

/// How closely `compensate` samples a toolpath for `model`: as the model needs for the
/// path between samples to follow its correction within a tenth of the tolerance
/// (`error_model/spacing.rs`), on arcs as closely as the terms that turn with them need and
/// at least every eighth of a turn, and, for `densify` at a fixed step, at a divisor of that
/// step so that its points fall on samples. `reach` is the farthest the path goes from the origin (`LocalPath::reach`).
pub fn sampling(fit: &FitOptions, model: &ErrorModel, reach: Xz) -> Sampling {
    let allowance = fit.tolerance_mm * INTERPOLATION_SHARE;
    let mut spacing = model.spacing(allowance, reach);
    if let Some(step) = fit.step_mm.filter(|s| s.is_finite() && *s > 0.0) {
        spacing.mm = step / (step / spacing.mm).ceil().max(1.0);
    }
    Sampling {
        spacing,
        arc: model.arc_terms(reach),
        allowance,
        max_arc_radians: Sampling::MAX_ARC_RADIANS,
        play: model.play(),
    }
}

/// Compensate `program` (lowered with nose-radius compensation into `lowered`, its
/// toolpath validated) on `machine` with `model`, leaving as written the moves `judged`
/// does not judge (`plan::Judged`).
pub fn compensate_program(
    program: &Program<'_>,
    lowered: &Validated<Lowered>,
    machine: &Machine,
    model: &ErrorModel,
    options: &CompensateOptions,
    judged: Judged<'_>,
) -> Outcome {
    let toolpath = lowered.valid().toolpath();
    let lowered: &Lowered = lowered;
    let tools = ToolTable::from_machine(machine);
    let path = LocalPath::new(toolpath);
    let sampling = sampling(&options.fit, model, path.reach());
    // A move that needs more samples than a piece may hold is refused before any is made,
    // and so are paths to keep (`plot`) of more samples than that in all: they are held at
    // once, as one piece.
    let mut oversampled = oversampled_moves(toolpath, &sampling);
    if options.paths && oversampled.is_empty() {
        oversampled.extend(overlong_paths(toolpath, &sampling));
    }
    if !oversampled.is_empty() {
        return Outcome {
            edits: Edits::new(),
            diagnostics: oversampled,
            report: super::report::build(&ReportInput {
                program,
                runs: &[],
                before: Default::default(),
                after: Default::default(),
                max_correction_mm: 0.0,
                samples: 0,
                plans: &Default::default(),
                edited: &[],
                cycles: &[],
                inverse_iterations: 0,
                inverse_residual_mm: 0.0,
                block_reports: false,
            }),
            paths: Paths::default(),
            edited: Vec::new(),
            cycles: Vec::new(),
            left_alone: LeftAlone::default(),
        };
    }
    // The rewrite's tables: what can be written for each move, the runs of moves each edited
    // block writes, and the rewrite itself, which reads the whole program.
    let mut motion = rewrite::MotionBlocks::new(program, lowered, &tools);
    motion.model = Some(model);
    motion.thread_tolerance_mm = Some(options.fit.tolerance_mm);
    if let Judged::Shaping(clearance) = judged {
        motion.clearance = Some(clearance);
    }
    if options.thread_pieces_every_pass {
        motion.every_thread_pass();
    }
    let (forms, runs) = motion.move_tables();
    let context = stream::Context {
        toolpath,
        tools: &tools,
        lowered,
        model,
        options,
        limits: machine.limits,
        sampling,
        writable: forms.writable,
        radius: forms.radius,
        path,
        plan_options: PlanOptions { fit: options.fit, play: model.play() },
        runs,
        judged,
    };
    let stream::Streamed { plans, mut diagnostics, figures, totals, paths, needs, motion, left_alone } =
        stream::run(&context, motion);
    diagnostics.extend(unwritable_cycles(program, lowered, &needs, &context.writable));
    let choice = rewrite::CycleChoice {
        expand_all: options.expand_cycles,
        profiles_in_place: options.profiles_in_place,
        profiles_copied: options.profiles_copied,
        threads_in_place: options.threads_in_place,
        singles_in_place: options.singles_in_place,
        others_as_written: options.others_as_written,
    };
    let rewritten = rewrite::finish(program, lowered, &plans, choice, motion, model);
    diagnostics.extend(rewritten.diagnostics);
    diagnostics.sort_by_key(|d| d.span.start);
    let report = super::report::build(&ReportInput {
        program,
        runs: &figures,
        before: totals.before,
        after: totals.after,
        max_correction_mm: totals.max_correction_mm,
        samples: totals.samples,
        plans: &plans,
        edited: &rewritten.edited,
        cycles: &rewritten.cycles,
        inverse_iterations: totals.inverse_iterations,
        inverse_residual_mm: totals.inverse_residual_mm,
        block_reports: options.block_reports,
    });
    Outcome {
        edits: rewritten.edits,
        diagnostics,
        report,
        paths,
        edited: rewritten.edited,
        cycles: rewritten.cycles,
        left_alone,
    }
}

/// A warning on each cycle that cannot be written back while its points need a
/// correction larger than the tolerance (`needs`, per move).
fn unwritable_cycles(program: &Program<'_>, lowered: &Lowered, needs: &[bool], writable: &[bool]) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for expansion in &lowered.expansions {
        if writable.get(expansion.moves.start).copied().unwrap_or(true) {
            continue;
        }
        if needs.get(expansion.moves.clone()).is_some_and(|moves| moves.iter().any(|&n| n)) {
            let span = program.block(expansion.block).span;
            let threads =
                lowered.toolpath.moves.get(expansion.moves.clone()).is_some_and(|m| m.iter().any(|m| m.threading));
            let reason = match expansion.kept {
                Some(reason) => reason,
                None if threads => super::rewrite::THREAD_WORDS_NOT_FINAL,
                None => "its moves have no plain-block form in this dialect",
            };
            out.push(Diagnostic::warning(DiagnosticKind::CycleNotCompensated { reason }, span));
        }
    }
    out
}

/// An error on the block whose move takes the samples of the whole path past
/// `MAX_SAMPLES_PER_MOVE`, if one does: the paths `plot` keeps are held whole.
fn overlong_paths(toolpath: &crate::toolpath::Toolpath, sampling: &Sampling) -> Option<Diagnostic> {
    use crate::error_model::sampling::{MAX_SAMPLES_PER_MOVE, samples_needed};
    let needed = |index| samples_needed(toolpath, index, sampling);
    let mut held = 0usize;
    let crossing = (0..toolpath.moves.len()).find(|&index| {
        held = held.saturating_add(needed(index));
        held > MAX_SAMPLES_PER_MOVE
    })?;
    let samples = held.saturating_add((crossing + 1..toolpath.moves.len()).map(needed).sum::<usize>());
    let kind = DiagnosticKind::PathNeedsTooManySamples { samples, max: MAX_SAMPLES_PER_MOVE };
    Some(Diagnostic::error(kind, toolpath.moves[crossing].source))
}

/// The moves that need more than `MAX_SAMPLES_PER_MOVE` samples, one error on each block that
/// makes some (`verify` refuses them too: `verify::oversampled`).
pub(crate) fn oversampled_moves(toolpath: &crate::toolpath::Toolpath, sampling: &Sampling) -> Vec<Diagnostic> {
    let needed = |index| crate::error_model::sampling::samples_needed(toolpath, index, sampling);
    oversampled_of(toolpath.moves.len(), needed, |index| toolpath.moves[index].source)
}

/// `oversampled_moves` of a program held compact.
pub(crate) fn oversampled_compact(
    path: &crate::toolpath::compact::CompactPath,
    sampling: &Sampling,
) -> Vec<Diagnostic> {
    let needed = |index| crate::error_model::sampling::samples_needed_compact(path, index, sampling);
    oversampled_of(path.len(), needed, |index| path.source(index))
}

/// The errors of `oversampled_moves` for `moves` moves, each needing `needed` samples, of
/// the block `source`.
fn oversampled_of(moves: usize, needed: impl Fn(usize) -> usize, source: impl Fn(usize) -> Span) -> Vec<Diagnostic> {
    let mut out: Vec<Diagnostic> = Vec::new();
    for index in 0..moves {
        let samples = needed(index);
        if samples > crate::error_model::sampling::MAX_SAMPLES_PER_MOVE
            && out.last().is_none_or(|d| d.span != source(index))
        {
            let kind = DiagnosticKind::MoveNeedsTooManySamples {
                samples,
                max: crate::error_model::sampling::MAX_SAMPLES_PER_MOVE,
            };
            out.push(Diagnostic::error(kind, source(index)));
        }
    }
    out
}
