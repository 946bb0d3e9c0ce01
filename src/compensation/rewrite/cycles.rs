//! Canned cycles whose motion changes: expanded into their compensated moves, unless their
//! profile can carry the correction in place (`profile_groups`, written by
//! `rewrite::MotionBlocks::write_profile`).
//!
//! A cycle call cannot carry a correction: the control computes its passes from the
//! call's words. A cycle none of whose moves changes stays as it is; any other is replaced
//! by explicit blocks, written by the back end from the compensated segments as `expand`
//! writes a cycle (`back::cycle_blocks`), and the blocks it consumed (its profile, the
//! first block of a two-block cycle) are deleted. Cycles that share consumed blocks are
//! expanded together: a finishing cycle
//! left as a call would need the profile the roughing cycle's expansion deletes, and a
//! profile left in place after an expanded call would run as plain moves.
//!
//! The call block's own words that are not the cycle's (its sequence name, comments, M
//! codes) go on the first written block, and a block-delete slash on every written block.
//! A consumed block with a comment leaves the comment behind.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::ops::{Range, RangeInclusive};

use crate::back::motion::Codes;
use crate::back::motion::{GivenNext, Restore};
use crate::back::thread_lead::{ProgrammedLead, WrittenLead, spelled, written_change, written_drift_mm, written_lead};
use crate::back::{Axes, CycleBlocks, carried_words, carry_traced, cycle_blocks};
use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::expand;
use crate::printer::{Edits, NewBlock, NewWord, ProgramStyle};
use crate::semantic::{Expansion, Lowered};
use crate::syntax::{CodeLetter, Program, WordId, WordKind};
use crate::toolpath::{Compensation, Motion, Move, Xz};

use super::super::fit::Segment;
use super::super::plan::{DepthAxis, KeptPlans, MovePlan};
use super::thread_pieces::{self, PieceSettings};

/// Whether the moves of `expansion` can be written back: on a control with no thread move
/// (OSP) a cycle's thread passes are written only as the cycle's own single-pass blocks,
/// which compensated passes are not.
pub fn expandable(program: &Program<'_>, lowered: &Lowered, expansion: &Expansion) -> bool {
    Codes::of(program).has_thread_move()
        || !lowered.toolpath.moves.get(expansion.moves.clone()).is_some_and(|moves| moves.iter().any(|m| m.threading))
}

/// The cycles to expand: those whose moves changed (every one with `all`), and those that
/// share blocks with one of them (a call block, or a consumed block). Indices into
/// `lowered.expansions`. A cycle to expand that shares blocks with one that cannot be
/// expanded is refused with an error in `diagnostics` (and not expanded). With them, each
/// cycle's group (the representative of the cycles that share blocks with it).
pub(super) fn chosen(
    program: &Program<'_>,
    lowered: &Lowered,
    plans: &KeptPlans,
    all: bool,
    diagnostics: &mut Vec<Diagnostic>,
) -> (Vec<bool>, Vec<usize>) {
    let expansions = &lowered.expansions;
    let expandable: Vec<bool> = expansions.iter().map(|e| expandable(program, lowered, e)).collect();
    let mut chosen: Vec<bool> = expansions
        .iter()
        .zip(&expandable)
        .map(|(e, &ok)| ok && (all || plans.get(e.moves.clone()).is_some_and(|p| p.iter().any(|p| p.changed))))
        .collect();
    // Cycles that share a block form a group (a roughing cycle, the finishing cycle on the
    // same profile): a group is expanded whole or not at all.
    let mut group: Vec<usize> = (0..expansions.len()).collect();
    let mut first_with: HashMap<usize, usize> = HashMap::new();
    for (k, e) in expansions.iter().enumerate() {
        // A finishing cycle's traced profile is the roughing cycle's even where neither
        // consumed it (a LAP contour written before its calls).
        for &block in std::iter::once(&e.block).chain(&e.consumed).chain(e.traced.iter().map(|(_, b)| b)) {
            match first_with.get(&block) {
                Some(&other) => {
                    let (a, b) = (root(&mut group, k), root(&mut group, other));
                    group[a] = b;
                }
                None => {
                    first_with.insert(block, k);
                }
            }
        }
    }
    let roots: Vec<usize> = (0..expansions.len()).map(|k| root(&mut group, k)).collect();
    let mut wanted: HashMap<usize, bool> = HashMap::new();
    let mut possible: HashMap<usize, bool> = HashMap::new();
    for k in 0..expansions.len() {
        *wanted.entry(roots[k]).or_default() |= chosen[k];
        *possible.entry(roots[k]).or_insert(true) &= expandable[k];
    }
    for k in 0..expansions.len() {
        let r = roots[k];
        let (want, can) = (wanted.get(&r).copied().unwrap_or(false), possible.get(&r).copied().unwrap_or(false));
        if want && !can && chosen[k] {
            diagnostics.push(Diagnostic::error(
                DiagnosticKind::CannotRewriteBlock {
                    reason: "its blocks are shared with a cycle whose passes cannot be written out",
                },
                program.block(expansions[k].block).span,
            ));
        }
        chosen[k] = want && can;
    }
    (chosen, roots)
}

/// A group of cycles chosen for expansion whose profile a finishing cycle of the group runs:
/// the group's cycles (indices into `lowered.expansions`), and each profile block with the
/// moves the finishing cycle makes for it.
pub(super) struct ProfileGroup {
    pub members: Vec<usize>,
    pub blocks: Vec<(usize, Range<usize>)>,
}

/// The groups of chosen cycles (`groups`, from `chosen`) that can stay calls with their
/// profile compensated in place: a finishing cycle of the group runs the profile, and the
/// moves that are the finishing cycle's own (its return to the start point) are rapids,
/// which cut nothing and are left as the control makes them. The roughing cycles of the
/// group are computed by the control from the profile, so their moves need no words of
/// their own.
pub(super) fn profile_groups(
    lowered: &Lowered,
    plans: &KeptPlans,
    chosen: &[bool],
    groups: &[usize],
) -> Vec<ProfileGroup> {
    let moves = &lowered.toolpath.moves;
    let mut by_root: BTreeMap<usize, ProfileGroup> = BTreeMap::new();
    let mut refused: HashSet<usize> = HashSet::new();
    for (k, e) in lowered.expansions.iter().enumerate() {
        if !chosen.get(k).copied().unwrap_or(false) {
            continue;
        }
        let root = groups.get(k).copied().unwrap_or(k);
        let group = by_root.entry(root).or_insert_with(|| ProfileGroup { members: Vec::new(), blocks: Vec::new() });
        group.members.push(k);
        if e.traced.is_empty() {
            continue;
        }
        let first = e.traced.first().map_or(e.moves.start, |&(m, _)| m);
        let end = e.traced_end.clamp(first, e.moves.end);
        // The cycle's own moves around the profile: rapids only, or they need writing.
        let own = (e.moves.start..first).chain(end..e.moves.end);
        let own_cut_changes = own.into_iter().any(|m| {
            let changed = plans.get(m..m + 1).is_none_or(|p| p.iter().any(|p| p.changed));
            changed && moves.get(m).is_none_or(|m| m.motion != Motion::Rapid)
        });
        if own_cut_changes {
            refused.insert(root);
            continue;
        }
        for (n, &(start, block)) in e.traced.iter().enumerate() {
            let next = e.traced.get(n + 1).map_or(end, |&(m, _)| m);
            group.blocks.push((block, start..next.max(start)));
        }
    }
    by_root
        .into_iter()
        .filter(|(root, group)| !refused.contains(root) && !group.blocks.is_empty())
        .map(|(_, group)| group)
        .collect()
}

