//! The part measure: the finished part each program cuts on the modelled machine, probed
//! along the nominal part's surface normal as a CMM probes it (issue 24, "verify judges the
//! part"). `verify` shows it by default and `compensate` checks what it writes with it.
//!
//! **Three parts.** The original program's nominal part is its toolpath cut from the stock
//! (`part::removal`, the same dexels `check` and `simulate` use). Each program's actual part
//! is the path the model predicts for it (`verify::measure::predicted`: the samples `verify`
//! measures, the knees of a take-up among them) cut from the same stock on the same rays: a
//! line between two predicted points, an arc (the programmed one moved) through two
//! predicted points of an arc with the mean of their radii about the programmed centre, and
//! a thread pass stamped every lead at the points the model puts the tool when the spindle
//! has turned a whole number of times (the lead of each piece scaled by its length on the
//! model over its length as programmed; a piece the model does not move, a take-up of
//! play, stands while the spindle turns its programmed stretch). Between two samples the model is followed as
//! `verify`'s sampling allows (a tenth of half the least increment). The part model sweeps
//! a line or an arc exactly, whole or in pieces, so the nominal part is cut along the
//! original's own moves and the parts differ by the model alone. Each program is cut a move
//! at a time as its points are predicted (`PieceCut`): the measure holds the three parts,
//! not the paths.
//!
//! **The probe.** Every end of an interval of material on a ray is a point of the nominal
//! surface with its outward normal `n` and the move that cut it. The actual part's edge of
//! the same kind (the near or the far end of material) nearest it on the same ray is where
//! the ray meets the actual surface: exact along the ray, at distance `t`, with its normal
//! `n'`. The probe along `n` meets the actual surface's tangent plane there at
//! `s = t (n'·r) / (n'·n)` (`r` the ray's direction): exact on a face or a diameter (`n`
//! along the ray) and wherever the actual surface is straight; on a surface curved with
//! radius `ρ` the tangent plane is off by at most `(0.71 t)² / 2ρ` (0.06 µm for a 10 µm
//! deviation on a 0.4 mm nose). A point is probed from the family of rays more nearly along
//! its normal (`|n·r| ≥ cos 45°`), so every stretch of surface is probed once, and stands for
//! the length of surface between two rays there (`spacing / |n·r|`): the RMS is along the
//! surface. `s > 0` is material left outside the nominal part, `s < 0` material removed
//! inside it (a gouge), whichever pass removed it.
//!
//! **Features.** A point belongs to the block of the original that cut it on the nominal
//! part; the stock's own faces, where the nominal part keeps them, are probed only where the
//! actual part cut them. A thread (the threading moves of one block) also gets its pitch
//! diameter (the diameter where the material fills half of a whole number of leads along
//! the rays along Z, interpolated between the two rays about it: exact on straight flanks)
//! and its lead (the slope of its grooves' centres on the ray nearest the pitch line).

use crate::compensation::fit::distance_to_chord;
use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::error_model::ErrorModel;
use crate::error_model::sampling::{SAMPLE_STEP_MM, Sampling};
use crate::geometry;
use crate::machine::StockSettings;
use crate::part::clearance::Finished;
use crate::part::dexel::{Dexels, STOCK, Spans};
use crate::part::removal::Removal;
use crate::part::{Part, Stock};
use crate::semantic::Machine;
use crate::source::Span;
use crate::toolpath::compact::CompactPath;
use crate::toolpath::{Motion, Move, Xz};

use super::super::deviation::{Figures, Tally};
use super::measure::predicted;
use super::{Deviation, Measured, Side, Worst};

/// What the part measure found (`part_deviation`).
#[derive(Debug, Clone, PartialEq)]
pub struct PartDeviation {
    /// The figures before (the original on the model) and after (the compensated program on
    /// the model); `worst.original_move` is the original's move that cut the worst point
    /// on the nominal part (`usize::MAX` for a face of the stock), `measured_move` the
    /// compensated program's move that cut it on the actual part.
    pub deviation: Deviation,
    /// The compensated part by surface feature, in the original's block order.
    pub features: Vec<Feature>,
    /// The deepest gouge of the compensated part (material removed inside the nominal part).
    pub gouge: Option<Probe>,
    pub threads: Vec<ThreadFigures>,
    /// The bar the three parts were cut from.
    pub stock: Stock,
    /// The rays' spacing, mm.
    pub spacing_mm: f64,
    /// The length of the nominal surface not probed, mm: at an edge of the actual part that
    /// the probe along the normal passes.
    pub unprobed_mm: f64,
    /// Where a part model stopped at its bound on work (the program, the block of its own
    /// text), none when all three ran to the end: the figures then cover only what was cut.
    pub stopped: Option<(Side, Span)>,
    /// Every probed point of the nominal surface, ray by ray (not along the surface), with
    /// the deviation of each actual part there: what the part figure draws.
    pub points: Vec<PartPoint>,
}

/// A point of the nominal finished surface and each actual part's deviation there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PartPoint {
    /// The point (IR frame, mm, X a radius) and the nominal part's outward unit normal there.
    pub at: Xz,
    pub normal: Xz,
    /// The original's move that cut it on the nominal part (none: a face of the stock).
    pub original_move: Option<usize>,
    /// The signed deviation along the normal (+ material left, − removed inside the nominal
    /// part) of the original's part (before) and of the compensated program's (after), mm;
    /// none where that part was not probed there (at an edge of it the probe passes, or a
    /// face of the stock it did not cut).
    pub before_mm: Option<f64>,
    pub after_mm: Option<f64>,
}

