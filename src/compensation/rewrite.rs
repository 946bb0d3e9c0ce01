//! The compensated program as edits to the parsed one: only the blocks whose motion
//! changes are touched.
//!
//! Input: the parsed program, the lowered toolpath (with nose-radius compensation:
//! `Move.end` is the tool reference point, `Move.contour` the programmed point), and each
//! move's plan (`plan.rs`: the segments to write in the contour frame). Every other block
//! prints byte-identical.
//!
//! * **Motion blocks** (`G00`–`G03`, a thread move) are written back in their own form
//!   (`rewrite/block.rs`). A block that runs more than once (a subprogram called twice, a
//!   loop) is edited only if every run writes the same text; a block that makes several
//!   moves (an OSP automatic corner) cannot carry several corrections. Both refuse with a
//!   diagnostic when their motion must change.
//! * **Under `G41`/`G42`** the program describes the contour, and so does the rewritten
//!   block: its points are the contour points moved by the correction of their reference
//!   points, `contour + (commanded − nominal)` (`written.rs`), never the reference points,
//!   so the control's nose-radius offset still applies on top.
//! * **Cycles** whose motion changes stay calls where a finishing cycle runs their profile
//!   (`G71`/`G72`/`G73` with `G70`, LAP `G85`/`G86` with `G87`): the profile blocks are
//!   compensated word by word from the finishing pass's moves, as motion blocks are, and
//!   the roughing, which the control computes from the profile, follows them. Where the
//!   profile cannot carry the correction in place (a take-up of the play that would be a
//!   block of its own in the profile, a block that makes several moves, a block that also
//!   runs as a plain block), the finishing cycle runs a compensated copy of it and the
//!   roughing the profile as written (`cycles::profile_copy`). A LAP continuous thread
//!   (`G88`) keeps its call with the contour it threads along, its root, compensated in place
//!   from the final pass (`cycles::root_blocks`). A thread cycle keeps its call with its end
//!   and lead words written from its final pass (`cycles::thread_final_pass`), and a single
//!   turning or facing cycle with its end words and taper written from its cut
//!   (`keep_singles`). The others are left as written or expanded into their compensated
//!   moves (`rewrite/cycles.rs`); cycles whose motion does not change stay calls.
//! * Moves of other blocks (`G28`, `G53` returns) stay as programmed: they go to fixed
//!   machine positions, not to points of the part.

mod block;
pub(crate) mod cycles;
pub(crate) mod thread_pieces;

use std::collections::{HashMap, HashSet};
use std::ops::Range;

use crate::back::grid::{Grid, GridPoint};
use crate::back::motion::{Codes, GivenNext, Kind, MotionWriter, Restore};
use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::Address;
use crate::printer::style::{BlockArcWords, StyleTally};
use crate::printer::{BlockWriter, Edits, ProgramStyle, WrittenText};
use crate::semantic::nose_radius::ToolTable;
use crate::semantic::{CoordinateMark, Expansion, Lowered};
use crate::source::Span;
use crate::syntax::{Program, Statement};
use crate::toolpath::{Motion, Xz};

use super::fit::Segment;
use super::plan::{KeptPlans, MovePlan};
use super::written;

/// The edits, their problems, and what was edited.
#[derive(Debug, Clone, Default)]
pub struct Rewrite {
    pub edits: Edits,
    /// Refusals (errors: nothing may be written) and notes.
    pub diagnostics: Vec<Diagnostic>,
    /// Each edited block (a motion block, or a cycle call that was expanded) and the moves
    /// it writes (for a block that runs several times, its first run).
    pub edited: Vec<EditedBlock>,
    /// What became of each cycle call.
    pub cycles: Vec<CycleOutcome>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct EditedBlock {
    pub block: usize,
    pub moves: Range<usize>,
    pub cycle: bool,
    /// Its moves are the turns of one variable-lead thread move (`Emitter::varying_thread`),
    /// which it writes as the one move it is.
    pub one_move: bool,
}

/// Per move, what can be written for it (`MotionBlocks::move_tables`).
#[derive(Debug, Clone, Default)]
pub struct MoveForms {
    /// The move can be written back: a move of a motion block, or of a cycle that can be
    /// expanded.
    pub writable: Vec<bool>,
    /// The arcs written for the move prefer the radius form (`R`/`L`) to the centre form
    /// (`I K`): a motion block's own form (`block::writes_radius`), a cycle's the
    /// program's (`back::cycle_blocks` writes its blocks so). `Grid::arc_words` still writes
    /// an arc by its centre where its radius would not hold it.
    pub radius: Vec<bool>,
}

/// Block indices by the start of their span.
struct BlockLookup {
    starts: Vec<u32>,
}

impl BlockLookup {
    fn index(&self, start: u32) -> Option<usize> {
        self.starts.binary_search(&start).ok()
    }

    /// `index`, trying the block `near` and the one after it first (moves come mostly in
    /// block order, and a block's moves one after another); `near` becomes the block found.
    fn index_near(&self, start: u32, near: &mut usize) -> Option<usize> {
        let found = [*near, *near + 1]
            .into_iter()
            .find(|&k| self.starts.get(k) == Some(&start))
            .or_else(|| self.index(start))?;
        *near = found;
        Some(found)
    }
}

/// What became of a cycle call (each call block once, in block order).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct CycleOutcome {
    #[serde(skip)]
    pub block: usize,
    #[serde(flatten)]
    pub form: CycleForm,
}

#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(tag = "outcome", rename_all = "snake_case")]
pub enum CycleForm {
    /// The call stays as written, its moves need no correction.
    Kept,
    /// The call stays as written though its moves take a correction that neither its words
    /// nor a profile can carry (a grooving cycle; a single turning or facing cycle whose
    /// words cannot name its cut, or whose cut needs none where its other moves do; a thread
    /// whose final pass needs a take-up), where the check before writing finds the part
    /// within the bound with the blocks around it compensated.
    LeftAsWritten,
    /// The call stays as written and the profile it shares with a finishing cycle is
    /// compensated in place (its blocks, `profile`): the roughing follows it, as on the
    /// control.
    ProfileEdited {
        #[serde(skip)]
        profile: Vec<usize>,
        /// Where it changes, the lead a LAP continuous thread's call is written with
        /// (`cycles::thread_lead`).
        #[serde(skip_serializing_if = "Option::is_none")]
        lead: Option<cycles::LeadChange>,
    },
    /// The call stays, its words carrying the correction of its final pass (a thread
    /// cycle: the final diameter and the end of the thread; a single turning or facing
    /// cycle: the end of its cut and its taper), and `lead`, where it changes, the lead the
    /// slide needs to cut the programmed one (`cycles::thread_lead`).
    WordsEdited {
        #[serde(skip_serializing_if = "Option::is_none")]
        lead: Option<cycles::LeadChange>,
        /// The call cuts one pass (`G92`, OSP's `G33`, `G90`, `G94`): its final pass is its
        /// only one.
        #[serde(skip)]
        single_pass: bool,
        /// The call cuts a thread (`CycleChoice::threads_in_place` keeps it so); else it is a
        /// single turning or facing cycle (`CycleChoice::singles_in_place`).
        #[serde(skip)]
        thread: bool,
    },
    /// A roughing call that stays as written on the profile as written: the roughing follows
    /// the nominal profile and its allowance, while its finishing cycle runs a compensated
    /// copy (`ProfileCopied`).
    RoughsOriginal,
    /// A finishing call that runs its own compensated copy of the profile `profile` (its
    /// blocks): the blocks `copy` (their first and last sequence names), written after the
    /// roughing call; its `P`/`Q` name them. `reason`: why the profile is not compensated in
    /// place.
    ProfileCopied {
        #[serde(skip)]
        profile: Vec<usize>,
        #[serde(skip)]
        copy: (String, String),
        #[serde(skip)]
        reason: String,
    },
    /// The call is written out as its compensated moves; `lead`, where it changes, the lead
    /// its thread moves are written with for the slide to cut the programmed one (the final
    /// pass's, `cycles::expanded_leads`).
    Expanded {
        reason: String,
        #[serde(skip_serializing_if = "Option::is_none")]
        lead: Option<cycles::LeadChange>,
    },
}

/// Why a cycle is expanded when profiles are not compensated in place (the caller that
/// asked for it says why).
pub const PROFILE_NOT_IN_PLACE: &str = "its moves change, and its profile is not compensated in place";

/// Why a profile is copied for its finishing cycle when it is not compensated in place (the
/// caller that asked for it says why).
pub const PROFILE_COPIED: &str = "its profile is not compensated in place";

/// Why a cycle is expanded when its profile is neither compensated in place nor copied for
/// its finishing cycle (the caller that asked for it says why).
pub const PROFILE_NOT_COPIED: &str = "its moves change, and its profile is neither compensated in place nor copied";

/// Why a profile is not compensated in place where its compensated blocks take up the play
/// (`MotionBlocks::profile_writable`); where its copy then misses the bound too and the
/// cycles are expanded, the caller says why the copy does.
pub const PROFILE_TAKE_UP: &str = "a block of its profile needs a take-up of the play written as a move of its own, \
                                   which the roughing cycle would run as part of the profile";

