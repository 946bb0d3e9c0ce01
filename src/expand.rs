//! `turnpass expand`: every cycle replaced by the explicit `G00`/`G01`/`G02`/`G03` blocks it
//! performs, in the program's own dialect and style, all other blocks untouched.
//!
//! The moves come from lowering without nose-radius compensation, so they are the
//! programmed contour, and the printed blocks stay under the program's own `G41`/`G42`.
//! Coordinates go back through the program's frame (units, diameter X) and are rounded to
//! the least increment; motion codes and F are written when they change; arcs use the
//! program's own form (`R`/`L` radius or `I K` centre).

use crate::back::grid::{ArcWords, Grid};
use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::{Address, Code, Dialect, GFunction};
use crate::printer::{Edits, NewBlock, NewWord};
use crate::semantic::{Lowered, ModalAfter};
use crate::syntax::{Block, CodeLetter, Number, Program, Statement, WordKind};
use crate::toolpath::{Compensation, Motion, Move, Xz};

mod thread_pass;

/// Edits that replace each cycle call with its moves (and delete the blocks it consumed).
/// On a control with no thread move (OSP) a thread pass is written as a single-pass cycle
/// block (`thread_pass.rs`); a cycle whose thread moves are not such passes stays as it
/// is, with a note.
pub fn expansion_edits(program: &Program<'_>, lowered: &Lowered) -> (Edits, Vec<Diagnostic>) {
    let mut edits = Edits::new();
    let mut notes = Vec::new();
    let calls: std::collections::HashSet<usize> = lowered.expansions.iter().map(|e| e.block).collect();
    let style = ProgramStyle::of(program);
    for expansion in &lowered.expansions {
        let moves = &lowered.toolpath.moves[expansion.moves.clone()];
        let start = lowered.toolpath.start_of(expansion.moves.start);
        // The compensation in effect when the cycle starts: the written blocks switch it
        // where the cycle's moves do (a G70 profile's own G41/G42/G40).
        let compensation_before = expansion
            .moves
            .start
            .checked_sub(1)
            .and_then(|k| lowered.toolpath.moves.get(k))
            .map_or(Compensation::Off, |m| m.compensation);
        let shift = lowered.coordinates_at(expansion.moves.start).shift;
        match expansion_blocks(program, expansion, moves, start, compensation_before, shift, style) {
            ExpansionBlocks::Keep => {}
            ExpansionBlocks::Blocks(blocks) => {
                edits.replace(expansion.block, blocks);
                delete_consumed(&mut edits, program, expansion, &calls);
            }
            ExpansionBlocks::NotExpandable => {
                let span = program.block(expansion.block).span;
                notes.push(Diagnostic::note(DiagnosticKind::NotExpandable, span));
            }
        }
    }
    (edits, notes)
}

/// What a cycle call becomes.
pub(crate) enum ExpansionBlocks {
    /// A single-pass thread cycle: it is one pass already; leave it.
    Keep,
    /// The blocks that replace the call.
    Blocks(Vec<NewBlock>),
    /// Its thread moves have no plain-block form in this dialect; leave it.
    NotExpandable,
}

/// The blocks that replace `expansion`'s call block when the cycle makes `moves` from
/// `start` (programmed contour points: `Move.contour`, arcs about `Move.centre`), with
/// `compensation_before` in force before it and the program's coordinates shifted by
/// `shift` (`G50 X Z`), in the program's `style` (`ProgramStyle::of`, read once per program:
/// it reads every block). `expand` passes the cycle's own moves, the compensation pass its
/// compensated ones.
pub(crate) fn expansion_blocks(
    program: &Program<'_>,
    expansion: &crate::semantic::Expansion,
    moves: &[Move],
    start: Xz,
    compensation_before: Compensation,
    shift: Xz,
    style: ProgramStyle,
) -> ExpansionBlocks {
    let tables = program.config().tables();
    let thread_code = tables.code_for(GFunction::ThreadMove);
    let compensation_codes = [
        tables.code_for(GFunction::CompensationOff).unwrap_or(Code::whole(40)),
        tables.code_for(GFunction::CompensationLeft).unwrap_or(Code::whole(41)),
        tables.code_for(GFunction::CompensationRight).unwrap_or(Code::whole(42)),
    ];
    let frame = expansion.frame;
    // S in force before the cycle's block: the written blocks give S where it changes
    // (the cycle block's own S included, since the block is replaced).
    let speed_before = Some(expansion.before.s_word).filter(|s| *s > 0.0);
    let mut writer = BlockWriter {
        grid: Grid::of(frame, shift),
        radius_arcs: style.radius_arcs,
        dialect: program.config().dialect,
        thread_code: thread_code.unwrap_or(Code::whole(32)),
        compensation_codes,
        motion: None,
        feed: None,
        speed: speed_before,
        compensation: compensation_before,
    };
    if thread_code.is_none() && moves.iter().any(|m| m.threading) {
        // No thread move in this dialect: passes become single-pass cycle blocks.
        return match thread_pass::expand(program, expansion, moves, start, style, &mut writer) {
            thread_pass::Threads::Keep => ExpansionBlocks::Keep,
            thread_pass::Threads::Blocks(blocks) => ExpansionBlocks::Blocks(blocks),
            thread_pass::Threads::NotExpandable => ExpansionBlocks::NotExpandable,
        };
    }
    let mut start = start;
    let mut blocks: Vec<NewBlock> = moves
        .iter()
        .map(|m| {
            let block = writer.block(start, m);
            start = m.contour;
            block
        })
        .collect();
    blocks.extend(writer.restore(&expansion.after));
    ExpansionBlocks::Blocks(blocks)
}

