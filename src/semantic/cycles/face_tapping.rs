//! Tapping along Z on the face: Fanuc `G84`, Haas `G84`. The tool
//! rapids to the hole's X at the level it is at and to the R point, taps to the bottom with the feed tied to the
//! spindle (under `G99` `F` is the lead; under `G98` the lead is `F` over the spindle
//! speed), dwells `P` if given, the spindle reverses and the tap backs out to the R point
//! the same way, then rapids to the return level (`drilling.rs`). Sources: the `G84`
//! entries of `grammar/fanuc.toml`. The tap's moves are thread moves, as OSP tapping's
//! (`tapping.rs`).

use super::super::interpreter::Interpreter;
use super::drilling::Hole;

pub(super) fn cut(interp: &mut Interpreter<'_, '_>, hole: &Hole) -> bool {
    let modal = interp.modal.clone();
    let feed_mm = modal.frame.feed_mm(modal.feed);
    let lead_mm = if modal.feed_per_rev {
        feed_mm
    } else {
        let rpm = modal.rpm_at(hole.at);
        if rpm > 0.0 { feed_mm / rpm } else { 0.0 }
    };
    let e = &mut interp.emitter;
    // To the hole's line at the level the tool is at (the R point after a `G99` hole).
    e.rapid(&modal, hole.at_z(e.at.z));
    e.rapid(&modal, hole.at_z(hole.r_point));
    e.thread(&modal, hole.at_z(hole.bottom), lead_mm);
    if hole.dwell_seconds > 0.0 {
        e.dwell(&modal, hole.dwell_seconds);
    }
    e.thread(&modal, hole.at_z(hole.r_point), lead_mm);
    e.rapid(&modal, hole.end());
    true
}
