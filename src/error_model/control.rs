//! The control's own axis compensation, as the model sees it: its pitch-error table and its
//! backlash compensation, which correct each axis' command as a function of that axis' own
//! commanded position and direction of travel, for every program.
//!
//! Which part of the model a control's tables can carry is each effect's own answer
//! ([`TablePart`], `ParametricEffect::control_table`): a function of one axis' own position
//! (a screw's scale and cyclic error, a slide table's linear column) is a pitch-error table;
//! the play of a drive is its backlash compensation; a function of the other axis' position
//! (straightness, squareness) only a cross-axis table carries; time, velocity, the tool and
//! the travel since a reversal no table carries.
//!
//! A loaded table ([`ControlCompensation`], read from the control's own file by
//! `crate::control_table`) adds a correction `c(p, d)` to each axis' command `p` moving in
//! direction `d` (LinuxCNC: `motor-pos-cmd = pos-cmd + backlash-filt`, `src/emc/motion/
//! control.c`), so the machine with the table loaded is the machine at `p + c`. The model
//! of that machine ([`ErrorModel::with_control`]) is the model with
//!
//! * each term a pitch table carries evaluated at the corrected command, plus the
//!   correction: what remains is what the table misses (its spacing, its units, its range);
//! * the backlash the control takes up subtracted from each drive's play: a control that
//!   adds `±b_c/2` in the direction of the command to a drive with play `b` leaves a drive
//!   with play `b − b_c` (the play operator on the corrected command is the play operator
//!   on the command with the play reduced, for every command, also a reversal inside the
//!   play; with `b_c > b` the slide leads by `(b_c − b)/2`, the model's negative backlash).
//!   `b_c` is the constant part of the table's reversal (a file's forward column less its
//!   reverse one, at its smallest), at most the drive's play; the rest of the reversal is
//!   switched with the direction. That is exact when the table takes up the whole play;
//!   when it takes up less, a reversal that stops between what it takes up and the play
//!   lands differently (the model switches the rest with the slide, after the play), and
//!   every reversal past the play lands alike (`control/tests.rs`).
//!
//! Everything else stays as it is, for the program to compensate. The correction is
//! switched by the direction the model's tracker gives the axis: with the play taken up
//! that is the direction of the command's last motion, as LinuxCNC switches on the sign of
//! the joint's commanded velocity and keeps the last correction while it rests.

use crate::error_model::effects::Effect;
use crate::error_model::effects::axis::{X, Z};
use crate::error_model::effects::backlash::Backlash;
use crate::error_model::interferometer::Profile;
use crate::error_model::model_file::Axis;
use crate::error_model::{ErrorModel, Sample};
use crate::toolpath::Xz;

/// What a control's axis compensation carries of one effect.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TablePart {
    /// All of it, along `axis` and a function of that axis' own commanded position: a
    /// pitch-error table carries it.
    Pitch(Axis),
    /// The play of `axis`' drive, mm: the control's backlash compensation carries it.
    Backlash(Axis, f64),
    /// All of it, along `axis` and a function of the other axis' position: only a control
    /// with a cross-axis (straightness) table could carry it.
    CrossAxis(Axis),
    /// None of it: the program carries it, for the reason given.
    Program(&'static str),
}

impl TablePart {
    /// Where it goes, in words, for a control that carries pitch tables and backlash.
    pub fn destination(&self) -> String {
        match self {
            TablePart::Pitch(axis) => format!("the {} pitch-error table", axis.letter()),
            TablePart::Backlash(axis, _) => format!("the {} backlash compensation", axis.letter()),
            TablePart::CrossAxis(axis) => {
                format!(
                    "the program: along {} as a function of the other axis, which a per-axis table cannot hold",
                    axis.letter()
                )
            }
            TablePart::Program(why) => format!("the program: {why}"),
        }
    }
}

/// How a control's correction runs between two nodes of its table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Between {
    /// Linear between nodes, held at the end values beyond them (LinuxCNC's joint
    /// compensation, `compute_screw_comp` in `src/emc/motion/control.c`).
    Linear,
    /// A staircase: a node's value from that node up to the next one, the first node's
    /// below it and the last one's beyond (the increments a Fanuc outputs at each
    /// compensation point; our reading, unverified: `control_table/fanuc.rs`).
    Steps,
}

