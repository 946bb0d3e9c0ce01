//! `turnpass simulate`: the toolpath as rows, and a summary (cycle time, cutting time, path
//! length, and the predicted roughness of each finishing pass).
//!
//! Roughness is the peak-to-valley height a nose of radius `R` leaves at feed per
//! revolution `f`. While the nose alone forms the surface (`f ≤ 2R sin K'`, with `K'` the
//! minor cutting edge angle), `Rt = R − √(R² − f²/4)`; above that the minor edge cuts too,
//! and eq. 9.1 of the reference thesis applies:
//!
//! ```txt
//! Rt = (1 − cos K') R + f sin K' cos K' − √(2 f R sin³K' − f² sin⁴K')
//! ```
//!
//! With no `K'` in the tool table the nose-only form is used. A finishing pass is each
//! `G70`/LAP finishing cycle, and each run of feed moves under nose-radius compensation.

use std::ops::Range;

use serde::Serialize;

use crate::semantic::{Lowered, Machine};
use crate::source::{LineIndex, Span};
use crate::syntax::Program;
use crate::toolpath::{Compensation, Motion, ValidToolpath, Validated};

/// One row of `simulate --format csv|json`. Its fields are in the order of the JSON keys
/// (alphabetical); the CSV columns are in the order `simulate` documents.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Row {
    pub cutting: bool,
    pub cx_mm: Option<f64>,
    pub cz_mm: Option<f64>,
    pub feed_mm_min: f64,
    pub line: usize,
    pub motion: &'static str,
    pub rpm: f64,
    pub t_end_s: f64,
    pub t_start_s: f64,
    pub x_mm: f64,
    pub z_mm: f64,
}

#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct FinishingPass {
    /// 1-based line of the block (the cycle call for a cycle).
    pub line: usize,
    pub tool: u16,
    pub feed_per_rev_mm: f64,
    pub nose_radius_mm: f64,
    /// Peak-to-valley roughness, mm; `None` without a nose radius in the tool table.
    pub roughness_mm: Option<f64>,
    /// Which formula gave it: "nose" or "eq. 9.1".
    pub formula: &'static str,
}

#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Summary {
    pub moves: usize,
    pub cycle_time_s: f64,
    pub cutting_time_s: f64,
    pub path_length_mm: f64,
    pub cutting_length_mm: f64,
    /// True when the machine settings gave no rapid rate and 10 m/min was assumed.
    pub rapid_rate_assumed: bool,
    pub finishing_passes: Vec<FinishingPass>,
    /// What the part model found, when it ran.
    pub part: Option<PartFigures>,
}

/// The part model's figures in `simulate`'s summary: the stock, and the feed moves that cut
/// air (remove nothing) with the time they take.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct PartFigures {
    /// True when neither `[stock]` nor `--stock` gave the bar.
    pub stock_assumed: bool,
    pub stock_diameter_mm: f64,
    pub stock_bore_mm: f64,
    pub stock_front_mm: f64,
    pub stock_length_mm: f64,
    pub air_moves: usize,
    pub air_time_s: f64,
    pub air_length_mm: f64,
    /// The Z where a part-off cut the part from the bar, if one did.
    pub parted_off_at_mm: Option<f64>,
    /// The move at which the part model stopped at its bound, if it did.
    pub stopped_at_move: Option<usize>,
}

impl Summary {
    /// The summary with the part model's figures, when it ran and found a stock.
    pub fn with_part(self, run: Option<&crate::part::PartRun>) -> Summary {
        let figures = run.and_then(|run| {
            let summary = run.summary.as_ref()?;
            let stock = summary.stock;
            Some(PartFigures {
                stock_assumed: stock.assumed,
                stock_diameter_mm: 2.0 * stock.outer,
                stock_bore_mm: 2.0 * stock.bore,
                stock_front_mm: stock.front,
                stock_length_mm: stock.front - stock.back,
                air_moves: summary.air_moves,
                air_time_s: summary.air_time_s,
                air_length_mm: summary.air_length_mm,
                parted_off_at_mm: run.part.as_ref().and_then(|p| p.separated_at),
                stopped_at_move: summary.stopped_at,
            })
        });
        Summary { part: figures, ..self }
    }
}

/// The rows of a toolpath, one per move, made as they are read (as a JSON array, through
/// `Serialize`): a table of millions of moves is written out without being held.
#[derive(Clone, Copy)]
pub struct Rows<'a> {
    program: &'a Program<'a>,
    toolpath: ValidToolpath<'a>,
}

/// One row per move of the validated toolpath.
pub fn rows<'a>(program: &'a Program<'_>, toolpath: ValidToolpath<'a>) -> Rows<'a> {
    Rows { program, toolpath }
}

