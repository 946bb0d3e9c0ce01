//! Emitting IR moves with their timing.
//!
//! Everything that moves the tool (plain blocks and canned cycles alike) goes through
//! [`Emitter`], which resolves the feed to mm/min and advances the clock:
//!
//! - rapids: each axis at its own rapid rate, not interpolated, so the slower axis decides;
//! - feed per minute: length over feed;
//! - feed per revolution at fixed rpm: length over `f × rpm`;
//! - feed per revolution under constant surface speed: the spindle speed changes with the
//!   radius, `rpm = v / (2π r)` up to the clamp. A straight move's time is integrated in
//!   closed form (the integrand is linear in r where the clamp is not reached); an arc's by
//!   Simpson's rule.
//!
//! A long program's arcs are timed on a second thread while the interpreter runs on
//! (`arc_times.rs`): their sines and arctangents were a third of the lowering.

mod arc_times;

use std::f64::consts::TAU;

use crate::geometry;
use crate::source::Span;
use crate::toolpath::{Compensation, Motion, Move, Xz};

use super::modal::{Modal, SpindleMode, SurfaceSpeed};

pub use arc_times::{ArcJob, time_arcs};

/// What the moves of the current block share.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Context {
    pub source: Span,
    pub cycle: Span,
}

#[derive(Debug)]
pub struct Emitter {
    pub moves: Vec<Move>,
    /// Seconds since the program started (it stands still while arcs are timed beside,
    /// `time_arcs_beside`, until `chain_times` runs the clock over the moves).
    pub time: f64,
    /// Where the tool is (programmed contour frame; compensation comes later).
    pub at: Xz,
    /// Rapid traverse rate of each axis, mm/min (X as the radial axis moves).
    pub rapid: Xz,
    pub context: Context,
    /// The spindle's turns from its index at which the thread passes emitted now start
    /// (`Move::phase`); a cycle sets it for the passes of one start and puts it back to 0.
    pub thread_phase: f64,
    /// Set when a feed move had no usable feed: the caller reports it once per block.
    pub zero_feed: bool,
    /// Where the first move started.
    pub first_start: Option<Xz>,
    /// Whether a move was made under nose-radius compensation, or a dwell: nose-radius
    /// compensation has nothing to do without either. (A dry run's moves, dropped again, may
    /// leave them set; that only costs the pass.)
    pub compensated: bool,
    pub dwelled: bool,
    /// Where arcs go to be timed on another thread, while one does (`time_arcs_beside`).
    beside: Option<arc_times::Beside>,
    /// The most moves a run keeps (`LowerOptions::max_moves`): a move past it is dropped,
    /// so that a cycle with a runaway parameter cannot take memory without bound before the
    /// interpreter stops the run.
    limit: usize,
}

/// Samples for Simpson's rule on arcs under constant surface speed.
const SIMPSON_INTERVALS: usize = 16;

impl Emitter {
    /// An emitter at `start`, with room for about `expected_moves` before it grows, that
    /// keeps at most `limit` moves.
    pub fn new(start: Xz, rapid: Xz, expected_moves: usize, limit: usize) -> Emitter {
        Emitter {
            moves: crate::memory::huge_page_vec(expected_moves.clamp(64, limit.max(64))),
            time: 0.0,
            at: start,
            rapid,
            context: Context { source: Span::SYNTHETIC, cycle: Span::SYNTHETIC },
            thread_phase: 0.0,
            zero_feed: false,
            first_start: None,
            compensated: false,
            dwelled: false,
            beside: None,
            limit,
        }
    }

    /// Whether the run has made as many moves as it keeps: the moves after are dropped, and
    /// a cycle stops making them.
    pub fn is_full(&self) -> bool {
        self.moves.len() >= self.limit
    }

    /// While the tool's position is not known (no home), a move only tells where it is
    /// afterwards: no move is emitted.
    pub fn arrive(&mut self, to: Xz) {
        self.at =
            Xz::new(if to.x.is_finite() { to.x } else { self.at.x }, if to.z.is_finite() { to.z } else { self.at.z });
    }

