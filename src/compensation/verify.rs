//! `turnpass verify ORIGINAL COMPENSATED`: does the compensated program cut the original's
//! nominal part on the modelled machine, and does it still do everything else the original
//! did?
//!
//! **Deviation.** Both programs are sampled and run through the model as written (the
//! forward model, `inverse::predict`, with the nominal path of each as its command). Each
//! predicted cutting point is measured against the ORIGINAL's nominal path, by its closest
//! point within a window of the original's path about the point's own nominal point
//! (`follow.rs`, which finds a compensated point's own point by following the original
//! along): the original's own prediction gives the error before compensation, the
//! compensated program's the error after.
//!
//! **Words.** Every word that is not motion — M codes, T, comments (save a provenance
//! comment, `provenance.rs`, which either program may carry or not), block-delete slashes,
//! program names and numbers — must appear in the compensated program in the same order
//! (other words may come between them: restored motion codes, expanded cycles' blocks).
//! Spindle speeds are compared as the sequence of speed changes, because an expanded cycle
//! writes `S` only where the speed changes.

use crate::error_model::ErrorModel;
use crate::semantic::nose_radius::ToolTable;
use crate::source::Span;
use crate::syntax::{CodeLetter, Program, WordKind};
use crate::toolpath::{Toolpath, ValidToolpath, Xz};

use super::deviation::{Figures, LocalPath};
use super::inverse::predict;
use super::sampling::{PathSample, sample_toolpath};

mod follow;
#[cfg(test)]
mod tests;

use follow::Follower;

/// The predicted deviation from the original's nominal path, before and after.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Deviation {
    pub before: Figures,
    pub after: Figures,
    pub improvement_percent: f64,
}

/// Predict both programs through `model` and measure them against `original`.
pub fn deviation(
    original: ValidToolpath<'_>,
    compensated: ValidToolpath<'_>,
    tools: &ToolTable,
    model: &ErrorModel,
    step_mm: f64,
) -> Deviation {
    deviation_each(original, compensated, tools, model, step_mm, |_, _| {})
}

/// Which program a measured point is of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    Original,
    Compensated,
}

/// A predicted cutting point as `deviation` measured it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// The sample of its own program's toolpath it was predicted for.
    pub sample: PathSample,
    /// The index of that sample among its program's samples (cutting or not).
    pub sample_index: usize,
    /// Where the model puts the tool.
    pub predicted: Xz,
    /// Its distance from the original's nominal path (what the figures are made of), the
    /// closest point of that path and the original's move it lies on.
    pub distance_mm: f64,
    pub closest: Xz,
    pub original_move: usize,
}

/// Both programs' deviations, every point measured also given to `each` (both programs'
/// points in their order, the original's first): `deviation` and `report` measure with
/// this one function, so the page's figures are `verify`'s.
pub fn deviation_each(
    original: ValidToolpath<'_>,
    compensated: ValidToolpath<'_>,
    tools: &ToolTable,
    model: &ErrorModel,
    step_mm: f64,
    mut each: impl FnMut(Side, Measured),
) -> Deviation {
    let predicted = |toolpath: &Toolpath| {
        let samples = sample_toolpath(toolpath, tools, step_mm);
        let nominal: Vec<_> = samples.iter().map(|s| s.nominal).collect();
        let predicted = predict(&samples, &nominal, toolpath.start, model);
        (samples, predicted)
    };
    let (original, compensated) = (original.toolpath(), compensated.toolpath());
    let path = LocalPath::new(original);
    let mut figures = |side: Side, toolpath: &Toolpath| {
        let (samples, points) = predicted(toolpath);
        let mut follower = Follower::new(&path);
        let cutting = samples.iter().zip(&points).enumerate().filter(|(_, (s, _))| s.cutting);
        Figures::of(cutting.filter_map(|(sample_index, (s, &p))| {
            let found = match side {
                Side::Original => follower.measure_from(s.move_index, s.param, p),
                Side::Compensated => follower.measure(s.nominal, p),
            }?;
            each(
                side,
                Measured {
                    sample: *s,
                    sample_index,
                    predicted: p,
                    distance_mm: found.distance,
                    closest: found.point,
                    original_move: found.move_index,
                },
            );
            Some(found.distance)
        }))
    };
    let before = figures(Side::Original, original);
    let after = figures(Side::Compensated, compensated);
    let improvement_percent = (before.improvement_percent(&after) * 1e4).round() / 1e4;
    Deviation { before: before.rounded(), after: after.rounded(), improvement_percent }
}

/// A word of the original that the compensated program lost (or moved out of order).
#[derive(Debug, Clone, PartialEq)]
pub struct MissingWord {
    /// The word as the original writes it.
    pub text: String,
    pub span: Span,
}

/// The words kept in order, and the first that was not.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct WordCheck {
    pub checked: usize,
    pub missing: Option<MissingWord>,
}

/// A word that must survive, in a form that compares across programs.
#[derive(Debug, Clone, PartialEq)]
enum Kept {
    M(u16, u16),
    Text(Vec<u8>),
}

/// The words that must survive, and the speed changes, each with its span.
type KeptWords = (Vec<(Kept, Span)>, Vec<(f64, Span)>);

fn kept_words(program: &Program<'_>) -> KeptWords {
    let mut words = Vec::new();
    let mut speeds: Vec<(f64, Span)> = Vec::new();
    for block in program.blocks() {
        for word in program.words_of(block) {
            let kept = match word.kind {
                WordKind::Code { letter: CodeLetter::M, code } => Some(Kept::M(code.major(), code.minor())),
                // A provenance comment is `compensate`'s, not the program's.
                WordKind::Comment(_) if super::provenance::is_mark(program.text(word.span)) => None,
                WordKind::Comment(_) | WordKind::BlockDelete { .. } | WordKind::ProgramName | WordKind::Header => {
                    Some(Kept::Text(program.text(word.span).to_vec()))
                }
                WordKind::Number { address, .. } | WordKind::Expr { address, .. }
                    if address == crate::dialect::Address::T =>
                {
                    Some(Kept::Text(program.text(word.span).to_vec()))
                }
                WordKind::Number { address, number } if address == crate::dialect::Address::S => {
                    let value = number.to_f64();
                    if speeds.last().is_none_or(|(s, _)| *s != value) {
                        speeds.push((value, word.span));
                    }
                    None
                }
                _ => None,
            };
            if let Some(kept) = kept {
                words.push((kept, word.span));
            }
        }
    }
    (words, speeds)
}

/// Check that `compensated` keeps the non-motion words of `original` in order.
pub fn check_words(original: &Program<'_>, compensated: &Program<'_>) -> WordCheck {
    let (words, speeds) = kept_words(original);
    let (new_words, new_speeds) = kept_words(compensated);
    let checked = words.len() + speeds.len();
    let missing = first_missing(&words, &new_words, |a, b| a == b)
        .map(|span| MissingWord { text: String::from_utf8_lossy(original.text(span)).into_owned(), span })
        .or_else(|| {
            first_missing(&speeds, &new_speeds, |a, b| a == b)
                .map(|span| MissingWord { text: String::from_utf8_lossy(original.text(span)).into_owned(), span })
        });
    WordCheck { checked, missing }
}

/// The first item of `wanted` that is not found, in order, in `found`.
fn first_missing<T>(wanted: &[(T, Span)], found: &[(T, Span)], same: impl Fn(&T, &T) -> bool) -> Option<Span> {
    let mut k = 0;
    for (item, span) in wanted {
        match found[k..].iter().position(|(f, _)| same(item, f)) {
            Some(at) => k += at + 1,
            None => return Some(*span),
        }
    }
    None
}