/// The final pass of a thread cycle that can carry its correction in its own words: the
/// cycle cuts only threads between rapids, and its call block writes only words whose
/// meaning is the final pass's end (`final_pass_role`) or shapes the passes before it from
/// that end, besides the sequence name, codes and comments. The final pass is the last
/// thread move, which runs along the axis, or, where the pass is chamfered out of the
/// thread, the move along the axis before the chamfer (`end_words_offset` says where the
/// end words lie from its end); the passes before it move with it, as the control computes
/// them from these words.
pub(super) fn thread_final_pass(program: &Program<'_>, lowered: &Lowered, e: &Expansion) -> Option<usize> {
    use crate::dialect::Address;
    let moves = lowered.toolpath.moves.get(e.moves.clone())?;
    if !moves.iter().all(|m| m.threading || m.motion == Motion::Rapid) || !moves.iter().any(|m| m.threading) {
        return None;
    }
    let block = program.block(e.block);
    let command = match block.statement {
        crate::syntax::Statement::Cycle(id) => Some(program.command(id)),
        _ => None,
    };
    let words_fit = program.words_of(block).iter().zip(block.word_ids()).all(|(word, id)| match word.kind {
        WordKind::Number { address, .. } => match command {
            Some(command) => command.params.iter().find(|p| p.word == id).is_some_and(|p| final_pass_role(p.role)),
            // A modal repeat of the cycle (Fanuc's `G92` then `X` alone) writes its end, and
            // may write its start angle, which turns the spindle and moves nothing.
            None => {
                matches!(address, Address::X | Address::Z | Address::U | Address::W)
                    || program.config().tables().thread_move.start_angle == Some(address)
            }
        },
        WordKind::Expr { .. } => false,
        // A contour's name (`G88 N…`): the passes follow the contour, whose blocks, not the
        // call's words, place the final pass (`root_blocks`).
        WordKind::Label { .. } => false,
        _ => true,
    });
    if !words_fit {
        return None;
    }
    // The last thread move, which must run along the thread (along X for a face thread).
    let face = face_thread(program, block);
    let along_the_thread = |k: usize| {
        let (from, to) = (lowered.toolpath.start_of(k), lowered.toolpath.moves[k].end);
        let (along, across) = if face {
            ((to.x - from.x).abs(), (to.z - from.z).abs())
        } else {
            ((to.z - from.z).abs(), (to.x - from.x).abs())
        };
        along > 2.0 * across
    };
    let last = e.moves.start + moves.iter().rposition(|m| m.threading)?;
    if along_the_thread(last) {
        return Some(last);
    }
    // A chamfer out of the thread (Fanuc's `r` of `G76 P(m)(r)(a)`, OSP's `L` with `M23`):
    // the move before it runs along the thread to where the chamfer starts, and the end
    // words name the chamfer's end along the thread at that move's depth, a fixed step from
    // its end that moves with it.
    let before = last.checked_sub(1).filter(|&k| k >= e.moves.start)?;
    let threads = lowered.toolpath.moves.get(before).is_some_and(|m| m.threading);
    (threads && along_the_thread(before)).then_some(before)
}

/// Where a kept thread call's end words lie from the end of its final pass `pass`
/// (`thread_final_pass`): nowhere else where the pass runs along the thread to them; where
/// it is chamfered out, at the chamfer's end along the thread, at the pass's depth.
pub(super) fn end_words_offset(program: &Program<'_>, lowered: &Lowered, e: &Expansion, pass: usize) -> Xz {
    let moves = &lowered.toolpath.moves;
    let chamfer = (pass + 1 < e.moves.end).then(|| moves.get(pass + 1)).flatten().filter(|m| m.threading);
    let (Some(chamfer), Some(along)) = (chamfer, moves.get(pass)) else { return Xz::default() };
    if face_thread(program, program.block(e.block)) {
        Xz::new(chamfer.end.x - along.end.x, 0.0)
    } else {
        Xz::new(0.0, chamfer.end.z - along.end.z)
    }
}

/// A run of a Fanuc single turning (`G90`) or facing (`G94`) cycle whose words can carry its
/// cut's correction (`single_cut`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct SingleCut {
    /// The cut, the cycle's second move: along Z (along X when facing), from where the taper
    /// puts its start to the end the call's `X` and `Z` name.
    pub cut: usize,
    /// A facing cycle: its cut runs along X, its taper `R` along Z.
    pub facing: bool,
    /// A block that repeats the cycle (`X` or `Z` alone, Fanuc's modal single cycles): the
    /// axis it does not name and its taper, where it writes none, are the call's before it.
    pub repeat: bool,
    /// The block names `X` (or `U`), and `Z` (or `W`).
    pub names: (bool, bool),
    /// The block writes `X`, and `Z`, incrementally (`U`/`W`, or `X`/`Z` under `G91`):
    /// counted from the call's start point, where the tool stands before the call, and for
    /// a repeat, where the run before it started (the cycle returns there).
    pub incremental: (bool, bool),
    /// The taper the block writes (its `R`), as a count of the grid's lengths, and the place of
    /// that word among the block's words.
    pub taper: Option<(usize, i64)>,
}

/// The cut of a single turning or facing cycle's run `e` whose words can carry its
/// correction: the run is the cycle's four moves (a rapid to the cut's start, the cut, the
/// feed back out to the start point's diameter, or face, and the rapid to the start point),
/// and its block writes only end words (both axes, on a call), a taper `R`, the feed, speed
/// and tool, besides the sequence name, codes and comments. The end words name the cut's
/// end, absolute or counted from the start point (`U`/`W`, `G91`), and the taper its start
/// from that end, so both are the words'; the cut's start along the other axis is the
/// tool's position before the call, and the move back out ends at the start point, neither
/// of them words of the call.
pub(super) fn single_cut(program: &Program<'_>, lowered: &Lowered, e: &Expansion) -> Option<SingleCut> {
    use crate::dialect::{Address, AddressKind, GFunction, Role};
    // The approach and the move back out travel one axis, the same one: X when turning.
    let facing = match super::super::plan::single_cycle_axis(&lowered.toolpath, e.moves.start) {
        Some(DepthAxis::X) if e.moves.len() == 4 => false,
        Some(DepthAxis::Z) if e.moves.len() == 4 => true,
        _ => return None,
    };
    let mark = lowered.coordinates_at(e.moves.start + 1);
    let block = program.block(e.block);
    let command = match block.statement {
        crate::syntax::Statement::Cycle(id) => {
            let function = if facing { GFunction::FacingCycle } else { GFunction::TurningCycle };
            if cycle_function(program, block) != Some(function) {
                return None;
            }
            Some(program.command(id))
        }
        crate::syntax::Statement::Motion => None,
        _ => return None,
    };
    let (mut x, mut z, mut taper) = (false, false, None);
    let (mut x_incremental, mut z_incremental) = (!mark.absolute, !mark.absolute);
    for (k, (word, id)) in program.words_of(block).iter().zip(block.word_ids()).enumerate() {
        match word.kind {
            WordKind::Number { address, number } => {
                let role = match command {
                    Some(command) => command.params.iter().find(|p| p.word == id).map(|p| p.role)?,
                    // A modal repeat names its end, a taper and a feed by address, as
                    // `semantic::cycles::single` reads them.
                    None => match address {
                        Address::X => Role::EndX,
                        Address::Z => Role::EndZ,
                        Address::U => Role::IncrementalX,
                        Address::W => Role::IncrementalZ,
                        Address::R => Role::Taper,
                        Address::F => Role::Feed,
                        _ => return None,
                    },
                };
                match role {
                    Role::EndX => x = true,
                    Role::EndZ => z = true,
                    Role::IncrementalX => (x, x_incremental) = (true, true),
                    Role::IncrementalZ => (z, z_incremental) = (true, true),
                    Role::Taper => {
                        let tables = program.config().tables();
                        let kind = || tables.address(address).map(|s| s.kind).or(Some(AddressKind::Length));
                        taper = Some((k, crate::back::grid::Grid::new(&mark).literal_count(number, kind)));
                    }
                    Role::Feed | Role::Speed | Role::Tool => {}
                    _ => return None,
                }
            }
            WordKind::Expr { .. } | WordKind::Label { .. } => return None,
            _ => {}
        }
    }
    let named = if command.is_some() { x && z } else { x || z };
    named.then_some(SingleCut {
        cut: e.moves.start + 1,
        facing,
        repeat: command.is_none(),
        names: (x, z),
        incremental: (x_incremental, z_incremental),
        taper,
    })
}

