//! The one writer of motion blocks.
//!
//! Every code a written block carries comes from the dialect tables (`grammar/`), looked up
//! once per program in [`Codes`]; every coordinate is a count on the least-increment grid
//! (`grid.rs`); an arc's words are the grid's choice (`Grid::arc_words`). The words go to a
//! [`WordSink`]: the printer's text of new blocks (compensation's motion blocks, millions in
//! a long program) or a list of words (a cycle's blocks, which their caller still edits).
//!
//! A cycle's moves are written as fresh blocks with [`MotionWriter::move_block`], which
//! writes a motion code, a compensation code, F and S only where they change ([`Modal`]);
//! compensation's rewrite writes a block in its own form word by word, through the same
//! writer.

use crate::dialect::{Address, Code, Dialect, DialectConfig, GFunction, Role, Tables};
use crate::printer::{BlockWriter, NewWord};
use crate::semantic::ModalAfter;
use crate::syntax::{CodeLetter, Number, Program, WordId};
use crate::toolpath::{Compensation, Motion, Move, Xz};

use super::grid::{ArcWords, Grid, GridPoint};

/// The motion a written block performs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    Rapid,
    Feed,
    Cw,
    Ccw,
    Thread,
}

impl Kind {
    /// The kind of block that writes `m` (a dwell is no motion: `MotionWriter::dwell`).
    pub(crate) fn of(m: &Move) -> Kind {
        match m.motion {
            _ if m.threading => Kind::Thread,
            Motion::Rapid => Kind::Rapid,
            Motion::Cw => Kind::Cw,
            Motion::Ccw => Kind::Ccw,
            _ => Kind::Feed,
        }
    }

    /// The plain (not thread) kind of `motion`; a dwell has none.
    fn of_motion(motion: Motion) -> Option<Kind> {
        match motion {
            Motion::Rapid => Some(Kind::Rapid),
            Motion::Feed => Some(Kind::Feed),
            Motion::Cw => Some(Kind::Cw),
            Motion::Ccw => Some(Kind::Ccw),
            Motion::Dwell => None,
        }
    }

    fn function(self) -> GFunction {
        match self {
            Kind::Rapid => GFunction::Rapid,
            Kind::Feed => GFunction::Linear,
            Kind::Cw => GFunction::Cw,
            Kind::Ccw => GFunction::Ccw,
            Kind::Thread => GFunction::ThreadMove,
        }
    }

    const ALL: [Kind; 5] = [Kind::Rapid, Kind::Feed, Kind::Cw, Kind::Ccw, Kind::Thread];
}

/// Every code and address the back end writes in a program's dialect, looked up in its
/// tables once for all the blocks it writes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Codes {
    pub tables: &'static Tables,
    pub dialect: Dialect,
    /// The code of each `Kind`, in `Kind::ALL` order; `None` where the dialect has no such
    /// motion (OSP has no thread move: `thread_pass.rs` writes its threads).
    motion: [Option<Code>; 5],
    /// `G40`, `G41`, `G42`.
    compensation: [Option<Code>; 3],
    /// The dwell code and the address of its time in seconds (the dwell schema's).
    dwell: Option<(Code, Address)>,
    /// The single-pass thread cycles, longitudinal and face (OSP `G33`, `G32`).
    pub thread_single: Option<Code>,
    pub thread_single_face: Option<Code>,
    /// The M codes that turn thread chamfering on and off (OSP `M23`, `M22`).
    pub chamfer_on: Option<u16>,
    pub chamfer_off: Option<u16>,
    /// The address of an arc's radius (`R`, OSP `L`).
    pub radius_address: Address,
    /// The word of a thread move that starts it past the spindle's index (`Q`, 0.001°).
    pub start_angle: Option<Address>,
}

impl Codes {
    pub(crate) fn of(program: &Program<'_>) -> Codes {
        Codes::of_config(program.config())
    }

