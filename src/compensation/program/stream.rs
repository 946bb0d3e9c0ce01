//! The program streamed through the compensation in pieces of moves, on four threads.
//!
//! Each piece's samples are made, solved, planned, rounded, predicted and measured, then
//! dropped: memory follows the moves, not the samples (a 50 MB program has millions of
//! samples). The stages that carry state along the path run in path order, each on its
//! own thread, and hand each piece on to the next:
//!
//! 1. **solve**: sample the piece, invert the model (`Inverse`: its tracker and the previous
//!    sample's correction carry over), predict the program as written, and measure that
//!    against the nominal path;
//! 2. **plan**: plan each move (`plan_range`: where the previous written move ends carries
//!    over);
//! 3. **round**: round the plans onto the grid, predict the rounded program, measure it,
//!    check the corrections (`safety::Check`) and tally the figures;
//! 4. **rewrite** (the calling thread): rewrite each motion block's run (`MotionBlocks`)
//!    and keep the plans that are read after the stream.
//!
//! Rounding and rewriting both read only the plans, but each is about as much work as
//! planning, so they are stages of their own rather than one: on two cores the four keep
//! both busy.
//!
//! A piece's samples start with the previous piece's last one (`lead`), which `jumps`
//! compares the first with, so the pieces plan as the whole program would. A piece ends
//! between two runs of moves (`MoveRun`), or inside a cycle's, whose blocks are written
//! only after every move is planned; so every motion block's run lies in one piece.

use std::ops::Range;
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};

use crate::back::grid::Grid;
use crate::diagnostic::Diagnostic;
use crate::error_model::ErrorModel;
use crate::semantic::Lowered;
use crate::semantic::nose_radius::ToolTable;
use crate::toolpath::{Limits, Toolpath, Xz};

use super::super::deviation::{LocalPath, Tally};
use super::super::inverse::{Inverse, InverseOptions, Predictor, time_terms};
use super::super::plan::{Judged, KeptPlans, LeftAlone, MovePlan, PlanInput, PlanOptions, plan_range};
use super::super::report::RunFigures;
use super::super::rewrite::{MotionBlocks, MoveRun};
use super::super::{quantised, safety};
use super::{CompensateOptions, Paths, SAMPLE_STEP_MM};
use crate::error_model::sampling::{PathSample, Sampling, sample_move};

/// Moves per piece (more where a piece would end inside a motion block's run).
const PIECE_MOVES: usize = 2048;

/// Pieces a stage may run ahead of the next.
const QUEUE: usize = 2;

/// What every piece is compensated with.
pub struct Context<'a> {
    pub toolpath: &'a Toolpath,
    pub tools: &'a ToolTable,
    pub lowered: &'a Lowered,
    pub model: &'a ErrorModel,
    pub options: &'a CompensateOptions,
    pub limits: Option<Limits>,
    pub sampling: Sampling,
    /// `rewrite::MoveForms::writable`.
    pub writable: Vec<bool>,
    /// `rewrite::MoveForms::radius`.
    pub radius: Vec<bool>,
    pub path: LocalPath<'a>,
    pub plan_options: PlanOptions,
    /// The runs of moves (`rewrite::MotionBlocks::move_tables`).
    pub runs: Vec<MoveRun>,
    /// `PlanInput::judged`.
    pub judged: Judged<'a>,
}

impl Context<'_> {
    fn grid(&self, index: usize) -> Grid {
        Grid::new(&self.lowered.coordinates_at(index))
    }

    /// What planning and rounding read of a piece (its samples and their ideal commands),
    /// with the sample ranges of its moves.
    fn plan_input<'p>(
        &'p self,
        samples: &'p [PathSample],
        (commanded, take_ups): (&'p [Xz], &'p [Xz]),
        ranges: &'p [Range<usize>],
    ) -> PlanInput<'p> {
        PlanInput {
            toolpath: self.toolpath,
            samples,
            commanded,
            take_ups,
            ranges,
            writable: &self.writable,
            radius: &self.radius,
            tools: self.tools,
            judged: self.judged,
        }
    }
}

