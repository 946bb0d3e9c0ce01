//! The part: the stock a program starts from, the material each move removes, and the
//! finished part it leaves (issue 24).
//!
//! **The representation** is dexels (`dexel.rs`): rays along Z at evenly spaced radii and
//! along X at evenly spaced Z over the stock's box, each holding its intervals of material.
//! A move subtracts, on every ray it crosses, the exact interval where the ray is inside the
//! region its tool sweeps (`sweep.rs`: a rounded convex polygon for a line, the same polygon
//! moved along an arc for an arc). Every end of an
//! interval is a point of the surface, computed in f64 from the sweep's equations, with the
//! move that made it and the material's outward normal there (`dexel::Edge`). README's
//! "The part" gives the measurements the choice was made on (`cargo bench --bench part`).
//!
//! **The tool** is a nose of the tool table's radius, placed from the IR's reference point
//! by its tip direction, on the insert behind it (`tool.rs`): grooving inserts as wide as
//! their `width`, threading inserts the V of their `angle`, drills a cylinder of their
//! `diameter`. A thread pass stamps its tool's form once per lead along the pass, from where
//! the pass began (each pass starts synchronised to the spindle); the half-section is the
//! one at spindle angle 0.
//!
//! **What it finds** (`run`): a rapid move whose tool meets material (`rapid-into-stock`,
//! with how deep), a cut deeper than the tool's `max_depth` (`cut-too-deep`), and the feed
//! moves that remove nothing (air cutting, in `simulate`'s summary). With an assumed stock
//! (no `[stock]`, no `--stock`) the first two are notes that say so.
//!
//! **Bounded work.** The dexel count is fixed by the stock's box (`removal.rs`), each move
//! visits only the rays of its box, and a run visits at most `removal::MAX_RAY_VISITS` rays:
//! past that it stops with a note on the block where it stopped.

pub mod clearance;
pub(crate) mod dexel;
pub(crate) mod removal;
pub mod stock;
pub mod surface;
pub(crate) mod sweep;
pub mod tool;

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::machine::StockSettings;
use crate::semantic::Machine;
use crate::source::Span;
use crate::toolpath::{Motion, ValidToolpath};

pub use stock::Stock;
pub use surface::Part;

/// Whether and on what stock a run checks the part: `stock` from the model file's `[stock]`
/// or `--stock`, none to assume one.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PartCheck {
    pub stock: Option<StockSettings>,
}

/// What the part model found for a program.
#[derive(Debug, Clone, PartialEq)]
pub struct PartSummary {
    pub stock: Stock,
    /// Feed moves (lines and arcs at the feed) that removed nothing, their time and length.
    pub air_moves: usize,
    pub air_time_s: f64,
    pub air_length_mm: f64,
    /// The move where the model stopped at its bound, if it did.
    pub stopped_at: Option<usize>,
}

/// The part model's run over a program.
#[derive(Debug, Clone)]
pub struct PartRun {
    pub diagnostics: Vec<Diagnostic>,
    /// None for a program that cuts nothing and gives no stock.
    pub summary: Option<PartSummary>,
    pub part: Option<Part>,
}

