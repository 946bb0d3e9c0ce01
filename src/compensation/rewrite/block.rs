//! One motion block written back in its own form.
//!
//! The block keeps every word that is not a coordinate of its motion, in place and as
//! written (`NewWord::Copy`): sequence name, block delete, modal codes, F, S, T, M,
//! comments. Its coordinate words take the new values in the form the block wrote them:
//! `X`/`Z` absolute, `U`/`W` or `G91` `X`/`Z` incremental, `R`/`L` radius or `I K` centre,
//! in the order they were written; a word whose value does not change is copied as it was.
//! An axis the block did not name is added only when the axis now moves. Increments are
//! differences of rounded absolutes (`back/grid.rs`), so they never drift.
//!
//! A move that becomes several segments puts the block's other words on its first block;
//! the others carry a motion code where it changes, and the coordinates. If the last one
//! leaves a different motion code in force than the original block did, a block with that
//! code alone restores it for the blocks that follow, unless the block the control runs
//! next writes its own (`back::motion::GivenNext`) or carries it (`BlockContext::carried`,
//! `MotionBlocks::fold`): then that block writes the code among its own words.
//!
//! This module decides which words the block gets; they are written through the back end's
//! writer (`back::motion::MotionWriter`): its codes from the dialect tables, its
//! coordinates as counts on the grid.

use smallvec::SmallVec;

use crate::back::grid::{ArcWords, Grid, GridPoint};
use crate::back::motion::{Codes, GivenNext, Kind, MotionWriter, Restore};
use crate::dialect::{Address, AddressKind, Dialect};
use crate::printer::{BlockWriter, WrittenText};
use crate::semantic::CoordinateMark;
use crate::semantic::nose_radius::ToolTable;
use crate::syntax::{CodeLetter, Program, WordKind};
use crate::toolpath::{Move, Xz};

use super::super::fit::Segment;
use super::super::plan::{MovePlan, nominal_segment};

/// The kind a segment is written as, in a block whose move was `original`.
fn segment_kind(segment: &Segment, original: Kind) -> Kind {
    match segment {
        Segment::Line { .. } if matches!(original, Kind::Rapid | Kind::Thread) => original,
        Segment::Line { .. } => Kind::Feed,
        Segment::Arc { ccw: true, .. } => Kind::Ccw,
        Segment::Arc { ccw: false, .. } => Kind::Cw,
    }
}

/// Which coordinate a word gives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Slot {
    X,
    Z,
    Radius,
    I,
    K,
    /// OSP `A`: a line's direction angle; dropped, both axes are written instead.
    Angle,
}

/// How the block writes its coordinates.
#[derive(Debug, Clone, Copy)]
struct Form {
    /// The address of each axis, and whether it is absolute.
    x: (Address, bool),
    z: (Address, bool),
    /// Arcs by radius (`R`, OSP `L`) rather than `I K`.
    radius_arcs: bool,
    radius_address: Address,
    /// The block names each axis (or gives `A`, which needs both).
    x_named: bool,
    z_named: bool,
}

/// The context one block is written in.
pub(super) struct BlockContext<'a, 'src> {
    pub program: &'a Program<'src>,
    /// The dialect's codes (`MotionWriter::codes`), looked up once for all blocks.
    pub codes: Codes,
    pub block: usize,
    pub mark: CoordinateMark,
    pub grid: Grid,
    /// The program's arcs are mostly `R`/`L` (for arcs in a block that wrote none).
    pub radius_arcs: bool,
    pub tools: &'a ToolTable,
    /// A kept thread cycle's lead words, written in place of its lead word
    /// (`cycles::thread_lead`).
    pub lead: Option<&'a super::cycles::LeadWords>,
    /// The lead words of each segment after the first, for a thread move written as thread
    /// blocks each with its own lead (`thread_pieces`); empty for any other.
    pub piece_leads: &'a [LeadWordList],
    /// After the pieces, the block's own lead word is written again on a block of its own:
    /// the pieces leave another `F` in force, and a later cut runs at the block's.
    pub restore_lead: bool,
    /// For a thread cycle call that repeats the call before it (`G92 X22.7` after `G92 X23.2
    /// Z-30. F2.`), the end that call's final pass runs to as written: the control takes
    /// the axes the block does not name from it, so such an axis is written only where the
    /// block's own final pass ends elsewhere.
    pub inherited: Option<GridPoint>,
    /// For a kept single turning or facing cycle (`cycles::single_cut`), the taper its cut
    /// needs (`R`, a count of the grid's lengths) where it differs from the one in force:
    /// written in place of the block's taper word, or after its coordinates where it writes
    /// none.
    pub taper: Option<i64>,
    /// Modal words the blocks before it left out of force, which this block puts back
    /// rather than a block of their own (`MotionBlocks::fold`): its motion code, F and S.
    pub carried: Restore,
}

