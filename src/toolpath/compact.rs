//! A validated toolpath as the measures read it: each move's geometry, its times and feed,
//! and what its samples carry (the tool and its offset, its tip, the side of the part), with
//! its block beside it, without the contour, the words and the cycle that a `Move` also
//! holds; an arc's centre, radius and angles beside the moves, measured once, and a thread
//! move's spindle speed. A long program's measure, and the part model that cuts its part
//! (`compensation::verify::part`, through [`CompactPath::as_move`]), then hold neither its
//! AST nor its full moves (`compensation::verify`): 64 bytes a move instead of 128.
//!
//! It is made only from a `ValidToolpath`, so what holds of a validated toolpath (finite,
//! arcs on their circle, times running on) holds of it.

use crate::geometry;

use crate::source::Span;

use super::{Compensation, Motion, Move, ValidToolpath, Xz};

/// One move (`CompactPath`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompactMove {
    /// The tool reference point at the end of the move, mm, X as a radius.
    pub end: Xz,
    pub t_start: f64,
    pub t_end: f64,
    /// Feed, mm/min.
    pub feed: f64,
    /// Where the arc's constants are in `CompactPath::arcs` (`NO_ARC`: no arc).
    arc: usize,
    pub tool: u16,
    /// The tool offset number in effect (the part model's insert).
    pub offset: u16,
    pub motion: Motion,
    pub compensation: Compensation,
    pub cutting: bool,
    /// The tool's tip direction code (0–9), from the tool table.
    pub tip: u8,
}

/// `CompactMove::arc` of a move that is no arc.
const NO_ARC: usize = usize::MAX;

impl CompactMove {
    pub fn is_arc(&self) -> bool {
        self.motion.is_arc()
    }

    /// Whether it is part of the cut surface: a cutting move that moves (no dwell).
    pub fn cuts(&self) -> bool {
        self.cutting && self.motion != Motion::Dwell
    }
}

/// An arc's constants, measured once (`geometry::angle`, `geometry::sweep_from`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompactArc {
    pub centre: Xz,
    /// The distance of its start from the centre, mm.
    pub radius: f64,
    /// The angle of its start about the centre, and the angle it sweeps (positive, in its
    /// own sense), radians.
    pub start_angle: f64,
    pub sweep: f64,
}

/// The moves of a validated toolpath, compact (see the module documentation).
#[derive(Debug, Clone, Default)]
pub struct CompactPath {
    /// Where the tool is before the first move.
    pub start: Xz,
    moves: Vec<CompactMove>,
    arcs: Vec<CompactArc>,
    /// The thread moves (`Move::threading`), each with its lead per spindle turn along the
    /// move, mm (its feed over its spindle speed), in move order: the lead measure
    /// (`compensation::verify::lead`) reads them; a program without threads holds none.
    threads: Vec<(usize, f64)>,
    /// Every move with `Move::threading` set, with its spindle speed (rpm) and phase
    /// (`Move::phase`), in move order: the part model cuts a thread's form from them
    /// (`as_move`).
    threading: Vec<(usize, f64, f64)>,
    /// The block each move comes from (`Move::source`).
    sources: Vec<Span>,
    reach: Xz,
}

impl CompactPath {
    /// `toolpath` compact, each move's tip direction code given by `tip` from its tool
    /// station and offset number.
    pub fn new(toolpath: ValidToolpath<'_>, tip: impl Fn(u16, u16) -> u8) -> CompactPath {
        let toolpath = toolpath.toolpath();
        let mut moves = Vec::with_capacity(toolpath.moves.len());
        let mut sources = Vec::with_capacity(toolpath.moves.len());
        let mut arcs = Vec::new();
        let mut threads = Vec::new();
        let mut threading = Vec::new();
        let mut reach = Xz::new(toolpath.start.x.abs(), toolpath.start.z.abs());
        for (k, m) in toolpath.moves.iter().enumerate() {
            let start = toolpath.start_of(k);
            let arc = if m.is_arc() {
                let radius = start.distance(m.centre);
                let start_angle = geometry::angle(start, m.centre);
                let sweep = geometry::sweep_from(start_angle, start, m.end, m.centre, m.motion == Motion::Ccw);
                reach = super::reach_past(reach, m.end, Some((m.centre, radius)));
                arcs.push(CompactArc { centre: m.centre, radius, start_angle, sweep });
                arcs.len() - 1
            } else {
                reach = super::reach_past(reach, m.end, None);
                NO_ARC
            };
            if m.threading && m.motion == Motion::Feed && m.rpm > 0.0 {
                threads.push((k, m.feed / m.rpm));
            }
            if m.threading {
                threading.push((k, m.rpm, m.phase));
            }
            sources.push(m.source);
            moves.push(CompactMove {
                end: m.end,
                t_start: m.t_start,
                t_end: m.t_end,
                feed: m.feed,
                arc,
                tool: m.tool,
                offset: m.offset,
                motion: m.motion,
                compensation: m.compensation,
                cutting: m.cutting,
                tip: tip(m.tool, m.offset),
            });
        }
        CompactPath { start: toolpath.start, moves, arcs, threads, threading, sources, reach }
    }

