//! Arcs timed on a second thread while the interpreter runs on.
//!
//! An arc's time takes two arctangents and, under constant surface speed, seventeen sines:
//! on a long program a third of the lowering, on one core while the other waited. While a
//! long program is lowered the emitter hands each arc it can time elsewhere to a thread
//! (`time_arcs`) and leaves the arc's time and feed open; every move keeps its own duration
//! until the run ends, and `Emitter::chain_times` then fills in the arcs and runs the clock
//! over the moves in order, adding the same durations in the same order as the emitter
//! does when it times them itself, so the times are the same to the bit.
//!
//! An arc is handed over only when its time cannot come out unusable (`ArcJob::new`): the
//! emitter reports a move without a usable feed on the block that makes it, and that must
//! be known when the block runs.

use std::sync::mpsc::{Receiver, Sender};

use crate::toolpath::{Motion, Xz};

use super::{ArcShape, Emitter, Modal, Rate, feed_of, usable_rate};

/// Arcs are sent to the other thread this many at a time.
const BATCH: usize = 1024;

/// An arc to be timed: where it starts and ends, its centre, its direction and its rate.
#[derive(Debug, Clone, Copy)]
pub struct ArcJob {
    at: Xz,
    to: Xz,
    centre: Xz,
    ccw: bool,
    rate: Rate,
}

/// Bounds within which an arc under constant surface speed certainly has a finite time:
/// every spindle speed along it lies between `v / (2π · 4·10⁶)` and `v / (2π · 10⁻⁹)` or
/// the clamp, so every term of Simpson's rule, their sum and the time are finite numbers.
const MAX_COORDINATE_MM: f64 = 1e6;
const FEED_MM: std::ops::RangeInclusive<f64> = 1e-6..=1e6;
const SURFACE_SPEED_MM_MIN: std::ops::RangeInclusive<f64> = 1e-3..=1e12;
const MIN_CLAMP_RPM: f64 = 1e-6;

impl ArcJob {
    /// The arc from `at` to `to` about `centre` under `modal`, when its time can be made on
    /// another thread: when it is certainly usable. `None` for the others, which the
    /// emitter times itself (and reports when unusable).
    pub(super) fn new(at: Xz, to: Xz, centre: Xz, ccw: bool, modal: &Modal) -> Option<ArcJob> {
        let rate = Rate::of(modal, at);
        let usable = match rate {
            Rate::PerMinute(mm_per_min) => usable_rate(mm_per_min),
            Rate::SurfaceSpeed { feed_mm, spindle } => {
                let bounded = |p: Xz| p.is_finite() && p.x.abs() <= MAX_COORDINATE_MM && p.z.abs() <= MAX_COORDINATE_MM;
                bounded(at)
                    && bounded(to)
                    && bounded(centre)
                    && FEED_MM.contains(&feed_mm)
                    && SURFACE_SPEED_MM_MIN.contains(&spindle.mm_per_min)
                    && spindle.clamp >= MIN_CLAMP_RPM
            }
        };
        usable.then_some(ArcJob { at, to, centre, ccw, rate })
    }

    /// The arc's time and feed, as `Emitter::arc` makes them.
    fn timed(&self) -> Timed {
        let arc = ArcShape::new(self.at, self.to, self.centre, self.ccw);
        // `new` handed over only arcs whose rate gives a time.
        let seconds = self.rate.seconds(&arc).unwrap_or(0.0);
        let motion = if self.ccw { Motion::Ccw } else { Motion::Cw };
        Timed { seconds, feed: feed_of(motion, arc.length, seconds) }
    }
}

/// An arc's time and feed (mm/min).
#[derive(Debug, Clone, Copy)]
pub struct Timed {
    seconds: f64,
    feed: f64,
}

/// Time the arcs that come through `jobs`, in order, until the sender is dropped.
pub fn time_arcs(jobs: Receiver<Vec<ArcJob>>) -> Vec<Timed> {
    let mut out = Vec::new();
    for batch in jobs {
        out.extend(batch.iter().map(ArcJob::timed));
    }
    out
}

/// What was handed over: the move of each arc, in order, and the first move timed at the
/// end.
#[derive(Debug, Default)]
pub struct JobMoves {
    moves: Vec<usize>,
    from_move: usize,
}

/// The emitter's side of the hand-over.
#[derive(Debug)]
pub(in crate::semantic) struct Beside {
    sender: Sender<Vec<ArcJob>>,
    batch: Vec<ArcJob>,
    handed: JobMoves,
}

impl Beside {
    pub(super) fn hand_over(&mut self, move_index: usize, job: ArcJob) {
        self.handed.moves.push(move_index);
        self.batch.push(job);
        if self.batch.len() >= BATCH {
            self.send();
        }
    }

    fn send(&mut self) {
        let batch = std::mem::replace(&mut self.batch, Vec::with_capacity(BATCH));
        // The thread stops only when it panics, which `Interpreter::run` passes on.
        let _ = self.sender.send(batch);
    }
}

impl Emitter {
    /// Hand the arcs that can be timed elsewhere to `sender` from now on (`time_arcs` at
    /// the other end), until `stop_timing_beside`. The clock stands still meanwhile: each
    /// move holds its own duration.
    pub fn time_arcs_beside(&mut self, sender: Sender<Vec<ArcJob>>) {
        let handed = JobMoves { moves: Vec::new(), from_move: self.moves.len() };
        self.beside = Some(Beside { sender, batch: Vec::with_capacity(BATCH), handed });
    }

    /// Send the last arcs, and close the hand-over: the thread's `time_arcs` returns. The
    /// moves of the arcs handed over, for `chain_times`.
    pub fn stop_timing_beside(&mut self) -> JobMoves {
        let Some(mut beside) = self.beside.take() else { return JobMoves::default() };
        beside.send();
        beside.handed
    }

    /// Time arcs in place for a while (a profile's scratch moves, which are dropped
    /// again): what `resume_timing_beside` takes back.
    pub(in crate::semantic) fn pause_timing_beside(&mut self) -> Option<Beside> {
        self.beside.take()
    }

    pub(in crate::semantic) fn resume_timing_beside(&mut self, paused: Option<Beside>) {
        self.beside = paused;
    }

    /// After `stop_timing_beside`: the handed-over arcs' times and feeds (`timed`, from
    /// `time_arcs`, in the order of `handed`) into their moves, and the clock run over
    /// the moves made since `time_arcs_beside`, each holding its duration in `t_end` until
    /// now.
    pub fn chain_times(&mut self, handed: &JobMoves, timed: &[Timed]) {
        for (&index, timed) in handed.moves.iter().zip(timed) {
            if let Some(m) = self.moves.get_mut(index) {
                m.t_end = timed.seconds;
                m.feed = timed.feed;
            }
        }
        let mut time = self.time;
        for m in self.moves.iter_mut().skip(handed.from_move) {
            let seconds = m.t_end;
            m.t_start = time;
            time += seconds;
            m.t_end = time;
        }
        self.time = time;
    }
}

#[cfg(test)]
mod tests;