impl PartDeviation {
    /// Whether no point of a finished surface was probed on either part: a program that
    /// cuts no bar (a ball bar's circle in the air), or a bar that leaves no surface the
    /// probe reaches. Such a measure says nothing of the program, and `verify` and
    /// `compensate` measure pass by pass instead.
    pub fn probed_nothing(&self) -> bool {
        self.deviation.before.points == 0 && self.deviation.after.points == 0
    }

    /// The error of a measure that did not cover the whole part (`stopped`), on the
    /// original's block where its part model stopped (the start of the text where the
    /// compensated program's did).
    pub fn incomplete(&self) -> Option<Diagnostic> {
        let (side, block) = self.stopped?;
        let kind = DiagnosticKind::PartModelStopped {
            rays: crate::part::removal::MAX_RAY_VISITS,
            stamps: crate::part::removal::MAX_STAMPS_PER_MOVE,
        };
        Some(Diagnostic::error(kind, if side == Side::Original { block } else { Span::new(0, 0) }))
    }
}

/// One probed point of the actual part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Probe {
    /// The point of the nominal surface, IR frame (mm, X a radius), and the nominal part's
    /// outward unit normal there.
    pub at: Xz,
    pub normal: Xz,
    /// The distance to the actual surface along the nominal normal, mm: positive where
    /// material is left, negative inside the nominal part.
    pub signed_mm: f64,
    /// The measured program's move that cut the actual surface there (none: the stock's face).
    pub cut_by: Option<usize>,
}

/// The compensated part's deviation on the surface one block of the original cut.
#[derive(Debug, Clone, PartialEq)]
pub struct Feature {
    /// The original's block (`Span::SYNTHETIC` for the stock's faces).
    pub block: Span,
    pub figures: Figures,
    pub worst: Probe,
}

/// A thread's pitch diameter and lead on the nominal part and on each actual part.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ThreadFigures {
    /// The first and the last block of its passes, in the original.
    #[serde(skip)]
    pub block: Span,
    #[serde(skip)]
    pub last_block: Span,
    /// The lead the program gives, mm.
    pub programmed_lead_mm: f64,
    /// How many leads the measures span.
    pub leads: usize,
    pub nominal: ThreadForm,
    pub before: Option<ThreadForm>,
    pub after: Option<ThreadForm>,
}

/// A thread as measured on one part: pitch diameter (a diameter, mm) and lead (mm).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ThreadForm {
    pub pitch_diameter_mm: f64,
    pub lead_mm: Option<f64>,
}

/// The part measure of `compensated` against `original` on `model` (see the module
/// documentation), both held compact (`verify::compact`), sampled as `sampling` allows, on
/// `machine`'s tools from what `from` gives.
pub fn part_deviation(
    programs: (&CompactPath, &CompactPath),
    model: &ErrorModel,
    sampling: &Sampling,
    machine: &Machine,
    from: PartFrom<'_>,
) -> PartDeviation {
    part_deviation_watched(programs, model, sampling, (machine, from), &|_, _| {})
}

/// What the part measure's parts are cut from: the stock (none: the bar `Stock::assumed`
/// takes for the original), and the original's nominal part where it is cut already from
/// that stock (`part::clearance`, which `compensate` cuts before it compensates).
#[derive(Debug, Clone, Copy, Default)]
pub struct PartFrom<'a> {
    pub stock: Option<&'a StockSettings>,
    pub finished: Option<&'a Finished>,
}

