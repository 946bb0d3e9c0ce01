//! The discrepancy workflow: compare what the model predicts with what was measured, say
//! where they disagree, name the missing effect, add it, and show the gap shrink.
//!
//! `thermal_fit.rs` fits the first-order warm-up and cool-down curves of a thermal log
//! (eq. 5.1–5.2 of the thesis).

pub mod forward;
pub mod lsq;
pub mod measured;
pub mod noise;
pub mod thermal_fit;

#[cfg(test)]
mod test_support;
