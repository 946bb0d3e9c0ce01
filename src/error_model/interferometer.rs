//! Interferometer tables of one slide in the style of ISO 230-2 / ASME B5.57: for each
//! target position, runs in each direction, with the linear positioning deviation and,
//! where measured, the straightness and the angular error of the slide.
//!
//! The CSV has a header row; `target_mm` and `direction` (`up`/`down`, or `+`/`-`) are
//! required, `run` is optional (repeated runs per target and direction), and each error is
//! an optional column: `linear_mm`, `straightness_mm` (or the two runs of the reversal
//! technique, `straightness_m1_mm` and `straightness_m2_mm`, reduced by eq. 2.7 of the
//! thesis: `s = (m2 − m1)/2`), and `angular_deg`. Deviations are measured − target, mm.
//! Any other column is refused: a misspelt name (`linear_um`) would otherwise drop its data.
//!
//! The model uses the mean deviation of the direction the slide moves in (the mean
//! bidirectional deviation ± half the reversal value), interpolated linearly between
//! targets and held at the end values beyond them. `report` gives the ISO 230-2 figures.

use std::collections::BTreeMap;

use crate::source::{LineIndex, Span};
use crate::toml_spans::nearest;

/// One measured quantity of a slide along its targets.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Profile {
    /// Target positions, mm, ascending.
    pub targets: Vec<f64>,
    /// Mean deviation per target approaching upward, and downward.
    pub up: Vec<f64>,
    pub down: Vec<f64>,
    /// Sample standard deviation per target and direction (0 with one run).
    pub up_sigma: Vec<f64>,
    pub down_sigma: Vec<f64>,
    /// Whether the table has runs in that direction at the target (a direction without
    /// takes the other's values).
    pub up_measured: Vec<bool>,
    pub down_measured: Vec<bool>,
    /// How many runs each direction has at the target (0 for none): ISO 230-2's figures
    /// of spread need two or more.
    pub up_runs: Vec<usize>,
    pub down_runs: Vec<usize>,
}

impl Profile {
    /// The deviation at `position` for a slide last moving in `direction` (+1 up, −1 down).
    pub fn at(&self, position: f64, direction: i8) -> f64 {
        let values = if direction >= 0 { &self.up } else { &self.down };
        interpolate(&self.targets, values, position)
    }

    /// The mean bidirectional deviation at `position`.
    pub fn mean(&self, position: f64) -> f64 {
        (self.at(position, 1) + self.at(position, -1)) / 2.0
    }
}

fn interpolate(targets: &[f64], values: &[f64], position: f64) -> f64 {
    let (Some(&first), Some(&last)) = (targets.first(), targets.last()) else { return 0.0 };
    if position <= first {
        return values[0];
    }
    if position >= last {
        return values[values.len() - 1];
    }
    let k = targets.partition_point(|&t| t <= position).clamp(1, targets.len() - 1);
    let (t0, t1) = (targets[k - 1], targets[k]);
    let w = if t1 > t0 { (position - t0) / (t1 - t0) } else { 0.0 };
    values[k - 1] + (values[k] - values[k - 1]) * w
}

/// The tables of one slide.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SlideTable {
    pub linear: Option<Profile>,
    pub straightness: Option<Profile>,
    /// Angular error, radians.
    pub angular: Option<Profile>,
    /// How many rows of readings the table was read from (a row is a target, or a target and
    /// a direction and a run, as the layout writes them).
    pub rows: usize,
}

impl SlideTable {
    pub fn linear(&self, position: f64, direction: i8) -> f64 {
        self.linear.as_ref().map_or(0.0, |p| p.at(position, direction))
    }

    pub fn straightness(&self, position: f64, direction: i8) -> f64 {
        self.straightness.as_ref().map_or(0.0, |p| p.at(position, direction))
    }

    pub fn angular(&self, position: f64, direction: i8) -> f64 {
        self.angular.as_ref().map_or(0.0, |p| p.at(position, direction))
    }
}

