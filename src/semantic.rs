//! The semantic pass: a parsed program to the toolpath the machine really moves.
//!
//! The interpreter walks the blocks the way a control does: it keeps the modal state
//! (units, absolute/incremental, feed mode, spindle mode and clamp, motion mode, tool,
//! nose-radius compensation), evaluates variables and expressions, follows `IF`/`GOTO`,
//! `WHILE`, `CALL`/`RTS` and `M98`/`M99`, and turns every motion, dwell and canned cycle
//! into IR moves (`crate::toolpath`). Nose-radius compensation is applied afterwards over
//! each run of compensated moves, so the IR holds both the tool's reference point path and
//! the programmed contour.
//!
//! **Invariant: lowering never fails.** Problems are diagnostics on the block that has
//! them; the block is skipped and the rest of the program is lowered.
//!
//! **Bounded work.** The number of executed blocks, the depth of subprogram calls and the
//! nesting of expressions are bounded, so a runaway loop is a diagnostic, not a hang.

mod block;
pub(crate) mod cycles;
mod decimal_point;
mod emitter;
mod eval;
pub(crate) mod frame;
mod interpreter;
pub(crate) mod labels;
mod modal;
mod motion;
pub mod nose_radius;
mod plausibility;
pub(crate) mod profile;

pub use frame::Frame;

use crate::diagnostic::Diagnostic;
use crate::dialect::{DecimalInput, Dialect, MachineKind};
use crate::machine::{MachineSettings, ToolSettings, Units};
use crate::syntax::Program;
use crate::toolpath::{Limits, Toolpath, Xz};

/// The moves a run may make for each block of its program, beyond
/// [`LowerOptions::max_moves`]: a program of millions of blocks, each a move, is no runaway.
pub const MOVES_PER_BLOCK: usize = 2;

/// How to run the program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LowerOptions {
    /// The block-delete switch: skip blocks that start with `/` (and, on Fanuc, the rest of
    /// a block after a mid-block `/`).
    pub block_delete: bool,
    /// Stop with a diagnostic after this many executed blocks (a runaway loop).
    pub max_executed_blocks: u64,
    /// … or after this many moves, or [`MOVES_PER_BLOCK`] for every block of the program
    /// when that is more (a loop of cycles fills memory long before it has run many
    /// blocks). The moves are what a run holds: at 128 bytes a move, the bound keeps a
    /// small program that runs away to about 260 MB, and a large one in proportion to its text.
    pub max_moves: usize,
    /// Apply nose-radius compensation (`expand` turns it off: the blocks it prints stay
    /// under the program's own `G41`/`G42`).
    pub nose_radius_compensation: bool,
}

impl LowerOptions {
    pub fn new(block_delete: bool) -> LowerOptions {
        LowerOptions {
            block_delete,
            max_executed_blocks: 10_000_000,
            max_moves: 2_000_000,
            nose_radius_compensation: true,
        }
    }
}

/// The machine, as the semantic pass needs it: settings resolved, in the toolpath frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Machine {
    pub units: Units,
    pub diameter_programming: bool,
    pub decimal_input: DecimalInput,
    /// Whether the settings give `decimal_input` (else it is the default, calculator input,
    /// and a program whose words read differently under the other is told so).
    pub decimal_input_given: bool,
    /// Least input increment, machine units.
    pub increment: f64,
    /// Home position in the toolpath frame, when the settings give it.
    pub home: Option<Xz>,
    pub limits: Option<Limits>,
    /// Rapid rate of each axis, mm/min; `assumed` when the settings do not give it.
    pub rapid: Xz,
    pub rapid_assumed: bool,
    pub max_rpm: f64,
    pub tools: Vec<ToolSettings>,
    /// Values of the common variables the machine keeps (`[machine] variables`, `--var`).
    pub variables: Vec<(String, f64)>,
}

/// Rapid traverse used when the machine settings give none, mm/min per axis.
pub const DEFAULT_RAPID_MM_MIN: f64 = 10_000.0;

/// The spindle's top speed when the settings give none, rpm: what constant surface speed
/// with no `G50 S` clamp reaches toward the centre (a common top speed of 200–250 mm chuck
/// lathes; the toolpath's times near X0 depend on it, and a warning says so).
pub const DEFAULT_MAX_SPINDLE_RPM: f64 = 4_000.0;