    fn of_config(config: DialectConfig) -> Codes {
        let tables = config.tables();
        let code = |function| tables.code_for(function);
        let dwell = code(GFunction::Dwell).and_then(|dwell| {
            let schema = tables.g(dwell).and_then(|g| g.schema).map(|id| tables.schema(id))?;
            let form = schema.forms.first()?;
            let seconds = form.words.iter().find(|(_, role)| *role == Role::DwellSeconds)?;
            Some((dwell, seconds.0))
        });
        Codes {
            tables,
            dialect: config.dialect,
            motion: Kind::ALL.map(|kind| code(kind.function())),
            compensation: [
                code(GFunction::CompensationOff),
                code(GFunction::CompensationLeft),
                code(GFunction::CompensationRight),
            ],
            dwell,
            thread_single: code(GFunction::ThreadSingle),
            thread_single_face: code(GFunction::ThreadSingleFace),
            chamfer_on: tables.m_functions.thread_chamfer_on.first().copied(),
            chamfer_off: tables.m_functions.thread_chamfer_off.first().copied(),
            radius_address: if config.dialect == Dialect::Osp { Address::L } else { Address::R },
            start_angle: tables.thread_move.start_angle,
        }
    }

    /// The code of a `kind` of motion.
    pub(crate) fn motion(&self, kind: Kind) -> Option<Code> {
        self.motion[kind as usize]
    }

    /// Whether the dialect has a plain thread move (`G32`, system C `G33`).
    pub(crate) fn has_thread_move(&self) -> bool {
        self.motion(Kind::Thread).is_some()
    }

    /// The kind of motion a G code performs, if it is a motion code (any code of the
    /// function, not only the one the back end writes).
    pub(crate) fn kind_of(&self, code: Code) -> Option<Kind> {
        let function = self.tables.g(code).and_then(|g| g.function)?;
        Kind::ALL.into_iter().find(|kind| kind.function() == function)
    }

    fn compensation(&self, compensation: Compensation) -> Option<Code> {
        match compensation {
            Compensation::Off => self.compensation[0],
            Compensation::Left => self.compensation[1],
            Compensation::Right => self.compensation[2],
        }
    }
}

/// Where the back end writes words.
pub(crate) trait WordSink {
    fn code(&mut self, letter: CodeLetter, code: Code);
    fn number(&mut self, address: Address, number: Number);
    /// A word of the program, as it was written.
    fn copy(&mut self, id: WordId);
    fn word(&mut self, word: &NewWord);
}

/// The text of new blocks, in the program's style.
impl WordSink for BlockWriter<'_, '_> {
    fn code(&mut self, letter: CodeLetter, code: Code) {
        BlockWriter::code(self, letter, code);
    }

    fn number(&mut self, address: Address, number: Number) {
        BlockWriter::number(self, address, number);
    }

    fn copy(&mut self, id: WordId) {
        BlockWriter::copy(self, id);
    }

    fn word(&mut self, word: &NewWord) {
        BlockWriter::word(self, word);
    }
}

/// The words of one new block.
impl WordSink for Vec<NewWord> {
    fn code(&mut self, letter: CodeLetter, code: Code) {
        self.push(NewWord::Code(letter, code));
    }

    fn number(&mut self, address: Address, number: Number) {
        self.push(NewWord::Number(address, number));
    }

    fn copy(&mut self, id: WordId) {
        self.push(NewWord::Copy(id));
    }

    fn word(&mut self, word: &NewWord) {
        self.push(word.clone());
    }
}

/// Writes motion blocks' words to `out` with the codes of the program's dialect.
pub(crate) struct MotionWriter<W> {
    pub codes: Codes,
    pub out: W,
}

/// What the blocks a `MotionWriter` wrote for a cycle leave in force: each new block
/// writes a code, F or S only where it changes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Modal {
    /// The last motion written (`None` before the first), and whether it was a thread.
    motion: Option<(Motion, bool)>,
    feed: Option<f64>,
    speed: Option<f64>,
    compensation: Compensation,
    /// Where the last block ends, on the grid, where straight moves write only the axes
    /// they travel (`Modal::writing_travelled_axes`); `None`: every block writes both.
    at: Option<GridPoint>,
}

