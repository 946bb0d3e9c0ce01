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

use crate::error_model::interferometer::{self, SlideTable};
pub use crate::error_model::model_file::Axis;

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

    /// The line in the file of point `i`.
    pub fn line(&self, i: usize) -> usize {
        match self {
            Measured::BallBar(rows) => rows.get(i).map_or(0, |r| r.line),
            Measured::Profile(points) => points.get(i).map_or(0, |p| p.line),
            Measured::Table { .. } => 0,
        }
    }
}

/// What is wrong with a measurement file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("line {line}: {message}")]
pub struct MeasuredError {
    pub line: usize,
    pub message: String,
}

fn error(line: usize, message: impl Into<String>) -> MeasuredError {
    MeasuredError { line, message: message.into() }
}

const BALL_BAR: [&str; 3] = ["angle_deg", "deviation_mm", "direction"];
const PROFILE: [&str; 4] = ["x_mm", "z_mm", "part", "start_min"];

/// Read a measurement, telling a ball bar trace from a CMM profile by the header (or,
/// with `kind`, insisting on one). An interferometer table needs its kind, for its axis.
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
            return Err(error(table.header_line, "an interferometer table: say which slide (--kind table --axis x|z)"));
        }
        None => {
            return Err(error(
                table.header_line,
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
    let table = interferometer::parse(text).map_err(|e| error(e.line().unwrap_or(1), e.message()))?;
    if table.linear.is_none() && table.straightness.is_none() {
        return Err(error(1, "the table has neither linear_mm nor straightness columns to diagnose"));
    }
    Ok(Measured::Table { axis, table: Box::new(table) })
}

/// A CSV file's header and rows, each with its line.
struct Table {
    header: Vec<String>,
    header_line: usize,
    rows: Vec<(usize, Vec<String>)>,
}

impl Table {
    fn new(text: &str) -> Result<Table, MeasuredError> {
        let mut reader = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            .flexible(true)
            .has_headers(false)
            .from_reader(text.as_bytes());
        let line_of = |byte: u64| interferometer::csv_record_line(text, byte);
        let mut records = Vec::new();
        for record in reader.records() {
            let record = record.map_err(|e| {
                let line = e.position().map_or(0, |p| line_of(p.byte()));
                error(line, e.to_string())
            })?;
            let line = record.position().map_or(0, |p| line_of(p.byte()));
            records.push((line, record.iter().map(str::to_string).collect::<Vec<_>>()));
        }
        let mut records = records.into_iter().filter(|(_, r)| !(r.len() == 1 && r[0].is_empty()));
        let Some((header_line, header)) = records.next() else { return Err(error(1, "the file is empty")) };
        Ok(Table { header: header.iter().map(|h| h.to_lowercase()).collect(), header_line, rows: records.collect() })
    }

    fn has(&self, name: &str) -> bool {
        self.header.iter().any(|h| h == name)
    }

    fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// Refuse unknown or repeated columns and missing required ones.
    fn check_columns(&self, known: &[&str], required: &[&str]) -> Result<(), MeasuredError> {
        for (i, name) in self.header.iter().enumerate() {
            if !known.contains(&name.as_str()) {
                return Err(error(
                    self.header_line,
                    format!("unknown column `{name}` (the columns are {})", known.join(", ")),
                ));
            }
            if self.header[..i].contains(name) {
                return Err(error(self.header_line, format!("the column `{name}` appears twice")));
            }
        }
        for name in required {
            if !self.has(name) {
                return Err(error(self.header_line, format!("the header has no `{name}` column")));
            }
        }
        if self.rows.is_empty() {
            return Err(error(self.header_line, "the file has a header but no rows"));
        }
        Ok(())
    }
}

fn field<'a>(row: &'a [String], column: usize, name: &str, line: usize) -> Result<&'a str, MeasuredError> {
    match row.get(column).map(String::as_str) {
        Some(value) if !value.is_empty() => Ok(value),
        _ => Err(error(line, format!("no value for `{name}`"))),
    }
}