/// Why a thread cycle stays as programmed (`cycle-not-compensated`) where its words do not
/// name its final pass and its passes cannot be written out.
pub(crate) const THREAD_WORDS_NOT_FINAL: &str = "its words do not name its final pass (a word written as an \
     expression, or a final pass that does not run along the thread), and its thread passes have no plain-block form \
     in this dialect";

/// Why a thread cycle stays as programmed where its final pass needs a take-up of the play.
const THREAD_TAKE_UP: &str = "its final pass needs more than one move (a take-up of the play), which its words \
     cannot carry, and its thread passes have no plain-block form in this dialect";

/// Why a LAP continuous thread (`G88`) stays as programmed where its root contour cannot
/// carry the final pass's correction.
const ROOT_NOT_WRITABLE: &str = "the blocks of its root contour cannot carry the final pass's correction (a take-up of \
     the play written as a move of its own, which every pass would run as part of the thread, or a block that makes \
     several moves or also runs as a plain block)";

/// Why a thread cycle is expanded when its words are not compensated in place.
pub const THREAD_NOT_IN_PLACE: &str = "its moves change, and its own words are not compensated in place";

/// Why a single turning or facing cycle is expanded when its words are not compensated in
/// place and it is not left as written (the caller that asked for it says why).
pub const SINGLE_NOT_IN_PLACE: &str = "its moves change, its own words are not compensated in place, and it is not \
     left as written";

/// Why a cycle whose words carry no correction, and which shares no profile with a finishing
/// cycle, is expanded when it is not left as written (the caller that asked for it says why).
pub const OTHER_NOT_AS_WRITTEN: &str = "its moves change, no finishing cycle runs a profile of it, and it is not \
     left as written";

/// How the rewrite treats the cycles whose moves change.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CycleChoice {
    /// Expand every cycle (`--expand-cycles`).
    pub expand_all: bool,
    /// Compensate a profile a finishing cycle runs in place rather than expand the cycles
    /// that share it.
    pub profiles_in_place: bool,
    /// Where a profile is not compensated in place, give its finishing cycle a compensated
    /// copy and leave the roughing on the profile as written, rather than expand them.
    pub profiles_copied: bool,
    /// Compensate a thread cycle's final pass in its own words rather than expand it.
    pub threads_in_place: bool,
    /// Compensate a single turning or facing cycle's cut in its own words (its end and
    /// taper) rather than leave it as written or expand it.
    pub singles_in_place: bool,
    /// Leave as written a cycle whose correction neither its words nor a profile can carry,
    /// rather than expand it: the check before writing judges it.
    pub others_as_written: bool,
}

