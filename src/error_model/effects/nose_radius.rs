//! `nose_radius {dr}`: the tool's nose radius is `dr` larger than the tool table says. The
//! tool is set on its imaginary tip, so the nose centre sits `dr` further back along the tip
//! direction and the cut point moves by `−dr · (tip + n)`, n the surface normal: nothing on
//! a diameter or a face, `0.414 · dr` off the surface on a 45° chamfer.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Range};
use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NoseRadius {
    /// Nose radius error, mm.
    pub dr: f64,
}

/// Plausible `dr`: within ±1 mm. Nose radii are 0.1 to 2.4 mm, and an error is a
/// fraction of one.
pub const DR: Range = Range::magnitude(1.0, "mm");

impl NoseRadius {
    /// The parameters against their plausible ranges (checked when a model file is read).
    pub fn check(&self) -> Result<(), Invalid> {
        DR.check_key("dr", self.dr)
    }

    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(-self.dr * (s.tip.x + s.normal.x), -self.dr * (s.tip.z + s.normal.z))
    }
}
