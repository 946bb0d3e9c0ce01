//! `turnpass verify ORIGINAL COMPENSATED`: does the compensated program cut the original's
//! nominal part on the modelled machine, and does it still do everything else the original
//! did?
//!
//! **Deviation.** Both programs are sampled and run through the model as written (the
//! forward model, `inverse::predict`, with the nominal path of each as its command). Each
//! predicted cutting point is measured against the ORIGINAL's nominal path, by its closest
//! point within a window of the original's path about the point's own nominal point
//! (`follow.rs`, which finds a compensated point's own point by following the original
//! along): the original's own prediction gives the error before compensation, the
//! compensated program's the error after.
//!
//! **Words.** Every word that is not motion — M codes, T, comments (save a provenance
//! comment, `provenance.rs`, which either program may carry or not), block-delete slashes,
//! program names and numbers — must appear in the compensated program in the same order
//! (other words may come between them: restored motion codes, expanded cycles' blocks).
//! Spindle speeds are compared as the sequence of speed changes, because an expanded cycle
//! writes `S` only where the speed changes.

use crate::diagnostic::Diagnostic;
use crate::error_model::ErrorModel;
use crate::pipeline::Settings;
use crate::semantic::nose_radius::ToolTable;
use crate::semantic::{Expansion, Machine};
use crate::source::Span;
use crate::syntax::{CodeLetter, Program, WordKind};
use crate::toolpath::compact::CompactPath;
use crate::toolpath::{Toolpath, ValidToolpath, Xz};

use super::deviation::{Figures, Tally};
use super::fit::{FitOptions, Strategy};
use crate::error_model::sampling::{PathSample, Sampling};

mod arc_steps;
mod follow;
mod knee;
pub mod lead;
mod measure;
mod part;
#[cfg(test)]
mod tests;

pub use part::{
    Feature, PartDeviation, PartFrom, PartPoint, Probe, ThreadFigures, ThreadForm, part_deviation,
    part_deviation_watched,
};

/// What `verify` measures: the finished part (by default, and `compensate`'s check), or the
/// passes one by one (`--passes`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Measure {
    /// The finished part each program cuts on the model against the original's nominal
    /// part, probed along the nominal surface normal (`part_deviation`).
    Part,
    /// Every predicted cutting point of every pass against the original's nominal path
    /// (`deviation`).
    Passes,
}

impl Measure {
    /// What the figures are, in words, for a table's heading.
    pub fn describe(self) -> &'static str {
        match self {
            Measure::Part => {
                "the finished part each program cuts on the model, probed along the surface normal of the nominal \
                 part at every point of its finished surface"
            }
            Measure::Passes => "every predicted cutting point of every pass, against the nominal path (pass by pass)",
        }
    }
}

use follow::Original;
use lead::LeadFigures;
use measure::measure;

/// The predicted deviation from the original's nominal path, before and after (by default,
/// nothing measured).
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Deviation {
    pub before: Figures,
    pub after: Figures,
    /// `None` where the original deviates by nothing (`Figures::improvement_percent`).
    pub improvement_percent: Option<f64>,
    /// Where the compensated program deviates most (none when nothing of it cuts).
    #[serde(skip)]
    pub worst: Option<Worst>,
    /// The thread passes' leads on the model (`lead.rs`), which the distance from the path
    /// does not see; none where the original cuts no thread.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lead: Option<LeadFigures>,
}

/// The largest deviation of a program's predicted path, and where it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Worst {
    pub deviation_mm: f64,
    /// The move of the original's path the point was measured against (its own point).
    pub original_move: usize,
    /// The move of the measured program the point lies on.
    pub measured_move: usize,
}

/// How closely `verify` samples a program on `model`: as `compensate` samples it
/// (`error_model::sampling`: one sample per line where every term of the model is affine
/// along it, a step from the second derivative of a curved term, every 0.254 mm with axis
/// tables, arcs at least every eighth of a turn and at their extremes), for the chord
/// between samples to follow the model within a tenth of half the least increment
/// (`increment_mm`), whatever tolerance the program was compensated to, over the farthest
/// any of `paths` goes from the origin (`CompactPath::reach`, the toolpath's). An arc's
/// steps are then cut as finely as the distance measured along it needs
/// (`verify/arc_steps.rs`).
pub fn sampling(model: &ErrorModel, increment_mm: f64, paths: &[&CompactPath]) -> Sampling {
    let reach = paths.iter().map(|t| t.reach()).fold(Xz::new(0.0, 0.0), |a, b| Xz::new(a.x.max(b.x), a.z.max(b.z)));
    let fit = FitOptions { strategy: Strategy::Auto, tolerance_mm: increment_mm / 2.0, step_mm: None };
    // The written program takes up its play where it does; verify follows it as written.
    let play = Xz::new(0.0, 0.0);
    Sampling { play, ..super::program::sampling(&fit, model, reach) }
}