impl Modal {
    /// In force before the first block: `compensation`, and the spindle speed `speed` where
    /// one is (positive).
    pub(crate) fn new(compensation: Compensation, speed: f64) -> Modal {
        Modal { motion: None, feed: None, speed: Some(speed).filter(|s| *s > 0.0), compensation, at: None }
    }

    /// The same, its straight moves writing only the axes they travel from `start` on (as a
    /// profile is written by hand: `Z-30.` after `X24. Z-2.`); an arc writes both ends.
    pub(crate) fn writing_travelled_axes(self, start: GridPoint) -> Modal {
        Modal { at: Some(start), ..self }
    }
}

impl<W: WordSink> MotionWriter<W> {
    pub(crate) fn new(codes: Codes, out: W) -> MotionWriter<W> {
        MotionWriter { codes, out }
    }

    /// The motion code of `kind`.
    pub(crate) fn motion(&mut self, kind: Kind) {
        if let Some(code) = self.codes.motion(kind) {
            self.out.code(CodeLetter::G, code);
        }
    }

    /// A coordinate word: `address` with `count` increments of `grid`.
    pub(crate) fn coordinate(&mut self, grid: &Grid, address: Address, count: i64) {
        self.out.number(address, grid.number(count));
    }

    /// The absolute `X` and `Z` words of `p` (toolpath frame) on `grid`.
    pub(crate) fn point(&mut self, grid: &Grid, p: Xz) {
        let on_grid = grid.point(p);
        self.coordinate(grid, Address::X, on_grid.x);
        self.coordinate(grid, Address::Z, on_grid.z);
    }

    /// A length (a taper, a shift, a chamfer) in mm on `grid`.
    pub(crate) fn length(&mut self, grid: &Grid, address: Address, mm: f64) {
        self.coordinate(grid, address, grid.length(mm));
    }

    /// Word `id` of the program, as it was written.
    pub(crate) fn copy(&mut self, id: WordId) {
        self.out.copy(id);
    }

    /// The words of move `m` from `start` (programmed contour points, toolpath frame) on
    /// `grid`, as one block after the blocks `modal` describes: the compensation code and
    /// the motion code where they change (an arc's always), absolute `X Z`, an arc's words in
    /// the radius form where `radius_arcs` prefers it and it holds the arc (`Grid::arc_words`),
    /// F and S where they change. A dwell is its own block (`dwell`). A thread move with
    /// `lead` is written with those lead words (`back::thread_lead`) instead of its F.
    pub(crate) fn move_block(
        &mut self,
        modal: &mut Modal,
        grid: &Grid,
        radius_arcs: bool,
        (start, m): (Xz, &Move),
        lead: Option<&[(Address, Number)]>,
    ) {
        if m.motion == Motion::Dwell {
            self.dwell(m.t_end - m.t_start);
            return;
        }
        if m.compensation != modal.compensation {
            if let Some(code) = self.codes.compensation(m.compensation) {
                self.out.code(CodeLetter::G, code);
            }
            modal.compensation = m.compensation;
        }
        // A thread move after any other starts a pass (a move after a thread move continues it).
        let starts_thread = m.threading && modal.motion != Some((m.motion, true));
        if modal.motion != Some((m.motion, m.threading)) || m.is_arc() {
            self.motion(Kind::of(m));
            modal.motion = Some((m.motion, m.threading));
        }
        let end = m.contour;
        match modal.at {
            Some(at) if !m.is_arc() => {
                let on_grid = grid.point(end);
                if on_grid.x != at.x {
                    self.coordinate(grid, Address::X, on_grid.x);
                }
                // A move that travels neither axis on the grid still names one.
                if on_grid.z != at.z || on_grid.x == at.x {
                    self.coordinate(grid, Address::Z, on_grid.z);
                }
                modal.at = Some(on_grid);
            }
            Some(_) => {
                self.point(grid, end);
                modal.at = Some(grid.point(end));
            }
            None => self.point(grid, end),
        }
        if m.is_arc() {
            // The words `compensate` predicts the control to run: the program's form where it
            // holds the arc after rounding, else the centre form.
            match grid.arc_words(start, end, m.centre, m.motion == Motion::Ccw, radius_arcs) {
                ArcWords::Radius(radius) => self.coordinate(grid, self.codes.radius_address, radius),
                ArcWords::Centre { i, k } => {
                    self.coordinate(grid, Address::I, i);
                    self.coordinate(grid, Address::K, k);
                }
                // An arc whose rounded ends meet (a cycle's own moves; `compensate` writes
                // such an arc as a line): its centre as the cycle has it.
                ArcWords::Line => {
                    self.length(grid, Address::I, m.centre.x - start.x);
                    self.length(grid, Address::K, m.centre.z - start.z);
                }
            }
        }
        match lead.filter(|_| m.threading) {
            Some(words) => self.lead(modal, words),
            None if m.motion != Motion::Rapid && modal.feed != Some(m.f_word) && m.f_word > 0.0 => {
                self.out.number(Address::F, feed_number(m.f_word));
                modal.feed = Some(m.f_word);
            }
            None => {}
        }
        if starts_thread && let Some(address) = self.codes.start_angle {
            let thousandths = start_angle_thousandths(m.phase);
            if thousandths != 0 {
                self.out.number(address, Number::new(thousandths, 0, false));
            }
        }
        if m.s_word > 0.0 && modal.speed != Some(m.s_word) {
            self.out.number(Address::S, feed_number(m.s_word));
            modal.speed = Some(m.s_word);
        }
    }