/// `part_deviation`, every predicted point shown to `watch` as the two programs are
/// predicted (`Measured::predicted` only): how far the measure has come, for a progress bar.
pub fn part_deviation_watched(
    (original, compensated): (&CompactPath, &CompactPath),
    model: &ErrorModel,
    sampling: &Sampling,
    (machine, from): (&Machine, PartFrom<'_>),
    watch: &(dyn Fn(Side, &Measured) + Sync),
) -> PartDeviation {
    // The points the model puts the tool at are predicted along the compact paths, as the
    // pass measure predicts them, and the parts are cut along their moves' pieces
    // (`CompactPath::as_move`).
    let (original_compact, compensated_compact) = (original, compensated);
    let stock = match from.stock {
        Some(settings) => Some(Stock::from_settings(settings, machine)),
        None => Stock::assumed_from((0..original.len()).filter_map(|index| {
            let m = original.moves()[index];
            let cuts = m.cutting && !matches!(m.motion, Motion::Rapid | Motion::Dwell);
            cuts.then(|| (original.start_of(index), m.end))
        })),
    };
    let Some(stock) = stock else {
        let deviation = Deviation::default();
        let stock = Stock { outer: 0.0, bore: 0.0, front: 0.0, back: 0.0, assumed: true };
        return PartDeviation {
            deviation,
            features: Vec::new(),
            gouge: None,
            threads: Vec::new(),
            stock,
            spacing_mm: 0.0,
            unprobed_mm: 0.0,
            stopped: None,
            points: Vec::new(),
        };
    };
    // The three parts on the same rays: the spacing follows the original's moves. The
    // nominal part is the original's moves cut as programmed (the part `check` finds); each
    // actual part is its program cut in pieces between the points the model puts the tool
    // at, a move at a time as the points are predicted, so that no path of pieces is held.
    let rays_for = original.len();
    let block =
        |toolpath: &CompactPath, k: usize| if k < toolpath.len() { toolpath.source(k) } else { Span::new(0, 0) };
    let original_side = || {
        // The same cut, where it is made already: the same moves from the same stock on the
        // same rays.
        let given = from.finished.filter(|f| f.stock == stock && f.moves == rays_for);
        let (nominal, nominal_stop) = match given {
            Some(finished) => (finished.dexels.clone(), None),
            None => cut(original, stock, machine, rays_for),
        };
        let mut before = PieceCut::new(original, stock, machine, rays_for);
        let threads = predicted(original_compact, model, sampling, Side::Original, &mut |side, measured| {
            watch(side, &measured);
            before.push(Point::of(&measured));
        });
        let (before, before_stop) = before.finish();
        (nominal, before, nominal_stop.or(before_stop), threads)
    };
    let compensated_side = || {
        let mut after = PieceCut::new(compensated, stock, machine, rays_for);
        let threads = predicted(compensated_compact, model, sampling, Side::Compensated, &mut |side, measured| {
            watch(side, &measured);
            after.push(Point::of(&measured));
        });
        let (after, after_stop) = after.finish();
        (after, after_stop, threads)
    };
    let ((after, after_stop, after_threads), (nominal, before, before_stop, before_threads)) = crate::parallel::join_if(
        original.len() >= crate::parallel::tuning().measure_moves,
        compensated_side,
        original_side,
    );
    let stopped = before_stop
        .map(|k| (Side::Original, block(original, k)))
        .or(after_stop.map(|k| (Side::Compensated, block(compensated, k))));
    let separated_at = Part::new(nominal.clone(), stock).separated_at;
    let probe_before = probe(&nominal, &before, separated_at);
    let probe_after = probe(&nominal, &after, separated_at);
    let unprobed_mm = probe_after.iter().filter(|p| p.1.is_none() && p.2 < 0.0).map(|p| -p.2).sum::<f64>();
    let (probe_before, probe_after): (Vec<_>, Vec<_>) = (
        probe_before.into_iter().filter(|p| p.2 > 0.0).collect(),
        probe_after.into_iter().filter(|p| p.2 > 0.0).collect(),
    );
    let points = points(&probe_before, &probe_after);
    let tally = |probes: &[Probed]| {
        let mut tally = Tally::default();
        for (p, _, weight, _) in probes {
            tally.add_along(p.signed_mm.abs(), None, weight / SAMPLE_STEP_MM);
        }
        tally.figures()
    };
    let (before_figures, after_figures) = (tally(&probe_before), tally(&probe_after));
    let worst =
        probe_after.iter().max_by(|a, b| a.0.signed_mm.abs().total_cmp(&b.0.signed_mm.abs())).map(|(p, by, ..)| {
            Worst {
                deviation_mm: p.signed_mm.abs(),
                original_move: by.unwrap_or(usize::MAX),
                measured_move: p.cut_by.unwrap_or(usize::MAX),
            }
        });
    let gouge = probe_after
        .iter()
        .map(|p| p.0)
        .filter(|p| p.signed_mm < -super::super::deviation::NOTHING_MM)
        .min_by(|a, b| a.signed_mm.total_cmp(&b.signed_mm));
    let features = features(original, &probe_after);
    let threads = threads(original, &nominal, &before, &after, stock);
    let improvement_percent = before_figures.improvement_percent(&after_figures);
    let deviation = Deviation {
        before: before_figures.rounded(),
        after: after_figures.rounded(),
        improvement_percent,
        worst: worst.map(|w| Worst { deviation_mm: super::super::deviation::nm(w.deviation_mm), ..w }),
        // The passes' leads from the same predicted points, as the pass measure gives them.
        lead: super::lead::figures((original_compact, &before_threads), (compensated_compact, &after_threads)),
    };
    PartDeviation {
        deviation,
        features,
        gouge,
        threads,
        stock,
        spacing_mm: nominal.spacing,
        unprobed_mm,
        stopped,
        points,
    }
}

/// The probed points of both actual parts, one per point of the nominal surface either
/// probed, in the order the probes came (`probe` visits the nominal part's edges in one order
/// whatever part it probes, and numbers each it considers).
fn points(before: &[Probed], after: &[Probed]) -> Vec<PartPoint> {
    let mut out = Vec::with_capacity(before.len().max(after.len()));
    let (mut b, mut a) = (before.iter().peekable(), after.iter().peekable());
    loop {
        let next = match (b.peek(), a.peek()) {
            (None, None) => break,
            (Some(x), Some(y)) if x.3 == y.3 => (b.next(), a.next()),
            (Some(x), Some(y)) if x.3 < y.3 => (b.next(), None),
            (Some(_), None) => (b.next(), None),
            _ => (None, a.next()),
        };
        let Some(&(p, by, ..)) = next.0.or(next.1) else { break };
        out.push(PartPoint {
            at: p.at,
            normal: p.normal,
            original_move: by,
            before_mm: next.0.map(|q| q.0.signed_mm),
            after_mm: next.1.map(|q| q.0.signed_mm),
        });
    }
    out
}

/// A probe, the original's move that cut its point on the nominal part, the length of
/// surface it stands for (mm; negative for a point not probed), and the number of the
/// nominal edge it is (the same on every part probed).
type Probed = (Probe, Option<usize>, f64, usize);

/// `toolpath` cut from `stock` on the rays a program of `rays_for` moves gets; the move
/// where the model stopped at its bound.
fn cut(toolpath: &CompactPath, stock: Stock, machine: &Machine, rays_for: usize) -> (Dexels, Option<usize>) {
    let mut removal = Removal::new(stock, machine, rays_for);
    for index in 0..toolpath.len() {
        let stepped = toolpath.as_move(index).and_then(|m| removal.shape_move(toolpath.start_of(index), &m, index));
        if stepped.is_none() {
            return (removal.dexels, Some(index));
        }
    }
    // A program that ends in a thread pass leaves its form at the pass's end.
    let stopped = removal.end_thread().is_none().then(|| toolpath.len().saturating_sub(1));
    (removal.dexels, stopped)
}

/// A point of a program's path as `measure::predicted` gives it: its move, where along it, the
/// point as programmed and as the model puts it.
#[derive(Clone, Copy)]
struct Point {
    move_index: usize,
    param: f64,
    nominal: Xz,
    predicted: Xz,
}

impl Point {
    fn of(measured: &Measured) -> Point {
        let s = measured.sample;
        Point { move_index: s.move_index, param: s.param, nominal: s.nominal, predicted: measured.predicted }
    }
}

/// A program cut from the stock in pieces that end at the points the model puts the tool at
/// (`measure::predicted`), a move at a time as its points come: a line between two
/// predicted points, an arc (the programmed one moved) through two predicted points of an
/// arc with the mean of their radii about the programmed centre, and a thread pass whose
/// pieces each run at the lead that takes the spindle through the turns the piece's
/// programmed stretch takes (the piece's length on the model over its length as
/// programmed), so that a stamp falls where the model puts the tool at each whole turn;
/// a piece the model does not move stands while the spindle turns (`Removal::stand_turning`).
/// Each piece's cuts are recorded as its move's.
struct PieceCut<'a> {
    toolpath: &'a CompactPath,
    removal: Removal<'a>,
    /// The point before: where the next piece starts on the model, as programmed, its move
    /// and where along it.
    last: (Xz, Xz, usize, f64),
    /// The points of the move under way, and its pieces.
    points: Vec<Point>,
    pieces: Vec<Move>,
    stopped: Option<usize>,
}