/// The words one lead is written with (`back::thread_lead::WrittenLead::words`).
pub(super) type LeadWordList = SmallVec<[(Address, crate::syntax::Number); 2]>;

/// The coordinate words of one segment, by slot, as counts of the increment (at most four:
/// `X Z`, and `R` or `I K`).
type Words = SmallVec<[(Slot, i64); 4]>;

/// A word of the block that gives a coordinate of its move.
#[derive(Debug, Clone, Copy)]
struct CoordinateWord {
    /// Its place among the block's words.
    position: usize,
    slot: Slot,
    address: Address,
    /// Its value when written as a literal (not an expression).
    literal: Option<crate::syntax::Number>,
}

/// A block's coordinate words in block order (a block rarely has more than four).
type CoordinateWords = SmallVec<[CoordinateWord; 4]>;

/// The coordinate words a block writes, by slot: a literal's value, or for an expression the
/// value it had on this run (`None` when the run has no such word).
type OriginalWords = SmallVec<[(Slot, Option<i64>); 4]>;

impl BlockContext<'_, '_> {
    /// The block's coordinate words, found once for everything that reads them.
    fn coordinate_words(&self, is_arc: bool) -> CoordinateWords {
        let block = self.program.block(self.block);
        let dialect = self.codes.dialect;
        let mut out = CoordinateWords::new();
        for (position, word) in self.program.words_of(block).iter().enumerate() {
            let (address, literal) = match word.kind {
                WordKind::Number { address, number } => (address, Some(number)),
                WordKind::Expr { address, .. } => (address, None),
                _ => continue,
            };
            if let Some(slot) = slot(dialect, address, is_arc) {
                out.push(CoordinateWord { position, slot, address, literal });
            }
        }
        out
    }

    fn form(&self, coordinates: &[CoordinateWord]) -> Form {
        let absolute = self.mark.absolute;
        let radius_address = self.codes.radius_address;
        let mut form = Form {
            x: (Address::X, absolute),
            z: (Address::Z, absolute),
            radius_arcs: radius_form(coordinates.iter().map(|c| c.slot)).unwrap_or(self.radius_arcs),
            radius_address,
            x_named: false,
            z_named: false,
        };
        for &CoordinateWord { slot, address, .. } in coordinates {
            match slot {
                Slot::X => {
                    form.x = (address, address == Address::X && absolute);
                    form.x_named = true;
                }
                Slot::Z => {
                    form.z = (address, address == Address::Z && absolute);
                    form.z_named = true;
                }
                Slot::Angle => {
                    form.x_named = true;
                    form.z_named = true;
                }
                _ => {}
            }
        }
        // An axis the block does not name is written the way it writes the other one
        // (`W-20.` gains a `U`, not an `X`).
        if form.z_named && !form.x_named && !form.z.1 {
            form.x = (if form.z.0 == Address::W { Address::U } else { Address::X }, false);
        }
        if form.x_named && !form.z_named && !form.x.1 {
            form.z = (if form.x.0 == Address::U { Address::W } else { Address::Z }, false);
        }
        form
    }

