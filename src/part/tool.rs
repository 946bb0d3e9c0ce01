//! The shape a tool of the tool table cuts with, placed at the IR's reference point.
//!
//! A tool is a nose (a disk of the nose radius; none for a point) grown from a convex core
//! placed about the nose centre: the insert behind the nose. The reference point the IR
//! moves is the imaginary tip (`semantic::nose_radius`): the nose centre is the reference
//! point less the nose radius times the tip vector.
//!
//! - **Turning** (and boring): the core is a square of side [`BODY_MM`] (or the tool's
//!   `max_depth`, if larger) reaching from the nose centre away from the tip (tip 3 reaches
//!   toward +X and +Z); for a tip along an axis (5–8) a line of that length, so the insert is
//!   a slot twice the nose radius wide.
//! - **Grooving** with a `width`: the core reaches from the reference corner's nose centre to
//!   the other corner's along Z, and up from there by the body's length: a rectangle with
//!   rounded corners, as wide as the insert.
//! - **Threading**: a V of the included angle, its apex at the nose centre, opening away
//!   from the part: along X for a thread on a diameter, along Z for a thread on a face
//!   (tips 7 and 5); the reference point is the V's tip.
//!   A tool the table gives without a `kind` is one where it cuts a thread pass
//!   (`removal::Removal::tool`): a thread is the insert's form stamped once per lead.
//! - **Drill**: a rectangle of the drill's diameter on its axis, reaching back along +Z (its
//!   flutes), square at its end.
//!
//! A tool whose tip direction is not in the table (0, 9, or no entry) has no side of its
//! own; it is taken as an outside tool (tip 3's body) unless its first cut lies nearer a
//! bore than the outside, when it is a boring tool (tip 2's): [`Orientation`].

use smallvec::SmallVec;

use super::sweep::Insert;
use crate::machine::{ToolKind, ToolSettings};
use crate::semantic::Machine;
use crate::semantic::nose_radius::tip_vector;
use crate::toolpath::Xz;

/// How far an insert's body reaches behind its nose when the tool table says nothing of it,
/// mm: the cutting edge a common 12 mm insert engages.
pub const BODY_MM: f64 = 6.0;

/// Which side of the part a tool works from, where its tip direction does not say.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Orientation {
    Outside,
    Inside,
}

/// A tool's cutting shape, about its nose centre.
#[derive(Debug, Clone, PartialEq)]
pub struct Tool {
    pub kind: ToolKind,
    /// The nose radius, mm (0 for a point or a drill).
    pub nose: f64,
    /// The nose centre less the reference point, mm.
    pub centre_offset: Xz,
    /// The core about the nose centre: the insert behind the nose.
    pub core: SmallVec<[Xz; 4]>,
    /// The deepest cut it takes, mm.
    pub max_depth: Option<f64>,
    /// Whether its orientation came from the table (else it was inferred).
    pub oriented: bool,
    /// The core grown by the nose, as an arc move sweeps it.
    pub(crate) insert: Insert,
}

/// The table's entry of a tool, as `simulate`'s summary finds it.
pub fn entry(machine: &Machine, station: u16, offset: u16) -> Option<&ToolSettings> {
    machine
        .tools
        .iter()
        .find(|t| t.station as u16 == station && t.offset.unwrap_or(t.station) as u16 == offset)
        .or_else(|| machine.tools.iter().find(|t| t.station as u16 == station))
}

impl Tool {
    /// Whether the table's tip direction says which side the tool works from.
    pub fn knows_its_side(settings: Option<&ToolSettings>) -> bool {
        settings.is_some_and(|t| (1..=8).contains(&t.tip))
    }

