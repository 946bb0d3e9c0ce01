//! Measured data for `diagnose`: a ball bar trace or a CMM profile, as CSV with a header.
//! Errors name the line of the file (counting the header and comments) and what is wrong.
//!
//! * Ball bar (`angle_deg,deviation_mm,direction`): the angle in the XZ plane from +Z
//!   toward +X about the test circle's centre, degrees; actual minus nominal radius, mm;
//!   `ccw` for the G03 run, `cw` for G02. Rows follow the program's order and timing.
//! * CMM profile (`x_mm,z_mm[,part][,start_min]`): points on the finished surface in the
//!   program's work coordinates, x the radius from the axis of rotation, z from the part's
//!   datum face; `part` labels the part a point was measured on and `start_min` the minutes
//!   since machine start at which that part's program started.
//!
//! * Interferometer table (ISO 230-2 CSV as in the model, `error_model::interferometer`):
//!   one slide's positioning and straightness deviations per target and direction.
//!
//! Lines starting with `#` are comments. Columns may come in any order; unknown columns are
//! refused so that a misspelt name is not silently ignored.

use serde::Serialize;

use crate::error_model::interferometer::{self, RecordLines, SlideTable};
pub use crate::error_model::model_file::Axis;
use crate::source::Span;

/// The direction a ball bar circle was run in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    /// `G03`: the angle increases.
    Ccw,
    /// `G02`.
    Cw,
}

impl Direction {
    pub fn name(self) -> &'static str {
        match self {
            Direction::Ccw => "ccw",
            Direction::Cw => "cw",
        }
    }

    /// `+1` for the direction of increasing angle.
    pub fn sign(self) -> f64 {
        match self {
            Direction::Ccw => 1.0,
            Direction::Cw => -1.0,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallBarRow {
    pub angle_deg: f64,
    pub deviation_mm: f64,
    pub direction: Direction,
    /// The row's line in the file.
    pub line: usize,
}

#[derive(Debug, Clone, PartialEq)]
pub struct ProfilePoint {
    pub x_mm: f64,
    pub z_mm: f64,
    pub part: Option<String>,
    pub start_min: Option<f64>,
    pub line: usize,
}

/// The kind of a measurement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    BallBar,
    Profile,
    /// An interferometer table of one slide.
    Table(Axis),
}

impl Kind {
    pub fn name(self) -> &'static str {
        match self {
            Kind::BallBar => "ballbar",
            Kind::Profile => "profile",
            Kind::Table(_) => "table",
        }
    }
}

/// A measurement.
#[derive(Debug, Clone, PartialEq)]
pub enum Measured {
    BallBar(Vec<BallBarRow>),
    Profile(Vec<ProfilePoint>),
    /// An ISO 230-2 table of one slide (`error_model::interferometer`): its positioning and
    /// straightness deviations, the mean of the runs per target and direction.
    Table {
        axis: Axis,
        table: Box<SlideTable>,
    },
}

impl Measured {
    pub fn kind(&self) -> Kind {
        match self {
            Measured::BallBar(_) => Kind::BallBar,
            Measured::Profile(_) => Kind::Profile,
            Measured::Table { axis, .. } => Kind::Table(*axis),
        }
    }

