//! OSP LAP contours (`G81`/`G82` … `G80`): finding the contour a `G85`-`G88` call names,
//! reading it, and the return to the AP start point of the roughing cycles `G85`/`G86`.
//!
//! **Finding it.** A call names its contour by the sequence name of the `G81`/`G82` block
//! (`G85 N0207` → `N0207 G81`, `G85 NLAP1` → `NLAP1 G81`); OSP compares names as text, so
//! `N0207` is not `N207`. The contour may stand before or after the call. When several
//! blocks carry the name, only contour blocks count, searched as a jump searches: the first
//! after the call, else the first from the top.
//!
//! **Consumed or kept.** A contour right after its call (nothing but empty or comment lines
//! between) belongs to that call: the flow continues after its `G80`, and `expand` deletes it
//! with the call. A contour anywhere else is a definition other calls may share (a `G85` and
//! a `G87` with another tool): it stays where it is, and the flow skips it as it meets it
//! (`block.rs`, `lap_marker_in_flow`).
//!
//! **Reading it.** The contour is read from the tool's position at the call, through the
//! ordinary motion code (`profile.rs`). Its first block (G00 or G01; the only block that may
//! be G00) is the approach from the AP start point to the contour's start point; the contour
//! proper follows. `F` and `S` inside are the finishing feed and speed, `E` the feed along the
//! contour in roughing; all three are modal inside the contour (M-P202, M-P218).
//!
//! **The return.** After a cycle the tool goes back to the AP start point at rapid, along the
//! cutting axis first and then across it: longitudinally Z to Zs, then X to Xs (M-P195 step
//! 8), transversely the mirror, X first. The manual says that this retraction depends on
//! whether the contour's first block is G00 or G01 (M-P202, M-P218), and the pages we could
//! read do not say how. We take the M-P195 order for a G00 first block (the usual one, and the
//! one the page describes) and the reverse order, across the cut first, for a G01 first
//! block. That second half is our assumption, not the manual's: check it on a control.

use std::ops::RangeInclusive;

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::{Address, GFunction, Role};
use crate::geometry;
use crate::source::Span;
use crate::syntax::{Command, Statement, WordKind};
use crate::toolpath::Xz;

use super::super::block::effective_words;
use super::super::interpreter::{Flow, Interpreter};
use super::super::labels;
use super::super::profile::{Profile, Shape};
use super::Call;

/// Which way the contour is roughed: `G81` passes run parallel to Z, `G82` parallel to X.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Direction {
    Longitudinal,
    Transverse,
}

/// A LAP contour, read for one call.
#[derive(Debug, Clone)]
pub(super) struct Contour {
    pub profile: Profile,
    pub direction: Direction,
    /// The `G81`/`G82` block and its `G80`.
    pub blocks: RangeInclusive<usize>,
    /// Right after the call: the call consumes it.
    pub follows_call: bool,
    /// The contour feed `E` in effect on each segment of the profile, program units.
    pub contour_feed: Vec<Option<f64>>,
    /// The `G81`/`G82` block, for diagnostics about the contour.
    pub span: Span,
}

impl Contour {
    /// The contour's first block is a rapid (`G00`), not a feed (`G01`).
    pub fn approach_rapid(&self) -> bool {
        self.profile.segments.first().is_some_and(|s| s.rapid)
    }

    /// The contour's start point: where its approach block ends.
    pub fn start(&self) -> Xz {
        self.profile.segments.first().map_or(self.profile.start, |s| s.end)
    }

    /// Where the program goes after the call: past the contour when the call consumed it.
    pub fn flow_after(&self) -> Flow {
        if self.follows_call { Flow::Jump(self.blocks.end() + 1) } else { Flow::Next }
    }

    /// The contour goes with the call when it belongs to it (right after it): `expand`
    /// deletes it with the call.
    pub fn consume(&self, interp: &mut Interpreter<'_, '_>) {
        if self.follows_call {
            interp.consume(self.blocks.clone());
        }
    }

    /// Whether roughing passes can follow the contour: it runs one way along the cutting
    /// axis. If not, the error is the contour's, pointing at the call that roughs it.
    pub fn roughable(&self, interp: &mut Interpreter<'_, '_>, call: Span) -> bool {
        let monotonic = self.monotonic_along_cut();
        if !monotonic {
            let kind = DiagnosticKind::LapContourNotMonotonic { axis: self.cutting_axis() };
            interp.diagnostics.push(Diagnostic::error(kind, self.span).with_related(call, "roughed by this call"));
        }
        monotonic
    }

    /// The axis the passes cut along.
    pub fn cutting_axis(&self) -> char {
        match self.direction {
            Direction::Longitudinal => 'Z',
            Direction::Transverse => 'X',
        }
    }

    /// Whether the contour after its approach block runs one way along the cutting axis:
    /// no line and no arc turns back. An arc turns back when it reaches further along the
    /// axis than both its ends.
    pub fn monotonic_along_cut(&self) -> bool {
        let along = |p: Xz| match self.direction {
            Direction::Longitudinal => p.z,
            Direction::Transverse => p.x,
        };
        let start = self.start();
        let sign = (along(self.profile.end()) - along(start)).signum();
        let mut at = start;
        for segment in self.profile.segments.iter().skip(1) {
            if (along(segment.end) - along(at)) * sign < -1e-9 {
                return false;
            }
            if let Shape::Arc { centre, ccw } = segment.shape {
                let (lo, hi) = (along(at).min(along(segment.end)), along(at).max(along(segment.end)));
                let reaches_past = geometry::arc_extremes(at, segment.end, centre, ccw)
                    .into_iter()
                    .any(|p| along(p) > hi + 1e-7 || along(p) < lo - 1e-7);
                if reaches_past {
                    return false;
                }
            }
            at = segment.end;
        }
        true
    }
}