    /// The words of `segment` from `start` (exact; `from` on the grid), in `form`; an arc's
    /// are `chosen` where the plan chose them already (`MovePlan::words`). Also the segment's
    /// end on the grid, where the next segment starts.
    fn words(
        &self,
        form: &Form,
        (start, from): (Xz, GridPoint),
        segment: &Segment,
        chosen: Option<ArcWords>,
    ) -> (Words, GridPoint) {
        self.words_inheriting(form, (start, from), segment, chosen, None)
    }

    /// [`Self::words`], where the control takes an axis the block does not name from
    /// `inherited` (a repeated cycle call, `BlockContext::inherited`) rather than from where
    /// the move starts.
    fn words_inheriting(
        &self,
        form: &Form,
        (start, from): (Xz, GridPoint),
        segment: &Segment,
        chosen: Option<ArcWords>,
        inherited: Option<GridPoint>,
    ) -> (Words, GridPoint) {
        let grid = &self.grid;
        let to = grid.point(segment.end());
        let mut out = Words::new();
        let axis = |absolute: bool, end: i64, begin: i64| if absolute { end } else { end - begin };
        // An axis a repeated cycle call does not name ends where the call before it ended,
        // absolute or incremental alike.
        let held_x = inherited.map_or(from.x, |p| p.x);
        let held_z = inherited.map_or(from.z, |p| p.z);
        if form.x_named || to.x != held_x {
            out.push((Slot::X, axis(form.x.1, to.x, from.x)));
        }
        if form.z_named || to.z != held_z {
            out.push((Slot::Z, axis(form.z.1, to.z, from.z)));
        }
        if let Segment::Arc { end, centre, ccw } = *segment {
            let words = chosen.unwrap_or_else(|| grid.arc_words(start, end, centre, ccw, form.radius_arcs));
            match words {
                ArcWords::Radius(radius) => out.push((Slot::Radius, radius)),
                ArcWords::Centre { i, k } => {
                    out.push((Slot::I, i));
                    out.push((Slot::K, k));
                }
                // The plan writes such an arc as a line (`plan::settle_arcs`); were one
                // to come here, its centre offsets are still words a control runs.
                ArcWords::Line => {
                    let at = grid.to_mm(from);
                    out.push((Slot::I, grid.length(centre.x - at.x)));
                    out.push((Slot::K, grid.length(centre.z - at.z)));
                }
            }
        }
        (out, to)
    }

    /// What the block's coordinate words say now: a literal's value, or for an expression
    /// the value it had on this run (the nominal move).
    fn original_words(
        &self,
        form: &Form,
        coordinates: &[CoordinateWord],
        m: &Move,
        contour_start: Xz,
    ) -> OriginalWords {
        let tables = self.codes.tables;
        // The programmed move's words, for a word written as an expression: computed only
        // for such a block.
        let nominal = std::cell::OnceCell::new();
        let nominal = || {
            nominal.get_or_init(|| {
                let start = (contour_start, self.grid.point(contour_start));
                self.words(form, start, &nominal_segment(m, self.tools), None).0
            })
        };
        let mut out = OriginalWords::new();
        for &CoordinateWord { slot, address, literal, .. } in coordinates {
            let value =
                match literal {
                    Some(number) => Some(self.grid.literal_count(number, || {
                        tables.address(address).map(|s| s.kind).or(Some(AddressKind::Length))
                    })),
                    None => nominal().iter().find(|(s, _)| *s == slot).map(|&(_, v)| v),
                };
            out.push((slot, value));
        }
        out
    }

    /// Write the coordinate word of `slot` with `value` (a count of increments) in `form`.
    fn write_coordinate(&self, form: &Form, slot: Slot, value: i64, out: &mut MotionWriter<BlockWriter<'_, '_>>) {
        let address = match slot {
            Slot::X => form.x.0,
            Slot::Z => form.z.0,
            Slot::Radius => form.radius_address,
            Slot::I => Address::I,
            Slot::K => Address::K,
            Slot::Angle => Address::A,
        };
        out.coordinate(&self.grid, address, value);
    }

