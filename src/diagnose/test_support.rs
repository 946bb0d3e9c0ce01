//! Programs for the unit tests of the discrepancy workflow.

use crate::diagnose::forward::Nominal;
use crate::dialect::{DialectChoice, GCodeSystem};
use crate::machine::{AxisPair, MachineSettings, ToolSettings};
use crate::pipeline::{Settings, analyse};
use crate::semantic::LowerOptions;
use crate::syntax::ParseOptions;

/// A ball bar test on a lathe: a 50 mm circle about x 50 z −50, run G03 then G02 at
/// 1000 mm/min, starting and ending at the top of the circle (angle 0, +Z).
pub const BALL_BAR: &str = "\
G21 G98
T0100
G00 X100. Z5.
G01 X100. Z0. F500.
G03 X100. Z0. I0. K-50. F1000.
G02 X100. Z0. I0. K-50.
G00 X150. Z20.
M30
";

/// A turned part: a 20 mm radius dome from the pole, a cylinder and a shoulder, finished
/// under G42 with a 0.8 mm nose (tip 3).
pub const DOME: &str = "\
G21 G99
T0101
G97 S1000 M03
G00 X60. Z2.
G42 G01 X0. Z0. F0.1
G03 X40. Z-20. R20.
G01 Z-40.
X60.
G40 G00 X80. Z5.
M30
";

pub fn settings() -> MachineSettings {
    MachineSettings {
        home: Some(AxisPair { x: 200.0, z: 50.0 }),
        tool: vec![ToolSettings {
            station: 1,
            offset: Some(1),
            x: 0.0,
            z: 0.0,
            nose_radius: 0.8,
            tip: 3,
            minor_edge_angle: None,
            kind: None,
            angle: None,
            diameter: None,
            width: None,
            max_depth: None,
        }],
        ..MachineSettings::default()
    }
}

pub fn nominal(text: &str) -> Nominal {
    let options = ParseOptions {
        dialect: DialectChoice::Auto,
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    let analysed = analyse(text.as_bytes(), &Settings::new(options, &settings(), LowerOptions::new(false)));
    match analysed.ready() {
        Ok(ready) => Nominal::new(ready.program(), &ready.lowered, &ready.machine),
        Err(analysed) => panic!("the test program does not lower cleanly: {:?}", analysed.diagnostics),
    }
}
