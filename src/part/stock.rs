//! The bar a program starts from, in the IR's frame (mm, X as a radius): given by the
//! model file's `[stock]` table or `--stock`, else assumed from the program.

use crate::machine::StockSettings;
use crate::semantic::Machine;
use crate::toolpath::{Motion, Toolpath, Xz};

/// A bar, possibly bored: material between radii `bore` and `outer`, from `back` to `front`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stock {
    pub outer: f64,
    pub bore: f64,
    pub front: f64,
    pub back: f64,
    /// True when no `[stock]` table or `--stock` gave it (see [`Stock::assumed`]).
    pub assumed: bool,
}

impl Stock {
    /// The stock `settings` give, in machine units (diameters), in the IR's frame.
    pub fn from_settings(settings: &StockSettings, machine: &Machine) -> Stock {
        let scale = machine.scale();
        let front = settings.front.unwrap_or(0.0) * scale;
        Stock {
            outer: settings.diameter / 2.0 * scale,
            bore: settings.bore.unwrap_or(0.0) / 2.0 * scale,
            front,
            back: front - settings.length * scale,
            assumed: false,
        }
    }

    /// The smallest solid bar that holds the start of every cutting move (a feed or an arc
    /// that cuts), reaching along Z as far as the cuts do; none for a program that cuts
    /// nothing.
    pub fn assumed(toolpath: &Toolpath) -> Option<Stock> {
        Stock::assumed_from(toolpath.moves.iter().enumerate().filter_map(|(index, m)| {
            let cuts = m.cutting && !matches!(m.motion, Motion::Rapid | Motion::Dwell);
            cuts.then(|| (toolpath.start_of(index), m.end))
        }))
    }

    /// `assumed` from the start and end of each cutting move, in any order (a compact path
    /// gives them as a toolpath does).
    pub fn assumed_from(cuts: impl IntoIterator<Item = (Xz, Xz)>) -> Option<Stock> {
        let (mut outer, mut front, mut back) = (0.0f64, f64::NEG_INFINITY, f64::INFINITY);
        for (start, end) in cuts {
            outer = outer.max(start.x);
            front = front.max(start.z);
            back = back.min(start.z).min(end.z);
        }
        (front.is_finite() && outer > 0.0 && front > back).then_some(Stock {
            outer,
            bore: 0.0,
            front,
            back,
            assumed: true,
        })
    }

    /// Whether `p` lies in the bar.
    pub fn contains(&self, p: Xz) -> bool {
        p.x >= self.bore && p.x <= self.outer && p.z >= self.back && p.z <= self.front
    }
}
