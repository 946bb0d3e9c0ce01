//! The machine state an error depends on, sampled along a commanded path.
//!
//! Direction-dependent effects need each axis' last direction of motion and the travel
//! since it last reversed; wear needs the cut length of the tool; thermal effects the time.
//! A `Tracker` walks the commanded points in order and produces a `Sample` at each.
//!
//! Backlash is a play between the drive and the slide: the slide stays where it is until
//! the command has travelled across the play, then follows it, lagging by half the play
//! (the classic play or hysteresis operator). The tracker runs that operator with the
//! model's total play per axis, so the slide really stays put for a command that reverses
//! by less than the play (as a compensated path's micrometre corrections do), and an
//! axis' direction is the direction the slide was last pushed in. With no play, the
//! direction is simply that of the last non-zero motion. Before an axis has moved, its
//! last direction is `+`: a machine starts from a reference return, which on the lathes we
//! model approaches in the positive direction.

use crate::toolpath::Xz;

/// Last direction of motion of each axis: `+1` or `-1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Signs {
    pub x: i8,
    pub z: i8,
}

/// Everything an effect may depend on at one commanded point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// The commanded tool reference point, mm, X as a radius.
    pub at: Xz,
    /// Minutes since the machine started.
    pub t_min: f64,
    /// Commanded velocity, mm/min (zero at rest).
    pub velocity: Xz,
    /// Each axis' last direction of motion (kept while it rests).
    pub direction: Signs,
    /// The model's play per axis (the sum of its backlash effects), mm, and where the slide
    /// sits in it: slide − command, between −play/2 and +play/2.
    pub play: Xz,
    pub backlash: Xz,
    /// Travel of each axis since it last reversed, mm.
    pub since_reversal: Xz,
    /// Length the current tool has cut since it was set, m.
    pub cut_length_m: f64,
    /// Unit normal of the surface being cut, pointing from the part to the tool; zero when
    /// the move does not cut.
    pub normal: Xz,
    /// The tool's tip direction: imaginary tip − nose centre, in nose radii (`tip_vector`).
    pub tip: Xz,
}

impl Sample {
    /// A tool at rest at `at`, at time `t_min`, axes last moved in `+`.
    pub fn at_rest(at: Xz, t_min: f64) -> Sample {
        Sample {
            at,
            t_min,
            velocity: Xz::new(0.0, 0.0),
            direction: Signs { x: 1, z: 1 },
            play: Xz::new(0.0, 0.0),
            backlash: Xz::new(0.0, 0.0),
            since_reversal: Xz::new(f64::INFINITY, f64::INFINITY),
            cut_length_m: 0.0,
            normal: Xz::new(0.0, 0.0),
            tip: Xz::new(0.0, 0.0),
        }
    }
}

/// What a sample takes from the path rather than from the tracker.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleInputs {
    pub t_min: f64,
    pub velocity: Xz,
    pub normal: Xz,
    pub tip: Xz,
}

/// What a move to a commanded point makes of the tracker's axes (`Tracker::step`): where
/// the slides are, the directions they were last pushed in and the travel since each
/// reversed. `sample_after` and `take` both take it, so a point that is looked at and then
/// moved to (every sample solved or predicted) runs the play operator once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    to: Xz,
    slide: Xz,
    direction: Signs,
    since_reversal: Xz,
}

impl Step {
    /// The commanded point the step moves to.
    pub fn to(&self) -> Xz {
        self.to
    }
}

/// Moves below this (mm) do not change an axis' direction: rounding noise is no reversal.
const STILL_MM: f64 = 1e-9;

/// Follows the machine state along a commanded path.
#[derive(Debug, Clone)]
pub struct Tracker {
    at: Xz,
    /// Where each slide is, on the play operator (equal to `at` with no play).
    slide: Xz,
    play: Xz,
    direction: Signs,
    since_reversal: Xz,
    /// Cut length per tool (turret station), m: wear belongs to the tool, not the program.
    cut: Vec<(u16, f64)>,
    /// Whether the cut length is followed (`counting_cut`).
    counts_cut: bool,
}

impl Tracker {
    /// A tracker at `start`, reached by a positive approach, for a machine whose slides
    /// have `play` (mm, zero for none).
    pub fn new(start: Xz, play: Xz) -> Tracker {
        let play = Xz::new(play.x.max(0.0), play.z.max(0.0));
        Tracker {
            at: start,
            slide: Xz::new(start.x - play.x / 2.0, start.z - play.z / 2.0),
            play,
            direction: Signs { x: 1, z: 1 },
            since_reversal: Xz::new(f64::INFINITY, f64::INFINITY),
            cut: Vec::new(),
            counts_cut: true,
        }
    }

    /// The tracker, following each tool's cut length only when `count` holds: a model
    /// without wear never reads it, and measuring every step's length was the largest cost
    /// of solving a sample. Samples then say the tools have cut nothing.
    pub fn counting_cut(self, count: bool) -> Tracker {
        Tracker { counts_cut: count, ..self }
    }

    /// The commanded point the tracker stands at.
    pub fn position(&self) -> Xz {
        self.at
    }

