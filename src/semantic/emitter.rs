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

use std::f64::consts::TAU;

use crate::geometry;
use crate::source::Span;
use crate::toolpath::{Compensation, Motion, Move, Xz};

use super::modal::{Modal, SpindleMode};

/// What the moves of the current block share.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Context {
    pub source: Span,
    pub cycle: Span,
}

#[derive(Debug)]
pub struct Emitter {
    pub moves: Vec<Move>,
    /// Seconds since the program started.
    pub time: f64,
    /// Where the tool is (programmed contour frame; compensation comes later).
    pub at: Xz,
    /// Rapid traverse rate of each axis, mm/min (X as the radial axis moves).
    pub rapid: Xz,
    pub context: Context,
    /// Set when a feed move had no usable feed: the caller reports it once per block.
    pub zero_feed: bool,
    /// Where the first move started.
    pub first_start: Option<Xz>,
    /// Whether a move was made under nose-radius compensation, or a dwell: nose-radius
    /// compensation has nothing to do without either. (A dry run's moves, dropped again, may
    /// leave them set; that only costs the pass.)
    pub compensated: bool,
    pub dwelled: bool,
}

/// Samples for Simpson's rule on arcs under constant surface speed.
const SIMPSON_INTERVALS: usize = 16;

impl Emitter {
    /// An emitter at `start`, with room for about `expected_moves` before it grows.
    pub fn new(start: Xz, rapid: Xz, expected_moves: usize) -> Emitter {
        Emitter {
            moves: crate::memory::huge_page_vec(expected_moves.max(64)),
            time: 0.0,
            at: start,
            rapid,
            context: Context { source: Span::SYNTHETIC, cycle: Span::SYNTHETIC },
            zero_feed: false,
            first_start: None,
            compensated: false,
            dwelled: false,
        }
    }

    /// While the tool's position is not known (no home), a move only tells where it is
    /// afterwards: no move is emitted.
    pub fn arrive(&mut self, to: Xz) {
        self.at =
            Xz::new(if to.x.is_finite() { to.x } else { self.at.x }, if to.z.is_finite() { to.z } else { self.at.z });
    }

    /// Append a move of `length` mm (the caller has it from the move's time) from `self.at`.
    fn push(
        &mut self,
        modal: &Modal,
        (motion, end, centre): (Motion, Xz, Xz),
        (length, seconds): (f64, f64),
        cutting: bool,
        threading: bool,
    ) {
        if self.first_start.is_none() {
            self.first_start = Some(self.at);
        }
        self.compensated |= modal.compensation != Compensation::Off;
        self.dwelled |= motion == Motion::Dwell;
        let start_time = self.time;
        self.time += seconds;
        let feed = if matches!(motion, Motion::Rapid | Motion::Dwell) || seconds <= 0.0 {
            0.0
        } else {
            length / seconds * 60.0
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
            t_start: start_time,
            t_end: self.time,
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
        self.push(modal, (Motion::Rapid, to, NAN_POINT), (length, seconds), false, false);
    }

    /// A straight feed move.
    pub fn line(&mut self, modal: &Modal, to: Xz, cutting: bool) {
        let length = self.at.distance(to);
        let seconds = self.line_seconds(modal, to, length);
        self.push(modal, (Motion::Feed, to, NAN_POINT), (length, seconds), cutting, false);
    }

    /// A thread-cutting pass: the tool advances `lead_mm` per revolution at the block's rpm.
    pub fn thread(&mut self, modal: &Modal, to: Xz, lead_mm: f64) {
        let rpm = modal.rpm_at(self.at.x);
        let length = self.at.distance(to);
        let seconds = self.seconds_for(length, lead_mm * rpm);
        self.push(modal, (Motion::Feed, to, NAN_POINT), (length, seconds), true, true);
    }

    /// An arc about `centre`.
    pub fn arc(&mut self, modal: &Modal, to: Xz, centre: Xz, ccw: bool, cutting: bool) {
        // The angles, the sweep and the length once, for the time and the feed alike.
        let radius = self.at.distance(centre);
        let a0 = geometry::angle(self.at, centre);
        let sweep = geometry::sweep_from_angles(self.at, to, a0, geometry::angle(to, centre), ccw);
        let arc = ArcShape { centre, radius, a0, sweep, ccw };
        let length = radius * sweep;
        let seconds = self.arc_seconds(modal, &arc, length);
        let motion = if ccw { Motion::Ccw } else { Motion::Cw };
        self.push(modal, (motion, to, centre), (length, seconds), cutting, false);
    }

    pub fn dwell(&mut self, modal: &Modal, seconds: f64) {
        let at = self.at;
        self.push(modal, (Motion::Dwell, at, NAN_POINT), (0.0, seconds.max(0.0)), false, false);
    }

    fn seconds_for(&mut self, length: f64, mm_per_min: f64) -> f64 {
        if length <= 0.0 {
            return 0.0;
        }
        if mm_per_min.is_nan() || mm_per_min <= 0.0 || !mm_per_min.is_finite() {
            self.zero_feed = true;
            return 0.0;
        }
        length / mm_per_min * 60.0
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
        let clamp = modal.clamp;
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

    fn arc_seconds(&mut self, modal: &Modal, arc: &ArcShape, length: f64) -> f64 {
        let feed_mm = modal.frame.feed_mm(modal.feed);
        if !modal.feed_per_rev {
            return self.seconds_for(length, feed_mm);
        }
        if modal.spindle == SpindleMode::Rpm {
            return self.seconds_for(length, feed_mm * modal.rpm_at(self.at.x));
        }
        if feed_mm.is_nan() || feed_mm <= 0.0 {
            self.zero_feed = true;
            return 0.0;
        }
        let ArcShape { centre, radius, a0, sweep, ccw } = *arc;
        let sign = if ccw { 1.0 } else { -1.0 };
        let minutes_per_mm = |i: usize| {
            1.0 / (feed_mm
                * modal.rpm_at(
                    geometry::on_circle(centre, radius, a0 + sign * sweep * i as f64 / SIMPSON_INTERVALS as f64).x,
                ))
        };
        let mut sum = minutes_per_mm(0) + minutes_per_mm(SIMPSON_INTERVALS);
        for i in 1..SIMPSON_INTERVALS {
            sum += if i % 2 == 1 { 4.0 } else { 2.0 } * minutes_per_mm(i);
        }
        let total = sum * length / (3.0 * SIMPSON_INTERVALS as f64);
        if !total.is_finite() {
            self.zero_feed = true;
            return 0.0;
        }
        total * 60.0
    }
}

const NAN_POINT: Xz = Xz::new(f64::NAN, f64::NAN);

/// An arc from the emitter's position: its centre, radius, start angle and sweep (radians).
#[derive(Debug, Clone, Copy)]
struct ArcShape {
    centre: Xz,
    radius: f64,
    a0: f64,
    sweep: f64,
    ccw: bool,
}
