//! A thread pass whose lead error is not uniform along it (a periodic screw error, `cyclic_z`)
//! written as consecutive thread blocks, each with its own lead: continuous thread cutting,
//! where the control keeps the slide synchronised with the spindle from block to block
//! (`continuous` in the dialect's `[thread_lead]`, `grammar/`).
//!
//! The control advances the command by the written lead every spindle turn. Along a piece
//! from command `c₀` to `c₁` written with one lead, the spindle's turn is a straight function
//! of the command; the tool is at `a(c)` along the thread's axis (the command moved by the
//! model). The programmed helix puts the tool `L` further every turn from the pass's nominal
//! start `z₀` (`L` the programmed lead along the axis), so with each piece's lead set for the
//! turns from the pass's start to the piece's end to be `(a(c₁) − z₀)/L`, the tool's helix
//! meets the programmed one at every piece's end (the first piece takes up how far the model
//! puts the tool from `z₀` at the start, in the approach), and between them it departs from
//! it by how far `a` departs from its chord over the piece. That is bounded at samples `h`
//! apart along the command by the
//! largest departure at the samples plus how far `a` departs from the straight line between
//! two samples, at most `c·h²/8` with `c` the model's curvature bound
//! (`ErrorModel::spacing`, which samples the path to `ALLOWANCE_SHARE` of the tolerance):
//! the pieces are cut at samples so that the departure at the samples stays within the rest
//! of the tolerance, each as long as it can be (fewest pieces, greedily). Each lead is
//! written by `back::thread_lead` at the digits that hold it (its rounding runs off by at
//! most half an increment over the piece), and each piece's lead is set from the turns the
//! pieces before it give as written, so that the rounding of one lead does not gather along
//! the thread: the helix holds within the tolerance and half an increment.
//!
//! Only the passes that shape the finished thread get pieces (`finishing_passes`: the last
//! pass of a thread, those at its depth, and those of a flank infeed, one of whose flanks
//! runs on the finished one); the infeed passes straight across the axis before them keep
//! one lead, as a machinist writes them (issue 25, item 2).

use smallvec::SmallVec;

use crate::back::grid::Grid;
use crate::back::thread_lead::{ProgrammedLead, WrittenLead, written_lead};
use crate::dialect::tables::ThreadLead;
use crate::error_model::ErrorModel;
use crate::toolpath::{Motion, Move, Toolpath, Xz};

use super::super::fit::Segment;
use super::super::plan::MovePlan;

/// The share of the tolerance the straight interpolation of the model between two samples
/// may take; the pieces' departure at the samples takes the rest.
const ALLOWANCE_SHARE: f64 = 0.25;

/// The most samples one thread move is cut at: a finer model (a table's step over a long
/// thread) keeps one lead.
const MAX_SAMPLES: usize = 4096;

/// What cutting a pass into pieces needs besides the pass: the model, the tolerance the
/// helix is held to, and which moves are of finishing passes (`finishing_passes`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PieceSettings<'a> {
    pub model: &'a ErrorModel,
    pub tolerance_mm: f64,
    pub finishing: &'a [bool],
}

/// A thread pass written as consecutive thread blocks.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ThreadPieces {
    /// The pass's plan with one line per piece (the ends on the grid but the last, which is
    /// the plan's own end).
    pub plan: MovePlan,
    /// Each piece's lead words.
    pub leads: Vec<WrittenLead>,
}

