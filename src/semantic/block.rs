//! One block that talks to the machine: modal codes, feed, speed, tool, M codes, and then
//! its motion, one-shot command or cycle.
//!
//! The order inside a block is the control's: modal G-codes first, then F, S and T, then the
//! spindle and coolant M codes, then the motion, then the M codes that end or leave the
//! program.

use crate::diagnostic::DiagnosticKind;
use crate::dialect::{Address, FeedAndSpeed, GFunction, GInfo, GKind};
use crate::source::Span;
use crate::syntax::{CodeLetter, Statement, Word, WordKind};
use crate::toolpath::{Compensation, Xz};

use super::emitter::Context;
use super::interpreter::{Flow, Interpreter};
use super::modal::{MotionMode, SpindleMode, ToolState};

/// The words of a block that take effect: with block delete on, a Fanuc mid-block `/`
/// drops the rest of the block.
pub(super) fn effective_words(words: &[Word], block_delete: bool) -> &[Word] {
    if !block_delete {
        return words;
    }
    let end = words.iter().position(|w| matches!(w.kind, WordKind::OptionalSkip { .. })).unwrap_or(words.len());
    &words[..end]
}

impl Interpreter<'_, '_> {
    /// The value of an address word (literal or expression) in program units.
    pub fn word_value(&mut self, word: &Word) -> Option<f64> {
        match word.kind {
            WordKind::Number { address, number } => {
                let kind = self.tables.address(address).map(|s| s.kind);
                let feed_counts = self.tables.increment_input.feed_per_revolution_counts && self.modal.feed_per_rev;
                Some(self.modal.frame.literal(number, kind, feed_counts))
            }
            WordKind::Expr { expr, .. } => self.value_of(expr),
            _ => None,
        }
    }

    /// The value of the first word with `address`.
    pub fn address_value(&mut self, words: &[Word], address: Address) -> Option<f64> {
        let word = *words.iter().find(|w| word_address(w) == Some(address))?;
        self.word_value(&word)
    }