/// `toolpath` compact (`toolpath::compact`), its tools' tips from `tools`: the form the
/// measure reads.
pub fn compact(toolpath: ValidToolpath<'_>, tools: &ToolTable) -> CompactPath {
    CompactPath::new(toolpath, |tool, offset| tools.lookup(tool, offset).1)
}

/// The moves of `toolpath` that need more samples than a measure holds
/// (`error_model::sampling::MAX_SAMPLES_PER_MOVE`), one error on each block that makes
/// some: `verify` and `report` refuse them before any is measured, as `compensate` and
/// `plot` refuse them before any is compensated.
pub fn oversampled(path: &CompactPath, sampling: &Sampling) -> Vec<Diagnostic> {
    super::program::oversampled_compact(path, sampling)
}

/// Predict both programs through `model`, sampled as `sampling` allows, and measure them
/// against `original`'s nominal path, along the path (each sample stands for the path from
/// the sample before it, so the figures do not depend on how closely the path was sampled).
/// The two are measured side by side.
pub fn deviation(
    original: ValidToolpath<'_>,
    compensated: ValidToolpath<'_>,
    tools: &ToolTable,
    model: &ErrorModel,
    sampling: &Sampling,
) -> Deviation {
    deviation_watched(original, compensated, tools, model, sampling, &|_, _| {})
}

/// `deviation`, every point measured also shown to `watch` as the two threads measure it (in
/// path order within each program, the two programs interleaved): how far the measure has
/// come, for a progress bar.
pub fn deviation_watched(
    original: ValidToolpath<'_>,
    compensated: ValidToolpath<'_>,
    tools: &ToolTable,
    model: &ErrorModel,
    sampling: &Sampling,
    watch: &(dyn Fn(Side, &Measured) + Sync),
) -> Deviation {
    let (original, compensated) = (compact(original, tools), compact(compensated, tools));
    deviation_of(&original, &compensated, model, sampling, watch)
}

/// `deviation_watched` of two programs held compact.
pub fn deviation_of(
    original: &CompactPath,
    compensated: &CompactPath,
    model: &ErrorModel,
    sampling: &Sampling,
    watch: &(dyn Fn(Side, &Measured) + Sync),
) -> Deviation {
    let path = Original::new(original);
    let side_by_side = original.len() >= crate::parallel::tuning().measure_moves;
    let ((after, worst, compensated_threads), (before, _, original_threads)) = crate::parallel::join_if(
        side_by_side,
        || measure(compensated, &path, model, sampling, Side::Compensated, &mut |side, m| watch(side, &m)),
        || measure(original, &path, model, sampling, Side::Original, &mut |side, m| watch(side, &m)),
    );
    let lead = lead::figures((original, &original_threads), (compensated, &compensated_threads));
    figures(before, after, worst, lead)
}

/// Which program a measured point is of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    Original,
    Compensated,
}

/// A predicted cutting point as `deviation` measured it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// The sample of its own program's toolpath it was predicted for.
    pub sample: PathSample,
    /// The index of that sample among the points its program's measure went through.
    pub sample_index: usize,
    /// Where the model puts the tool.
    pub predicted: Xz,
    /// Its distance from the original's nominal path (what the figures are made of), the
    /// closest point of that path and the original's move it lies on.
    pub distance_mm: f64,
    pub closest: Xz,
    pub original_move: usize,
}

/// `deviation`, every point measured also given to `each` (the original's points first,
/// then the compensated program's, each in path order): `deviation` and `report` measure
/// with this one computation, so the page's figures are `verify`'s.
pub fn deviation_each(
    original: &CompactPath,
    compensated: &CompactPath,
    model: &ErrorModel,
    sampling: &Sampling,
    mut each: impl FnMut(Side, Measured),
) -> Deviation {
    let path = Original::new(original);
    let (before, _, original_threads) = measure(original, &path, model, sampling, Side::Original, &mut each);
    let (after, worst, compensated_threads) =
        measure(compensated, &path, model, sampling, Side::Compensated, &mut each);
    let lead = lead::figures((original, &original_threads), (compensated, &compensated_threads));
    figures(before, after, worst, lead)
}

