//! What the compensation unit tests share: a metric Fanuc program lowered on a machine
//! whose home is known.

use crate::dialect::{DialectChoice, GCodeSystem};
use crate::machine::{AxisPair, MachineSettings};
use crate::pipeline::{Analysed, Ready, Settings, analyse};
use crate::semantic::{LowerOptions, Lowered, Machine};
use crate::syntax::ParseOptions;
use crate::toolpath::Validated;

/// `program` (G-code system A) through the pipeline, with the home at X200 (diameter) Z50.
pub fn analysed(program: &str) -> Analysed<'_> {
    let options = ParseOptions {
        dialect: DialectChoice::Auto,
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    let settings = MachineSettings { home: Some(AxisPair { x: 200.0, z: 50.0 }), ..MachineSettings::default() };
    analyse(program.as_bytes(), &Settings::new(options, &settings, LowerOptions::new(false)))
}

/// [`analysed`] for a program that must read and lower without errors, its toolpath valid.
pub fn ready(program: &str) -> Ready<'_> {
    match analysed(program).ready() {
        Ok(ready) => ready,
        Err(analysed) => panic!("the test program does not lower cleanly: {:?}", analysed.diagnostics),
    }
}

/// The lowered program and the machine of [`ready`].
pub fn lower_program(program: &str) -> (Validated<Lowered>, Machine) {
    let ready = ready(program);
    (ready.lowered, ready.machine)
}
