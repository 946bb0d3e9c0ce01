//! Motion blocks: rapids, lines, arcs and thread moves, from their words to IR moves.
//!
//! - End points: `X`/`Z` absolute (incremental under `G91`), Fanuc `U`/`W` incremental; X is
//!   converted from diameter and program units by the frame, then shifted by `G50 X Z`.
//! - Arcs: `I`/`K` give the centre from the start (I as a radius); `R` (Fanuc) or `L` (OSP)
//!   the radius, negative for more than half a circle. A radius that cannot reach is an
//!   error; an `I`/`K` centre whose end radius differs by up to 0.02 mm is moved onto the
//!   chord's bisector, as the controls tolerate it.
//! - OSP `A`, Fanuc `,A` (direct drawing dimension input): a line given by one coordinate
//!   and its direction angle (from +Z, counter-clockwise).
//! - OSP `G75`/`G76` with `L`, Fanuc `,C`/`,R` in a `G01` block: a chamfer or a rounding
//!   between this line and the next, which waits for the next move. Corners may follow
//!   each other block after block: a corner block after a corner completes the first and
//!   waits in its turn (`grammar/fanuc.toml` `[comma]` cites the manual that shows it).

use crate::diagnostic::DiagnosticKind;
use crate::dialect::{Address, Dialect, GFunction};
use crate::geometry;
use crate::source::Span;
use crate::syntax::{Statement, Word};
use crate::toolpath::Xz;

use super::block::word_address;
use super::interpreter::{Flow, Interpreter};
use super::modal::{Modal, MotionMode};

/// The end point a block's axis words give, and which axes they named.
#[derive(Debug, Clone, Copy)]
pub(super) struct AxisTarget {
    pub target: Option<Xz>,
    pub x_given: bool,
    pub z_given: bool,
    pub any: bool,
}

/// An automatic corner waiting for the move after it.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct PendingCorner {
    pub round: bool,
    pub size: f64,
    pub from: Xz,
    pub corner: Xz,
    pub modal: Modal,
    pub context: super::emitter::Context,
    /// The word that gave the size (`L`, `,C`, `,R`), for diagnostics.
    pub word: &'static str,
    /// A Fanuc corner's block and the modal words before it: `expand` writes its moves out
    /// (an OSP corner is a code the control has, and stays).
    pub expand: Option<(usize, super::ModalAfter)>,
}

/// A corner a line block asks for: rounded or chamfered, its size (program units) and the
/// word that gives it.
struct CornerRequest {
    round: bool,
    size: f64,
    word: &'static str,
    fanuc: bool,
}

impl Interpreter<'_, '_> {
    /// The start angle a thread move block writes (`G32 Q`, a count of 0.001°). The control
    /// takes the word without a decimal point only: one written with a point is an error,
    /// and the block starts at the spindle's index.
    fn thread_start_angle(&mut self, words: &[Word]) -> Option<f64> {
        let address = self.tables.thread_move.start_angle?;
        let word = *words.iter().find(|w| word_address(w) == Some(address))?;
        if let crate::syntax::WordKind::Number { number, .. } = word.kind
            && number.has_point()
        {
            let unit = crate::dialect::IntegerUnit::AngleIncrements;
            let code = self.tables.code_for(GFunction::ThreadMove).map_or_else(String::new, |c| c.display('G'));
            let counted = crate::diagnostic::CountedWord {
                command: format!("{code} (thread cutting)"),
                address: address.name(),
                written: format!("{}{}", address.name(), crate::syntax::spelling::plain(number)),
                unit,
                meant: crate::dialect::roles::meant(unit, number.to_f64(), None)
                    .map(|(count, reading)| (format!("{}{count}", address.name()), reading)),
                control: self.tables.config.control.name(),
                elsewhere: None,
            };
            self.error(DiagnosticKind::IntegerExpected(Box::new(counted)), word.span);
            return None;
        }
        self.word_value(&word)
    }

