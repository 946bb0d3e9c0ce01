//! Tool nose radius compensation (`G41`/`G42`/`G40`) with imaginary tip directions.
//!
//! Without compensation a lathe program describes the path of the tool's imaginary tip
//! (the reference point). With it, the program describes the part contour, and the control
//! moves the nose centre on a path offset by the nose radius `r` (left of the direction of
//! travel with `G41`, right with `G42`, seen with Z to the right and X up), so the
//! reference point is the nose centre plus `r` times the tip-direction vector:
//!
//! ```txt
//!   X ▲   2  6  1        tip 3 (outside turning toward the chuck): the imaginary tip is
//!     │   7  0  5        below and left of the nose centre, at (−r, −r) in (X, Z);
//!     │   3  8  4        tips 0 and 9 are the nose centre itself.
//!     └──────────▶ Z
//! ```
//!
//! **Runs.** Compensation works on each run of consecutive compensated moves with one side,
//! tool and offset (a tool change or a change of side starts a new run). The first move of
//! a run is the start-up: it ends offset perpendicular to the next element at that
//! element's start (C-type start-up); when the run has no other element, perpendicular to
//! itself at its own end. The last element ends perpendicular to itself at its end, and
//! the `G40` block (or the next run's start-up) leaves from there to its own end. An arc
//! cannot start or end compensation; such a block is made a straight move, with a warning.
//!
//! **Corners** (see [`path`]). Each element is offset to the tool's side: lines stay
//! parallel lines, arcs stay concentric with radius `R ± r`. Where the path turns toward
//! the tool (a concave corner) the two offset elements are cut back to where they cross.
//! Where it turns away from the tool or reverses (a convex corner), the nose rolls round
//! the corner: an arc of radius `r` about the contour corner, turning the way the path
//! turns, from the perpendicular offset point of one element to that of the next. It is
//! a move of its own in the IR, in front of the move it leads into, with that move's block,
//! cycle, tool and spindle, and `contour` the corner itself. Where the offset points
//! coincide (a tangent join) the elements share that point. A nose that cannot follow the
//! contour (a concave arc smaller than the nose, an element the cuts at its corners use
//! up) is an error on the block; the path is still made. (Some controls run a convex
//! corner on extended offsets or extra straight vectors instead of the arc; the nose
//! touches the same contour either way, only its path through the air at the corner
//! differs.)
//!
//! **Times.** A programmed move keeps the time the emitter gave it: the feed is the feed
//! of the cutting point along the contour, which is where the nose touches the part. A
//! corner arc has no contour length (the cutting point stays on the corner), so it takes
//! its own length at the feed of the move it leads into: the F word at the spindle speed
//! of the corner's radius under constant surface speed, or the slower axis' rapid rate
//! before a rapid. Every later move is delayed by the corner arcs before it, so the clock
//! stays continuous. [`apply`] returns the [`MoveMap`] that carries move indices (the
//! cycles' expansions) over the inserted moves.
//!
//! The IR keeps both paths: `end` becomes the reference point, `contour` stays the
//! programmed point.

use std::ops::Range;

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::toolpath::{Compensation, Motion, Move, Toolpath, Xz};

use super::Machine;
use path::Curve;

pub(crate) mod path;

/// Nose radius (mm) and tip direction by turret station and offset number.
#[derive(Debug, Clone, Default)]
pub struct ToolTable {
    entries: Vec<(u16, u16, f64, u8)>,
}

impl ToolTable {
    pub fn from_machine(machine: &Machine) -> ToolTable {
        let scale = machine.scale();
        ToolTable {
            entries: machine
                .tools
                .iter()
                .map(|t| (t.station as u16, t.offset.unwrap_or(t.station) as u16, t.nose_radius * scale, t.tip))
                .collect(),
        }
    }

    /// Nose radius (mm) and tip direction of a tool; nothing for offset 0 or an unknown tool.
    pub fn lookup(&self, station: u16, offset: u16) -> (f64, u8) {
        if offset == 0 {
            return (0.0, 0);
        }
        self.entries
            .iter()
            .find(|e| e.0 == station && e.1 == offset)
            .or_else(|| self.entries.iter().find(|e| e.0 == station))
            .map_or((0.0, 0), |e| (e.2, e.3))
    }
}