fn figures(before: Tally, after: Tally, worst: Option<Worst>, lead: Option<LeadFigures>) -> Deviation {
    let (before, after) = (before.figures(), after.figures());
    let improvement_percent = before.improvement_percent(&after);
    Deviation { before: before.rounded(), after: after.rounded(), improvement_percent, worst, lead }
}

/// What `check_written` found: the figures of the program about to be written, on the
/// measure asked for, and the first word or feed change its read-back lost.
#[derive(Debug, Clone)]
pub struct Written {
    pub deviation: Deviation,
    /// The finished-part measure's findings (none on the pass measure, and none where the
    /// part measure probed nothing and the passes were measured instead,
    /// `PartDeviation::probed_nothing`).
    pub part: Option<PartDeviation>,
    pub feed_change: Option<FeedChange>,
    pub lost: Option<MissingWord>,
    /// The original as it was measured (its moves' blocks place what the figures find).
    pub original: Held,
}

/// What `compensate` checks before it writes: `written`, the program it is about to write,
/// read back as the control reads it (through `pipeline::analyse`, with the settings the
/// original was read with) and measured against `original` by `turnpass verify`'s own
/// computation on `measure`: the finished part (`part_deviation` from what `from` gives:
/// no stock to assume it as `verify` does) or pass by pass (`deviation_of`), with `sampling`, so that
/// the figures it reports are the ones verify finds, with verify's checks of the feed and
/// spindle words (`check_feeds`) and of the other words of the original (`check_words`:
/// the first one lost). The original is held (`original`) only once the read-back is held:
/// a long program's caller lets the original's AST and moves go before the read-back and
/// holds it again here, so that no two programs are analysed at once.
/// `Err` holds what did not read back: a defect of turnpass, never of the program.
pub fn check_written(
    original: impl FnOnce() -> Result<Held, Vec<Diagnostic>>,
    written: &[u8],
    reading: &Settings,
    tools: &ToolTable,
    (model, measure, from): (&ErrorModel, Measure, PartFrom<'_>),
) -> Result<Written, Vec<Diagnostic>> {
    let read = match crate::pipeline::analyse(written, reading).ready() {
        Ok(read) => read,
        Err(analysed) => {
            let errors: Vec<Diagnostic> = analysed.diagnostics.iter().filter(|d| d.is_error()).cloned().collect();
            return Err(if errors.is_empty() { analysed.diagnostics } else { errors });
        }
    };
    // Its words taken, the read-back's AST goes, then its full moves once compact: the
    // measure holds the two compact paths.
    let written = Held::of(read, tools);
    let original = original()?;
    let machine = &reading.machine;
    let sampling = sampling(model, machine.increment * machine.scale(), &[&original.path, &written.path]);
    let oversampled = oversampled(&written.path, &sampling);
    if !oversampled.is_empty() {
        return Err(oversampled);
    }
    let lost = check_words(&original.words, &written.words).missing;
    let feed_change = check_feeds(&original.feeds, &written.feeds);
    let (original_path, written_path) = (&original.path, &written.path);
    match measure {
        Measure::Part => {
            let part = part_deviation((original_path, written_path), model, &sampling, machine, from);
            if part.probed_nothing() {
                let deviation = deviation_of(original_path, written_path, model, &sampling, &|_, _| {});
                return Ok(Written { deviation, part: None, feed_change, lost, original });
            }
            Ok(Written { deviation: part.deviation, part: Some(part), feed_change, lost, original })
        }
        Measure::Passes => {
            let deviation = deviation_of(original_path, written_path, model, &sampling, &|_, _| {});
            Ok(Written { deviation, part: None, feed_change, lost, original })
        }
    }
}

/// A program as `verify`'s checks hold it: its compact path (`compact`, each move with its
/// block), the words that must survive (`check_words`) and the runs of feed and spindle
/// words of its cuts (`check_feeds`). A long program's AST and full moves are let go once
/// these are taken, before the measure: `verify` and `compensate`'s check then hold each
/// program's text, or the lines of it, and these.
#[derive(Debug, Clone)]
pub struct Held {
    pub path: CompactPath,
    pub words: Words,
    pub feeds: FeedRuns,
}

impl Held {
    /// `program` held (its tools' tips from `tools`): its words taken, its AST let go, then its
    /// moves made compact and let go, so that no two of the three are held at once.
    pub fn of(program: crate::pipeline::Ready<'_>, tools: &ToolTable) -> Held {
        let crate::pipeline::Ready { parsed, lowered, .. } = program;
        let words = Words::of(&parsed.program, &lowered.expansions);
        drop(parsed);
        Held::from_toolpath(words, lowered.valid(), tools)
    }

    /// A program whose `words` are taken, its toolpath held compact.
    pub fn from_toolpath(words: Words, toolpath: ValidToolpath<'_>, tools: &ToolTable) -> Held {
        let feeds = feed_runs(&toolpath);
        Held { path: compact(toolpath, tools), words, feeds }
    }
}

/// The deviation `verify` allows by default: two least increments, mm.
pub fn default_bound_mm(machine: &Machine) -> f64 {
    2.0 * machine.increment * machine.scale()
}

/// A word of the original that the compensated program lost (or moved out of order).
#[derive(Debug, Clone, PartialEq)]
pub struct MissingWord {
    /// The word as the original writes it.
    pub text: String,
    pub span: Span,
}

/// The words kept in order, and the first that was not.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct WordCheck {
    pub checked: usize,
    pub missing: Option<MissingWord>,
}