    /// Append a move from `self.at` that takes `timing`.
    fn push(
        &mut self,
        modal: &Modal,
        (motion, end, centre): (Motion, Xz, Xz),
        timing: Timing,
        cutting: bool,
        threading: bool,
    ) {
        if self.is_full() {
            self.at = end;
            return;
        }
        if self.first_start.is_none() {
            self.first_start = Some(self.at);
        }
        self.compensated |= modal.compensation != Compensation::Off;
        self.dwelled |= motion == Motion::Dwell;
        let (feed, seconds) = match timing {
            Timing::Known { length, seconds } => (feed_of(motion, length, seconds), seconds),
            // Both come back from the other thread (`chain_times`).
            Timing::Later => (f64::NAN, f64::NAN),
        };
        // While arcs are timed beside, a move holds its duration in `t_end` until
        // `chain_times` makes the clock; otherwise the clock runs here.
        let (t_start, t_end) = if self.beside.is_some() {
            (f64::NAN, seconds)
        } else {
            let start_time = self.time;
            self.time += seconds;
            (start_time, self.time)
        };
        self.moves.push(Move {
            motion,
            compensation: modal.compensation,
            cutting,
            threading,
            per_revolution: modal.feed_per_rev,
            tool: modal.tool.station,
            offset: modal.tool.offset,
            end,
            centre,
            contour: end,
            feed,
            f_word: modal.feed,
            s_word: modal.speed,
            rpm: modal.rpm_at(self.at.x),
            phase: if threading { self.thread_phase } else { 0.0 },
            t_start,
            t_end,
            source: self.context.source,
            cycle: self.context.cycle,
        });
        self.at = end;
    }

    /// Positioning at the rapid rate. A rapid that goes nowhere (`G28 U0` from home) is no move.
    pub fn rapid(&mut self, modal: &Modal, to: Xz) {
        let length = self.at.distance(to);
        if length < 1e-9 {
            return;
        }
        let dx = (to.x - self.at.x).abs() / self.rapid.x.max(1e-9);
        let dz = (to.z - self.at.z).abs() / self.rapid.z.max(1e-9);
        let seconds = dx.max(dz) * 60.0;
        self.push(modal, (Motion::Rapid, to, NAN_POINT), Timing::Known { length, seconds }, false, false);
    }

    /// A straight feed move.
    pub fn line(&mut self, modal: &Modal, to: Xz, cutting: bool) {
        let length = self.at.distance(to);
        let seconds = self.line_seconds(modal, to, length);
        self.push(modal, (Motion::Feed, to, NAN_POINT), Timing::Known { length, seconds }, cutting, false);
    }

    /// A thread-cutting pass: the tool advances `lead_mm` per revolution at the block's rpm.
    pub fn thread(&mut self, modal: &Modal, to: Xz, lead_mm: f64) {
        let rpm = modal.rpm_at(self.at.x);
        let length = self.at.distance(to);
        let seconds = self.seconds_for(length, lead_mm * rpm);
        self.push(modal, (Motion::Feed, to, NAN_POINT), Timing::Known { length, seconds }, true, true);
    }

    /// A thread whose lead per turn starts at `lead_mm` and changes by `change_mm` every
    /// spindle turn (`G34`/`G35`): one move per whole turn from the thread's start, each at
    /// its own turn's lead, so that the tool is where the control puts it at every whole turn
    /// (where the lead measure and the part model look) and every turn takes one turn of the
    /// spindle. `turns` is how far the thread has turned when it reaches this move (a
    /// chamfer goes on from the pass before it), and comes back as far as it has turned at
    /// `to`. `None` where the lead shrinks to nothing before `to`: the rest is one move at
    /// the last lead, and the caller says so.
    pub fn varying_thread(
        &mut self,
        modal: &Modal,
        to: Xz,
        (lead_mm, change_mm): (f64, f64),
        turns: &mut f64,
    ) -> Option<()> {
        let from = self.at;
        let length = from.distance(to);
        let lead_at = |n: f64| lead_mm + change_mm * n;
        // The thread's advance over the turns from `n` to `n + f`.
        let advance = |n: f64, f: f64| lead_at(n) * f + change_mm * f * f / 2.0;
        let mut done = 0.0;
        loop {
            let n = *turns;
            // The turns to the next whole turn, and the rest of the move.
            let whole = (n + 1e-9).floor() + 1.0 - n;
            let step = advance(n, whole);
            if !(lead_at(n) > 0.0 && step > 0.0) {
                self.thread(modal, to, lead_mm);
                return None;
            }
            let rest = length - done;
            if step >= rest - 1e-9 || self.is_full() {
                // The last part turn: the turns `f` that advance `rest`.
                let discriminant = lead_at(n) * lead_at(n) + 2.0 * change_mm * rest;
                let f = if change_mm.abs() < 1e-15 {
                    rest / lead_at(n)
                } else if discriminant >= 0.0 {
                    (discriminant.sqrt() - lead_at(n)) / change_mm
                } else {
                    self.thread(modal, to, lead_at(n));
                    return None;
                };
                if rest > 1e-9 && f > 0.0 {
                    self.thread(modal, to, rest / f);
                    *turns = n + f;
                }
                return Some(());
            }
            done += step;
            let t = done / length;
            self.thread(modal, Xz::new(from.x + (to.x - from.x) * t, from.z + (to.z - from.z) * t), step / whole);
            *turns = n + whole;
        }
    }