impl Rows<'_> {
    pub fn iter(&self) -> impl Iterator<Item = Row> + '_ {
        let lines = LineIndex::new(self.program.source());
        self.toolpath.moves.iter().map(move |m| Row {
            line: if m.source.is_synthetic() { 0 } else { lines.position(m.source.start).0 },
            motion: m.motion.name(),
            x_mm: m.end.x,
            z_mm: m.end.z,
            cx_mm: m.is_arc().then_some(m.centre.x),
            cz_mm: m.is_arc().then_some(m.centre.z),
            feed_mm_min: m.feed,
            rpm: m.rpm,
            t_start_s: m.t_start,
            t_end_s: m.t_end,
            cutting: m.cutting,
        })
    }
}

impl Serialize for Rows<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.iter())
    }
}

/// The rows as CSV with the column order `simulate` documents, written to `out` row by row.
pub fn write_csv(rows: Rows<'_>, out: impl std::io::Write) -> Result<(), csv::Error> {
    let mut writer = csv::Writer::from_writer(out);
    writer.write_record([
        "line",
        "motion",
        "x_mm",
        "z_mm",
        "cx_mm",
        "cz_mm",
        "feed_mm_min",
        "rpm",
        "t_start_s",
        "t_end_s",
        "cutting",
    ])?;
    let f = |v: f64| format!("{v:.6}");
    for row in rows.iter() {
        writer.write_record([
            row.line.to_string(),
            row.motion.to_string(),
            f(row.x_mm),
            f(row.z_mm),
            row.cx_mm.map(f).unwrap_or_default(),
            row.cz_mm.map(f).unwrap_or_default(),
            format!("{:.3}", row.feed_mm_min),
            format!("{:.1}", row.rpm),
            f(row.t_start_s),
            f(row.t_end_s),
            row.cutting.to_string(),
        ])?;
    }
    writer.flush()?;
    Ok(())
}

/// Peak-to-valley roughness for feed `f` per revolution and nose radius `r` (mm), and the
/// formula used; see the module documentation.
pub fn roughness(f: f64, r: f64, minor_edge_angle_deg: Option<f64>) -> (f64, &'static str) {
    let nose_only = |f: f64| if f <= 2.0 * r { r - (r * r - f * f / 4.0).sqrt() } else { f * f / (8.0 * r) };
    match minor_edge_angle_deg {
        Some(k) if k > 0.0 && f > 2.0 * r * k.to_radians().sin() => {
            let (s, c) = k.to_radians().sin_cos();
            let root = (2.0 * f * r * s.powi(3) - f * f * s.powi(4)).max(0.0).sqrt();
            ((1.0 - c) * r + f * s * c - root, "eq. 9.1")
        }
        _ => (nose_only(f), "nose"),
    }
}

/// The times, lengths and finishing passes of a validated program.
pub fn summary(program: &Program<'_>, lowered: &Validated<Lowered>, machine: &Machine) -> Summary {
    let toolpath = lowered.valid().toolpath();
    let lines = LineIndex::new(program.source());
    let mut cycle_time = 0.0;
    let mut cutting_time = 0.0;
    let mut path = 0.0;
    let mut cutting_length = 0.0;
    for (i, m) in toolpath.moves.iter().enumerate() {
        let start = toolpath.start_of(i);
        let length = match m.motion {
            Motion::Cw | Motion::Ccw => crate::geometry::arc_length(start, m.end, m.centre, m.motion == Motion::Ccw),
            Motion::Dwell => 0.0,
            _ => start.distance(m.end),
        };
        path += length;
        if m.cutting {
            cutting_time += m.t_end - m.t_start;
            cutting_length += length;
        }
        cycle_time = m.t_end;
    }

    // Finishing passes: the finishing cycles, then compensated runs outside cycles.
    let mut passes = Vec::new();
    // The feed per revolution as programmed, in mm through the units in force at the move
    // (a `G20` program on a metric machine writes inches); a per-minute feed divided by the
    // spindle speed.
    let per_rev = |index: usize, m: &crate::toolpath::Move| {
        if m.per_revolution { m.f_word * lowered.coordinates_at(index).frame.scale() } else { m.feed / m.rpm.max(1e-9) }
    };
    let mut pass = |source: Span, range: Range<usize>| {
        let cutting: Vec<_> = toolpath.moves[range.clone()]
            .iter()
            .enumerate()
            .map(|(i, m)| (range.start + i, m))
            .filter(|(_, m)| m.cutting && m.motion != Motion::Rapid && m.rpm > 0.0)
            .collect();
        let Some((_, first)) = cutting.first() else { return };
        let feed_per_rev = cutting.iter().map(|(i, m)| per_rev(*i, m)).fold(0.0, f64::max);
        let entry = crate::part::tool::entry(machine, first.tool, first.offset);
        let nose = entry.map_or(0.0, |t| t.nose_radius * machine.scale());
        let (roughness_mm, formula) = if nose > 0.0 {
            let (value, formula) = roughness(feed_per_rev, nose, entry.and_then(|t| t.minor_edge_angle));
            (Some(value), formula)
        } else {
            (None, "no nose radius in the tool table")
        };
        passes.push(FinishingPass {
            line: lines.position(source.start).0,
            tool: first.tool,
            feed_per_rev_mm: feed_per_rev,
            nose_radius_mm: nose,
            roughness_mm,
            formula,
        });
    };
    for (source, moves) in finishing_moves(program, lowered) {
        pass(source, moves);
    }
    passes.sort_by_key(|p| p.line);

    Summary {
        moves: toolpath.moves.len(),
        cycle_time_s: cycle_time,
        cutting_time_s: cutting_time,
        path_length_mm: path,
        cutting_length_mm: cutting_length,
        rapid_rate_assumed: machine.rapid_assumed,
        finishing_passes: passes,
        part: None,
    }
}

