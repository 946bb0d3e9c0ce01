//! The toolpath IR: the moves a lathe really makes.
//!
//! **The frame.** Millimetres; X is a *radius* (distance from the spindle axis), Z runs
//! along the axis; absolute coordinates in the work coordinate system; XZ plane. Units,
//! diameter programming and incremental words are converted at the boundary (the semantic
//! pass reading a program, the expand printer writing one), never inside.
//!
//! **The moves.** A move starts where the previous one ended (the toolpath's `start` for
//! the first), so a move stores only its end. Arcs store their absolute centre. Every move
//! carries its feed in mm/min (feed per revolution and constant surface speed already
//! resolved), the spindle speed, its start and end time, the tool and offset in effect, the
//! nose-radius compensation state, whether it cuts, and the spans of the block it comes from
//! and of the cycle call that produced it.
//!
//! **Two paths.** `end` is the tool's reference point after nose-radius compensation;
//! `contour` is the programmed contour point the move was made for. The error model needs
//! both: the machine moves the reference point, the part takes the contour.
//!
//! **Validation.** [`validate`] checks finite coordinates, arc end points on their circle
//! (within 0.001 mm), non-decreasing time, and the travel limits when the machine gives
//! them. Later passes take a [`ValidToolpath`], which only `validate` can make. It borrows
//! the toolpath it checked rather than owning a copy (a large program's moves are hundreds
//! of MB), so the toolpath cannot change while the proof lives; [`Validated`] keeps the
//! proof with the value that owns the toolpath (the lowered program).

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::source::Span;

pub use crate::geometry::Xz;

pub mod compact;

/// What a move does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Motion {
    /// Positioning at the rapid rate; the axes move independently.
    Rapid,
    /// A straight cut at the feed.
    Feed,
    /// An arc clockwise as seen in the program's G02 sense.
    Cw,
    /// An arc counter-clockwise (G03).
    Ccw,
    /// The tool stands still for a time.
    Dwell,
}

impl Motion {
    pub fn name(self) -> &'static str {
        match self {
            Motion::Rapid => "rapid",
            Motion::Feed => "feed",
            Motion::Cw => "cw",
            Motion::Ccw => "ccw",
            Motion::Dwell => "dwell",
        }
    }

    pub fn is_arc(self) -> bool {
        matches!(self, Motion::Cw | Motion::Ccw)
    }
}

/// Tool nose radius compensation state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Compensation {
    Off,
    /// G41: the tool is left of the path.
    Left,
    /// G42: the tool is right of the path.
    Right,
}

/// One move. See the module documentation for the frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Move {
    pub motion: Motion,
    pub compensation: Compensation,
    /// Part of a cutting pass (a feed or arc inside a cycle's cut, or any programmed feed).
    pub cutting: bool,
    /// Feed synchronised with the spindle (thread cutting).
    pub threading: bool,
    /// `f_word` is per revolution (`G99`/`G95`) rather than per minute.
    pub per_revolution: bool,
    /// Turret station and offset number in effect.
    pub tool: u16,
    pub offset: u16,
    /// The tool reference point at the end of the move.
    pub end: Xz,
    /// The arc centre (arcs only; NaN otherwise).
    pub centre: Xz,
    /// The programmed contour point the move ends at.
    pub contour: Xz,
    /// Feed, mm/min (0 for rapids and dwells).
    pub feed: f64,
    /// The F and S words in effect as the program writes them (program units; per
    /// revolution or per minute, rpm or surface speed), for printing the move back.
    pub f_word: f64,
    pub s_word: f64,
    /// Spindle speed, rpm.
    pub rpm: f64,
    /// Where the spindle stands, in turns from its index, as a thread pass starts: the start
    /// of a multi-start thread its pass cuts (OSP `Q` starts or `C`, Fanuc `G92 Q`); 0 for
    /// one start and for every move that does not thread.
    pub phase: f64,
    pub t_start: f64,
    pub t_end: f64,
    /// The block the move comes from; for a cycle, its call block.
    pub source: Span,
    /// The cycle call block that produced the move, or `Span::SYNTHETIC`.
    pub cycle: Span,
}

impl Move {
    pub fn is_arc(&self) -> bool {
        self.motion.is_arc()
    }
}

/// The moves of a program, from `start`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Toolpath {
    /// Where the tool is before the first move.
    pub start: Xz,
    pub moves: Vec<Move>,
}

impl Toolpath {
    /// Where move `index` starts.
    pub fn start_of(&self, index: usize) -> Xz {
        if index == 0 { self.start } else { self.moves[index - 1].end }
    }

    pub fn duration(&self) -> f64 {
        self.moves.last().map_or(0.0, |m| m.t_end)
    }

    /// The farthest the path goes from the origin in each axis, mm (X as a radius): an arc's
    /// whole circle counts, which bounds it without finding its extremes (`reach_past`).
    pub fn reach(&self) -> Xz {
        let start = Xz::new(self.start.x.abs(), self.start.z.abs());
        self.moves.iter().enumerate().fold(start, |reach, (k, m)| {
            let arc = m.is_arc().then(|| (m.centre, self.start_of(k).distance(m.centre)));
            reach_past(reach, m.end, arc)
        })
    }
}

/// `reach` (the farthest a path goes from the origin in each axis) with a move ending at
/// `end` added; an arc, about its centre with its radius (`arc`), counts its whole circle.
pub fn reach_past(reach: Xz, end: Xz, arc: Option<(Xz, f64)>) -> Xz {
    match arc {
        Some((centre, radius)) => Xz::new(reach.x.max(centre.x.abs() + radius), reach.z.max(centre.z.abs() + radius)),
        None => Xz::new(reach.x.max(end.x.abs()), reach.z.max(end.z.abs())),
    }
}