/// A Fanuc groove on a diameter (`G75`) whose end words can carry the correction of its
/// bottoms (`groove`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Groove {
    /// The feed that reaches each plunge's bottom (its last feed), in the order the plunges
    /// run: one for a groove of one plunge, the last the plunge at the end `Z` (the groove's
    /// far wall) for a wide groove.
    pub bottoms: Vec<usize>,
}

/// The plunges' bottoms of a `G75` call `e` whose words can carry their correction: its
/// block writes only end words (`X` or `U` the bottom, `Z`/`W` the last plunge's place),
/// the peck, step and relief, and the feed, besides the sequence name, codes and comments,
/// and every feed runs along X. The pecks of a plunge count from the start point's X and
/// stop at the bottom, so only the last reaches it, and it ends where `X` (or `U`) says.
/// The first plunge runs at the start point's Z, which the move before the call places;
/// the others step by `Q` from there, the last at the end `Z` (or `W`) whatever `Q`
/// (`semantic/cycles/peck_grooving.rs`). The one `X` writes every plunge's bottom, so it
/// carries their correction only where their plans agree on it (`keep_groove` asks).
pub(super) fn groove(program: &Program<'_>, lowered: &Lowered, e: &Expansion) -> Option<Groove> {
    use crate::dialect::{GFunction, Role};
    let block = program.block(e.block);
    let crate::syntax::Statement::Cycle(id) = block.statement else { return None };
    if cycle_function(program, block) != Some(GFunction::DiameterGrooving) {
        return None;
    }
    let command = program.command(id);
    let mut x = false;
    for (word, id) in program.words_of(block).iter().zip(block.word_ids()) {
        match word.kind {
            WordKind::Number { .. } => match command.params.iter().find(|p| p.word == id)?.role {
                Role::EndX | Role::IncrementalX => x = true,
                Role::EndZ
                | Role::IncrementalZ
                | Role::PeckDepth
                | Role::StepZ
                | Role::BottomRelief
                | Role::Feed
                | Role::Speed
                | Role::Tool => {}
                _ => return None,
            },
            WordKind::Expr { .. } | WordKind::Label { .. } => return None,
            _ => {}
        }
    }
    let toolpath = &lowered.toolpath;
    let moves = toolpath.moves.get(e.moves.clone())?;
    let start = toolpath.start_of(e.moves.start);
    // Every feed runs along X, at one plunge's Z.
    let along_x = |k: usize, m: &Move| {
        let from = super::super::written::contour_start(toolpath, k);
        m.compensation == Compensation::Off && from.z == m.contour.z
    };
    let mut bottoms: Vec<usize> = Vec::new();
    // The last feed seen, and its plunge's Z.
    let mut last: Option<(usize, f64)> = None;
    for (k, m) in (e.moves.start..).zip(moves) {
        if m.threading || m.is_arc() {
            return None;
        }
        if m.motion == Motion::Feed {
            if !along_x(k, m) {
                return None;
            }
            if let Some((bottom, z)) = last
                && z != m.contour.z
            {
                bottoms.push(bottom);
            }
            last = Some((k, m.contour.z));
        }
    }
    let (bottom, _) = last?;
    bottoms.push(bottom);
    // The first plunge runs at the start point's Z.
    let first = moves.get(bottoms.first()? - e.moves.start)?;
    (x && first.contour.z == start.z).then_some(Groove { bottoms })
}

/// Whether a thread cycle's word of `role` leaves its end words naming the final pass's end
/// (grammar/*.toml, the thread cycles' schemas), so that they carry its correction:
///
/// - the end (`X`/`Z`, Fanuc's `U`/`W`) is the final pass's;
/// - the lead (`F`, Fanuc's `E`) is the thread's, written with the lead correction;
/// - the height, first depth, minimum depth, finishing allowance, infeed angle, mode and
///   pattern, and the tool angle (Fanuc's `G76` `P`/`Q`/`R` or Haas's `K`/`D`/`A`/`P`;
///   OSP's `H`/`D`/`U`/`W`/`B`) place the passes before the last from the final pass;
/// - a taper (Fanuc's `R`, Haas's `I`, OSP's `I`/`K`/`A`) places each pass's start from its
///   end, and a start shift (OSP's single-pass `K`/`I`) from the tool's position, which the
///   rapid before the cycle carries along the thread: both move with the end words;
/// - the number of starts and a start's angle or phase turn the spindle and move nothing;
/// - the speed and the tool select, and move nothing;
/// - a chamfer out of the thread (OSP's `L`) ends each pass a fixed step from where it
///   leaves the thread (`end_words_offset`);
/// - a count of threads (OSP's `J`, with which `F` is the length of that many) is the lead
///   word's, which `thread_lead` writes with it (as it writes a lead the slide needs as
///   `F` over `J`);
/// - a lead change every turn (OSP's `E` of `G34`/`G35` and the compound cycles) is the
///   lead's, which `thread_lead` scales with it.
fn final_pass_role(role: crate::dialect::Role) -> bool {
    use crate::dialect::Role;
    matches!(
        role,
        Role::EndX
            | Role::EndZ
            | Role::IncrementalX
            | Role::IncrementalZ
            | Role::Lead
            | Role::ThreadHeight
            | Role::FirstDepth
            | Role::MinDepth
            | Role::ThreadParameters
            | Role::FinishAllowance
            | Role::InfeedAngle
            | Role::InfeedMode
            | Role::InfeedPattern
            | Role::ToolAngle
            | Role::Taper
            | Role::TaperAngle
            | Role::StartShift
            | Role::Starts
            | Role::ShiftAngle
            | Role::Phase
            | Role::Speed
            | Role::Tool
            | Role::Chamfer
            | Role::ThreadsPerInch
            | Role::LeadChange
    )
}

/// Whether `block` calls a face thread cycle (OSP's `G72` and `G32`), whose thread runs along
/// X: its `X` names where the thread ends and its `Z` the final pass's depth.
pub(super) fn face_thread(program: &Program<'_>, block: &crate::syntax::Block) -> bool {
    use crate::dialect::GFunction;
    matches!(cycle_function(program, block), Some(GFunction::CompoundThreadFace | GFunction::ThreadSingleFace))
}

/// The function of the cycle `block` calls, from the dialect's tables.
fn cycle_function(program: &Program<'_>, block: &crate::syntax::Block) -> Option<crate::dialect::GFunction> {
    let crate::syntax::Statement::Cycle(id) = block.statement else { return None };
    let WordKind::Code { code, .. } = program.word(program.command(id).code_word).kind else { return None };
    program.config().tables().g(code).and_then(|g| g.function)
}

