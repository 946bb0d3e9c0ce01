//! Drilling, tapping and boring along X on the side of the part: Fanuc `G87`, `G88`, `G89`
//! (`grammar/fanuc.toml`). A live tool drills across the axis at the C angle the part is
//! turned to, off the XZ plane the toolpath of a turned part lies in; the error model and
//! compensation are of that plane. The cycle is said so and its moves are left out: the
//! tool is taken to be back at the initial level when it ends, as it is.

use crate::diagnostic::DiagnosticKind;
use crate::source::Span;

use super::super::interpreter::Interpreter;

pub(super) fn cut(interp: &mut Interpreter<'_, '_>, span: Span) -> bool {
    let code = interp.cycle_memory.drilling.cycle.map_or(String::new(), |m| m.code.display('G'));
    interp.warning(DiagnosticKind::CycleOutOfPlane { code }, span);
    false
}
