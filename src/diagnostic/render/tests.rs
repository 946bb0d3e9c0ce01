//! Locating diagnostics is counted, not timed: how many line starts and bytes the
//! locations of a program's diagnostics look at.

use std::cell::Cell;

use super::*;
use crate::dialect::{Dialect, DialectChoice, GCodeSystem};
use crate::syntax::{ParseOptions, parse};

thread_local! {
    static LOOKED_AT: Cell<usize> = const { Cell::new(0) };
}

/// A location bisected `lines` line starts and counted the characters of `bytes` bytes of
/// its line.
pub(super) fn count_looked_at(lines: usize, bytes: usize) {
    let bisection = (usize::BITS - lines.leading_zeros()) as usize;
    LOOKED_AT.with(|n| n.set(n.get() + bisection + bytes));
}

/// `check --format json` of a program with an error on each of its 2,000 lines: each
/// diagnostic's range looks at its own line and a bisection of the line starts, about 60
/// bytes, where a pass over the text for each would look at 2,000 times its 60 KB.
#[test]
fn json_of_an_error_on_every_line_looks_at_each_line_once() {
    let source = include_bytes!("../../../tests/cases/bounded/check-an-error-on-every-line.nc");
    let options = ParseOptions {
        dialect: DialectChoice::Fixed(Dialect::Fanuc),
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    let parsed = parse(source, &options);
    assert_eq!(parsed.error_count(), 2000);
    LOOKED_AT.with(|n| n.set(0));
    let json = to_json(&RenderSource::new("many.nc", source), &parsed.diagnostics);
    assert_eq!(json.len(), 2000);
    assert_eq!((json[1999].range.start.line, json[1999].range.start.column), (2002, 30));
    let looked_at = LOOKED_AT.with(Cell::get);
    assert!(looked_at <= 4 * source.len(), "{looked_at} bytes looked at for a text of {}", source.len());
}