impl Machine {
    /// The machine a program runs on, from its settings; documented defaults fill the gaps
    /// (mm, diameter programming, calculator decimal input, no home, no travel limits,
    /// 10 m/min rapids, no spindle limit).
    pub fn from_settings(settings: &MachineSettings) -> Machine {
        let units = settings.units.unwrap_or(Units::Mm);
        let diameter_programming = settings.diameter_programming.unwrap_or(true);
        let scale = if units == Units::Inch { frame::MM_PER_INCH } else { 1.0 };
        let x_mm = |x: f64| if diameter_programming { x / 2.0 * scale } else { x * scale };
        let home = settings.home.map(|h| Xz::new(x_mm(h.x), h.z * scale));
        let limits = settings.travel.map(|t| {
            let (a, b) = (x_mm(t.x_min), x_mm(t.x_max));
            Limits { x_min: a.min(b), x_max: a.max(b), z_min: t.z_min * scale, z_max: t.z_max * scale }
        });
        let rapid = settings.rapid_rate.map(|r| Xz::new(r.x * scale, r.z * scale));
        Machine {
            units,
            diameter_programming,
            decimal_input: settings.decimal_input.unwrap_or_default(),
            decimal_input_given: settings.decimal_input.is_some(),
            increment: settings.least_increment.unwrap_or(if units == Units::Inch { 0.0001 } else { 0.001 }),
            home,
            limits,
            rapid: rapid.unwrap_or(Xz::new(DEFAULT_RAPID_MM_MIN, DEFAULT_RAPID_MM_MIN)),
            rapid_assumed: rapid.is_none(),
            max_rpm: settings.max_spindle_rpm.unwrap_or(f64::INFINITY),
            tools: settings.tool.clone(),
            variables: settings.variables.iter().map(|(name, value)| (name.clone(), *value)).collect(),
        }
    }

    /// The spindle's top speed, rpm, which constant surface speed never exceeds: the
    /// settings' `max_spindle_rpm`, else [`DEFAULT_MAX_SPINDLE_RPM`]; and whether it is that
    /// default.
    pub fn spindle_limit(&self) -> (f64, bool) {
        if self.max_rpm.is_finite() { (self.max_rpm, false) } else { (DEFAULT_MAX_SPINDLE_RPM, true) }
    }

    /// Millimetres per machine unit.
    pub fn scale(&self) -> f64 {
        if self.units == Units::Inch { frame::MM_PER_INCH } else { 1.0 }
    }

    /// The finest distance a program on this machine can write, mm: its least increment in
    /// millimetres, in whichever unit gives the finer (a control pairs 0.0001 in with
    /// 0.001 mm, `Frame::set_inch`). A step finer than this puts points on the same
    /// increments.
    pub fn finest_increment_mm(&self) -> f64 {
        let other_mm =
            if self.units == Units::Inch { self.increment * 10.0 } else { self.increment / 10.0 * frame::MM_PER_INCH };
        (self.increment * self.scale()).min(other_mm)
    }
}

