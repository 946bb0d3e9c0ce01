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
use crate::measurement_file::{ColumnName, DataError, DataFile, Unit, column_name};

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

/// What is wrong with a measurement file (`measurement_file::DataError`): the line of the
/// file (counting the preamble, header and comments), the text it is about and what is wrong.
pub type MeasuredError = DataError;

/// The kind of a measurement asked for, before a table's slide is known.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KindName {
    BallBar,
    Profile,
    Table,
}

/// The preamble keys of a ball bar trace.
pub const BALL_BAR_PREAMBLE: [&str; 9] =
    ["units", "unit", "angle_units", "direction", "start_angle", "angle_step", "angle_zero", "angle_sense", "radius"];
/// The preamble keys of a CMM profile.
pub const PROFILE_PREAMBLE: [&str; 3] = ["units", "unit", "x"];

/// Read a measurement, telling its kind by the header (or, with `kind`, insisting on one).
/// An interferometer table needs its slide: `Kind::Table`'s.
pub fn read(text: &str, kind: Option<Kind>) -> Result<Measured, MeasuredError> {
    let (name, axis) = match kind {
        None => (None, None),
        Some(Kind::BallBar) => (Some(KindName::BallBar), None),
        Some(Kind::Profile) => (Some(KindName::Profile), None),
        Some(Kind::Table(axis)) => (Some(KindName::Table), Some(axis)),
    };
    read_as(text, name, axis)
}

/// Read a measurement of the kind `kind` (else told by its header); a table's slide is
/// `axis`, else the one its preamble names (`axis: z`). The rows are read one at a time, in
/// one pass: the first bad one ends the reading.
pub fn read_as(text: &str, kind: Option<KindName>, axis: Option<Axis>) -> Result<Measured, MeasuredError> {
    let mut file = DataFile::open(text)?;
    let kind = match kind {
        Some(kind) => kind,
        None => told_by_header(&file)?,
    };
    match kind {
        KindName::Table => read_slide_table(text, &file, axis),
        KindName::BallBar => read_ball_bar(&mut file).map(Measured::BallBar),
        KindName::Profile => read_profile(&mut file).map(Measured::Profile),
    }
}

/// The kind a header names: a table by its target column, a profile by its X or Z, a ball
/// bar by its angle or deviation.
fn told_by_header(file: &DataFile<'_>) -> Result<KindName, MeasuredError> {
    let names: Vec<ColumnName> = file.header.iter().map(|c| column_name(&c.text)).collect();
    let any = |f: &dyn Fn(&ColumnName) -> bool| names.iter().any(f);
    if any(&|n| n.has_any(&["target", "nominal", "commanded"])) {
        Ok(KindName::Table)
    } else if any(&|n| n.is(&["x"]) || n.is(&["z"]) || n.has_any(&["radius", "diameter", "dia"])) {
        Ok(KindName::Profile)
    } else if any(&|n| n.has_any(&["angle", "theta", "deviation", "radial"])) {
        Ok(KindName::BallBar)
    } else {
        Err(file
            .header_error(
                "this header",
                "the header names neither a ball bar trace (angle_deg,deviation_mm,direction) nor a CMM profile \
             (x_mm,z_mm[,part,start_min]) nor an interferometer table (target_mm,direction,linear_mm)",
            )
            .with_hint("give --kind, and see docs/measurements.md for the columns each kind takes"))
    }
}

