//! `turnpass compensate` as one library call: a lowered, validated program and a machine
//! model in, the edits that compensate it (or the reasons to refuse), the report, and the
//! paths `plot` draws, out.
//!
//! sample the nominal path → invert the model (`inverse.rs`) → plan each move's segments
//! (`plan.rs`) → check the corrections (`safety.rs`) → edit the blocks (`rewrite.rs`) →
//! predict the rounded program through the model and report (`quantised.rs`,
//! `report.rs`).

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::error_model::ErrorModel;
use crate::printer::Edits;
use crate::semantic::nose_radius::ToolTable;
use crate::semantic::{Lowered, Machine};
use crate::syntax::Program;
use crate::toolpath::{ValidToolpath, Xz};

use super::deviation::LocalPath;
use super::fit::FitOptions;
use super::grid::Grid;
use super::inverse::{InverseOptions, compensate_samples, predict};
use super::plan::{PlanInput, PlanOptions, plan_moves};
use super::report::{Report, ReportInput};
use super::sampling::{PathSample, sample_toolpath};
use super::{quantised, rewrite, safety, written};

/// Samples along cutting moves at most this far apart, mm: the thesis interpolated its
/// error tables every 0.254 mm (0.01 in).
pub const SAMPLE_STEP_MM: f64 = 0.254;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompensateOptions {
    pub fit: FitOptions,
    /// Refuse a correction larger than this, mm.
    pub max_shift_mm: f64,
    /// Expand every cycle, not only those whose motion changes.
    pub expand_cycles: bool,
}

/// What `compensate` produced.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub edits: Edits,
    /// Errors (refusals: write nothing), warnings and notes, in program order.
    pub diagnostics: Vec<Diagnostic>,
    pub report: Report,
    pub paths: Paths,
    /// The blocks edited (motion blocks and expanded cycle calls).
    pub edited: Vec<rewrite::EditedBlock>,
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

/// The sampling step for `fit`: the thesis' 0.254 mm, or a divisor of the `densify` step so
/// that its points fall on samples.
pub fn sample_step(fit: &FitOptions) -> f64 {
    match fit.step_mm.filter(|s| s.is_finite() && *s > 0.0) {
        Some(step) => step / (step / SAMPLE_STEP_MM).ceil().max(1.0),
        None => SAMPLE_STEP_MM,
    }
}

/// Compensate `program` (lowered with nose-radius compensation into `lowered`, whose
/// toolpath validated as `valid`) on `machine` with `model`.
pub fn compensate_program(
    program: &Program<'_>,
    lowered: &Lowered,
    valid: &ValidToolpath,
    machine: &Machine,
    model: &ErrorModel,
    options: &CompensateOptions,
) -> Outcome {
    let toolpath = valid.toolpath();
    let tools = ToolTable::from_machine(machine);
    let samples = sample_toolpath(toolpath, &tools, sample_step(&options.fit));
    let inverse = InverseOptions { tolerance_mm: options.fit.tolerance_mm, ..InverseOptions::default() };
    let compensated = compensate_samples(&samples, toolpath.start, model, &inverse);
    let ranges = written::sample_ranges(toolpath.moves.len(), &samples);
    let writable = rewrite::writable_moves(program, lowered);
    let grid_of = |index: usize| Grid::new(&lowered.coordinates_at(index));
    let input = PlanInput {
        toolpath,
        samples: &samples,
        commanded: &compensated.commanded,
        ranges: &ranges,
        writable: &writable,
        tools: &tools,
    };
    let plans = plan_moves(&input, grid_of, &PlanOptions { fit: options.fit, play: model.play() });

    let mut diagnostics =
        safety::check(toolpath, &samples, &compensated.commanded, options.max_shift_mm, machine.limits);
    diagnostics.extend(unwritable_cycles(
        program,
        lowered,
        &samples,
        &compensated.commanded,
        &ranges,
        &writable,
        options,
    ));
    let rewritten = rewrite::rewrite(program, lowered, &plans, &tools, options.expand_cycles);
    diagnostics.extend(rewritten.diagnostics);
    diagnostics.sort_by_key(|d| d.span.start);

    let radius_arcs = crate::expand::uses_radius_arcs(program);
    let commanded = quantised::commanded_path(&input, &plans, grid_of, radius_arcs);
    let after = predict(&samples, &commanded, toolpath.start, model);
    let path = LocalPath::new(toolpath);
    let distance =
        |points: &[Xz]| -> Vec<Option<f64>> { samples.iter().zip(points).map(|(s, &p)| path.distance(s, p)).collect() };
    let before_distances = distance(&compensated.uncompensated);
    let after_distances = distance(&after);
    let report = super::report::build(&ReportInput {
        program,
        toolpath,
        samples: &samples,
        ranges: &ranges,
        commanded: &compensated.commanded,
        before: &before_distances,
        after: &after_distances,
        plans: &plans,
        edited: &rewritten.edited,
        inverse_iterations: compensated.iterations,
        inverse_residual_mm: compensated.max_residual_mm,
    });
    Outcome {
        edits: rewritten.edits,
        diagnostics,
        report,
        paths: Paths { samples, uncompensated: compensated.uncompensated, compensated: after },
        edited: rewritten.edited,
    }
}

/// A warning on each cycle that cannot be written back while its points need a
/// correction larger than the tolerance.
fn unwritable_cycles(
    program: &Program<'_>,
    lowered: &Lowered,
    samples: &[PathSample],
    commanded: &[Xz],
    ranges: &[std::ops::Range<usize>],
    writable: &[bool],
    options: &CompensateOptions,
) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for expansion in &lowered.expansions {
        if writable.get(expansion.moves.start).copied().unwrap_or(true) {
            continue;
        }
        let first = ranges.get(expansion.moves.start).map_or(0, |r| r.start);
        let last = expansion.moves.end.checked_sub(1).and_then(|k| ranges.get(k)).map_or(first, |r| r.end);
        let needs = (first..last.max(first)).any(|j| {
            matches!((samples.get(j), commanded.get(j)), (Some(s), Some(c)) if c.distance(s.nominal) > options.fit.tolerance_mm)
        });
        if needs {
            let span = program.block(expansion.block).span;
            out.push(Diagnostic::warning(DiagnosticKind::CycleNotCompensated, span));
        }
    }
    out
}