impl<'a> PieceCut<'a> {
    fn new(toolpath: &'a CompactPath, stock: Stock, machine: &'a Machine, rays_for: usize) -> PieceCut<'a> {
        PieceCut {
            toolpath,
            removal: Removal::new(stock, machine, rays_for),
            last: (toolpath.start, toolpath.start, usize::MAX, 0.0),
            points: Vec::new(),
            pieces: Vec::new(),
            stopped: None,
        }
    }

    fn push(&mut self, point: Point) {
        if self.stopped.is_some() {
            return;
        }
        if self.points.last().is_some_and(|p| p.move_index != point.move_index) {
            self.flush();
        }
        self.points.push(point);
    }

    /// Cut the pieces of the move under way.
    fn flush(&mut self) {
        let Some(index) = self.points.first().map(|p| p.move_index) else { return };
        let Some(m) = self.toolpath.as_move(index) else {
            self.points.clear();
            return;
        };
        if m.motion == Motion::Rapid {
            // A rapid removes nothing (`Removal::shape_move`): it is stepped whole, without
            // its pieces, and the next piece starts at its last point.
            let start = self.last.0;
            if let Some(p) = self.points.last() {
                self.last = (p.predicted, p.nominal, p.move_index, p.param);
            }
            self.points.clear();
            if self.removal.shape_move(start, &m, index).is_none() {
                self.stopped = Some(index);
            }
            return;
        }
        let start = self.last.0;
        self.pieces.clear();
        // Each piece's length as programmed, for a thread pass's lead.
        let mut programmed = Vec::new();
        for k in 0..self.points.len() {
            let point = self.points[k];
            let from_nominal = self.last.1;
            if let Some(piece) = piece(self.toolpath, &mut self.last, &point) {
                self.pieces.push(piece);
                if m.threading {
                    programmed.push(from_nominal.distance(point.nominal));
                }
            }
        }
        self.points.clear();
        if m.threading {
            // A piece with no programmed stretch (the model's step at a corner) runs at the
            // whole move's lead on the model.
            let (mut from, mut length) = (start, 0.0);
            for piece in &self.pieces {
                if piece.threading {
                    length += from.distance(piece.end);
                }
                from = piece.end;
            }
            let whole = self.toolpath.start_of(index).distance(m.end);
            let mut from = start;
            for (piece, &programmed) in self.pieces.iter_mut().zip(&programmed) {
                let on_model = from.distance(piece.end);
                from = piece.end;
                if programmed > 1e-9 && on_model > 0.0 {
                    piece.feed = m.feed * (on_model / programmed);
                } else if whole > 0.0 && length > 0.0 {
                    piece.feed = m.feed * (length / whole);
                }
            }
        }
        if !m.threading {
            merge_straight_runs(start, &mut self.pieces);
        }
        // A threading piece with a programmed stretch that the model does not move (a
        // take-up of play) stands while the spindle turns the stretch's turns.
        let lead = if m.threading && m.rpm > 0.0 { m.feed / m.rpm } else { 0.0 };
        let mut from = start;
        for (k, piece) in self.pieces.iter().enumerate() {
            let stands = programmed.get(k).filter(|&&p| p > 1e-9 && lead > 0.0 && piece.threading && from == piece.end);
            let done = match stands {
                Some(&stretch) => self.removal.stand_turning(from, piece, index, stretch / lead),
                None => self.removal.shape_move(from, piece, index),
            };
            if done.is_none() {
                self.stopped = Some(index);
                return;
            }
            from = piece.end;
        }
    }

    /// The part, and the move where the model stopped at its bound.
    fn finish(mut self) -> (Dexels, Option<usize>) {
        if self.stopped.is_none() {
            self.flush();
        }
        // A program that ends in a thread pass leaves its form at the pass's end.
        if self.stopped.is_none() && self.removal.end_thread().is_none() {
            self.stopped = Some(self.toolpath.len().saturating_sub(1));
        }
        (self.removal.dexels, self.stopped)
    }
}