/// What a program is read and run with under `settings`, each setting written as the
/// `[machine]` key that sets it (`units = "mm", least_increment = 0.001, …`), for the note
/// that says a program is read with the machine defaults because no model file gives
/// settings. The values are read from [`Machine::from_settings`] and the settings' own
/// defaults, so the note says what is in force and states no number of its own. `stock` is
/// for a run of the part model: whether a `[stock]` table or `--stock` gives the bar (without
/// one it is assumed, and the note says so); none for a run without it.
pub fn settings_in_force(settings: &MachineSettings, stock: Option<bool>) -> String {
    let machine = Machine::from_settings(settings);
    let given = [
        format!("units = {}", toml_string(&machine.units)),
        format!("least_increment = {}", machine.increment),
        format!("diameter_programming = {}", machine.diameter_programming),
        format!("gcode_system = {}", toml_string(&settings.gcode_system.unwrap_or_default())),
        format!("decimal_input = {}", toml_string(&machine.decimal_input)),
        format!("block_delete = {}", settings.block_delete_switch()),
        match settings.dialect {
            Some(dialect) => format!("dialect = {}", toml_string(&dialect)),
            None => "dialect decided from the text".to_string(),
        },
    ];
    let mut parts = vec![given.join(", ")];
    let missing: Vec<&str> = [
        ("home", machine.home.is_none()),
        ("travel", machine.limits.is_none()),
        ("max_spindle_rpm", machine.max_rpm.is_infinite()),
        ("tool table", machine.tools.is_empty()),
        ("stock", stock == Some(false)),
    ]
    .into_iter()
    .filter_map(|(name, missing)| missing.then_some(name))
    .collect();
    if let Some((last, rest)) = missing.split_last() {
        let list = if rest.is_empty() { last.to_string() } else { format!("{} or {last}", rest.join(", ")) };
        parts.push(format!("no {list}"));
    }
    if machine.rapid_assumed {
        parts.push(format!("rapid traverse assumed {} mm/min per axis", machine.rapid.x));
    }
    if stock == Some(false) {
        parts.push("stock assumed: the smallest bar holding every cutting move's start".to_string());
    }
    parts.join("; ")
}

/// A setting's value as TOML writes it (a string as JSON writes it).
fn toml_string<T: serde::Serialize>(value: &T) -> String {
    serde_json::to_string(value).unwrap_or_default()
}

/// Which moves a cycle call produced, for `expand`: the call block, the other blocks the
/// cycle consumed (the first block of a two-block Fanuc cycle, a LAP contour that follows
/// its call), and the range of moves.
#[derive(Debug, Clone, PartialEq)]
pub struct Expansion {
    pub block: usize,
    /// The program's frame at the call (units may change along the program).
    pub frame: Frame,
    pub consumed: Vec<usize>,
    /// The consumed first block of a two-block cycle (`G71 U R`): the control runs it where
    /// it is, so its M codes and T words stay there when the call is written out.
    pub setup: Option<usize>,
    /// The profile blocks the cycle runs as the program's own blocks (a finishing pass:
    /// `G70`, a LAP finishing cycle), each as (the index in the cycle's moves of the first
    /// move it makes there, the block): their M codes, T words and comments go on the block
    /// written for that move, where the control runs them.
    pub traced: Vec<(usize, usize)>,
    /// The move after the last one the traced profile makes (the moves after it, up to
    /// `moves.end`, are the cycle's own: `G70`'s return to the start point); equal to
    /// `moves.start` where nothing is traced.
    pub traced_end: usize,
    /// A LAP continuous thread (`G88`, `cycles/lap_thread.rs`): the blocks of the contour
    /// its final pass runs on, the thread's root, each with the index of the move that pass
    /// makes for it (the contour's last approach block with the rapid to the thread's start,
    /// each thread element with its thread move). The passes before it are the control's
    /// offsets of the same contour, so these blocks place every pass. Empty for any other
    /// cycle, and where the final pass's moves do not match the contour's blocks one for one.
    pub root: Vec<(usize, usize)>,
    pub moves: std::ops::Range<usize>,
    /// The modal words in force before the call, and after it: the expanded blocks must
    /// leave the latter behind so that the blocks after them run as before.
    pub before: ModalAfter,
    pub after: ModalAfter,
    /// Why `expand` leaves the call as it is, if it does (a drilling cycle).
    pub kept: Option<&'static str>,
    /// What `expand` says of the blocks it writes for the call (how an OSP thread cycle's
    /// height reads), a note at the call.
    pub note: Option<crate::diagnostic::DiagnosticKind>,
    /// Whether a move after the cycle reads the F it leaves in force (`after.f_word`,
    /// [`modal_feed_read`]): where none does, the blocks written for it need not put that F
    /// back (a lone `F0.1` before the closing rapid and `M30` is a block of no use).
    /// Set once the program has run; true until then.
    pub feed_read_after: bool,
    /// Whether a move after the cycle runs under the motion code it leaves in force
    /// (`after.motion`, [`modal_motion_read`]): where none does, the blocks written for it
    /// need not put that code back (a lone `G1` before a tool change and a `G00` block).
    /// Set once the program has run; true until then.
    pub motion_read_after: bool,
}