/// The columns a table may have, in the order the module documentation gives them.
pub const COLUMNS: [&str; 8] = [
    "target_mm",
    "direction",
    "run",
    "linear_mm",
    "straightness_mm",
    "straightness_m1_mm",
    "straightness_m2_mm",
    "angular_deg",
];

/// A table that does not read. Lines are 1-based lines of the text; spans are byte ranges
/// of it.
#[derive(Debug, Clone, PartialEq)]
pub enum TableError {
    /// A row whose value in `column` (0-based) does not read.
    Row {
        line: usize,
        column: usize,
        message: String,
    },
    MissingColumn {
        line: usize,
        name: &'static str,
    },
    /// A header cell that names no column of `COLUMNS` (a misspelt name is refused, not
    /// ignored); `suggestion` is the column it most likely means.
    UnknownColumn {
        line: usize,
        span: Span,
        name: String,
        suggestion: Option<&'static str>,
    },
    DuplicateColumn {
        line: usize,
        span: Span,
        name: String,
    },
    NoErrors {
        line: usize,
    },
    Empty,
    Csv {
        line: usize,
        message: String,
    },
}

impl TableError {
    /// The line the error is on (`None` for a table with no rows at all).
    pub fn line(&self) -> Option<usize> {
        match self {
            TableError::Row { line, .. }
            | TableError::MissingColumn { line, .. }
            | TableError::UnknownColumn { line, .. }
            | TableError::DuplicateColumn { line, .. }
            | TableError::NoErrors { line }
            | TableError::Csv { line, .. } => Some(*line),
            TableError::Empty => None,
        }
    }

    /// What is wrong, without the line.
    pub fn message(&self) -> String {
        match self {
            TableError::Row { message, .. } | TableError::Csv { message, .. } => message.clone(),
            TableError::MissingColumn { name, .. } => format!("the table has no `{name}` column"),
            TableError::UnknownColumn { name, .. } => {
                format!("unknown column `{name}` (the columns are {})", COLUMNS.join(", "))
            }
            TableError::DuplicateColumn { name, .. } => format!("the column `{name}` appears twice"),
            TableError::NoErrors { .. } => {
                "the table has no error column (linear_mm, straightness_mm, straightness_m1_mm/_m2_mm, angular_deg)"
                    .to_string()
            }
            TableError::Empty => "the table has no rows".to_string(),
        }
    }

    /// The text the error is about in `text`, the table it was read from: the header cell of
    /// a column, else the whole line (the end of the text for a table with no rows).
    pub fn span(&self, text: &str) -> Span {
        match self {
            TableError::UnknownColumn { span, .. } | TableError::DuplicateColumn { span, .. } => *span,
            TableError::Row { line, column, .. } => {
                let lines = LineIndex::new(text.as_bytes());
                let start = if *line >= 1 && *line <= lines.line_count() { lines.line_start(line - 1) } else { 0 };
                match line_cells(text, start as usize).get(*column) {
                    Some(cell) => *cell,
                    None => Span::new(start, start),
                }
            }
            _ => {
                let end = u32::try_from(text.len()).unwrap_or(u32::MAX);
                let lines = LineIndex::new(text.as_bytes());
                match self.line() {
                    Some(line) if line >= 1 && line <= lines.line_count() => {
                        let start = lines.line_start(line - 1);
                        let next = if line < lines.line_count() { lines.line_start(line) } else { end };
                        let trimmed = text[start as usize..next as usize].trim_end().len() as u32;
                        Span::new(start, start + trimmed)
                    }
                    _ => Span::new(end, end),
                }
            }
        }
    }
}

impl std::fmt::Display for TableError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.line() {
            Some(line) => write!(f, "line {line}: {}", self.message()),
            None => f.write_str(&self.message()),
        }
    }
}

impl std::error::Error for TableError {}

