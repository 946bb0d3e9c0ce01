//! OSP LAP `G87 N<name>`: finish turning. One pass along the contour as it is written: the
//! approach block from the AP start point, then every element with the `F` and `S` written
//! inside the contour (modal there; the feed in force where the contour sets none) and its
//! own `G41`/`G42`/`G40`. The tool stays at the contour's end: unlike `G85`/`G86`, the
//! finishing call has no return to the AP start point in our reading. No retrieved manual
//! page says which it is, and the one real program decides it: OSP7000L follows each of its
//! four `G87` calls with its own short retract from the contour's end (`N0825 G01 X72.22
//! Z173.9` after a contour that ends at X72.02 Z175, then `G00 X88`); with a return to the
//! start those blocks would be feeds of up to 232 mm back across the part. The call block
//! takes nothing but the contour's name (M-P218); the contour may be shared with a
//! `G85`/`G86` that roughed it with another tool.

use crate::syntax::Command;

use super::super::interpreter::{Flow, Interpreter};
use super::lap_contour;

pub(super) fn run(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command) -> Flow {
    let Some((_, contour)) = lap_contour::call(interp, index, command) else { return Flow::Next };
    interp.trace_profile(&contour.profile, None);
    // The contour ends its own compensation (`G40` after the last move), and the blocks
    // after the call run in that state.
    interp.modal.compensation = contour.profile.modal_after.compensation;
    contour.consume(interp);
    contour.flow_after()
}
