//! The program counter: which block runs next.
//!
//! Control flow follows the controls: a jump searches forward for its label and then from
//! the top; `CALL`/`M98` push a return point and a fresh frame of local variables, `RTS`/
//! `M99` pop them; Fanuc `WHILE … DOn` loops back from its `ENDn`; `M02`, `M30`, the closing
//! `%`, `RTS` in the main program, or a second program name end the run. Every executed
//! block counts toward `max_executed_blocks`.
//!
//! A jump back that finds the run exactly as it was when the same jump was last taken
//! (`LoopState`: no variable changed, the same position, modes and calls) closes a loop
//! that a control repeats forever: it is an error there, at the second pass, not after the
//! bound's millions of blocks (a pass that reads a LAP contour and repeats its diagnostics
//! is slow enough that the bound takes minutes to reach).

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::tables::KeywordKind;
use crate::dialect::{Dialect, Tables};
use crate::source::Span;
use crate::syntax::{Program, Statement, WordKind};
use crate::toolpath::{Compensation, Toolpath, Xz};

use super::cycles::CycleMemory;
use super::emitter::Emitter;
use super::eval::{Evaluator, Variables};
use super::labels::{self, Labels};
use super::modal::{Modal, MotionMode, SpindleMode, ToolState};
use super::{Expansion, LowerOptions, Lowered, Machine};

/// How many diagnostics may pile up past those merged before their repeats are merged again.
const MERGE_DIAGNOSTICS_EVERY: usize = 4096;

/// What to do after a block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Flow {
    Next,
    Jump(usize),
    End,
}

/// A subprogram call in progress.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Call {
    /// Where to continue after the last repetition.
    return_to: usize,
    /// The first block of the subprogram, for repetitions.
    entry: usize,
    remaining: u32,
}

/// Subprogram calls nest at most this deep.
const MAX_CALL_DEPTH: usize = 32;

/// Everything the run's course from a jump on depends on. Conditions read only variables,
/// and blocks act on the modes, the cycles' memory, the calls and loops in progress and the
/// position: when all of them are as they were at the jump's last take, the blocks between
/// the two takes run again the same way, forever, making the same moves (the moves made so
/// far and the clock change nothing a block decides).
#[derive(Debug, Clone, PartialEq)]
struct LoopState {
    variables: u64,
    at: (u64, u64),
    started: bool,
    compensated: bool,
    dwelled: bool,
    pending_corner: Option<super::motion::PendingCorner>,
    modal: Modal,
    cycle_memory: CycleMemory,
    calls: Vec<Call>,
    loops: Vec<(usize, u32)>,
    modal_call: Option<usize>,
    first_program_name: Option<usize>,
    tape_opened: bool,
    position_damaged: bool,
}

/// A jump back that has been taken: how often, and the run as it was at its last take.
#[derive(Debug)]
struct LoopJump {
    taken: u64,
    state: LoopState,
}