/// An ISO 230-2 table of one slide, read by the error model's own reader.
fn read_slide_table(text: &str, file: &DataFile<'_>, axis: Option<Axis>) -> Result<Measured, MeasuredError> {
    let read = interferometer::read_file(text)?;
    let said = read.axis.map(|(letter, line, span)| (if letter == 'x' { Axis::X } else { Axis::Z }, line, span));
    let axis = match (axis, said) {
        (Some(given), Some((said, line, span))) if given != said => {
            let message =
                format!("the table says it measured the {} slide, and --axis the {}", said.letter(), given.letter());
            return Err(DataError::new(line, span, "this slide", message).with_hint("give the --axis the table says"));
        }
        (Some(given), _) => given,
        (None, Some((said, _, _))) => said,
        (None, None) => {
            return Err(file
                .header_error("this header", "an interferometer table: say which slide it measured")
                .with_hint("give --kind table --axis x|z, or a line `axis: x` above the header"));
        }
    };
    let table = read.table;
    if table.linear.is_none() && table.straightness.is_none() {
        let message = "the table has neither linear nor straightness readings to diagnose";
        return Err(file.header_error("this table", message));
    }
    Ok(Measured::Table { axis, table: Box::new(table) })
}

/// The unit of a length column: its own, else the preamble's `units`.
fn length_unit(file: &DataFile<'_>, i: usize, name: &ColumnName, example: &str) -> Result<f64, MeasuredError> {
    let cell = &file.header[i].text;
    let unit = match name.unit {
        Some(unit) => unit,
        None => {
            let Some(entry) = file.meta_any(&["units", "unit"]) else {
                return Err(file.cell_error(i, "no unit", format!("the column `{cell}` has no unit")).with_hint(
                    format!("write it in the header, `{example} (mm)`, or add a line `units: mm` above the header"),
                ));
            };
            Unit::parse(&entry.value).ok_or_else(|| {
                DataFile::meta_error(entry, "not a unit", format!("`{}` is no unit turnpass knows", entry.value))
                    .with_hint("a length is in mm, um (µm), nm or in")
            })?
        }
    };
    unit.mm().ok_or_else(|| {
        file.cell_error(i, "not a length unit", format!("the column `{cell}` is in {}, not a length", unit.name()))
            .with_hint("a length is in mm, µm, nm or in")
    })
}

/// A column the reader does not read: a row's number or name, the time of a reading.
fn is_label(name: &ColumnName) -> bool {
    !name.words.is_empty()
        && name.words.iter().all(|w| {
            ["point", "pt", "sample", "index", "no", "n", "number", "id", "name", "label", "feature", "count", "time"]
                .contains(&w.as_str())
                || w.parse::<f64>().is_ok()
        })
}

/// The unknown column `i` of `file`, with what the reader takes.
fn unknown_column(file: &DataFile<'_>, i: usize, known: &[&str], takes: &str) -> MeasuredError {
    let cell = &file.header[i].text;
    let mut error =
        file.cell_error(i, "unknown column", format!("unknown column `{cell}` (the columns are {})", known.join(", ")));
    error.unknown_column = Some(cell.clone());
    error.hint = Some(match crate::toml_spans::nearest(cell, known.iter().copied()) {
        Some(near) => format!("did you mean `{near}`?"),
        None => takes.to_string(),
    });
    error
}

/// A direction of a ball bar run as a file writes it: `G03` (counter-clockwise, the angle
/// increasing) or `G02`.
fn run_direction(text: &str) -> Option<Direction> {
    let words: String = text.to_lowercase().chars().filter(|c| c.is_alphanumeric()).collect();
    match words.as_str() {
        "ccw" | "anticlockwise" | "counterclockwise" | "g03" | "g3" => Some(Direction::Ccw),
        "cw" | "clockwise" | "g02" | "g2" => Some(Direction::Cw),
        _ => None,
    }
}

const DIRECTION_HINT: &str = "write ccw (anticlockwise, counterclockwise, G03) or cw (clockwise, G02)";