/// The edits, once every move is planned and every run of a motion block was given to
/// `motion`: the cycles, then the motion blocks.
pub fn finish(
    program: &Program<'_>,
    lowered: &Lowered,
    plans: &KeptPlans,
    choice: CycleChoice,
    mut motion: MotionBlocks<'_, '_>,
    model: &crate::error_model::ErrorModel,
) -> Rewrite {
    let mut out = Rewrite::default();
    let (mut chosen, groups) = cycles::chosen(program, lowered, plans, choice.expand_all, &mut out.diagnostics);
    let mut in_place: HashMap<usize, Vec<usize>> = HashMap::new();
    // Why a cycle that could have stayed is expanded, where it is more than the default.
    let mut why: HashMap<usize, String> = HashMap::new();
    // The groups whose finishing cycle gets a copy of the profile, and why not in place.
    let mut to_copy: Vec<(cycles::ProfileGroup, &'static str)> = Vec::new();
    if (choice.profiles_in_place || choice.profiles_copied) && !choice.expand_all {
        for group in cycles::profile_groups(lowered, plans, &chosen, &groups) {
            let writable = if choice.profiles_in_place {
                motion.profile_writable(&group.blocks, plans)
            } else {
                Err(PROFILE_COPIED)
            };
            if let Err(reason) = writable {
                if choice.profiles_copied {
                    to_copy.push((group, reason));
                } else {
                    for e in group.members.iter().filter_map(|&k| lowered.expansions.get(k)) {
                        why.insert(e.block, reason.to_string());
                    }
                }
            } else {
                motion.write_profile(&group.blocks, plans);
                let profile: Vec<usize> = {
                    let mut b: Vec<usize> = group.blocks.iter().map(|&(b, _)| b).collect();
                    b.sort_unstable();
                    b.dedup();
                    b
                };
                for &k in &group.members {
                    chosen[k] = false;
                    if let Some(e) = lowered.expansions.get(k) {
                        in_place.insert(e.block, profile.clone());
                    }
                }
            }
        }
    }
    let mut copied: HashMap<usize, CycleForm> = HashMap::new();
    if !to_copy.is_empty() {
        let style = motion.writer.out.style();
        for (group, reason) in to_copy {
            match cycles::profile_copy(program, lowered, plans, &group, style) {
                Ok(copy) => {
                    let mut profile: Vec<usize> = group.blocks.iter().map(|&(b, _)| b).collect();
                    profile.sort_unstable();
                    profile.dedup();
                    for &k in &group.members {
                        chosen[k] = false;
                    }
                    for block in copy.blocks {
                        out.edits.insert_after(copy.after, block);
                    }
                    out.edits.replace(copy.finish, vec![copy.call]);
                    if let Some(e) = lowered.expansions.iter().find(|e| e.block == copy.finish) {
                        out.edited.push(EditedBlock {
                            block: copy.finish,
                            moves: e.moves.clone(),
                            cycle: false,
                            one_move: false,
                        });
                    }
                    copied.insert(copy.rough, CycleForm::RoughsOriginal);
                    copied.insert(
                        copy.finish,
                        CycleForm::ProfileCopied { profile, copy: copy.names, reason: reason.to_string() },
                    );
                }
                Err(no_copy) => {
                    let reason = if reason == PROFILE_COPIED {
                        PROFILE_NOT_COPIED.to_string()
                    } else {
                        format!("{reason}, and no copy of it can be written for the finishing cycle: {no_copy}")
                    };
                    for e in group.members.iter().filter_map(|&k| lowered.expansions.get(k)) {
                        why.insert(e.block, reason.clone());
                    }
                }
            }
        }
    }
    // A LAP continuous thread keeps its call, the final pass's correction in the blocks of
    // its contour, the thread's root.
    // Its lead is the call's own word, written for the slide to cut the programmed lead as a
    // kept thread cycle's is (`cycles::thread_lead`).
    let mut root_leads: HashMap<usize, cycles::LeadChange> = HashMap::new();
    for e in &lowered.expansions {
        let root = cycles::root_blocks(e);
        if root.is_empty() || choice.expand_all {
            continue;
        }
        let changed = root.iter().any(|(_, m)| plans.get(m.clone()).is_some_and(|p| p.iter().any(|p| p.changed)));
        // The lead from the final pass's longest thread move on the root: the lead words are
        // chosen for the length they must hold the thread over.
        let toolpath = &lowered.toolpath;
        let length = |k: usize| toolpath.moves.get(k).map_or(0.0, |m| toolpath.start_of(k).distance(m.end));
        let lead = e
            .root
            .iter()
            .map(|&(m, _)| m)
            .filter(|&k| toolpath.moves.get(k).is_some_and(|m| m.threading))
            .max_by(|&a, &b| length(a).total_cmp(&length(b)))
            .and_then(|pass| cycles::thread_lead(program, lowered, e.block, pass, model));
        if !changed && lead.is_none() {
            continue;
        }
        if choice.profiles_in_place && motion.profile_writable(&root, plans).is_ok() {
            motion.write_profile(&root, plans);
            let mut profile: Vec<usize> = root.iter().map(|&(b, _)| b).collect();
            profile.sort_unstable();
            in_place.insert(e.block, profile);
            if let Some((words, change)) = lead {
                out.edits.replace(e.block, vec![cycles::with_lead(program, e.block, &words)]);
                out.edited.push(EditedBlock { block: e.block, moves: e.moves.clone(), cycle: false, one_move: false });
                root_leads.insert(e.block, change);
            }
        } else {
            let span = program.block(e.block).span;
            let reason = ROOT_NOT_WRITABLE;
            out.diagnostics.push(Diagnostic::warning(DiagnosticKind::CycleNotCompensated { reason }, span));
        }
    }
    // A thread cycle keeps its call, the final pass's correction in its own words.
    let mut threads: HashMap<usize, (Option<cycles::LeadChange>, bool)> = HashMap::new();
    // The plan each kept call's final pass is written from, by its move.
    let mut pass_plans: HashMap<usize, MovePlan> = HashMap::new();
    // Where each thread call starts as written, by its expansion.
    let mut call_starts: HashMap<usize, Xz> = HashMap::new();
    if choice.threads_in_place && !choice.expand_all {
        for (k, e) in lowered.expansions.iter().enumerate() {
            let alone = groups.iter().enumerate().all(|(j, &g)| j == k || g != groups[k]);
            let Some(pass) = cycles::thread_final_pass(program, lowered, e).filter(|_| alone) else { continue };
            // A call that repeats the kept thread cycle call right before it (Fanuc's `G92`
            // modal: a block of `X` alone) takes the axes it does not name from that call as
            // written.
            if let Some(before) = k.checked_sub(1).and_then(|j| lowered.expansions.get(j))
                && before.moves.end == e.moves.start
                && !chosen.get(k - 1).copied().unwrap_or(true)
                && let Some(before_pass) = cycles::thread_final_pass(program, lowered, before)
                && let Some(before_plan) = pass_plans
                    .get(&before_pass)
                    .or_else(|| plans.get(before_pass..before_pass + 1).and_then(<[MovePlan]>::first))
            {
                let grid = Grid::new(&lowered.coordinates_at(before_pass));
                motion.inherited.insert(e.block, grid.point(before_plan.end()));
            }
            // Where the call starts as written: where the move before it leaves the tool, or
            // right after a call that stays, where that call started (a cycle returns to its
            // start point, whatever the plan of its last move says).
            let after_call = k.checked_sub(1).filter(|&j| {
                lowered.expansions.get(j).is_some_and(|before| before.moves.end == e.moves.start)
                    && !chosen.get(j).copied().unwrap_or(true)
            });
            let Some(call_start) = after_call
                .and_then(|j| call_starts.get(&j).copied())
                .or_else(|| plans.get(e.moves.start..e.moves.start + 1)?.first().map(|p| p.start))
            else {
                continue;
            };
            call_starts.insert(k, call_start);
            // A cycle that cannot be written out (an OSP thread) is not chosen: its final pass
            // says whether it needs a correction.
            let expandable = cycles::expandable(program, lowered, e);
            let changed = plans.get(pass..pass + 1).is_some_and(|p| p.iter().any(|p| p.changed));
            if !(chosen.get(k).copied().unwrap_or(false) || (!expandable && changed)) {
                continue;
            }
            if motion.thread_writable(e.block, pass, plans)
                && let Some(plan) = motion.thread_pass_plan(e, (call_start, pass), plans)
            {
                let lead = cycles::thread_lead(program, lowered, e.block, pass, model);
                let change = lead.map(|(words, change)| {
                    motion.leads.insert(e.block, words);
                    change
                });
                motion.write_pass(e.block, (Some(e.moves.start), pass), &plan);
                pass_plans.insert(pass, plan);
                chosen[k] = false;
                // A call whose words already hold its final pass (a repeated `G92` that takes
                // the corrected Z from the call before) is kept as it is.
                if !matches!(motion.first_runs.get(e.block), Some(FirstRun::AsWritten)) {
                    let moves = lowered.toolpath.moves.get(e.moves.clone()).unwrap_or_default();
                    let passes =
                        moves.iter().enumerate().filter(|&(n, m)| m.threading && (n == 0 || !moves[n - 1].threading));
                    threads.insert(e.block, (change, passes.count() == 1));
                }
            } else if !expandable {
                let span = program.block(e.block).span;
                let reason = THREAD_TAKE_UP;
                out.diagnostics.push(Diagnostic::warning(DiagnosticKind::CycleNotCompensated { reason }, span));
            } else {
                why.insert(
                    e.block,
                    "its final pass needs more than one move (a take-up of the play), which its words cannot carry"
                        .to_string(),
                );
            }
        }
    }
    // A single turning or facing cycle keeps its call, its cut's correction in its own end
    // words and taper; a modal repeat of it (`X` alone) takes what it does not name from the
    // run before it as written. A groove of one plunge keeps its call, its bottom's
    // correction in its end words.
    let mut singles: HashSet<usize> = HashSet::new();
    if choice.singles_in_place && !choice.expand_all {
        singles = keep_singles(program, lowered, plans, (&mut chosen, &groups), choice, &mut motion);
    }
    // What is still to be expanded is a cycle whose correction neither its words nor a
    // profile carries: it stays as written where the caller asks for it, and the check
    // judges the part it cuts.
    let mut left: HashSet<usize> = HashSet::new();
    if choice.others_as_written && !choice.expand_all {
        for (k, e) in lowered.expansions.iter().enumerate() {
            if chosen.get(k).copied().unwrap_or(false) {
                chosen[k] = false;
                left.insert(e.block);
            }
        }
    }
    let style = motion.writer.out.style();
    let pieces = motion.piece_settings();
    let (expanded, mut expanded_leads, restores) =
        cycles::write(program, lowered, (plans, model, pieces), &chosen, style, &mut out.edits, &mut out.diagnostics);
    for cycles::CycleRestore { call, next, next_move, restore } in restores {
        if let Some(next) = next {
            motion.folds.push(Fold { after: RestoreAfter::Cycle(call), next, next_move, restore });
        }
    }
    // The first expansion of each call block (a call that runs several times has several).
    let mut first_expansion: HashMap<usize, usize> = HashMap::new();
    for (k, e) in lowered.expansions.iter().enumerate() {
        first_expansion.entry(e.block).or_insert(k);
    }
    let expanded_set: HashSet<usize> = expanded.iter().copied().collect();
    for block in expanded {
        if let Some(e) = first_expansion.get(&block).and_then(|&k| lowered.expansions.get(k)) {
            out.edited.push(EditedBlock { block, moves: e.moves.clone(), cycle: true, one_move: false });
        }
    }
    let single_cycle = |block: usize| {
        let e = first_expansion.get(&block).and_then(|&k| lowered.expansions.get(k));
        e.is_some_and(|e| {
            cycles::single_cut(program, lowered, e).is_some() || cycles::groove(program, lowered, e).is_some()
        })
    };
    let mut calls: Vec<usize> = first_expansion.keys().copied().collect();
    calls.sort_unstable();
    for block in calls {
        let form = if let Some(profile) = in_place.remove(&block) {
            CycleForm::ProfileEdited { profile, lead: root_leads.remove(&block) }
        } else if let Some(form) = copied.remove(&block) {
            form
        } else if let Some((lead, single_pass)) = threads.remove(&block) {
            CycleForm::WordsEdited { lead, single_pass, thread: true }
        } else if singles.contains(&block) {
            CycleForm::WordsEdited { lead: None, single_pass: true, thread: false }
        } else if expanded_set.contains(&block) {
            let threads_cut = first_expansion
                .get(&block)
                .and_then(|&k| lowered.expansions.get(k))
                .and_then(|e| lowered.toolpath.moves.get(e.moves.clone()))
                .is_some_and(|moves| moves.iter().any(|m| m.threading));
            let reason = if choice.expand_all {
                "--expand-cycles"
            } else if let Some(reason) = why.get(&block) {
                reason.as_str()
            } else if threads_cut && !choice.threads_in_place {
                THREAD_NOT_IN_PLACE
            } else if threads_cut {
                "its moves change, and its end words do not name its final pass (a word written as an \
                 expression, or a final pass that does not run along the thread), so they cannot carry the \
                 correction"
            } else if !choice.singles_in_place && single_cycle(block) {
                SINGLE_NOT_IN_PLACE
            } else if !choice.profiles_in_place && !choice.profiles_copied {
                PROFILE_NOT_COPIED
            } else if !choice.profiles_in_place {
                PROFILE_NOT_IN_PLACE
            } else if !choice.others_as_written {
                OTHER_NOT_AS_WRITTEN
            } else {
                "its moves change, and no finishing cycle runs a profile of it (a single cycle, a roughing cycle \
                 with no finishing cycle, a finishing cycle whose own moves cut)"
            };
            let lead = expanded_leads.remove(&block);
            let reason = match lead.as_ref().and_then(|lead| lead.pieces) {
                Some(pieces) => format!(
                    "{reason}; the lead error is not uniform along the thread, which one lead word cannot \
                     carry: the passes that shape the finished thread are written as consecutive thread blocks, \
                     each with its own lead ({pieces} for the final pass)"
                ),
                None => reason.to_string(),
            };
            CycleForm::Expanded { reason, lead }
        } else if left.contains(&block) {
            CycleForm::LeftAsWritten
        } else {
            CycleForm::Kept
        };
        out.cycles.push(CycleOutcome { block, form });
    }
    motion.finish(&mut out, plans);
    out.edited.sort_by_key(|e| e.block);
    out.diagnostics.sort_by_key(|d| d.span.start);
    out
}

/// What a single turning or facing cycle's run leaves in force as written, for a modal
/// repeat of it right after (`keep_singles`).
#[derive(Debug, Clone, Copy)]
struct SingleInForce {
    /// The move after the run's: a repeat's first.
    next_move: usize,
    facing: bool,
    /// The end of its cut and its taper, on the grid, as the control runs them.
    end: GridPoint,
    taper: i64,
    /// Its words were edited: a repeat after it that names not every axis runs elsewhere
    /// than as written.
    edited: bool,
}

/// Keep the single turning and facing cycles (`G90`, `G94`) whose cut's correction their
/// words can carry (`cycles::single_cut`), with those words written from the plan of the
/// cut (`MotionBlocks::write_pass`): `X` and `Z` its end (`U` and `W` its end less the call's
/// start point, `written_start`), the taper `R` its start from that end where it differs
/// from the one in force (the call's own, else none; a repeat's, the run's before it), added
/// where the block writes none. A run whose whole feed moves keep clear of the finished
/// part, and whose words as written end within half that clearance of the plan (a roughing
/// pass), stays as written, as a thread's infeed pass does. The move
/// back out of the cut ends at the start point, which no word of the call moves: the check
/// before writing judges it with the rest. A groove (`G75`) whose plunges' bottoms one `X`
/// can carry is kept the same way (`keep_groove`). The calls kept with their words edited,
/// by block; a call kept as written has its `chosen` cleared, so nothing expands it.
fn keep_singles(
    program: &Program<'_>,
    lowered: &Lowered,
    plans: &KeptPlans,
    (chosen, groups): (&mut [bool], &[usize]),
    choice: CycleChoice,
    motion: &mut MotionBlocks<'_, '_>,
) -> HashSet<usize> {
    let mut edited: HashSet<usize> = HashSet::new();
    let mut in_force: Option<SingleInForce> = None;
    // Where each call that stays starts as written, by the move after its last: the
    // control returns there, whatever the plan of its move back says.
    let mut returns: HashMap<usize, Xz> = HashMap::new();
    for (k, e) in lowered.expansions.iter().enumerate() {
        // The kept run that ends where this one starts: its end and taper stay in force.
        let adjacent = in_force.take().filter(|b| b.next_move == e.moves.start);
        let alone = groups.iter().enumerate().all(|(j, &g)| j == k || g != groups[k]);
        let Some(cut) = cycles::single_cut(program, lowered, e).filter(|_| alone) else {
            if chosen.get(k).copied().unwrap_or(false)
                && alone
                && let Some(groove) = cycles::groove(program, lowered, e)
                && let Some(start) = written_start(program, lowered, plans, &returns, e)
            {
                if let Some(words_edited) = keep_groove(lowered, plans, (e, &groove, start), motion) {
                    if let Some(c) = chosen.get_mut(k) {
                        *c = false;
                    }
                    if words_edited {
                        edited.insert(e.block);
                    }
                }
                if !chosen.get(k).copied().unwrap_or(false) || choice.others_as_written {
                    returns.insert(e.moves.end, start);
                }
            }
            continue;
        };
        // A repeat runs from the end and taper the run before it leaves in force.
        let before = adjacent.filter(|b| b.facing == cut.facing && cut.repeat);
        if cut.repeat && before.is_none() {
            continue;
        }
        // Where the call starts as written, which incremental end words count from.
        let Some(call_start) = written_start(program, lowered, plans, &returns, e) else { continue };
        let grid = Grid::new(&lowered.coordinates_at(cut.cut));
        let Some(m) = lowered.toolpath.moves.get(cut.cut) else { continue };
        // Where the block as written ends the cut, and its taper: the axes it names as
        // written (counted from the call's start point where they are incremental), the
        // others as the run before it leaves them.
        let nominal = grid.point(m.contour);
        let (from, nominal_from) =
            (grid.point(call_start), grid.point(written::contour_start(&lowered.toolpath, e.moves.start)));
        let axis = |(named, incremental): (bool, bool),
                    (end, from, nominal_from): (i64, i64, i64),
                    held: Option<i64>| match held.filter(|_| !named) {
            Some(held) => held,
            None if incremental => from + end - nominal_from,
            None => end,
        };
        let as_written = GridPoint {
            x: axis((cut.names.0, cut.incremental.0), (nominal.x, from.x, nominal_from.x), before.map(|b| b.end.x)),
            z: axis((cut.names.1, cut.incremental.1), (nominal.z, from.z, nominal_from.z), before.map(|b| b.end.z)),
        };
        let taper_as_written = cut.taper.map_or(before.map_or(0, |b| b.taper), |(_, t)| t);
        let as_written_run = SingleInForce {
            next_move: e.moves.end,
            facing: cut.facing,
            end: as_written,
            taper: taper_as_written,
            edited: false,
        };
        let changed = chosen.get(k).copied().unwrap_or(false);
        if !changed && !before.is_some_and(|b| b.edited) {
            in_force = Some(as_written_run);
            returns.insert(e.moves.end, call_start);
            continue;
        }
        let Some(plan) = plans.get(cut.cut..cut.cut + 1).and_then(<[MovePlan]>::first) else { continue };
        let (Some(&Segment::Line { end }), true) =
            (plan.segments.last(), plan.segments.iter().all(|s| matches!(s, Segment::Line { .. })))
        else {
            continue;
        };
        if !matches!(motion.first_runs.get(e.block), Some(FirstRun::NotYet)) {
            continue;
        }
        // A roughing pass: it cuts no finished surface, and stays as written.
        let feeds_clear = motion.clearance.filter(|c| c.is_clear(cut.cut) && c.is_clear(cut.cut + 1));
        if let Some(clearance) = feeds_clear
            && grid.to_mm(as_written).distance(end) <= clearance.by_mm() / 2.0
        {
            if let Some(c) = chosen.get_mut(k) {
                *c = false;
            }
            in_force = Some(as_written_run);
            returns.insert(e.moves.end, call_start);
            continue;
        }
        // The cut starts where its plan's take-up of the play ends (a jump at the start of a
        // straight move, in the air before the part), and runs straight to its end: where
        // the plan follows the model in several lines, the words give their chord, which the
        // check judges.
        let start = match plan.jumps.min(plan.segments.len() - 1) {
            0 => plan.start,
            jumps => plan.segments[jumps - 1].end(),
        };
        let at = grid.point(end);
        let written_end = grid.to_mm(at);
        let taper = grid.length(if cut.facing { start.z - written_end.z } else { start.x - written_end.x });
        if let Some(b) = before {
            motion.inherited.insert(e.block, b.end);
        }
        if taper != taper_as_written {
            motion.tapers.insert(e.block, taper);
        }
        // The words count from the call's start point: incremental ones are the cut's end
        // less it, absolute ones the end alone.
        let plan = MovePlan {
            start: call_start,
            segments: smallvec::smallvec![Segment::Line { end }],
            changed: true,
            jumps: 0,
            lead_in: false,
            words: smallvec::SmallVec::new(),
        };
        motion.write_pass(e.block, (Some(e.moves.start), cut.cut), &plan);
        if matches!(motion.first_runs.get(e.block), Some(FirstRun::Replaced(_))) {
            if let Some(c) = chosen.get_mut(k) {
                *c = false;
            }
            edited.insert(e.block);
            in_force = Some(SingleInForce { end: at, taper, edited: true, ..as_written_run });
            returns.insert(e.moves.end, call_start);
        } else {
            // Its words as written are those of its plan. Where its cut needs a correction
            // they hold it (a repeat that takes the corrected end from the run before it):
            // it is kept as it is. Where only the moves its words do not place change (the
            // move back out), it is left as written, which the check judges, or expanded.
            let Some(from) = lowered.toolpath.moves.get(cut.cut - 1) else { continue };
            let nominal_taper =
                grid.length(if cut.facing { from.contour.z - m.contour.z } else { from.contour.x - m.contour.x });
            if (at != nominal || taper != nominal_taper)
                && let Some(c) = chosen.get_mut(k)
            {
                *c = false;
            }
            if !chosen.get(k).copied().unwrap_or(false) || choice.others_as_written {
                in_force = Some(as_written_run);
                returns.insert(e.moves.end, call_start);
            }
        }
    }
    edited
}

/// Keep a groove on a diameter (`G75`) whose bottoms' correction its end words can carry
/// (`cycles::groove`), with `X` (or `U`) written from the plans of the feeds that reach the
/// bottoms, where they all round to one `X` on the grid (the one word writes every plunge's
/// bottom), and `Z` (or `W`) where it names one from the plan of the last plunge's bottom,
/// which the control places at the end `Z` whatever the step `Q`: the groove's far wall. A
/// groove of one plunge runs at its start point: its `Z` is the start point's (`start`, as
/// written), since a `Z` elsewhere would step the groove into a second plunge. Incremental
/// words count from that start point. The first plunge, and so the near wall, runs at the
/// start point's Z, which the move before the call places; the plunges between step by `Q`
/// as written, the pecks count from the start point, and the moves back out end there: the
/// check before writing judges them with the rest. `Some(true)` where its words are
/// edited, `Some(false)` where its words as written already reach the bottoms the plans
/// correct (`U`/`W` from a start point that moved with them): kept as it is; `None` where
/// its words cannot carry them (plans of two bottoms a grid step apart in X), or its
/// bottoms need no correction (only the moves its words do not place change).
fn keep_groove(
    lowered: &Lowered,
    plans: &KeptPlans,
    (e, groove, start): (&Expansion, &cycles::Groove, Xz),
    motion: &mut MotionBlocks<'_, '_>,
) -> Option<bool> {
    let (&last, one_plunge) = (groove.bottoms.last()?, groove.bottoms.len() == 1);
    let mut ends: Vec<Xz> = Vec::with_capacity(groove.bottoms.len());
    for &bottom in &groove.bottoms {
        let plan = plans.get(bottom..bottom + 1).and_then(<[MovePlan]>::first)?;
        let (Some(&Segment::Line { end }), true) =
            (plan.segments.last(), plan.segments.iter().all(|s| matches!(s, Segment::Line { .. })))
        else {
            return None;
        };
        ends.push(end);
    }
    let grid = Grid::new(&lowered.coordinates_at(last));
    let x = grid.point(*ends.last()?).x;
    if ends.iter().any(|&end| grid.point(end).x != x) {
        return None;
    }
    if !matches!(motion.first_runs.get(e.block), Some(FirstRun::NotYet)) {
        return None;
    }
    let end = *ends.last()?;
    let plan = MovePlan {
        start,
        segments: smallvec::smallvec![Segment::Line { end: Xz::new(end.x, if one_plunge { start.z } else { end.z }) }],
        changed: true,
        jumps: 0,
        lead_in: false,
        words: smallvec::SmallVec::new(),
    };
    motion.write_pass(e.block, (Some(e.moves.start), last), &plan);
    if matches!(motion.first_runs.get(e.block), Some(FirstRun::Replaced(_))) {
        return Some(true);
    }
    let (planned, nominal) = (grid.point(end), grid.point(lowered.toolpath.moves.get(last)?.contour));
    (planned.x != nominal.x || (!one_plunge && planned.z != nominal.z)).then_some(false)
}

/// Where the call `e` starts as written, which its incremental end words count from: where
/// the moves before it leave the tool. That is the plan of its first move's start, unless a
/// call that stays comes before it with only plain moves between (`returns`, by the move
/// after its last: its start point, where the control returns whatever the plan of its move
/// back says). Then it is that start point, each move between taking the tool along the
/// axes its block names to its plan's end (`X`, `Z`) or by its plan's travel (`U`, `W`),
/// and leaving it where it stands along the others.
fn written_start(
    program: &Program<'_>,
    lowered: &Lowered,
    plans: &KeptPlans,
    returns: &HashMap<usize, Xz>,
    e: &Expansion,
) -> Option<Xz> {
    let moves = &lowered.toolpath.moves;
    let planned = plans.get(e.moves.start..e.moves.start + 1)?.first()?.start;
    let mut first = e.moves.start;
    while !returns.contains_key(&first)
        && let Some(before) = first.checked_sub(1)
        && moves.get(before).is_some_and(|m| m.cycle == Span::SYNTHETIC)
    {
        first = before;
    }
    let Some(&start) = returns.get(&first) else { return Some(planned) };
    let mut at = start;
    for k in first..e.moves.start {
        let (plan, m) = (plans.get(k..k + 1)?.first()?, moves.get(k)?);
        let block = program.blocks().binary_search_by_key(&m.source.start, |b| b.span.start).ok()?;
        let [x, z] = block::named_axes(program, block, lowered.coordinates_at(k).absolute);
        let end = plan.end();
        let axis = |incremental: Option<bool>, start: f64, end: f64, at: f64| match incremental {
            Some(true) => at + end - start,
            Some(false) => end,
            None => at,
        };
        at = Xz::new(axis(x, plan.start.x, end.x, at.x), axis(z, plan.start.z, end.z, at.z));
    }
    Some(at)
}

/// A stretch of moves one edited block can write: the moves of one cycle call, or a run
/// of consecutive moves of one block outside cycles (one run of a block that runs several
/// times).
#[derive(Debug, Clone, PartialEq)]
pub struct MoveRun {
    pub moves: Range<usize>,
    pub cycle: bool,
}

/// Every move's run, in path order (each `EditedBlock` writes the moves of one of them),
/// split move by move in the pass over the moves that also finds what can be written for
/// each (`MotionBlocks::move_tables`): a long program's moves are hundreds of MB, read from
/// memory once rather than twice.
struct RunSplitter {
    /// The cycle each move belongs to (the first that lists it); a program without cycles
    /// needs no table.
    cycle_of: Vec<Option<usize>>,
    /// At most one run per move, written front to back.
    runs: Vec<MoveRun>,
    /// The run being extended: its first move, that move's block and cycle.
    current: Option<(usize, Span, Option<usize>)>,
    /// The number of moves, all of which are given before `finish`.
    moves: usize,
}

impl RunSplitter {
    fn new(lowered: &Lowered) -> RunSplitter {
        let moves = lowered.toolpath.moves.len();
        let mut cycle_of: Vec<Option<usize>> = Vec::new();
        if !lowered.expansions.is_empty() {
            cycle_of.resize(moves, None);
        }
        for (index, e) in lowered.expansions.iter().enumerate() {
            for k in e.moves.clone() {
                if let Some(c) = cycle_of.get_mut(k) {
                    c.get_or_insert(index);
                }
            }
        }
        RunSplitter { cycle_of, runs: crate::memory::huge_page_vec(moves), current: None, moves }
    }

    /// Move `k` (the one after the last given), from the block at `source`: it extends the
    /// current run when it is of the same cycle call, or outside cycles of the same block.
    /// Whether the move is one of a cycle's.
    fn add(&mut self, k: usize, source: Span) -> bool {
        let cycle = self.cycle_of.get(k).copied().flatten();
        if let Some((first, run_source, run_cycle)) = self.current {
            if run_cycle == cycle && (cycle.is_some() || run_source == source) {
                return cycle.is_some();
            }
            self.runs.push(MoveRun { moves: first..k, cycle: run_cycle.is_some() });
        }
        self.current = Some((k, source, cycle));
        cycle.is_some()
    }

    fn finish(mut self) -> Vec<MoveRun> {
        if let Some((first, _, cycle)) = self.current {
            self.runs.push(MoveRun { moves: first..self.moves, cycle: cycle.is_some() });
        }
        self.runs
    }
}

/// The motion blocks rewritten run by run, in path order (`add`), then settled (`finish`):
/// a block that runs several times is edited only if every run writes the same text.
///
/// Each run's blocks are written to text as they are made (`BlockWriter`); a block's first
/// run keeps its text, a later run's is only compared with it.
pub struct MotionBlocks<'a, 'src> {
    program: &'a Program<'src>,
    lowered: &'a Lowered,
    tools: &'a ToolTable,
    lookup: BlockLookup,
    /// The block looked up last (`BlockLookup::index_near`).
    near: usize,
    /// Per block, its arc words, read with the program's style (`ProgramTables::new`):
    /// an arc's form is then known without reading its block's words again, which are far
    /// apart in a long program's memory.
    arc_words: Vec<BlockArcWords>,
    radius_arcs: bool,
    /// The grid of the coordinates in force for the last run (they change rarely).
    grid: Option<(CoordinateMark, Grid)>,
    writer: MotionWriter<BlockWriter<'a, 'src>>,
    /// Each block replaced, with its first run's text, in path order.
    replacements: Vec<(usize, WrittenText)>,
    /// The same blocks, with their first run's moves.
    edited: Vec<EditedBlock>,
    /// Per block of the program, what its first run wrote.
    first_runs: Vec<FirstRun>,
    /// Blocks whose runs wrote different blocks: not edited.
    differing: HashSet<usize>,
    /// Blocks refused with a diagnostic already (one per block).
    refused: HashSet<usize>,
    /// Blocks whose moves are the turns of one variable-lead thread move, written as one.
    one_move_blocks: HashSet<usize>,
    diagnostics: Vec<Diagnostic>,
    /// Kept thread cycles' lead words, by call block (`cycles::thread_lead`).
    leads: HashMap<usize, cycles::LeadWords>,
    /// The model a thread move's lead is written for (none: leads are left as written).
    pub model: Option<&'a crate::error_model::ErrorModel>,
    /// The tolerance a finishing thread pass's helix is held to where it is written as
    /// thread blocks of their own leads (`thread_pieces`; none: one lead per pass).
    pub thread_tolerance_mm: Option<f64>,
    /// Per move, whether it is a thread move of a finishing pass (`thread_pieces::finishing_passes`).
    finishing: Vec<bool>,
    /// The lead words of the pieces after the first of a thread move written as pieces, by
    /// block (the first piece's are in `leads`).
    piece_leads: HashMap<usize, Vec<block::LeadWordList>>,
    /// Thread move blocks written as pieces after which the block's own `F` is written again
    /// (`BlockContext::restore_lead`).
    restore_lead: HashSet<usize>,
    /// Kept thread cycle calls that repeat the call before them, with the end its final pass
    /// runs to as written (`BlockContext::inherited`).
    inherited: HashMap<usize, GridPoint>,
    /// Kept single cycle calls whose taper changes, with the taper their cut needs
    /// (`BlockContext::taper`).
    tapers: HashMap<usize, i64>,
    /// Which feed moves keep clear of the finished part, where the check measures it
    /// (`thread_pass_plan`).
    pub clearance: Option<&'a crate::part::clearance::Clearance>,
    /// Blocks that run more than once (a subprogram's): none carries another's modal words.
    repeated: HashSet<usize>,
    /// Lone blocks of modal words the block after them may carry (`fold`).
    folds: Vec<Fold>,
    /// The block `block_text` writes carrying modal words, and which (`fold`).
    carrying: Option<(usize, Restore)>,
    /// How many of `folds` were handed to `next_moves_to_keep`.
    folds_told: usize,
}

/// A block that only puts back modal words (`back::motion::Restore`), written after `after`,
/// and the block the control runs next (`next`, its moves from `next_move`), which may
/// carry them instead (`MotionBlocks::fold`).
#[derive(Debug, Clone, Copy)]
struct Fold {
    after: RestoreAfter,
    next: usize,
    next_move: usize,
    restore: Restore,
}

/// How many blocks an `F` put back is carried past (rapids) to the block that reads it.
pub(crate) const FOLD_REACH: usize = 16;

/// Which block carries a fold's words.
enum Carrier {
    /// This block, making these moves.
    Block { block: usize, moves: Range<usize> },
    /// None: a block gives its own before any reads them.
    NoneNeeded,
    /// None can: the lone block stays.
    Nothing,
}

/// Where a block that only puts back modal words is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum RestoreAfter {
    /// Last of an expanded cycle's blocks, which replace its call block.
    Cycle(usize),
    /// Last of the blocks a motion block is written as.
    Block(usize),
}