pub(super) struct Interpreter<'p, 'src> {
    pub program: &'p Program<'src>,
    pub tables: &'static Tables,
    pub dialect: Dialect,
    pub machine: &'p Machine,
    pub options: &'p LowerOptions,
    pub modal: Modal,
    pub emitter: Emitter,
    pub variables: Variables,
    /// Built on the first jump, call or profile lookup: most programs make none, and the
    /// table is a pass over every word of the program.
    labels: std::cell::OnceCell<Labels>,
    pub diagnostics: Vec<Diagnostic>,
    pub expansions: Vec<Expansion>,
    pub cycle_memory: CycleMemory,
    /// OSP `MODIN`: the subprogram called after every motion block.
    pub modal_call: Option<usize>,
    /// An OSP `G75`/`G76` corner waiting for the move after it.
    pub pending_corner: Option<super::motion::PendingCorner>,
    /// Blocks a cycle consumed (a LAP contour right after its call): the flow skips them.
    pub skip_to: Option<usize>,
    /// The blocks the cycle being run consumes (its profile, its first block, a LAP contour
    /// right after it): `expand` deletes them with its call.
    pub cycle_consumed: Vec<usize>,
    /// The consumed first block of the cycle being run, and the profile blocks it runs with
    /// their first moves (`Expansion::setup`, `Expansion::traced`).
    pub cycle_setup: Option<usize>,
    pub cycle_traced: Vec<(usize, usize)>,
    /// The move after the traced profile's last (`Expansion::traced_end`).
    pub cycle_traced_end: Option<usize>,
    /// The contour blocks that place a LAP continuous thread's final pass (`Expansion::root`).
    pub cycle_root: Vec<(usize, usize)>,
    /// The number of diagnostics at which their repeats are merged next.
    merge_diagnostics_at: usize,
    /// The modal words in force before the block being executed (for `expand`, which
    /// replaces a cycle's block, words and all).
    pub modal_before_block: super::ModalAfter,
    /// Where the program's coordinates change meaning (`Lowered::coordinates`).
    pub coordinates: Vec<super::CoordinateMark>,
    calls: Vec<Call>,
    /// Fanuc `WHILE` blocks being looped, with their loop number.
    loops: Vec<(usize, u32)>,
    /// Each jump back taken so far, by its block.
    loop_jumps: std::collections::HashMap<usize, LoopJump>,
    /// The block of the jump back taken last: the runaway bound is reported there.
    last_loop_jump: Option<usize>,
    executed: u64,
    first_program_name: Option<usize>,
    /// The missing home position has been noted (it is one fact, said once per run).
    noted_home_unknown: bool,
    /// What `plausibility.rs` has warned of already.
    pub plausibility: super::plausibility::Warned,
    /// What `decimal_point.rs` has said already.
    pub decimal_point: super::decimal_point::Said,
    tape_opened: bool,
    cut_off: Option<Span>,
    /// Time arcs on a second thread from this many blocks on (`parallel::Tuning::arc_times_blocks`).
    arc_times_beside_from_blocks: usize,
    /// Whether the tape's `%` follows the leader lines (`check_leader`), once found.
    leader_confirmed: Option<bool>,
    /// The position is unknown because of a block that does not parse (`damaged_block`).
    position_damaged: bool,
    /// Why `expand` should leave the cycle being run as it is (`Expansion::kept`).
    pub expansion_kept: Option<&'static str>,
    /// What `expand` says of the cycle being run (`Expansion::note`).
    pub expansion_note: Option<DiagnosticKind>,
}

impl<'p, 'src> Interpreter<'p, 'src> {
    pub fn new(
        program: &'p Program<'src>,
        machine: &'p Machine,
        options: &'p LowerOptions,
        tuning: &crate::parallel::Tuning,
    ) -> Self {
        let frame = super::initial_frame(program, machine);
        let dialect = program.config().dialect;
        let start = machine.home.unwrap_or(Xz::new(f64::NAN, f64::NAN));
        let modal = Modal {
            frame,
            absolute: true,
            feed_per_rev: true,
            feed: 0.0,
            spindle: SpindleMode::Rpm,
            speed: 0.0,
            clamp: machine.max_rpm,
            clamp_programmed: false,
            spindle_limit: machine.spindle_limit().0,
            motion: MotionMode::Rapid,
            compensation: Compensation::Off,
            tool: ToolState { station: 0, offset: 0, nose_radius: 0.0, tip: 0, minor_edge_angle: None },
            shift: Xz::default(),
        };
        Interpreter {
            program,
            tables: program.config().tables(),
            dialect,
            machine,
            options,
            modal,
            // Most blocks make one move; cycles make many more, and the vector grows for them.
            emitter: Emitter::new(
                start,
                machine.rapid,
                program.blocks().len(),
                options.max_moves.max(program.blocks().len().saturating_mul(super::MOVES_PER_BLOCK)),
            ),
            variables: Variables::from_machine(&machine.variables, dialect),
            labels: std::cell::OnceCell::new(),
            diagnostics: Vec::new(),
            expansions: Vec::new(),
            cycle_memory: CycleMemory::default(),
            modal_call: None,
            pending_corner: None,
            skip_to: None,
            cycle_consumed: Vec::new(),
            cycle_setup: None,
            cycle_traced: Vec::new(),
            cycle_traced_end: None,
            cycle_root: Vec::new(),
            merge_diagnostics_at: MERGE_DIAGNOSTICS_EVERY,
            modal_before_block: super::ModalAfter { motion: None, f_word: 0.0, s_word: 0.0 },
            coordinates: Vec::new(),
            calls: Vec::new(),
            loops: Vec::new(),
            loop_jumps: std::collections::HashMap::new(),
            last_loop_jump: None,
            executed: 0,
            first_program_name: None,
            noted_home_unknown: false,
            plausibility: super::plausibility::Warned::default(),
            decimal_point: super::decimal_point::Said::default(),
            tape_opened: false,
            cut_off: None,
            arc_times_beside_from_blocks: tuning.arc_times_blocks,
            leader_confirmed: None,
            position_damaged: false,
            expansion_kept: None,
            expansion_note: None,
        }
    }