/// Travel limits of the tool reference point in the toolpath frame (X radius, mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    pub x_min: f64,
    pub x_max: f64,
    pub z_min: f64,
    pub z_max: f64,
}

impl Limits {
    fn contains(&self, p: Xz) -> bool {
        // A micrometre of slack keeps rounding at a limit from reading as a violation.
        const SLACK: f64 = 0.001;
        p.x >= self.x_min - SLACK && p.x <= self.x_max + SLACK && p.z >= self.z_min - SLACK && p.z <= self.z_max + SLACK
    }
}

/// A toolpath that passed [`validate`], borrowed: while the proof lives the toolpath cannot
/// change. Only `validate` (and [`Validated::valid`], which holds its result) makes one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ValidToolpath<'a>(&'a Toolpath);

impl<'a> ValidToolpath<'a> {
    pub fn toolpath(self) -> &'a Toolpath {
        self.0
    }
}

impl std::ops::Deref for ValidToolpath<'_> {
    type Target = Toolpath;
    fn deref(&self) -> &Toolpath {
        self.0
    }
}

/// A value that owns a toolpath (the lowered program, or a toolpath itself) whose toolpath
/// passed [`validate`]. It gives only shared access to the value, so the toolpath stays the
/// one that was checked, and [`Validated::valid`] hands out the proof without checking again.
#[derive(Debug, Clone, PartialEq)]
pub struct Validated<T>(T);

impl<T: AsRef<Toolpath>> Validated<T> {
    /// Validate the toolpath `owner` holds; on failure, the owner comes back with the problems.
    pub fn new(owner: T, limits: Option<Limits>) -> Result<Validated<T>, (T, Vec<Diagnostic>)> {
        match validate(owner.as_ref(), limits) {
            Ok(_) => Ok(Validated(owner)),
            Err(problems) => Err((owner, problems)),
        }
    }

    pub fn valid(&self) -> ValidToolpath<'_> {
        ValidToolpath(self.0.as_ref())
    }

    pub fn into_inner(self) -> T {
        self.0
    }
}

impl<T> std::ops::Deref for Validated<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.0
    }
}

impl AsRef<Toolpath> for Toolpath {
    fn as_ref(&self) -> &Toolpath {
        self
    }
}

/// Arc end points must lie on their circle within this distance, mm.
pub const ARC_TOLERANCE: f64 = 0.001;

/// Check the IR's invariants. Returns the proof that the toolpath is valid, or the problems
/// found (each on the source block of the offending move).
pub fn validate(toolpath: &Toolpath, limits: Option<Limits>) -> Result<ValidToolpath<'_>, Vec<Diagnostic>> {
    let problems = check_moves(toolpath, limits);
    if problems.is_empty() { Ok(ValidToolpath(toolpath)) } else { Err(problems) }
}

/// The problems of the moves, in order.
fn check_moves(toolpath: &Toolpath, limits: Option<Limits>) -> Vec<Diagnostic> {
    let mut problems = Vec::new();
    let mut merge_at = 4096;
    // The time of the last move whose time was checked: a move with non-finite values is
    // reported as such and does not count.
    let mut previous_time = 0.0;
    for (index, m) in toolpath.moves.iter().enumerate() {
        let start = toolpath.start_of(index);
        let span = m.source;
        if non_finite(m) {
            problems.push(Diagnostic::error(DiagnosticKind::NonFiniteMove, span));
            continue;
        }
        if m.is_arc() {
            let r_start = start.distance(m.centre);
            let r_end = m.end.distance(m.centre);
            if !m.centre.is_finite() || (r_start - r_end).abs() > ARC_TOLERANCE {
                problems.push(Diagnostic::error(
                    DiagnosticKind::ArcEndOffCircle { start_radius: r_start, end_radius: r_end },
                    span,
                ));
            }
        }
        if m.t_start + 1e-9 < previous_time || m.t_end + 1e-9 < m.t_start {
            problems.push(Diagnostic::error(DiagnosticKind::TimeGoesBack, span));
        }
        previous_time = m.t_end;
        if let Some(limits) = limits
            && let Some(outside) = first_point_outside(start, m, &limits)
        {
            problems.push(Diagnostic::error(DiagnosticKind::OutsideTravel { x_mm: outside.x, z_mm: outside.z }, span));
        }
        // The moves of a block run many times repeat its problems: merged as they pile up.
        if problems.len() >= merge_at {
            crate::diagnostic::merge_repeats(&mut problems);
            merge_at = 2 * problems.len() + 4096;
        }
    }
    crate::diagnostic::merge_repeats(&mut problems);
    problems
}

/// Whether a move has a coordinate, time or feed that is not a finite number.
fn non_finite(m: &Move) -> bool {
    !m.end.is_finite() || !m.contour.is_finite() || !m.t_end.is_finite() || !m.feed.is_finite()
}

/// The end point, or for an arc the extreme point of its sweep, that leaves the limits.
fn first_point_outside(start: Xz, m: &Move, limits: &Limits) -> Option<Xz> {
    if !limits.contains(m.end) {
        return Some(m.end);
    }
    if m.is_arc() {
        for extreme in crate::geometry::arc_extremes(start, m.end, m.centre, m.motion == Motion::Ccw) {
            if !limits.contains(extreme) {
                return Some(extreme);
            }
        }
    }
    None
}

#[cfg(test)]
mod tests;