impl RestoreAfter {
    fn block(self) -> usize {
        match self {
            RestoreAfter::Cycle(block) | RestoreAfter::Block(block) => block,
        }
    }
}

/// What a block's first run wrote.
#[derive(Debug, Clone, Copy, PartialEq)]
enum FirstRun {
    NotYet,
    /// Nothing: the block writes its move already.
    AsWritten,
    /// The blocks of `MotionBlocks::replacements` at this index.
    Replaced(usize),
}

/// What the rewrite of the motion blocks needs of the program alone: the block lookup, the
/// program's writing style (its arc form among it), and the per-block tables, made in one
/// pass over the program.
struct ProgramTables {
    lookup: BlockLookup,
    /// Per block, its arc words (`MotionBlocks::arc_words`).
    arc_words: Vec<BlockArcWords>,
    style: ProgramStyle,
    replacements: Vec<(usize, WrittenText)>,
    edited: Vec<EditedBlock>,
    first_runs: Vec<FirstRun>,
}

impl ProgramTables {
    fn new(program: &Program<'_>) -> ProgramTables {
        let blocks = program.blocks().len();
        // The block lookup and the style each need every block (and the style every word): one
        // pass reads a long program's blocks and words from memory once.
        let mut starts = Vec::with_capacity(blocks);
        let mut arc_words = Vec::with_capacity(blocks);
        let mut style = StyleTally::new(program);
        for (index, block) in program.blocks().iter().enumerate() {
            starts.push(block.span.start);
            arc_words.push(style.add_block(program, index, block));
        }
        ProgramTables {
            lookup: BlockLookup { starts },
            arc_words,
            style: style.style(),
            // At most one of each per block: huge pages where the program is long (written
            // front to back, they only take the memory they fill).
            replacements: crate::memory::huge_page_vec(blocks),
            edited: crate::memory::huge_page_vec(blocks),
            first_runs: {
                let mut first_runs = crate::memory::huge_page_vec(blocks);
                first_runs.resize(blocks, FirstRun::NotYet);
                first_runs
            },
        }
    }
}