    /// An arc about `centre`.
    pub fn arc(&mut self, modal: &Modal, to: Xz, centre: Xz, ccw: bool, cutting: bool) {
        let motion = if ccw { Motion::Ccw } else { Motion::Cw };
        if !self.is_full()
            && let Some(beside) = &mut self.beside
            && let Some(job) = ArcJob::new(self.at, to, centre, ccw, modal)
        {
            beside.hand_over(self.moves.len(), job);
            self.push(modal, (motion, to, centre), Timing::Later, cutting, false);
            return;
        }
        let arc = ArcShape::new(self.at, to, centre, ccw);
        let seconds = self.arc_seconds(modal, &arc);
        self.push(modal, (motion, to, centre), Timing::Known { length: arc.length, seconds }, cutting, false);
    }

    pub fn dwell(&mut self, modal: &Modal, seconds: f64) {
        let at = self.at;
        self.push(
            modal,
            (Motion::Dwell, at, NAN_POINT),
            Timing::Known { length: 0.0, seconds: seconds.max(0.0) },
            false,
            false,
        );
    }

    fn seconds_for(&mut self, length: f64, mm_per_min: f64) -> f64 {
        if length <= 0.0 {
            return 0.0;
        }
        if !usable_rate(mm_per_min) {
            self.zero_feed = true;
            return 0.0;
        }
        seconds_at(length, mm_per_min)
    }

    fn line_seconds(&mut self, modal: &Modal, to: Xz, length: f64) -> f64 {
        let feed_mm = modal.frame.feed_mm(modal.feed);
        if !modal.feed_per_rev {
            return self.seconds_for(length, feed_mm);
        }
        if modal.spindle == SpindleMode::Rpm || (to.x - self.at.x).abs() < 1e-12 {
            return self.seconds_for(length, feed_mm * modal.rpm_at(self.at.x));
        }
        if length <= 0.0 {
            return 0.0;
        }
        if feed_mm.is_nan() || feed_mm <= 0.0 {
            self.zero_feed = true;
            return 0.0;
        }
        // t = ∫ ds / (f · rpm(r)) over the move, with rpm = min(clamp, k / r).
        let k = modal.frame.surface_speed_mm_min(modal.speed) / TAU;
        let clamp = modal.surface_speed().clamp;
        let (r0, r1) = (self.at.x.abs(), to.x.abs());
        let crossover = if clamp > 0.0 { k / clamp } else { f64::INFINITY };
        // Minutes per unit of the move parameter t ∈ [0, 1] where r(t) is linear.
        let minutes = |from: f64, to_t: f64| -> f64 {
            if to_t <= from {
                return 0.0;
            }
            let r_at = |t: f64| r0 + (r1 - r0) * t;
            let mid = r_at((from + to_t) / 2.0);
            let rpm = if mid <= crossover { clamp } else { k / mid };
            if mid <= crossover {
                length * (to_t - from) / (feed_mm * rpm)
            } else {
                // rpm = k / r is linear in 1/r, so its reciprocal integrates exactly at the midpoint.
                length * (to_t - from) * mid / (feed_mm * k)
            }
        };
        let split = if (r1 - r0).abs() > 1e-12 { ((crossover - r0) / (r1 - r0)).clamp(0.0, 1.0) } else { 0.0 };
        let total = minutes(0.0, split) + minutes(split, 1.0);
        if !total.is_finite() {
            self.zero_feed = true;
            return 0.0;
        }
        total * 60.0
    }

    fn arc_seconds(&mut self, modal: &Modal, arc: &ArcShape) -> f64 {
        Rate::of(modal, self.at).seconds(arc).unwrap_or_else(|| {
            self.zero_feed = true;
            0.0
        })
    }
}