/// The finishing passes of a program, each as the block that makes it and its range of
/// moves: every `G70`/LAP finishing cycle, less its approach (`cycle_approach`), then every
/// run of feed moves under nose-radius compensation outside cycles (less the move that
/// switches compensation on, which approaches the surface and does not finish it). In
/// program order of the passes' kinds, not sorted.
/// The moves at the start of a finishing cycle's `moves` that bring the tool from the cycle's
/// start point to its profile, not on the finished surface: the moves before the first
/// cut (the profile's first block written `G00`), and the first cut itself where it is the
/// profile's first block (written `G01`: Fanuc's move from A to A', which only positions the
/// tool; the finishing shape is A' to B) or switches nose-radius compensation on.
fn cycle_approach(moves: &[crate::toolpath::Move], range: Range<usize>) -> Range<usize> {
    let first_cut = range.clone().find(|&i| moves[i].cutting).unwrap_or(range.end);
    let switches_on = |i: usize| {
        moves[i].compensation != Compensation::Off && (i == 0 || moves[i - 1].compensation == Compensation::Off)
    };
    let approach = first_cut < range.end && (first_cut == range.start || switches_on(first_cut));
    range.start..if approach { first_cut + 1 } else { first_cut }
}

pub fn finishing_moves(program: &Program<'_>, lowered: &Validated<Lowered>) -> Vec<(Span, Range<usize>)> {
    let toolpath = lowered.valid().toolpath();
    let mut out = Vec::new();
    for expansion in &lowered.expansions {
        let block = program.block(expansion.block);
        let is_finishing = program.words_of(block).iter().any(|w| match w.kind {
            crate::syntax::WordKind::Code { letter: crate::syntax::CodeLetter::G, code } => {
                program.config().tables().g(code).and_then(|g| g.function).is_some_and(|f| {
                    matches!(f, crate::dialect::GFunction::Finishing | crate::dialect::GFunction::LapFinish)
                })
            }
            _ => false,
        });
        if is_finishing {
            let moves = expansion.moves.clone();
            out.push((block.span, cycle_approach(&toolpath.moves, moves.clone()).end..moves.end));
        }
    }
    let mut i = 0;
    while i < toolpath.moves.len() {
        let m = &toolpath.moves[i];
        if m.compensation == Compensation::Off || !m.cycle.is_synthetic() {
            i += 1;
            continue;
        }
        let start = i;
        while i < toolpath.moves.len()
            && toolpath.moves[i].compensation != Compensation::Off
            && toolpath.moves[i].cycle.is_synthetic()
        {
            i += 1;
        }
        if i > start + 1 {
            out.push((toolpath.moves[start + 1].source, start + 1..i));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roughness_matches_the_thesis_example() {
        // Nose radius 0.792 mm, minor edge 5°, feed 0.2032 mm/rev: Rt = 0.00615 mm (eq. 9.1).
        let (rt, formula) = roughness(0.2032, 0.792, Some(5.0));
        assert_eq!(formula, "eq. 9.1");
        assert!((rt - 0.00615).abs() < 0.00002, "{rt}");
        // The nose alone: R − √(R² − f²/4), close to f²/8R.
        let (rt, formula) = roughness(0.1, 0.8, None);
        assert_eq!(formula, "nose");
        assert!((rt - 0.1f64 * 0.1 / 6.4).abs() < 1e-5);
    }
}
