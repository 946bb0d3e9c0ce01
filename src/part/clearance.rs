//! Which feed moves keep clear of the finished part: the moves compensation may leave as
//! written (issue 25, "moves that cut no finished surface are left alone").
//!
//! The finished part is the program's toolpath cut from the stock, as the part measure cuts
//! its nominal part (same stock, same rays). A straight feed move keeps clear of it by
//! [`CLEARANCE_MM`] where its whole tool (nose and insert, `tool.rs`), grown by that much
//! and by the rays' spacing, meets no material of the finished part on any ray: the body
//! cuts too, so the nose alone would not say it. Growing by the spacing covers material
//! between two rays: a surface within the clearance of the sweep crosses a ray inside the
//! grown sweep. The test is the finished part against each move, so it does not depend on
//! which move the rays credit with a stretch of surface: a roughing pass that a later pass
//! cuts away stays clear wherever the finishing pass leaves its allowance.
//!
//! Only a tool whose side the tool table gives (its tip direction) is tested: the part model
//! guesses the side of one it does not give from its first cut, and a boring bar taken for
//! a turning tool leaves a finished part where its first pass runs, so that the pass that
//! really finishes the bore would seem clear of it. Arcs are not tested: compensation leaves
//! only straight moves as written (`compensation/plan/air.rs`).
//!
//! A threading move is tested where it cuts: its insert at each stamp of the part model
//! (`removal::ThreadStamps`, every whole spindle turn) and at its end. An infeed pass that
//! the deeper passes after it cut away keeps clear of the finished thread where its form
//! keeps the clearance from the thread's flanks (half its depth short of the final pass's,
//! for a 60° form): compensation writes such a pass of a thread cycle at its diameter as
//! written (`compensation/rewrite.rs`).

use crate::machine::StockSettings;
use crate::semantic::Machine;
use crate::toolpath::{Motion, ValidToolpath};

use super::Stock;
use super::dexel::Dexels;
use super::removal::{MAX_RAY_VISITS, MAX_STAMPS_PER_MOVE, Removal, ThreadStamps};
use super::sweep::Sweep;
use super::tool::Tool;
use crate::toolpath::Xz;

/// How far a feed move's whole tool keeps from the finished part for it to cut no finished
/// surface, mm: more than a model's corrections (micrometres to tens of them) and the
/// allowance a roughing pass is usually left with on the radius no less than this.
pub const CLEARANCE_MM: f64 = 0.1;

/// The straight feed moves of a program that keep [`CLEARANCE_MM`] from its finished part.
#[derive(Debug, Clone)]
pub struct Clearance {
    clear: Vec<bool>,
    finished: Finished,
}

/// The finished part a program cuts as programmed, from `stock` on the rays a program of
/// `moves` moves gets: the nominal part of the part measure, which it takes from here rather
/// than cut it again (`compensation::verify::part`).
#[derive(Debug, Clone)]
pub struct Finished {
    pub(crate) dexels: Dexels,
    pub(crate) stock: Stock,
    pub(crate) moves: usize,
}

impl Clearance {
    /// Whether move `index` keeps clear of the finished part.
    pub fn is_clear(&self, index: usize) -> bool {
        self.clear.get(index).copied().unwrap_or(false)
    }

    /// The finished part the clearance is measured from.
    pub fn finished(&self) -> &Finished {
        &self.finished
    }

    /// The clearance every clear move keeps, mm.
    pub fn by_mm(&self) -> f64 {
        CLEARANCE_MM
    }
}

/// The clearance of `toolpath`'s feed moves from the part it cuts on `machine` from `stock`
/// (none: the bar `Stock::assumed` takes, as the part measure does). `None` where no stock
/// can be assumed or the part model stops at its bound on work.
pub fn clearance(toolpath: ValidToolpath<'_>, machine: &Machine, stock: Option<&StockSettings>) -> Option<Clearance> {
    let toolpath = toolpath.toolpath();
    let stock = match stock {
        Some(settings) => Stock::from_settings(settings, machine),
        None => Stock::assumed(toolpath)?,
    };
    let mut removal = Removal::new(stock, machine, toolpath.moves.len());
    for (index, m) in toolpath.moves.iter().enumerate() {
        removal.shape_move(toolpath.start_of(index), m, index)?;
    }
    removal.end_thread()?;
    let grow = CLEARANCE_MM + removal.dexels.spacing;
    let mut clear = vec![false; toolpath.moves.len()];
    // The spindle turns of the thread pass under way, whose stamps a threading move goes on.
    let mut turns = 0.0;
    for (index, m) in toolpath.moves.iter().enumerate() {
        let threading = m.threading && m.motion == Motion::Feed;
        if !threading {
            turns = 0.0;
        }
        if m.motion != Motion::Feed {
            continue;
        }
        let start = toolpath.start_of(index);
        let tool = removal.tool(m, start);
        let (c0, c1) = (tool.centre(start), tool.centre(m.end));
        if threading {
            let Some(stamps) = ThreadStamps::along(turns, (c0, c1), start, m, &removal.stock) else { continue };
            turns = stamps.turns_after;
            if tool.oriented && stamps.count <= MAX_STAMPS_PER_MOVE {
                // Every stamp, and the insert at the move's end, where the pass may stop.
                let at = (0..stamps.count).map(|k| stamps.at(k)).chain(std::iter::once(c1));
                clear[index] = stamps_clear(&mut removal, &tool, at, grow, index)?;
            }
            continue;
        }
        if !tool.oriented {
            continue;
        }
        let sweep = Sweep::rounded(tool.placed(c0).chain(tool.placed(c1)), tool.nose + grow);
        clear[index] = meets_nothing(&mut removal, &sweep, index)?;
    }
    let finished = Finished { dexels: removal.dexels, stock, moves: toolpath.moves.len() };
    Some(Clearance { clear, finished })
}

/// Whether the insert of `tool` at each nose centre of `at` (a threading move's stamps), grown
/// by `grow`, meets no material of the finished part; None once the bound on work is passed.
fn stamps_clear(
    removal: &mut Removal<'_>,
    tool: &Tool,
    at: impl Iterator<Item = Xz>,
    grow: f64,
    index: usize,
) -> Option<bool> {
    for centre in at {
        let sweep = Sweep::rounded(tool.placed(centre), tool.nose + grow);
        if !meets_nothing(removal, &sweep, index)? {
            return Some(false);
        }
    }
    Some(true)
}

/// Whether `sweep` (of move `index`) meets no material of the finished part; None once the
/// bound on work is passed.
fn meets_nothing(removal: &mut Removal<'_>, sweep: &Sweep, index: usize) -> Option<bool> {
    let (lo, hi) = sweep.bounds();
    if !removal.dexels.may_meet(lo, hi) {
        return Some(true);
    }
    let planned = removal.dexels.rays_crossed(sweep);
    if removal.visits + planned > MAX_RAY_VISITS {
        return None;
    }
    let met = removal.dexels.sweep_families(sweep, index as u32, false, [true, false], None);
    removal.visits += met.rays;
    Some(met.total <= 0.0)
}
