//! The material each move removes, in program order: the in-process stock after every move,
//! what each took, and the crashes and deep cuts on the way.

use std::rc::Rc;

use smallvec::SmallVec;

use super::dexel::{Dexels, Edge, STOCK, Span, Spans, Taken};
use super::stock::Stock;
use super::sweep::Sweep;
use super::tool::{self, Orientation, Tool};
use crate::machine::{ToolKind, ToolSettings};
use crate::semantic::Machine;
use crate::toolpath::{Motion, Move, Toolpath, Xz};

/// How many rays the longer side of the stock's box holds: the spacing of the dexels is
/// that side over this (a 300 mm bar: 0.15 mm; a 50 mm part: 0.024 mm).
pub const RAYS_ALONG_LONGER_SIDE: f64 = 2048.0;
/// The finest spacing, mm.
pub const FINEST_SPACING: f64 = 0.001;
/// The ray visits a run is sized for: a program of many moves gets rays far enough apart
/// that its moves, each reaching [`REACH_OF_A_MOVE`] across the rays of both families,
/// visit about this many (a million-move program: rays 0.2 mm apart), so that its check
/// costs about what its simulation does. Programs of up to some 10,000 moves on a 100 mm
/// bar keep the spacing [`RAYS_ALONG_LONGER_SIDE`] gives.
pub const VISITS_PLANNED: f64 = 100_000_000.0;
/// What a move reaches across the rays, mm, for sizing them: its insert's body and nose in
/// both families and a few millimetres of travel.
pub const REACH_OF_A_MOVE: f64 = 20.0;
/// The most ray visits one run makes: past it the model stops with a note, so a hostile
/// program (a runaway of fine thread stamps, a million full-length moves) ends in bounded
/// time.
pub const MAX_RAY_VISITS: u64 = 3_000_000_000;
/// The most forms one threading move stamps: past it (a lead of micrometres over metres) the
/// model stops with a note.
pub const MAX_STAMPS_PER_MOVE: u64 = 100_000;
/// Material thinner than this along a ray (mm) is not a crash or a cut: a tool touching a
/// face it was programmed to touch.
pub const TOUCH: f64 = 0.0005;

/// What one move did to the stock.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Outcome {
    /// Material inside the move's sweep (removed, or for a rapid met), summed along the
    /// rays it crossed, mm.
    pub met: f64,
    /// How deep it went across its direction of travel, mm (see [`Removal::step`]).
    pub depth: f64,
}

/// A thread pass under way: the spindle turns since its first threading move started, the
/// turn of its last stamp, and the insert at the pass's end so far (placed, with the move
/// that put it there) for the stamp the pass leaves at its end. Turns, not length: each
/// move of a pass (each piece of one on the model) runs at its own lead, and the insert is
/// at the section's angle at every whole turn.
struct ThreadPass {
    turns: f64,
    stamped: Option<f64>,
    end: Sweep,
    index: usize,
}

/// The stock as the moves cut it.
pub struct Removal<'a> {
    pub dexels: Dexels,
    pub stock: Stock,
    machine: &'a Machine,
    /// Each tool's shape, made once: a long program steps through millions of moves.
    tools: Vec<((u16, u16, bool), Rc<Tool>)>,
    /// The shape the last move's tool, offset and threading took (one of `tools`): most
    /// moves run with the tool of the move before.
    last_tool: Option<((u16, u16, bool), Rc<Tool>)>,
    /// The thread pass under way (see [`ThreadPass`]).
    thread: Option<ThreadPass>,
    pub visits: u64,
}