    /// Write the blocks that replace this block for one move and its plan to `out`, or
    /// nothing (`None`) when the block already writes it; with what its last block puts
    /// back where that block only restores modal words for the blocks after it.
    pub(super) fn rewrite(
        &self,
        m: &Move,
        contour_start: Xz,
        plan: &MovePlan,
        out: &mut MotionWriter<BlockWriter<'_, '_>>,
    ) -> Option<(WrittenText, Restore)> {
        let start = self.grid.point(plan.start);
        let carries = !self.carried.is_none();
        if !plan.changed
            && start == self.grid.point(contour_start)
            && self.lead.is_none()
            && self.taper.is_none()
            && !carries
        {
            // The move is as programmed, from where the program puts it.
            return None;
        }
        let original_kind = Kind::of(m);
        let coordinates = self.coordinate_words(m.is_arc());
        let form = self.form(&coordinates);
        let mut at = (plan.start, start);
        // The motion code the block's own words run under, when it is not the modal one.
        let mut in_force = original_kind;
        let mut segments = plan.segments.as_slice();
        let mut chosen = plan.words.iter().map(|&w| Some(w)).chain(std::iter::repeat(None));
        // The play taken up before the block, by a positioning move of its own.
        let mut lead_words = None;
        if plan.lead_in
            && let Some((lead, rest)) = segments.split_first()
        {
            let (words, end) = self.words(&form, at, lead, chosen.next().flatten());
            lead_words = Some(words);
            in_force = Kind::Rapid;
            at = (lead.end(), end);
            segments = rest;
        }
        let (first, rest) = segments.split_first()?;
        let first_kind = segment_kind(first, original_kind);
        let original = self.original_words(&form, &coordinates, m, contour_start);
        let (new, end) = self.words_inheriting(&form, at, first, chosen.next().flatten(), self.inherited);
        let same_words = original.len() == new.len()
            && new.iter().all(|(slot, value)| original.iter().any(|(s, v)| s == slot && *v == Some(*value)));
        if lead_words.is_none()
            && rest.is_empty()
            && first_kind == original_kind
            && same_words
            && self.lead.is_none()
            && self.taper.is_none()
            && !carries
        {
            return None;
        }
        let mark = out.out.begin();
        if let Some(lead_words) = lead_words {
            out.motion(Kind::Rapid);
            for (slot, value) in lead_words {
                self.write_coordinate(&form, slot, value, out);
            }
            out.out.next_block();
        }
        let code_changes = first_kind != original_kind || in_force != original_kind || self.carried.motion.is_some();
        self.first_block(&form, &coordinates, &new, &original, code_changes.then_some(first_kind), out);
        let mut kind = first_kind;
        at = (first.end(), end);
        for (n, segment) in rest.iter().enumerate() {
            out.out.next_block();
            let segment_kind = segment_kind(segment, original_kind);
            if segment_kind != kind {
                out.motion(segment_kind);
                kind = segment_kind;
            }
            let (words, end) = self.words(&form, at, segment, chosen.next().flatten());
            for (slot, value) in words {
                self.write_coordinate(&form, slot, value, out);
            }
            for &(address, number) in self.piece_leads.get(n).into_iter().flatten() {
                out.out.number(address, number);
            }
            at = (segment.end(), end);
        }
        // The block's own lead (`restore_lead`) and motion code, put back for the blocks after
        // it, on one block.
        let lead = self.lead.filter(|_| self.restore_lead);
        let motion = (kind != original_kind
            && !GivenNext::after(self.program, &self.codes, self.block, |_| false).motion)
            .then_some(original_kind);
        let mut restore = Restore::default();
        if lead.is_some() || motion.is_some() {
            out.out.next_block();
            if let Some(kind) = motion {
                out.motion(kind);
                restore.motion = Some(kind);
            }
            if let Some(lead) = lead {
                let at = self.program.block(self.block).first_word + lead.at as u32;
                out.copy(at);
                // An `F` written as an expression stays on the block of its own.
                match self.program.word(at).kind {
                    WordKind::Number { address: Address::F, number } => restore.feed = Some(number),
                    _ => restore = Restore::default(),
                }
            }
        }
        Some((out.out.finish(mark), restore))
    }