/// The contour blocks of a LAP continuous thread (`Expansion::root`), each with the move its
/// final pass makes for it: they carry that pass's correction word by word, as a finishing
/// cycle's profile blocks do, and the control offsets the passes before it from them.
pub(super) fn root_blocks(e: &Expansion) -> Vec<(usize, Range<usize>)> {
    e.root.iter().map(|&(m, block)| (block, m..m + 1)).collect()
}

/// The block `call` (a LAP continuous thread's) with its lead word written as `lead`'s
/// words, every other word as written.
pub(super) fn with_lead(program: &Program<'_>, call: usize, lead: &LeadWords) -> NewBlock {
    let block = program.block(call);
    let mut words = Vec::new();
    for k in 0..program.words_of(block).len() {
        if k == lead.at {
            words.extend(lead.words.iter().map(|&(address, number)| NewWord::Number(address, number)));
        } else if let Some((_, value)) = lead.change.filter(|&(at, _)| at == k)
            && let WordKind::Number { address, .. } = program.word(block.first_word + k as u32).kind
        {
            words.push(NewWord::Number(address, value));
        } else {
            words.push(NewWord::Copy(block.first_word + k as u32));
        }
    }
    NewBlock::new(words)
}

/// Whether after the Fanuc roughing call at `call` the program goes on after its `Q` block
/// (`Interpreter::after_profile`): `Q` names exactly one block, and it comes after the call.
fn jumps_past_q(program: &Program<'_>, call: usize) -> bool {
    let block = program.block(call);
    let crate::syntax::Statement::Cycle(id) = block.statement else { return false };
    let Some(word) = program.command(id).param(crate::dialect::Role::ProfileEnd) else { return false };
    let WordKind::Number { number, .. } = program.word(word).kind else { return false };
    let q = number.to_f64();
    let named: Vec<usize> = program
        .blocks()
        .iter()
        .enumerate()
        .filter(|(_, b)| {
            program
                .sequence(b)
                .is_some_and(|w| matches!(w.kind, WordKind::Sequence { number: Some(n) } if f64::from(n) == q))
        })
        .map(|(k, _)| k)
        .collect();
    matches!(named.as_slice(), [one] if *one > call)
}

/// The representative of `k`'s group (with path halving).
fn root(group: &mut [usize], mut k: usize) -> usize {
    while group[k] != k {
        group[k] = group[group[k]];
        k = group[k];
    }
    k
}

/// The compensated moves of a cycle, as the back end's cycle writer takes them: one move per
/// segment, in the contour frame, and the index of the first of each move's. A take-up of
/// the play before a move that switches compensation is a rapid under the compensation in
/// force before it.
fn compensated_moves(moves: &[Move], plans: &[MovePlan], compensation_before: Compensation) -> (Vec<Move>, Vec<usize>) {
    let mut out = Vec::with_capacity(moves.len());
    let mut firsts = Vec::with_capacity(moves.len());
    let mut compensation = compensation_before;
    for (m, plan) in moves.iter().zip(plans) {
        firsts.push(out.len());
        if m.motion == Motion::Dwell {
            out.push(*m);
            continue;
        }
        for (k, segment) in plan.segments.iter().enumerate() {
            let (motion, centre) = match *segment {
                Segment::Line { .. } if m.motion == Motion::Rapid || (plan.lead_in && k == 0) => {
                    (Motion::Rapid, Xz::new(f64::NAN, f64::NAN))
                }
                Segment::Line { .. } => (Motion::Feed, Xz::new(f64::NAN, f64::NAN)),
                Segment::Arc { centre, ccw, .. } => (if ccw { Motion::Ccw } else { Motion::Cw }, centre),
            };
            let compensation = if plan.lead_in && k == 0 { compensation } else { m.compensation };
            out.push(Move { motion, centre, compensation, contour: segment.end(), end: segment.end(), ..*m });
        }
        compensation = m.compensation;
    }
    (out, firsts)
}

/// A written cycle whose last block only puts back modal words, which the block the control
/// runs after the call may carry instead (`MotionBlocks::fold`).
pub(super) struct CycleRestore {
    pub call: usize,
    /// The block the control runs after the call, and its first move.
    pub next: Option<usize>,
    pub next_move: usize,
    pub restore: Restore,
}