/// Program-wide figures, tallied over every sample in path order.
#[derive(Debug, Clone, Copy, Default)]
pub struct Totals {
    pub before: Tally,
    pub after: Tally,
    pub max_correction_mm: f64,
    pub samples: usize,
    pub inverse_iterations: u32,
    pub inverse_residual_mm: f64,
}

/// What streaming leaves: everything the rewrite and the report need, none of the samples
/// (unless `paths` were asked for).
pub struct Streamed<'a, 'src> {
    pub plans: KeptPlans,
    /// The safety checks' refusals.
    pub diagnostics: Vec<Diagnostic>,
    /// One per run of moves, in path order.
    pub figures: Vec<RunFigures>,
    pub totals: Totals,
    pub paths: Paths,
    /// Per move: some sample's correction exceeds the tolerance.
    pub needs: Vec<bool>,
    pub motion: MotionBlocks<'a, 'src>,
    /// The moves left as written (`plan::air`).
    pub left_alone: LeftAlone,
}

/// What the round stage leaves.
struct Measured {
    diagnostics: Vec<Diagnostic>,
    figures: Vec<RunFigures>,
    totals: Totals,
    paths: Paths,
    needs: Vec<bool>,
}

/// One piece's samples and what is computed for them. `samples` and `commanded` (and
/// `rounded`) start with the previous piece's last sample when there is one (`lead`); the
/// other vectors hold only the piece's own samples.
#[derive(Default)]
struct Piece {
    moves: Range<usize>,
    lead: usize,
    samples: Vec<PathSample>,
    /// The samples of each of `moves` (`written::sample_ranges`), as indices into `samples`,
    /// recorded as they are made.
    ranges: Vec<Range<usize>>,
    /// The model's terms of time at each sample (`inverse::time_terms`): evaluated once for
    /// the solve and both predictions.
    time_terms: Vec<Xz>,
    commanded: Vec<Xz>,
    /// `Compensated::take_ups`, beside `commanded`.
    take_ups: Vec<Xz>,
    uncompensated: Vec<Xz>,
    before: Vec<Option<f64>>,
    rounded: Vec<Xz>,
    after: Vec<Xz>,
    plans: Vec<MovePlan>,
}

impl Piece {
    fn clear(&mut self) {
        self.samples.clear();
        self.ranges.clear();
        self.time_terms.clear();
        self.commanded.clear();
        self.take_ups.clear();
        self.uncompensated.clear();
        self.before.clear();
        self.rounded.clear();
        self.after.clear();
        self.plans.clear();
    }

    /// Copy the sample ranges of the piece's moves into `ranges`, which is indexed by move
    /// (as `PlanInput::ranges` is).
    fn spread_ranges(&self, ranges: &mut [Range<usize>]) {
        let slots = ranges.get_mut(self.moves.clone()).unwrap_or_default();
        for (slot, range) in slots.iter_mut().zip(&self.ranges) {
            slot.clone_from(range);
        }
    }

    /// The piece's own samples (after the lead).
    fn fresh(&self) -> Range<usize> {
        self.lead..self.samples.len()
    }
}

/// Stream the whole program (see the module documentation); the rewrite stage rewrites
/// the motion blocks into `motion`.
pub fn run<'a, 'src>(context: &Context<'src>, mut motion: MotionBlocks<'a, 'src>) -> Streamed<'a, 'src> {
    let (to_plan, planning) = sync_channel::<Piece>(QUEUE);
    let (to_round, rounding) = sync_channel::<Piece>(QUEUE);
    let (to_rewrite, rewriting) = sync_channel::<Piece>(QUEUE);
    // Rewritten pieces go back to be filled again.
    let (to_reuse, reusable) = sync_channel::<Piece>(QUEUE * 3 + 2);
    crate::parallel::scope(|scope| {
        let solver = scope.spawn(move || solve(context, &to_plan, &reusable));
        let planner = scope.spawn(move || plan(context, &planning, &to_round));
        let rounder = scope.spawn(move || round(context, &rounding, &to_rewrite));
        let plans = rewrite(context, &mut motion, &rewriting, &to_reuse);
        let (iterations, residual) = solver.join();
        let left_alone = planner.join();
        let Measured { diagnostics, figures, mut totals, paths, needs } = rounder.join();
        totals.inverse_iterations = iterations;
        totals.inverse_residual_mm = residual;
        Streamed { plans, diagnostics, figures, totals, paths, needs, motion, left_alone }
    })
}