/// Per move of `toolpath`: whether it is a thread move of a pass that shapes the finished
/// thread. A thread is a run of thread passes (consecutive thread moves) of one tool and one
/// programmed lead with nothing but moves in the air between them. Its last pass shapes it,
/// and so does a pass cut at the same depth (a spring pass) and a pass that starts on
/// another helix than the last (by other than whole leads along the axis): a flank infeed
/// (`G76`'s) shifts each pass along the axis by its depth over the flank's slope, so that one
/// flank of every pass runs on the finished flank. A pass infed straight across the axis
/// (plain `G32` passes from one start) is shallower than the last by its depth of cut, which
/// takes both its flanks that far inside the finished ones.
pub(crate) fn finishing_passes(toolpath: &Toolpath) -> Vec<bool> {
    /// How far two passes' depths or helices may differ and still be the same, mm.
    const SAME_MM: f64 = 1e-6;
    let moves = &toolpath.moves;
    let mut out = vec![false; moves.len()];
    // The passes of the thread under way: (first move, end, depth across the axis, start
    // along it, lead mm).
    let mut thread: Vec<(usize, usize, f64, f64, f64)> = Vec::new();
    let mut key: Option<(u16, u16, f64)> = None;
    let close = |thread: &mut Vec<(usize, usize, f64, f64, f64)>, out: &mut Vec<bool>| {
        if let Some(&(_, _, last_depth, last_start, _)) = thread.last() {
            for &(first, end, depth, start, lead) in thread.iter() {
                let turns = (start - last_start) / lead;
                let other_helix = lead > 0.0 && ((turns - turns.round()) * lead).abs() > SAME_MM;
                if (depth - last_depth).abs() <= SAME_MM || other_helix || lead.is_nan() || lead <= 0.0 {
                    for slot in out.iter_mut().take(end).skip(first) {
                        *slot = true;
                    }
                }
            }
        }
        thread.clear();
    };
    let mut k = 0;
    while k < moves.len() {
        let m = &moves[k];
        if !m.threading {
            if m.cutting && m.motion != Motion::Rapid && m.motion != Motion::Dwell {
                close(&mut thread, &mut out);
                key = None;
            }
            k += 1;
            continue;
        }
        let first = k;
        while moves.get(k).is_some_and(|m| m.threading) {
            k += 1;
        }
        let (from, to) = (toolpath.start_of(first), m.end);
        let along_z = (to.z - from.z).abs() >= (to.x - from.x).abs();
        let (depth, start) = if along_z { (from.x, from.z) } else { (from.z, from.x) };
        let lead = if m.rpm > 0.0 { m.feed / m.rpm } else { f64::NAN };
        let this = (m.tool, m.offset, m.f_word);
        if key != Some(this) {
            close(&mut thread, &mut out);
            key = Some(this);
        }
        thread.push((first, k, depth, start, lead));
    }
    close(&mut thread, &mut out);
    out
}

/// Where the tool goes on `model` when the command is at `at`, `seconds` into the program,
/// on thread move `m` from `from` (its direction and feed; the play, which a pass takes up
/// before it cuts, left out).
pub(super) fn actual_on(model: &ErrorModel, m: &Move, from: Xz, at: Xz, seconds: f64) -> Xz {
    let to = m.end;
    let mut sample = crate::error_model::state::Sample::at_rest(at, model.start_min + seconds / 60.0);
    let sign = |d: f64| if d < 0.0 { -1 } else { 1 };
    sample.direction = crate::error_model::state::Signs { x: sign(to.x - from.x), z: sign(to.z - from.z) };
    let length = from.distance(to);
    if length > 0.0 {
        sample.velocity = Xz::new((to.x - from.x) / length * m.feed, (to.z - from.z) / length * m.feed);
    }
    let d = model.displacement_without_play(&sample);
    Xz::new(at.x + d.x, at.z + d.z)
}

