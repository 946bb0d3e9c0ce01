//! `nose_radius {dr}`: the tool's nose radius is `dr` larger than the tool table says. The
//! tool is set on its imaginary tip, so the nose centre sits `dr` further back along the tip
//! direction and the cut point moves by `−dr · (tip + n)`, n the surface normal: nothing on
//! a diameter or a face, `0.414 · dr` off the surface on a 45° chamfer.

use serde::{Deserialize, Serialize};

use crate::error_model::Sample;
use crate::toolpath::Xz;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NoseRadius {
    /// Nose radius error, mm.
    pub dr: f64,
}

impl NoseRadius {
    pub fn displacement(&self, s: &Sample) -> Xz {
        Xz::new(-self.dr * (s.tip.x + s.normal.x), -self.dr * (s.tip.z + s.normal.z))
    }
}