    /// Where each sequence name and program name is.
    pub fn labels(&self) -> &Labels {
        self.labels.get_or_init(|| Labels::new(self.program))
    }

    pub fn evaluator(&self) -> Evaluator<'p, 'src> {
        Evaluator { program: self.program, dialect: self.dialect }
    }

    pub fn error(&mut self, kind: DiagnosticKind, span: Span) {
        self.diagnostics.push(Diagnostic::error(kind, span));
    }

    pub fn warning(&mut self, kind: DiagnosticKind, span: Span) {
        self.diagnostics.push(Diagnostic::warning(kind, span));
    }

    /// The tool's position is unknown (no home in the machine settings) on the block at
    /// `span`: noted once per run, as is [`Interpreter::home_unknown`] — both say the
    /// settings give no home position, and the note says what the toolpath does about it.
    pub fn unknown_position(&mut self, span: Span) {
        if self.position_damaged {
            return;
        }
        self.note_home_unknown(DiagnosticKind::UnknownStartPosition, span);
    }

    /// A block that moves relative to the home position (`G28`, `G53`) on a machine whose
    /// settings give none: noted once per run (see [`Interpreter::unknown_position`]).
    pub fn home_unknown(&mut self, span: Span) {
        self.note_home_unknown(DiagnosticKind::HomeUnknown, span);
    }

    fn note_home_unknown(&mut self, kind: DiagnosticKind, span: Span) {
        if !std::mem::replace(&mut self.noted_home_unknown, true) {
            self.diagnostics.push(Diagnostic::note(kind, span));
        }
    }

    pub fn run(mut self) -> Lowered {
        if self.program.blocks().len() >= self.arc_times_beside_from_blocks {
            // Arcs are timed on a second thread as the blocks run (`emitter/arc_times.rs`).
            let (sender, receiver) = std::sync::mpsc::channel();
            self.emitter.time_arcs_beside(sender);
            let (handed, timed) = crate::parallel::join(
                || {
                    self.execute_blocks();
                    self.emitter.stop_timing_beside()
                },
                move || super::emitter::time_arcs(receiver),
            );
            self.emitter.chain_times(&handed, &timed);
        } else {
            self.execute_blocks();
        }
        self.finish()
    }

    /// Run the blocks from the first until the program ends.
    fn execute_blocks(&mut self) {
        let blocks = self.program.blocks();
        let mut pc = 0;
        while pc < blocks.len() {
            if self.executed >= self.options.max_executed_blocks {
                // Blocks without end come from a loop: the jump back taken last closes it.
                let jump = self.last_loop_jump.and_then(|at| Some((at, self.loop_jumps.get(&at)?.taken)));
                self.runaway(blocks[jump.map_or(pc, |(at, _)| at)].span, jump.map(|(_, taken)| taken));
                break;
            }
            self.executed += 1;
            // A block run again and again (a loop) repeats its diagnostics: merged as they
            // pile up, so that memory follows the blocks that have them, not the repeats.
            if self.diagnostics.len() >= self.merge_diagnostics_at {
                crate::diagnostic::merge_repeats(&mut self.diagnostics);
                self.merge_diagnostics_at = 2 * self.diagnostics.len() + MERGE_DIAGNOSTICS_EVERY;
            }
            let first_move = self.emitter.moves.len();
            let flow = self.execute(pc);
            self.check_moves(first_move, blocks[pc].span);
            if self.position_damaged && self.emitter.at.is_finite() {
                self.position_damaged = false;
            }
            // The moves the run keeps are bounded, inside a block (a cycle's passes) too.
            if self.emitter.is_full() {
                self.runaway(blocks[pc].span, None);
                break;
            }
            if let Some(target) = self.skip_to.take() {
                pc = target;
                continue;
            }
            pc = match flow {
                Flow::Next => pc + 1,
                Flow::Jump(target) if target <= pc && self.is_loop_jump(pc) && self.loops_forever(pc, target) => break,
                Flow::Jump(target) => target,
                Flow::End => break,
            };
        }
        // Run off the end of the text with no program end, in the middle of a block: the
        // text was cut (`Lowered::cut_off`).
        let mid_block = !matches!(self.program.source().last(), None | Some(b'\n' | b'\r' | b'%'));
        if pc >= blocks.len() && mid_block {
            self.cut_off = blocks.last().map(|b| b.span);
        }
        self.finish_corner();
    }