/// How an arc's time follows from its length: the one rule for arcs timed here and on the
/// arc timer's thread (`arc_times.rs`).
#[derive(Debug, Clone, Copy)]
enum Rate {
    /// A feed in mm/min (per minute, or per revolution at a fixed spindle speed).
    PerMinute(f64),
    /// Per revolution under constant surface speed (Simpson's rule, `simpson_minutes`).
    SurfaceSpeed { feed_mm: f64, spindle: SurfaceSpeed },
}

impl Rate {
    /// The rate of an arc starting at `at` under `modal`.
    fn of(modal: &Modal, at: Xz) -> Rate {
        let feed_mm = modal.frame.feed_mm(modal.feed);
        if !modal.feed_per_rev {
            Rate::PerMinute(feed_mm)
        } else if modal.spindle == SpindleMode::Rpm {
            Rate::PerMinute(feed_mm * modal.rpm_at(at.x))
        } else {
            Rate::SurfaceSpeed { feed_mm, spindle: modal.surface_speed() }
        }
    }

    /// The seconds `arc` takes, or `None` where the rate gives no usable time (no feed).
    fn seconds(self, arc: &ArcShape) -> Option<f64> {
        match self {
            // A move of no length takes no time, whatever the feed.
            Rate::PerMinute(_) if arc.length <= 0.0 => Some(0.0),
            Rate::PerMinute(mm_per_min) => usable_rate(mm_per_min).then(|| seconds_at(arc.length, mm_per_min)),
            Rate::SurfaceSpeed { feed_mm, .. } if feed_mm.is_nan() || feed_mm <= 0.0 => None,
            Rate::SurfaceSpeed { feed_mm, spindle } => {
                let total = simpson_minutes(arc, feed_mm, spindle);
                total.is_finite().then_some(total * 60.0)
            }
        }
    }
}

/// How long a move takes.
#[derive(Debug, Clone, Copy)]
enum Timing {
    Known {
        length: f64,
        seconds: f64,
    },
    /// An arc timed on another thread.
    Later,
}

/// The feed a move of `length` mm in `seconds` makes, mm/min (0 for rapids and dwells).
fn feed_of(motion: Motion, length: f64, seconds: f64) -> f64 {
    if matches!(motion, Motion::Rapid | Motion::Dwell) || seconds <= 0.0 { 0.0 } else { length / seconds * 60.0 }
}

/// A feed in mm/min a move can be timed at.
fn usable_rate(mm_per_min: f64) -> bool {
    !(mm_per_min.is_nan() || mm_per_min <= 0.0 || !mm_per_min.is_finite())
}

/// The seconds `length` mm take at `mm_per_min`.
fn seconds_at(length: f64, mm_per_min: f64) -> f64 {
    length / mm_per_min * 60.0
}

/// The minutes an arc takes at `feed_mm` per revolution under constant surface speed, by
/// Simpson's rule on the spindle speed along it (infinite or NaN where the speed is not
/// usable).
fn simpson_minutes(arc: &ArcShape, feed_mm: f64, spindle: SurfaceSpeed) -> f64 {
    let ArcShape { centre, radius, a0, sweep, ccw, length } = *arc;
    let sign = if ccw { 1.0 } else { -1.0 };
    let minutes_per_mm = |i: usize| {
        1.0 / (feed_mm
            * spindle
                .rpm_at(geometry::on_circle(centre, radius, a0 + sign * sweep * i as f64 / SIMPSON_INTERVALS as f64).x))
    };
    let mut sum = minutes_per_mm(0) + minutes_per_mm(SIMPSON_INTERVALS);
    for i in 1..SIMPSON_INTERVALS {
        sum += if i % 2 == 1 { 4.0 } else { 2.0 } * minutes_per_mm(i);
    }
    sum * length / (3.0 * SIMPSON_INTERVALS as f64)
}

const NAN_POINT: Xz = Xz::new(f64::NAN, f64::NAN);

/// An arc from the emitter's position: its centre, radius, start angle, sweep (radians)
/// and length.
#[derive(Debug, Clone, Copy)]
struct ArcShape {
    centre: Xz,
    radius: f64,
    a0: f64,
    sweep: f64,
    ccw: bool,
    length: f64,
}

impl ArcShape {
    fn new(at: Xz, to: Xz, centre: Xz, ccw: bool) -> ArcShape {
        // The angles, the sweep and the length once, for the time and the feed alike.
        let radius = at.distance(centre);
        let a0 = geometry::angle(at, centre);
        let sweep = geometry::sweep_from_angles(at, to, a0, geometry::angle(to, centre), ccw);
        ArcShape { centre, radius, a0, sweep, ccw, length: radius * sweep }
    }
}