    /// The end point of a block's `X Z U W` words (and OSP `A`).
    pub fn axis_target(&mut self, words: &[Word]) -> AxisTarget {
        let frame = self.modal.frame;
        let at = self.emitter.at;
        let shift = self.modal.shift;
        let (mut x, mut z) = (None::<f64>, None::<f64>);
        let (mut x_given, mut z_given) = (false, false);
        for word in words {
            let Some(address) = word_address(word) else { continue };
            let incremental_xz = !self.modal.absolute;
            match (address, self.dialect) {
                (Address::X, _) => {
                    let Some(v) = self.word_value(word) else { continue };
                    x = Some(if incremental_xz { at.x + frame.x_mm(v) } else { frame.x_mm(v) + shift.x });
                    x_given = true;
                }
                (Address::Z, _) => {
                    let Some(v) = self.word_value(word) else { continue };
                    z = Some(if incremental_xz { at.z + frame.mm(v) } else { frame.mm(v) + shift.z });
                    z_given = true;
                }
                (Address::U, Dialect::Fanuc) => {
                    let Some(v) = self.word_value(word) else { continue };
                    x = Some(at.x + frame.x_mm(v));
                    x_given = true;
                }
                (Address::W, Dialect::Fanuc) => {
                    let Some(v) = self.word_value(word) else { continue };
                    z = Some(at.z + frame.mm(v));
                    z_given = true;
                }
                _ => {}
            }
        }
        // One coordinate and the direction angle (OSP `A`, Fanuc `,A`) give the other.
        let angle_address = if self.dialect == Dialect::Osp { Address::A } else { Address::comma(b'A') };
        if x_given != z_given
            && let Some(angle) = self.address_value(words, angle_address)
            && at.is_finite()
        {
            let (sin, cos) = angle.to_radians().sin_cos();
            if let Some(tx) = x.filter(|_| sin.abs() > 1e-9) {
                z = Some(at.z + (tx - at.x) * cos / sin);
                z_given = true;
            } else if let Some(tz) = z.filter(|_| cos.abs() > 1e-9) {
                x = Some(at.x + (tz - at.z) * sin / cos);
                x_given = true;
            }
        }
        let any = x_given || z_given;
        let target = any.then(|| Xz::new(x.unwrap_or(at.x), z.unwrap_or(at.z)));
        AxisTarget { target, x_given, z_given, any }
    }

    /// A rapid to `to`, or, while the position is not known yet, arriving there.
    pub fn rapid_to(&mut self, to: Xz, span: Span) {
        self.finish_corner();
        if !self.emitter.at.is_finite() {
            self.unknown_position(span);
            self.emitter.arrive(to);
            return;
        }
        self.emitter.rapid(&self.modal, to);
    }

    /// A straight feed move to `to` (cutting), through any pending corner.
    pub fn line_to(&mut self, to: Xz, span: Span) {
        if !self.emitter.at.is_finite() {
            self.unknown_position(span);
            self.emitter.arrive(to);
            return;
        }
        if self.pending_corner.is_some() {
            self.corner_then_line(to);
            return;
        }
        self.emitter.line(&self.modal, to, true);
        self.report_zero_feed(span);
    }

    pub fn report_zero_feed(&mut self, span: Span) {
        if std::mem::take(&mut self.emitter.zero_feed) {
            self.error(DiagnosticKind::NoFeed, span);
        }
    }

    pub(super) fn motion_block(&mut self, index: usize, words: &[Word]) -> Flow {
        let block = *self.program.block(index);
        let span = block.span;
        self.observe_move_words(words, block.statement == Statement::ThreadMove);
        let axes = self.axis_target(words);
        let moves_before = self.emitter.moves.len();
        let angle_given =
            self.dialect == Dialect::Fanuc && words.iter().any(|w| word_address(w) == Some(Address::comma(b'A')));
        match self.modal.motion {
            MotionMode::TurningCycle | MotionMode::ThreadCycle | MotionMode::FacingCycle => {
                // A single cycle repeats with the new end point.
                return super::cycles::single_cycle_again(self, index, words);
            }
            MotionMode::Drilling => return super::cycles::drilling::again(self, index, words),
            MotionMode::Rapid => {
                if let Some(to) = axes.target {
                    self.rapid_to(to, span);
                }
            }
            MotionMode::Linear => {
                let Some(to) = axes.target else {
                    self.finish_corner();
                    return Flow::Next;
                };
                match self.corner_request(words) {
                    Some(request) => self.start_corner(request, to, index, span),
                    None => self.line_to(to, span),
                }
            }
            MotionMode::Cw | MotionMode::Ccw => {
                self.finish_corner();
                let ccw = self.modal.motion == MotionMode::Ccw;
                if let Some(to) = axes.target.or(Some(self.emitter.at)) {
                    self.arc_to(to, words, ccw, span);
                }
            }
            MotionMode::Thread | MotionMode::VariableLeadThread => {
                self.finish_corner();
                let lead = self.address_value(words, Address::F).or(self.address_value(words, Address::E));
                let lead =
                    lead.map(|v| self.modal.frame.feed_mm(v)).unwrap_or(self.modal.frame.feed_mm(self.modal.feed));
                // Fanuc `G34 X Z F K`: the table's change word (`K`) is the lead's change every
                // spindle turn, written in each block; a block without one cuts a constant lead.
                let change = match (self.modal.motion, self.tables.thread_lead.change) {
                    (MotionMode::VariableLeadThread, Some(address)) => {
                        self.address_value(words, address).map_or(0.0, |k| self.modal.frame.feed_mm(k))
                    }
                    _ => 0.0,
                };
                if let Some(to) = axes.target {
                    if !self.emitter.at.is_finite() {
                        self.unknown_position(span);
                        self.emitter.arrive(to);
                    } else {
                        let modal = self.modal.clone();
                        // The start angle (`G32 Q`, 0.001°) places a pass's start; a move
                        // continuing a thread keeps the spindle where the one before left it.
                        let start_angle = self.thread_start_angle(words);
                        self.emitter.thread_phase =
                            start_angle.map_or(0.0, super::cycles::thread_pass::start_angle_turns);
                        if change == 0.0 {
                            self.emitter.thread(&modal, to, lead);
                        } else if self.emitter.varying_thread(&modal, to, (lead, change), &mut 0.0).is_none() {
                            self.error(DiagnosticKind::LeadShrinksToNothing, span);
                        }
                        self.emitter.thread_phase = 0.0;
                        self.report_zero_feed(span);
                    }
                }
            }
        }
        let _ = block.statement == Statement::Motion;
        // A Fanuc `,A` line that no corner waits on: `expand` writes it with both coordinates.
        let own_move = self.emitter.moves.len().checked_sub(1).filter(|&last| last >= moves_before);
        if angle_given
            && self.pending_corner.is_none()
            && let Some(last) = own_move
            && self.emitter.moves[last].source == span
        {
            self.expansions.push(super::Expansion {
                block: index,
                frame: self.modal.frame,
                consumed: Vec::new(),
                setup: None,
                traced: Vec::new(),
                traced_end: last,
                root: Vec::new(),
                moves: last..last + 1,
                before: self.modal_before_block,
                after: super::ModalAfter::of(&self.modal),
                kept: None,
                note: None,
                feed_read_after: true,
                motion_read_after: true,
            });
        }
        Flow::Next
    }

