//! What the compensation unit tests share: a metric Fanuc program lowered on a machine
//! whose home is known.

use crate::dialect::{DialectChoice, GCodeSystem};
use crate::machine::{AxisPair, MachineSettings};
use crate::pipeline::{Settings, analyse};
use crate::semantic::{LowerOptions, Lowered, Machine};
use crate::syntax::ParseOptions;
use crate::toolpath::Validated;

/// `program` (G-code system A) lowered with the home at X200 (diameter) Z50; it must read
/// and lower without errors, and its toolpath must validate.
pub fn lower_program(program: &str) -> (Validated<Lowered>, Machine) {
    let options = ParseOptions { dialect: DialectChoice::Auto, gcode_system: GCodeSystem::A, machine_kind: None };
    let settings = MachineSettings { home: Some(AxisPair { x: 200.0, z: 50.0 }), ..MachineSettings::default() };
    let analysed = analyse(program.as_bytes(), &Settings::new(options, &settings, LowerOptions::new(false)));
    match analysed.ready() {
        Ok(ready) => (ready.lowered, ready.machine),
        Err(analysed) => panic!("the test program does not lower cleanly: {:?}", analysed.diagnostics),
    }
}
