//! The machine error model: where the tool really is when the control commands a point.
//!
//! A model is the sum of small displacements (actual tool position − commanded, mm, X as a
//! radius), each a function of the commanded point and of the machine's state at that
//! moment: the time since the machine started (thermal growth), the direction each axis
//! last moved in (backlash), the velocity (servo lag), the travel since an axis reversed
//! (reversal spikes), the cut length since the tool was set (wear) and the surface normal
//! (nose radius). Two kinds of terms add up:
//!
//! * measured axis tables (`interferometer.rs`): linear positioning, straightness and
//!   angular errors of each slide in ISO 230-2 form, composed with the homogeneous
//!   transformation of the thesis' eq. 8.6–8.12 (`htm.rs`);
//! * parametric effects (`effects/`, one file each), read from `[[effect]]` tables.
//!
//! Errors are micrometres on positions of hundreds of millimetres, so first-order
//! superposition is exact to far below the least increment; `htm.rs` keeps the one
//! second-order product the thesis' matrix has.

pub mod control;
pub mod counted_twice;
pub mod effects;
pub(crate) mod fitting;
pub(crate) mod htm;
pub mod interferometer;
pub mod model_file;
pub mod report;
pub(crate) mod sampling;
pub(crate) mod spacing;
pub(crate) mod state;

pub use effects::Effect;
pub use spacing::Spacing;
pub use state::{Sample, SampleInputs, Step, Tracker};

use crate::toolpath::Xz;

/// A machine's error model.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ErrorModel {
    /// The measured slides, when the model has interferometer tables.
    pub tables: Option<htm::AxisTables>,
    pub effects: Vec<Effect>,
    /// Minutes since the machine started when the program starts (thermal effects).
    pub start_min: f64,
    /// The control's own axis compensation, when the machine runs with a table loaded
    /// (`control.rs`, `ErrorModel::with_control`): the terms it works on, which `effects`
    /// and `tables` then lack.
    pub control: Option<Box<control::ControlTerm>>,
}

impl ErrorModel {
    /// The displacement of the tool at `sample`: actual − commanded, mm, X as a radius.
    pub fn displacement(&self, sample: &Sample) -> Xz {
        self.displacement_timed(sample, &[])
    }

    /// `displacement`, with the terms of time (`Effect::at_time`) taken from `time_terms`
    /// (`time_terms` at the sample's time, in the model's order) rather than evaluated again:
    /// the inverse tries several commands at each sample and the stream predicts it twice
    /// more, all at the sample's one time, and the exponential of a warm-up was the largest
    /// part of an evaluation. A term `time_terms` lacks is evaluated.
    pub fn displacement_timed(&self, sample: &Sample, time_terms: &[Xz]) -> Xz {
        let mut d = match &self.tables {
            Some(tables) => tables.displacement(sample),
            None => Xz::new(0.0, 0.0),
        };
        let mut timed = time_terms.iter();
        for effect in &self.effects {
            let e = match effect.is_of_time().then(|| timed.next()).flatten() {
                Some(&e) => e,
                None => effect.displacement(sample),
            };
            d = Xz::new(d.x + e.x, d.z + e.z);
        }
        if let Some(control) = &self.control {
            let e = control.displacement(sample);
            d = Xz::new(d.x + e.x, d.z + e.z);
        }
        d
    }

    /// The terms of the model that are functions of time alone at `t_min`, in the model's
    /// order, appended to `out` (one per such term: `time_term_count`).
    pub fn time_terms(&self, t_min: f64, out: &mut Vec<Xz>) {
        let before = out.len();
        for effect in &self.effects {
            if let Some(term) = effect.at_time(t_min) {
                out.push(term);
            }
        }
        // `displacement_timed` pairs the terms with the effects by `Effect::is_of_time`: the
        // two lists of time-only effects must agree.
        debug_assert_eq!(out.len() - before, self.time_term_count(), "Effect::at_time and is_of_time disagree");
    }

    /// How many of the model's terms are functions of time alone.
    pub fn time_term_count(&self) -> usize {
        self.effects.iter().filter(|effect| effect.is_of_time()).count()
    }

    /// The displacement less the backlash, which the tracker's play operator gives (the
    /// part of the error that is a function of the commanded point and the state).
    pub fn displacement_without_play(&self, sample: &Sample) -> Xz {
        without_play(sample, self.displacement(sample))
    }

    /// Where the tool really goes when `sample.at` is commanded.
    pub fn actual(&self, sample: &Sample) -> Xz {
        self.actual_timed(sample, &[])
    }

    /// `actual`, with the terms of time taken from `time_terms` (`displacement_timed`).
    pub fn actual_timed(&self, sample: &Sample, time_terms: &[Xz]) -> Xz {
        let d = self.displacement_timed(sample, time_terms);
        Xz::new(sample.at.x + d.x, sample.at.z + d.z)
    }

    /// The total play of each axis' drive (its backlash effects), for the `Tracker`.
    pub fn play(&self) -> Xz {
        self.effects.iter().map(Effect::play).fold(Xz::new(0.0, 0.0), |a, p| Xz::new(a.x + p.x, a.z + p.z))
    }

    /// How closely a move must be sampled for the straight interpolation between samples
    /// to follow the whole model within `allowance` mm; `reach` is the farthest the
    /// program goes from the origin in each axis (mm, X as a radius). Axis tables keep the
    /// thesis' step (`spacing.rs`).
    pub fn spacing(&self, allowance: f64, reach: Xz) -> Spacing {
        // A control's table is linear between nodes with a kink at each, as a slide table is.
        let tables = if self.tables.is_some() || self.control.is_some() {
            Spacing::mm(spacing::TABLE_STEP_MM)
        } else {
            Spacing::ANY
        };
        self.terms().fold(tables, |spacing, effect| spacing.closer(effect.spacing(allowance, reach)))
    }

    /// What makes the whole model's correction turn around an arc (`spacing::ArcTerms`).
    /// Axis tables add none here: they keep the thesis' 0.254 mm along the arc.
    pub fn arc_terms(&self, reach: Xz) -> spacing::ArcTerms {
        self.terms().fold(spacing::ArcTerms::default(), |terms, effect| terms.plus(effect.arc_terms(reach)))
    }

    /// Every parametric term of the machine: its effects and those a loaded control table
    /// works on.
    fn terms(&self) -> impl Iterator<Item = &Effect> {
        self.effects.iter().chain(self.control.iter().flat_map(|control| control.carried()))
    }

    /// Whether a term of the model depends on the length the tool has cut (wear): the
    /// trackers follow it only then.
    pub fn wears(&self) -> bool {
        self.effects.iter().any(Effect::wears)
    }

    /// Whether the model has any term (an empty model moves nothing).
    pub fn is_empty(&self) -> bool {
        self.tables.is_none() && self.effects.is_empty() && self.control.is_none()
    }
}

/// `displacement` (the model's at `sample`) less the backlash the tracker's play operator
/// gives: `ErrorModel::displacement_without_play` for a displacement already evaluated.
pub fn without_play(sample: &Sample, displacement: Xz) -> Xz {
    let take = |play: f64, offset: f64| if play > 0.0 { offset } else { 0.0 };
    Xz::new(
        displacement.x - take(sample.play.x, sample.backlash.x),
        displacement.z - take(sample.play.z, sample.backlash.z),
    )
}

#[cfg(test)]
mod tests;
