//! Round numbers for the plots: ring divisions, magnifications and scale bars.

/// 1, 2 or 5 times a power of ten, at least `value` (and at least `floor`).
pub(crate) fn nice_at_least(value: f64, floor: f64) -> f64 {
    let value = if value.is_finite() { value.max(floor) } else { floor };
    let power = 10f64.powf(value.log10().floor());
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|k| k * power).find(|d| *d >= value * (1.0 - 1e-12)).unwrap_or(10.0 * power)
}

/// 1, 2 or 5 times a power of ten, at most `value` (which is above 0).
pub(crate) fn nice_at_most(value: f64) -> f64 {
    let power = 10f64.powf(value.log10().floor());
    [5.0, 2.0, 1.0].into_iter().map(|k| k * power).find(|d| *d <= value * (1.0 + 1e-12)).unwrap_or(power)
}

/// The share of the drawing's larger side the largest deviation is drawn at when no
/// magnification is given: large enough to read at a glance, small enough that the
/// magnified path stays beside the nominal one.
pub(crate) const LARGEST_DRAWN_SHARE: f64 = 1.0 / 30.0;

/// The round magnification that draws `largest_mm` at about `LARGEST_DRAWN_SHARE` of
/// `size_mm` (1 when there is no deviation, or when it is that large already).
pub(crate) fn magnification(largest_mm: f64, size_mm: f64) -> f64 {
    if !(largest_mm > 0.0 && size_mm > 0.0) {
        return 1.0;
    }
    nice_at_most(size_mm * LARGEST_DRAWN_SHARE / largest_mm).max(1.0)
}

/// The scale bar for a drawing of `pixels_per_um` pixels per micrometre of deviation:
/// a round number of micrometres drawn at least `min_pixels` long.
pub(crate) fn scale_bar_um(pixels_per_um: f64, min_pixels: f64) -> f64 {
    nice_at_least(min_pixels / pixels_per_um, 1e-3)
}

/// A length in micrometres as the plots print it: no more digits than it has.
pub(crate) fn micrometres(um: f64) -> String {
    let text = format!("{um:.3}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" { "0".to_string() } else { text.to_string() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_numbers() {
        assert_eq!(nice_at_least(3.2, 0.1), 5.0);
        assert_eq!(nice_at_least(0.0, 0.1), 0.1);
        assert_eq!(nice_at_least(20.0, 0.1), 20.0);
        assert_eq!(nice_at_most(480.0), 200.0);
        assert_eq!(nice_at_most(500.0), 500.0);
        assert_eq!(magnification(0.005, 45.0), 200.0);
        assert_eq!(magnification(0.0, 45.0), 1.0);
        assert_eq!(magnification(10.0, 45.0), 1.0);
        assert_eq!(scale_bar_um(4.0, 60.0), 20.0);
        assert_eq!(micrometres(2.50), "2.5");
        assert_eq!(micrometres(10.0), "10");
        assert_eq!(micrometres(-0.0001), "0");
    }
}