/// The spans of the cells of the line that starts at byte `start` of `text`, one per cell,
/// each without its blanks and quotes (a quoted cell with a comma in it shifts the ones
/// after it; the cells of these tables are numbers and names).
pub(crate) fn line_cells(text: &str, start: usize) -> Vec<Span> {
    let line_end = text[start..].find(['\n', '\r']).map_or(text.len(), |n| start + n);
    let mut cells = Vec::new();
    let mut cell_start = start;
    for piece in text[start..line_end].split(',') {
        // The cell is the piece without its blanks and quotes, however many: its place is
        // where that slice starts in the piece.
        let trimmed = piece.trim().trim_matches('"');
        let from = cell_start + (trimmed.as_ptr() as usize - piece.as_ptr() as usize);
        cells.push(Span::new(from as u32, (from + trimmed.len()) as u32));
        cell_start += piece.len() + 1;
    }
    cells
}

#[derive(Default)]
struct Runs {
    up: Vec<f64>,
    down: Vec<f64>,
}

/// The 1-based lines of the CSV records of a text, found as a reader goes through it. The
/// reader's own line count skips blank lines, and a record's position is where the reader
/// started looking for it, before the blank and `#` comment lines it passed over: lines are
/// counted up to the position, then over those. Positions come in order, so each count goes
/// on from the last one and reading a table is one pass over its text, not one per row.
pub struct RecordLines<'t> {
    text: &'t str,
    /// Where each line starts, up to the furthest line counted.
    starts: Vec<usize>,
}