/// The piece of `toolpath` that ends at `point` as the model puts it, from the point before
/// (`last`, which becomes `point`); none for a point of no move.
fn piece(toolpath: &CompactPath, last: &mut (Xz, Xz, usize, f64), point: &Point) -> Option<Move> {
    let m = toolpath.as_move(point.move_index)?;
    let (from, from_nominal, from_move, from_param) = *last;
    let end = point.predicted;
    *last = (end, point.nominal, point.move_index, point.param);
    let mut piece = m;
    piece.end = end;
    // A piece along its move (from its start, or from the point before on it); else the
    // model's step at a corner, where the point does not move along the path.
    let along = point.param > 0.0 && (from_move != point.move_index || from_param < point.param);
    if m.is_arc() {
        let ccw = m.motion == Motion::Ccw;
        let centre = arc_centre(from, end, m.centre).filter(|&centre| {
            // The piece turns as the programmed piece does (a piece of a few nanometres has
            // no direction to take its centre from: a line).
            let turns = geometry::sweep(from, end, centre, ccw);
            let programmed = geometry::sweep(from_nominal, point.nominal, m.centre, ccw);
            along && from.distance(end) > ARC_PIECE_MM && (turns - programmed).abs() <= ARC_TURN
        });
        match centre {
            Some(centre) => piece.centre = centre,
            None => {
                piece.motion = Motion::Feed;
                piece.centre = Xz::new(f64::NAN, f64::NAN);
            }
        }
    }
    if m.threading && !(from_nominal.distance(point.nominal) > 0.0 && along) {
        // A step of the model at a corner: no thread is cut along it.
        piece.threading = false;
    }
    Some(piece)
}

/// How far a predicted point may lie from the straight piece that replaces the two line
/// pieces it joins (mm): a thousandth of the nanometre the figures are given to.
const STRAIGHT_MM: f64 = 1e-9;

/// Consecutive line pieces (from `start`) whose joints lie within [`STRAIGHT_MM`] of the
/// segment from the first one's start to the last one's end, joined into that one piece.
/// A tool swept along a path whose every point lies within `d` of a segment, from one end
/// of it to the other, covers the tool swept along the segment to within `d` (the
/// Hausdorff distance of the two paths bounds that of their sweeps by a convex tool), so
/// the part moves by less than the figures show. A line move is predicted at several
/// points, which a model of position-dependent terms keeps on one line to the rounding of
/// f64, and each piece sweeps the whole insert across the rays: one sweep in place of
/// several spares most of that work. A knee of a backlash take-up is not straight, nor is
/// a move that warm-up growth bends by more than the bound, and those stay in pieces.
fn merge_straight_runs(start: Xz, pieces: &mut Vec<Move>) {
    if pieces.len() < 2 {
        return;
    }
    let line = |p: &Move| !p.is_arc() && !p.threading;
    let mut out: Vec<Move> = Vec::with_capacity(pieces.len());
    // The start of the run of line pieces the last piece of `out` ends, and its joints.
    let mut run_start = start;
    let mut joints: smallvec::SmallVec<[Xz; 8]> = smallvec::SmallVec::new();
    let mut from = start;
    for piece in pieces.drain(..) {
        let joinable = out.last().is_some_and(|last| {
            line(last)
                && line(&piece)
                && last.motion == piece.motion
                && joints
                    .iter()
                    .chain(std::iter::once(&from))
                    .all(|&p| distance_to_chord(p, run_start, piece.end) <= STRAIGHT_MM)
        });
        let end = piece.end;
        if joinable {
            joints.push(from);
            if let Some(last) = out.last_mut() {
                last.end = end;
            }
        } else {
            run_start = from;
            joints.clear();
            out.push(piece);
        }
        from = end;
    }
    *pieces = out;
}

/// A piece of an arc shorter than this (mm) is cut as a line: its chord gives no direction.
const ARC_PIECE_MM: f64 = 1e-6;
/// The most a piece of an arc on the model may turn other than the programmed piece
/// (radians); past it, the piece is cut as a line.
const ARC_TURN: f64 = 0.01;