/// One node of a control's table: where, and the correction added to the command there when
/// the axis moves in + and in −, mm (the backlash compensation apart).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Node {
    pub at: f64,
    pub forward: f64,
    pub reverse: f64,
    /// The slopes to the next node, as the control computes and keeps them (LinuxCNC in
    /// single precision); zero for the last node and for a staircase.
    pub forward_slope: f64,
    pub reverse_slope: f64,
}

/// What a control does to one axis' command, in the model's frame (mm, X a radius).
#[derive(Debug, Clone, PartialEq)]
pub struct AxisCompensation {
    /// The table's nodes, ascending (none: the axis has only its backlash compensation).
    pub nodes: Vec<Node>,
    pub between: Between,
    /// The backlash compensation, mm: half of it is added in the direction of motion.
    pub backlash: f64,
}

impl AxisCompensation {
    /// An axis with the table `points` (ascending positions, each with its forward and
    /// reverse correction) run `between` them, and `backlash`.
    pub fn new(points: &[(f64, f64, f64)], between: Between, backlash: f64) -> AxisCompensation {
        let mut nodes: Vec<Node> = points
            .iter()
            .map(|&(at, forward, reverse)| Node { at, forward, reverse, forward_slope: 0.0, reverse_slope: 0.0 })
            .collect();
        if between == Between::Linear {
            for k in 1..nodes.len() {
                let span = nodes[k].at - nodes[k - 1].at;
                if span > 0.0 {
                    nodes[k - 1].forward_slope = (nodes[k].forward - nodes[k - 1].forward) / span;
                    nodes[k - 1].reverse_slope = (nodes[k].reverse - nodes[k - 1].reverse) / span;
                }
            }
        }
        AxisCompensation { nodes, between, backlash }
    }

    /// The correction the table adds to a command at `p` moving in `direction` (+1, −1),
    /// the backlash compensation apart, mm.
    pub fn correction(&self, p: f64, direction: i8) -> f64 {
        let Some(first) = self.nodes.first() else { return 0.0 };
        // The node at or below `p` (the first node below the table: its values, slope none).
        let k = self.nodes.partition_point(|n| n.at <= p);
        let (node, offset) = if k == 0 { (first, None) } else { (&self.nodes[k - 1], Some(p - self.nodes[k - 1].at)) };
        let (value, slope) =
            if direction >= 0 { (node.forward, node.forward_slope) } else { (node.reverse, node.reverse_slope) };
        match (self.between, offset) {
            (Between::Linear, Some(offset)) => value + slope * offset,
            _ => value,
        }
    }

    /// The correction including the backlash compensation, as the control adds it to the
    /// command.
    pub fn total(&self, p: f64, direction: i8) -> f64 {
        self.correction(p, direction) + f64::from(direction.signum()) * self.backlash / 2.0
    }
}

/// A control's axis compensation, each axis it compensates.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ControlCompensation {
    pub x: Option<AxisCompensation>,
    pub z: Option<AxisCompensation>,
}

impl ControlCompensation {
    pub fn axis(&self, axis: Axis) -> Option<&AxisCompensation> {
        match axis {
            Axis::X => self.x.as_ref(),
            Axis::Z => self.z.as_ref(),
        }
    }
}

/// The machine with a control's table loaded: the terms the table works on, evaluated
/// where the corrected command puts the slide.
#[derive(Debug, Clone, PartialEq)]
pub struct ControlTerm {
    pub compensation: ControlCompensation,
    /// The model's terms of one axis' own position (`TablePart::Pitch`), with that axis.
    carried: Vec<(Axis, Effect)>,
    /// The slide tables' linear columns (X, Z), taken out of the slide tables.
    linear: [Option<Profile>; 2],
}