/// The imaginary tip's offset from the nose centre, in nose radii.
pub fn tip_vector(tip: u8) -> Xz {
    match tip {
        1 => Xz::new(1.0, 1.0),
        2 => Xz::new(1.0, -1.0),
        3 => Xz::new(-1.0, -1.0),
        4 => Xz::new(-1.0, 1.0),
        5 => Xz::new(0.0, 1.0),
        6 => Xz::new(1.0, 0.0),
        7 => Xz::new(0.0, -1.0),
        8 => Xz::new(-1.0, 0.0),
        _ => Xz::new(0.0, 0.0),
    }
}

/// What compensation needs to know besides the toolpath.
#[derive(Debug, Clone)]
pub struct Setup {
    pub tools: ToolTable,
    /// Rapid traverse rate of each axis, mm/min: a corner arc in front of a rapid runs at
    /// the slower one.
    pub rapid: Xz,
    /// Millimetres per program unit, for the F word of a corner arc.
    pub mm_per_unit: f64,
}

impl Setup {
    /// The machine's tools and rapid rates, and the program's units (the units in effect
    /// when the program ends: programs do not switch units while compensating).
    pub fn new(machine: &Machine, mm_per_unit: f64) -> Setup {
        Setup { tools: ToolTable::from_machine(machine), rapid: machine.rapid, mm_per_unit }
    }
}

/// Where the moves of the uncompensated toolpath went after compensation inserted corner
/// arcs. An inserted move belongs to the move it leads into (it has that move's block and
/// cycle), so a range of moves maps to the range from the first move its first move became
/// up to the first move the move after it became.
#[derive(Debug, Clone, PartialEq)]
pub struct MoveMap {
    /// For each old move, the new index of the first move it became; then the new length.
    /// Empty when nothing was inserted (the common case, kept free of a per-move table).
    first: Vec<usize>,
    /// The number of moves, for the identity map.
    len: usize,
}

impl MoveMap {
    /// Nothing inserted into a toolpath of `len` moves.
    pub fn identity(len: usize) -> MoveMap {
        MoveMap { first: Vec::new(), len }
    }

    /// The new range of the moves an old range held (indices past the end map to the end).
    pub fn range(&self, old: Range<usize>) -> Range<usize> {
        let at = |k: usize| {
            if self.first.is_empty() {
                k.min(self.len)
            } else {
                self.first.get(k).or(self.first.last()).copied().unwrap_or(0)
            }
        };
        let start = at(old.start);
        start..at(old.end).max(start)
    }
}

/// Apply compensation to every run of compensated moves; returns where the moves went.
pub fn apply(toolpath: &mut Toolpath, setup: &Setup, diagnostics: &mut Vec<Diagnostic>) -> MoveMap {
    // Moves to insert, each in front of the (old) index it leads into, in index order.
    let mut inserted: Vec<(usize, Move)> = Vec::new();
    // Whether any dwell needs standing where the tool is, found on the same pass.
    let mut dwells = false;
    let mut i = 0;
    while i < toolpath.moves.len() {
        if toolpath.moves[i].compensation == Compensation::Off {
            dwells |= toolpath.moves[i].motion == Motion::Dwell;
            i += 1;
            continue;
        }
        let run_start = i;
        let first = toolpath.moves[i];
        while i < toolpath.moves.len()
            && toolpath.moves[i].compensation == first.compensation
            && toolpath.moves[i].tool == first.tool
            && toolpath.moves[i].offset == first.offset
        {
            dwells |= toolpath.moves[i].motion == Motion::Dwell;
            i += 1;
        }
        let (radius, tip) = setup.tools.lookup(first.tool, first.offset);
        if radius > 0.0 {
            let run = Run { moves: run_start..i, r: radius, tip, setup };
            run.compensate(toolpath, &mut inserted, diagnostics);
            straighten_cancel_arc(toolpath, i, &setup.tools, diagnostics);
        }
    }
    merge(toolpath, inserted, dwells)
}