/// Write the chosen cycles into `edits`; problems go to `diagnostics`.
/// With the written call blocks, the lead changes of those whose thread moves are written
/// with a corrected lead (`expanded_leads`), by call block, and the cycles whose last block
/// only puts back modal words.
pub(super) fn write(
    program: &Program<'_>,
    lowered: &Lowered,
    (plans, model, pieces): (&KeptPlans, &crate::error_model::ErrorModel, Option<PieceSettings<'_>>),
    chosen: &[bool],
    style: &ProgramStyle,
    edits: &mut Edits,
    diagnostics: &mut Vec<Diagnostic>,
) -> (Vec<usize>, HashMap<usize, LeadChange>, Vec<CycleRestore>) {
    let calls: HashSet<usize> = lowered.expansions.iter().map(|e| e.block).collect();
    // The profile blocks whose words a written cycle carries (`back::carry_traced`).
    let traced: HashSet<usize> = lowered
        .expansions
        .iter()
        .zip(chosen)
        .filter(|(_, chosen)| **chosen)
        .flat_map(|(e, _)| e.traced.iter().map(|&(_, block)| block))
        .collect();
    // A call block that runs more than once (a cycle in a subprogram) must come out the
    // same every time.
    let mut by_block: BTreeMap<usize, Vec<NewBlock>> = BTreeMap::new();
    let mut refused = HashSet::new();
    let mut written = Vec::new();
    let mut lead_changes = HashMap::new();
    let mut restores = Vec::new();
    for (expansion, _) in lowered.expansions.iter().zip(chosen).filter(|(_, chosen)| **chosen) {
        let range = expansion.moves.clone();
        let (Some(moves), Some(cycle_plans)) = (lowered.toolpath.moves.get(range.clone()), plans.get(range.clone()))
        else {
            continue;
        };
        let start = cycle_plans.first().map_or(lowered.toolpath.start, |p| p.start);
        let compensation_before = range
            .start
            .checked_sub(1)
            .and_then(|k| lowered.toolpath.moves.get(k))
            .map_or(Compensation::Off, |m| m.compensation);
        let shift = lowered.coordinates_at(range.start).shift;
        // A finishing pass whose lead error is not uniform along it runs as thread blocks of
        // their own leads (`thread_pieces`).
        let mut own_plans = None;
        let mut piece_leads: HashMap<usize, Vec<WrittenLead>> = HashMap::new();
        let table = program.config().tables().thread_lead;
        for (k, m) in range.clone().zip(moves).filter(|(_, m)| m.threading) {
            let Some(settings) = pieces else { break };
            let grid = crate::back::grid::Grid::new(&lowered.coordinates_at(k));
            let programmed = ProgrammedLead { address: crate::dialect::Address::F, written: m.f_word, count: None };
            let Some(plan) = cycle_plans.get(k - range.start) else { continue };
            if let Some(cut) = thread_pieces::pieces(&lowered.toolpath, (k, plan), settings, &table, &grid, programmed)
            {
                own_plans.get_or_insert_with(|| cycle_plans.to_vec())[k - range.start] = cut.plan;
                piece_leads.insert(k, cut.leads);
            } else if k > range.start && piece_leads.contains_key(&(k - 1)) {
                // A thread move after pieces (a chamfer out of the thread) goes on from where
                // the last piece meets the helix: its lead takes the spindle through the
                // turns of the programmed move over the move written.
                let nominal = lowered.toolpath.start_of(k).distance(m.end);
                let written = plan.start.distance(plan.end());
                let lead = (nominal > 0.0)
                    .then(|| written_lead(&table, &grid, programmed, m.f_word * written / nominal, written))
                    .flatten();
                if let Some(lead) = lead {
                    piece_leads.insert(k, vec![lead]);
                }
            }
        }
        let cycle_plans = own_plans.as_deref().unwrap_or(cycle_plans);
        let (compensated, firsts) = compensated_moves(moves, cycle_plans, compensation_before);
        let (leads, lead_change) =
            expanded_leads(program, lowered, expansion, (&firsts, compensated.len()), model, &piece_leads);
        let blocks = match cycle_blocks(
            program,
            expansion,
            (&compensated, &leads),
            (start, Axes::Every),
            compensation_before,
            shift,
            style,
        ) {
            CycleBlocks::Blocks(mut blocks, restore) => {
                if let Some(restore) = restore {
                    let next = GivenNext::next_block(program, expansion.block, |b| expansion.consumed.contains(&b));
                    restores.push(CycleRestore { call: expansion.block, next, next_move: range.end, restore });
                }
                let at = |m: usize| firsts.get(m - range.start).copied().unwrap_or(compensated.len());
                carry_traced(
                    program,
                    &mut blocks,
                    compensated.len(),
                    expansion.traced.iter().map(|&(m, b)| (at(m), b)),
                );
                with_call_words(program, expansion.block, blocks)
            }
            CycleBlocks::Keep | CycleBlocks::NotExpandable(_)
                if expansion.moves.clone().any(|k| lowered.toolpath.moves.get(k).is_some_and(|m| m.threading)) =>
            {
                let span = program.block(expansion.block).span;
                let reason = super::THREAD_WORDS_NOT_FINAL;
                diagnostics.push(Diagnostic::warning(DiagnosticKind::CycleNotCompensated { reason }, span));
                continue;
            }
            CycleBlocks::Keep => continue,
            CycleBlocks::NotExpandable(reason) => {
                let span = program.block(expansion.block).span;
                diagnostics.push(Diagnostic::warning(DiagnosticKind::CycleNotCompensated { reason }, span));
                continue;
            }
        };
        match by_block.get(&expansion.block) {
            Some(previous) if *previous != blocks => {
                if refused.insert(expansion.block) {
                    let span = program.block(expansion.block).span;
                    diagnostics.push(Diagnostic::error(
                        DiagnosticKind::CannotRewriteBlock {
                            reason: "the cycle runs more than once with different corrections",
                        },
                        span,
                    ));
                }
            }
            Some(_) => {}
            None => {
                by_block.insert(expansion.block, blocks);
                written.push(expansion.block);
                if let Some(change) = lead_change {
                    lead_changes.insert(expansion.block, change);
                }
                delete_consumed(program, expansion, (&calls, &traced), edits, diagnostics);
            }
        }
    }
    for (block, blocks) in by_block {
        edits.replace(block, blocks);
    }
    // A call that runs more than once has one restore for each run; the block after it runs
    // as often, and carries none (`MotionBlocks::fold`).
    (written, lead_changes, restores)
}

/// The leads the thread moves of a cycle written out take for the slide to cut the
/// programmed lead on `model`, per compensated move (`firsts`: the first compensated move of
/// each of the cycle's moves, of `count` in all), and the change of the final pass's lead
/// for the report; `None` for a move whose lead stays as the move gives it. Each pass's lead
/// is its first thread move's (`lead_ratio`, written by `back::thread_lead` as a kept cycle's
/// is, the programmed lead the move's F); the thread moves after it in the pass (a chamfer
/// out) go on with it, as the pass cuts one helix.
fn expanded_leads(
    program: &Program<'_>,
    lowered: &Lowered,
    expansion: &Expansion,
    (firsts, count): (&[usize], usize),
    model: &crate::error_model::ErrorModel,
    pieces: &HashMap<usize, Vec<WrittenLead>>,
) -> (Vec<Option<WrittenLead>>, Option<LeadChange>) {
    let table = program.config().tables().thread_lead;
    let range = expansion.moves.clone();
    let mut leads: Vec<Option<WrittenLead>> = vec![None; count];
    let mut pass: Option<WrittenLead> = None;
    let mut last: Option<(f64, WrittenLead)> = None;
    let mut last_pieces: Option<(f64, &[WrittenLead])> = None;
    for k in range.clone() {
        let Some(m) = lowered.toolpath.moves.get(k) else { break };
        if !m.threading {
            pass = None;
            continue;
        }
        let offset = k - range.start;
        let begins_pass = k == range.start || lowered.toolpath.moves.get(k - 1).is_some_and(|before| !before.threading);
        if let Some(cut) = pieces.get(&k) {
            // One lead per piece (a chamfer out after pieces has one of its own); the thread
            // moves after it in the pass go on with the last.
            let first = firsts.get(offset).copied().unwrap_or(count);
            for (slot, lead) in leads.iter_mut().skip(first).zip(cut) {
                *slot = Some(lead.clone());
            }
            pass = cut.last().cloned();
            if begins_pass {
                last_pieces = Some((m.f_word, cut));
            }
            continue;
        }
        if begins_pass {
            let grid = crate::back::grid::Grid::new(&lowered.coordinates_at(k));
            let programmed = ProgrammedLead { address: crate::dialect::Address::F, written: m.f_word, count: None };
            let thread_mm = lowered.toolpath.start_of(k).distance(m.end);
            pass = lead_ratio(lowered, k..=k, model)
                .and_then(|ratio| written_lead(&table, &grid, programmed, m.f_word * ratio, thread_mm))
                .filter(|lead| lead.lead != m.f_word || lead.unheld_mm.is_some());
            last = pass.clone().map(|lead| (m.f_word, lead));
        }
        let end = firsts.get(offset + 1).copied().unwrap_or(count);
        for slot in leads.iter_mut().take(end).skip(firsts.get(offset).copied().unwrap_or(count)) {
            slot.clone_from(&pass);
        }
    }
    let from = |old: f64| {
        let from = match program.block(expansion.block).statement {
            crate::syntax::Statement::Cycle(id) | crate::syntax::Statement::LapCall(id) => {
                program.command(id).param(crate::dialect::Role::Lead)
            }
            _ => None,
        };
        match from {
            Some(id) => String::from_utf8_lossy(program.text(program.word(id).span)).into_owned(),
            None => spelled(&[(crate::dialect::Address::F, crate::back::motion::feed_number(old))]),
        }
    };
    // The final pass's lead: its pieces' where it is cut into pieces.
    let change = match last_pieces {
        Some((old, cut)) => LeadChange::of_pieces(from(old), old, cut),
        None => last.map(|(old, lead)| LeadChange {
            from: from(old),
            to: spelled(&lead.words),
            change_ppm: ppm(lead.lead, old),
            unheld_mm: lead.unheld_mm,
            pieces: None,
        }),
    };
    (leads, change)
}

/// The change of `lead` against `old`, parts per million to a tenth.
fn ppm(lead: f64, old: f64) -> f64 {
    ((lead / old - 1.0) * 1e6 * 10.0).round() / 10.0
}

/// The call block's sequence name, comments and M codes on the first written block, and
/// its block-delete slash on every one.
fn with_call_words(program: &Program<'_>, call: usize, mut blocks: Vec<NewBlock>) -> Vec<NewBlock> {
    let block = program.block(call);
    let mut leading = Vec::new();
    let mut trailing = Vec::new();
    let mut slash = None;
    for (k, word) in program.words_of(block).iter().enumerate() {
        let id = block.first_word + k as u32;
        match word.kind {
            WordKind::BlockDelete { .. } => slash = Some(id),
            WordKind::Sequence { .. } => leading.push(NewWord::Copy(id)),
            WordKind::Comment(_) | WordKind::Code { letter: CodeLetter::M, .. } => trailing.push(NewWord::Copy(id)),
            _ => {}
        }
    }
    if let Some(first) = blocks.first_mut() {
        leading.append(&mut first.words);
        leading.append(&mut trailing);
        first.words = leading;
    }
    if let Some(slash) = slash {
        for b in &mut blocks {
            b.words.insert(0, NewWord::Copy(slash));
        }
    }
    blocks
}

/// Delete the blocks a cycle consumed (not another cycle's call, `calls`), keeping every
/// word of theirs that runs: the cycle's first block ran where it is (`Expansion::setup`),
/// so its M codes, T words and comments stay there; a profile block's words go with the
/// written cycle that runs it (`traced`, `back::carry_traced`). A profile block no written
/// cycle runs keeps its comments where it was; its M codes and T words, which only a
/// finishing cycle runs, have no block to go on: the cycle is refused (an error in
/// `diagnostics` on the block), as `verify` would find them lost.
fn delete_consumed(
    program: &Program<'_>,
    expansion: &Expansion,
    (calls, traced): (&HashSet<usize>, &HashSet<usize>),
    edits: &mut Edits,
    diagnostics: &mut Vec<Diagnostic>,
) {
    let mut plain = Edits::new();
    expand::delete_consumed(&mut plain, program, expansion, calls);
    for &consumed in &expansion.consumed {
        if !plain.touches(consumed) {
            continue;
        }
        let mut words = carried_words(program, consumed);
        let kept = if expansion.setup == Some(consumed) {
            words
        } else if traced.contains(&consumed) {
            Vec::new()
        } else {
            let comment = |word: &NewWord| matches!(word, NewWord::Copy(id) if matches!(program.word(*id).kind, WordKind::Comment(_)));
            if let Some(&NewWord::Copy(id)) = words.iter().find(|word| !comment(word)) {
                let span = program.word(id).span;
                let word = String::from_utf8_lossy(program.text(span)).into_owned();
                diagnostics.push(Diagnostic::error(DiagnosticKind::ProfileWordNotRun { word }, span));
            }
            words.retain(comment);
            words
        };
        if kept.is_empty() {
            edits.delete(consumed);
        } else {
            edits.replace(consumed, vec![NewBlock::new(kept)]);
        }
    }
}

/// A finishing cycle's own compensated copy of the profile it shares with a roughing cycle
/// (`profile_copy`): the blocks to write after a call, and the finishing call written again
/// naming them.
pub(super) struct ProfileCopy {
    /// The roughing call, which stays on the profile as written.
    pub rough: usize,
    /// The call the copy goes right after.
    pub after: usize,
    /// The finishing call, which names the copy.
    pub finish: usize,
    pub blocks: Vec<NewBlock>,
    pub call: NewBlock,
    /// The copy's first and last sequence names.
    pub names: (String, String),
}

/// The copy of the profile of `group` that its finishing cycle runs, compensated, where the
/// roughing cycle is to stay on the profile as written (the compensated profile would break
/// a rule of the roughing cycle, or cannot carry the correction block for block); why not,
/// where it cannot be written. The copy is the finishing pass's compensated moves written as
/// a cycle's blocks are (`back::cycle_blocks`), the profile blocks' M codes, T words and
/// comments on the blocks of their moves, under names the program does not use.
///
/// * **Fanuc**: the finishing call finds its profile by searching the program for the
///   sequence numbers its `P` and `Q` name (`semantic::cycles::finishing`), and after a
///   roughing call whose profile follows it the program goes on after the `Q` block, so the
///   blocks between the call and the profile never run as plain blocks
///   (`Interpreter::consume_skipped`): the copy goes there, numbered at its first and last
///   block, and only the finishing call's `P` and `Q` change.
/// * **OSP**: a finishing call followed by its own contour (`G87 N0808` then `N0808 G81` …
///   `G80`, as the real program OSP7000L writes each of its finishing calls) runs it and goes
///   on after its `G80` (`semantic::cycles::lap_contour`): the copy goes right after the
///   finishing call between the contour's own `G81`/`G82` and `G80` words, under a new name
///   that only the call's name word changes to.
pub(super) fn profile_copy(
    program: &Program<'_>,
    lowered: &Lowered,
    plans: &KeptPlans,
    group: &ProfileGroup,
    style: &ProgramStyle,
) -> Result<ProfileCopy, &'static str> {
    use crate::dialect::{Address, Dialect, Role};
    use crate::syntax::{Number, Statement};
    let osp = program.config().dialect == Dialect::Osp;
    let expansions = &lowered.expansions;
    let (finishing, roughing): (Vec<usize>, Vec<usize>) =
        group.members.iter().partition(|&&k| expansions.get(k).is_some_and(|e| !e.traced.is_empty()));
    let ([finish], [rough]) = (finishing.as_slice(), roughing.as_slice()) else {
        return Err("its profile is shared by other than one roughing and one finishing cycle");
    };
    let (Some(finish), Some(rough)) = (expansions.get(*finish), expansions.get(*rough)) else {
        return Err("its cycles are not found");
    };
    let profile_first = finish.traced.iter().map(|&(_, b)| b).min().unwrap_or(0);
    let profile_last = finish.traced.iter().map(|&(_, b)| b).max().unwrap_or(0);
    if !osp && (profile_first <= rough.block || !jumps_past_q(program, rough.block)) {
        return Err("the program does not go on after the profile from the roughing call (the profile comes before \
                    the call, or its Q names no single block), so no block after the call is skipped to hold a copy");
    }
    // The words of the finishing call that name its profile, to be written again: `P` and
    // `Q` numbers, or the contour's name.
    let call = program.block(finish.block);
    let command = match call.statement {
        Statement::Cycle(id) | Statement::LapCall(id) => Some(program.command(id)),
        _ => None,
    };
    let role_word = |role| {
        command.and_then(|c| c.param(role)).filter(|&id| match program.word(id).kind {
            WordKind::Number { address: Address::P | Address::Q, .. } => !osp,
            WordKind::Label { .. } => osp,
            _ => false,
        })
    };
    let naming: Vec<WordId> = if osp {
        role_word(Role::ContourName).into_iter().collect()
    } else {
        role_word(Role::ProfileStart).into_iter().chain(role_word(Role::ProfileEnd)).collect()
    };
    if naming.len() != if osp { 1 } else { 2 } {
        return Err("the finishing call does not name its profile by plain words that can be written again");
    }
    // An OSP contour's own first and last blocks (`G81`/`G82`, `G80`), whose words other
    // than their names the copy writes again.
    let marker = |block: usize| matches!(program.block(block).statement, Statement::LapMarker(_));
    let markers = if osp {
        let open = (0..profile_first).rev().find(|&b| marker(b));
        let close = (profile_last + 1..program.blocks().len()).find(|&b| marker(b));
        match (open, close) {
            (Some(open), Some(close)) => Some((open, close)),
            _ => return Err("the contour's G81/G82 and G80 blocks are not found"),
        }
    } else {
        None
    };
    let first = finish.traced.first().map_or(finish.moves.start, |&(m, _)| m);
    let end = finish.traced_end.clamp(first, finish.moves.end);
    let (Some(moves), Some(copy_plans)) = (lowered.toolpath.moves.get(first..end), plans.get(first..end)) else {
        return Err("its finishing pass was not planned");
    };
    let start = copy_plans.first().map_or(lowered.toolpath.start, |p| p.start);
    let compensation_before =
        first.checked_sub(1).and_then(|k| lowered.toolpath.moves.get(k)).map_or(Compensation::Off, |m| m.compensation);
    let shift = lowered.coordinates_at(first).shift;
    let (compensated, firsts) = compensated_moves(moves, copy_plans, compensation_before);
    // The copy names only the axes each move travels, as its profile does.
    let from = (start, Axes::Travelled);
    let mut blocks = match cycle_blocks(program, finish, (&compensated, &[]), from, compensation_before, shift, style) {
        CycleBlocks::Blocks(blocks, _) if !blocks.is_empty() => blocks,
        _ => return Err("its finishing pass has no plain-block form"),
    };
    let at = |m: usize| firsts.get(m - first).copied().unwrap_or(compensated.len());
    carry_traced(program, &mut blocks, compensated.len(), finish.traced.iter().map(|&(m, b)| (at(m), b)));
    // Names the program does not use: numbers above its largest, in steps of ten (at least
    // four digits on OSP, whose names are text: `N0220` and `N220` name different blocks).
    let largest = program
        .blocks()
        .iter()
        .flat_map(|b| program.words_of(b))
        .filter_map(|w| match w.kind {
            WordKind::Sequence { number } | WordKind::Label { number } => number,
            _ => None,
        })
        .max()
        .unwrap_or(0);
    let mut p = (u64::from(largest) / 10 + 1) * 10;
    if osp {
        p = p.max(1000);
    }
    let q = if blocks.len() > 1 && !osp { p + 10 } else { p };
    let digits = program.config().tables().lexical.sequence_max;
    let max = 10u64.saturating_pow(u32::try_from(digits).unwrap_or(u32::MAX)) - 1;
    if q > max {
        return Err("no free sequence numbers are left above the program's largest for the copy");
    }
    let unnamed = |block: usize| -> Vec<NewWord> {
        let b = program.block(block);
        (0..program.words_of(b).len() as u32)
            .map(|k| b.first_word + k)
            .filter(|&id| !matches!(program.word(id).kind, WordKind::Sequence { .. }))
            .map(NewWord::Copy)
            .collect()
    };
    let names = if let Some((open, close)) = markers {
        let name = format!("N{p}");
        blocks.insert(0, NewBlock { sequence: Some(name.clone()), words: unnamed(open) });
        blocks.push(NewBlock::new(unnamed(close)));
        (name.clone(), name)
    } else {
        let names = (format!("N{p}"), format!("N{q}"));
        if let Some(b) = blocks.first_mut() {
            b.sequence = Some(names.0.clone());
        }
        if let Some(b) = blocks.last_mut() {
            b.sequence = Some(names.1.clone());
        }
        names
    };
    let number = |n: u64| Number::new(n as i64, 0, false);
    let call_words = (0..program.words_of(call).len() as u32)
        .map(|k| call.first_word + k)
        .map(|id| match naming.iter().position(|&w| w == id) {
            Some(0) if osp => NewWord::Number(Address::N, number(p)),
            Some(0) => NewWord::Number(Address::P, number(p)),
            Some(_) => NewWord::Number(Address::Q, number(q)),
            None => NewWord::Copy(id),
        })
        .collect();
    let after = if osp { finish.block } else { rough.block };
    Ok(ProfileCopy { rough: rough.block, after, finish: finish.block, blocks, call: NewBlock::new(call_words), names })
}