/// The thread move `k` of `toolpath` (planned as `plan`: one line), of a finishing pass,
/// written as consecutive thread blocks where one lead cannot hold the programmed helix
/// within the tolerance on the model (see the module documentation); `None` where one lead
/// holds it, where the move is not of a finishing pass, where the dialect has no continuous
/// thread cutting, or where the pass cannot be cut so (a take-up before it, a move too short
/// or too finely sampled). `programmed`: the lead word of the block, at whose digits the
/// leads are written on `grid`.
pub(crate) fn pieces(
    toolpath: &Toolpath,
    (k, plan): (usize, &MovePlan),
    settings: PieceSettings<'_>,
    table: &ThreadLead,
    grid: &Grid,
    programmed: ProgrammedLead,
) -> Option<ThreadPieces> {
    let PieceSettings { model, tolerance_mm, finishing } = settings;
    let m = toolpath.moves.get(k)?;
    if !finishing.get(k).copied().unwrap_or(false)
        || !table.continuous
        || !m.threading
        || plan.lead_in
        || programmed.count.is_some()
    {
        return None;
    }
    let [Segment::Line { end }] = plan.segments.as_slice() else { return None };
    let end = *end;
    let nominal_from = toolpath.start_of(k);
    let start = grid.round(plan.start);
    let length = start.distance(end);
    let lead_mm = grid.frame.mm(programmed.written);
    if !(length > 0.0 && lead_mm > 0.0 && tolerance_mm > 0.0) {
        return None;
    }
    let along_z = (end.z - start.z).abs() >= (end.x - start.x).abs();
    let axis = |p: Xz| if along_z { p.z } else { p.x };
    let sign = (axis(end) - axis(start)).signum();
    // The programmed lead along the axis, per turn.
    let axial_lead = lead_mm * (axis(m.end) - axis(nominal_from)).abs() / nominal_from.distance(m.end);
    if axial_lead.is_nan() || axial_lead <= 0.0 {
        return None;
    }
    // The samples along the command: on the grid, where a piece may end.
    let allowance = tolerance_mm * ALLOWANCE_SHARE;
    let reach = Xz::new(start.x.abs().max(end.x.abs()), start.z.abs().max(end.z.abs()));
    let spacing = model.spacing(allowance, reach);
    let duration_min = (m.t_end - m.t_start) / 60.0;
    let steps = spacing.steps(length, duration_min);
    if !(2..=MAX_SAMPLES).contains(&steps) {
        // Straight between the ends (one lead is exact), or too fine to cut.
        return None;
    }
    let mut samples: Vec<(Xz, f64)> = Vec::with_capacity(steps + 1);
    for j in 0..=steps {
        let t = j as f64 / steps as f64;
        let c = if j == steps {
            end
        } else {
            grid.round(Xz::new(start.x + (end.x - start.x) * t, start.z + (end.z - start.z) * t))
        };
        if samples.last().is_some_and(|&(p, _)| axis(p) == axis(c)) {
            continue;
        }
        let seconds = m.t_start + (m.t_end - m.t_start) * t;
        samples.push((c, axis(actual_on(model, m, start, c, seconds))));
    }
    // Each piece as long as the departure at its samples stays within the tolerance less the
    // allowance between samples.
    let within = tolerance_mm - allowance;
    // Whether a sample between samples `i` and `j` lies farther than `within` from their chord.
    let departs = |samples: &[(Xz, f64)], i: usize, j: usize| {
        let ((ci, ai), (cj, aj)) = (samples[i], samples[j]);
        let span = axis(cj) - axis(ci);
        samples[i + 1..j].iter().any(|&(c, a)| {
            let chord = ai + (aj - ai) * (axis(c) - axis(ci)) / span;
            (a - chord).abs() > within
        })
    };
    if !departs(&samples, 0, samples.len() - 1) {
        // One lead holds the helix.
        return None;
    }
    // The helix the pieces follow is the programmed one from the pass's nominal start,
    // where the spindle's turn 0 puts the nominal tool: the first piece takes up how far
    // the model puts the tool from it at the start (in the approach, before the part).
    // The samples leave out the play, which the slide sits at the trailing end of as it
    // runs along the thread (slide − command is −play/2 running in +).
    let play = if along_z { model.play().z } else { model.play().x };
    samples[0].1 = axis(nominal_from) + sign * play / 2.0;
    let mut ends = vec![0usize];
    let mut i = 0;
    while i + 1 < samples.len() {
        let mut j = i + 1;
        while j + 1 < samples.len() && !departs(&samples, i, j + 1) {
            j += 1;
        }
        ends.push(j);
        i = j;
    }
    // Each piece's lead: the turns from the thread's start to its end that the programmed
    // helix takes to where the model puts the tool there, less the turns the pieces before
    // it give as written.
    let a0 = samples[0].1;
    let mut turns_written = 0.0;
    let mut leads = Vec::with_capacity(ends.len() - 1);
    let mut segments = SmallVec::with_capacity(ends.len() - 1);
    for pair in ends.windows(2) {
        let ((c0, _), (c1, a1)) = (samples[pair[0]], samples[pair[1]]);
        let piece_mm = c0.distance(c1);
        let turns = sign * (a1 - a0) / axial_lead - turns_written;
        if !(turns > 0.0 && piece_mm > 0.0) {
            return None;
        }
        let exact = programmed.written * (piece_mm / turns) / lead_mm;
        let lead = written_lead(table, grid, programmed, exact, piece_mm)?;
        turns_written += piece_mm / grid.frame.mm(lead.lead);
        leads.push(lead);
        segments.push(Segment::Line { end: c1 });
    }
    let plan = MovePlan {
        start: plan.start,
        segments,
        changed: true,
        jumps: plan.jumps,
        lead_in: false,
        words: SmallVec::new(),
    };
    Some(ThreadPieces { plan, leads })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error_model::effects::{CyclicZ, Effect, ScaleZ, Z};

    const PROGRAM: &str = "G21 G99\nT0303\nG97 S700 M03\nG00 X26. Z6.\nX21.546\nG32 Z-30. F2.\nG00 X26.\nM30\n";

    /// The thread move of `PROGRAM` cut on `model` at the default tolerance (half the
    /// increment), from its nominal start.
    fn cut(model: &ErrorModel) -> (Option<ThreadPieces>, Xz, f64) {
        let ready = crate::compensation::test_support::ready(PROGRAM);
        let lowered: &crate::semantic::Lowered = &ready.lowered;
        let toolpath = &lowered.toolpath;
        let k = toolpath.moves.iter().position(|m| m.threading).unwrap();
        let start = toolpath.start_of(k);
        let plan = MovePlan {
            start,
            segments: smallvec::smallvec![Segment::Line { end: toolpath.moves[k].contour }],
            changed: false,
            jumps: 0,
            lead_in: false,
            words: SmallVec::new(),
        };
        let grid = Grid::new(&lowered.coordinates_at(k));
        let table = ready.program().config().tables().thread_lead;
        let finishing = finishing_passes(toolpath);
        let settings = PieceSettings { model, tolerance_mm: 0.0005, finishing: &finishing };
        let programmed = ProgrammedLead { address: crate::dialect::Address::F, written: 2.0, count: None };
        (pieces(toolpath, (k, &plan), settings, &table, &grid, programmed), start, grid.length_mm(1) / 2.0)
    }

    #[test]
    fn a_periodic_screw_error_is_cut_into_pieces_that_hold_the_helix_within_the_tolerance() {
        let cyclic = CyclicZ { amp: 0.003, pitch: 7.5, phase: 0.5, axis: Z };
        let model = ErrorModel { effects: vec![Effect::CyclicZ(cyclic)], ..ErrorModel::default() };
        let (cut, start, half_increment) = cut(&model);
        let cut = cut.expect("a lead error that changes along the thread is cut into pieces");
        assert!(cut.plan.segments.len() >= 2 && cut.plan.segments.len() == cut.leads.len());
        // Independently of how the pieces were found: walk them at their written leads, and
        // compare where the model puts the tool after each spindle turn with the programmed
        // helix from the nominal start. From the first piece's end on (the first takes up the
        // start's offset, in the approach) it holds within the tolerance and the leads'
        // rounding (half an increment).
        let (mut from, mut turns, mut worst) = (start, 0.0, 0.0f64);
        for (n, (segment, lead)) in cut.plan.segments.iter().zip(&cut.leads).enumerate() {
            let to = segment.end();
            let length = from.distance(to);
            for step in 0..=100 {
                let t = f64::from(step) / 100.0;
                let c = Xz::new(from.x + (to.x - from.x) * t, from.z + (to.z - from.z) * t);
                let actual = c.z + cyclic.amp * (std::f64::consts::TAU * c.z / cyclic.pitch + cyclic.phase).sin();
                let helix = start.z - 2.0 * (turns + length * t / lead.lead);
                if n > 0 {
                    worst = worst.max((actual - helix).abs());
                }
            }
            turns += length / lead.lead;
            from = to;
        }
        assert!(worst <= 0.0005 + half_increment, "the helix departs by {worst} mm");
        // Without pieces the same lead error gathers to micrometres along the thread.
        let uncut = (0..=3600)
            .map(|k| -30.0 + 36.0 * f64::from(k) / 3600.0)
            .map(|z: f64| cyclic.amp * (std::f64::consts::TAU * z / cyclic.pitch + cyclic.phase).sin())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| (lo.min(d), hi.max(d)));
        assert!(uncut.1 - uncut.0 > 0.005, "{uncut:?}");
    }

    #[test]
    fn a_uniform_lead_error_keeps_one_lead() {
        let model =
            ErrorModel { effects: vec![Effect::ScaleZ(ScaleZ { ppm: 100.0, axis: Z })], ..ErrorModel::default() };
        assert_eq!(cut(&model).0, None);
    }

    #[test]
    fn the_infeed_passes_straight_across_the_axis_are_not_finishing_passes() {
        let program = "G21 G99\nT0303\nG97 S700 M03\nG00 X26. Z6.\nX23.\nG32 Z-30. F2.\nG00 X26.\nZ6.\n\
                       X21.546\nG32 Z-30. F2.\nG00 X26.\nZ6.\nX21.546\nG32 Z-30. F2.\nG00 X26.\nM30\n";
        let ready = crate::compensation::test_support::ready(program);
        let toolpath = &ready.lowered.toolpath;
        let threads: Vec<bool> = toolpath
            .moves
            .iter()
            .zip(finishing_passes(toolpath))
            .filter(|(m, _)| m.threading)
            .map(|(_, f)| f)
            .collect();
        // The first pass is shallower; the last and the spring pass at its depth shape the thread.
        assert_eq!(threads, [false, true, true]);
    }
}
