//! Compensation: the commanded path that makes a measured machine cut the nominal part.
//!
//! The nominal toolpath (a `ValidToolpath`: the tool reference points the program asks
//! for) is sampled along every move (`error_model/sampling.rs`). Each sample is moved by the iteration
//! of the thesis' eq. 2.14–2.16 (`inverse.rs`): command `U_c`, predict `U_a = U_c + Δ(U_c)`
//! with the error model, correct `U_c += γ (U_d − U_a)`, until every sample's predicted
//! position is within the tolerance of its nominal one. Direction-dependent terms are
//! evaluated along the compensated path itself, in order, on every pass, so a reversal
//! point that compensation moves is seen where it moved to.
//!
//! The samples' shifts are then re-expressed as G-code by the strategies of `fit.rs`, and
//! written into the program by editing only the blocks whose motion changes.

pub mod deviation;
pub mod fit;
pub(crate) mod inverse;
pub(crate) mod plan;
pub mod program;
pub mod provenance;
pub(crate) mod quantised;
pub(crate) mod report;
pub(crate) mod rewrite;
pub(crate) mod safety;
mod squares;
#[cfg(test)]
pub(crate) mod test_support;
pub mod verify;
pub(crate) mod written;

pub use crate::error_model::sampling::{PathSample, sample_toolpath};
pub use fit::{FitOptions, MovePoints, NominalShape, Segment, Strategy};
pub use inverse::{Compensated, InverseOptions, compensate_samples, predict};
pub use plan::{Judged, LeftAlone};
pub use program::{CompensateOptions, Outcome, Paths, compensate_program};
pub use rewrite::cycles::LeadChange;
pub use rewrite::{
    CycleForm, CycleOutcome, OTHER_NOT_AS_WRITTEN, PROFILE_COPIED, PROFILE_NOT_COPIED, PROFILE_NOT_IN_PLACE,
    PROFILE_TAKE_UP, SINGLE_NOT_IN_PLACE, THREAD_NOT_IN_PLACE,
};