    /// The run as the course from here on depends on it (`LoopState`).
    fn loop_state(&self) -> LoopState {
        LoopState {
            variables: self.variables.revision(),
            at: (self.emitter.at.x.to_bits(), self.emitter.at.z.to_bits()),
            started: self.emitter.first_start.is_some(),
            compensated: self.emitter.compensated,
            dwelled: self.emitter.dwelled,
            pending_corner: self.pending_corner.clone(),
            modal: self.modal.clone(),
            cycle_memory: self.cycle_memory,
            calls: self.calls.clone(),
            loops: self.loops.clone(),
            modal_call: self.modal_call,
            first_program_name: self.first_program_name,
            tape_opened: self.tape_opened,
            position_damaged: self.position_damaged,
        }
    }

    /// Whether block `index` is a jump that can close a loop: `GOTO`, `IF … GOTO`/`IF … N<label>`
    /// or `ENDn`. A return (`RTS`, `M99`) or a repetition of a call goes back by the call's
    /// own count, and is bounded by it.
    fn is_loop_jump(&self, index: usize) -> bool {
        let block = self.program.block(index);
        block.statement == Statement::Control
            && self.program.words_of(block).iter().any(|w| {
                matches!(w.kind, WordKind::Keyword { index } if matches!(
                    self.tables.keyword_info(index as usize).kind,
                    KeywordKind::If | KeywordKind::Goto | KeywordKind::EndLoop
                ))
            })
    }

    /// Whether the jump back at block `from` to block `target` finds the run as it was at
    /// the jump's last take: then it loops forever, and an error there says so.
    fn loops_forever(&mut self, from: usize, target: usize) -> bool {
        let state = self.loop_state();
        self.last_loop_jump = Some(from);
        let jump = match self.loop_jumps.entry(from) {
            std::collections::hash_map::Entry::Vacant(vacant) => {
                vacant.insert(LoopJump { taken: 1, state });
                return false;
            }
            std::collections::hash_map::Entry::Occupied(occupied) => occupied.into_mut(),
        };
        jump.taken += 1;
        if jump.state != state {
            jump.state = state;
            return false;
        }
        let (jump_span, target_span) = (self.program.block(from).span, self.program.block(target).span);
        let error = Diagnostic::error(DiagnosticKind::EndlessLoop { passes: jump.taken }, jump_span)
            .with_related(target_span, "the loop starts here; each pass runs as the one before");
        self.diagnostics.push(error);
        true
    }

    /// The run stopped at a bound (blocks or moves) at `span`; `passes`, the jump back's takes
    /// where a loop ran the blocks.
    fn runaway(&mut self, span: Span, passes: Option<u64>) {
        let moves = self.emitter.moves.len();
        self.error(DiagnosticKind::RunawayProgram { blocks: self.executed, moves, passes }, span);
    }

