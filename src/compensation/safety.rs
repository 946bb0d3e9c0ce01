//! The checks that make `compensate` refuse a program rather than write it.
//!
//! A correction is a few micrometres on a healthy machine. One larger than `--max-shift`
//! means a wrong model (a table in inches read as mm, a sign turned over) or a program the
//! model does not cover, and a program moved that far must not reach a machine unread. A
//! commanded point outside the travel limits would stop the machine mid-cut: the control
//! checks its stroke limits on the points the program commands, so the check takes the
//! points as written (rounded to the increment), where a move left as written (a rapid to
//! the reference point) commands exactly what it did. Both are
//! errors on the block whose move has them (the cycle call for a cycle's moves), one per
//! block, naming the worst point.

use std::collections::BTreeMap;

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::source::Span;
use crate::toolpath::{Limits, Toolpath, Xz};

use crate::error_model::sampling::PathSample;

/// Slack at a travel limit, mm: rounding at a limit is no violation (as `toolpath::validate`).
const LIMIT_SLACK_MM: f64 = 0.001;

/// The refusals for the commanded points of samples given one by one, in path order.
#[derive(Debug, Clone)]
pub struct Check {
    max_shift_mm: f64,
    limits: Option<Limits>,
    /// Per block (keyed by span start, so the diagnostics come out in program order): the
    /// largest correction, and the first point outside the travel.
    shifts: BTreeMap<u32, (Span, f64)>,
    outside: BTreeMap<u32, (Span, Xz)>,
}

impl Check {
    pub fn new(max_shift_mm: f64, limits: Option<Limits>) -> Check {
        Check { max_shift_mm, limits, shifts: BTreeMap::new(), outside: BTreeMap::new() }
    }

    /// Check the next sample: `shift`, the inverse's correction there (the distance of its
    /// commanded point from the sample's nominal one, which the caller has measured already),
    /// and `written`, the point the written program commands there.
    pub fn add(&mut self, toolpath: &Toolpath, s: &PathSample, written: Xz, shift: f64) {
        let Some(m) = toolpath.moves.get(s.move_index) else { return };
        let span = m.source;
        let shift = if shift.is_finite() { shift } else { f64::INFINITY };
        if shift > self.max_shift_mm {
            let entry = self.shifts.entry(span.start).or_insert((span, shift));
            entry.1 = entry.1.max(shift);
        }
        if let Some(limits) = self.limits
            && !inside(&limits, written)
        {
            self.outside.entry(span.start).or_insert((span, written));
        }
    }

    /// The refusals, in program order.
    pub fn finish(self) -> Vec<Diagnostic> {
        let max_mm = self.max_shift_mm;
        let mut out: Vec<Diagnostic> = self
            .shifts
            .into_values()
            .map(|(span, shift)| {
                Diagnostic::error(DiagnosticKind::CorrectionTooLarge { shift_mm: shift, max_mm }, span)
            })
            .collect();
        out.extend(self.outside.into_values().map(|(span, p)| {
            Diagnostic::error(DiagnosticKind::CompensatedOutsideTravel { x_mm: p.x, z_mm: p.z }, span)
        }));
        out.sort_by_key(|d| d.span.start);
        out
    }
}

fn inside(limits: &Limits, p: Xz) -> bool {
    p.x >= limits.x_min - LIMIT_SLACK_MM
        && p.x <= limits.x_max + LIMIT_SLACK_MM
        && p.z >= limits.z_min - LIMIT_SLACK_MM
        && p.z <= limits.z_max + LIMIT_SLACK_MM
}
