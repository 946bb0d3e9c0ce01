//! What measurement would show what this one cannot: for candidates the data cannot tell
//! apart (confounded), and for effects the set-up terms absorb. Written for the machinist
//! who has to go and make that measurement.

use super::measured::Kind;

/// What measurement would tell confounded candidates apart, after a measurement of `kind`.
pub fn separate_by(effects: &[&str], kind: Kind) -> String {
    let has = |name: &str| effects.contains(&name);
    let any = |names: &[&str]| names.iter().any(|n| has(n));
    let mut out: Vec<&str> = Vec::new();
    if has("squareness") && has("servo_mismatch") {
        out.push(
            "a ball bar run in both directions (CW and CCW): squareness keeps its sign, servo mismatch flips with \
             the direction (and grows with the feed)",
        );
    }
    if any(&["thermal_x", "thermal_z"])
        && any(&["scale_x", "scale_z", "squareness", "straightness_x", "straightness_z"])
    {
        out.push(
            "the same path again later in the warm-up, or run in the reverse order: a thermal drift follows the \
             clock, a scale or squareness error the position",
        );
    }
    if any(&["thermal_x", "thermal_z"]) && has("tool_wear") {
        out.push("parts made at uneven intervals or after a tool change: wear follows the cut length, thermal growth the clock");
    }
    if (has("tool_offset_x") && has("backlash_x")) || (has("tool_offset_z") && has("backlash_z")) {
        out.push(
            "a path that reverses the axis (a ball bar circle, or a profile that turns back): backlash changes \
             sign at a reversal, a tool offset does not",
        );
    }
    if has("scale_x") && has("scale_z") {
        out.push(match kind {
            Kind::BallBar => {
                "a CMM profile with diameters and lengths, or interferometer runs: a ball bar sees only the \
                 mismatch of the two scales"
            }
            Kind::Profile | Kind::Table(_) => {
                "a part with diameters and faces spread over X and Z, or interferometer runs"
            }
        });
    }
    if any(&["cyclic_x", "cyclic_z"]) && any(&["scale_x", "scale_z", "straightness_x", "straightness_z", "squareness"])
    {
        out.push(
            "a run with targets not spaced at a multiple of the screw's lead, and a fine-step run over two leads \
             (ISO 230-2 Annex C): a cyclic error read at a spacing near its pitch aliases to a slow slope",
        );
    }
    if has("nose_radius") && any(&["tool_offset_x", "tool_offset_z"]) {
        out.push("a part with diameters and faces beside arcs or tapers: a nose-radius error vanishes on diameters and faces");
    }
    if has("tool_wear") && any(&["tool_offset_x", "scale_x"]) {
        out.push("several parts cut one after another with the same tool: wear grows with the cut length");
    }
    if out.is_empty() {
        out.push(
            "a measurement in which their signatures differ: another path, the other direction, or the same test \
             repeated at another time",
        );
    }
    out.join("; ")
}

/// Which measurement would show an effect that this one's set-up terms absorb.
pub fn shown_by(effect: &str, kind: Kind) -> &'static str {
    match (effect, kind) {
        ("tool_offset_z", _) => {
            "a Z length from a face this program does not cut (the chuck face or a tool setter) shows it"
        }
        ("tool_offset_x", Kind::BallBar) => "a CMM profile (a diameter) shows it",
        ("tool_offset_x", Kind::Table(_)) => "a cut part shows it",
        ("backlash_x", _) => "a path that reverses X shows it",
        ("backlash_z", _) => "a path that reverses Z shows it",
        ("squareness", Kind::Table(_)) => "a ball bar, or a straightness run against a square, shows it",
        _ => "another path or test shows it",
    }
}