/// Whether a move of `moves` from `from` on runs under the modal motion code in force there
/// before a block or a cycle sets another: the first move other than a dwell, where its
/// block writes no motion code (`G00`-`G03`, a thread move) and it is no cycle's
/// (`in_cycle`: a cycle makes its moves by its own codes, and leaves its own in force).
/// `block_of` finds a move's block by the start of its source; a move whose block is not
/// found is taken to read it.
pub(crate) fn modal_motion_read(
    program: &Program<'_>,
    moves: &[crate::toolpath::Move],
    from: usize,
    in_cycle: impl Fn(usize) -> bool,
    block_of: impl Fn(u32) -> Option<usize>,
) -> bool {
    use crate::dialect::GFunction;
    use crate::syntax::{CodeLetter, WordKind};
    use crate::toolpath::Motion;
    let tables = program.config().tables();
    let Some(k) = (from..moves.len()).find(|&k| moves[k].motion != Motion::Dwell) else { return false };
    if in_cycle(k) {
        return false;
    }
    let Some(block) = block_of(moves[k].source.start) else { return true };
    !program.words_of(program.block(block)).iter().any(|word| match word.kind {
        WordKind::Code { letter: CodeLetter::G, code } => matches!(
            tables.g(code).and_then(|g| g.function),
            Some(GFunction::Rapid | GFunction::Linear | GFunction::Cw | GFunction::Ccw | GFunction::ThreadMove)
        ),
        _ => false,
    })
}

/// Whether a move of `moves` from `from` on reads the modal F in force there before a block
/// writes another: the first feed, arc or thread move whose block writes no `F` of its own
/// (a thread move with its precise lead, Fanuc's `E`, reads no F and writes none: the moves
/// after it are looked at). `block_of` finds a move's block by the start of its source; a
/// move whose block is not found is taken to read it.
pub(crate) fn modal_feed_read(
    program: &Program<'_>,
    moves: &[crate::toolpath::Move],
    from: usize,
    block_of: impl Fn(u32) -> Option<usize>,
) -> bool {
    use crate::dialect::Address;
    use crate::syntax::WordKind;
    use crate::toolpath::Motion;
    let precise = program.config().tables().thread_lead.precise.map(|p| p.address);
    for m in moves.iter().skip(from).filter(|m| !matches!(m.motion, Motion::Rapid | Motion::Dwell)) {
        let Some(block) = block_of(m.source.start) else { return true };
        let (mut writes_feed, mut precise_lead) = (false, false);
        for word in program.words_of(program.block(block)) {
            if let WordKind::Number { address, .. } | WordKind::Expr { address, .. } = word.kind {
                writes_feed |= address == Address::F;
                precise_lead |= m.threading && Some(address) == precise;
            }
        }
        if writes_feed {
            return false;
        }
        if !precise_lead {
            return true;
        }
    }
    false
}

/// The modal words a cycle leaves in force: the motion code (when it is a plain one; after
/// a single cycle the blocks that rely on it are repetitions, expanded themselves), and F
/// and S as the program writes them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModalAfter {
    pub motion: Option<crate::toolpath::Motion>,
    pub f_word: f64,
    pub s_word: f64,
}

impl ModalAfter {
    pub(crate) fn of(modal: &modal::Modal) -> ModalAfter {
        use crate::toolpath::Motion;
        let motion = match modal.motion {
            modal::MotionMode::Rapid => Some(Motion::Rapid),
            modal::MotionMode::Linear => Some(Motion::Feed),
            modal::MotionMode::Cw => Some(Motion::Cw),
            modal::MotionMode::Ccw => Some(Motion::Ccw),
            _ => None,
        };
        ModalAfter { motion, f_word: modal.feed, s_word: modal.speed }
    }
}