/// The lead words a kept thread cycle is written with: the block's lead word (its place
/// among the block's words) replaced by `words` (the lead word again, a precise-lead word
/// instead, or the lead word and a count of threads after it).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LeadWords {
    pub at: usize,
    pub words: smallvec::SmallVec<[(crate::dialect::Address, crate::syntax::Number); 2]>,
    /// A variable lead's change word (`E` of OSP `G34`/`G35`, `K` of Fanuc `G34`), where it
    /// changes: its place among the block's words and its new value.
    pub change: Option<(usize, crate::syntax::Number)>,
}

/// A thread cycle's lead as written and as compensation writes it.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LeadChange {
    /// The lead words as the block writes them (`F2.`, `F1.5`) and as they are written now
    /// (`E1.9998`, `F29.997 J20`).
    pub from: String,
    pub to: String,
    /// The lead the words give now against the one they gave, parts per million.
    pub change_ppm: f64,
    /// Where no word of the dialect holds the lead the slide needs: how far the lead written
    /// runs from it over the thread, mm (`back::thread_lead`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unheld_mm: Option<f64>,
    /// Where the lead error is not uniform along the final pass: how many consecutive thread
    /// blocks it is written as, each with its own lead (`thread_pieces`); `to` then gives the
    /// least and the largest of their leads, and `change_ppm` the change farthest from none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pieces: Option<usize>,
}