impl<'a> Removal<'a> {
    /// The stock cut by the `moves` moves of a program on `machine`.
    pub fn new(stock: Stock, machine: &'a Machine, moves: usize) -> Removal<'a> {
        let size = (stock.outer - stock.bore).max(stock.front - stock.back);
        let spacing =
            (size / RAYS_ALONG_LONGER_SIDE).max(moves as f64 * REACH_OF_A_MOVE / VISITS_PLANNED).max(FINEST_SPACING);
        let lo = Xz::new(stock.bore, stock.back);
        let hi = Xz::new(stock.outer, stock.front);
        let dexels = Dexels::new(lo, hi, spacing, |line| {
            let face = |at: f64, normal: [f32; 2]| Edge { at, normal, by: STOCK };
            let span = if line.along_z {
                Span { lo: face(stock.back, [0.0, -1.0]), hi: face(stock.front, [0.0, 1.0]) }
            } else {
                Span { lo: face(stock.bore, [-1.0, 0.0]), hi: face(stock.outer, [1.0, 0.0]) }
            };
            let mut spans = Spans::new();
            if line.at > if line.along_z { stock.bore } else { stock.back }
                && line.at < if line.along_z { stock.outer } else { stock.front }
            {
                spans.push(span);
            }
            spans
        });
        Removal { dexels, stock, machine, tools: Vec::new(), last_tool: None, thread: None, visits: 0 }
    }

    /// The shape of the tool of move `m` from `start`; a tool whose side the table does not
    /// give takes it from its first cut (`tool::Orientation`).
    pub(super) fn tool(&mut self, m: &Move, start: Xz) -> Rc<Tool> {
        // A tool the table gives without a kind is taken as a threading insert where it cuts
        // a thread pass: each stamp leaves the insert's form, and a turning insert's core
        // (a slot of no width for a tip along an axis and no nose) leaves none.
        let asked = (m.tool, m.offset, m.threading);
        if let Some((_, tool)) = self.last_tool.as_ref().filter(|(k, _)| *k == asked) {
            return Rc::clone(tool);
        }
        let entry = tool::entry(self.machine, m.tool, m.offset);
        let threading = m.threading && entry.is_some_and(|t| t.kind.is_none());
        let key = (m.tool, m.offset, threading);
        if let Some((_, tool)) = self.tools.iter().find(|(k, _)| *k == key) {
            self.last_tool = Some((asked, Rc::clone(tool)));
            return Rc::clone(tool);
        }
        let as_threading = entry.map(|t| ToolSettings { kind: Some(ToolKind::Threading), ..*t });
        let settings = if threading { as_threading.as_ref() } else { entry };
        let reach = self.stock.front - self.stock.back + 10.0;
        let orientation = if Tool::knows_its_side(settings) { Orientation::Outside } else { self.side_of(start) };
        let shape = Rc::new(Tool::new(settings, self.machine, orientation, reach));
        // A rapid before the first cut does not decide an unknown side.
        if m.motion != Motion::Rapid || Tool::knows_its_side(settings) {
            self.tools.push((key, Rc::clone(&shape)));
            self.last_tool = Some((asked, Rc::clone(&shape)));
        }
        shape
    }

    /// Whether a tool at `p` works from outside or from a bore: the nearer free surface
    /// along X at its Z (the axis is none).
    fn side_of(&self, p: Xz) -> Orientation {
        let index = ((p.z - self.dexels.z_lo) / self.dexels.spacing - 0.5).round();
        let Some(spans) = (index >= 0.0).then(|| self.dexels.along_x.get(index as usize)).flatten() else {
            return Orientation::Outside;
        };
        for span in spans {
            if p.x < span.lo.at {
                return if span.lo.at > 0.0 && std::ptr::eq(span, &spans[0]) && p.x >= 0.0 {
                    Orientation::Inside
                } else {
                    Orientation::Outside
                };
            }
            if p.x <= span.hi.at {
                let up = span.hi.at - p.x;
                let down = if span.lo.at <= 1e-9 { f64::INFINITY } else { p.x - span.lo.at };
                return if up <= down { Orientation::Outside } else { Orientation::Inside };
            }
        }
        Orientation::Outside
    }

    /// The sweeps of move `index` (`m`, from `start`) with `tool`.
    /// None when a thread pass would stamp more forms than [`MAX_STAMPS_PER_MOVE`], or more
    /// than the work left.
    fn sweeps(
        &mut self,
        tool: &Tool,
        start: Xz,
        m: &Move,
        index: usize,
        turn: Option<(f64, f64)>,
    ) -> Option<SmallVec<[Sweep; 6]>> {
        let mut out = SmallVec::new();
        let (c0, c1) = (tool.centre(start), tool.centre(m.end));
        if m.threading && m.motion == Motion::Feed {
            let pass = self.thread.take();
            // A pass starts where the spindle stands from its index (`Move::phase`): the
            // section at the index sees a later start's grooves that share of a turn on.
            let turns = pass.as_ref().map_or(m.phase, |p| p.turns);
            let mut stamped = pass.as_ref().and_then(|p| p.stamped);
            if let Some(stamps) = ThreadStamps::along(turns, (c0, c1), start, m, &self.stock) {
                let count = stamps.count;
                if count > 0 {
                    let each = self.dexels.rays_crossed(&Sweep::rounded(tool.placed(stamps.at(0)), tool.nose)).max(1);
                    if count > MAX_STAMPS_PER_MOVE || self.visits + count * each > MAX_RAY_VISITS {
                        return None;
                    }
                    stamped = Some(stamps.first + (count - 1) as f64);
                }
                for k in 0..count {
                    out.push(Sweep::rounded(tool.placed(stamps.at(k)), tool.nose));
                }
                let end = Sweep::rounded(tool.placed(c1), tool.nose);
                self.thread = Some(ThreadPass { turns: stamps.turns_after, stamped, end, index });
                return Some(out);
            }
            // A threading move of no length or no lead turns the spindle through no turn: the
            // pass goes on as it was.
            self.thread = pass.map(|p| ThreadPass { stamped, ..p });
        }
        if let Some(turn) = turn {
            let centre = tool.centre(m.centre);
            let ccw = m.motion == Motion::Ccw;
            out.push(Sweep::body_along_arc(&tool.insert, (c0, c1, centre), ccw, turn));
        } else {
            out.push(Sweep::rounded(tool.placed(c0).chain(tool.placed(c1)), tool.nose));
        }
        Some(out)
    }

    /// Run move `index` of `toolpath`: a rapid only measures what it meets, every other
    /// move removes what it sweeps. `None` once the bound on work is passed.
    pub fn step(&mut self, toolpath: &Toolpath, index: usize) -> Option<Outcome> {
        self.step_move(toolpath.start_of(index), &toolpath.moves[index], index)
    }

    /// [`Removal::step_move`] where only the part left is asked for, not what each move met:
    /// a rapid removes nothing (it only measures, for the crash checks), so it only ends the
    /// thread pass under way. `None` once the bound on work is passed.
    pub fn shape_move(&mut self, start: Xz, m: &Move, index: usize) -> Option<()> {
        if m.motion == Motion::Rapid {
            return self.end_thread();
        }
        self.step_move(start, m, index).map(|_| ())
    }

    /// [`Removal::step`] for the move `m` from `start`, its cuts recorded as move `index`'s
    /// (a piece of a move, cut as the move it is a piece of).
    pub fn step_move(&mut self, start: Xz, m: &Move, index: usize) -> Option<Outcome> {
        if !(m.threading && m.motion == Motion::Feed) {
            self.end_thread()?;
        }
        if m.motion == Motion::Dwell {
            return Some(Outcome::default());
        }
        let tool = self.tool(m, start);
        // An arc's nose centre's angles, for its box and its sweep.
        let turn = m.is_arc().then(|| {
            crate::geometry::turn(
                tool.centre(start),
                tool.centre(m.end),
                tool.centre(m.centre),
                m.motion == Motion::Ccw,
            )
        });
        // Most moves of a long program run in air: a move whose tool's box meets no material
        // does nothing, and its sweeps are not built (a thread pass's count of leads is).
        if !m.threading {
            let (lo, hi) = reach_of_move(&tool, start, m, turn);
            if !self.dexels.may_meet(lo, hi) {
                return Some(Outcome::default());
            }
        }
        let sweeps = self.sweeps(&tool, start, m, index, turn)?;
        let planned: u64 = sweeps.iter().map(|s| self.dexels.rays_crossed(s)).sum();
        if self.visits + planned > MAX_RAY_VISITS {
            return None;
        }
        let remove = m.motion != Motion::Rapid;
        // Across the direction of travel: rays along X measure a move along Z.
        let (dx, dz) = ((m.end.x - start.x).abs(), (m.end.z - start.z).abs());
        let across_family = dz < dx;
        let mut taken = Taken::default();
        // A cut's depth is measured on the rays across it between its nose's two ends.
        let (c0, c1) = (tool.centre(start), tool.centre(m.end));
        let window = if across_family {
            (true, c0.x.min(c1.x), c0.x.max(c1.x))
        } else {
            (false, c0.z.min(c1.z), c0.z.max(c1.z))
        };
        let window = (remove && window.2 > window.1).then_some(window);
        let run = |families: &[bool], taken: &mut Taken, dexels: &mut Dexels| {
            for sweep in &sweeps {
                let t = dexels.sweep_families(sweep, index as u32, remove, families.iter().copied(), window);
                taken.total += t.total;
                taken.along_x = taken.along_x.max(t.along_x);
                taken.along_z = taken.along_z.max(t.along_z);
                taken.rays += t.rays;
            }
        };
        if remove {
            run(&[true, false], &mut taken, &mut self.dexels);
        } else {
            // A rapid only measures; the rays across it are asked first, and those along it
            // only when they met something (or nothing thicker than their spacing).
            run(&[across_family], &mut taken, &mut self.dexels);
            run(&[!across_family], &mut taken, &mut self.dexels);
        }
        self.visits += taken.rays;
        let (across, along) =
            if across_family { (taken.along_z, taken.along_x) } else { (taken.along_x, taken.along_z) };
        // A cut's depth is what it engages across its direction. A rapid goes as deep as the
        // lesser of the two: head-on into a face, the length it travels in; sliding under a
        // diameter, the depth below it.
        let depth = if remove {
            if across > 0.0 { across } else { along }
        } else if across > 0.0 && along > 0.0 {
            across.min(along)
        } else {
            across.max(along)
        };
        Some(Outcome { met: taken.total, depth })
    }
}

impl Removal<'_> {
    /// The spindle turning `turns` times while the tool of the threading move `m` stands at
    /// `at`, its cuts recorded as move `index`'s: the take-up of a drive's play inside a
    /// thread pass, where the control's feed, locked to the spindle, goes on and the slide
    /// has not moved yet. The tool cuts its form all round there, and the pass's later
    /// stamps fall those turns later: the thread's start moves with the play. None once the
    /// bound on work is passed.
    pub fn stand_turning(&mut self, at: Xz, m: &Move, index: usize, turns: f64) -> Option<()> {
        let tool = self.tool(m, at);
        let form = Sweep::rounded(tool.placed(tool.centre(at)), tool.nose);
        self.stamp(&form, index)?;
        let turns = self.thread.as_ref().map_or(m.phase, |p| p.turns) + turns.max(0.0);
        self.thread = Some(ThreadPass { turns, stamped: Some(turns), end: form, index });
        Some(())
    }

