//! How closely a path must be sampled for a model's correction to be followed between
//! samples.
//!
//! Compensation inverts the model at samples along each move and joins them; between two
//! samples the correction is taken as the straight interpolation of theirs. A correction
//! that is constant or affine along a straight move (tool offsets, scale, squareness, the
//! play of a slide that does not reverse, servo lag at a constant velocity, wear that grows
//! with the cut length) is followed exactly by one sample at each end, so a model made of
//! such terms needs no sample inside a line at all. A curved correction departs from the
//! chord between samples `h` apart by at most `c·h²/8`, where `c` bounds its second
//! derivative; each effect with one gives the step at which that reaches the allowance.
//!
//! Measured axis tables are interpolated linearly between their nodes, with a kink at
//! each: they keep the thesis' step of 0.254 mm (0.01 in), at which its own compensation
//! (Table 8) was computed.

/// The thesis' sampling step, mm: it interpolated its error tables every 0.01 in.
pub const TABLE_STEP_MM: f64 = 0.254;

/// The finest step any term asks for (a thousandth of a millimetre, a minute or a radian):
/// finer than a least increment helps nothing, and a tolerance near zero would otherwise ask
/// for unboundedly many samples.
pub const FINEST_STEP: f64 = 1e-3;

/// The longest distance between two samples along a move: in path length and in time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spacing {
    /// Path length, mm.
    pub mm: f64,
    /// Time, minutes (for corrections that drift with time, not position).
    pub minutes: f64,
}

impl Spacing {
    /// No bound: one sample at each end of a straight move follows the correction.
    pub const ANY: Spacing = Spacing { mm: f64::INFINITY, minutes: f64::INFINITY };

    /// A bound in path length only.
    pub fn mm(mm: f64) -> Spacing {
        Spacing { mm, minutes: f64::INFINITY }
    }

    /// A bound in time only.
    pub fn minutes(minutes: f64) -> Spacing {
        Spacing { mm: f64::INFINITY, minutes }
    }

    /// The closer of two spacings, in each measure.
    pub fn closer(self, other: Spacing) -> Spacing {
        Spacing { mm: self.mm.min(other.mm), minutes: self.minutes.min(other.minutes) }
    }

    /// How many equal steps a move of `length_mm` taking `duration_min` needs, at least one.
    pub fn steps(&self, length_mm: f64, duration_min: f64) -> usize {
        let count = |extent: f64, step: f64| if step > 0.0 && extent > 0.0 { (extent / step).ceil() } else { 0.0 };
        let n = count(length_mm, self.mm).max(count(duration_min, self.minutes));
        // `as` saturates, and a NaN (a degenerate move) becomes 0: one step either way.
        (n as usize).max(1)
    }
}

/// What makes a correction turn as the tool goes round an arc, for sampling arcs. Around
/// an arc of radius R at feed F, the correction's second derivative by the angle is at most
/// `gradient·R + lag_min·F + nose_mm`: a term of the position turns with the radius vector
/// (its gradient times R), servo lag with the velocity (F times the lag), a nose radius
/// error with the surface normal (its size). What curves along the path itself is in
/// `Spacing`, in path length.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ArcTerms {
    /// A bound on the gradient of the position's terms, mm of correction per mm of travel.
    pub gradient: f64,
    /// The lag of an axis behind its command, minutes.
    pub lag_min: f64,
    /// The size of a nose radius error, mm.
    pub nose_mm: f64,
}

impl ArcTerms {
    /// The terms of a correction of the position whose gradient is at most `gradient` (its
    /// sign does not matter): it turns with the radius vector.
    pub fn gradient(gradient: f64) -> ArcTerms {
        ArcTerms { gradient: gradient.abs(), ..ArcTerms::default() }
    }

    /// Both sets of terms.
    pub fn plus(self, other: ArcTerms) -> ArcTerms {
        ArcTerms {
            gradient: self.gradient + other.gradient,
            lag_min: self.lag_min + other.lag_min,
            nose_mm: self.nose_mm + other.nose_mm,
        }
    }

    /// Whether a correction steps where the path turns a corner: terms of the commanded
    /// velocity (a loop lag) or of the surface normal (a nose radius error) change at once
    /// where the direction does.
    pub fn steps_at_corners(&self) -> bool {
        self.lag_min != 0.0 || self.nose_mm != 0.0
    }

    /// The largest angle between samples of an arc of `radius_mm` at `feed` mm/min for the
    /// chord between them to follow these terms within `allowance` mm; unbounded for none.
    pub fn radians(&self, radius_mm: f64, feed: f64, allowance: f64) -> f64 {
        let turning = self.gradient.abs() * radius_mm.abs() + self.lag_min.abs() * feed.abs() + self.nose_mm.abs();
        step_for_curvature(turning, allowance)
    }
}

/// The step over which a function whose second derivative is at most `curvature` departs
/// from its chord by `allowance`: `√(8·allowance/curvature)`; unbounded for a straight one,
/// and never below `FINEST_STEP`.
pub fn step_for_curvature(curvature: f64, allowance: f64) -> f64 {
    let curvature = curvature.abs();
    if curvature > 0.0 && curvature.is_finite() && allowance > 0.0 {
        (8.0 * allowance / curvature).sqrt().max(FINEST_STEP)
    } else if curvature > 0.0 {
        // No allowance (or an infinite curvature): as fine as the thesis sampled.
        TABLE_STEP_MM
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_parabola_sampled_at_the_step_departs_from_its_chords_by_the_allowance() {
        // f(s) = a·s², f'' = 2a: the chord over [0, h] misses the midpoint by a·h²/4.
        let a = 3e-6;
        let allowance = 5e-5;
        let h = step_for_curvature(2.0 * a, allowance);
        let sag = a * h * h / 4.0;
        assert!((sag - allowance).abs() < 1e-12, "{sag}");
    }

    #[test]
    fn a_straight_correction_needs_no_inner_sample() {
        assert_eq!(step_for_curvature(0.0, 1e-4), f64::INFINITY);
        assert_eq!(Spacing::ANY.steps(120.0, 3.0), 1);
        assert_eq!(Spacing::mm(0.254).steps(2.54, 1.0), 10);
        assert_eq!(Spacing::minutes(0.5).steps(1.0, 1.2), 3);
        assert_eq!(Spacing::mm(0.254).steps(0.0, 0.0), 1);
        assert_eq!(Spacing::mm(0.254).steps(f64::NAN, 0.0), 1);
    }
}