impl LeadChange {
    /// The change of a pass written as the pieces `cut` (leads), from the lead word `from`
    /// that gives `old`; `None` for no pieces.
    pub(super) fn of_pieces(from: String, old: f64, cut: &[WrittenLead]) -> Option<LeadChange> {
        let least = cut.iter().min_by(|a, b| a.lead.total_cmp(&b.lead))?;
        let largest = cut.iter().max_by(|a, b| a.lead.total_cmp(&b.lead))?;
        let farthest = if (largest.lead - old).abs() > (least.lead - old).abs() { largest } else { least };
        let unheld = cut
            .iter()
            .filter_map(|lead| lead.unheld_mm)
            .fold(None, |most: Option<f64>, mm| Some(most.map_or(mm, |m| m.max(mm))));
        Some(LeadChange {
            from,
            to: format!("{}…{}", spelled(&least.words), spelled(&largest.words)),
            change_ppm: ppm(farthest.lead, old),
            unheld_mm: unheld,
            pieces: Some(cut.len()),
        })
    }
}

/// The lead word of the thread move `block` (`G32`): its own `F` or precise-lead word, its
/// place among the block's words and the lead it writes; `None` where the block writes none
/// (it runs at the lead written before it) or writes it as other than a plain number.
pub(super) fn thread_move_lead(program: &Program<'_>, block: usize) -> Option<(usize, ProgrammedLead)> {
    use crate::dialect::Address;
    let block = program.block(block);
    if block.statement != crate::syntax::Statement::ThreadMove {
        return None;
    }
    let precise = program.config().tables().thread_lead.precise.map(|p| p.address);
    let id = block.word_ids().find(|&w| {
        matches!(program.word(w).kind, WordKind::Number { address, .. }
            if address == Address::F || Some(address) == precise)
    })?;
    let WordKind::Number { address, number } = program.word(id).kind else { return None };
    let at = usize::try_from(id.checked_sub(block.first_word)?).ok()?;
    Some((at, ProgrammedLead { address, written: number.to_f64(), count: None }))
}