impl<'a, 'src> MotionBlocks<'a, 'src> {
    pub fn new(program: &'a Program<'src>, lowered: &'a Lowered, tools: &'a ToolTable) -> MotionBlocks<'a, 'src> {
        let ProgramTables { lookup, arc_words, style, replacements, edited, first_runs } = ProgramTables::new(program);
        let radius_arcs = style.radius_arcs;
        MotionBlocks {
            program,
            lowered,
            tools,
            lookup,
            near: 0,
            arc_words,
            radius_arcs,
            grid: None,
            writer: MotionWriter::new(Codes::of(program), BlockWriter::with_style(program, style)),
            replacements,
            edited,
            first_runs,
            differing: HashSet::new(),
            refused: HashSet::new(),
            one_move_blocks: HashSet::new(),
            diagnostics: Vec::new(),
            leads: HashMap::new(),
            model: None,
            thread_tolerance_mm: None,
            finishing: thread_pieces::finishing_passes(&lowered.toolpath),
            piece_leads: HashMap::new(),
            restore_lead: HashSet::new(),
            inherited: HashMap::new(),
            tapers: HashMap::new(),
            clearance: None,
            repeated: HashSet::new(),
            folds: Vec::new(),
            carrying: None,
            folds_told: 0,
        }
    }

    /// Whether a move from move `from` on runs at the modal F (`semantic::modal_feed_read`).
    fn modal_feed_read_after(&self, from: usize) -> bool {
        crate::semantic::modal_feed_read(self.program, &self.lowered.toolpath.moves, from, |start| {
            self.lookup.index(start)
        })
    }