/// The centre of the arc from `a` to `b` about a centre near `programmed` (on its side of
/// the chord: a piece of an arc is far less than half a turn), with the mean of the two ends' distances from `programmed` as its radius: the
/// programmed arc moved as the model moves its ends. None where the chord is longer than
/// the diameter (no such arc).
fn arc_centre(a: Xz, b: Xz, programmed: Xz) -> Option<Xz> {
    let radius = (a.distance(programmed) + b.distance(programmed)) / 2.0;
    let chord = a.distance(b);
    if chord.is_nan() || chord <= 0.0 || chord > 2.0 * radius {
        return None;
    }
    let mid = Xz::new((a.x + b.x) / 2.0, (a.z + b.z) / 2.0);
    let half = chord / 2.0;
    let h = (radius * radius - half * half).max(0.0).sqrt();
    // The unit normal of the chord, toward the side the programmed centre is on.
    let mut n = Xz::new(-(b.z - a.z) / chord, (b.x - a.x) / chord);
    if n.x * (programmed.x - mid.x) + n.z * (programmed.z - mid.z) < 0.0 {
        n = Xz::new(-n.x, -n.z);
    }
    Some(Xz::new(mid.x + n.x * h, mid.z + n.z * h))
}

/// Each point of `nominal`'s surface probed on `actual`, from the family more nearly along
/// its normal, in front of a part-off at `separated_at`: the probe, the original's move that
/// cut the point on the nominal part, and the length of surface it stands for (mm).
fn probe(nominal: &Dexels, actual: &Dexels, separated_at: Option<f64>) -> Vec<Probed> {
    let mut out = Vec::new();
    let mut candidate = 0;
    for along_z in [true, false] {
        let (rays, actual_rays) =
            if along_z { (&nominal.along_z, &actual.along_z) } else { (&nominal.along_x, &actual.along_x) };
        for (index, spans) in rays.iter().enumerate() {
            let line = nominal.line(along_z, index);
            let found: &Spans = &actual_rays[index];
            for span in spans {
                for (edge, high) in [(&span.lo, false), (&span.hi, true)] {
                    let normal = edge.normal();
                    // The component of the normal along the ray.
                    let along = if along_z { normal.z } else { normal.x };
                    let steep = if along_z {
                        along.abs() >= std::f64::consts::FRAC_1_SQRT_2
                    } else {
                        along.abs() > std::f64::consts::FRAC_1_SQRT_2
                    };
                    // The axis, the low end of a solid part's rays along X, is no surface; nor
                    // is the bar's back end, the low end of its rays along Z where no move cut
                    // it: the bar goes on into the chuck there.
                    let axis = !along_z && !high && edge.by == STOCK && edge.at <= 1e-12;
                    let back = along_z && !high && edge.by == STOCK;
                    if !steep || axis || back {
                        continue;
                    }
                    let at = line.point(edge.at);
                    if separated_at.is_some_and(|z| at.z < z) {
                        continue;
                    }
                    candidate += 1;
                    let nearest = found
                        .iter()
                        .map(|s| if high { s.hi } else { s.lo })
                        .min_by(|a, b| (a.at - edge.at).abs().total_cmp(&(b.at - edge.at).abs()));
                    let (signed_mm, cut_by) = match nearest {
                        Some(actual_edge) => {
                            let t = actual_edge.at - edge.at;
                            let actual_normal = actual_edge.normal();
                            let along_actual = if along_z { actual_normal.z } else { actual_normal.x };
                            let facing = actual_normal.x * normal.x + actual_normal.z * normal.z;
                            // The tangent plane of the actual surface where the ray meets it;
                            // the nominal one where the two face apart (another feature).
                            let s = if facing > 0.5 { t * along_actual / facing } else { t * along };
                            let by = (actual_edge.by != STOCK).then_some(actual_edge.by as usize);
                            (s, by)
                        }
                        // No material left on the ray: all of it is gone.
                        None => (-(span.hi.at - span.lo.at) * along.abs(), None),
                    };
                    // A probe that passes an edge the model moved (a point a few µm from a
                    // corner) meets a surface beyond it: the point is then as far from the
                    // actual part as its nearest surface. Where that is less than half as far
                    // as the probe went, the point is at an edge of the actual part, where a
                    // probe along the normal measures nothing, and is not probed.
                    let within = signed_mm.abs().min(NEAREST_WITHIN_MM);
                    let nearest_mm =
                        if signed_mm.abs() > NEAREST_FROM_MM { nearest_surface(actual, at, within) } else { within };
                    let at_edge = nearest_mm < signed_mm.abs() / 2.0;
                    let signed_mm = if nearest_mm < within { signed_mm.signum() * nearest_mm } else { signed_mm };
                    let nominal_by = (edge.by != STOCK).then_some(edge.by as usize);
                    // A face of the stock the nominal part keeps is probed only where the
                    // actual part cut it.
                    if nominal_by.is_none() && (cut_by.is_none() && nearest.is_some()) {
                        continue;
                    }
                    let weight = nominal.spacing / along.abs();
                    if at_edge {
                        // Not probed: its length is kept, negative, for the total.
                        out.push((Probe { at, normal, signed_mm: 0.0, cut_by: None }, None, -weight, candidate));
                        continue;
                    }
                    out.push((Probe { at, normal, signed_mm, cut_by }, nominal_by, weight, candidate));
                }
            }
        }
    }
    out
}