    /// The lowered program, once the blocks have run.
    fn finish(mut self) -> Lowered {
        self.judge_missing_points();
        let start = self.emitter.moves.first().map(|_| self.first_move_start()).unwrap_or(self.emitter.at);
        let mut toolpath = Toolpath { start, moves: std::mem::take(&mut self.emitter.moves) };
        if self.options.nose_radius_compensation {
            let setup = super::nose_radius::Setup::new(self.machine, self.modal.frame.scale());
            // Compensation inserts corner arcs: the cycles' move ranges follow them. Without
            // a compensated move or a dwell it changes nothing, and its pass over the moves
            // is skipped.
            let moved = if self.emitter.compensated || self.emitter.dwelled {
                super::nose_radius::apply(&mut toolpath, &setup, &mut self.diagnostics)
            } else {
                super::nose_radius::MoveMap::identity(toolpath.moves.len())
            };
            for expansion in &mut self.expansions {
                expansion.moves = moved.range(expansion.moves.clone());
                // A corner inserted in front of a profile block's first move is that block's.
                for (first, _) in &mut expansion.traced {
                    *first = moved.range(*first..*first).start;
                }
                expansion.traced_end = moved.range(expansion.traced_end..expansion.traced_end).start;
                // A corner inserted in front of a root block's move is not that move.
                for (m, _) in &mut expansion.root {
                    *m = moved.range(*m..*m + 1).end - 1;
                }
            }
            for mark in &mut self.coordinates {
                mark.from_move = moved.range(mark.from_move..mark.from_move).start;
            }
        }
        let blocks = self.program.blocks();
        let block_of = |start: u32| blocks.binary_search_by_key(&start, |b| b.span.start).ok();
        // The moves the cycles make, as ranges in order that do not overlap (one cycle's may
        // hold another's): whether move `k` is a cycle's.
        let mut cycles: Vec<std::ops::Range<usize>> = self.expansions.iter().map(|e| e.moves.clone()).collect();
        cycles.sort_unstable_by_key(|r| r.start);
        cycles.dedup_by(|later, earlier| {
            let overlaps = later.start < earlier.end;
            if overlaps {
                earlier.end = earlier.end.max(later.end);
            }
            overlaps
        });
        let in_cycle = |k: usize| {
            let after = cycles.partition_point(|r| r.start <= k);
            after.checked_sub(1).is_some_and(|last| cycles[last].contains(&k))
        };
        for expansion in &mut self.expansions {
            let end = expansion.moves.end;
            expansion.feed_read_after = super::modal_feed_read(self.program, &toolpath.moves, end, block_of);
            expansion.motion_read_after =
                super::modal_motion_read(self.program, &toolpath.moves, end, in_cycle, block_of);
        }
        crate::diagnostic::merge_repeats(&mut self.diagnostics);
        self.diagnostics.sort_by_key(|d| (d.span.start, d.span.end));
        // A system variable read as 0 is said once, where the program first reads it.
        let mut unknown = std::collections::HashSet::new();
        self.diagnostics.retain(|d| match &d.kind {
            DiagnosticKind::SystemVariableUnknown { name } => unknown.insert(name.clone()),
            _ => true,
        });
        Lowered {
            toolpath,
            diagnostics: self.diagnostics,
            expansions: self.expansions,
            frame: super::initial_frame(self.program, self.machine),
            executed_blocks: self.executed,
            coordinates: self.coordinates,
            cut_off: self.cut_off,
        }
    }

    /// Record the program coordinates in force for the moves the current block is about
    /// to make, when they differ from the last mark.
    pub fn mark_coordinates(&mut self) {
        let mark = super::CoordinateMark {
            from_move: self.emitter.moves.len(),
            frame: self.modal.frame,
            absolute: self.modal.absolute,
            shift: self.modal.shift,
        };
        let same =
            |m: &super::CoordinateMark| m.frame == mark.frame && m.absolute == mark.absolute && m.shift == mark.shift;
        if self.coordinates.is_empty() {
            if !same(&self.initial_mark()) {
                self.coordinates.push(mark);
            }
            return;
        }
        match self.coordinates.last_mut() {
            Some(last) if same(last) => {}
            Some(last) if last.from_move == mark.from_move => *last = mark,
            _ => self.coordinates.push(mark),
        }
    }

    fn initial_mark(&self) -> super::CoordinateMark {
        super::CoordinateMark {
            from_move: 0,
            frame: super::initial_frame(self.program, self.machine),
            absolute: true,
            shift: Xz::default(),
        }
    }

    /// Whether sequence `key`, which names no block that parses, is the name of a block that
    /// does not: then what refers to it at `span` is not checked, and a note says so (its
    /// parse error is the finding). `what` says how the word refers to it.
    pub(super) fn damaged_target(&mut self, key: &str, span: Span, what: &'static str) -> bool {
        let Some(damaged) = self.labels().damaged(key) else { return false };
        let damaged = self.program.block(damaged).span;
        let note = Diagnostic::note(DiagnosticKind::DependsOnDamagedBlock { what }, span)
            .with_related(damaged, format!("N{key}, which does not parse"));
        self.diagnostics.push(note);
        true
    }

    /// A block that does not parse and names an axis (`X`, `Z`, `U`, `W` with a value after
    /// it) may have moved the tool anywhere: the position is not known until the next moves
    /// name both axes, and what depends on it (the moves and checks from there) is left
    /// out, without the note a missing home position gets. A block that names no axis (a
    /// cycle call the schema rejects, a note outside a comment) leaves the tool where it is.
    fn damaged_block(&mut self, index: usize) {
        let text = self.program.text(self.program.block(index).span);
        let names_an_axis = text.windows(2).any(|pair| {
            matches!(pair[0].to_ascii_uppercase(), b'X' | b'Z' | b'U' | b'W')
                && matches!(pair[1], b'0'..=b'9' | b'-' | b'+' | b'.' | b'=' | b'[' | b'#')
        });
        if !names_an_axis {
            return;
        }
        self.finish_corner();
        self.emitter.at = Xz::new(f64::NAN, f64::NAN);
        self.position_damaged = true;
    }