impl<'t> RecordLines<'t> {
    pub fn new(text: &'t str) -> RecordLines<'t> {
        RecordLines { text, starts: vec![0] }
    }

    /// Count lines up to byte `to`.
    fn count_to(&mut self, to: usize) {
        let from = self.starts.last().copied().unwrap_or(0);
        if to > from {
            #[cfg(test)]
            tests::count_looked_at(to - from);
            let mut at = from;
            while let Some((_, next)) = next_line_end(self.text.as_bytes(), at, to) {
                if next > to {
                    break;
                }
                self.starts.push(next);
                at = next;
            }
        }
    }

    /// The line of the record a reader found at `byte`.
    pub fn line_of(&mut self, byte: u64) -> usize {
        let mut at = (byte as usize).min(self.text.len());
        let mut line = self.line_at(at);
        loop {
            let (piece, next) = match next_line_end(self.text.as_bytes(), at, self.text.len()) {
                Some((end, next)) => (&self.text[at..end], Some(next)),
                None => (&self.text[at..], None),
            };
            #[cfg(test)]
            tests::count_looked_at(piece.len());
            let trimmed = piece.trim();
            if !(trimmed.is_empty() || trimmed.starts_with('#')) {
                return line;
            }
            line += 1;
            match next {
                Some(next) => at = next,
                None => return line,
            }
        }
    }

    /// The 1-based line that byte `at` is on.
    fn line_at(&mut self, at: usize) -> usize {
        self.count_to(at);
        self.starts.partition_point(|&s| s <= at).max(1)
    }

    /// Where line `line` (1-based) starts, counting lines as far as needed.
    pub fn start_of(&mut self, line: usize) -> usize {
        while self.starts.len() < line {
            let from = self.starts.last().copied().unwrap_or(0);
            let found = next_line_end(self.text.as_bytes(), from, self.text.len());
            #[cfg(test)]
            tests::count_looked_at(found.map_or(self.text.len() - from, |(_, next)| next - from));
            match found {
                Some((_, next)) => self.starts.push(next),
                None => return self.text.len(),
            }
        }
        self.starts[line.max(1) - 1]
    }
}

/// The first line end in `text[from..to]`: where the line's text ends and where the next
/// line starts. A line ends at LF, CR LF or a lone CR, as [`LineIndex`] counts lines and as
/// the CSV reader ends records; a CR LF cut by `to` still counts as one end.
fn next_line_end(text: &[u8], from: usize, to: usize) -> Option<(usize, usize)> {
    let at = from + memchr::memchr2(b'\n', b'\r', &text[from..to])?;
    let next = if text[at] == b'\r' && text.get(at + 1) == Some(&b'\n') { at + 2 } else { at + 1 };
    Some((at, next))
}

/// Read a slide's CSV table.
pub fn parse(text: &str) -> Result<SlideTable, TableError> {
    let mut reader = csv::ReaderBuilder::new().trim(csv::Trim::All).comment(Some(b'#')).from_reader(text.as_bytes());
    let headers = reader.headers().map_err(|e| csv_error(&mut RecordLines::new(text), &e))?.clone();
    let header_start = headers.position().map_or(0, |p| p.byte() as usize);
    let mut lines = RecordLines::new(text);
    let header_line = lines.line_of(header_start as u64);
    let cells = {
        let lines = LineIndex::new(text.as_bytes());
        let start = if header_line >= 1 && header_line <= lines.line_count() {
            lines.line_start(header_line - 1) as usize
        } else {
            0
        };
        let cells = line_cells(text, start);
        if cells.len() == headers.len() { cells } else { vec![Span::new(start as u32, start as u32); headers.len()] }
    };
    for (i, name) in headers.iter().enumerate() {
        if !COLUMNS.contains(&name) {
            let suggestion = nearest(name, COLUMNS);
            return Err(TableError::UnknownColumn {
                line: header_line,
                span: cells[i],
                name: name.to_string(),
                suggestion,
            });
        }
        if headers.iter().take(i).any(|h| h == name) {
            return Err(TableError::DuplicateColumn { line: header_line, span: cells[i], name: name.to_string() });
        }
    }
    let column = |name: &str| headers.iter().position(|h| h == name);
    let missing = |name: &'static str| TableError::MissingColumn { line: header_line, name };
    let target = column("target_mm").ok_or_else(|| missing("target_mm"))?;
    let direction = column("direction").ok_or_else(|| missing("direction"))?;
    let quantities: [(&str, Option<usize>); 5] = [
        ("linear_mm", column("linear_mm")),
        ("straightness_mm", column("straightness_mm")),
        ("straightness_m1_mm", column("straightness_m1_mm")),
        ("straightness_m2_mm", column("straightness_m2_mm")),
        ("angular_deg", column("angular_deg")),
    ];
    if quantities.iter().all(|(_, c)| c.is_none()) {
        return Err(TableError::NoErrors { line: header_line });
    }
    // Per quantity, per target (keyed by its exact bits, in order), the runs each way.
    let mut data: Vec<BTreeMap<OrderedTarget, Runs>> = (0..5).map(|_| BTreeMap::new()).collect();
    let mut rows = 0;
    for record in reader.records() {
        rows += 1;
        let record = record.map_err(|e| csv_error(&mut lines, &e))?;
        let line = record.position().map_or(0, |p| lines.line_of(p.byte()));
        let number = |c: usize, name: &str| -> Result<f64, TableError> {
            let text = record.get(c).unwrap_or("");
            text.parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| TableError::Row {
                line,
                column: c,
                message: format!("`{text}` is not a number in column {name}"),
            })
        };
        let t = number(target, "target_mm")?;
        let up = match record.get(direction).unwrap_or("") {
            "up" | "+" | "forward" => true,
            "down" | "-" | "reverse" | "backward" => false,
            other => {
                let message = format!("direction `{other}` is neither up nor down");
                return Err(TableError::Row { line, column: direction, message });
            }
        };
        for (k, (name, c)) in quantities.iter().enumerate() {
            let Some(c) = *c else { continue };
            if record.get(c).is_none_or(|s| s.is_empty()) {
                continue;
            }
            let v = number(c, name)?;
            let runs = data[k].entry(OrderedTarget(t)).or_default();
            if up { runs.up.push(v) } else { runs.down.push(v) }
        }
    }
    let profile = |k: usize| build(&data[k]);
    let straightness = match (profile(1), profile(2), profile(3)) {
        (Some(s), _, _) => Some(s),
        (None, Some(m1), Some(m2)) => Some(reversal(&m1, &m2)),
        _ => None,
    };
    let angular = profile(4).map(|mut p| {
        for v in p.up.iter_mut().chain(p.down.iter_mut()).chain(p.up_sigma.iter_mut()).chain(p.down_sigma.iter_mut()) {
            *v = v.to_radians();
        }
        p
    });
    let table = SlideTable { linear: profile(0), straightness, angular, rows };
    if table.linear.is_none() && table.straightness.is_none() && table.angular.is_none() {
        return Err(TableError::Empty);
    }
    Ok(table)
}