/// A word that must survive, in a form that compares across programs: an M code by its
/// number, any other by its text.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kept {
    M(u16, u16),
    Text,
}

/// A word that must survive, with its span and its text as written.
#[derive(Debug, Clone, PartialEq)]
struct Word {
    kept: Kept,
    span: Span,
    text: Box<[u8]>,
}

impl Word {
    fn same(&self, other: &Word) -> bool {
        match (self.kept, other.kept) {
            (Kept::M(a, b), Kept::M(c, d)) => (a, b) == (c, d),
            (Kept::Text, Kept::Text) => self.text == other.text,
            _ => false,
        }
    }
}

/// The words of a program that must survive in order, and its speed changes, each with its
/// span and text (`check_words`), taken from its AST (`Words::of`) so that the AST need not
/// be held for the check.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Words {
    words: Vec<Word>,
    speeds: Vec<(f64, Word)>,
}

/// The blocks of `program` in the order their words run: each in its place, but for a block a
/// cycle consumes (a profile between P and Q, which the roughing cycle reads and the program
/// skips), whose words run where a cycle runs it as its own block (`Expansion::traced`: a
/// `G70` or LAP finishing pass), after that call's own words, once per such call. A
/// consumed profile no finishing cycle runs runs nowhere. Expanding a cycle, or keeping it,
/// writes the words where they run, so two programs that run the same words compare equal
/// in this order even where the text moved them.
fn run_order(program: &Program<'_>, expansions: &[Expansion]) -> Vec<usize> {
    let blocks = program.blocks().len();
    let mut skipped = vec![false; blocks];
    let mut traced: Vec<Vec<usize>> = vec![Vec::new(); blocks];
    for expansion in expansions {
        for &block in expansion.consumed.iter().filter(|&&b| Some(b) != expansion.setup) {
            if let Some(skip) = skipped.get_mut(block) {
                *skip = true;
            }
        }
        if let Some(calls) = traced.get_mut(expansion.block) {
            calls.extend(expansion.traced.iter().map(|&(_, block)| block));
        }
    }
    let mut order = Vec::with_capacity(blocks);
    for block in 0..blocks {
        if !skipped[block] {
            order.push(block);
        }
        order.extend(traced[block].iter().copied().filter(|&b| b < blocks));
    }
    order
}

impl Words {
    /// The words of `program` that must survive, in the order they run with the cycles its
    /// lowering expanded (`expansions`, see [`run_order`]).
    pub fn of(program: &Program<'_>, expansions: &[Expansion]) -> Words {
        let mut words = Vec::new();
        let mut speeds: Vec<(f64, Word)> = Vec::new();
        let word = |kept: Kept, span: Span| Word { kept, span, text: program.text(span).into() };
        for block in run_order(program, expansions) {
            let block = program.block(block);
            for w in program.words_of(block) {
                let kept = match w.kind {
                    WordKind::Code { letter: CodeLetter::M, code } => Some(Kept::M(code.major(), code.minor())),
                    // A provenance comment is `compensate`'s, not the program's.
                    WordKind::Comment(_) if super::provenance::is_mark(program.text(w.span)) => None,
                    WordKind::Comment(_) | WordKind::BlockDelete { .. } | WordKind::ProgramName | WordKind::Header => {
                        Some(Kept::Text)
                    }
                    WordKind::Number { address, .. } | WordKind::Expr { address, .. }
                        if address == crate::dialect::Address::T =>
                    {
                        Some(Kept::Text)
                    }
                    WordKind::Number { address, number } if address == crate::dialect::Address::S => {
                        let value = number.to_f64();
                        if speeds.last().is_none_or(|(s, _)| *s != value) {
                            speeds.push((value, word(Kept::Text, w.span)));
                        }
                        None
                    }
                    _ => None,
                };
                if let Some(kept) = kept {
                    words.push(word(kept, w.span));
                }
            }
        }
        Words { words, speeds }
    }
}