/// The lead words of `block`, a thread cycle whose final pass is move `pass` or a thread
/// move (`G32`) that is move `pass`, for the slide to cut the programmed lead on `model`:
/// the command advances by the written lead every spindle turn, so the lead written is the
/// programmed one times `lead_ratio`. Written by `back::thread_lead` at the digits the
/// control takes for a lead, with the word that holds it. `None` where the lead word is not
/// a plain number of this block or the lead written does not change.
pub(super) fn thread_lead(
    program: &Program<'_>,
    lowered: &Lowered,
    block: usize,
    pass: usize,
    model: &crate::error_model::ErrorModel,
) -> Option<(LeadWords, LeadChange)> {
    use crate::dialect::{Address, Role};
    use crate::syntax::Statement;
    let block = program.block(block);
    let tables = program.config().tables();
    let mut table = tables.thread_lead;
    // The lead word: a cycle's lead parameter, or a thread move's own `F` (or precise-lead
    // word); a thread move without one runs at the lead written before it.
    let (lead_id, command) = match block.statement {
        Statement::Cycle(id) | Statement::LapCall(id) => {
            let command = program.command(id);
            (command.param(Role::Lead)?, Some(command))
        }
        Statement::ThreadMove => {
            let precise = table.precise.map(|p| p.address);
            let lead = block.word_ids().find(|&w| {
                matches!(program.word(w).kind, WordKind::Number { address, .. }
                    if address == Address::F || Some(address) == precise)
            })?;
            (lead, None)
        }
        _ => return None,
    };
    // A cycle whose form has no precise-lead word (Haas's one-block `G76 X Z K D F`) writes
    // its lead with the lead word alone.
    let form = command.and_then(|c| tables.schema(c.schema).forms.get(c.form as usize));
    if let (Some(form), Some(precise)) = (form, table.precise)
        && form.role_of(precise.address).is_none()
    {
        table.precise = None;
    }
    let WordKind::Number { address, number } = program.word(lead_id).kind else { return None };
    let at = usize::try_from(lead_id.checked_sub(block.first_word)?).ok()?;
    // With a count of threads (OSP `J`), the lead word is the length of that many threads.
    let count_word = table.count.zip(command).and_then(|(count, command)| {
        command
            .params
            .iter()
            .map(|p| p.word)
            .find(|&w| matches!(program.word(w).kind, WordKind::Number { address: a, .. } if a == count))
    });
    let count = match count_word.map(|w| program.word(w).kind) {
        Some(WordKind::Number { number, .. }) if number.to_f64() > 0.0 => number.to_f64(),
        Some(_) => return None,
        None => 1.0,
    };
    let moves = pass_moves(lowered, pass);
    let ratio = lead_ratio(lowered, moves.clone(), model)?;
    let mark = lowered.coordinates_at(pass);
    let grid = crate::back::grid::Grid::new(&mark);
    let written = number.to_f64();
    let programmed = ProgrammedLead { address, written, count: count_word.map(|_| count) };
    let thread_mm = lowered.toolpath.start_of(*moves.start()).distance(lowered.toolpath.moves.get(pass)?.end);
    // A variable lead's change every turn scales with the lead: the slide's travel over `n`
    // turns, `F·n + E·n²/2`, is the programmed one times the ratio where both words are.
    let change_word = match command {
        Some(command) => command.param(Role::LeadChange),
        // A thread move's change word changes its lead only where it cuts a variable lead (one
        // move a turn): a `G32` with a `K` is not a `G34`.
        None => table.change.filter(|_| moves.start() < moves.end()).and_then(|change| {
            block
                .word_ids()
                .find(|&w| matches!(program.word(w).kind, WordKind::Number { address, .. } if address == change))
        }),
    };
    let change = match change_word.map(|w| (w, program.word(w).kind)) {
        Some((w, WordKind::Number { number, .. })) => written_change(&grid, number, number.to_f64() * ratio)
            .and_then(|value| Some((usize::try_from(w.checked_sub(block.first_word)?).ok()?, value))),
        Some(_) => return None,
        None => None,
    };
    // A lead written with more digits than the table gives it (a program's `F0.07692308`)
    // that holds the lead the slide needs over the thread stays as written.
    let lead = match written_drift_mm(&grid, programmed, written / count * ratio, thread_mm) {
        Some(_) => written_lead(&table, &grid, programmed, written / count * ratio, thread_mm)?,
        None if change.is_some() => {
            WrittenLead { words: smallvec::smallvec![(address, number)], lead: written / count, unheld_mm: None }
        }
        None => return None,
    };
    let (words, unheld_mm, lead) = (lead.words, lead.unheld_mm, lead.lead);
    let old = written / count;
    if lead == old && unheld_mm.is_none() && change.is_none() {
        return None;
    }
    let mut from_text = {
        let mut text = String::from_utf8_lossy(program.text(program.word(lead_id).span)).into_owned();
        if let Some(w) = count_word {
            text.push(' ');
            text.push_str(&String::from_utf8_lossy(program.text(program.word(w).span)));
        }
        text
    };
    // A count of threads the lead word is written over stays, and is said with it.
    let mut to = spelled(&words);
    if let Some(w) = count_word.filter(|_| words.len() == 1) {
        to.push(' ');
        to.push_str(&String::from_utf8_lossy(program.text(program.word(w).span)));
    }
    if let (Some(w), Some((_, value))) = (change_word, change)
        && let WordKind::Number { address: change_address, .. } = program.word(w).kind
    {
        from_text.push(' ');
        from_text.push_str(&String::from_utf8_lossy(program.text(program.word(w).span)));
        to.push(' ');
        to.push_str(&spelled(&[(change_address, value)]));
    }
    let lead_change = LeadChange { from: from_text, to, change_ppm: ppm(lead, old), unheld_mm, pieces: None };
    Some((LeadWords { at, words, change }, lead_change))
}

/// The programmed lead of the thread moves `moves` (one pass, along one line) over the lead
/// the slide needs to cut them on `model`: the nominal travel along the thread's axis over
/// the travel the model predicts for it (the model's mean slope over the pass, from its start
/// to its end at the times it runs: a slide 100 ppm long gets a lead 100 ppm short). The
/// slope is the model's, not the written end words': those are rounded to the increment,
/// which over a short thread would be tens of ppm.
pub(super) fn lead_ratio(
    lowered: &Lowered,
    moves: RangeInclusive<usize>,
    model: &crate::error_model::ErrorModel,
) -> Option<f64> {
    let (first, last) = (*moves.start(), *moves.end());
    let (m0, m) = (lowered.toolpath.moves.get(first)?, lowered.toolpath.moves.get(last)?);
    let (from, to) = (lowered.toolpath.start_of(first), m.end);
    let along_z = (to.z - from.z).abs() >= (to.x - from.x).abs();
    let axis = |p: Xz| if along_z { p.z } else { p.x };
    let actual = |at: Xz, seconds: f64| super::thread_pieces::actual_on(model, m, from, at, seconds);
    let ratio = (axis(to) - axis(from)) / (axis(actual(to, m.t_end)) - axis(actual(from, m0.t_start)));
    Some(ratio).filter(|r| r.is_finite() && *r > 0.0)
}

/// The thread moves of the pass that ends with thread move `pass`: it and the thread moves
/// of its block right before it that run on along its line (a variable lead is one move a
/// turn, `Emitter::varying_thread`).
pub(super) fn pass_moves(lowered: &Lowered, pass: usize) -> RangeInclusive<usize> {
    let toolpath = &lowered.toolpath;
    let Some(m) = toolpath.moves.get(pass) else { return pass..=pass };
    let (from, to) = (toolpath.start_of(pass), m.end);
    let length = from.distance(to);
    let mut first = pass;
    while let Some(k) = first.checked_sub(1)
        && let Some(before) = toolpath.moves.get(k)
        && before.threading
        && before.motion == Motion::Feed
        && before.source == m.source
        && length > 0.0
    {
        let (a, b) = (toolpath.start_of(k), before.end);
        let across = ((b.x - a.x) * (to.z - from.z) - (b.z - a.z) * (to.x - from.x)) / length;
        if across.abs() > 1e-6 * a.distance(b).max(1.0) {
            break;
        }
        first = k;
    }
    first..=pass
}