/// One run of compensated moves and its tool.
struct Run<'s> {
    moves: Range<usize>,
    r: f64,
    tip: u8,
    setup: &'s Setup,
}

impl Run<'_> {
    /// The reference point of a nose-centre point.
    fn reference(&self, p: Xz) -> Xz {
        let tip = tip_vector(self.tip);
        Xz::new(p.x + tip.x * self.r, p.z + tip.z * self.r)
    }

    fn compensate(
        &self,
        toolpath: &mut Toolpath,
        inserted: &mut Vec<(usize, Move)>,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let side = if toolpath.moves[self.moves.start].compensation == Compensation::Left { 1.0 } else { -1.0 };
        // The contour elements of the run; dwells keep their place and are skipped.
        let geometric: Vec<usize> = self.moves.clone().filter(|&k| toolpath.moves[k].motion != Motion::Dwell).collect();
        let Some((&startup, elements)) = geometric.split_first() else { return };
        let contours: Vec<Curve> = elements.iter().map(|&k| contour_of(toolpath, k)).collect();
        let offsets = path::offset_chain(&contours, self.r, side);

        // The start-up ends where the first real element's path starts, or, with none,
        // perpendicular to itself at its own end.
        let first_real = contours.iter().zip(&offsets).find(|(c, _)| !c.is_null()).map(|(_, o)| o.path.start());
        let startup_end = first_real.unwrap_or_else(|| {
            let own = contour_of(toolpath, startup);
            if own.is_null() { own.end() } else { path::offset(own, self.r, side).0.end() }
        });
        let m = &mut toolpath.moves[startup];
        if m.is_arc() {
            diagnostics.push(Diagnostic::warning(DiagnosticKind::CompensationOnArc { cancel: false }, m.source));
            straighten(m);
        }
        m.end = self.reference(startup_end);

        for ((&k, offset), contour) in elements.iter().zip(&offsets).zip(&contours) {
            if let Some(problem) = offset.problem {
                let kind = DiagnosticKind::NoseDoesNotFit { radius_mm: self.r, reason: problem.reason() };
                diagnostics.push(Diagnostic::error(kind, toolpath.moves[k].source));
            }
            if let Some(lead_in) = offset.lead_in {
                inserted.push((k, self.lead_in_move(&toolpath.moves[k], lead_in, contour.start())));
            }
            // With no real element in the run, null elements stand at the start-up's end.
            let path =
                if first_real.is_none() { Curve::Line { start: startup_end, end: startup_end } } else { offset.path };
            let m = &mut toolpath.moves[k];
            m.end = self.reference(path.end());
            if let Curve::Arc { centre, .. } = path {
                m.centre = self.reference(centre);
            }
        }
    }

    /// The move that joins two elements' paths at a corner (a corner arc, or a straight
    /// link where concave offsets never cross), in front of the move `next` it leads into.
    fn lead_in_move(&self, next: &Move, curve: Curve, corner: Xz) -> Move {
        let rapid = next.motion == Motion::Rapid;
        let (motion, centre) = match curve {
            Curve::Arc { centre, ccw, .. } => (if ccw { Motion::Ccw } else { Motion::Cw }, self.reference(centre)),
            Curve::Line { .. } => (if rapid { Motion::Rapid } else { Motion::Feed }, NAN_POINT),
        };
        let (start, end) = (curve.start(), curve.end());
        let rate = if rapid {
            self.setup.rapid.x.min(self.setup.rapid.z)
        } else {
            // The cutting point stays on the corner: under constant surface speed the
            // spindle turns at the corner's rpm, the rpm `next` starts with.
            let per_unit = next.f_word * self.setup.mm_per_unit;
            if next.per_revolution { per_unit * next.rpm } else { per_unit }
        };
        let seconds = if motion == Motion::Rapid {
            // A rapid link moves each axis at its own rate, as every rapid does.
            let dx = (end.x - start.x).abs() / self.setup.rapid.x.max(1e-9);
            let dz = (end.z - start.z).abs() / self.setup.rapid.z.max(1e-9);
            dx.max(dz) * 60.0
        } else if rate.is_finite() && rate > 0.0 {
            curve.length() / rate * 60.0
        } else {
            0.0
        };
        let feed = if motion == Motion::Rapid || seconds <= 0.0 { 0.0 } else { rate };
        Move {
            motion,
            compensation: next.compensation,
            cutting: next.cutting && !rapid,
            threading: false,
            per_revolution: next.per_revolution,
            tool: next.tool,
            offset: next.offset,
            end: self.reference(end),
            centre,
            contour: corner,
            feed,
            f_word: next.f_word,
            s_word: next.s_word,
            rpm: next.rpm,
            phase: 0.0,
            t_start: 0.0,
            t_end: seconds,
            source: next.source,
            cycle: next.cycle,
        }
    }
}