    /// Cut every thread pass into pieces where its lead error is not uniform along it, not
    /// only those that shape the finished thread.
    pub fn every_thread_pass(&mut self) {
        self.finishing.fill(true);
    }

    /// What cutting a finishing thread pass into pieces needs, where it is asked for.
    fn piece_settings(&self) -> Option<thread_pieces::PieceSettings<'_>> {
        Some(thread_pieces::PieceSettings {
            model: self.model?,
            tolerance_mm: self.thread_tolerance_mm?,
            finishing: &self.finishing,
        })
    }

    /// What can be written for each move (`MoveForms`), and the runs of moves
    /// (`RunSplitter`), in one pass over the moves.
    pub fn move_tables(&self) -> (MoveForms, Vec<MoveRun>) {
        let (program, lowered) = (self.program, self.lowered);
        let moves = &lowered.toolpath.moves;
        let mut writable = vec![false; moves.len()];
        let mut radius = vec![self.radius_arcs; moves.len()];
        for expansion in &lowered.expansions {
            // A thread cycle whose final pass its words can carry is planned like one that
            // can be written out (`finish` decides which it is).
            let expandable = cycles::expandable(program, lowered, expansion)
                || cycles::thread_final_pass(program, lowered, expansion).is_some()
                || !expansion.root.is_empty();
            for w in writable.get_mut(expansion.moves.clone()).unwrap_or_default() {
                *w = expandable;
            }
        }
        let mut runs = RunSplitter::new(lowered);
        let mut near = 0;
        for (k, m) in moves.iter().enumerate() {
            if runs.add(k, m.source) {
                continue;
            }
            let Some(b) = self.lookup.index_near(m.source.start, &mut near) else { continue };
            writable[k] = matches!(program.block(b).statement, Statement::Motion | Statement::ThreadMove);
            radius[k] = self.writes_radius(b, m.is_arc());
        }
        (MoveForms { writable, radius }, runs.finish())
    }

    /// `block::writes_radius` for `block`, from its arc words where they were read.
    fn writes_radius(&self, block: usize, is_arc: bool) -> bool {
        if !is_arc {
            return self.radius_arcs;
        }
        match self.arc_words.get(block) {
            Some(BlockArcWords::Radius) => true,
            Some(BlockArcWords::Centre) => false,
            Some(BlockArcWords::Neither) => self.radius_arcs,
            Some(BlockArcWords::NotRead) | None => block::writes_radius(self.program, block, is_arc, self.radius_arcs),
        }
    }

    /// The next run (after those given before it), with the plans of its moves; a cycle's
    /// run is the cycles' business (`finish`).
    pub fn add(&mut self, run: &MoveRun, plans: &[MovePlan]) {
        let (program, lowered) = (self.program, self.lowered);
        let Some(source) = lowered.toolpath.moves.get(run.moves.start).map(|m| m.source) else { return };
        if run.cycle {
            return;
        }
        let Some(block) = self.lookup.index_near(source.start, &mut self.near) else { return };
        if !matches!(program.block(block).statement, Statement::Motion | Statement::ThreadMove) {
            return;
        }
        // A thread move's lead word is written for the slide to cut the programmed lead, as
        // a kept thread cycle's is (`cycles::thread_lead`); a finishing pass whose lead error
        // is not uniform along it, as thread blocks each with its own (`thread_pieces`).
        let mut own_plans: Option<Vec<MovePlan>> = None;
        let threading = |k: &usize| lowered.toolpath.moves[*k].threading;
        if program.block(block).statement == Statement::ThreadMove
            && let Some(model) = self.model
            && run.moves.clone().filter(threading).nth(1).is_some()
            && let Some(pass) = run.moves.clone().rfind(threading)
        {
            // A variable lead (one move a turn): its lead and change words are written for
            // the whole pass (`cycles::thread_lead`), and no pieces of their own.
            if let Some((words, _)) = cycles::thread_lead(program, lowered, block, pass, model) {
                self.leads.insert(block, words);
            }
        } else if program.block(block).statement == Statement::ThreadMove
            && let Some(model) = self.model
            && let Some(pass) = run.moves.clone().find(threading)
        {
            let cut = self.piece_settings().zip(cycles::thread_move_lead(program, block)).and_then(
                |(settings, (at, programmed))| {
                    let plan = own_plans.as_deref().unwrap_or(plans).get(pass - run.moves.start)?;
                    let grid = Grid::new(&lowered.coordinates_at(pass));
                    let table = program.config().tables().thread_lead;
                    let cut =
                        thread_pieces::pieces(&lowered.toolpath, (pass, plan), settings, &table, &grid, programmed)?;
                    Some((at, programmed, cut))
                },
            );
            if let Some((at, programmed, cut)) = cut {
                // A piece at the `F` lead of the one before it writes none: `F` is modal (a
                // precise `E` is read from its own block only, `back::motion`).
                let mut in_force = block::LeadWordList::new();
                let mut words = cut.leads.iter().map(|lead| {
                    if lead.words == in_force && matches!(lead.words.as_slice(), [(Address::F, _)]) {
                        block::LeadWordList::new()
                    } else {
                        in_force.clone_from(&lead.words);
                        lead.words.clone()
                    }
                });
                if let Some(first) = words.next() {
                    self.leads.insert(block, cycles::LeadWords { at, words: first, change: None });
                }
                self.piece_leads.insert(block, words.collect());
                // The block's `F` is the modal F of the blocks after it: where the pieces leave
                // another in force and a later cut runs at it, the block's `F` is put back.
                let in_force_after = cut.leads.iter().rev().find_map(|lead| match lead.words.as_slice() {
                    [(Address::F, number)] => Some(number.to_f64()),
                    _ => None,
                });
                if programmed.address == Address::F
                    && in_force_after != Some(programmed.written)
                    && self.modal_feed_read_after(run.moves.end)
                {
                    self.restore_lead.insert(block);
                }
                let own = own_plans.get_or_insert_with(|| plans.to_vec());
                own[pass - run.moves.start] = cut.plan;
            } else if let Some((words, _)) = cycles::thread_lead(program, lowered, block, pass, model) {
                self.leads.insert(block, words);
            }
        }
        let plans = own_plans.as_deref().unwrap_or(plans);
        let text = self.block_text(block, run.moves.clone(), plans, None);
        self.settle(block, run.moves.clone(), text);
    }

    /// The first move of each block that may carry the modal words a block written since
    /// the last call leaves behind (`fold`), whose plans must be kept for it.
    pub fn next_moves_to_keep(&mut self) -> impl Iterator<Item = usize> + '_ {
        let new = self.folds.get(self.folds_told..).unwrap_or_default();
        self.folds_told = self.folds.len();
        new.iter().map(|f| f.next_move)
    }

    /// The moves `moves` of `block` that write a segment (not dwells or corners the control
    /// makes): none, one, or several, and whether any changes.
    fn written_moves(moves: Range<usize>, plans: &[MovePlan]) -> (Option<usize>, bool, bool) {
        let (mut single, mut several, mut any_change) = (None, false, false);
        for (index, plan) in moves.zip(plans).filter(|(_, p)| !p.segments.is_empty()) {
            several |= single.is_some();
            single.get_or_insert(index);
            any_change |= plan.changed;
        }
        (single, several, any_change)
    }

    /// The text `block` is written as for its moves `moves` (`plans` theirs), `None` where it
    /// writes them as it is or cannot carry them (refused with a diagnostic).
    /// `from`: the move whose start the block's words count from where it is not the move
    /// they name (a thread cycle call's incremental end words count from its start point).
    fn block_text(
        &mut self,
        block: usize,
        moves: Range<usize>,
        plans: &[MovePlan],
        from: Option<usize>,
    ) -> Option<WrittenText> {
        let (program, lowered, tools) = (self.program, self.lowered, self.tools);
        let first = moves.start;
        let (mut single, mut several, any_change) = Self::written_moves(moves.clone(), plans);
        // A variable lead's moves (one a turn) are the block's one thread move: its end words
        // carry the last one's end, its lead words the rest (`add`).
        let merged = several.then(|| Self::variable_lead_plan(lowered, moves.clone(), plans)).flatten();
        if let Some((last, _, _)) = merged {
            (single, several) = (Some(last), false);
            self.one_move_blocks.insert(block);
        }
        match single {
            None => None,
            Some(single) if !several => {
                let mark = lowered.coordinates_at(single);
                let grid = match self.grid {
                    Some((last, grid)) if last == mark => grid,
                    _ => self.grid.insert((mark, Grid::new(&mark))).1,
                };
                let context = block::BlockContext {
                    program,
                    codes: self.writer.codes,
                    block,
                    mark,
                    grid,
                    radius_arcs: self.radius_arcs,
                    tools,
                    lead: self.leads.get(&block),
                    piece_leads: self.piece_leads.get(&block).map_or(&[], Vec::as_slice),
                    restore_lead: self.restore_lead.contains(&block),
                    inherited: self.inherited.get(&block).copied(),
                    taper: self.tapers.get(&block).copied(),
                    carried: self.carrying.filter(|&(b, _)| b == block).map_or_else(Restore::default, |(_, r)| r),
                };
                let from = from.or(merged.as_ref().map(|&(_, from, _)| from)).unwrap_or(single);
                let contour_start = written::contour_start(&lowered.toolpath, from);
                let plan = match &merged {
                    Some((_, _, plan)) => Some(plan),
                    None => plans.get(single - first),
                };
                let (text, restore) = match (lowered.toolpath.moves.get(single), plan) {
                    (Some(m), Some(plan)) => context.rewrite(m, contour_start, plan, &mut self.writer)?,
                    _ => return None,
                };
                if !restore.is_none()
                    && self.carrying.is_none()
                    && let Some(next) = GivenNext::next_block(program, block, |_| false)
                {
                    self.folds.push(Fold { after: RestoreAfter::Block(block), next, next_move: moves.end, restore });
                }
                Some(text)
            }
            Some(_) if any_change => {
                if self.refused.insert(block) {
                    self.diagnostics.push(Diagnostic::error(
                        DiagnosticKind::CannotRewriteBlock {
                            reason: "it makes several moves (an automatic corner), which cannot each carry a correction",
                        },
                        program.block(block).span,
                    ));
                }
                None
            }
            Some(_) => None,
        }
    }

    /// Where the moves `moves` (planned as `plans`) are the turns of one variable-lead thread
    /// move (`cycles::pass_moves`), each planned as one line: the last, the first, and the
    /// plan of the one move they make, from the first's start to the last's end.
    fn variable_lead_plan(
        lowered: &Lowered,
        moves: Range<usize>,
        plans: &[MovePlan],
    ) -> Option<(usize, usize, MovePlan)> {
        let last = moves.end.checked_sub(1)?;
        let pass = cycles::pass_moves(lowered, last);
        if *pass.start() != moves.start || moves.len() < 2 {
            return None;
        }
        let one_line = |p: &MovePlan| p.segments.len() == 1 && p.jumps == 0 && !p.lead_in;
        if !plans.iter().take(moves.len()).all(one_line) {
            return None;
        }
        let (first_plan, last_plan) = (plans.first()?, plans.get(moves.len() - 1)?);
        let mut plan = last_plan.clone();
        plan.start = first_plan.start;
        plan.changed = plans.iter().take(moves.len()).any(|p| p.changed);
        Some((last, moves.start, plan))
    }

    /// Record one run of `block` (its moves `moves`) that writes `text`: a first run keeps
    /// it, a later one is only compared with the first.
    fn settle(&mut self, block: usize, moves: Range<usize>, text: Option<WrittenText>) {
        let Some(first_run) = self.first_runs.get_mut(block) else { return };
        if *first_run != FirstRun::NotYet {
            self.repeated.insert(block);
        }
        match (*first_run, text) {
            (FirstRun::NotYet, None) => *first_run = FirstRun::AsWritten,
            (FirstRun::NotYet, Some(text)) => {
                *first_run = FirstRun::Replaced(self.replacements.len());
                self.replacements.push((block, text));
                let one_move = self.one_move_blocks.contains(&block);
                self.edited.push(EditedBlock { block, moves, cycle: false, one_move });
            }
            (FirstRun::AsWritten, None) => {}
            (FirstRun::AsWritten, Some(text)) => {
                self.differing.insert(block);
                self.writer.out.discard(text);
            }
            (FirstRun::Replaced(k), text) => {
                // A later run: its text is only compared with the first run's, and dropped.
                let first_text = self.replacements.get(k).map(|&(_, t)| self.writer.out.text(t));
                if first_text != text.map(|t| self.writer.out.text(t)) {
                    self.differing.insert(block);
                }
                if let Some(text) = text {
                    self.writer.out.discard(text);
                }
            }
        }
    }

    /// Whether the profile blocks `blocks` (each with the moves a finishing cycle makes for
    /// it) can each carry their moves' correction as a motion block does, and if not, why:
    /// each writes at most one segment-writing move where any changes, none writes a take-up
    /// of the play (a backlash jump, a lead-in, a rapid in several segments), and
    /// none ran as a plain block. A take-up written into the profile would be a block of its
    /// own there, which a roughing cycle roughs as part of the shape (and a LAP thread's
    /// passes, which each approach the root on their own, never run).
    pub(super) fn profile_writable(
        &self,
        blocks: &[(usize, Range<usize>)],
        plans: &KeptPlans,
    ) -> Result<(), &'static str> {
        for (block, moves) in blocks {
            let Some(plans) = plans.get(moves.clone()) else { return Err("its profile was not planned") };
            let (_, several, any_change) = Self::written_moves(moves.clone(), plans);
            // A rapid's take-up is a segment of its own (`plan::one_move`), not a counted jump.
            let rapid = |k: usize| self.lowered.toolpath.moves.get(k).is_some_and(|m| m.motion == Motion::Rapid);
            let take_up = moves
                .clone()
                .zip(plans)
                .any(|(k, p)| p.changed && (p.jumps > 0 || p.lead_in || (rapid(k) && p.segments.len() > 1)));
            if take_up {
                return Err(PROFILE_TAKE_UP);
            }
            if !matches!(self.first_runs.get(*block), Some(FirstRun::NotYet))
                || (several && any_change)
                || !matches!(self.program.block(*block).statement, Statement::Motion)
            {
                return Err("a block of its profile makes several moves that change (an automatic corner), or also \
                            runs as a plain block: the profile cannot carry the correction");
            }
        }
        Ok(())
    }

    /// Whether the thread cycle called at `block` can carry the correction of its final
    /// pass `pass` in its own words: the pass is written as one segment, and the block has
    /// not been written for another run.
    pub(super) fn thread_writable(&self, block: usize, pass: usize, plans: &KeptPlans) -> bool {
        let Some([plan]) = plans.get(pass..pass + 1) else { return false };
        plan.segments.len() == 1 && !plan.lead_in && matches!(self.first_runs.get(block), Some(FirstRun::NotYet))
    }

    /// The plan the words of a kept thread cycle's final pass `pass` (of the call `e`) are
    /// written from: its plan, but at its depth as written (its diameter; its `Z` on a face
    /// thread) where the check measures the finished part and every thread move of the call
    /// keeps clear of it (`part::clearance`): an infeed pass that a deeper pass after it cuts
    /// away needs no micrometres (issue 25), and a `G92` pass of `X` alone stays as written.
    /// Its other words (the end of the thread, which a repeated call takes on) and its lead
    /// keep their correction.
    pub(super) fn thread_pass_plan(
        &self,
        e: &Expansion,
        (start, pass): (Xz, usize),
        plans: &KeptPlans,
    ) -> Option<MovePlan> {
        let [plan] = plans.get(pass..pass + 1)? else { return None };
        let mut plan = plan.clone();
        let moves = &self.lowered.toolpath.moves;
        let clear = self.clearance.filter(|clearance| {
            e.moves.clone().filter(|&k| moves.get(k).is_some_and(|m| m.threading)).all(|k| clearance.is_clear(k))
        });
        let nominal = moves.get(pass)?.contour;
        let end = plan.end();
        let face = cycles::face_thread(self.program, self.program.block(e.block));
        let off = if face { end.z - nominal.z } else { end.x - nominal.x };
        if let Some(clearance) = clear
            && off.abs() <= clearance.by_mm() / 2.0
        {
            let end = if face { Xz::new(end.x, nominal.z) } else { Xz::new(nominal.x, end.z) };
            let grid = Grid::new(&self.lowered.coordinates_at(pass));
            plan.changed = grid.point(end) != grid.point(nominal);
            plan.segments = smallvec::smallvec![Segment::Line { end }];
        }
        // A pass chamfered out: its end words lie the chamfer's length on.
        let offset = cycles::end_words_offset(self.program, self.lowered, e, pass);
        // Incremental end words count from the call's start point.
        plan.start = start;
        for segment in &mut plan.segments {
            if let Segment::Line { end } = segment {
                *end = Xz::new(end.x + offset.x, end.z + offset.z);
            }
        }
        Some(plan)
    }

    /// Write the words of the kept cycle called at `block` for its pass `pass`, from `plan`:
    /// a thread cycle's final pass (`thread_pass_plan`), a single turning or facing cycle's
    /// cut (`keep_singles`). `call`: the call's first move, where a thread call's incremental
    /// end words count from.
    pub(super) fn write_pass(&mut self, block: usize, (call, pass): (Option<usize>, usize), plan: &MovePlan) {
        let text = self.block_text(block, pass..pass + 1, std::slice::from_ref(plan), call);
        self.settle(block, pass..pass + 1, text);
    }

    /// Write the profile blocks `blocks` in place, each from the moves a finishing cycle makes
    /// for it (`profile_writable` said they can).
    pub(super) fn write_profile(&mut self, blocks: &[(usize, Range<usize>)], plans: &KeptPlans) {
        for (block, moves) in blocks {
            let Some(plans) = plans.get(moves.clone()) else { continue };
            let text = self.block_text(*block, moves.clone(), plans, None);
            self.settle(*block, moves.clone(), text);
        }
    }

    /// Where a block that only puts back modal words (`folds`) is followed by a plain motion
    /// block the control runs next, which runs once and can carry them, that block writes
    /// them (`N210 G01 X56.003` rather than `G01` and `N210 X56.003`) and the lone block
    /// goes. An `F` alone goes on to the first block that reads it, past rapids, which read
    /// none (`N100 G01 Z-2. F2.`, the rapids before it as written), and goes altogether where
    /// such a block gives its own. A block the operator may skip (`/`) keeps them apart: the
    /// words must be in force whichever runs.
    fn fold(&mut self, edits: &mut Edits, plans: &KeptPlans) {
        let mut folds = std::mem::take(&mut self.folds);
        folds.sort_by_key(|f| f.after.block());
        folds.dedup_by_key(|f| f.after);
        for fold in folds {
            let after = fold.after.block();
            if self.unwritable(after) || self.skippable(after) {
                continue;
            }
            match self.carrier(&fold) {
                Carrier::Block { block, moves } => {
                    let Some(next_plans) = plans.get(moves.clone()) else { continue };
                    self.carrying = Some((block, fold.restore));
                    let text = self.block_text(block, moves.clone(), next_plans, None);
                    self.carrying = None;
                    let Some(text) = text else { continue };
                    match self.first_runs.get(block).copied() {
                        Some(FirstRun::Replaced(k)) => self.replacements[k].1 = text,
                        Some(_) => {
                            self.first_runs[block] = FirstRun::Replaced(self.replacements.len());
                            self.replacements.push((block, text));
                            let one_move = self.one_move_blocks.contains(&block);
                            self.edited.push(EditedBlock { block, moves, cycle: false, one_move });
                        }
                        None => continue,
                    }
                }
                Carrier::NoneNeeded => {}
                Carrier::Nothing => continue,
            }
            match fold.after {
                RestoreAfter::Cycle(call) => edits.drop_last_block(call),
                RestoreAfter::Block(block) => {
                    if let Some(FirstRun::Replaced(k)) = self.first_runs.get(block).copied() {
                        self.replacements[k].1 = self.writer.out.without_last_block(self.replacements[k].1);
                    }
                }
            }
        }
    }

    /// The block that carries `fold`'s words, and its moves (`fold`).
    fn carrier(&self, fold: &Fold) -> Carrier {
        let (program, moves) = (self.program, &self.lowered.toolpath.moves);
        let restore = fold.restore;
        let feed_alone = restore.feed.is_some() && restore.motion.is_none() && restore.speed.is_none();
        let (mut block, mut first) = (fold.next, fold.next_move);
        for _ in 0..FOLD_REACH {
            if program.block(block).statement != Statement::Motion || self.skippable(block) {
                return Carrier::Nothing;
            }
            let source = program.block(block).span.start;
            let run = moves.get(first..).unwrap_or_default();
            let end = first + run.iter().take_while(|m| m.source.start == source && m.cycle.is_synthetic()).count();
            let Some(made) = moves.get(first..end).filter(|made| !made.is_empty()) else { return Carrier::Nothing };
            if !(feed_alone && made.iter().all(|m| m.motion == Motion::Rapid)) {
                if self.unwritable(block) || restore.motion.is_some_and(|kind| Kind::of(&made[0]) != kind) {
                    return Carrier::Nothing;
                }
                return Carrier::Block { block, moves: first..end };
            }
            if GivenNext::after(program, &self.writer.codes, block, |_| false).feed {
                return Carrier::NoneNeeded;
            }
            let Some(next) = GivenNext::next_block(program, block, |_| false) else { return Carrier::Nothing };
            (block, first) = (next, end);
        }
        Carrier::Nothing
    }

    /// Whether `block` may not be written for one run alone: it runs more than once, or
    /// was refused.
    fn unwritable(&self, block: usize) -> bool {
        self.repeated.contains(&block) || self.differing.contains(&block) || self.refused.contains(&block)
    }

    /// Whether the operator may skip `block` (`/`).
    fn skippable(&self, block: usize) -> bool {
        let words = self.program.words_of(self.program.block(block));
        words.iter().any(|w| matches!(w.kind, crate::syntax::WordKind::BlockDelete { .. }))
    }

    /// The edits of the motion blocks, after the cycles' in `out`.
    fn finish(mut self, out: &mut Rewrite, plans: &KeptPlans) {
        let program = self.program;
        self.fold(&mut out.edits, plans);
        out.diagnostics.append(&mut self.diagnostics);
        if !self.differing.is_empty() {
            let mut differing: Vec<usize> = self.differing.iter().copied().collect();
            differing.sort_unstable();
            for block in differing {
                if self.refused.insert(block) {
                    out.diagnostics.push(Diagnostic::error(
                        DiagnosticKind::CannotRewriteBlock {
                            reason: "it runs more than once, and its runs need different corrections",
                        },
                        program.block(block).span,
                    ));
                }
            }
            self.replacements.retain(|(block, _)| !self.differing.contains(block));
            self.edited.retain(|e| !self.differing.contains(&e.block));
        }
        // By block: they come in block order but where a block runs again (a subprogram's).
        if !self.replacements.is_sorted_by_key(|&(block, _)| block) {
            self.replacements.sort_unstable_by_key(|&(block, _)| block);
            self.edited.sort_unstable_by_key(|e| e.block);
        }
        if out.edited.is_empty() {
            out.edited = self.edited;
        } else {
            out.edited.append(&mut self.edited);
        }
        out.edits.replace_written(self.writer.out, self.replacements);
    }
}