/// The result of lowering: the toolpath (not yet validated), what went wrong, and where the
/// cycles are.
#[derive(Debug, Clone)]
pub struct Lowered {
    pub toolpath: Toolpath,
    pub diagnostics: Vec<Diagnostic>,
    pub expansions: Vec<Expansion>,
    /// The program's frame at its start (units and diameter programming), for printing
    /// moves back.
    pub frame: Frame,
    /// Executed blocks, for the bounded-work report.
    pub executed_blocks: u64,
    /// How the program's coordinate words map to the toolpath frame, from a move on: one
    /// mark where the frame, the absolute/incremental mode or the `G50` shift changes. A
    /// later pass that writes a move back into its own block (`compensation::rewrite`)
    /// reads them; empty means the start frame, absolute, unshifted throughout.
    pub coordinates: Vec<CoordinateMark>,
    /// The last block, when the program ran off the end of its text in the middle of a
    /// block with no program end (M02, M30, M99, `RTS`, a closing `%`): the text was cut (a
    /// pipe whose writer died, a copy that stopped). What it holds runs, but it is not the
    /// program, and an output made from it would look whole. A run of a file refuses it
    /// (`DiagnosticKind::ProgramCut`); an editor's buffer is often in this state as it is
    /// typed, and is not.
    pub cut_off: Option<crate::source::Span>,
}

/// The program coordinates in force from move `from_move` on (see `Lowered::coordinates`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoordinateMark {
    pub from_move: usize,
    pub frame: Frame,
    /// `X`/`Z` words are absolute (`G90`; always on Fanuc system A, which uses `U`/`W`).
    pub absolute: bool,
    /// Toolpath frame minus program coordinates, mm (`G50 X Z`).
    pub shift: Xz,
}

/// What `toolpath::Validated` checks of a lowered program: its toolpath.
impl AsRef<Toolpath> for Lowered {
    fn as_ref(&self) -> &Toolpath {
        &self.toolpath
    }
}

impl Lowered {
    /// The coordinates in force for move `index`.
    pub fn coordinates_at(&self, index: usize) -> CoordinateMark {
        let k = self.coordinates.partition_point(|m| m.from_move <= index);
        match k.checked_sub(1).and_then(|k| self.coordinates.get(k)) {
            Some(mark) => *mark,
            None => CoordinateMark { from_move: 0, frame: self.frame, absolute: true, shift: Xz::default() },
        }
    }
}

/// Lower a parsed program. Never fails; see the module documentation. A program the pass
/// does not lower (see [`lowers`]) gives an empty toolpath and no diagnostics: the front end
/// has already said what it is.
pub fn lower(program: &Program<'_>, machine: &Machine, options: &LowerOptions) -> Lowered {
    lower_tuned(program, machine, options, crate::parallel::tuning())
}

/// [`lower`] with `tuning` in place of the process's: the same result for any tuning
/// (`tests/it/arc_times.rs` holds the arcs timed on a second thread to the plain run).
pub fn lower_tuned(
    program: &Program<'_>,
    machine: &Machine,
    options: &LowerOptions,
    tuning: &crate::parallel::Tuning,
) -> Lowered {
    if !lowers(program) {
        return Lowered {
            toolpath: Toolpath { start: machine.home.unwrap_or(Xz::new(f64::NAN, f64::NAN)), moves: Vec::new() },
            diagnostics: Vec::new(),
            expansions: Vec::new(),
            frame: initial_frame(program, machine),
            executed_blocks: 0,
            coordinates: Vec::new(),
            cut_off: None,
        };
    }
    interpreter::Interpreter::new(program, machine, options, tuning).run()
}

/// Whether the semantic pass lowers this program. It simulates lathes: an OSP
/// machining-centre program (the front end notes it, `machining-centre-program`, and checks
/// only its syntax) moves a milling spindle in three axes, and its G-codes mean other things
/// there, so it has no lathe toolpath.
pub fn lowers(program: &Program<'_>) -> bool {
    let config = program.config();
    !(config.dialect == Dialect::Osp && config.machine_kind == MachineKind::MachiningCentre)
}

/// The frame a program starts in on this machine.
pub fn initial_frame(program: &Program<'_>, machine: &Machine) -> Frame {
    Frame {
        dialect: program.config().dialect,
        inch: machine.units == Units::Inch,
        diameter: machine.diameter_programming,
        decimal_input: if program.config().dialect == Dialect::Fanuc {
            machine.decimal_input
        } else {
            DecimalInput::Calculator
        },
        increment: machine.increment,
    }
}
