//! Greedy growth of a piece over a run of points.
//!
//! ArcWelder extends a segment one point at a time and refits at each step, which costs
//! the square of the piece's length. Here the run doubles until a piece fails and is then
//! bisected between the longest run that passed and the shortest that failed: a logarithmic
//! number of fits per piece. Acceptance is not strictly monotone (a longer run can pass
//! where a shorter one failed), so this finds a long run that passes, not always the
//! longest; every piece it returns has passed the test.

/// The last index `l` in `first..count` of a long run `first..=l` that `accept` takes, with
/// what `accept` made of it; `None` when not even `first..=first` passes.
pub(crate) fn longest<P>(first: usize, count: usize, mut accept: impl FnMut(usize) -> Option<P>) -> Option<(usize, P)> {
    if first >= count {
        return None;
    }
    let mut best: Option<(usize, P)> = None;
    let mut span = 1;
    let mut failed = loop {
        let last = (first + span - 1).min(count - 1);
        match accept(last) {
            Some(piece) => {
                best = Some((last, piece));
                if last + 1 == count {
                    return best;
                }
                span *= 2;
            }
            None => break last,
        }
    };
    let mut passed = best.as_ref().map(|(last, _)| *last);
    // Bisect between the longest run that passed (or none) and the shortest that failed.
    loop {
        let low = passed.map_or(first, |l| l + 1);
        if low >= failed {
            return best;
        }
        let middle = low + (failed - low) / 2;
        match accept(middle) {
            Some(piece) => {
                passed = Some(middle);
                best = Some((middle, piece));
            }
            None => failed = middle,
        }
    }
}