/// Check that `compensated` keeps the non-motion words of `original` in the order they run
/// (each program's words as [`Words::of`] takes them).
pub fn check_words(original: &Words, compensated: &Words) -> WordCheck {
    let checked = original.words.len() + original.speeds.len();
    let missing = |word: &Word| MissingWord { text: String::from_utf8_lossy(&word.text).into_owned(), span: word.span };
    let missing = first_missing(&original.words, &compensated.words, |w| w, Word::same)
        .map(missing)
        .or_else(|| first_missing(&original.speeds, &compensated.speeds, |(_, w)| w, |a, b| a.0 == b.0).map(missing));
    WordCheck { checked, missing }
}

/// The first item of `wanted` that is not found, in order, in `found` (its word, `word`).
fn first_missing<'a, T>(
    wanted: &'a [T],
    found: &[T],
    word: impl Fn(&'a T) -> &'a Word,
    same: impl Fn(&T, &T) -> bool,
) -> Option<&'a Word> {
    let mut k = 0;
    for item in wanted {
        match found[k..].iter().position(|f| same(item, f)) {
            Some(at) => k += at + 1,
            None => return Some(word(item)),
        }
    }
    None
}

/// A cut whose feed or spindle words the compensated program changed: the original's move
/// (its block) and the words each program cuts with there (`None`: it has no such cut).
#[derive(Debug, Clone, PartialEq)]
pub struct FeedChange {
    pub source: Span,
    pub original: Option<CutWords>,
    pub compensated: Option<CutWords>,
}

/// The feed and spindle words a cut runs with, as the program writes them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CutWords {
    pub feed: f64,
    pub per_revolution: bool,
    pub speed: f64,
    pub threading: bool,
}

/// The runs of equal feed and spindle words along a program's cutting moves, in execution
/// order, each with the block of its first move (`feed_runs`).
pub type FeedRuns = Vec<(CutWords, Span)>;

/// Whether two cuts run with the same words (a thread's lead is not compared, see
/// `check_feeds`).
fn same_cut(a: &CutWords, b: &CutWords) -> bool {
    a.threading == b.threading
        && a.per_revolution == b.per_revolution
        && a.speed == b.speed
        && (a.threading || a.feed == b.feed)
}

/// The runs of equal feed and spindle words along the cutting moves of `toolpath`, in
/// execution order; rapids and dwells carry no feed and are skipped.
pub fn feed_runs(toolpath: &Toolpath) -> FeedRuns {
    let mut runs: FeedRuns = Vec::new();
    for m in toolpath.moves.iter().filter(|m| m.cutting && m.motion != crate::toolpath::Motion::Dwell) {
        let words =
            CutWords { feed: m.f_word, per_revolution: m.per_revolution, speed: m.s_word, threading: m.threading };
        if runs.last().is_none_or(|(last, _)| !same_cut(last, &words)) {
            runs.push((words, m.source));
        }
    }
    runs
}

/// Check that `compensated` cuts with the feed and spindle words `original` cuts with, in the
/// order it runs them (each program's runs as `feed_runs` finds them). Compensation moves
/// end points, splits moves and writes take-ups, so moves are not matched one for one: the
/// runs of equal words along the cutting moves, in execution order, must be the same runs.
/// A thread's lead is not compared as a word: compensation writes the lead the slide needs
/// to cut the programmed one, and the lead measure (`lead.rs`) judges what it cuts.
pub fn check_feeds(wanted: &[(CutWords, Span)], found: &[(CutWords, Span)]) -> Option<FeedChange> {
    let differ = |k: usize| match (wanted.get(k), found.get(k)) {
        (Some(a), Some(b)) => !same_cut(&a.0, &b.0),
        (None, None) => false,
        _ => true,
    };
    let at = (0..wanted.len().max(found.len())).find(|&k| differ(k))?;
    // Past the end of the shorter list, the words its last cut runs with go on.
    let (original, compensated) = (wanted.get(at).or(wanted.last()), found.get(at).or(found.last()));
    Some(FeedChange {
        source: original.map_or(Span::SYNTHETIC, |r| r.1),
        original: original.map(|r| r.0),
        compensated: compensated.map(|r| r.0),
    })
}