/// The pieces: about `PIECE_MOVES` moves each, ending between runs or inside a cycle's.
fn pieces(context: &Context<'_>) -> Vec<Range<usize>> {
    let count = context.toolpath.moves.len();
    let mut out = Vec::new();
    let mut first = 0;
    let mut run = 0;
    while first < count {
        let mut end = (first + PIECE_MOVES).min(count);
        while context.runs.get(run).is_some_and(|r| r.moves.end <= end) {
            run += 1;
        }
        if let Some(r) = context.runs.get(run).filter(|r| !r.cycle && r.moves.start < end) {
            end = r.moves.end;
        }
        out.push(first..end);
        first = end;
    }
    out
}

/// Stage 1: sample, solve, predict as written, measure that.
fn solve(context: &Context<'_>, to_plan: &SyncSender<Piece>, reusable: &Receiver<Piece>) -> (u32, f64) {
    let Context { toolpath, model, options, .. } = *context;
    let tolerance_mm = options.fit.tolerance_mm;
    let dead_band_mm = tolerance_mm.max(context.grid(0).increment_mm() / 2.0);
    let inverse_options = InverseOptions { tolerance_mm, dead_band_mm, ..InverseOptions::default() };
    let mut inverse = Inverse::new(toolpath.start, model, &inverse_options);
    let mut as_written = Predictor::new(toolpath.start, model);
    let mut last: Option<(PathSample, Xz, Xz)> = None;
    for moves in pieces(context) {
        let mut piece = reusable.try_recv().unwrap_or_default();
        piece.clear();
        piece.moves = moves.clone();
        piece.lead = match last {
            Some((sample, commanded, take_up)) => {
                piece.samples.push(sample);
                piece.commanded.push(commanded);
                piece.take_ups.push(take_up);
                1
            }
            None => 0,
        };
        for index in moves {
            let first = piece.samples.len();
            // An arc's angles were measured for the path's measures already.
            let angles = context.path.arc_angles(index);
            sample_move(toolpath, index, context.tools, &context.sampling, angles, &mut piece.samples);
            piece.ranges.push(first..piece.samples.len());
        }
        let fresh = piece.fresh();
        let samples = piece.samples.get(fresh).unwrap_or_default();
        time_terms(samples, model, &mut piece.time_terms);
        // Where the model predicts the commanded points go is not read: the round stage
        // predicts the rounded ones.
        inverse.solve(samples, &piece.time_terms, (&mut piece.commanded, &mut piece.take_ups), None);
        as_written.predict_nominal(samples, &piece.time_terms, &mut piece.uncompensated);
        piece.before.extend(samples.iter().zip(&piece.uncompensated).map(|(s, &p)| context.path.distance(s, p)));
        last = match (piece.samples.last(), piece.commanded.last(), piece.take_ups.last()) {
            (Some(&sample), Some(&commanded), Some(&take_up)) => Some((sample, commanded, take_up)),
            _ => None,
        };
        if to_plan.send(piece).is_err() {
            break;
        }
    }
    (inverse.iterations, inverse.max_residual_mm())
}

/// Stage 2: plan the moves; returns how many were left as written.
fn plan(context: &Context<'_>, planning: &Receiver<Piece>, to_round: &SyncSender<Piece>) -> LeftAlone {
    let toolpath = context.toolpath;
    let mut ranges = vec![0..0; toolpath.moves.len()];
    let mut at = toolpath.start;
    let mut left_alone = LeftAlone::default();
    while let Ok(mut piece) = planning.recv() {
        piece.spread_ranges(&mut ranges);
        let mut plans = std::mem::take(&mut piece.plans);
        let input = context.plan_input(&piece.samples, (&piece.commanded, &piece.take_ups), &ranges);
        let left;
        (at, left) =
            plan_range(&input, piece.moves.clone(), at, |k| context.grid(k), &context.plan_options, &mut plans);
        left_alone += left;
        piece.plans = plans;
        if to_round.send(piece).is_err() {
            break;
        }
    }
    left_alone
}

