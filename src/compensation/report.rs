//! `compensate --report json`: what was changed, by how much, and what the model predicts.
//!
//! Per edited block: the largest and the RMS correction of its points (|commanded −
//! nominal|), the arcs it now writes (centre and radius, mm, X as a radius), its segments,
//! the predicted residual (the largest distance from the nominal path of the point the
//! model predicts when the rounded, re-expressed block is run) and the SSQ of eq. 5.8
//! (`deviation.rs`) of its cutting points before (the program as it was) and after. The
//! totals cover every cutting point of the program.

use std::ops::Range;

use serde::Serialize;

use crate::source::LineIndex;
use crate::syntax::Program;

use super::deviation::{Figures, Tally, nm};
use super::fit::Segment;
use super::plan::KeptPlans;
use super::rewrite::cycles::LeadChange;
use super::rewrite::{CycleForm, CycleOutcome, EditedBlock};

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    pub blocks: Vec<BlockReport>,
    /// Every cycle call, and what became of it.
    pub cycles: Vec<CycleReport>,
    pub totals: Totals,
}

impl Report {
    /// The report of the program written as it came: no block edited, every cycle kept, the
    /// deviation after as it was before.
    pub fn unchanged(&self) -> Report {
        let cycles = self
            .cycles
            .iter()
            .map(|c| CycleReport {
                outcome: "kept",
                profile_lines: Vec::new(),
                copy: None,
                reason: None,
                lead: None,
                ..c.clone()
            })
            .collect();
        let before = self.totals.before;
        let totals = Totals {
            edited_blocks: 0,
            expanded_cycles: 0,
            profiles_edited: 0,
            profiles_copied: 0,
            max_correction_mm: 0.0,
            after: before,
            improvement_percent: before.improvement_percent(&before),
            ..self.totals
        };
        Report { blocks: Vec::new(), cycles, totals }
    }
}

/// A cycle call: kept as written, kept with its profile compensated in place, or expanded
/// (and why).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CycleReport {
    /// 1-based line of the call block.
    pub line: usize,
    /// The call block as written.
    pub block: String,
    /// `kept`, `profile_edited`, `words_edited` (a thread cycle's final pass),
    /// `profile_copied` (a finishing cycle that runs a compensated copy of its profile),
    /// `roughs_profile_as_written` (the roughing cycle beside it) or `expanded`.
    pub outcome: &'static str,
    /// With `profile_edited`, the 1-based lines of the profile blocks edited in place; with
    /// `profile_copied`, those of the profile copied.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub profile_lines: Vec<usize>,
    /// With `profile_copied`, the sequence names of the copy's first and last blocks, which
    /// its `P` and `Q` name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub copy: Option<[String; 2]>,
    /// With `expanded`, why the call could not stay; with `profile_copied`, why its profile
    /// is not compensated in place.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
    /// With `words_edited`, the thread's lead words where they change: as written, as
    /// written now, and the change of the lead, ppm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lead: Option<LeadChange>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BlockReport {
    /// 1-based line of the block.
    pub line: usize,
    /// A cycle call that was expanded, rather than a motion block.
    pub cycle: bool,
    pub segments: usize,
    pub max_correction_mm: f64,
    pub rms_correction_mm: f64,
    pub arcs: Vec<ArcReport>,
    /// Backlash jumps written as their own moves.
    pub backlash_moves: usize,
    pub predicted_residual_mm: f64,
    pub ssq_before_mm: f64,
    pub ssq_after_mm: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ArcReport {
    /// Centre, mm, X as a radius.
    pub centre_x_mm: f64,
    pub centre_z_mm: f64,
    pub radius_mm: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Totals {
    pub edited_blocks: usize,
    pub expanded_cycles: usize,
    /// Cycle calls kept as written while their profile is compensated in place.
    pub profiles_edited: usize,
    /// Finishing cycle calls that run a compensated copy of their profile.
    pub profiles_copied: usize,
    pub samples: usize,
    pub max_correction_mm: f64,
    /// Iterations of the inverse at the worst sample, and its largest residual, mm.
    pub inverse_iterations: u32,
    pub inverse_residual_mm: f64,
    /// Deviation of the cutting points from the nominal path, as programmed and compensated.
    pub before: Figures,
    pub after: Figures,
    /// `None` where the program as written deviates by nothing (`Figures::improvement_percent`).
    pub improvement_percent: Option<f64>,
}

/// The figures of one run of moves (`rewrite::MotionBlocks::move_tables`: the moves an edited block can
/// write), tallied over its samples in path order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RunFigures {
    pub moves: Range<usize>,
    /// |commanded − nominal| of every sample.
    pub correction: Tally,
    /// Distance from the nominal path of each cutting sample's predicted point, before
    /// (the program as written) and after (the compensated program, rounded as written).
    pub before: Tally,
    pub after: Tally,
}

/// Everything the report is computed from.
pub struct ReportInput<'a> {
    pub program: &'a Program<'a>,
    /// Every run of moves, in path order.
    pub runs: &'a [RunFigures],
    /// The same tallies over the whole program, and its number of samples.
    pub before: Tally,
    pub after: Tally,
    pub max_correction_mm: f64,
    pub samples: usize,
    pub plans: &'a KeptPlans,
    pub edited: &'a [EditedBlock],
    pub cycles: &'a [CycleOutcome],
    pub inverse_iterations: u32,
    pub inverse_residual_mm: f64,
    /// Report every edited block, not only the totals.
    pub block_reports: bool,
}