    /// End the thread pass under way (before the next move, or when the program ends): a
    /// pass whose last stamp is short of its end stamps the insert's form there too. The
    /// part is a half-section at one spindle angle, where a pass stamps its form every lead;
    /// its groove runs on around the part to where the pass ends, at another angle. Without
    /// the stamp at the end, a pass ending a micrometre short of a whole number of leads
    /// would leave the bar whole where one ending on it cuts the full groove: a part that
    /// jumps by the thread's depth for an end that moved by a micrometre, which no
    /// measurement of the real part sees. With it, the part follows where the pass ends.
    /// None once the bound on work is passed.
    pub fn end_thread(&mut self) -> Option<()> {
        let Some(pass) = self.thread.take() else { return Some(()) };
        let short = pass.stamped.is_none_or(|at| pass.turns - at > 1e-9);
        if !short {
            return Some(());
        }
        self.stamp(&pass.end, pass.index)
    }

    /// Remove what the insert's `form` covers, as move `index`'s cut. None once the bound on
    /// work is passed.
    fn stamp(&mut self, form: &Sweep, index: usize) -> Option<()> {
        let planned = self.dexels.rays_crossed(form);
        if self.visits + planned > MAX_RAY_VISITS {
            return None;
        }
        let taken = self.dexels.sweep_families(form, index as u32, true, [true, false], None);
        self.visits += taken.rays;
        Some(())
    }
}