    /// The arc of a `G02`/`G03` block ending at `to`.
    pub fn arc_to(&mut self, to: Xz, words: &[Word], ccw: bool, span: Span) {
        let start = self.emitter.at;
        if !start.is_finite() {
            self.unknown_position(span);
            self.emitter.arrive(to);
            return;
        }
        let frame = self.modal.frame;
        let radius_address = if self.dialect == Dialect::Osp { Address::L } else { Address::R };
        let centre = if let Some(r) = self.address_value(words, radius_address) {
            let r = frame.mm(r);
            match geometry::centre_from_radius(start, to, r, ccw, geometry::ARC_RADIUS_REACH_MM) {
                Some(c) => c,
                None => {
                    let chord = start.distance(to);
                    self.error(
                        DiagnosticKind::ArcRadiusTooSmall { radius_mm: r.abs(), half_chord_mm: chord / 2.0 },
                        span,
                    );
                    return;
                }
            }
        } else {
            let i = self.address_value(words, Address::I).map(|v| frame.mm(v));
            let k = self.address_value(words, Address::K).map(|v| frame.mm(v));
            if i.is_none() && k.is_none() {
                self.error(DiagnosticKind::ArcWithoutCentre, span);
                return;
            }
            let centre = Xz::new(start.x + i.unwrap_or(0.0), start.z + k.unwrap_or(0.0));
            match geometry::centre_from_offsets(start, to, centre) {
                Ok(centre) => centre,
                Err((r0, r1)) => {
                    self.error(DiagnosticKind::ArcCentreMismatch { start_radius_mm: r0, end_radius_mm: r1 }, span);
                    return;
                }
            }
        };
        self.emitter.arc(&self.modal, to, centre, ccw, true);
        self.report_zero_feed(span);
    }

    /// The corner a line block asks for: OSP `G75`/`G76` with `L`, Fanuc `,C`/`,R`.
    fn corner_request(&mut self, words: &[Word]) -> Option<CornerRequest> {
        let osp = self.g_infos(words).find_map(|(_, g)| match g.function {
            Some(GFunction::ChamferCorner) => Some(false),
            Some(GFunction::RoundCorner) => Some(true),
            _ => None,
        });
        if let Some(round) = osp {
            let size = self.address_value(words, Address::L).unwrap_or(0.0);
            return Some(CornerRequest { round, size, word: "L", fanuc: false });
        }
        if self.dialect != Dialect::Fanuc {
            return None;
        }
        if let Some(size) = self.address_value(words, Address::comma(b'C')) {
            return Some(CornerRequest { round: false, size, word: ",C", fanuc: true });
        }
        let size = self.address_value(words, Address::comma(b'R'))?;
        Some(CornerRequest { round: true, size, word: ",R", fanuc: true })
    }