    /// Write the block's own words with the first segment's coordinates, and the motion
    /// code `new_code` where it changes.
    fn first_block(
        &self,
        form: &Form,
        coordinates: &[CoordinateWord],
        new: &Words,
        original: &[(Slot, Option<i64>)],
        new_code: Option<Kind>,
        out: &mut MotionWriter<BlockWriter<'_, '_>>,
    ) {
        let block = self.program.block(self.block);
        let words = self.program.words_of(block);
        let last_coordinate = coordinates.last().map(|c| c.position);
        let first_coordinate = coordinates.first().map(|c| c.position);
        // The coordinate words still ahead, in block order.
        let mut ahead = coordinates.iter().peekable();
        let mut written: SmallVec<[Slot; 4]> = SmallVec::new();
        let mut code_written = false;
        // A single cycle's taper goes in place of its `R`, or after its coordinates: once.
        let has_taper_word = words.iter().any(|w| matches!(w.kind, WordKind::Number { address: Address::R, .. }));
        let mut taper_written = false;
        let mut taper = || (!std::mem::replace(&mut taper_written, true)).then_some(self.taper).flatten();
        let first = block.first_word;
        for (k, word) in words.iter().enumerate() {
            let id = first + k as u32;
            if let Some(kind) = new_code
                && !code_written
                && first_coordinate == Some(k)
            {
                out.motion(kind);
                code_written = true;
            }
            let coordinate = ahead.next_if(|c| c.position == k);
            match (word.kind, new_code, coordinate) {
                (_, _, Some(&CoordinateWord { slot, address, literal, .. })) => {
                    if let Some((slot, value)) = new.iter().find(|(n, _)| *n == slot).copied()
                        && !written.contains(&slot)
                    {
                        let unchanged = original.iter().any(|(s, v)| *s == slot && *v == Some(value))
                            && literal.is_some()
                            && same_address(form, slot, address);
                        if unchanged {
                            out.copy(id);
                        } else {
                            self.write_coordinate(form, slot, value, out);
                        }
                        written.push(slot);
                    }
                }
                (WordKind::Code { letter: CodeLetter::G, code }, Some(kind), None)
                    if self.codes.kind_of(code).is_some() =>
                {
                    if !code_written {
                        if self.codes.kind_of(code) == Some(kind) {
                            out.copy(id);
                        } else {
                            out.motion(kind);
                        }
                        code_written = true;
                    }
                }
                (WordKind::Number { address: Address::R, .. }, ..) if self.taper.is_some() => {
                    if let Some(taper) = taper() {
                        out.coordinate(&self.grid, Address::R, taper);
                    }
                }
                _ => match self.lead {
                    Some(lead) if lead.at == k => {
                        for &(address, number) in &lead.words {
                            out.out.number(address, number);
                        }
                    }
                    Some(super::cycles::LeadWords { change: Some((at, value)), .. }) if *at == k => match word.kind {
                        WordKind::Number { address, .. } => out.out.number(address, *value),
                        _ => out.copy(id),
                    },
                    _ => out.copy(id),
                },
            }
            if last_coordinate == Some(k) {
                for &(slot, value) in new {
                    if !written.contains(&slot) {
                        self.write_coordinate(form, slot, value, out);
                        written.push(slot);
                    }
                }
                if !has_taper_word && let Some(taper) = taper() {
                    out.coordinate(&self.grid, Address::R, taper);
                }
                out.restored(Restore { motion: None, ..self.carried });
            }
        }
        if last_coordinate.is_none() {
            if let Some(kind) = new_code
                && !code_written
            {
                out.motion(kind);
            }
            for &(slot, value) in new {
                self.write_coordinate(form, slot, value, out);
            }
            if let Some(taper) = taper() {
                out.coordinate(&self.grid, Address::R, taper);
            }
            out.restored(Restore { motion: None, ..self.carried });
        }
    }
}