    /// A thread move's lead `words`. An `F` lead is the modal F, written where it changes; any
    /// other lead word (the precise `E`) is written on every thread move, as the thread move
    /// reads it from its own block only and otherwise runs at the modal F
    /// (`semantic/motion.rs`).
    fn lead(&mut self, modal: &mut Modal, words: &[(Address, Number)]) {
        match words {
            [(Address::F, number)] => {
                let value = number.to_f64();
                if modal.feed != Some(value) {
                    self.out.number(Address::F, *number);
                    modal.feed = Some(value);
                }
            }
            _ => words.iter().for_each(|&(address, number)| self.out.number(address, number)),
        }
    }

    /// A dwell of `seconds`, to the millisecond.
    fn dwell(&mut self, seconds: f64) {
        if let Some((code, address)) = self.codes.dwell {
            self.out.code(CodeLetter::G, code);
            self.out.number(address, Number::new((seconds * 1000.0).round() as i64, 3, true));
        }
    }

    /// The words that put back the modal motion code, F and S the program has after a
    /// cycle (`after`), where the blocks written for it (`modal`) left others in force (a
    /// `G01 F0.25` from a roughing pass would otherwise carry into the blocks after the
    /// call) and the block the control runs next does not give them itself (`next`), as a
    /// block of their own; what they are (`Restore::is_none`: none).
    pub(crate) fn restore(&mut self, modal: &mut Modal, after: &ModalAfter, next: GivenNext) -> Restore {
        let mut restore = Restore::default();
        if let Some(motion) = after.motion
            && !next.motion
            && modal.motion.is_some_and(|written| written != (motion, false))
        {
            // A dwell leaves no motion to put back, nor anything else.
            let Some(kind) = Kind::of_motion(motion) else { return restore };
            restore.motion = Some(kind);
            modal.motion = Some((motion, false));
        }
        if after.f_word > 0.0 && !next.feed && modal.feed.is_some_and(|f| f != after.f_word) {
            restore.feed = Some(feed_number(after.f_word));
            modal.feed = Some(after.f_word);
        }
        if after.s_word > 0.0 && !next.speed && modal.speed.is_some_and(|s| s != after.s_word) {
            restore.speed = Some(feed_number(after.s_word));
            modal.speed = Some(after.s_word);
        }
        self.restored(restore);
        restore
    }

    /// The words of `restore`, in the order a block writes them: the motion code, F, S.
    pub(crate) fn restored(&mut self, restore: Restore) {
        if let Some(kind) = restore.motion {
            self.motion(kind);
        }
        if let Some(feed) = restore.feed {
            self.out.number(Address::F, feed);
        }
        if let Some(speed) = restore.speed {
            self.out.number(Address::S, speed);
        }
    }
}