    /// A line the parser took for a tape leader (`syntax.rs`) is one only if the tape's
    /// `%` follows the leader: a control reading a file with no `%` there reads the line as
    /// a block and rejects it. The lines up to the `%` are leaders or empty, so the first
    /// other block decides, once.
    fn check_leader(&mut self, index: usize) {
        let tape_follows = *self.leader_confirmed.get_or_insert_with(|| {
            self.program.blocks()[index..]
                .iter()
                .find(|b| !matches!(b.statement, Statement::Leader | Statement::Empty))
                .is_some_and(|b| b.statement == Statement::TapeMark)
        });
        if !tape_follows {
            self.error(DiagnosticKind::LeaderWithoutTape, self.program.block(index).span);
        }
    }

    fn first_move_start(&self) -> Xz {
        self.emitter.first_start.unwrap_or(self.emitter.at)
    }

    /// Run one block.
    fn execute(&mut self, index: usize) -> Flow {
        self.modal_before_block = super::ModalAfter::of(&self.modal);
        let block = self.program.block(index);
        let words = self.program.words_of(block);
        if self.options.block_delete && words.iter().any(|w| matches!(w.kind, WordKind::BlockDelete { .. })) {
            return Flow::Next;
        }
        match block.statement {
            Statement::Invalid => {
                self.damaged_block(index);
                Flow::Next
            }
            Statement::Empty | Statement::Header | Statement::Graphics | Statement::Pattern => Flow::Next,
            Statement::Trailing => Flow::End,
            Statement::Leader => {
                self.check_leader(index);
                Flow::Next
            }
            Statement::TapeMark => {
                // The first `%` opens the tape (comment lines may stand before it); a second
                // one ends the program, and the parser already made the rest Trailing.
                let opened = std::mem::replace(&mut self.tape_opened, true);
                if opened && words.iter().all(|w| matches!(w.kind, WordKind::TapeMark | WordKind::Comment(_))) {
                    Flow::End
                } else {
                    Flow::Next
                }
            }
            Statement::ProgramName => match self.first_program_name {
                None => {
                    self.first_program_name = Some(index);
                    Flow::Next
                }
                // Running into the next program's name: the main program had no end code.
                Some(_) if self.calls.is_empty() => Flow::End,
                Some(_) => Flow::Next,
            },
            Statement::Assignment => {
                self.assignments(index);
                Flow::Next
            }
            Statement::Control => self.control(index),
            _ => self.machine_block(index),
        }
    }

    /// `NAME=expr`, `#1=expr`, several in one block.
    pub fn assignments(&mut self, index: usize) {
        let block = self.program.block(index);
        for word in self.program.words_of(block) {
            if let WordKind::Assign { target, value } = word.kind {
                let evaluator = self.evaluator();
                let mut warnings = Vec::new();
                let result = evaluator
                    .value(value, &mut self.variables, &mut warnings)
                    .and_then(|v| evaluator.key(target, &mut self.variables, &mut warnings).map(|k| (k, v)));
                self.diagnostics.append(&mut warnings);
                match result {
                    Ok((key, v)) => self.variables.set(key, v, self.dialect),
                    Err(diagnostic) => self.diagnostics.push(diagnostic),
                }
            }
        }
    }

    /// Evaluate an expression, reporting problems; `None` when it fails.
    pub fn value_of(&mut self, expr: u32) -> Option<f64> {
        let mut warnings = Vec::new();
        let result = self.evaluator().value(expr, &mut self.variables, &mut warnings);
        self.diagnostics.append(&mut warnings);
        match result {
            Ok(v) => Some(v),
            Err(diagnostic) => {
                self.diagnostics.push(diagnostic);
                None
            }
        }
    }