/// Run the part model over a validated toolpath on `machine` (see the module documentation).
pub fn run(toolpath: ValidToolpath<'_>, machine: &Machine, check: &PartCheck) -> PartRun {
    let toolpath = toolpath.toolpath();
    let stock = match &check.stock {
        Some(settings) => Some(Stock::from_settings(settings, machine)),
        None => Stock::assumed(toolpath),
    };
    let Some(stock) = stock else { return PartRun { diagnostics: Vec::new(), summary: None, part: None } };
    let mut removal = removal::Removal::new(stock, machine, toolpath.moves.len());
    let mut diagnostics = Vec::new();
    let mut summary = PartSummary { stock, air_moves: 0, air_time_s: 0.0, air_length_mm: 0.0, stopped_at: None };
    // The deepest crash and the deepest over-deep cut of the block being run: one diagnostic
    // per block, however many moves it makes (a cycle's call makes hundreds).
    let mut block: Option<(Span, f64, f64, f64)> = None;
    // On an assumed bar the findings are guesses: a feed approach from clearance makes the
    // bar reach out to it, and every rapid near it then "meets" material. They are gathered
    // (the deepest kept, the others counted) and said once for the run, where the deepest is.
    let mut assumed_crashes: Option<(Span, f64, u32)> = None;
    let mut assumed_deep: Option<(Span, f64, f64, u32)> = None;
    let mut flush = |block: Option<(Span, f64, f64, f64)>, diagnostics: &mut Vec<Diagnostic>| {
        let Some((span, crash, deep, max)) = block else { return };
        if crash > 0.0 {
            if stock.assumed {
                let found = assumed_crashes.get_or_insert((span, crash, 0));
                if crash > found.1 {
                    (found.0, found.1) = (span, crash);
                }
                found.2 += 1;
            } else {
                let kind = DiagnosticKind::RapidIntoStock { depth_mm: crash, assumed: None };
                diagnostics.push(Diagnostic::error(kind, span));
            }
        }
        if deep > 0.0 {
            if stock.assumed {
                let found = assumed_deep.get_or_insert((span, deep, max, 0));
                if deep > found.1 {
                    (found.0, found.1, found.2) = (span, deep, max);
                }
                found.3 += 1;
            } else {
                let kind = DiagnosticKind::CutTooDeep { depth_mm: deep, max_mm: max, assumed: None };
                diagnostics.push(Diagnostic::warning(kind, span));
            }
        }
    };
    for (index, m) in toolpath.moves.iter().enumerate() {
        let Some(outcome) = removal.step(toolpath, index) else {
            flush(block.take(), &mut diagnostics);
            diagnostics.push(Diagnostic::note(
                DiagnosticKind::PartModelStopped {
                    rays: removal::MAX_RAY_VISITS,
                    stamps: removal::MAX_STAMPS_PER_MOVE,
                },
                m.source,
            ));
            summary.stopped_at = Some(index);
            break;
        };
        if block.is_some_and(|(span, ..)| span != m.source) {
            flush(block.take(), &mut diagnostics);
        }
        let entry = block.get_or_insert((m.source, 0.0, 0.0, 0.0));
        match m.motion {
            Motion::Rapid => {
                // The pull-out after a thread pass starts in the groove at the spindle angle
                // where the pass ended, which the half-section at angle 0 does not show.
                let pull_out = index > 0 && toolpath.moves[index - 1].threading;
                if outcome.depth > removal::TOUCH && !pull_out {
                    entry.1 = entry.1.max(outcome.depth);
                }
            }
            Motion::Dwell => {}
            Motion::Feed | Motion::Cw | Motion::Ccw => {
                if outcome.met <= removal::TOUCH && outcome.depth <= removal::TOUCH {
                    summary.air_moves += 1;
                    summary.air_time_s += m.t_end - m.t_start;
                    let start = toolpath.start_of(index);
                    summary.air_length_mm += if m.is_arc() {
                        crate::geometry::arc_length(start, m.end, m.centre, m.motion == Motion::Ccw)
                    } else {
                        start.distance(m.end)
                    };
                }
                let max = tool::entry(machine, m.tool, m.offset).and_then(|t| t.max_depth).map(|d| d * machine.scale());
                if let Some(max) = max
                    && !m.threading
                    && outcome.depth > max + removal::TOUCH
                    && outcome.depth > entry.2
                {
                    entry.2 = outcome.depth;
                    entry.3 = max;
                }
            }
        }
    }
    flush(block.take(), &mut diagnostics);
    // A program that ends in a thread pass leaves its form at the pass's end.
    if summary.stopped_at.is_none() && removal.end_thread().is_none() {
        let last = toolpath.moves.len().saturating_sub(1);
        let kind =
            DiagnosticKind::PartModelStopped { rays: removal::MAX_RAY_VISITS, stamps: removal::MAX_STAMPS_PER_MOVE };
        diagnostics.push(Diagnostic::note(kind, toolpath.moves.get(last).map_or(Span::new(0, 0), |m| m.source)));
        summary.stopped_at = Some(last);
    }
    if let Some((span, depth_mm, blocks)) = assumed_crashes {
        let kind = DiagnosticKind::RapidIntoStock { depth_mm, assumed: Some(blocks - 1) };
        diagnostics.push(Diagnostic::note(kind, span));
    }
    if let Some((span, depth_mm, max_mm, blocks)) = assumed_deep {
        let kind = DiagnosticKind::CutTooDeep { depth_mm, max_mm, assumed: Some(blocks - 1) };
        diagnostics.push(Diagnostic::note(kind, span));
    }
    let part = Part::new(removal.dexels, stock);
    PartRun { diagnostics, summary: Some(summary), part: Some(part) }
}

#[cfg(test)]
mod tests;
