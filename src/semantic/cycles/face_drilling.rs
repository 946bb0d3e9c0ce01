//! Drilling along Z on the face: Fanuc `G83`, Haas `G81` (drill), `G82` (with a dwell) and
//! `G83` (peck). The tool rapids to the hole's X at the level it is at, then to the R
//! point, feeds to the bottom, dwells `P` there if given, and rapids back to the return
//! level (`drilling.rs`). With pecks (`Q`, Haas `I J K`) it feeds one peck at a time: a
//! Fanuc high-speed peck backs off a little after each one and feeds on, a Haas peck
//! rapids out to the R point and back down to just above the last depth. The facts and
//! their sources are the `G83` and `G81`-`G83` entries of `grammar/fanuc.toml`.

use crate::diagnostic::DiagnosticKind;
use crate::dialect::{DrillPeck, DrillingFacts};
use crate::source::Span;

use super::super::interpreter::Interpreter;
use super::MAX_CYCLE_PASSES;
use super::drilling::{FULL_PECK_CLEARANCE_MM, HIGH_SPEED_PECK_RETRACT_MM, Hole, Pecks};

/// Drill `hole`; `false` when its pecks are more than the simulation runs (reported).
pub(super) fn cut(interp: &mut Interpreter<'_, '_>, facts: DrillingFacts, hole: &Hole, span: Span) -> bool {
    let Some(depths) = hole.peck_depths() else {
        interp.error(DiagnosticKind::CycleTooManyPasses { passes: MAX_CYCLE_PASSES + 1, max: MAX_CYCLE_PASSES }, span);
        return false;
    };
    let modal = interp.modal.clone();
    let e = &mut interp.emitter;
    // To the hole's line at the level the tool is at (the R point after a `G99` hole).
    e.rapid(&modal, hole.at_z(e.at.z));
    e.rapid(&modal, hole.at_z(hole.r_point));
    let direction = (hole.bottom - hole.r_point).signum();
    let mut reached = hole.r_point;
    for (n, &depth) in depths.iter().enumerate() {
        if n > 0 && hole.pecks != Pecks::None {
            match facts.peck {
                Some(DrillPeck::HighSpeed) => {
                    e.rapid(&modal, hole.at_z(reached - direction * HIGH_SPEED_PECK_RETRACT_MM));
                }
                Some(DrillPeck::Full) | None => {
                    e.rapid(&modal, hole.at_z(hole.r_point));
                    e.rapid(&modal, hole.at_z(reached - direction * FULL_PECK_CLEARANCE_MM));
                }
            }
        }
        e.line(&modal, hole.at_z(depth), true);
        reached = depth;
    }
    if hole.dwell_seconds > 0.0 {
        e.dwell(&modal, hole.dwell_seconds);
    }
    e.rapid(&modal, hole.end());
    true
}
