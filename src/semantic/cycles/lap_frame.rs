//! The frame the LAP roughing cycles (`G85`, `G86`) share: the canonical frame of
//! `canonical.rs` set up for a LAP contour, the finishing allowance, and the stock the
//! control assumes.
//!
//! In the canonical frame levels step down in `u` toward the contour and passes cut toward
//! decreasing `v`: a `G81` contour maps X to `u` and Z to `v`, a `G82` contour swaps them; an
//! inside contour mirrors `u` and a contour running toward +Z (+X) mirrors `v`. The allowance
//! then always points up and back, toward the stock: `(+U/2, +W)` for `G81`, `(+W, +U/2)` for
//! `G82` (`U` and `W` are unsigned on OSP, M-P175).
//!
//! **The stock.** Without a `G83` blank nothing but the AP start point bounds the stock.
//! M-P195 puts the N-th infeed point on the straight line from the AP start point A = (Xs,
//! Zs) to the contour's start point shifted by the allowance, C0 = (Xa + U, Za + W): its
//! `Zp = Za + W + (Zs − Za − W)(1 − N·D/(Xs − Xa − U))` is that line's parametric form, the
//! parameter being the share of the stock depth already cut. We read the line as the edge
//! of the stock the control assumes: on A's side of it is air, on the contour's side stock.
//! When the line leans so that a plunge down to the next level crosses stock (A further back
//! along the cut than C0), the plunge is fed; otherwise it is a rapid. In the usual program,
//! whose first contour block names only X (`G00 X42.018`, so Za = Zs), the line is a face
//! line just in front of the part and every plunge is in air.

use crate::toolpath::Xz;

use super::super::interpreter::Interpreter;
use super::super::profile::Shape;
use super::canonical::{self, Canon, Element, Uv};
use super::lap_contour::{Contour, Direction};

/// The relief after each roughing pass (`Relieving amount in LAP-bar turning`, an optional
/// parameter of the control, 100 µm by default, M-P175), mm, in each axis.
pub(super) const RELIEF_MM: f64 = 0.1;

/// The control stops after this many passes; a depth that would need more is rejected.
pub(super) const MAX_PASSES: f64 = 10_000.0;

#[derive(Debug, Clone)]
pub(super) struct RoughFrame {
    pub canon: Canon,
    /// The AP start point, canonical.
    pub start: Uv,
    /// The contour's start point shifted by the allowance, canonical.
    pub contour_start: Uv,
    /// The allowance as a vector in the toolpath frame.
    pub allowance: Xz,
    /// The contour after its approach block, shifted by the allowance, canonical.
    pub elements: Vec<Element>,
}

impl RoughFrame {
    /// The frame for `contour` roughed from `start`, with the allowances in X (`U`, as a
    /// radius) and Z (`W`), mm.
    pub fn new(contour: &Contour, start: Xz, x_allowance: f64, z_allowance: f64) -> RoughFrame {
        let swap = contour.direction == Direction::Transverse;
        let first = contour.start();
        let end = contour.profile.end();
        let across = |p: Xz| if swap { p.z } else { p.x };
        let along = |p: Xz| if swap { p.x } else { p.z };
        let canon = Canon { swap, mirror_u: across(start) < across(first), mirror_v: along(end) > along(first) };
        let (u_allowance, v_allowance) = if swap { (z_allowance, x_allowance) } else { (x_allowance, z_allowance) };
        // A vector maps like a point: the canonical maps are linear.
        let allowance = canon.from(Uv { u: u_allowance, v: v_allowance });
        let elements = canonical::elements(&canon, &contour.profile, allowance, true);
        let contour_start = canon.to(Xz::new(first.x + allowance.x, first.z + allowance.z));
        RoughFrame { canon, start: canon.to(start), contour_start, allowance, elements }
    }

    /// The depth of stock above the contour start, along `u`.
    pub fn stock_depth(&self) -> f64 {
        self.start.u - self.contour_start.u
    }

    /// The infeed line from A to C0 at level `u`: M-P195's Zp (Xp for `G82`).
    pub fn line_v(&self, u: f64) -> f64 {
        let depth = self.stock_depth();
        if depth <= 1e-12 {
            return self.start.v;
        }
        self.contour_start.v + (self.start.v - self.contour_start.v) * (u - self.contour_start.u) / depth
    }

    /// Whether a plunge at the infeed line crosses the stock the control assumes (see the
    /// module documentation): A lies further back along the cut than C0.
    pub fn plunge_cuts(&self) -> bool {
        self.start.v > self.contour_start.v + 1e-9
    }

    /// Move the tool to the canonical point `p`, at rapid or as a cut at the modal feed.
    /// A feed move that goes nowhere is no move.
    pub fn go(&self, interp: &mut Interpreter<'_, '_>, p: Uv, rapid: bool) {
        let modal = interp.modal.clone();
        let to = self.canon.from(p);
        if rapid {
            interp.emitter.rapid(&modal, to);
        } else if interp.emitter.at.distance(to) > 1e-9 {
            interp.emitter.line(&modal, to, true);
        }
    }
}

/// Cut along the contour after its approach block, shifted by `offset` (toolpath frame), at
/// the feed `feed(segment index)` gives each element, program units.
pub(super) fn cut_along(interp: &mut Interpreter<'_, '_>, contour: &Contour, offset: Xz, feed: impl Fn(usize) -> f64) {
    let shift = |p: Xz| Xz::new(p.x + offset.x, p.z + offset.z);
    let mut at = shift(contour.start());
    for (i, segment) in contour.profile.segments.iter().enumerate().skip(1) {
        let end = shift(segment.end);
        // The same elements `canonical::elements` keeps: nothing of zero length.
        if at.distance(end) <= 1e-12 {
            continue;
        }
        interp.modal.feed = feed(i);
        let modal = interp.modal.clone();
        match segment.shape {
            Shape::Line => interp.emitter.line(&modal, end, true),
            Shape::Arc { centre, ccw } => interp.emitter.arc(&modal, end, shift(centre), ccw, true),
        }
        at = end;
    }
}