    /// The G codes of `words` the tables know, with their positions. The iterator borrows only
    /// the words, so the interpreter can change its state while it runs.
    pub fn g_infos<'w>(&self, words: &'w [Word]) -> impl Iterator<Item = (usize, &'static GInfo)> + use<'w> {
        let tables = self.tables;
        words.iter().enumerate().filter_map(move |(i, w)| match w.kind {
            WordKind::Code { letter: CodeLetter::G, code } => tables.g(code).map(|info| (i, info)),
            _ => None,
        })
    }

    pub(super) fn machine_block(&mut self, index: usize) -> Flow {
        // The program outlives the interpreter's borrow: its words need no copy.
        let program = self.program;
        let block = *program.block(index);
        let words = effective_words(program.words_of(&block), self.options.block_delete);
        self.emitter.context = Context { source: block.span, cycle: Span::SYNTHETIC };
        let found = Found::in_words(words);

        // Modal G-codes, and the G code that commands the block.
        let mut command = None;
        for (_, info) in self.g_infos(words) {
            if command.is_none() && info.kind.rank() >= 3 {
                command = Some(info);
            }
            self.apply_modal(info);
        }
        // F: the modal feed, except in the cycles whose F and S are their own (a thread lead,
        // a grooving feed), as `feed_and_speed` in `grammar/` says of each. The F and S of the
        // Fanuc stock-removal and finishing cycles are ordinary modal words: the cycle cuts
        // at them and they stay in effect after it, which is how `G70 P Q` with no F of its
        // own finishes at the roughing cycle's F.
        let cycle_feed = command.and_then(|c| c.feed_and_speed) == Some(FeedAndSpeed::Own);
        // OSP writes the dwell time as F (`G04 F5`): that F is no feed.
        let dwell_in_f = match block.statement {
            Statement::Dwell(id) => self.program.command(id).params.iter().any(|p| {
                p.role == crate::dialect::Role::DwellSeconds
                    && matches!(
                        self.program.word(p.word).kind,
                        WordKind::Number { address: Address::F, .. } | WordKind::Expr { address: Address::F, .. }
                    )
            }),
            _ => false,
        };
        if !cycle_feed
            && !dwell_in_f
            && let Some(feed) = found.feed.and_then(|word| self.word_value(word))
        {
            self.modal.feed = feed;
            if let Some(word) = found.feed {
                self.observe_feed(word);
            }
        }
        // S: a spindle clamp with G50/G92, otherwise the speed.
        if let Some(speed) = found.speed.and_then(|word| self.word_value(word)) {
            let clamp = command.and_then(|c| c.function) == Some(GFunction::CoordinateSetOrClamp);
            if clamp {
                self.modal.clamp = speed.min(self.machine.max_rpm);
                self.modal.clamp_programmed = true;
            } else if !cycle_feed {
                self.modal.speed = speed;
            }
        }
        // Modes set by M codes that the motion of this block already obeys.
        if found.m_codes {
            self.m_code_modes(words);
        }
        if !matches!(block.statement, Statement::LapCall(_))
            && !matches!(command.map(|c| c.kind), Some(GKind::Cycle))
            && let Some(word) = found.tool
        {
            self.tool_change(word);
        }

        self.mark_coordinates();
        let flow = match block.statement {
            Statement::Motion | Statement::ThreadMove => self.motion_block(index, words),
            Statement::Dwell(id) => {
                self.dwell(id, words);
                Flow::Next
            }
            Statement::OneShot(_) => {
                if let Some(info) = command {
                    self.one_shot(index, info, words);
                }
                Flow::Next
            }
            Statement::Cycle(id) | Statement::LapCall(id) => super::cycles::run(self, index, id),
            Statement::LapMarker(_) => self.lap_marker_in_flow(index, command),
            _ => Flow::Next,
        };

        // M codes that end or leave the program, after the motion.
        if !found.m_codes {
            return self.modal_call_after(index, block.statement, flow);
        }
        let m_codes = || {
            words.iter().filter_map(|w| match w.kind {
                WordKind::Code { letter: CodeLetter::M, code } => Some(code.major()),
                _ => None,
            })
        };
        let functions = &self.tables.m_functions;
        if m_codes().any(|m| functions.subprogram_call.contains(&m)) {
            let program = self.address_value(words, Address::P).unwrap_or(0.0);
            let count = self.address_value(words, Address::L).unwrap_or(1.0);
            return self.subprogram_call(index, program, count);
        }
        if m_codes().any(|m| functions.subprogram_return.contains(&m)) {
            return self.return_from_call();
        }
        if m_codes().any(|m| functions.end.contains(&m)) {
            return Flow::End;
        }
        self.modal_call_after(index, block.statement, flow)
    }

    /// OSP `MODIN`: a motion block that goes on to the next block calls the modal subprogram.
    fn modal_call_after(&mut self, index: usize, statement: Statement, flow: Flow) -> Flow {
        if flow == Flow::Next
            && matches!(statement, Statement::Motion)
            && let Some(target) = self.modal_call
        {
            return self.enter(index, target, 1, Vec::new());
        }
        flow
    }

    /// OSP `M23`/`M22`: thread-end chamfering on or off, from this block on.
    fn m_code_modes(&mut self, words: &[Word]) {
        let functions = &self.tables.m_functions;
        for word in words {
            if let WordKind::Code { letter: CodeLetter::M, code } = word.kind {
                if functions.thread_chamfer_on.contains(&code.major()) {
                    self.cycle_memory.thread_chamfer = true;
                } else if functions.thread_chamfer_off.contains(&code.major()) {
                    self.cycle_memory.thread_chamfer = false;
                }
            }
        }
    }

    fn apply_modal(&mut self, info: &GInfo) {
        let Some(function) = info.function else { return };
        match function {
            GFunction::Rapid => self.modal.motion = MotionMode::Rapid,
            GFunction::Linear => self.modal.motion = MotionMode::Linear,
            GFunction::Cw => self.modal.motion = MotionMode::Cw,
            GFunction::Ccw => self.modal.motion = MotionMode::Ccw,
            GFunction::ThreadMove => self.modal.motion = MotionMode::Thread,
            GFunction::VariableLeadThreadMove => self.modal.motion = MotionMode::VariableLeadThread,
            GFunction::TurningCycle => self.modal.motion = MotionMode::TurningCycle,
            GFunction::ThreadCycle => self.modal.motion = MotionMode::ThreadCycle,
            GFunction::FacingCycle => self.modal.motion = MotionMode::FacingCycle,
            GFunction::Inch => self.modal.frame.set_inch(true),
            GFunction::Metric => self.modal.frame.set_inch(false),
            GFunction::Absolute => self.modal.absolute = true,
            GFunction::Incremental => self.modal.absolute = false,
            GFunction::FeedPerMinute => self.modal.feed_per_rev = false,
            GFunction::FeedPerRev => self.modal.feed_per_rev = true,
            GFunction::SurfaceSpeed => self.modal.spindle = SpindleMode::SurfaceSpeed,
            GFunction::Rpm => self.modal.spindle = SpindleMode::Rpm,
            GFunction::CompensationOff => self.modal.compensation = Compensation::Off,
            GFunction::CompensationLeft => self.modal.compensation = Compensation::Left,
            GFunction::CompensationRight => self.modal.compensation = Compensation::Right,
            GFunction::DrillingCancel => super::cycles::drilling::cancel(self),
            GFunction::DrillReturnInitial => self.cycle_memory.drilling.return_to_r_point = false,
            GFunction::DrillReturnRPoint => self.cycle_memory.drilling.return_to_r_point = true,
            _ => {}
        }
        // A code of the motion group ends a modal drilling cycle (group 10).
        if self.modal.motion != MotionMode::Drilling {
            self.cycle_memory.drilling.cycle = None;
        }
    }

    /// `T0404` (station and offset), OSP `T010101` (nose-R number, station, offset); the
    /// tool table supplies the nose radius and tip direction.
    fn tool_change(&mut self, word: &Word) {
        let Some(value) = self.word_value(word) else { return };
        let digits = self.program.text(word.span).iter().filter(|c| c.is_ascii_digit()).count();
        let value = value.round().max(0.0) as u64;
        let (station, offset) = if digits <= 2 { (value, value) } else { ((value / 100) % 100, value % 100) };
        let scale = self.machine.scale();
        let entry = self
            .machine
            .tools
            .iter()
            .find(|t| t.station as u64 == station && t.offset.unwrap_or(t.station) as u64 == offset)
            .or_else(|| self.machine.tools.iter().find(|t| t.station as u64 == station));
        self.modal.tool = ToolState {
            station: station as u16,
            offset: offset as u16,
            nose_radius: if offset == 0 { 0.0 } else { entry.map_or(0.0, |t| t.nose_radius * scale) },
            tip: entry.map_or(0, |t| t.tip),
            minor_edge_angle: entry.and_then(|t| t.minor_edge_angle),
        };
    }

    /// `G04`: seconds in X, U or F, milliseconds in P.
    /// A dwell: its time from the word's role (`grammar/`: seconds, or milliseconds; a Haas
    /// `P` written with a decimal point is seconds), read as written.
    fn dwell(&mut self, id: crate::syntax::CommandId, words: &[Word]) {
        let mut seconds = 0.0;
        let params = self.program.command(id).params.clone();
        for param in params {
            let word = *self.program.word(param.word);
            // A block-delete `/` may have cut the word off.
            if !words.iter().any(|w| w.span == word.span) {
                continue;
            }
            let raw = match word.kind {
                WordKind::Number { number, .. } => Some(number.to_f64()),
                _ => self.word_value(&word),
            };
            match (param.role, raw) {
                (crate::dialect::Role::DwellSeconds, Some(v)) => seconds = v,
                (crate::dialect::Role::DwellMilliseconds, Some(v)) => seconds = v / 1000.0,
                _ => {}
            }
        }
        let modal = self.modal.clone();
        self.emitter.dwell(&modal, seconds);
    }

    /// `G28`, `G53`, `G50 X Z`, `G52`: positioning and coordinate changes.
    fn one_shot(&mut self, index: usize, info: &GInfo, words: &[Word]) {
        let span = self.program.block(index).span;
        match info.function {
            Some(GFunction::ReferenceReturn | GFunction::AtcHome | GFunction::SecondReferenceReturn) => {
                // Through the intermediate point (the axes given), then home for those axes.
                let axes = self.axis_target(words);
                if let Some(via) = axes.target {
                    self.rapid_to(via, span);
                }
                let Some(home) = self.machine.home else {
                    self.home_unknown(span);
                    let unknown_x = axes.x_given || !axes.any;
                    let unknown_z = axes.z_given || !axes.any;
                    let at = self.emitter.at;
                    self.emitter.at =
                        Xz::new(if unknown_x { f64::NAN } else { at.x }, if unknown_z { f64::NAN } else { at.z });
                    return;
                };
                let at = self.emitter.at;
                let to = Xz::new(
                    if axes.x_given || !axes.any { home.x } else { at.x },
                    if axes.z_given || !axes.any { home.z } else { at.z },
                );
                self.rapid_to(to, span);
            }
            Some(GFunction::MachineCoordinates) => {
                // Machine coordinates count from the reference position: without it, the
                // axes the block names go somewhere unknown, and the toolpath resumes at the
                // next programmed point, as after `G28`.
                let Some(home) = self.machine.home else {
                    self.home_unknown(span);
                    let at = self.emitter.at;
                    let unknown = |address, now: f64| {
                        if words.iter().any(|w| word_address(w) == Some(address)) { f64::NAN } else { now }
                    };
                    self.emitter.at = Xz::new(unknown(Address::X, at.x), unknown(Address::Z, at.z));
                    return;
                };
                let frame = self.modal.frame;
                let x = self.address_value(words, Address::X).map(|v| home.x + frame.x_mm(v));
                let z = self.address_value(words, Address::Z).map(|v| home.z + frame.mm(v));
                let at = self.emitter.at;
                let to = Xz::new(x.unwrap_or(at.x), z.unwrap_or(at.z));
                self.rapid_to(to, span);
            }
            Some(GFunction::CoordinateSetOrClamp) => {
                // `G50 X Z` says where the tool is now in program coordinates: the toolpath
                // keeps its frame, and later program coordinates are shifted into it.
                let frame = self.modal.frame;
                if let Some(x) = self.address_value(words, Address::X) {
                    self.modal.shift.x = self.emitter.at.x - frame.x_mm(x);
                }
                if let Some(z) = self.address_value(words, Address::Z) {
                    self.modal.shift.z = self.emitter.at.z - frame.mm(z);
                }
            }
            _ => {}
        }
    }

    /// A LAP contour met in the normal flow is a definition: skip to its `G80`.
    fn lap_marker_in_flow(&mut self, index: usize, command: Option<&GInfo>) -> Flow {
        let starts = matches!(
            command.and_then(|c| c.function),
            Some(GFunction::LapContourLongitudinal | GFunction::LapContourTransverse | GFunction::LapBlank)
        );
        if !starts {
            return Flow::Next;
        }
        match self.lap_end(index) {
            Some(end) => Flow::Jump(end + 1),
            None => {
                let span = self.program.block(index).span;
                self.error(DiagnosticKind::LapContourNotClosed, span);
                Flow::End
            }
        }
    }

    /// The `G80` that closes the LAP contour starting at `start`.
    pub fn lap_end(&self, start: usize) -> Option<usize> {
        (start + 1..self.program.blocks().len()).find(|&i| {
            let block = self.program.block(i);
            block.statement != Statement::Invalid
                && self.g_infos(self.program.words_of(block)).any(|(_, g)| g.function == Some(GFunction::LapEnd))
        })
    }
}

/// The words of a block that `machine_block` looks for, found in one pass: the first F, S and
/// T words, and whether there is any M code (most blocks are an axis move without one).
struct Found<'w> {
    feed: Option<&'w Word>,
    speed: Option<&'w Word>,
    tool: Option<&'w Word>,
    m_codes: bool,
}

impl<'w> Found<'w> {
    fn in_words(words: &'w [Word]) -> Found<'w> {
        let mut found = Found { feed: None, speed: None, tool: None, m_codes: false };
        for word in words {
            match word_address(word) {
                Some(Address::F) => found.feed = found.feed.or(Some(word)),
                Some(Address::S) => found.speed = found.speed.or(Some(word)),
                Some(Address::T) => found.tool = found.tool.or(Some(word)),
                Some(_) => {}
                None => found.m_codes |= matches!(word.kind, WordKind::Code { letter: CodeLetter::M, .. }),
            }
        }
        found
    }
}

pub(super) fn word_address(word: &Word) -> Option<Address> {
    match word.kind {
        WordKind::Number { address, .. } | WordKind::Expr { address, .. } => Some(address),
        _ => None,
    }
}
