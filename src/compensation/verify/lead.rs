//! The lead a thread is cut with on the model. A thread pass runs the slide in step with the
//! spindle: the control advances the command by the programmed lead every turn, so a scale
//! error of the slide is a lead error, which the distance from the nominal path does not
//! see (the predicted points slide along the pass, which is the path itself). Each thread
//! pass is measured here by where the model puts the tool after each whole spindle turn
//! from the pass's start: its advance along the thread's axis after `n` turns against `n`
//! times the lead the original program cuts. The pass's cumulative lead error is the largest
//! of that difference over the whole turns after the first, measured from the helix of the
//! programmed lead placed to fit best (half the spread: a lead gauge's reading over the
//! thread's length, centred): the first turn is the approach in front of the part, where
//! the slide accelerates and takes up its play, and a difference the same at every turn
//! shifts where the thread starts, not its lead.
//!
//! The predicted points are the measure's own (`measure.rs` keeps those on thread moves and
//! the one where a pass starts), interpolated at the whole turns: the sampling follows the
//! model between samples within its allowance. The measured stretch of a pass is its first
//! thread move and the ones after it that go on along its line (a chamfer out of the
//! thread, which turns off it, is not the thread's lead); each move takes the spindle
//! through its length over its own lead, so a pass written as thread blocks of their own
//! leads is measured at its whole turns. The passes of the two programs are paired in order.

use crate::toolpath::Xz;
use crate::toolpath::compact::CompactPath;

/// The points a measure predicted where a lead is measured: on thread moves, and at the end
/// of the move before one (where the pass starts), each with its move and place along it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ThreadPoints {
    points: Vec<(usize, f64, Xz)>,
}

impl ThreadPoints {
    /// Keep the point `predicted` for the sample at `param` of move `index` of `program` where
    /// a lead measure needs it.
    pub fn keep(&mut self, program: &CompactPath, index: usize, param: f64, predicted: Xz) {
        if program.threads().is_empty() {
            return;
        }
        let wanted = program.thread_lead(index).is_some()
            || (param >= 1.0 && index.checked_add(1).and_then(|next| program.thread_lead(next)).is_some());
        if wanted {
            self.points.push((index, param, predicted));
        }
    }
}

/// The lead figures of the thread passes of two programs (`verify`'s).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LeadFigures {
    /// The original's thread passes measured.
    pub passes: usize,
    /// The largest cumulative lead error over a pass's length, mm: the original's own
    /// prediction against its programmed lead, and the compensated program's against the
    /// original's programmed lead.
    pub before_mm: f64,
    pub after_mm: f64,
    /// The compensated program cuts another number of thread passes than the original.
    pub passes_differ: bool,
    /// The first thread move of the original's pass whose compensated pass errs most.
    #[serde(skip)]
    pub worst_move: Option<usize>,
}

/// One pass measured: its first move, and after each whole turn from its start the
/// advance along the axis its moves program and the one predicted (mm, signed).
#[derive(Debug, Clone, PartialEq)]
struct PassLead {
    first_move: usize,
    programmed: Vec<f64>,
    advances: Vec<f64>,
}

/// The lead figures of `original` and `compensated` from the points their measures kept;
/// none where the original cuts no thread.
pub fn figures(
    (original, original_points): (&CompactPath, &ThreadPoints),
    (compensated, compensated_points): (&CompactPath, &ThreadPoints),
) -> Option<LeadFigures> {
    let before = passes(original, original_points);
    if before.is_empty() {
        return None;
    }
    let after = passes(compensated, compensated_points);
    // The axial error over the whole turns after the first, against the helix of the
    // programmed lead placed where it fits best (half the spread): the first turn is the
    // approach, where the slide accelerates and takes up its play in front of the part (a
    // thread cycle starts there), and a constant offset moves where the thread starts, not
    // its lead. Centred, the figure is how far a flank lies along the axis from where the
    // ideal thread puts it, the same kind of figure as the deviation it is bounded with.
    let error = |pass: &PassLead, programmed: &[f64]| {
        let errors = pass.advances.iter().zip(programmed).skip(1).map(|(advance, programmed)| advance - programmed);
        let (low, high) = errors.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), e| (l.min(e), h.max(e)));
        if high >= low { (high - low) / 2.0 } else { 0.0 }
    };
    let before_mm = before.iter().map(|p| error(p, &p.programmed)).fold(0.0, f64::max);
    let mut after_mm = 0.0;
    let mut worst_move = None;
    for (programmed, cut) in before.iter().zip(&after) {
        // Turns the original does not make are not its thread.
        let turns = cut.advances.len().min(programmed.advances.len());
        let cut = PassLead { advances: cut.advances[..turns].to_vec(), ..cut.clone() };
        let e = error(&cut, &programmed.programmed);
        if worst_move.is_none() || e > after_mm {
            (after_mm, worst_move) = (e, Some(programmed.first_move));
        }
    }
    // To the nanometre, as the deviation's figures (`Figures::rounded`).
    let nm = |mm: f64| (mm * 1e6).round() / 1e6;
    Some(LeadFigures {
        passes: before.len(),
        before_mm: nm(before_mm),
        after_mm: nm(after_mm),
        passes_differ: before.len() != after.len(),
        worst_move,
    })
}