/// Delete the blocks a cycle consumed; a block that is itself a cycle call keeps its own
/// expansion.
pub(crate) fn delete_consumed(
    edits: &mut Edits,
    program: &Program<'_>,
    expansion: &crate::semantic::Expansion,
    calls: &std::collections::HashSet<usize>,
) {
    for &consumed in &expansion.consumed {
        if !calls.contains(&consumed) && program.block(consumed).statement != Statement::Invalid {
            edits.delete(consumed);
        }
    }
}

/// What the blocks written for a cycle take from the whole program. Each reads every block,
/// so a pass that writes many cycles reads them once (`ProgramStyle::of`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ProgramStyle {
    /// Arcs are written with a radius (`uses_radius_arcs`).
    pub radius_arcs: bool,
    /// Some block turns thread chamfering on (OSP `M23`): an unchamfered thread pass then
    /// writes chamfering off (`thread_pass.rs`).
    pub thread_chamfering: bool,
}

impl ProgramStyle {
    pub(crate) fn of(program: &Program<'_>) -> ProgramStyle {
        let chamfer_on = program.config().tables().m_functions.thread_chamfer_on.first().copied();
        ProgramStyle {
            radius_arcs: uses_radius_arcs(program),
            thread_chamfering: chamfer_on.is_some_and(|m| program_uses_m(program, m)),
        }
    }
}

/// Whether any block of the program writes M code `m`.
fn program_uses_m(program: &Program<'_>, m: u16) -> bool {
    program.blocks().iter().any(|block| {
        program
            .words_of(block)
            .iter()
            .any(|w| matches!(w.kind, WordKind::Code { letter: CodeLetter::M, code } if code.major() == m))
    })
}

/// Whether the program writes its arcs with a radius (`R`, OSP `L`) rather than `I K`.
pub(crate) fn uses_radius_arcs(program: &Program<'_>) -> bool {
    let mut tally = ArcFormTally::default();
    for block in program.blocks() {
        tally.add_block(program, block);
    }
    tally.radius_arcs()
}

/// The radius and centre words of a program's motion blocks, counted block by block
/// (`uses_radius_arcs`), so that a caller reading every block anyway counts them in its own
/// pass (`compensation::rewrite::ProgramTables`).
#[derive(Default)]
pub(crate) struct ArcFormTally {
    by_radius: u32,
    by_centre: u32,
}

/// The arc words of one block, as `ArcFormTally::add_block` read them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum BlockArcWords {
    /// Not a motion block: its words were not read.
    NotRead,
    /// Neither a radius nor a centre word.
    Neither,
    /// A radius word (`R`, OSP `L`), with or without centre words.
    Radius,
    /// Centre words (`I`, `K`) and no radius word.
    Centre,
}

impl ArcFormTally {
    /// Count `block`'s radius and centre words, and say which it has.
    pub(crate) fn add_block(&mut self, program: &Program<'_>, block: &Block) -> BlockArcWords {
        if block.statement != Statement::Motion {
            return BlockArcWords::NotRead;
        }
        let radius = if program.config().dialect == Dialect::Osp { Address::L } else { Address::R };
        let (by_radius, by_centre) = (self.by_radius, self.by_centre);
        for word in program.words_of(block) {
            if let WordKind::Number { address, .. } | WordKind::Expr { address, .. } = word.kind {
                if address == radius {
                    self.by_radius += 1;
                } else if address == Address::I || address == Address::K {
                    self.by_centre += 1;
                }
            }
        }
        if self.by_radius > by_radius {
            BlockArcWords::Radius
        } else if self.by_centre > by_centre {
            BlockArcWords::Centre
        } else {
            BlockArcWords::Neither
        }
    }

    /// Whether the program, all of whose blocks were counted, writes its arcs with a radius.
    pub(crate) fn radius_arcs(&self) -> bool {
        self.by_radius > self.by_centre
    }
}

struct BlockWriter {
    /// The grid of the cycle's coordinates.
    grid: Grid,
    radius_arcs: bool,
    dialect: Dialect,
    /// `G32` (system A/B) or `G33` (system C): one thread pass.
    thread_code: Code,
    /// `G40`, `G41`, `G42` in this dialect.
    compensation_codes: [Code; 3],
    /// The last motion code written (`None` before the first), and whether it was a thread.
    motion: Option<(Motion, bool)>,
    feed: Option<f64>,
    speed: Option<f64>,
    compensation: Compensation,
}