/// Probes farther than this (mm) are checked against the nearest surface of the actual part
/// (`nearest_surface`), to tell an edge the probe passes.
const NEAREST_FROM_MM: f64 = 1e-4;
/// How far about a point the nearest surface is looked for, mm: a probe farther than this
/// is a feature missing or gone, and its figure is already far past any bound.
const NEAREST_WITHIN_MM: f64 = 0.5;

/// The distance from `p` to the surface of `part` within `within` of it (`within` where
/// none is nearer): each point where a ray meets the surface stands for the stretch of its
/// tangent between it and the next ray (half the surface length between two rays on each
/// side), so on a straight surface the distance is exact.
fn nearest_surface(part: &Dexels, p: Xz, within: f64) -> f64 {
    let mut best = within;
    for along_z in [true, false] {
        let (rays, across, origin) =
            if along_z { (&part.along_z, p.x, part.x_lo) } else { (&part.along_x, p.z, part.z_lo) };
        // A ray's crossing stands for its tangent half a spacing either side across the rays.
        let reach = within + part.spacing;
        let first = ((across - reach - origin) / part.spacing - 0.5).ceil().max(0.0);
        let last = ((across + reach - origin) / part.spacing - 0.5).floor();
        if !(first.is_finite() && last.is_finite()) || last < first {
            continue;
        }
        let end = (last as usize + 1).min(rays.len());
        for (index, spans) in rays.iter().enumerate().take(end).skip(first as usize) {
            let line = part.line(along_z, index);
            let along_p = if along_z { p.z } else { p.x };
            for span in spans {
                for (edge, high) in [(&span.lo, false), (&span.hi, true)] {
                    // Neither the axis nor the bar's back end where no move cut it is a
                    // surface (as `probe` takes them).
                    if (edge.at - along_p).abs() > best + part.spacing
                        || (!along_z && edge.by == STOCK && edge.at <= 1e-12)
                        || (along_z && !high && edge.by == STOCK)
                    {
                        continue;
                    }
                    let n = edge.normal();
                    let along = if along_z { n.z } else { n.x };
                    if along.abs() < std::f64::consts::FRAC_1_SQRT_2 - 1e-9 {
                        continue;
                    }
                    let q = line.point(edge.at);
                    let v = Xz::new(p.x - q.x, p.z - q.z);
                    let (normal, tangent) = (n.x * v.x + n.z * v.z, n.z * v.x - n.x * v.z);
                    let half = part.spacing / (2.0 * along.abs());
                    let beyond = (tangent.abs() - half).max(0.0);
                    best = best.min((normal * normal + beyond * beyond).sqrt());
                }
            }
        }
    }
    best
}

/// The probes grouped by the block of the original that cut their point, in block order.
fn features(original: &CompactPath, probes: &[Probed]) -> Vec<Feature> {
    let mut by_block: Vec<(Span, Tally, Probe)> = Vec::new();
    let mut index = std::collections::HashMap::new();
    for (p, by, weight, _) in probes {
        let block = by.map_or(Span::SYNTHETIC, |k| original.source(k));
        let slot = *index.entry((block.start, block.end)).or_insert_with(|| {
            by_block.push((block, Tally::default(), *p));
            by_block.len() - 1
        });
        let entry = &mut by_block[slot];
        entry.1.add_along(p.signed_mm.abs(), None, weight / SAMPLE_STEP_MM);
        if p.signed_mm.abs() > entry.2.signed_mm.abs() {
            entry.2 = *p;
        }
    }
    by_block.sort_by_key(|(block, ..)| (block == &Span::SYNTHETIC, block.start));
    by_block
        .into_iter()
        .map(|(block, tally, worst)| Feature { block, figures: tally.figures().rounded(), worst })
        .collect()
}

/// A thread of the original program: its first and last block, tool, lead, the box of its
/// passes, and the phases its passes start at (one per start, millionths of a turn).
struct ThreadRun {
    block: Span,
    last_block: Span,
    tool: u16,
    lead: f64,
    lo: Xz,
    hi: Xz,
    phases: Vec<i64>,
}