    pub fn len(&self) -> usize {
        match self {
            Measured::BallBar(rows) => rows.len(),
            Measured::Profile(points) => points.len(),
            Measured::Table { table, .. } => [&table.linear, &table.straightness]
                .iter()
                .filter_map(|p| p.as_ref())
                .map(|p| p.up_measured.iter().chain(&p.down_measured).filter(|&&m| m).count())
                .sum(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The rows of the file it was read from (or is written as): a ball bar's or a CMM
    /// profile's points, a table's rows of readings (`len` counts a table's values, the mean
    /// of the runs per target, direction and quantity).
    pub fn rows(&self) -> usize {
        match self {
            Measured::Table { table, .. } => table.rows,
            _ => self.len(),
        }
    }

    /// The line in the file of point `i`.
    pub fn line(&self, i: usize) -> usize {
        match self {
            Measured::BallBar(rows) => rows.get(i).map_or(0, |r| r.line),
            Measured::Profile(points) => points.get(i).map_or(0, |p| p.line),
            Measured::Table { .. } => 0,
        }
    }
}

/// What is wrong with a measurement file: the line of the file (counting the header and
/// comments), the text it is about (a field, a header cell, or the line) and what is wrong.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("line {line}: {message}")]
pub struct MeasuredError {
    pub line: usize,
    pub span: Span,
    pub label: &'static str,
    pub message: String,
    /// What was probably meant, where a guess is possible.
    pub hint: Option<String>,
}

const BALL_BAR: [&str; 3] = ["angle_deg", "deviation_mm", "direction"];
const PROFILE: [&str; 4] = ["x_mm", "z_mm", "part", "start_min"];

/// Read a measurement, telling a ball bar trace from a CMM profile by the header (or,
/// with `kind`, insisting on one). An interferometer table needs its kind, for its axis.
/// The rows are read one at a time, in one pass: the first bad one ends the reading.
pub fn read(text: &str, kind: Option<Kind>) -> Result<Measured, MeasuredError> {
    if let Some(Kind::Table(axis)) = kind {
        return read_slide_table(text, axis);
    }
    let table = Table::new(text)?;
    let kind = match kind {
        Some(kind) => kind,
        None if table.has("angle_deg") => Kind::BallBar,
        None if table.has("x_mm") => Kind::Profile,
        None if table.has("target_mm") => {
            return Err(table.header_error("an interferometer table: say which slide (--kind table --axis x|z)"));
        }
        None => {
            return Err(table.header_error(
                "the header names neither a ball bar trace (angle_deg,deviation_mm,direction) nor a CMM \
                 profile (x_mm,z_mm[,part,start_min])",
            ));
        }
    };
    match kind {
        Kind::BallBar => read_ball_bar(table).map(Measured::BallBar),
        Kind::Profile | Kind::Table(_) => read_profile(table).map(Measured::Profile),
    }
}

/// An ISO 230-2 table of one slide, read by the error model's own reader.
fn read_slide_table(text: &str, axis: Axis) -> Result<Measured, MeasuredError> {
    let table = interferometer::parse(text).map_err(|e| MeasuredError {
        line: e.line().unwrap_or(1),
        span: e.span(text),
        label: match e {
            interferometer::TableError::Row { .. } => "this value",
            interferometer::TableError::UnknownColumn { .. } => "unknown column",
            _ => "here",
        },
        message: e.message(),
        hint: None,
    })?;
    if table.linear.is_none() && table.straightness.is_none() {
        let message = "the table has neither linear_mm nor straightness columns to diagnose".to_string();
        return Err(MeasuredError { line: 1, span: Span::new(0, 0), label: "this table", message, hint: None });
    }
    Ok(Measured::Table { axis, table: Box::new(table) })
}

/// A CSV file's header, and its rows read one at a time, each with its line.
struct Table<'t> {
    text: &'t str,
    header: Vec<String>,
    header_line: usize,
    header_cells: Vec<Span>,
    reader: csv::Reader<&'t [u8]>,
    lines: RecordLines<'t>,
    record: csv::StringRecord,
}

/// A row: its line, the span of the line, and its fields' spans.
struct Row {
    line: usize,
    span: Span,
    fields: Vec<Span>,
}

impl<'t> Table<'t> {
    fn new(text: &'t str) -> Result<Table<'t>, MeasuredError> {
        let reader = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            .flexible(true)
            .has_headers(false)
            .from_reader(text.as_bytes());
        let mut table = Table {
            text,
            header: Vec::new(),
            header_line: 1,
            header_cells: Vec::new(),
            reader,
            lines: RecordLines::new(text),
            record: csv::StringRecord::new(),
        };
        let Some(row) = table.next_row()? else {
            let end = Span::new(text.len() as u32, text.len() as u32);
            let message = "the file is empty".into();
            return Err(MeasuredError { line: 1, span: end, label: "here", message, hint: None });
        };
        table.header = table.record.iter().map(str::to_lowercase).collect();
        table.header_line = row.line;
        table.header_cells = row.fields;
        Ok(table)
    }

    /// The next row that is not blank, read into `self.record`.
    fn next_row(&mut self) -> Result<Option<Row>, MeasuredError> {
        loop {
            let read = self.reader.read_record(&mut self.record).map_err(|e| {
                let line = e.position().map_or(1, |p| self.lines.line_of(p.byte()));
                let span = line_span(self.text, &mut self.lines, line);
                MeasuredError { line, span, label: "here", message: e.to_string(), hint: None }
            })?;
            if !read {
                return Ok(None);
            }
            #[cfg(test)]
            tests::count_row_read();
            if self.record.len() == 1 && self.record[0].is_empty() {
                continue;
            }
            let line = self.record.position().map_or(1, |p| self.lines.line_of(p.byte()));
            let span = line_span(self.text, &mut self.lines, line);
            return Ok(Some(Row { line, span, fields: interferometer::line_cells(self.text, span.start as usize) }));
        }
    }

    fn has(&self, name: &str) -> bool {
        self.header.iter().any(|h| h == name)
    }

    fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    fn header_error(&self, message: impl Into<String>) -> MeasuredError {
        let span = match (self.header_cells.first(), self.header_cells.last()) {
            (Some(first), Some(last)) => Span::new(first.start, last.end),
            _ => Span::new(0, 0),
        };
        MeasuredError { line: self.header_line, span, label: "this header", message: message.into(), hint: None }
    }

    /// Refuse unknown or repeated columns and missing required ones.
    fn check_columns(&self, known: &[&str], required: &[&str]) -> Result<(), MeasuredError> {
        let cell = |i: usize| self.header_cells.get(i).copied().unwrap_or(Span::new(0, 0));
        for (i, name) in self.header.iter().enumerate() {
            if !known.contains(&name.as_str()) {
                return Err(MeasuredError {
                    line: self.header_line,
                    span: cell(i),
                    label: "unknown column",
                    message: format!("unknown column `{name}` (the columns are {})", known.join(", ")),
                    hint: crate::toml_spans::nearest(name, known.iter().copied())
                        .map(|near| format!("did you mean `{near}`?")),
                });
            }
            if self.header[..i].contains(name) {
                return Err(MeasuredError {
                    line: self.header_line,
                    span: cell(i),
                    label: "second of this name",
                    message: format!("the column `{name}` appears twice"),
                    hint: None,
                });
            }
        }
        for name in required {
            if !self.has(name) {
                return Err(self.header_error(format!("the header has no `{name}` column")));
            }
        }
        Ok(())
    }

    /// The rows, each read and checked by `each` before the next is read; a table with a
    /// header and no rows is refused.
    fn rows(mut self, mut each: impl FnMut(&Fields<'_>) -> Result<(), MeasuredError>) -> Result<(), MeasuredError> {
        let mut any = false;
        while let Some(row) = self.next_row()? {
            any = true;
            each(&Fields { row: &row, record: &self.record })?;
        }
        if any { Ok(()) } else { Err(self.header_error("the file has a header but no rows")) }
    }
}

/// One row's fields, for reading values with the span they came from.
struct Fields<'r> {
    row: &'r Row,
    record: &'r csv::StringRecord,
}

impl Fields<'_> {
    fn line(&self) -> usize {
        self.row.line
    }

    /// The span of field `column`, else of the line.
    fn span(&self, column: usize) -> Span {
        self.row.fields.get(column).copied().unwrap_or(self.row.span)
    }

    fn error(&self, column: usize, label: &'static str, message: impl Into<String>) -> MeasuredError {
        MeasuredError { line: self.row.line, span: self.span(column), label, message: message.into(), hint: None }
    }

    fn text(&self, column: usize, name: &str) -> Result<&str, MeasuredError> {
        match self.record.get(column) {
            Some(value) if !value.is_empty() => Ok(value),
            _ => Err(self.error(column, "no value", format!("no value for `{name}`"))),
        }
    }

    fn number(&self, column: usize, name: &str) -> Result<f64, MeasuredError> {
        let text = self.text(column, name)?;
        match text.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok(value),
            _ => {
                let mut error =
                    self.error(column, "not a finite number", format!("`{name}` is `{text}`, not a finite number"));
                // OCR and typing put the letter O for a zero, as in programs.
                let zeros = text.replace(['O', 'o'], "0");
                if zeros != text && zeros.parse::<f64>().is_ok_and(f64::is_finite) {
                    error.hint = Some(format!("`O` typed for `0`? did you mean `{zeros}`?"));
                }
                Err(error)
            }
        }
    }
}

/// The span of line `line` (1-based) of `text`, without its line break.
fn line_span(text: &str, lines: &mut RecordLines<'_>, line: usize) -> Span {
    let start = lines.start_of(line);
    let rest = &text[start..];
    let end = start + rest.find(['\n', '\r']).unwrap_or(rest.len());
    Span::new(start as u32, end as u32)
}

/// A thermal log (`t_min,value`): times in minutes, increasing, and the logged values.
pub fn read_thermal_log(text: &str) -> Result<(Vec<f64>, Vec<f64>), MeasuredError> {
    let table = Table::new(text)?;
    table.check_columns(&["t_min", "value"], &["t_min", "value"])?;
    let (t, v) = (table.column("t_min").unwrap_or(0), table.column("value").unwrap_or(1));
    let mut times: Vec<f64> = Vec::new();
    let mut values = Vec::new();
    table.rows(|row| {
        let time = row.number(t, "t_min")?;
        if times.last().is_some_and(|&before| time <= before) {
            return Err(row.error(
                t,
                "not after the time before",
                format!("t_min {time} does not come after the row before: times must increase"),
            ));
        }
        times.push(time);
        values.push(row.number(v, "value")?);
        Ok(())
    })?;
    Ok((times, values))
}

fn read_ball_bar(table: Table<'_>) -> Result<Vec<BallBarRow>, MeasuredError> {
    table.check_columns(&BALL_BAR, &BALL_BAR)?;
    let [angle, deviation, direction] = BALL_BAR.map(|name| table.column(name).unwrap_or(0));
    let mut out = Vec::new();
    table.rows(|row| {
        let text = row.text(direction, "direction")?;
        let direction = match text.to_ascii_lowercase().as_str() {
            "ccw" => Direction::Ccw,
            "cw" => Direction::Cw,
            _ => {
                let message = format!("`direction` is `{text}`: write `ccw` (G03) or `cw` (G02)");
                return Err(row.error(direction, "not a direction", message));
            }
        };
        let deviation_mm = row.number(deviation, "deviation_mm")?;
        if deviation_mm.abs() > 1.0 {
            return Err(row.error(
                deviation,
                "not a deviation",
                format!("a ball bar deviation of {deviation_mm} mm is not a deviation: write actual − nominal radius"),
            ));
        }
        let angle_deg = row.number(angle, "angle_deg")?;
        out.push(BallBarRow { angle_deg, deviation_mm, direction, line: row.line() });
        Ok(())
    })?;
    Ok(out)
}

fn read_profile(table: Table<'_>) -> Result<Vec<ProfilePoint>, MeasuredError> {
    table.check_columns(&PROFILE, &PROFILE[..2])?;
    let x = table.column("x_mm").unwrap_or(0);
    let z = table.column("z_mm").unwrap_or(0);
    let part = table.column("part");
    let start = table.column("start_min");
    let mut out: Vec<ProfilePoint> = Vec::new();
    // Each part's start time and the line that first gave it.
    let mut started: std::collections::HashMap<Option<String>, (Option<f64>, usize)> = Default::default();
    table.rows(|row| {
        let x_mm = row.number(x, "x_mm")?;
        if x_mm < 0.0 {
            return Err(row.error(
                x,
                "negative",
                format!("x_mm is {x_mm}: x is a radius from the axis of rotation, never negative"),
            ));
        }
        let part = part.map(|c| row.text(c, "part").map(str::to_string)).transpose()?;
        let start_min = start.map(|c| row.number(c, "start_min")).transpose()?;
        let (first_start, first_line) = *started.entry(part.clone()).or_insert((start_min, row.line()));
        if let (Some(t), Some(column)) = (start_min, start)
            && first_start != Some(t)
        {
            return Err(row.error(
                column,
                "another start time",
                format!(
                    "part {} started at {} min on line {first_line}, not {t}: one part has one start time",
                    part.as_deref().unwrap_or("(unnamed)"),
                    first_start.unwrap_or(f64::NAN),
                ),
            ));
        }
        let z_mm = row.number(z, "z_mm")?;
        out.push(ProfilePoint { x_mm, z_mm, part, start_min, line: row.line() });
        Ok(())
    })?;
    Ok(out)
}

#[cfg(test)]
mod tests;