    /// `IF`, `GOTO`, `CALL`, `RTS`, `MODIN`, `MODOUT`, `WHILE`, `END`, I/O statements.
    fn control(&mut self, index: usize) -> Flow {
        let block = self.program.block(index);
        let words = self.program.words_of(block);
        let Some((position, kind)) = words.iter().enumerate().find_map(|(i, w)| match w.kind {
            WordKind::Keyword { index } => Some((i, self.tables.keyword_info(index as usize).kind)),
            _ => None,
        }) else {
            return Flow::Next;
        };
        let rest = &words[position + 1..];
        match kind {
            KeywordKind::If => {
                let Some(condition) = rest.iter().find_map(|w| match w.kind {
                    WordKind::Operand { expr } => Some(expr),
                    _ => None,
                }) else {
                    return Flow::Next;
                };
                let Some(value) = self.value_of(condition) else { return Flow::Next };
                if value == 0.0 {
                    return Flow::Next;
                }
                // `IF [..] GOTO n`, `IF [..] N<label>` (OSP) or `IF [..] THEN assignment`.
                if rest.iter().any(|w| matches!(w.kind, WordKind::Assign { .. })) {
                    self.assignments(index);
                    return Flow::Next;
                }
                self.jump_from(index, &rest[1..])
            }
            KeywordKind::Goto => self.jump_from(index, rest),
            KeywordKind::Call => self.call(index, rest, false),
            KeywordKind::ModalCall => {
                self.modal_call = self.call_target(index, rest);
                Flow::Next
            }
            KeywordKind::ModalCallEnd => {
                self.modal_call = None;
                Flow::Next
            }
            KeywordKind::Return => self.return_from_call(),
            KeywordKind::While => {
                let condition = rest.iter().find_map(|w| match w.kind {
                    WordKind::Operand { expr } => Some(expr),
                    _ => None,
                });
                let loop_number = rest.iter().rev().find_map(|w| match w.kind {
                    WordKind::Operand { expr } => Some(expr),
                    _ => None,
                });
                let number = loop_number.and_then(|e| self.value_of(e)).unwrap_or(0.0) as u32;
                let holds = condition.and_then(|c| self.value_of(c)).is_some_and(|v| v != 0.0);
                if holds {
                    if self.loops.last() != Some(&(index, number)) {
                        self.loops.push((index, number));
                    }
                    Flow::Next
                } else {
                    self.loops.retain(|&(b, _)| b != index);
                    match self.matching_end(index, number) {
                        Some(end) => Flow::Jump(end + 1),
                        None => {
                            self.error(DiagnosticKind::UnmatchedLoop { number }, block.span);
                            Flow::End
                        }
                    }
                }
            }
            KeywordKind::EndLoop => {
                let number = rest
                    .iter()
                    .find_map(|w| match w.kind {
                        WordKind::Operand { expr } => Some(expr),
                        _ => None,
                    })
                    .and_then(|e| self.value_of(e))
                    .unwrap_or(0.0) as u32;
                match self.loops.iter().rev().find(|&&(_, n)| n == number) {
                    Some(&(start, _)) => Flow::Jump(start),
                    None => Flow::Next,
                }
            }
            KeywordKind::Then | KeywordKind::Do | KeywordKind::Io | KeywordKind::Schedule => Flow::Next,
            KeywordKind::Graphics | KeywordKind::Pattern => Flow::Next,
        }
    }

    /// The `ENDn` that closes `WHILE … DOn` at `start`.
    fn matching_end(&self, start: usize, number: u32) -> Option<usize> {
        let blocks = self.program.blocks();
        (start + 1..blocks.len()).find(|&i| {
            let words = self.program.words_of(&blocks[i]);
            words.iter().any(|w| {
                matches!(w.kind, WordKind::Keyword { index } if self.tables.keyword_info(index as usize).kind == KeywordKind::EndLoop)
            }) && words.iter().any(|w| match w.kind {
                WordKind::Operand { expr } => matches!(self.program.expr(expr).kind,
                    crate::syntax::ExprKind::Number(n) if n.to_f64() as u32 == number),
                _ => false,
            })
        })
    }