    /// The shape of the tool `settings` describe (none: a point turning tool), in mm, its
    /// side `orientation` where the table does not give it; the body reaches to at least
    /// `reach` for a drill (the stock's length).
    pub fn new(settings: Option<&ToolSettings>, machine: &Machine, orientation: Orientation, reach: f64) -> Tool {
        let scale = machine.scale();
        let kind = settings.and_then(|t| t.kind).unwrap_or_default();
        let nose = settings.map_or(0.0, |t| t.nose_radius * scale);
        let max_depth = settings.and_then(|t| t.max_depth).map(|d| d * scale);
        let body = max_depth.unwrap_or(0.0).max(BODY_MM);
        let oriented = Tool::knows_its_side(settings);
        let tip = match settings.map(|t| t.tip) {
            Some(tip @ 1..=8) => tip,
            _ => match orientation {
                Orientation::Outside => 3,
                Orientation::Inside => 2,
            },
        };
        let vector = tip_vector(tip);
        // Away from the tip: where the insert is.
        let (ax, az) = (-vector.x, -vector.z);
        let offset_of = |v: Xz| Xz::new(-nose * v.x, -nose * v.z);
        let mut core: SmallVec<[Xz; 4]> = SmallVec::new();
        let centre_offset;
        match kind {
            ToolKind::Turning => {
                // A tool given with no tip direction is programmed at its nose centre.
                centre_offset = if oriented { offset_of(vector) } else { Xz::new(0.0, 0.0) };
                core.push(Xz::new(0.0, 0.0));
                if ax != 0.0 && az != 0.0 {
                    core.extend([Xz::new(body * ax, 0.0), Xz::new(body * ax, body * az), Xz::new(0.0, body * az)]);
                } else {
                    core.push(Xz::new(body * ax, body * az));
                }
            }
            ToolKind::Grooving => {
                centre_offset = if oriented { offset_of(vector) } else { Xz::new(0.0, 0.0) };
                let across = settings.and_then(|t| t.width).map_or(0.0, |w| (w * scale - 2.0 * nose).max(0.0));
                let (from, to) = match vector.z {
                    z if z < 0.0 => (0.0, across),
                    z if z > 0.0 => (-across, 0.0),
                    _ => (-across / 2.0, across / 2.0),
                };
                let up = if ax != 0.0 { body * ax } else { body };
                core.extend([Xz::new(0.0, from), Xz::new(0.0, to), Xz::new(up, to), Xz::new(up, from)]);
            }
            ToolKind::Threading => {
                // The V opens away from its tip: along X for a thread on a diameter (tip 8
                // outside, 6 inside), along Z for one on a face (tip 7 on a face toward the
                // chuck, 5 on one facing away); otherwise the side the part model takes it on.
                let opening = match (settings.map(|t| t.tip), orientation) {
                    (Some(5..=8), _) => Xz::new(ax, az),
                    (_, Orientation::Inside) => Xz::new(-1.0, 0.0),
                    (_, Orientation::Outside) => Xz::new(1.0, 0.0),
                };
                centre_offset = Xz::new(nose * opening.x, nose * opening.z);
                let half = settings.and_then(|t| t.angle).unwrap_or(60.0).to_radians() / 2.0;
                let wide = body * half.tan();
                let across = Xz::new(opening.z * wide, opening.x * wide);
                let (deep_x, deep_z) = (body * opening.x, body * opening.z);
                core.extend([
                    Xz::new(0.0, 0.0),
                    Xz::new(deep_x - across.x, deep_z - across.z),
                    Xz::new(deep_x + across.x, deep_z + across.z),
                ]);
            }
            ToolKind::Drill => {
                centre_offset = Xz::new(0.0, 0.0);
                let half = settings.and_then(|t| t.diameter).unwrap_or(0.0) * scale / 2.0;
                let back = reach.max(body);
                core.extend([Xz::new(-half, 0.0), Xz::new(half, 0.0), Xz::new(half, back), Xz::new(-half, back)]);
            }
        }
        let nose = if kind == ToolKind::Drill { 0.0 } else { nose };
        let insert = Insert::new(core.iter().copied(), nose);
        Tool { kind, nose, centre_offset, core, max_depth, oriented, insert }
    }

    /// The nose centre when the reference point is at `reference`.
    pub fn centre(&self, reference: Xz) -> Xz {
        Xz::new(reference.x + self.centre_offset.x, reference.z + self.centre_offset.z)
    }

    /// The core's points with the nose centre at `centre`.
    pub fn placed(&self, centre: Xz) -> impl Iterator<Item = Xz> + '_ {
        self.core.iter().map(move |p| Xz::new(centre.x + p.x, centre.z + p.z))
    }
}
