//! Distances compared by their squares, with the same answers as the distances themselves.
//!
//! A square root's latency sits between a distance and every branch on it, and the hot loops
//! of the stream branch on distances they do not keep: whether a residual is small enough,
//! which of a move's rounded segments is nearest a sample. The square root, correctly
//! rounded, never decreases as its argument grows, so the squares order the roots wherever
//! they differ clearly; only where they lie within a billionth of each other (where two
//! roots may round alike) are the roots taken and compared.

/// How far apart, relatively, two squares must lie for their order to be their roots'
/// order after rounding: far more than the few units in the last place (about 1e-16) a
/// square and a rounded root are off by.
const CLEAR: f64 = 1e-9;

/// `squared.sqrt() <= limit`, decided by the squares where they clearly tell it.
///
/// For a `limit` whose square is a normal number, the square is within a few units in the
/// last place of `limit²`: a `squared` a billionth below it has a root below `limit`, whose
/// rounding cannot pass `limit` (a representable number); one a billionth above has a root
/// more than a unit in the last place above `limit`. Between the two, and for every other
/// `limit` or `squared` (NaN included), the root decides.
pub fn root_at_most(squared: f64, limit: f64) -> bool {
    let bound = limit * limit;
    if limit > 0.0 && bound.is_normal() {
        if squared <= bound * (1.0 - CLEAR) {
            return true;
        }
        if squared >= bound * (1.0 + CLEAR) {
            return false;
        }
    }
    squared.sqrt() <= limit
}

/// `a.sqrt() < b.sqrt()`, decided by the squares where they clearly tell it: a square at
/// least as large has a root at least as large, and one a billionth smaller than a normal
/// (or infinite) square has a root smaller by far more than the rounding; between the two,
/// and for NaN, the roots decide.
pub fn root_less(a: f64, b: f64) -> bool {
    if a >= b {
        return false;
    }
    if (b.is_normal() || b == f64::INFINITY) && a < b * (1.0 - CLEAR) {
        return true;
    }
    a.sqrt() < b.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A square, or one a few units in the last place from `near`.
    fn squares(near: f64) -> impl Strategy<Value = f64> {
        prop_oneof![
            0.0f64..4.0,
            1e-300f64..1e300,
            (-8i64..8).prop_map(move |ulps| f64::from_bits(near.to_bits().wrapping_add_signed(ulps))),
            (0.999_999f64..1.000_001).prop_map(move |scale| near * scale),
            Just(0.0),
            Just(f64::INFINITY),
            Just(f64::NAN),
            Just(f64::MIN_POSITIVE / 3.0),
        ]
    }

    proptest! {
        /// `root_at_most` answers as the square root compared: near the limit's square (a
        /// few units in the last place either way), far from it, and at the edges.
        #[test]
        fn root_at_most_decides_as_the_square_root(
            (limit, squared) in prop_oneof![1e-12f64..1e-3, 1e-300f64..1e300, Just(0.0), -1.0f64..1.0]
                .prop_flat_map(|limit| (Just(limit), squares(limit * limit))),
        ) {
            prop_assert_eq!(root_at_most(squared, limit), squared.sqrt() <= limit, "{} {}", squared, limit);
        }

        /// `root_less` answers as the square roots compared, where the squares are near each
        /// other (their roots may round alike) and far apart.
        #[test]
        fn root_less_decides_as_the_square_roots(
            (b, a) in prop_oneof![1e-14f64..1e4, 1e-300f64..1e300, Just(0.0), Just(f64::INFINITY)]
                .prop_flat_map(|b| (Just(b), squares(b))),
        ) {
            prop_assert_eq!(root_less(a, b), a.sqrt() < b.sqrt(), "{} {}", a, b);
            prop_assert_eq!(root_less(b, a), b.sqrt() < a.sqrt(), "{} {}", b, a);
        }
    }

    #[test]
    fn squares_whose_roots_round_alike_are_not_less() {
        // 1 and the next f64 up have the same rounded root.
        let next = f64::from_bits(1.0f64.to_bits() + 1);
        assert_eq!(next.sqrt(), 1.0);
        assert!(!root_less(1.0, next) && !root_less(next, 1.0));
        assert!(root_at_most(next, 1.0));
    }
}