/// A preamble angle in degrees (`90`, `90 deg`, `1.5708 rad`).
fn preamble_degrees(entry: &crate::measurement_file::Entry) -> Result<f64, MeasuredError> {
    let text = entry.value.trim();
    let split =
        text.find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E'))).unwrap_or(text.len());
    let (number, unit) = text.split_at(split);
    let unit = if unit.trim().is_empty() { Some(Unit::Deg) } else { Unit::parse(unit.trim()) };
    match (number.trim().parse::<f64>(), unit.and_then(Unit::radians)) {
        (Ok(value), Some(radians)) if value.is_finite() => Ok((value * radians).to_degrees()),
        _ => Err(DataFile::meta_error(entry, "not an angle", format!("`{}` is not an angle", entry.value))
            .with_hint("write degrees (`90`, `90 deg`) or another angle unit (`1.5708 rad`)")),
    }
}

fn read_ball_bar(file: &mut DataFile<'_>) -> Result<Vec<BallBarRow>, MeasuredError> {
    file.check_preamble(&BALL_BAR_PREAMBLE)?;
    const KNOWN: [&str; 3] = ["angle_deg", "deviation_mm", "direction"];
    let (mut angle, mut deviation, mut direction) = (None, None, None);
    for (i, cell) in file.header.iter().enumerate() {
        let name = column_name(&cell.text);
        let slot = if name.has_any(&["angle", "theta"]) {
            &mut angle
        } else if name.has_any(&["deviation", "radial", "error", "dev", "deviations"]) {
            &mut deviation
        } else if name.is(&["direction"]) || name.is(&["dir"]) || name.is(&["run", "direction"]) {
            &mut direction
        } else if is_label(&name) {
            continue;
        } else {
            return Err(unknown_column(
                file,
                i,
                &KNOWN,
                "a ball bar trace's columns are the angle, the radial deviation and the direction of the run, \
                 each with its unit (`Angle (deg)`, `Deviation (um)`); see docs/measurements.md",
            ));
        };
        if slot.is_some() {
            return Err(file.cell_error(i, "second of this column", format!("a second column like `{}`", cell.text)));
        }
        *slot = Some((i, name));
    }
    let Some((deviation, deviation_name)) = deviation else {
        return Err(file.header_error("this header", "the header has no `deviation_mm` column").with_hint(
            "the radial deviation (actual − nominal length of the bar) is `deviation_mm`, or `Deviation (um)`",
        ));
    };
    let deviation_mm = length_unit(file, deviation, &deviation_name, &file.header[deviation].text)?;
    // The angle: a column in the file's sense from its zero, or counted from a start angle.
    let zero = match file.meta("angle_zero") {
        None => 0.0,
        Some(entry) => match entry.value.to_lowercase().replace(' ', "").trim_end_matches("axis") {
            "+z" | "z" | "z+" => 0.0,
            "+x" | "x" | "x+" => 90.0,
            "-z" | "z-" => 180.0,
            "-x" | "x-" => 270.0,
            _ => {
                return Err(DataFile::meta_error(
                    entry,
                    "not an axis",
                    format!("`{}` is no axis of the XZ plane", entry.value),
                )
                .with_hint("write `angle zero: +z` (turnpass's), `+x`, `-z` or `-x`"));
            }
        },
    };
    let sense = match file.meta("angle_sense") {
        None => 1.0,
        Some(entry) => match run_direction(&entry.value) {
            Some(direction) => direction.sign(),
            None => {
                return Err(DataFile::meta_error(
                    entry,
                    "not a sense",
                    format!("`{}` is no sense of rotation", entry.value),
                )
                .with_hint("write `angle sense: ccw` (turnpass's: from +Z toward +X, as G03 turns) or `cw`"));
            }
        },
    };
    let said_direction = match file.meta("direction") {
        None => None,
        Some(entry) => Some(run_direction(&entry.value).ok_or_else(|| {
            DataFile::meta_error(entry, "not a direction", format!("`direction` is `{}`", entry.value))
                .with_hint(DIRECTION_HINT)
        })?),
    };
    let direction = direction.map(|(i, _)| i);
    if let (Some(i), Some(entry)) = (direction, file.meta("direction")) {
        let message = format!("the file has a direction column (`{}`) and a `direction` line", file.header[i].text);
        return Err(DataFile::meta_error(entry, "a second direction", message).with_hint("keep one of the two"));
    }
    if direction.is_none() && said_direction.is_none() {
        return Err(file.header_error("this header", "the trace says no direction of its run").with_hint(
            "give a `direction` column (ccw or cw on each row), or a line `direction: anticlockwise` above the header",
        ));
    }
    enum Angles {
        Column(usize, f64),
        Counted { start: f64, step: f64 },
    }
    let angles = match (angle, file.meta("start_angle"), file.meta("angle_step")) {
        (Some((i, name)), start, _) => {
            if let Some(entry) = start {
                return Err(DataFile::meta_error(
                    entry,
                    "a start angle beside an angle column",
                    "the trace has an angle column and a start angle",
                )
                .with_hint("a start angle places rows with no angle column: keep one of the two"));
            }
            let unit = match name.unit {
                Some(unit) => Some(unit),
                None => file
                    .meta("angle_units")
                    .map(|e| {
                        Unit::parse(&e.value).ok_or_else(|| {
                            DataFile::meta_error(e, "not a unit", format!("`{}` is no unit turnpass knows", e.value))
                        })
                    })
                    .transpose()?,
            };
            let Some(radians) = unit.and_then(Unit::radians) else {
                let cell = &file.header[i].text;
                return Err(file
                    .cell_error(i, "no angle unit", format!("the angle column `{cell}` has no angle unit"))
                    .with_hint(format!(
                        "write it in the header, `{cell} (deg)`, or add a line `angle units: deg` above the header"
                    )));
            };
            Angles::Column(i, radians.to_degrees())
        }
        (None, Some(start), Some(step)) => {
            Angles::Counted { start: preamble_degrees(start)?, step: preamble_degrees(step)? }
        }
        (None, _, _) => {
            return Err(file.header_error("this header", "the trace has no angle").with_hint(
                "give an angle column (`angle_deg`, `Angle (deg)`), or lines `start angle: 0` and `angle step: 1` above \
                 the header for rows taken at equal steps in the direction of the run",
            ));
        }
    };
    let mut out: Vec<BallBarRow> = Vec::new();
    let deviation_text = file.header[deviation].text.clone();
    let direction_text = direction.map(|i| file.header[i].text.clone());
    let angle_text = match angles {
        Angles::Column(c, _) => file.header[c].text.clone(),
        Angles::Counted { .. } => String::new(),
    };
    file.rows(|row| {
        let run = match direction {
            Some(c) => {
                let text = row.text(c, direction_text.as_deref().unwrap_or("direction"))?;
                run_direction(text).ok_or_else(|| {
                    row.error(c, "not a direction", format!("`direction` is `{text}`: write `ccw` (G03) or `cw` (G02)"))
                        .with_hint(DIRECTION_HINT)
                })?
            }
            None => said_direction.unwrap_or(Direction::Ccw),
        };
        let value = row.number(deviation, &deviation_text)? * deviation_mm;
        if value.abs() > 1.0 {
            return Err(row
                .error(
                    deviation,
                    "not a deviation",
                    format!("a ball bar deviation of {value} mm is not a deviation: write actual − nominal radius"),
                )
                .with_hint("check the column's unit"));
        }
        let angle_deg = match angles {
            Angles::Column(c, degrees) => zero + sense * row.number(c, &angle_text)? * degrees,
            Angles::Counted { start, step } => {
                // Rows follow the run: each one a step further in its direction.
                let k = out.len() as f64;
                zero + sense * start + run.sign() * k * step
            }
        };
        let angle_deg = angle_deg.rem_euclid(360.0) + 0.0;
        out.push(BallBarRow { angle_deg, deviation_mm: value, direction: run, line: row.line });
        Ok(())
    })?;
    Ok(out)
}