fn number(row: &[String], column: usize, name: &str, line: usize) -> Result<f64, MeasuredError> {
    let text = field(row, column, name, line)?;
    match text.parse::<f64>() {
        Ok(value) if value.is_finite() => Ok(value),
        _ => Err(error(line, format!("`{name}` is `{text}`, not a finite number"))),
    }
}

/// A thermal log (`t_min,value`): times in minutes, increasing, and the logged values.
pub fn read_thermal_log(text: &str) -> Result<(Vec<f64>, Vec<f64>), MeasuredError> {
    let table = Table::new(text)?;
    table.check_columns(&["t_min", "value"], &["t_min", "value"])?;
    let (t, v) = (table.column("t_min").unwrap_or(0), table.column("value").unwrap_or(1));
    let mut times: Vec<f64> = Vec::with_capacity(table.rows.len());
    let mut values = Vec::with_capacity(table.rows.len());
    for (line, row) in &table.rows {
        let time = number(row, t, "t_min", *line)?;
        if times.last().is_some_and(|&before| time <= before) {
            return Err(error(*line, format!("t_min {time} does not come after the row before: times must increase")));
        }
        times.push(time);
        values.push(number(row, v, "value", *line)?);
    }
    Ok((times, values))
}

fn read_ball_bar(table: Table) -> Result<Vec<BallBarRow>, MeasuredError> {
    table.check_columns(&BALL_BAR, &BALL_BAR)?;
    let [angle, deviation, direction] = BALL_BAR.map(|name| table.column(name).unwrap_or(0));
    let mut out = Vec::with_capacity(table.rows.len());
    for (line, row) in &table.rows {
        let line = *line;
        let text = field(row, direction, "direction", line)?;
        let direction = match text.to_ascii_lowercase().as_str() {
            "ccw" => Direction::Ccw,
            "cw" => Direction::Cw,
            _ => return Err(error(line, format!("`direction` is `{text}`: write `ccw` (G03) or `cw` (G02)"))),
        };
        let deviation_mm = number(row, deviation, "deviation_mm", line)?;
        if deviation_mm.abs() > 1.0 {
            return Err(error(
                line,
                format!("a ball bar deviation of {deviation_mm} mm is not a deviation: write actual − nominal radius"),
            ));
        }
        out.push(BallBarRow { angle_deg: number(row, angle, "angle_deg", line)?, deviation_mm, direction, line });
    }
    Ok(out)
}

fn read_profile(table: Table) -> Result<Vec<ProfilePoint>, MeasuredError> {
    table.check_columns(&PROFILE, &PROFILE[..2])?;
    let x = table.column("x_mm").unwrap_or(0);
    let z = table.column("z_mm").unwrap_or(0);
    let part = table.column("part");
    let start = table.column("start_min");
    let mut out: Vec<ProfilePoint> = Vec::with_capacity(table.rows.len());
    for (line, row) in &table.rows {
        let line = *line;
        let x_mm = number(row, x, "x_mm", line)?;
        if x_mm < 0.0 {
            return Err(error(
                line,
                format!("x_mm is {x_mm}: x is a radius from the axis of rotation, never negative"),
            ));
        }
        let part = part.map(|c| field(row, c, "part", line).map(str::to_string)).transpose()?;
        let start_min = start.map(|c| number(row, c, "start_min", line)).transpose()?;
        if let Some(t) = start_min
            && let Some(earlier) = out.iter().find(|p| p.part == part && p.start_min != Some(t))
        {
            return Err(error(
                line,
                format!(
                    "part {} started at {} min on line {}, not {t}: one part has one start time",
                    part.as_deref().unwrap_or("(unnamed)"),
                    earlier.start_min.unwrap_or(f64::NAN),
                    earlier.line
                ),
            ));
        }
        out.push(ProfilePoint { x_mm, z_mm: number(row, z, "z_mm", line)?, part, start_min, line });
    }
    Ok(out)
}

#[cfg(test)]
mod tests;
