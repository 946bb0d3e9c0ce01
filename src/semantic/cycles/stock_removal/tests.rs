//! The cycle's work is counted, not timed: how many stretches cut before a pass its
//! questions look at (`Cleared::highest_at_or_below`).

use std::cell::Cell;

use crate::dialect::{DialectChoice, GCodeSystem};
use crate::machine::MachineSettings;
use crate::semantic::{LowerOptions, Machine, lower};
use crate::syntax::{ParseOptions, parse};

thread_local! {
    /// Stretches looked at by the questions asked on this thread, and the bisection steps
    /// that found them.
    static LOOKED_AT: Cell<usize> = const { Cell::new(0) };
}

/// A question about the stretches cut so far (`cut` of them) looked at `found`.
pub(super) fn count_looked_at(cut: usize, found: usize) {
    let bisection = (usize::BITS - cut.leading_zeros()) as usize;
    LOOKED_AT.with(|n| n.set(n.get() + bisection + found));
}

/// 10,000 passes at a depth of one increment: every pass asks a few questions, each of
/// which looks at the one stretch under the tool and finds it by bisection; a question that
/// scanned every stretch cut before it would look at about 50 million.
#[test]
fn ten_thousand_passes_look_at_a_few_stretches_each() {
    let source = include_bytes!("../../../../tests/cases/bounded/g71-ten-thousand-passes.nc");
    let options = ParseOptions {
        dialect: DialectChoice::Fixed(crate::dialect::Dialect::Fanuc),
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    let parsed = parse(source, &options);
    assert!(parsed.diagnostics.is_empty(), "{:?}", parsed.diagnostics);
    let machine = Machine::from_settings(&MachineSettings::default());
    LOOKED_AT.with(|n| n.set(0));
    let lowered = lower(&parsed.program, &machine, &LowerOptions::new(false));
    assert!(lowered.diagnostics.iter().all(|d| !d.is_error()), "{:?}", lowered.diagnostics);
    let passes = lowered.toolpath.moves.iter().filter(|m| m.cutting && m.end.z < -19.9 && m.end.z > -20.1).count();
    assert!(passes >= 9_999, "{passes} passes reach the shoulder");
    let looked_at = LOOKED_AT.with(Cell::get);
    assert!(looked_at <= 50 * passes, "{looked_at} stretches looked at for {passes} passes");
}
