//! Boring along Z on the face: Fanuc `G85`, Haas `G85`-`G89`. The
//! tool rapids to the hole's X at the level it is at and to the R point, feeds to the bottom, dwells `P` if
//! given, and leaves the hole as the code's `retract` says (`grammar/fanuc.toml`, with the
//! sources): at the feed to the R point (Fanuc `G85`, Haas `G85`, `G89`), or with the
//! spindle stopped at the rapid rate (Haas `G86`), then to the return level
//! (`drilling.rs`); or it stops at the bottom for the operator to jog it out (Haas `G87`,
//! `G88`): the toolpath cannot follow a hand, so it takes the tool out along the hole at
//! the rapid rate, and a warning says so.

use crate::diagnostic::DiagnosticKind;
use crate::dialect::{DrillRetract, DrillingFacts};
use crate::source::Span;

use super::super::interpreter::Interpreter;
use super::drilling::Hole;

pub(super) fn cut(interp: &mut Interpreter<'_, '_>, facts: DrillingFacts, hole: &Hole, span: Span) -> bool {
    let modal = interp.modal.clone();
    let e = &mut interp.emitter;
    // To the hole's line at the level the tool is at (the R point after a `G99` hole).
    e.rapid(&modal, hole.at_z(e.at.z));
    e.rapid(&modal, hole.at_z(hole.r_point));
    e.line(&modal, hole.at_z(hole.bottom), true);
    if hole.dwell_seconds > 0.0 {
        e.dwell(&modal, hole.dwell_seconds);
    }
    match facts.retract {
        DrillRetract::Feed => {
            e.line(&modal, hole.at_z(hole.r_point), true);
            e.rapid(&modal, hole.end());
        }
        DrillRetract::Rapid | DrillRetract::SpindleStopRapid | DrillRetract::Reverse => e.rapid(&modal, hole.end()),
        DrillRetract::Manual => {
            // The operator jogs the tool out; the toolpath takes it out along the hole.
            e.rapid(&modal, hole.end());
            interp.warning(DiagnosticKind::ManualRetract, span);
        }
    }
    true
}