    /// A line block with a corner: remember the corner; the next line completes it. A
    /// corner already waiting is completed by this line, which then starts at its end.
    fn start_corner(&mut self, request: CornerRequest, to: Xz, index: usize, span: Span) {
        if self.pending_corner.is_some() {
            self.complete_corner(to);
        }
        if !self.emitter.at.is_finite() {
            self.unknown_position(span);
            self.emitter.arrive(to);
            return;
        }
        let size = self.modal.frame.mm(request.size).abs();
        self.pending_corner = Some(PendingCorner {
            round: request.round,
            size,
            from: self.emitter.at,
            corner: to,
            modal: self.modal.clone(),
            context: self.emitter.context,
            word: request.word,
            expand: request.fanuc.then_some((index, self.modal_before_block)),
        });
        // The control is at the corner as far as later blocks are concerned.
        self.emitter.at = to;
    }

    /// Emit a pending corner's first line as programmed (no line follows it).
    pub fn finish_corner(&mut self) {
        let Some(corner) = self.pending_corner.take() else { return };
        let context = std::mem::replace(&mut self.emitter.context, corner.context);
        self.emitter.at = corner.from;
        self.emitter.line(&corner.modal, corner.corner, true);
        self.warning(DiagnosticKind::CornerWithoutNextLine, corner.context.source);
        self.emitter.context = context;
    }

    /// The pending corner's line, the chamfer or rounding, then the line to `to`.
    fn corner_then_line(&mut self, to: Xz) {
        self.complete_corner(to);
        let modal = self.modal.clone();
        let span = self.emitter.context.source;
        self.emitter.line(&modal, to, true);
        self.report_zero_feed(span);
    }

    /// The pending corner's line and its chamfer or rounding toward a line to `to`; the
    /// tool is left at the corner's end.
    fn complete_corner(&mut self, to: Xz) {
        let Some(corner) = self.pending_corner.take() else { return };
        let first_move = self.emitter.moves.len();
        let d1 = geometry::direction(corner.from, corner.corner);
        let d2 = geometry::direction(corner.corner, to);
        let (len1, len2) = (corner.from.distance(corner.corner), corner.corner.distance(to));
        // Turn angle between the two lines, and which way it turns in the (Z, X) view.
        let cross = d1.z * d2.x - d1.x * d2.z;
        let dot = d1.z * d2.z + d1.x * d2.x;
        let turn = cross.atan2(dot);
        let back = if corner.round { corner.size * (turn.abs() / 2.0).tan() } else { corner.size };
        let context = std::mem::replace(&mut self.emitter.context, corner.context);
        self.emitter.at = corner.from;
        if turn.abs() < 1e-9 || back > len1 + 1e-9 || back > len2 + 1e-9 {
            self.emitter.line(&corner.modal, corner.corner, true);
            self.error(
                DiagnosticKind::CornerDoesNotFit { size_mm: corner.size, word: corner.word },
                corner.context.source,
            );
            // The corner's block and the line after it decide whether it fits: a word of
            // theirs read without its decimal point is the likelier cause.
            self.slip_scope(corner.context.source, corner.context.source.start, context.source.end);
        } else {
            let p1 = Xz::new(corner.corner.x - d1.x * back, corner.corner.z - d1.z * back);
            let p2 = Xz::new(corner.corner.x + d2.x * back, corner.corner.z + d2.z * back);
            // A corner as long as its first line leaves nothing of it before the corner.
            if p1.distance(corner.from) > 1e-9 {
                self.emitter.line(&corner.modal, p1, true);
            }
            if corner.round {
                // The centre lies on the inside of the turn, a radius from p1.
                let normal = if cross > 0.0 { Xz::new(d1.z, -d1.x) } else { Xz::new(-d1.z, d1.x) };
                let centre = Xz::new(p1.x + normal.x * corner.size, p1.z + normal.z * corner.size);
                self.emitter.arc(&corner.modal, p2, centre, cross > 0.0, true);
            } else {
                self.emitter.line(&corner.modal, p2, true);
            }
        }
        self.emitter.context = context;
        if let Some((block, before)) = corner.expand {
            self.expansions.push(super::Expansion {
                block,
                frame: corner.modal.frame,
                consumed: Vec::new(),
                setup: None,
                traced: Vec::new(),
                traced_end: first_move,
                root: Vec::new(),
                moves: first_move..self.emitter.moves.len(),
                before,
                after: super::ModalAfter::of(&corner.modal),
                kept: None,
                note: None,
                feed_read_after: true,
                motion_read_after: true,
            });
        }
    }
}