/// The threads of `original` measured on each part: a thread is a run of threading moves of
/// one tool and one lead, whatever moves between them do not cut (a thread cycle's passes, or
/// a pass per block).
fn threads(
    original: &CompactPath,
    nominal: &Dexels,
    before: &Dexels,
    after: &Dexels,
    stock: Stock,
) -> Vec<ThreadFigures> {
    let mut blocks: Vec<ThreadRun> = Vec::new();
    let mut open = false;
    for (index, m) in (0..original.len()).filter_map(|index| Some((index, original.as_move(index)?))) {
        if !(m.threading && m.motion == Motion::Feed) || m.rpm <= 0.0 {
            // A cut of another kind ends the thread; moves in the air do not.
            open &= !m.cutting || m.motion == Motion::Rapid || m.motion == Motion::Dwell;
            continue;
        }
        let start = original.start_of(index);
        let lo = Xz::new(start.x.min(m.end.x), start.z.min(m.end.z));
        let hi = Xz::new(start.x.max(m.end.x), start.z.max(m.end.z));
        let lead = m.feed / m.rpm;
        // The starts of a multi-start thread: its passes' phases (`Move::phase`).
        let phase = (m.phase * 1e6).round() as i64;
        match blocks.last_mut().filter(|b| open && b.tool == m.tool && (b.lead - lead).abs() <= 1e-9 * lead) {
            Some(b) => {
                b.last_block = m.source;
                b.lo = Xz::new(b.lo.x.min(lo.x), b.lo.z.min(lo.z));
                b.hi = Xz::new(b.hi.x.max(hi.x), b.hi.z.max(hi.z));
                if !b.phases.contains(&phase) {
                    b.phases.push(phase);
                }
            }
            None => blocks.push(ThreadRun {
                block: m.source,
                last_block: m.source,
                tool: m.tool,
                lead,
                lo,
                hi,
                phases: vec![phase],
            }),
        }
        open = true;
    }
    let mut out = Vec::new();
    for ThreadRun { block, last_block, lead, lo, hi, phases, .. } in blocks {
        let starts = phases.len().max(1) as f64;
        // Whole leads of full form: a lead in from each end of the threaded length on the bar.
        let (z0, z1) = (lo.z.max(stock.back) + lead, hi.z.min(stock.front) - lead);
        let leads = ((z1 - z0) / lead).floor();
        if !(lead > 0.0 && leads >= 1.0) {
            continue;
        }
        let window = (z0, z0 + leads * lead);
        let band = (lo.x - lead, hi.x + lead);
        let Some(nominal_form) = form(nominal, window, band, (lead, starts), None) else { continue };
        let pitch_radius = nominal_form.pitch_diameter_mm / 2.0;
        let measure = |dexels: &Dexels| form(dexels, window, band, (lead, starts), Some(pitch_radius));
        let mut nominal_form = nominal_form;
        nominal_form.lead_mm = lead_at(nominal, window, pitch_radius, (lead, starts));
        out.push(ThreadFigures {
            block,
            last_block,
            programmed_lead_mm: lead,
            leads: leads as usize,
            nominal: nominal_form,
            before: measure(before),
            after: measure(after),
        });
    }
    out
}

/// The share of `window` (z from, z to) that holds material on a ray along Z.
fn filled(spans: &Spans, window: (f64, f64)) -> f64 {
    let inside: f64 = spans.iter().map(|s| (s.hi.at.min(window.1) - s.lo.at.max(window.0)).max(0.0)).sum();
    inside / (window.1 - window.0)
}

/// The pitch diameter of the thread in `window` (whole leads) on the rays along Z between the
/// radii of `band`: where the material fills half the window, interpolated between the two
/// rays about it (the crossing nearest `near`, a pitch radius, when given), and the lead
/// measured at the nominal pitch radius `near` where given; `lead`: the programmed lead and
/// the thread's number of starts.
fn form(
    dexels: &Dexels,
    window: (f64, f64),
    band: (f64, f64),
    lead: (f64, f64),
    near: Option<f64>,
) -> Option<ThreadForm> {
    let rays: Vec<(f64, f64)> = (0..dexels.along_z.len())
        .map(|i| (dexels.line(true, i).at, i))
        .filter(|(x, _)| *x >= band.0 && *x <= band.1)
        .map(|(x, i)| (x, filled(&dexels.along_z[i], window)))
        .collect();
    let mut best: Option<f64> = None;
    for pair in rays.windows(2) {
        let ((x0, f0), (x1, f1)) = (pair[0], pair[1]);
        if (f0 - 0.5) * (f1 - 0.5) > 0.0 || f0 == f1 {
            continue;
        }
        let x = x0 + (0.5 - f0) / (f1 - f0) * (x1 - x0);
        let closer = |b: f64| near.is_some_and(|n| (x - n).abs() < (b - n).abs());
        if best.is_none_or(closer) {
            best = Some(x);
        }
    }
    let radius = best?;
    let lead_mm = near.and_then(|n| lead_at(dexels, window, n, lead));
    Some(ThreadForm { pitch_diameter_mm: 2.0 * radius, lead_mm })
}

/// The lead of the thread in `window` on the ray along Z nearest `radius`: the slope of its
/// grooves' centres (the middles of the gaps between material) against their count, by least
/// squares, times its number of starts (a groove every pitch); none with fewer than two
/// grooves.
fn lead_at(dexels: &Dexels, window: (f64, f64), radius: f64, (lead, starts): (f64, f64)) -> Option<f64> {
    // A groove every pitch, a start's every lead: the slope over the grooves is the pitch.
    let pitch = lead / starts;
    let index = ((radius - dexels.x_lo) / dexels.spacing - 0.5).round();
    let spans = dexels.along_z.get(usize::try_from(index as i64).ok()?)?;
    let centres: Vec<f64> = spans
        .windows(2)
        .map(|w| (w[0].hi.at + w[1].lo.at) / 2.0)
        .filter(|c| *c >= window.0 && *c <= window.1)
        .collect();
    if centres.len() < 2 {
        return None;
    }
    let first = centres[0];
    let points: Vec<(f64, f64)> = centres.iter().map(|c| (((c - first) / pitch).round(), *c)).collect();
    let n = points.len() as f64;
    let (mk, mc) = (points.iter().map(|p| p.0).sum::<f64>() / n, points.iter().map(|p| p.1).sum::<f64>() / n);
    let sxx: f64 = points.iter().map(|p| (p.0 - mk) * (p.0 - mk)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mk) * (p.1 - mc)).sum();
    (sxx > 0.0).then(|| sxy / sxx * starts)
}