/// A box that holds everything the tool of move `m` (from `start`) sweeps: its nose centre's
/// path (with an arc's extremes, from its `turn`) grown by the core's extent and the nose.
fn reach_of_move(tool: &Tool, start: Xz, m: &Move, turn: Option<(f64, f64)>) -> (Xz, Xz) {
    let (c0, c1) = (tool.centre(start), tool.centre(m.end));
    let mut lo = Xz::new(c0.x.min(c1.x), c0.z.min(c1.z));
    let mut hi = Xz::new(c0.x.max(c1.x), c0.z.max(c1.z));
    if let Some((a0, total)) = turn {
        let centre = tool.centre(m.centre);
        let ccw = m.motion == Motion::Ccw;
        for p in crate::geometry::arc_extremes_from(centre, c0.distance(centre), a0, total, ccw) {
            lo = Xz::new(lo.x.min(p.x), lo.z.min(p.z));
            hi = Xz::new(hi.x.max(p.x), hi.z.max(p.z));
        }
    }
    let (mut core_lo, mut core_hi) = (Xz::new(0.0, 0.0), Xz::new(0.0, 0.0));
    for p in &tool.core {
        core_lo = Xz::new(core_lo.x.min(p.x), core_lo.z.min(p.z));
        core_hi = Xz::new(core_hi.x.max(p.x), core_hi.z.max(p.z));
    }
    let r = tool.nose;
    (Xz::new(lo.x + core_lo.x - r, lo.z + core_lo.z - r), Xz::new(hi.x + core_hi.x + r, hi.z + core_hi.z + r))
}