/// Stage 3: round, predict as rounded, measure, check, tally.
fn round(context: &Context<'_>, rounding: &Receiver<Piece>, to_rewrite: &SyncSender<Piece>) -> Measured {
    let Context { toolpath, model, options, .. } = *context;
    let count = toolpath.moves.len();
    let mut as_rounded = Predictor::new(toolpath.start, model);
    let mut safety = safety::Check::new(options.max_shift_mm, context.limits);
    let mut out = Measured {
        diagnostics: Vec::new(),
        // Each run's figures are read only by the per-block report.
        figures: if options.block_reports {
            context.runs.iter().map(|r| RunFigures { moves: r.moves.clone(), ..RunFigures::default() }).collect()
        } else {
            Vec::new()
        },
        totals: Totals::default(),
        paths: Paths::default(),
        needs: vec![false; count],
    };
    let mut ranges = vec![0..0; count];
    let mut run = 0;
    let mut trail = Trail::default();
    while let Ok(mut piece) = rounding.recv() {
        piece.spread_ranges(&mut ranges);
        piece.rounded.extend(piece.samples.iter().map(|s| s.nominal));
        let grid = |k| context.grid(k);
        let input = context.plan_input(&piece.samples, (&piece.commanded, &piece.take_ups), &ranges);
        quantised::commanded_moves(&input, piece.moves.start, &piece.plans, grid, &mut piece.rounded);
        let fresh = piece.fresh();
        let samples = piece.samples.get(fresh.clone()).unwrap_or_default();
        let rounded = piece.rounded.get(fresh).unwrap_or_default();
        as_rounded.predict(samples, &piece.time_terms, rounded, &mut piece.after);
        measure(context, &piece, &mut safety, &mut out, &mut run, &mut trail);
        if options.paths {
            out.paths.samples.extend_from_slice(samples);
            out.paths.uncompensated.extend_from_slice(&piece.uncompensated);
            out.paths.compensated.extend_from_slice(&piece.after);
        }
        if to_rewrite.send(piece).is_err() {
            break;
        }
    }
    out.diagnostics = safety.finish();
    out
}

/// Stage 4: rewrite the motion blocks of each piece into `motion`; the plans read after
/// the stream (`keep_plans`), one per move.
fn rewrite(
    context: &Context<'_>,
    motion: &mut MotionBlocks<'_, '_>,
    rewriting: &Receiver<Piece>,
    to_reuse: &SyncSender<Piece>,
) -> KeptPlans {
    let mut plans = KeptPlans::default();
    let mut rewritten = 0;
    let mut read_after = cycle_moves(context);
    while let Ok(mut piece) = rewriting.recv() {
        // Every motion block's run that ends in this piece lies in it (`pieces`).
        while let Some(r) = context.runs.get(rewritten).filter(|r| r.moves.end <= piece.moves.end) {
            let first = r.moves.start.max(piece.moves.start) - piece.moves.start;
            let last = r.moves.end - piece.moves.start;
            motion.add(r, piece.plans.get(first..last).unwrap_or_default());
            rewritten += 1;
        }
        // The block after one that leaves a block of modal words behind may carry them, once
        // the stream has passed (`MotionBlocks::fold`): its plans are read then. It comes
        // after the block, in this piece or a later one.
        for next in motion.next_moves_to_keep() {
            if let Some(read) = read_after.as_mut() {
                mark_block_run(context.toolpath, next, read);
            }
        }
        keep_plans(&mut piece.plans, piece.moves.start, read_after.as_deref(), &mut plans);
        // The solver may have finished: then the piece is dropped.
        let _ = to_reuse.try_send(piece);
    }
    plans
}

/// Keep the plans of a piece whose first move is `first` that are read after the stream
/// (`read_after`: a cycle's moves, which are written only when every move is planned, or
/// every move for the per-block report); a motion block's plans were rewritten in the
/// piece, and are dropped with it.
fn keep_plans(plans: &mut Vec<MovePlan>, first: usize, read_after: Option<&[bool]>, kept: &mut KeptPlans) {
    for (index, plan) in (first..).zip(plans.drain(..)) {
        if read_after.is_none_or(|read| read.get(index).copied().unwrap_or(true)) {
            kept.push(index, plan);
        }
    }
}