impl BlockWriter {
    /// The absolute `X` and `Z` words of a point in the toolpath frame.
    fn point_words(&self, p: Xz) -> [NewWord; 2] {
        let on_grid = self.grid.point(p);
        [
            NewWord::Number(Address::X, self.grid.number(on_grid.x)),
            NewWord::Number(Address::Z, self.grid.number(on_grid.z)),
        ]
    }

    /// A block that puts back the modal motion code, F and S the original program has after
    /// the cycle, where the written blocks left others in force (a `G01 F0.25` from a
    /// roughing pass would otherwise carry into the blocks after the call).
    fn restore(&mut self, after: &ModalAfter) -> Option<NewBlock> {
        let mut words = Vec::new();
        if let Some(motion) = after.motion
            && self.motion.is_some_and(|written| written != (motion, false))
        {
            let code = match motion {
                Motion::Rapid => 0,
                Motion::Feed => 1,
                Motion::Cw => 2,
                Motion::Ccw => 3,
                Motion::Dwell => return None,
            };
            words.push(NewWord::Code(CodeLetter::G, Code::whole(code)));
            self.motion = Some((motion, false));
        }
        if after.f_word > 0.0 && self.feed.is_some_and(|f| f != after.f_word) {
            words.push(NewWord::Number(Address::F, feed_number(after.f_word)));
            self.feed = Some(after.f_word);
        }
        if after.s_word > 0.0 && self.speed.is_some_and(|s| s != after.s_word) {
            words.push(NewWord::Number(Address::S, feed_number(after.s_word)));
            self.speed = Some(after.s_word);
        }
        (!words.is_empty()).then(|| NewBlock::new(words))
    }

    fn block(&mut self, start: Xz, m: &Move) -> NewBlock {
        let mut words = Vec::new();
        if m.motion == Motion::Dwell {
            let seconds = m.t_end - m.t_start;
            words.push(NewWord::Code(CodeLetter::G, Code::whole(4)));
            let address = if self.dialect == Dialect::Osp { Address::F } else { Address::X };
            words.push(NewWord::Number(address, Number::new((seconds * 1000.0).round() as i64, 3, true)));
            return NewBlock::new(words);
        }
        let code = match m.motion {
            _ if m.threading => self.thread_code,
            Motion::Rapid => Code::whole(0),
            Motion::Feed => Code::whole(1),
            Motion::Cw => Code::whole(2),
            Motion::Ccw => Code::whole(3),
            Motion::Dwell => unreachable!("dwells return above"),
        };
        if m.compensation != self.compensation {
            let code = match m.compensation {
                Compensation::Off => self.compensation_codes[0],
                Compensation::Left => self.compensation_codes[1],
                Compensation::Right => self.compensation_codes[2],
            };
            words.push(NewWord::Code(CodeLetter::G, code));
            self.compensation = m.compensation;
        }
        if self.motion != Some((m.motion, m.threading)) || m.is_arc() {
            words.push(NewWord::Code(CodeLetter::G, code));
            self.motion = Some((m.motion, m.threading));
        }
        let end = m.contour;
        words.extend(self.point_words(end));
        if m.is_arc() {
            // The words `compensate` predicts the control to run (`Grid::arc_words`): the
            // program's form where it holds the arc after rounding, else the centre form.
            let grid = self.grid;
            let (i, k) = (grid.length(m.centre.x - start.x), grid.length(m.centre.z - start.z));
            match grid.arc_words(start, end, m.centre, m.motion == Motion::Ccw, self.radius_arcs) {
                ArcWords::Radius(radius) => {
                    let address = if self.dialect == Dialect::Osp { Address::L } else { Address::R };
                    words.push(NewWord::Number(address, grid.number(radius)));
                }
                ArcWords::Centre { i, k } => {
                    words.push(NewWord::Number(Address::I, grid.number(i)));
                    words.push(NewWord::Number(Address::K, grid.number(k)));
                }
                // An arc whose rounded ends meet (a cycle's own moves; `compensate` writes
                // such an arc as a line): its centre as the cycle has it.
                ArcWords::Line => {
                    words.push(NewWord::Number(Address::I, grid.number(i)));
                    words.push(NewWord::Number(Address::K, grid.number(k)));
                }
            }
        }
        if m.motion != Motion::Rapid && self.feed != Some(m.f_word) && m.f_word > 0.0 {
            words.push(NewWord::Number(Address::F, feed_number(m.f_word)));
            self.feed = Some(m.f_word);
        }
        if m.s_word > 0.0 && self.speed != Some(m.s_word) {
            words.push(NewWord::Number(Address::S, feed_number(m.s_word)));
            self.speed = Some(m.s_word);
        }
        NewBlock::new(words)
    }
}

/// A feed, speed or thread lead written with the digits it needs: up to eight decimals, as
/// an inch thread lead such as `F0.07692308` (13 threads per inch) needs.
fn feed_number(value: f64) -> Number {
    let mut scale = 0u8;
    while scale < 8 && ((value * 10f64.powi(scale as i32)).round() - value * 10f64.powi(scale as i32)).abs() > 1e-9 {
        scale += 1;
    }
    Number::new((value * 10f64.powi(scale as i32)).round() as i64, scale, true)
}