pub fn build(input: &ReportInput<'_>) -> Report {
    let edited = input.edited;
    let blocks = if input.block_reports {
        // Indexed only here: a 50 MB program has two million lines.
        let lines = LineIndex::new(input.program.source());
        block_reports(input, &lines, edited)
    } else {
        Vec::new()
    };
    let before = input.before.figures();
    let after = input.after.figures();
    let cycles = if input.block_reports { cycle_reports(input) } else { Vec::new() };
    let profiles_edited = input.cycles.iter().filter(|c| matches!(c.form, CycleForm::ProfileEdited { .. })).count();
    Report {
        blocks,
        cycles,
        totals: Totals {
            edited_blocks: input.edited.iter().filter(|e| !e.cycle).count(),
            expanded_cycles: input.cycles.iter().filter(|c| matches!(c.form, CycleForm::Expanded { .. })).count(),
            profiles_edited,
            profiles_copied: input.cycles.iter().filter(|c| matches!(c.form, CycleForm::ProfileCopied { .. })).count(),
            samples: input.samples,
            max_correction_mm: nm(input.max_correction_mm),
            inverse_iterations: input.inverse_iterations,
            inverse_residual_mm: nm(input.inverse_residual_mm),
            before: before.rounded(),
            after: after.rounded(),
            improvement_percent: before.improvement_percent(&after),
        },
    }
}

/// What became of each cycle call, by line.
fn cycle_reports(input: &ReportInput<'_>) -> Vec<CycleReport> {
    let program = input.program;
    let lines = LineIndex::new(program.source());
    let line = |block: usize| lines.position(program.block(block).span.start).0;
    input
        .cycles
        .iter()
        .map(|c| {
            let text = String::from_utf8_lossy(program.text(program.block(c.block).span)).trim_end().to_string();
            let mut copy = None;
            let mut lead = None;
            let (outcome, profile_lines, reason) = match &c.form {
                CycleForm::Kept => ("kept", Vec::new(), None),
                CycleForm::LeftAsWritten => ("left_as_written", Vec::new(), None),
                CycleForm::WordsEdited { lead: change, .. } => {
                    lead.clone_from(change);
                    ("words_edited", Vec::new(), None)
                }
                CycleForm::RoughsOriginal => ("roughs_profile_as_written", Vec::new(), None),
                CycleForm::ProfileEdited { profile, lead: change } => {
                    lead.clone_from(change);
                    ("profile_edited", profile.iter().map(|&b| line(b)).collect(), None)
                }
                CycleForm::ProfileCopied { profile, copy: (first, last), reason } => {
                    copy = Some([first.clone(), last.clone()]);
                    ("profile_copied", profile.iter().map(|&b| line(b)).collect(), Some(reason.clone()))
                }
                CycleForm::Expanded { reason, lead: change } => {
                    lead.clone_from(change);
                    ("expanded", Vec::new(), Some(reason.clone()))
                }
            };
            CycleReport { line: line(c.block), block: text, outcome, profile_lines, copy, reason, lead }
        })
        .collect()
}

/// The reports of `edited`, in order.
fn block_reports(input: &ReportInput<'_>, lines: &LineIndex, edited: &[EditedBlock]) -> Vec<BlockReport> {
    edited
        .iter()
        .map(|edited| {
            let plans = input.plans.get(edited.moves.clone()).unwrap_or(&[]);
            let run = run_figures(input.runs, edited.moves.clone());
            let (correction, before, after) = (run.correction.figures(), run.before.figures(), run.after.figures());
            let arcs = plans
                .iter()
                .flat_map(|p| {
                    let mut from = p.start;
                    p.segments.iter().filter_map(move |s| {
                        let arc = match *s {
                            Segment::Arc { centre, .. } => Some(ArcReport {
                                centre_x_mm: nm(centre.x),
                                centre_z_mm: nm(centre.z),
                                radius_mm: nm(from.distance(centre)),
                            }),
                            Segment::Line { .. } => None,
                        };
                        from = s.end();
                        arc
                    })
                })
                .collect();
            BlockReport {
                line: lines.position(input.program.block(edited.block).span.start).0,
                cycle: edited.cycle,
                // A variable lead's turns are written as the block's one move.
                segments: if edited.one_move { 1 } else { plans.iter().map(|p| p.segments.len()).sum() },
                max_correction_mm: nm(correction.max_mm),
                rms_correction_mm: nm(correction.rms_mm),
                arcs,
                backlash_moves: plans.iter().map(|p| p.jumps).sum(),
                predicted_residual_mm: nm(after.max_mm),
                ssq_before_mm: nm(before.ssq_mm),
                ssq_after_mm: nm(after.ssq_mm),
            }
        })
        .collect()
}

/// The tallies of the moves `moves`: an edited block covers one run exactly; should it
/// cover several, their tallies are merged.
fn run_figures(runs: &[RunFigures], moves: Range<usize>) -> RunFigures {
    if moves.is_empty() {
        return RunFigures { moves, ..RunFigures::default() };
    }
    let first = runs.partition_point(|r| r.moves.end <= moves.start);
    let covered = runs.get(first..).unwrap_or_default().iter().take_while(|r| r.moves.start < moves.end);
    covered.fold(RunFigures { moves: moves.clone(), ..RunFigures::default() }, |acc, r| RunFigures {
        moves: acc.moves,
        correction: acc.correction.merged(r.correction),
        before: acc.before.merged(r.before),
        after: acc.after.merged(r.after),
    })
}