    /// Where the slides are (the commanded point, less the play they lag by).
    pub fn slide(&self) -> Xz {
        self.slide
    }

    /// The play of each axis, mm.
    pub fn play(&self) -> Xz {
        self.play
    }

    /// The direction each slide was last pushed in.
    pub fn direction(&self) -> Signs {
        self.direction
    }

    /// The sample the tracker would give after `advance(to, tool, cutting)`, without
    /// moving it: for solving where to command a point.
    pub fn peek(&self, to: Xz, tool: u16, cutting: bool, inputs: &SampleInputs) -> Sample {
        self.sample_after(&self.step(to), tool, cutting, inputs)
    }

    /// What a move to `to` makes of the axes, without moving the tracker.
    pub fn step(&self, to: Xz) -> Step {
        let (mut slide, mut direction, mut since) = (self.slide, self.direction, self.since_reversal);
        advance_axis(to.x, self.play.x, &mut slide.x, &mut direction.x, &mut since.x);
        advance_axis(to.z, self.play.z, &mut slide.z, &mut direction.z, &mut since.z);
        Step { to, slide, direction, since_reversal: since }
    }

    /// The part of the move `step` describes (`step` of this tracker) that the command
    /// travels inside the play before a reversing slide moves: per axis that reverses, from
    /// the commanded point to the edge of the play in the new direction (zero on an axis
    /// that keeps its direction). Compensation writes it as a move of its own, the take-up.
    pub fn take_up(&self, step: &Step) -> Xz {
        let axis = |new: i8, old: i8, slide: f64, at: f64, play: f64| {
            if new == old { 0.0 } else { slide + f64::from(new) * play / 2.0 - at }
        };
        Xz::new(
            axis(step.direction.x, self.direction.x, self.slide.x, self.at.x, self.play.x),
            axis(step.direction.z, self.direction.z, self.slide.z, self.at.z, self.play.z),
        )
    }

    /// `peek` of the move `step` describes (`step` of this tracker).
    // Inlined where the model is evaluated on the sample at once: the parts of the sample
    // the model does not read need not be written out and read back.
    #[inline]
    pub fn sample_after(&self, step: &Step, tool: u16, cutting: bool, inputs: &SampleInputs) -> Sample {
        let Step { to, slide, direction, since_reversal: since } = *step;
        let mut cut = self.cut_length(tool);
        if cutting && self.counts_cut {
            cut += self.at.distance(to) / 1000.0;
        }
        Sample {
            at: to,
            t_min: inputs.t_min,
            velocity: inputs.velocity,
            direction,
            play: self.play,
            backlash: Xz::new(slide.x - to.x, slide.z - to.z),
            since_reversal: since,
            cut_length_m: cut,
            normal: inputs.normal,
            tip: inputs.tip,
        }
    }

    fn cut_length(&self, tool: u16) -> f64 {
        self.cut.iter().find(|(t, _)| *t == tool).map_or(0.0, |(_, m)| *m)
    }

    /// Move to `to`; `cutting` adds the travel to `tool`'s cut length.
    pub fn advance(&mut self, to: Xz, tool: u16, cutting: bool) {
        let step = self.step(to);
        self.take(&step, tool, cutting);
    }

    /// `advance` by the move `step` describes (`step` of this tracker, not moved since).
    pub fn take(&mut self, step: &Step, tool: u16, cutting: bool) {
        let to = step.to;
        let (dx, dz) = (to.x - self.at.x, to.z - self.at.z);
        (self.slide, self.direction, self.since_reversal) = (step.slide, step.direction, step.since_reversal);
        if cutting && self.counts_cut {
            let length_m = (dx * dx + dz * dz).sqrt() / 1000.0;
            match self.cut.iter_mut().find(|(t, _)| *t == tool) {
                Some((_, m)) => *m += length_m,
                None => self.cut.push((tool, length_m)),
            }
        }
        self.at = to;
    }

    /// The sample at the current point.
    pub fn sample(&self, t_min: f64, velocity: Xz, tool: u16, normal: Xz, tip: Xz) -> Sample {
        Sample {
            at: self.at,
            t_min,
            velocity,
            direction: self.direction,
            play: self.play,
            backlash: Xz::new(self.slide.x - self.at.x, self.slide.z - self.at.z),
            since_reversal: self.since_reversal,
            cut_length_m: self.cut_length(tool),
            normal,
            tip,
        }
    }
}

/// The play operator on one axis: the slide moves only when the command leaves the band
/// of width `play` around it, and then by as much as the command goes beyond the band.
fn advance_axis(command: f64, play: f64, slide: &mut f64, direction: &mut i8, since: &mut f64) {
    let half = play / 2.0;
    let pushed = if command - *slide > half + STILL_MM {
        command - half - *slide
    } else if *slide - command > half + STILL_MM {
        command + half - *slide
    } else {
        return;
    };
    *slide += pushed;
    let sign = if pushed > 0.0 { 1 } else { -1 };
    if sign == *direction {
        *since += pushed.abs();
    } else {
        *direction = sign;
        *since = pushed.abs();
    }
}