/// The axes the motion block `block` names (`X`/`U`, `Z`/`W`; OSP's `A` with one of them
/// places both), each with whether its word counts from where the move starts (`U`, `W`,
/// or `X`, `Z` where the coordinates are not `absolute`); `None` for an axis it leaves
/// where the tool stands.
pub(super) fn named_axes(program: &Program<'_>, block: usize, absolute: bool) -> [Option<bool>; 2] {
    let dialect = program.config().dialect;
    let mut named = [None, None];
    for word in program.words_of(program.block(block)) {
        let address = match word.kind {
            WordKind::Number { address, .. } | WordKind::Expr { address, .. } => address,
            _ => continue,
        };
        let incremental = !absolute || matches!(address, Address::U | Address::W);
        match slot(dialect, address, false) {
            Some(Slot::X) => named[0] = Some(incremental),
            Some(Slot::Z) => named[1] = Some(incremental),
            Some(Slot::Angle) => {
                named[0] = named[0].or(Some(incremental));
                named[1] = named[1].or(Some(incremental));
            }
            _ => {}
        }
    }
    named
}

/// Which coordinate the word at `address` gives in a block of `dialect` (`is_arc`: the
/// block's move is an arc, where `R`/`L`, `I` and `K` place the centre).
fn slot(dialect: Dialect, address: Address, is_arc: bool) -> Option<Slot> {
    let radius = if dialect == Dialect::Osp { Address::L } else { Address::R };
    match address {
        Address::X => Some(Slot::X),
        Address::Z => Some(Slot::Z),
        Address::U if dialect == Dialect::Fanuc => Some(Slot::X),
        Address::W if dialect == Dialect::Fanuc => Some(Slot::Z),
        Address::A if dialect == Dialect::Osp && !is_arc => Some(Slot::Angle),
        a if a == radius && is_arc => Some(Slot::Radius),
        Address::I if is_arc => Some(Slot::I),
        Address::K if is_arc => Some(Slot::K),
        _ => None,
    }
}

/// Whether the arcs written for `block` (whose move is an arc when `is_arc`) prefer the
/// radius form: as the block writes its own arc (`R`/`L`, or `I K`), else as the program
/// mostly does (`program_radius_arcs`). A line block has no arc words (an `R` there is no
/// radius).
pub(super) fn writes_radius(program: &Program<'_>, block: usize, is_arc: bool, program_radius_arcs: bool) -> bool {
    // `slot` gives a line's words no radius or centre slot, so a line takes the program's
    // form without its words being read (most moves of a long program are lines).
    if !is_arc {
        return program_radius_arcs;
    }
    let dialect = program.config().dialect;
    let slots = program.words_of(program.block(block)).iter().filter_map(|word| match word.kind {
        WordKind::Number { address, .. } | WordKind::Expr { address, .. } => slot(dialect, address, is_arc),
        _ => None,
    });
    radius_form(slots).unwrap_or(program_radius_arcs)
}

/// Whether a block whose coordinate words give `slots` writes its arc by radius, or `None`
/// when it writes neither a radius nor a centre.
fn radius_form(slots: impl Iterator<Item = Slot>) -> Option<bool> {
    let (mut radius, mut centre) = (false, false);
    for slot in slots {
        match slot {
            Slot::Radius => radius = true,
            Slot::I | Slot::K => centre = true,
            _ => {}
        }
    }
    (radius || centre).then_some(radius)
}

/// Whether the word at `address` is written with the address the form uses for `slot`.
fn same_address(form: &Form, slot: Slot, address: Address) -> bool {
    match slot {
        Slot::X => form.x.0 == address,
        Slot::Z => form.z.0 == address,
        Slot::Radius => form.radius_address == address,
        Slot::I => address == Address::I,
        Slot::K => address == Address::K,
        Slot::Angle => false,
    }
}

#[cfg(test)]
mod tests;
