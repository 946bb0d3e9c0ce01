//! The pass depths of the OSP multi-pass thread cycles (`G71`/`G72` compound threads and the
//! `G88` LAP thread): where each pass cuts, measured from the thread's crest, and on which
//! flank it goes in.
//!
//! The words (all in one unit, as the program writes them; diameters for a longitudinal
//! thread): `H` the thread height, `D` the first depth, `U` (`W`) the finishing allowance.
//! The passes rough down to `H − U`, then one finishing pass cuts the allowance, so the last
//! pass is at `H`. With no allowance (or zero) there is no finishing pass.
//!
//! Infeed patterns ([M3277] P-170, the OSP-P200L manual P-113/P-114, dialects.md §1.6):
//!
//! - pattern 1 (`M73`): a constant depth `D` per pass; the control rejects `H − U < D`;
//! - pattern 2 (`M74`): a constant cut area: the n-th pass at `D·√n`, so each pass removes
//!   the same area of the V-shaped groove (area grows with the square of the depth); the
//!   control rejects `H − U < 0`;
//! - pattern 3 (`M75`): along one flank (`M32`, `M34`) the n-th pass at `D·√n` as in pattern
//!   2; zigzag (`M33`) the even passes at `D·√(n/2)` and each odd pass halfway between its
//!   neighbours. Both hold while `D² ≥ H² − (H − U)²` (the first cut is at least as large
//!   as the finishing cut); otherwise the control chooses depths "most appropriate" for
//!   metal removal by a rule the manual does not give, and the plan says it approximated
//!   them with the rule above.
//!
//! Ambiguities of the sources, and what this module does:
//!
//! - The manual's OCR loses the formula of pattern 3 zigzag's even passes; `D·√(n/2)` is
//!   the reading that makes every zig-zag pair remove the area of one pattern-2 pass.
//! - Patterns 2 and 3 are the same rule along one flank; they differ in the zigzag rule and
//!   in pattern 3's switch to the undocumented rule.
//! - When no pattern code is written, pattern 1 is used, and when no mode code is written,
//!   infeed along one flank (`M32`): the manual asks for both codes in the cycle block.
//! - `U0` counts as no allowance: no finishing pass at the depth the roughing ended on.
//!
//! Flanks: a pass `flank` of +1 goes in along the flank `M32` names, −1 along the other;
//! zigzag alternates, starting with +1. The caller turns that into a shift along the thread
//! axis of `flank · (H − depth) · tan(B/2)` (zero for `B = 0`, radial infeed).

/// Passes beyond this make the plan an error (bounded work).
pub const MAX_PASSES: usize = 1000;

/// `M32`, `M33`, `M34`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InfeedMode {
    OneFlank,
    Zigzag,
    OtherFlank,
}

/// `M73`, `M74`, `M75`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InfeedPattern {
    ConstantDepth,
    ConstantArea,
    Pattern3,
}

/// What the cycle block asks for, in program units (one unit for all three depths).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Infeed {
    pub mode: InfeedMode,
    pub pattern: InfeedPattern,
    pub first_depth: f64,
    pub height: f64,
    pub allowance: Option<f64>,
}

/// One pass: its depth from the crest, the flank it goes in on, and whether it is the
/// finishing pass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pass {
    pub depth: f64,
    pub flank: f64,
    pub finishing: bool,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    pub passes: Vec<Pass>,
    /// Pattern 3 fell back to the documented rule where the control uses its own.
    pub approximated: bool,
}

/// What the control rejects, and what the simulation will not run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum InfeedError {
    /// `D` is not a positive number.
    FirstDepthNotPositive,
    /// `H` is not a positive number.
    HeightNotPositive,
    /// Pattern 1 with `H − U < D`.
    RoughDepthBelowFirstCut {
        rough_depth: f64,
    },
    /// `U > H`.
    AllowanceOverHeight,
    TooManyPasses {
        passes: usize,
    },
}

/// Depths closer than this count as equal (program units, far below any increment).
const EPSILON: f64 = 1e-9;

pub fn plan(infeed: &Infeed) -> Result<Plan, InfeedError> {
    let Infeed { mode, pattern, first_depth: d, height: h, .. } = *infeed;
    if !(d.is_finite() && d > 0.0) {
        return Err(InfeedError::FirstDepthNotPositive);
    }
    if !(h.is_finite() && h > 0.0) {
        return Err(InfeedError::HeightNotPositive);
    }
    let allowance = infeed.allowance.filter(|u| u.is_finite() && *u > 0.0).unwrap_or(0.0);
    let rough = h - allowance;
    if rough < -EPSILON {
        return Err(InfeedError::AllowanceOverHeight);
    }
    if pattern == InfeedPattern::ConstantDepth && rough < d - EPSILON {
        return Err(InfeedError::RoughDepthBelowFirstCut { rough_depth: rough });
    }
    let zigzag_pairs = pattern == InfeedPattern::Pattern3 && mode == InfeedMode::Zigzag;
    // The number of passes before generating them, so a tiny D cannot run long.
    let ratio = rough.max(0.0) / d;
    let estimate = match pattern {
        InfeedPattern::ConstantDepth => ratio.ceil(),
        _ if zigzag_pairs => 2.0 * (ratio * ratio).ceil(),
        _ => (ratio * ratio).ceil(),
    } + 1.0;
    if !estimate.is_finite() || estimate > MAX_PASSES as f64 {
        return Err(InfeedError::TooManyPasses {
            passes: if estimate.is_finite() { estimate as usize } else { usize::MAX },
        });
    }

    let depth_at = |n: usize| match pattern {
        InfeedPattern::ConstantDepth => d * n as f64,
        _ => d * (n as f64).sqrt(),
    };
    // The rough depths, each short of `rough`, then `rough` itself.
    let mut depths = Vec::new();
    if rough > EPSILON {
        let mut n = 1;
        while depth_at(n) < rough - EPSILON {
            depths.push(depth_at(n));
            n += 1;
        }
        depths.push(rough);
    }
    if zigzag_pairs {
        let mut paired = Vec::with_capacity(depths.len() * 2);
        let mut previous = 0.0;
        for depth in depths {
            paired.push((previous + depth) / 2.0);
            paired.push(depth);
            previous = depth;
        }
        depths = paired;
    }
    let mut passes: Vec<Pass> = depths.into_iter().map(|depth| Pass { depth, flank: 0.0, finishing: false }).collect();
    if allowance > 0.0 {
        passes.push(Pass { depth: h, flank: 0.0, finishing: true });
    }
    for (i, pass) in passes.iter_mut().enumerate() {
        pass.flank = match mode {
            InfeedMode::OneFlank => 1.0,
            InfeedMode::OtherFlank => -1.0,
            InfeedMode::Zigzag if i % 2 == 0 => 1.0,
            InfeedMode::Zigzag => -1.0,
        };
    }
    let approximated = pattern == InfeedPattern::Pattern3 && d * d < h * h - rough * rough - EPSILON;
    Ok(Plan { passes, approximated })
}

#[cfg(test)]
mod tests;
