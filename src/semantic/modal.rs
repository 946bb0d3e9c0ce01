//! Modal state: what a control remembers from block to block.

use crate::toolpath::{Compensation, Xz};

use super::frame::Frame;

/// The motion a block with axis words but no motion code performs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MotionMode {
    Rapid,
    Linear,
    Cw,
    Ccw,
    /// Fanuc `G32`/`G33`: a thread-cutting move.
    Thread,
    /// Fanuc `G34`: a thread-cutting move whose lead changes by `K` every spindle turn.
    VariableLeadThread,
    /// Fanuc single cycles repeat on later blocks that give new end points.
    TurningCycle,
    ThreadCycle,
    FacingCycle,
    /// A drilling cycle (group 10) repeats at the hole positions of later blocks.
    Drilling,
}

/// Spindle speed mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpindleMode {
    /// `G97 S`: revolutions per minute.
    Rpm,
    /// `G96 S`: constant surface speed, in program units per minute (m/min or ft/min).
    SurfaceSpeed,
}

/// The tool in the turret and what the tool table says about it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToolState {
    pub station: u16,
    pub offset: u16,
    /// Nose radius, mm (0 when the table has no entry).
    pub nose_radius: f64,
    /// Imaginary tip direction 0-9.
    pub tip: u8,
    /// Minor cutting edge angle, degrees, when the table gives it.
    pub minor_edge_angle: Option<f64>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Modal {
    pub frame: Frame,
    /// Absolute coordinates (`G90` on OSP and Fanuc systems B/C); Fanuc system A uses U/W.
    pub absolute: bool,
    /// Feed per revolution (`G99`/`G95`) or per minute (`G98`/`G94`).
    pub feed_per_rev: bool,
    /// The programmed feed, program units per revolution or per minute.
    pub feed: f64,
    pub spindle: SpindleMode,
    /// `S` as programmed: rpm, or surface speed under `G96`.
    pub speed: f64,
    /// Spindle speed clamp, rpm (`G50 S`, `G92 S`), and the machine's own top speed.
    pub clamp: f64,
    /// The program has set the clamp (`G50 S`, `G92 S`).
    pub clamp_programmed: bool,
    /// What constant surface speed reaches when neither the program nor the settings
    /// limit the spindle: `Machine::spindle_limit`.
    pub spindle_limit: f64,
    pub motion: MotionMode,
    pub compensation: Compensation,
    pub tool: ToolState,
    /// Toolpath frame minus program coordinates, set by `G50 X Z`, mm: the tool's position
    /// lives in the emitter, in the toolpath frame.
    pub shift: Xz,
}

impl Modal {
    /// Spindle speed at radius `x_mm`: the programmed rpm, or under constant surface speed
    /// `v / (2π r)`, never above the clamp.
    pub fn rpm_at(&self, x_mm: f64) -> f64 {
        match self.spindle {
            SpindleMode::Rpm => self.speed.min(self.clamp),
            SpindleMode::SurfaceSpeed => self.surface_speed().rpm_at(x_mm),
        }
    }

    /// The constant surface speed in force, as `rpm_at` uses it under `G96`.
    pub fn surface_speed(&self) -> SurfaceSpeed {
        let clamp = if self.clamp.is_finite() { self.clamp } else { self.spindle_limit };
        SurfaceSpeed { mm_per_min: self.frame.surface_speed_mm_min(self.speed), clamp }
    }
}

/// What the spindle speed under constant surface speed depends on, apart from the rest of
/// the modal state (arcs are timed on another thread with it, `emitter::ArcJob`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceSpeed {
    pub mm_per_min: f64,
    /// Spindle speed clamp, rpm.
    pub clamp: f64,
}

impl SurfaceSpeed {
    /// Spindle speed at radius `x_mm`: `v / (2π r)`, never above the clamp.
    pub fn rpm_at(self, x_mm: f64) -> f64 {
        let r = x_mm.abs();
        if r < 1e-9 { self.clamp } else { (self.mm_per_min / (std::f64::consts::TAU * r)).min(self.clamp) }
    }
}