/// A CSV reader's error, at the line it gives.
fn csv_error(lines: &mut RecordLines<'_>, e: &csv::Error) -> TableError {
    let line = e.position().map_or(1, |p| lines.line_of(p.byte()));
    TableError::Csv { line, message: e.to_string() }
}

/// A target position as a map key: targets are read from text, so equal targets have
/// equal bits.
#[derive(Debug, Clone, Copy, PartialEq)]
struct OrderedTarget(f64);

impl Eq for OrderedTarget {}

impl PartialOrd for OrderedTarget {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for OrderedTarget {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

fn build(runs: &BTreeMap<OrderedTarget, Runs>) -> Option<Profile> {
    if runs.is_empty() {
        return None;
    }
    let mut p = Profile::default();
    for (target, r) in runs {
        // A direction with no run takes the other's values: no reversal measured there.
        let (up, down) = match (r.up.is_empty(), r.down.is_empty()) {
            (false, false) => (&r.up, &r.down),
            (false, true) => (&r.up, &r.up),
            (true, false) => (&r.down, &r.down),
            (true, true) => continue,
        };
        p.targets.push(target.0);
        p.up.push(mean(up));
        p.down.push(mean(down));
        p.up_sigma.push(sigma(up));
        p.down_sigma.push(sigma(down));
        p.up_measured.push(!r.up.is_empty());
        p.down_measured.push(!r.down.is_empty());
        p.up_runs.push(r.up.len());
        p.down_runs.push(r.down.len());
    }
    (!p.targets.is_empty()).then_some(p)
}

/// The reversal technique (eq. 2.5–2.7): `m1 = a − s`, `m2 = a + s`, so `s = (m2 − m1)/2`
/// whatever the straightness `a` of the optics. Targets both runs share (a profile's targets
/// are in order, `build`, so each is found by bisection).
fn reversal(m1: &Profile, m2: &Profile) -> Profile {
    let mut p = Profile::default();
    for (i, &t) in m1.targets.iter().enumerate() {
        if let Ok(j) = m2.targets.binary_search_by(|u| u.partial_cmp(&t).unwrap_or(std::cmp::Ordering::Less)) {
            p.targets.push(t);
            p.up.push((m2.up[j] - m1.up[i]) / 2.0);
            p.down.push((m2.down[j] - m1.down[i]) / 2.0);
            p.up_sigma.push((m1.up_sigma[i].powi(2) + m2.up_sigma[j].powi(2)).sqrt() / 2.0);
            p.down_sigma.push((m1.down_sigma[i].powi(2) + m2.down_sigma[j].powi(2)).sqrt() / 2.0);
            p.up_measured.push(m1.up_measured[i] && m2.up_measured[j]);
            p.down_measured.push(m1.down_measured[i] && m2.down_measured[j]);
            p.up_runs.push(m1.up_runs[i].min(m2.up_runs[j]));
            p.down_runs.push(m1.down_runs[i].min(m2.down_runs[j]));
        }
    }
    p
}

fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len().max(1) as f64
}

fn sigma(values: &[f64]) -> f64 {
    if values.len() < 2 {
        return 0.0;
    }
    let m = mean(values);
    (values.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (values.len() - 1) as f64).sqrt()
}

/// The ISO 230-2 figures of a linear positioning profile, mm. A figure the table cannot
/// give is `None` (JSON null), and `not_measured` says why, keyed by the figure's field.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Iso230_2 {
    /// Bidirectional accuracy A: it needs the spread s at every target.
    pub accuracy: Option<f64>,
    /// Bidirectional systematic positioning error E.
    pub systematic: f64,
    /// Range of the mean bidirectional deviation M.
    pub mean_range: f64,
    /// Axis reversal value B (largest |B_i|), and the mean reversal value: they need both
    /// directions at a target.
    pub reversal: Option<f64>,
    pub mean_reversal: Option<f64>,
    /// Bidirectional repeatability R: it needs the spread s at every target.
    pub repeatability: Option<f64>,
    /// Why a figure is `None`, by its field's name.
    pub not_measured: BTreeMap<&'static str, &'static str>,
}