/// What X is in a CMM file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum XIs {
    Radius,
    Diameter,
}

fn read_profile(file: &mut DataFile<'_>) -> Result<Vec<ProfilePoint>, MeasuredError> {
    file.check_preamble(&PROFILE_PREAMBLE)?;
    const KNOWN: [&str; 4] = ["x_mm", "z_mm", "part", "start_min"];
    let said = match file.meta("x") {
        None => None,
        Some(entry) => Some(match entry.value.to_lowercase().trim() {
            "radius" | "r" | "radii" => XIs::Radius,
            "diameter" | "dia" | "d" | "diameters" => XIs::Diameter,
            _ => {
                return Err(DataFile::meta_error(entry, "not radius or diameter", format!("`x` is `{}`", entry.value))
                    .with_hint("write `x: radius` or `x: diameter`"));
            }
        }),
    };
    let (mut x, mut y, mut z, mut part, mut start) = (None, None, None, None, None);
    for (i, cell) in file.header.iter().enumerate() {
        let name = column_name(&cell.text);
        let radius = name.has_any(&["radius", "radii"]) || name.is(&["x", "r"]);
        let diameter = name.has_any(&["diameter", "dia", "diam"]) || name.is(&["x", "d"]);
        let slot = if name.is(&["x"]) || ((radius || diameter) && !name.has("z")) {
            // `x_mm` is turnpass's own column: a radius, as its format says.
            let is = if cell.text.eq_ignore_ascii_case("x_mm") || radius {
                Some(XIs::Radius)
            } else if diameter {
                Some(XIs::Diameter)
            } else {
                None
            };
            if let (Some(is), Some(said), Some(entry)) = (is, said, file.meta("x"))
                && is != said
            {
                let message =
                    format!("the column `{}` and the line `x: {}` say different things", cell.text, entry.value);
                return Err(DataFile::meta_error(entry, "not what the column says", message));
            }
            if x.is_some() {
                return Err(file.cell_error(i, "second of this column", "a second X column"));
            }
            x = Some((i, name, is.or(said)));
            continue;
        } else if name.is(&["y"]) {
            &mut y
        } else if name.is(&["z"]) {
            &mut z
        } else if name.is(&["part"])
            || name.is(&["part", "name"])
            || name.is(&["part", "id"])
            || name.is(&["workpiece"])
        {
            &mut part
        } else if name.is(&["start"]) || name.is(&["start", "min"]) || name.is(&["start", "time"]) {
            &mut start
        } else if is_label(&name)
            || name.is(&["i"])
            || name.is(&["j"])
            || name.is(&["k"])
            || name.has_any(&["nx", "ny", "nz", "normal"])
        {
            // A point's name, and the surface normal the CMM software gives: turnpass takes
            // the normal of the program's surface at the point.
            continue;
        } else {
            return Err(unknown_column(
                file,
                i,
                &KNOWN,
                "a CMM profile's columns are X (a radius or a diameter, said in the column's name or a line `x: \
                 radius` or `x: diameter`), Z, optionally Y (X and Y then place the point across the axis), part \
                 and start_min; see docs/measurements.md",
            ));
        };
        if slot.is_some() {
            return Err(file.cell_error(i, "second of this column", format!("a second column like `{}`", cell.text)));
        }
        *slot = Some((i, name));
    }
    let Some((x, x_name, x_is)) = x else {
        return Err(file
            .header_error("this header", "the header has no `x_mm` column")
            .with_hint("X across the part's axis: `x_mm` (a radius), `X radius (mm)` or `X diameter (mm)`"));
    };
    let Some((z, z_name)) = z else {
        return Err(file
            .header_error("this header", "the header has no `z_mm` column")
            .with_hint("Z along the part's axis from its datum face: `z_mm` or `Z (mm)`"));
    };
    let x_is = match (x_is, &y) {
        // With Y, X and Y are the point's coordinates across the axis.
        (Some(XIs::Diameter), Some((i, _))) => {
            return Err(file
                .cell_error(*i, "a Y beside a diameter", "X is a diameter, and the file has a Y coordinate")
                .with_hint(
                    "with a Y column, X and Y are the coordinates across the part's axis: leave the diameter out",
                ));
        }
        (_, Some(_)) => XIs::Radius,
        (Some(is), None) => is,
        (None, None) => {
            let cell = &file.header[x].text;
            return Err(file
                .cell_error(x, "a radius or a diameter?", format!("the column `{cell}` may be a radius or a diameter"))
                .with_hint(
                    "say which: a line `x: radius` or `x: diameter` above the header, or name the column `X radius` or \
                     `X diameter` (a CMM measures a turned part's diameter; turnpass's own `x_mm` is a radius)",
                ));
        }
    };
    let x_mm = length_unit(file, x, &x_name, &file.header[x].text)? * if x_is == XIs::Diameter { 0.5 } else { 1.0 };
    let z_mm = length_unit(file, z, &z_name, &file.header[z].text)?;
    let y_mm = match &y {
        Some((i, name)) => Some((*i, length_unit(file, *i, name, &file.header[*i].text)?)),
        None => None,
    };
    if let Some((i, name)) = &start
        && name.unit.is_some_and(|u| u != Unit::Min)
    {
        return Err(file.cell_error(*i, "not minutes", "a part's start time is in minutes since the machine started"));
    }
    let names: Vec<String> = file.header.iter().map(|c| c.text.clone()).collect();
    let (part, start) = (part.map(|(i, _)| i), start.map(|(i, _)| i));
    let mut out: Vec<ProfilePoint> = Vec::new();
    // Each part's start time and the line that first gave it.
    let mut started: std::collections::HashMap<Option<String>, (Option<f64>, usize)> = Default::default();
    file.rows(|row| {
        let mut x_value = row.number(x, &names[x])? * x_mm;
        if let Some((i, scale)) = y_mm {
            x_value = x_value.hypot(row.number(i, &names[i])? * scale);
        }
        if x_value < 0.0 {
            let what = if x_is == XIs::Diameter { "a diameter" } else { "a radius" };
            return Err(row.error(
                x,
                "negative",
                format!("{} is {}: x is {what} from the axis of rotation, never negative", names[x], row.cell(x)),
            ));
        }
        let part = part.map(|c| row.text(c, &names[c]).map(str::to_string)).transpose()?;
        let start_min = start.map(|c| row.number(c, &names[c])).transpose()?;
        let (first_start, first_line) = *started.entry(part.clone()).or_insert((start_min, row.line));
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
        let z_value = row.number(z, &names[z])? * z_mm;
        out.push(ProfilePoint { x_mm: x_value, z_mm: z_value, part, start_min, line: row.line });
        Ok(())
    })?;
    Ok(out)
}

/// A thermal log (`t_min,value`): times in minutes, increasing, and the logged values.
pub fn read_thermal_log(text: &str) -> Result<(Vec<f64>, Vec<f64>), MeasuredError> {
    let mut file = DataFile::open(text)?;
    const KNOWN: [&str; 2] = ["t_min", "value"];
    let mut columns = [None, None];
    for (i, cell) in file.header.iter().enumerate() {
        let Some(k) = KNOWN.iter().position(|k| cell.text.eq_ignore_ascii_case(k)) else {
            return Err(unknown_column(&file, i, &KNOWN, "a thermal log's columns are t_min and value"));
        };
        if columns[k].is_some() {
            return Err(file.cell_error(i, "second of this name", format!("the column `{}` appears twice", KNOWN[k])));
        }
        columns[k] = Some(i);
    }
    let [Some(t), Some(v)] = columns else {
        let missing = if columns[0].is_none() { "t_min" } else { "value" };
        return Err(file.header_error("this header", format!("the header has no `{missing}` column")));
    };
    let mut times: Vec<f64> = Vec::new();
    let mut values = Vec::new();
    file.rows(|row| {
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

#[cfg(test)]
mod tests;
