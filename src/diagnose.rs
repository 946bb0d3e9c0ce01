//! The discrepancy workflow: compare what the model predicts with what was measured, say
//! where they disagree, name the missing effect, add it, and show the gap shrink
//! (`docs/measurements.md`).
//!
//! ```txt
//! measured.rs ─▶ forward.rs ─▶ workflow.rs ─┬─ select.rs (candidates.rs, lsq.rs, advice.rs)
//! (CSV readers)  (simulate the  (iterate to  ├─ breakdown.rs, iso230_4.rs (where)
//!                 measurement)   the noise)  ├─ unexplained.rs (what no effect explains)
//!                                            └─ report.rs, model_text.rs (--write-model)
//! ```
//!
//! `synth.rs` makes measurements from a truth model with the seeded noise of `noise.rs`;
//! `thermal_fit.rs` fits the first-order warm-up and cool-down curves of a thermal log
//! (eq. 5.1–5.2 of the thesis).

pub(crate) mod advice;
pub(crate) mod breakdown;
pub(crate) mod candidates;
pub mod forward;
pub(crate) mod iso230_4;
pub(crate) mod lsq;
pub mod measured;
pub mod model_text;
pub mod noise;
pub mod report;
pub(crate) mod select;
pub mod synth;
pub mod thermal_fit;
pub(crate) mod unexplained;
pub(crate) mod workflow;

pub use forward::{Forward, ForwardError, Nominal};
pub use measured::{Kind, Measured};
pub use workflow::{Diagnosis, Options, diagnose};

#[cfg(test)]
mod test_support;
