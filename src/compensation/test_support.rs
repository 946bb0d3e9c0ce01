//! What the compensation unit tests share: a metric Fanuc program lowered on a machine
//! whose home is known.

use crate::dialect::{DialectChoice, GCodeSystem};
use crate::machine::{AxisPair, MachineSettings};
use crate::semantic::{LowerOptions, Lowered, Machine, lower};
use crate::syntax::{ParseOptions, parse};

/// `program` (G-code system A) lowered with the home at X200 (diameter) Z50; it must read
/// and lower without errors.
pub fn lower_program(program: &str) -> (Lowered, Machine) {
    let options = ParseOptions {
        dialect: DialectChoice::Auto,
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    let parsed = parse(program.as_bytes(), &options);
    assert_eq!(parsed.error_count(), 0);
    let settings = MachineSettings { home: Some(AxisPair { x: 200.0, z: 50.0 }), ..MachineSettings::default() };
    let machine = Machine::from_settings(&settings);
    let lowered = lower(&parsed.program, &machine, &LowerOptions::new(false));
    assert!(lowered.diagnostics.iter().all(|d| !d.is_error()));
    (lowered, machine)
}