/// Where a thread pass's insert stamps its form along one threading move: its nose centre at
/// every whole spindle turn from where the pass began (`stamps`).
pub(super) struct ThreadStamps {
    /// The first stamp's turn from the pass's start, and how many there are.
    pub first: f64,
    pub count: u64,
    /// The turns the pass has made at the move's end.
    pub turns_after: f64,
    turns: f64,
    lead: f64,
    length: f64,
    centres: (Xz, Xz),
}

impl ThreadStamps {
    /// The stamps of the threading move `m` from `start`, the insert's nose centre running
    /// from `centres.0` to `centres.1`, the pass having made `turns` turns before it. None
    /// where the move has no lead or no length: it stamps nothing.
    pub(super) fn along(turns: f64, centres: (Xz, Xz), start: Xz, m: &Move, stock: &Stock) -> Option<ThreadStamps> {
        let length = start.distance(m.end);
        let lead = if m.rpm > 0.0 { m.feed / m.rpm } else { 0.0 };
        if !(lead > 0.0 && lead.is_finite() && length > 0.0) {
            return None;
        }
        let (first, count) = stamps(turns, length, lead, start, m.end, stock);
        Some(ThreadStamps { first, count, turns_after: turns + length / lead, turns, lead, length, centres })
    }

    /// The nose centre at stamp `k`.
    pub(super) fn at(&self, k: u64) -> Xz {
        let (c0, c1) = self.centres;
        let s = (self.first + k as f64 - self.turns) * self.lead;
        Xz::new(c0.x + (c1.x - c0.x) * s / self.length, c0.z + (c1.z - c0.z) * s / self.length)
    }
}

/// Where a thread pass stamps its form along a move: at every whole spindle turn from where
/// the pass began (`turns` before this move), as far as the stock reaches; the first
/// stamp's turn from the pass's start, and how many there are.
fn stamps(turns: f64, length: f64, lead: f64, start: Xz, end: Xz, stock: &Stock) -> (f64, u64) {
    // Only where the stamp can meet the bar (with the insert's reach about it).
    let margin = tool::BODY_MM + (stock.outer - stock.bore);
    let (min, max) = (stock.back - margin, stock.front + margin);
    let (mut lo, mut hi) = (0.0f64, length);
    let d = end.z - start.z;
    if d.abs() < 1e-12 {
        if start.z < min || start.z > max {
            return (0.0, 0);
        }
    } else {
        let (t0, t1) = ((min - start.z) / d * length, (max - start.z) / d * length);
        lo = lo.max(t0.min(t1));
        hi = hi.min(t0.max(t1));
    }
    if hi < lo {
        return (0.0, 0);
    }
    // A stamp at an end of the stretch, to the rounding of the sums, is on it: a pass cut in
    // pieces (verify's predicted path) stamps where it does whole.
    let first = (turns + lo / lead - 1e-9).ceil();
    let last = (turns + hi / lead + 1e-9).floor();
    if !(first.is_finite() && last.is_finite()) || last < first {
        return (0.0, 0);
    }
    (first, (last - first) as u64 + 1)
}