/// Per move, whether it belongs to a cycle's expansion; `None` when every plan is kept.
fn cycle_moves(context: &Context<'_>) -> Option<Vec<bool>> {
    if context.options.block_reports {
        return None;
    }
    let mut out = vec![false; context.toolpath.moves.len()];
    for expansion in &context.lowered.expansions {
        if let Some(moves) = out.get_mut(expansion.moves.clone()) {
            moves.fill(true);
        }
        // The block after the cycle may carry the modal words its written blocks put back
        // (`MotionBlocks::fold`).
        mark_block_run(context.toolpath, expansion.moves.end, &mut out);
    }
    Some(out)
}

/// Mark in `read` the moves from `first` on that a plain block makes, and where they are
/// all rapids, the next block's, up to one that cuts (an `F` put back goes on past rapids
/// to the block that reads it: `MotionBlocks::fold`).
fn mark_block_run(toolpath: &Toolpath, mut first: usize, read: &mut [bool]) {
    use crate::compensation::rewrite::FOLD_REACH;
    for _ in 0..FOLD_REACH {
        let Some(source) = toolpath.moves.get(first).filter(|m| m.cycle.is_synthetic()).map(|m| m.source) else {
            return;
        };
        let run = toolpath.moves.get(first..).unwrap_or_default();
        let run = &run[..run.iter().take_while(|m| m.source == source && m.cycle.is_synthetic()).count()];
        for read in read.get_mut(first..first + run.len()).unwrap_or_default() {
            *read = true;
        }
        if !run.iter().all(|m| m.motion == crate::toolpath::Motion::Rapid) {
            return;
        }
        first += run.len();
    }
}

/// What was measured at the sample before, for the stretch of path up to the next.
#[derive(Debug, Clone, Copy, Default)]
struct Trail {
    correction: Option<f64>,
    before: Option<f64>,
    after: Option<f64>,
}

/// Tally a piece's own samples into the run figures and the totals, mark the moves whose
/// correction exceeds the tolerance, and check each correction (`safety`, which takes the
/// correction measured here). Each sample stands for the path from the sample before it
/// (`PathSample::covers_mm`, in the thesis' steps): the figures are along the path, the
/// same however closely the model let it be sampled.
fn measure(
    context: &Context<'_>,
    piece: &Piece,
    safety: &mut safety::Check,
    out: &mut Measured,
    run: &mut usize,
    trail: &mut Trail,
) {
    let tolerance = context.options.fit.tolerance_mm;
    let fresh = piece.fresh();
    let samples = piece.samples.get(fresh.clone()).unwrap_or_default();
    let commanded = piece.commanded.get(fresh.clone()).unwrap_or_default();
    let written = piece.rounded.get(fresh).unwrap_or_default();
    let points = samples.iter().zip(commanded).zip(written).zip(&piece.before).zip(&piece.after);
    for ((((s, c), w), &before), &after) in points {
        let weight = s.covers_mm / SAMPLE_STEP_MM;
        let correction = c.distance(s.nominal);
        safety.add(context.toolpath, s, *w, correction);
        let after = context.path.distance(s, after);
        let totals = &mut out.totals;
        totals.samples += 1;
        totals.max_correction_mm = totals.max_correction_mm.max(correction);
        if correction > tolerance
            && let Some(needs) = out.needs.get_mut(s.move_index)
        {
            *needs = true;
        }
        if let Some(d) = before {
            totals.before.add_along(d, trail.before, weight);
        }
        if let Some(d) = after {
            totals.after.add_along(d, trail.after, weight);
        }
        while out.figures.get(*run).is_some_and(|r| r.moves.end <= s.move_index) {
            *run += 1;
        }
        if let Some(figures) = out.figures.get_mut(*run) {
            figures.correction.add_along(correction, trail.correction, weight);
            if let Some(d) = before {
                figures.before.add_along(d, trail.before, weight);
            }
            if let Some(d) = after {
                figures.after.add_along(d, trail.after, weight);
            }
        }
        *trail = Trail { correction: Some(correction), before, after };
    }
}