/// The passes of `program`, measured from `points` (see the module documentation).
fn passes(program: &CompactPath, points: &ThreadPoints) -> Vec<PassLead> {
    let threads = program.threads();
    let mut out = Vec::new();
    let mut k = 0;
    while k < threads.len() {
        // A pass: consecutive thread moves.
        let mut end = k + 1;
        while threads.get(end).is_some_and(|&(m, _)| m == threads[end - 1].0 + 1) {
            end += 1;
        }
        if let Some(pass) = pass(program, &threads[k..end], &points.points) {
            out.push(pass);
        }
        k = end;
    }
    out
}

/// The lead measure of one pass, its thread moves `moves` (with their leads).
fn pass(program: &CompactPath, moves: &[(usize, f64)], points: &[(usize, f64, Xz)]) -> Option<PassLead> {
    let &(first, lead) = moves.first()?;
    let last = moves.last().map_or(first, |&(m, _)| m);
    // The points are in path order: those of the move before the pass to its last.
    let points = &points[points.partition_point(|p| p.0 + 1 < first)..points.partition_point(|p| p.0 <= last)];
    let (start, end) = (program.start_of(first), program.moves().get(first)?.end);
    let along_z = (end.z - start.z).abs() >= (end.x - start.x).abs();
    let axis = |p: Xz| if along_z { p.z } else { p.x };
    let length = start.distance(end);
    if lead.is_nan() || lead <= 0.0 || length <= 0.0 {
        return None;
    }
    let direction = Xz::new((end.x - start.x) / length, (end.z - start.z) / length);
    // The measured stretch: the first move and those that go on along its line (not a
    // chamfer out of the thread), their lengths and leads. A pass written as consecutive
    // thread blocks of their own leads (`compensation::rewrite::thread_pieces`) goes on along
    // the line to the grid's rounding of its joints.
    let mut stretch: Vec<(usize, f64, f64)> = Vec::new();
    for &(m, lead) in moves {
        let (a, b) = (program.start_of(m), program.moves().get(m)?.end);
        let len = a.distance(b);
        let along = (b.x - a.x) * direction.x + (b.z - a.z) * direction.z;
        let across = (b.x - a.x) * direction.z - (b.z - a.z) * direction.x;
        if len.is_nan()
            || len <= 0.0
            || along <= 0.0
            || across.abs() > ALONG_THE_LINE * len
            || lead.is_nan()
            || lead <= 0.0
        {
            break;
        }
        stretch.push((m, len, lead));
    }
    // The predicted points along the stretch, by the spindle turns from its start: each
    // move's length over its own lead.
    let mut along: Vec<(f64, Xz)> = Vec::new();
    let mut before = 0.0;
    for &(m, len, lead) in &stretch {
        for &(index, param, p) in points {
            if index + 1 == m && param >= 1.0 && along.is_empty() {
                along.push((before, p));
            } else if index == m {
                along.push((before + param * len / lead, p));
            }
        }
        before += len / lead;
    }
    let &(s0, p0) = along.first()?;
    if s0 > 1e-9 {
        // The pass's start was not predicted (it starts the program): not measured.
        return None;
    }
    let turns = (before + 1e-9).floor() as usize;
    // Where the moves put the tool after each whole turn: each move turns the spindle its
    // length over its own lead (a variable lead is one move per turn, `Emitter::varying_thread`).
    let mut programmed = Vec::with_capacity(turns + 1);
    let (mut m, mut turned) = (0, 0.0);
    for n in 0..=turns {
        let s = n as f64;
        while let Some(&(_, len, lead)) = stretch.get(m).filter(|&&(_, len, lead)| turned + len / lead < s - 1e-9) {
            turned += len / lead;
            m += 1;
        }
        let Some(&(index, len, lead)) = stretch.get(m).or(stretch.last()) else { break };
        let (a, b) = (program.start_of(index), program.moves().get(index)?.end);
        let t = (s - turned) * lead / len;
        programmed.push(axis(a) + (axis(b) - axis(a)) * t - axis(start));
    }
    let mut advances = Vec::with_capacity(turns + 1);
    let mut j = 0;
    for n in 0..=turns {
        let s = n as f64;
        while j + 1 < along.len() && along[j + 1].0 < s {
            j += 1;
        }
        let p = match (along.get(j), along.get(j + 1)) {
            (Some(&(sa, a)), Some(&(sb, b))) if sb > sa => {
                let t = ((s - sa) / (sb - sa)).clamp(0.0, 1.0);
                Xz::new(a.x + (b.x - a.x) * t, a.z + (b.z - a.z) * t)
            }
            (Some(&(_, a)), _) => a,
            _ => break,
        };
        advances.push(axis(p) - axis(p0));
    }
    Some(PassLead { first_move: first, programmed, advances })
}

/// How far across the first move's line a thread move after it may run, per length, and
/// still go on along it: the grid's rounding of a joint of thread blocks (half an
/// increment over a piece of a few tenths of a millimetre) is within it, a chamfer out of
/// the thread (tens of degrees) far outside it.
const ALONG_THE_LINE: f64 = 0.01;
