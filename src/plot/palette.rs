//! The colours of every plot: Okabe and Ito's palette, whose eight colours stay apart for
//! the common colour-vision deficiencies. Before is warm and after is cool, and where a
//! plot has two directions the second is the lighter of each pair and dashed, so no
//! series depends on telling two hues apart.

use plotters::style::RGBColor;

/// The nominal path and the zero circle.
pub(crate) const NOMINAL: RGBColor = RGBColor(0, 0, 0);
/// Rapids, grid lines and the scale's furniture.
pub(crate) const GREY: RGBColor = RGBColor(128, 128, 128);
/// As programmed (before compensation, or the working model): Okabe–Ito vermillion.
pub(crate) const BEFORE: RGBColor = RGBColor(213, 94, 0);
/// The second direction as programmed: Okabe–Ito orange.
pub(crate) const BEFORE_SECOND: RGBColor = RGBColor(230, 159, 0);
/// Compensated (or with the effects found): Okabe–Ito blue.
pub(crate) const AFTER: RGBColor = RGBColor(0, 114, 178);
/// The second direction compensated: Okabe–Ito sky blue.
pub(crate) const AFTER_SECOND: RGBColor = RGBColor(86, 180, 233);
/// The finished part's half-section, filled under the paths.
pub(crate) const PART: RGBColor = RGBColor(215, 215, 215);