/// Why B and the mean reversal value are not measured.
pub const ONE_DIRECTION: &str = "measured in one direction only (a reversal value needs both)";
/// Why A and R are not measured.
pub const ONE_RUN: &str = "a single run in a direction at some target (the spread s of the runs needs two or more)";

/// ISO 230-2 figures (the formulas of its sections 2.10–2.24, with k = 2). B and the mean
/// reversal value are taken over the targets measured both ways; A and R need every
/// measured direction at every target to have two or more runs (s of one run is unknown,
/// not zero).
pub fn report(p: &Profile) -> Iso230_2 {
    let n = p.targets.len();
    let runs = |v: &[usize], i: usize| v.get(i).copied().unwrap_or(1);
    let measured = |v: &[bool], i: usize| v.get(i).copied().unwrap_or(true);
    let mut max_up_down = f64::NEG_INFINITY;
    let mut min_up_down = f64::INFINITY;
    let mut max_acc = f64::NEG_INFINITY;
    let mut min_acc = f64::INFINITY;
    let mut means = Vec::with_capacity(n);
    let mut reversal: Option<f64> = None;
    let mut reversal_sum = 0.0;
    let mut both_ways = 0usize;
    let mut repeatability: f64 = 0.0;
    let mut spread_known = true;
    for i in 0..n {
        let (u, d, su, sd) = (p.up[i], p.down[i], p.up_sigma[i], p.down_sigma[i]);
        let (up, down) = (measured(&p.up_measured, i), measured(&p.down_measured, i));
        spread_known &= (!up || runs(&p.up_runs, i) >= 2) && (!down || runs(&p.down_runs, i) >= 2);
        max_up_down = max_up_down.max(u.max(d));
        min_up_down = min_up_down.min(u.min(d));
        max_acc = max_acc.max((u + 2.0 * su).max(d + 2.0 * sd));
        min_acc = min_acc.min((u - 2.0 * su).min(d - 2.0 * sd));
        means.push((u + d) / 2.0);
        // A direction not measured holds the other's values: B_i is 0 there, not measured.
        let b = if up && down { u - d } else { 0.0 };
        if up && down {
            if reversal.is_none_or(|r: f64| b.abs() > r) {
                reversal = Some(b.abs());
            }
            reversal_sum += b;
            both_ways += 1;
        }
        let r = (2.0 * su + 2.0 * sd + b.abs()).max(4.0 * su).max(4.0 * sd);
        repeatability = repeatability.max(r);
    }
    let (mean_max, mean_min) = means.iter().fold((f64::NEG_INFINITY, f64::INFINITY), |(a, b), &m| (a.max(m), b.min(m)));
    let mut not_measured = BTreeMap::new();
    if reversal.is_none() {
        not_measured.insert("reversal", ONE_DIRECTION);
        not_measured.insert("mean_reversal", ONE_DIRECTION);
    }
    if !spread_known {
        not_measured.insert("accuracy", ONE_RUN);
        not_measured.insert("repeatability", ONE_RUN);
    }
    Iso230_2 {
        accuracy: spread_known.then_some(max_acc - min_acc),
        systematic: max_up_down - min_up_down,
        mean_range: mean_max - mean_min,
        reversal,
        mean_reversal: (both_ways > 0).then(|| reversal_sum / both_ways as f64),
        repeatability: spread_known.then_some(repeatability),
        not_measured,
    }
}

#[cfg(test)]
pub(crate) mod tests;