const NAN_POINT: Xz = Xz::new(f64::NAN, f64::NAN);

/// The programmed contour of move `k`: from the previous move's contour point to its own.
fn contour_of(toolpath: &Toolpath, k: usize) -> Curve {
    let m = &toolpath.moves[k];
    let start = if k == 0 { toolpath.start } else { toolpath.moves[k - 1].contour };
    match m.motion {
        Motion::Cw | Motion::Ccw => {
            Curve::Arc { start, end: m.contour, centre: m.centre, ccw: m.motion == Motion::Ccw }
        }
        _ => Curve::Line { start, end: m.contour },
    }
}

/// An arc that starts or ends compensation becomes a straight move to its end.
fn straighten(m: &mut Move) {
    m.motion = Motion::Feed;
    m.centre = NAN_POINT;
}

/// The move that cancels compensation after a run (its first move that is not a dwell)
/// leaves from an offset point, off its own circle if it is an arc. A move under a tool
/// with no nose radius in the table cancels it as `G40` does.
fn straighten_cancel_arc(
    toolpath: &mut Toolpath,
    after_run: usize,
    tools: &ToolTable,
    diagnostics: &mut Vec<Diagnostic>,
) {
    let next = (after_run..toolpath.moves.len()).find(|&k| toolpath.moves[k].motion != Motion::Dwell);
    let Some(m) = next.map(|k| &mut toolpath.moves[k]) else { return };
    let compensated = m.compensation != Compensation::Off && tools.lookup(m.tool, m.offset).0 > 0.0;
    if m.is_arc() && !compensated {
        diagnostics.push(Diagnostic::warning(DiagnosticKind::CompensationOnArc { cancel: true }, m.source));
        straighten(m);
    }
}

/// Put the inserted moves in place, delay every later move by their time, and stand each
/// dwell (there are some when `dwells`) where the move before it ended.
fn merge(toolpath: &mut Toolpath, inserted: Vec<(usize, Move)>, dwells: bool) -> MoveMap {
    if inserted.is_empty() {
        if dwells {
            stand_dwells(toolpath);
        }
        return MoveMap::identity(toolpath.moves.len());
    }
    let old = std::mem::take(&mut toolpath.moves);
    let mut moves = Vec::with_capacity(old.len() + inserted.len());
    let mut first = Vec::with_capacity(old.len() + 1);
    let mut delay = 0.0;
    let mut pending = inserted.into_iter().peekable();
    for (k, mut m) in old.into_iter().enumerate() {
        first.push(moves.len());
        while let Some((_, mut extra)) = pending.next_if(|(before, _)| *before == k) {
            let seconds = extra.t_end - extra.t_start;
            extra.t_start = m.t_start + delay;
            extra.t_end = extra.t_start + seconds;
            delay += seconds;
            moves.push(extra);
        }
        m.t_start += delay;
        m.t_end += delay;
        moves.push(m);
    }
    first.push(moves.len());
    let len = moves.len();
    toolpath.moves = moves;
    if dwells {
        stand_dwells(toolpath);
    }
    MoveMap { first, len }
}

/// A dwell stands where the tool is: where the move before it ended (an offset point
/// inside or right after a compensated run).
fn stand_dwells(toolpath: &mut Toolpath) {
    for k in 0..toolpath.moves.len() {
        if toolpath.moves[k].motion == Motion::Dwell {
            toolpath.moves[k].end = toolpath.start_of(k);
        }
    }
}

#[cfg(test)]
mod tests;