/// The call of the LAP cycle in block `index` and the contour it names, read from the tool's
/// position there; `None` when the position is not known or the contour cannot be had
/// (reported).
pub(super) fn call(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command) -> Option<(Call, Contour)> {
    let call = interp.cycle_call(index)?;
    let contour = find(interp, index, command, call.start)?;
    Some((call, contour))
}

/// The contour a LAP call names, read from `start`. `None` (with the diagnostic reported)
/// when there is none, it has no `G80`, it is a `G83` blank, or it does not read.
pub(super) fn find(interp: &mut Interpreter<'_, '_>, index: usize, command: &Command, start: Xz) -> Option<Contour> {
    let span = interp.program.block(index).span;
    let word = *interp.program.word(command.param(Role::ContourName)?);
    let WordKind::Label { number } = word.kind else { return None };
    let key = labels::key(interp.dialect, interp.program.text(word.span), number);
    let named = interp.labels().blocks(&key).to_vec();
    let contours: Vec<(usize, GFunction)> =
        named.iter().filter_map(|&b| contour_function(interp, b).map(|f| (b, f))).collect();
    let Some(&(first, function)) = contours.iter().find(|(b, _)| *b > index).or_else(|| contours.first()) else {
        if named.is_empty() && interp.damaged_target(&key, word.span, "the call names") {
            return None;
        }
        let mut diagnostic =
            Diagnostic::error(DiagnosticKind::LapContourMissing { name: format!("N{key}") }, word.span);
        if let Some(&other) = named.first() {
            let label = format!("`N{key}` names this block, which does not start a contour");
            diagnostic = diagnostic.with_related(interp.program.block(other).span, label);
        }
        interp.diagnostics.push(diagnostic);
        return None;
    };
    let contour_span = interp.program.block(first).span;
    if function == GFunction::LapBlank {
        // LAP4 (AP modes IV and V): roughing from a blank shape is not simulated.
        let code = interp.program.text(interp.program.word(command.code_word).span);
        let code = format!("{} with a G83 blank (LAP4)", String::from_utf8_lossy(code));
        interp.warning(DiagnosticKind::CycleNotSimulated { code }, span);
        return None;
    }
    let Some(last) = interp.lap_end(first) else {
        interp.error(DiagnosticKind::LapContourNotClosed, contour_span);
        return None;
    };
    let reported = interp.diagnostics.len();
    let profile = interp.profile(first..=last, start);
    // Reading runs the contour's moves on scratch state, where a contour that writes only
    // `E` (roughing) has no feed yet; the cycle that cuts it reports a missing feed itself.
    let mut position = 0;
    interp.diagnostics.retain(|d| {
        position += 1;
        position <= reported || d.kind != DiagnosticKind::NoFeed
    });
    let profile = match profile {
        Ok(profile) => profile,
        Err(diagnostic) => {
            interp.diagnostics.push(diagnostic);
            return None;
        }
    };
    if profile.segments.len() < 2 {
        interp.error(DiagnosticKind::LapContourEmpty, contour_span);
        return None;
    }
    let follows_call =
        first > index && (index + 1..first).all(|b| matches!(interp.program.block(b).statement, Statement::Empty));
    let contour_feed = contour_feeds(interp, &profile);
    let direction =
        if function == GFunction::LapContourTransverse { Direction::Transverse } else { Direction::Longitudinal };
    Some(Contour { profile, direction, blocks: first..=last, follows_call, contour_feed, span: contour_span })
}

/// The LAP marker function of a block (`G81`, `G82`, `G83`), if it starts a contour or blank.
fn contour_function(interp: &Interpreter<'_, '_>, index: usize) -> Option<GFunction> {
    let block = interp.program.block(index);
    if !matches!(block.statement, Statement::LapMarker(_)) {
        return None;
    }
    interp.g_infos(interp.program.words_of(block)).find_map(|(_, g)| match g.function {
        Some(f @ (GFunction::LapContourLongitudinal | GFunction::LapContourTransverse | GFunction::LapBlank)) => {
            Some(f)
        }
        _ => None,
    })
}

/// The modal `E` of the contour's blocks, for each segment: the value after the last block
/// that starts at or before the segment's block.
fn contour_feeds(interp: &mut Interpreter<'_, '_>, profile: &Profile) -> Vec<Option<f64>> {
    let mut in_force = None;
    let mut by_block: Vec<(u32, Option<f64>)> = Vec::new();
    for index in profile.blocks.clone() {
        let block = *interp.program.block(index);
        let words = effective_words(interp.program.words_of(&block), interp.options.block_delete).to_vec();
        if let Some(e) = interp.address_value(&words, Address::E) {
            in_force = Some(e);
        }
        by_block.push((block.span.start, in_force));
    }
    profile
        .segments
        .iter()
        .map(|s| by_block.iter().rev().find(|(start, _)| *start <= s.source.start).and_then(|(_, e)| *e))
        .collect()
}

/// Back to the AP start point `start` at rapid, in the order the module documentation gives.
pub(super) fn return_to_start(interp: &mut Interpreter<'_, '_>, contour: &Contour, start: Xz) {
    let at = interp.emitter.at;
    let z_first = match contour.direction {
        Direction::Longitudinal => contour.approach_rapid(),
        Direction::Transverse => !contour.approach_rapid(),
    };
    let via = if z_first { Xz::new(at.x, start.z) } else { Xz::new(start.x, at.z) };
    let modal = interp.modal.clone();
    interp.emitter.rapid(&modal, via);
    interp.emitter.rapid(&modal, start);
}