/// Modal words put back after blocks that left others in force (an expanded cycle's, a move
/// written in pieces), for the blocks after them: written on a block of their own, or
/// carried by the block the control runs next (`compensation::rewrite`), which then writes
/// them itself: no block only restores a modal word where the next one can say it.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Restore {
    pub motion: Option<Kind>,
    pub feed: Option<Number>,
    pub speed: Option<Number>,
}

impl Restore {
    pub(crate) fn is_none(&self) -> bool {
        *self == Restore::default()
    }
}

/// The modal words the block the control runs after some written blocks gives itself: a
/// motion code, F, S. A word it gives needs no block of its own to put it back (a lone
/// `G01` or `F0.05` before a block that writes `G00` or its own F); a word it does not
/// give is restored, as the block may run under it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct GivenNext {
    pub motion: bool,
    pub feed: bool,
    pub speed: bool,
}

impl GivenNext {
    /// What the first block after `after` that `skipped` does not pass over gives, read as
    /// the control runs the text on: blocks that run nothing (comments, labels) are passed
    /// over. A block the operator may skip (`/`), or one that is not a plain motion block
    /// (a cycle call, `M99`, a jump), gives nothing: the control may run another block next.
    pub(crate) fn after(
        program: &Program<'_>,
        codes: &Codes,
        after: usize,
        skipped: impl Fn(usize) -> bool,
    ) -> GivenNext {
        use crate::syntax::{Statement, WordKind};
        let Some(next) = Self::next_block(program, after, skipped) else {
            return GivenNext::default();
        };
        let block = program.block(next);
        let plain = matches!(block.statement, Statement::Motion);
        if !(plain || matches!(block.statement, Statement::ThreadMove)) {
            return GivenNext::default();
        }
        let mut given = GivenNext::default();
        for word in program.words_of(block) {
            match word.kind {
                WordKind::BlockDelete { .. } => return GivenNext::default(),
                WordKind::Code { letter: CodeLetter::G, code } if codes.kind_of(code).is_some() => given.motion = true,
                // A thread move's F is its lead: it gives the feed of the blocks after it,
                // not of a feed move.
                WordKind::Number { address: Address::F, .. } | WordKind::Expr { address: Address::F, .. } => {
                    given.feed |= plain
                }
                WordKind::Number { address: Address::S, .. } | WordKind::Expr { address: Address::S, .. } => {
                    given.speed = true
                }
                _ => {}
            }
        }
        given
    }

    /// The block the control runs after `after`, passing over those `skipped` says and those
    /// that run nothing (`after`).
    pub(crate) fn next_block(program: &Program<'_>, after: usize, skipped: impl Fn(usize) -> bool) -> Option<usize> {
        use crate::syntax::Statement;
        (after + 1..program.blocks().len())
            .find(|&b| !skipped(b) && !matches!(program.block(b).statement, Statement::Empty))
    }
}

impl MotionWriter<Vec<NewWord>> {
    /// The words written since the last block was taken, as a block.
    pub(crate) fn take_words(&mut self) -> Vec<NewWord> {
        std::mem::take(&mut self.out)
    }
}

/// A feed, speed or thread lead written with the digits it needs: up to eight decimals, as
/// an inch thread lead such as `F0.07692308` (13 threads per inch) needs.
pub(crate) fn feed_number(value: f64) -> Number {
    let mut scale = 0u8;
    while scale < 8 && ((value * 10f64.powi(scale as i32)).round() - value * 10f64.powi(scale as i32)).abs() > 1e-9 {
        scale += 1;
    }
    Number::new((value * 10f64.powi(scale as i32)).round() as i64, scale, true)
}

/// The start-angle word's count (0.001°) for a pass that starts `phase` turns past the
/// spindle's index (`Move::phase`).
pub(crate) fn start_angle_thousandths(phase: f64) -> i64 {
    (phase.rem_euclid(1.0) * 360_000.0).round() as i64 % 360_000
}

#[cfg(test)]
mod tests;