impl ControlTerm {
    /// The displacement of the carried terms at `s`, commanded through the table, plus the
    /// table's correction: what the table leaves of them, mm.
    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(self.axis_rest(Axis::X, s), self.axis_rest(Axis::Z, s))
    }

    fn axis_rest(&self, axis: Axis, s: &Sample) -> f64 {
        let (p, direction, profile) = match axis {
            Axis::X => (s.at.x, s.direction.x, &self.linear[0]),
            Axis::Z => (s.at.z, s.direction.z, &self.linear[1]),
        };
        let c = self.compensation.axis(axis).map_or(0.0, |table| table.correction(p, direction));
        let at = match axis {
            Axis::X => Xz::new(p + c, s.at.z),
            Axis::Z => Xz::new(s.at.x, p + c),
        };
        let shifted = Sample { at, ..*s };
        let mut rest = c + profile.as_ref().map_or(0.0, |profile| profile.at(p + c, direction));
        for (_, effect) in self.carried.iter().filter(|(a, _)| *a == axis) {
            let d = effect.displacement(&shifted);
            rest += match axis {
                Axis::X => d.x,
                Axis::Z => d.z,
            };
        }
        rest
    }

    /// The carried terms, for the spacing and arc terms of the model.
    pub(crate) fn carried(&self) -> impl Iterator<Item = &Effect> {
        self.carried.iter().map(|(_, effect)| effect)
    }
}

impl ErrorModel {
    /// This machine with the control's `compensation` loaded (module documentation).
    pub fn with_control(&self, mut compensation: ControlCompensation) -> ErrorModel {
        // A table's constant reversal part beyond the drive's play is no play it takes up but a
        // switched correction: kept with the nodes, so that the play the tracker runs is the
        // drive's less what the control takes up, never below it for that reason.
        for axis in [Axis::X, Axis::Z] {
            let play: f64 = self
                .effects
                .iter()
                .filter_map(|e| match e.control_table() {
                    TablePart::Backlash(a, b) if a == axis && b > 0.0 => Some(b),
                    _ => None,
                })
                .sum();
            let table = match axis {
                Axis::X => compensation.x.as_mut(),
                Axis::Z => compensation.z.as_mut(),
            };
            if let Some(table) = table.filter(|t| !t.nodes.is_empty() && t.backlash > play) {
                let shift = (table.backlash - play) / 2.0;
                for node in &mut table.nodes {
                    node.forward += shift;
                    node.reverse -= shift;
                }
                table.backlash = play;
            }
        }
        let mut carried = Vec::new();
        let mut effects = Vec::new();
        let mut play = [0.0f64; 2];
        for effect in &self.effects {
            match effect.control_table() {
                TablePart::Pitch(axis) => carried.push((axis, effect.clone())),
                TablePart::Backlash(axis, b) if compensation.axis(axis).is_some_and(|c| c.backlash != 0.0) => {
                    play[index(axis)] += b;
                }
                _ => effects.push(effect.clone()),
            }
        }
        for axis in [Axis::X, Axis::Z] {
            let Some(table) = compensation.axis(axis).filter(|c| c.backlash != 0.0) else { continue };
            let rest = play[index(axis)] - table.backlash;
            if rest != 0.0 {
                effects.push(match axis {
                    Axis::X => Effect::BacklashX(Backlash { b: rest, axis: X }),
                    Axis::Z => Effect::BacklashZ(Backlash { b: rest, axis: Z }),
                });
            }
        }
        let mut tables = self.tables.clone();
        let mut linear = [None, None];
        if let Some(tables) = tables.as_mut() {
            if compensation.x.is_some() {
                linear[0] = tables.x.linear.take();
            }
            if compensation.z.is_some() {
                linear[1] = tables.z.linear.take();
            }
        }
        ErrorModel {
            tables,
            effects,
            start_min: self.start_min,
            control: Some(Box::new(ControlTerm { compensation, carried, linear })),
        }
    }

    /// The loaded control table, when the model is of a machine with one.
    pub fn control(&self) -> Option<&ControlCompensation> {
        self.control.as_ref().map(|term| &term.compensation)
    }
}

fn index(axis: Axis) -> usize {
    match axis {
        Axis::X => 0,
        Axis::Z => 1,
    }
}

#[cfg(test)]
mod tests;