    /// Move `index` as the part model reads it (`part::removal`): its geometry, times, feed,
    /// tool and offset, thread and spindle speed (a thread move's; 0 for any other move,
    /// whose speed nothing that reads this uses) and block as the toolpath holds them. What
    /// the compact path does not hold reads as no word: the contour point as the end, the F
    /// and S words as NaN, feed per minute, and no cycle.
    pub fn as_move(&self, index: usize) -> Option<Move> {
        let m = self.moves.get(index)?;
        let thread = self.threading.binary_search_by_key(&index, |&(k, ..)| k).ok().map(|k| self.threading[k]);
        let rpm = thread.map(|(_, rpm, _)| rpm);
        Some(Move {
            motion: m.motion,
            compensation: m.compensation,
            cutting: m.cutting,
            threading: rpm.is_some(),
            per_revolution: false,
            tool: m.tool,
            offset: m.offset,
            end: m.end,
            centre: self.centre(index),
            contour: m.end,
            feed: m.feed,
            f_word: f64::NAN,
            s_word: f64::NAN,
            rpm: rpm.unwrap_or(0.0),
            phase: thread.map_or(0.0, |(.., phase)| phase),
            t_start: m.t_start,
            t_end: m.t_end,
            source: self.source(index),
            cycle: Span::SYNTHETIC,
        })
    }

    /// The block move `index` comes from (`Span::SYNTHETIC` past the end).
    pub fn source(&self, index: usize) -> Span {
        self.sources.get(index).copied().unwrap_or(Span::SYNTHETIC)
    }

    pub fn moves(&self) -> &[CompactMove] {
        &self.moves
    }

    pub fn len(&self) -> usize {
        self.moves.len()
    }

    pub fn is_empty(&self) -> bool {
        self.moves.is_empty()
    }

    /// Where move `index` starts.
    pub fn start_of(&self, index: usize) -> Xz {
        match index.checked_sub(1) {
            Some(before) => self.moves.get(before).map_or(self.start, |m| m.end),
            None => self.start,
        }
    }

    /// The thread moves and their leads per turn, mm, in move order.
    pub fn threads(&self) -> &[(usize, f64)] {
        &self.threads
    }

    /// The lead per turn of move `index` when it is a thread move, mm.
    pub fn thread_lead(&self, index: usize) -> Option<f64> {
        let k = self.threads.binary_search_by_key(&index, |&(m, _)| m).ok()?;
        self.threads.get(k).map(|&(_, lead)| lead)
    }

    /// The constants of move `index` when it is an arc.
    pub fn arc(&self, index: usize) -> Option<&CompactArc> {
        self.moves.get(index).and_then(|m| self.arcs.get(m.arc))
    }

    /// The arc's centre of move `index`: NaN for a move that is no arc, as `Move::centre`.
    pub fn centre(&self, index: usize) -> Xz {
        self.arc(index).map_or(Xz::new(f64::NAN, f64::NAN), |arc| arc.centre)
    }

    /// The farthest the path goes from the origin in each axis, mm (X as a radius): an
    /// arc's whole circle counts (`Toolpath::reach`, which it equals).
    pub fn reach(&self) -> Xz {
        self.reach
    }

    /// The length of move `index`, mm (an arc's along it; 0 for a dwell).
    pub fn length(&self, index: usize) -> f64 {
        let Some(m) = self.moves.get(index) else { return 0.0 };
        match (m.motion, self.arc(index)) {
            (Motion::Dwell, _) => 0.0,
            (_, Some(arc)) => arc.radius * arc.sweep,
            (_, None) => self.start_of(index).distance(m.end),
        }
    }
}
