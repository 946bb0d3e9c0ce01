//! The homogeneous transformation of the thesis (eq. 8.6–8.12) for a two-slide lathe: the
//! carriage moves along Z and carries the cross slide, which moves along X.
//!
//! * X slide (cross slide), functions of x: linear error Δx, straightness δ'_Xz (its
//!   deviation in Z while it travels in X), pitch ε_z.
//! * Z slide (carriage), functions of z: linear error Δz, straightness δ'_Zx (its
//!   deviation in X while it travels in Z), yaw ε_x.
//!
//! The total error matrix (eq. 8.11) applied to the tool point (x, y, z, 1) — eq. 8.12
//! prints a 0 for the last coordinate, which would drop every translation, and is read as
//! the homogeneous 1 — gives, less the commanded point:
//!
//! ```txt
//! dx = Δx + δ'_Zx(z) − ε_z·y + ε_x·ε_z·(z + Δz)
//! dz = Δz + δ'_Xz(x) + ε_x·y
//! ```
//!
//! with y the tool point's offset from the slides' measuring line along Y (the Abbe offset,
//! `abbe_y_mm`, zero for a tool on centre). With y = 0 the angular errors enter only
//! through their product. Each slide's errors are those of the direction it last moved in.

use crate::error_model::Sample;
use crate::error_model::interferometer::SlideTable;
use crate::toolpath::Xz;

#[derive(Debug, Clone, PartialEq, Default)]
pub struct AxisTables {
    pub x: SlideTable,
    pub z: SlideTable,
    /// The tool point's offset along Y from the measuring line, mm.
    pub abbe_y_mm: f64,
}

impl AxisTables {
    pub fn displacement(&self, s: &Sample) -> Xz {
        let (x, z, y) = (s.at.x, s.at.z, self.abbe_y_mm);
        let (dir_x, dir_z) = (s.direction.x, s.direction.z);
        let linear_x = self.x.linear(x, dir_x);
        let pitch = self.x.angular(x, dir_x);
        let straightness_xz = self.x.straightness(x, dir_x);
        let linear_z = self.z.linear(z, dir_z);
        let yaw = self.z.angular(z, dir_z);
        let straightness_zx = self.z.straightness(z, dir_z);
        Xz::new(
            linear_x + straightness_zx - pitch * y + yaw * pitch * (z + linear_z),
            linear_z + straightness_xz + yaw * y,
        )
    }
}