    /// Jump to the label (OSP `N<name>`) or sequence number (Fanuc operand) in `words`.
    fn jump_from(&mut self, index: usize, words: &[crate::syntax::Word]) -> Flow {
        let span = self.program.block(index).span;
        for word in words {
            match word.kind {
                WordKind::Label { number } => {
                    let key = labels::key(self.dialect, self.program.text(word.span), number);
                    return match self.labels().jump(&key, index) {
                        Some(target) => Flow::Jump(target),
                        None => {
                            if !self.damaged_target(&key, word.span, "the jump goes to") {
                                self.error(DiagnosticKind::MissingLabel { name: format!("N{key}") }, word.span);
                            }
                            Flow::End
                        }
                    };
                }
                WordKind::Operand { expr } => {
                    let Some(value) = self.value_of(expr) else { return Flow::End };
                    let key = (value.round() as i64).to_string();
                    return match self.labels().jump(&key, index) {
                        Some(target) => Flow::Jump(target),
                        None => {
                            if !self.damaged_target(&key, word.span, "the jump goes to") {
                                self.error(DiagnosticKind::MissingLabel { name: format!("N{key}") }, word.span);
                            }
                            Flow::End
                        }
                    };
                }
                WordKind::Keyword { .. } => continue,
                _ => {}
            }
        }
        self.error(DiagnosticKind::MissingLabel { name: String::new() }, span);
        Flow::Next
    }

    /// The block that starts the subprogram a `CALL`/`MODIN` names.
    fn call_target(&mut self, index: usize, words: &[crate::syntax::Word]) -> Option<usize> {
        let word = words.iter().find(|w| matches!(w.kind, WordKind::ProgramRef))?;
        let key = labels::program_key(self.dialect, self.program.text(word.span));
        let target = self.labels().program(&key);
        if target.is_none() {
            self.warning(DiagnosticKind::MissingProgram { name: format!("O{key}") }, word.span);
        }
        let _ = index;
        target
    }

    /// OSP `CALL O<name> [Q<n>] [var=value …]`: run the subprogram (Q times).
    fn call(&mut self, index: usize, words: &[crate::syntax::Word], _modal: bool) -> Flow {
        let Some(target) = self.call_target(index, words) else { return Flow::Next };
        let repeat = words
            .iter()
            .find_map(|w| match w.kind {
                WordKind::Number { address, number } if address == crate::dialect::Address::Q => Some(number.to_f64()),
                _ => None,
            })
            .unwrap_or(1.0)
            .max(1.0) as u32;
        // Arguments are evaluated in the caller's frame and set in the callee's.
        let mut arguments = Vec::new();
        for word in words {
            if let WordKind::Assign { target, value } = word.kind
                && let Some(v) = self.value_of(value)
            {
                let mut warnings = Vec::new();
                if let Ok(key) = self.evaluator().key(target, &mut self.variables, &mut warnings) {
                    arguments.push((key, v));
                }
                self.diagnostics.append(&mut warnings);
            }
        }
        self.enter(index, target, repeat, arguments)
    }

    /// Push a call frame and jump into the subprogram (past its name block).
    pub fn enter(
        &mut self,
        from: usize,
        target: usize,
        repeat: u32,
        arguments: Vec<(super::eval::VarKey, f64)>,
    ) -> Flow {
        if self.calls.len() >= MAX_CALL_DEPTH {
            let span = self.program.block(from).span;
            self.error(DiagnosticKind::CallsTooDeep { max: MAX_CALL_DEPTH }, span);
            return Flow::End;
        }
        self.calls.push(Call { return_to: from + 1, entry: target + 1, remaining: repeat.saturating_sub(1) });
        self.variables.push_frame();
        for (key, value) in arguments {
            self.variables.set(key, value, self.dialect);
        }
        Flow::Jump(target + 1)
    }

    /// `RTS`, `M99`: repeat, return, or (in the main program) end.
    pub fn return_from_call(&mut self) -> Flow {
        match self.calls.last_mut() {
            None => Flow::End,
            Some(call) if call.remaining > 0 => {
                call.remaining -= 1;
                Flow::Jump(call.entry)
            }
            Some(_) => {
                let call = self.calls.pop().map(|c| c.return_to).unwrap_or(usize::MAX);
                self.variables.pop_frame();
                Flow::Jump(call)
            }
        }
    }

    /// Fanuc `M98 P<program> [L<count>]`.
    pub fn subprogram_call(&mut self, index: usize, program_number: f64, count: f64) -> Flow {
        let key = (program_number.round() as i64).to_string();
        match self.labels().program(&key) {
            Some(target) => self.enter(index, target, count.max(1.0) as u32, Vec::new()),
            None => {
                let span = self.program.block(index).span;
                self.warning(DiagnosticKind::MissingProgram { name: format!("O{key}") }, span);
                Flow::Next
            }
        }
    }
}
