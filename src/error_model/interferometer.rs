//! Interferometer tables of one slide in the style of ISO 230-2 / ASME B5.57: for each
//! target position, runs in each direction, with the linear positioning deviation and,
//! where measured, the straightness and the angular error of the slide.
//!
//! One reader takes the table in the layouts laser software exports (`docs/measurements.md`),
//! each a mapping of its columns onto the same readings (target, direction, run, quantity):
//!
//! * long, a row per reading: a target column, a `direction` column (up/down, +/−,
//!   forward/reverse, ↑/↓), optionally a `run` column, and a column per quantity: the
//!   canonical `target_mm,direction,run,linear_mm,straightness_mm,straightness_m1_mm,
//!   straightness_m2_mm,angular_deg`, or names with their units (`Target (mm)`,
//!   `Error (µm)`, `Pitch (arcsec)`);
//! * wide, a row per target: a target column and a column per run and direction
//!   (`Run 1 Fwd (um)`, `Run 1 Rev (um)`, …: ISO 230-2's runs j = 1, 2, … in each direction),
//!   linear readings unless the name says another quantity.
//!
//! A column's unit is in its name, else in the preamble (`units: um`, `target units: in`,
//! `angle units: arcsec`); linear readings are errors (measured − target) or positions, as
//! the name (`error`, `position`) or the preamble (`readings: positions`) says, else as the
//! values tell (an error is within 1 mm of zero, a position within 1 mm of its target; when
//! both or neither hold, the file must say). Columns the software computed from the runs
//! (means, spreads, the reversal) and the conditions it logged (temperatures, time) are not
//! read. Any other column is refused: a misspelt name would otherwise drop its data. The two
//! straightness runs of the reversal technique are reduced by eq. 2.7 of the thesis,
//! `s = (m2 − m1)/2`. Values are kept as deviations in mm and angles in radians.
//!
//! The model uses the mean deviation of the direction the slide moves in (the mean
//! bidirectional deviation ± half the reversal value), interpolated linearly between
//! targets and held at the end values beyond them. `report` gives the ISO 230-2 figures.

use std::collections::BTreeMap;

use crate::measurement_file::{ColumnName, DataError, DataFile, Row, Unit, column_name};
use crate::source::Span;

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
    /// The straightness was given as the two runs of the reversal technique (eq. 2.5–2.7).
    pub straightness_by_reversal: bool,
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

/// The columns of the canonical long layout, in the order the documentation gives them.
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

/// The preamble keys a table's reader takes (`measurement_file`).
pub const PREAMBLE: [&str; 9] =
    ["units", "unit", "target_units", "position_units", "angle_units", "angular_units", "readings", "axis", "slide"];

/// What a table's reading is of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Quantity {
    Linear,
    Straightness,
    /// The two runs of the reversal technique.
    StraightnessM1,
    StraightnessM2,
    Angular,
}

impl Quantity {
    fn index(self) -> usize {
        match self {
            Quantity::Linear => 0,
            Quantity::Straightness => 1,
            Quantity::StraightnessM1 => 2,
            Quantity::StraightnessM2 => 3,
            Quantity::Angular => 4,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Quantity::Linear => "linear positioning",
            Quantity::Straightness => "straightness",
            Quantity::StraightnessM1 => "straightness (reversal run m1)",
            Quantity::StraightnessM2 => "straightness (reversal run m2)",
            Quantity::Angular => "angular",
        }
    }
}

/// Whether a linear column's readings are errors (measured − target) or the positions the
/// laser measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Form {
    Errors,
    Positions,
    /// Neither its name nor the preamble says: the values tell (`resolve_form`).
    Unsaid,
}

/// A column of readings.
#[derive(Debug, Clone, Copy)]
struct Readings {
    quantity: Quantity,
    /// The direction of approach its name gives (wide layout): `true` up.
    up: Option<bool>,
    /// The run its name gives (wide layout).
    run: Option<u32>,
    /// Millimetres (lengths) or radians (angles) per value; for `Unit::Ppm`, per value and
    /// millimetre of target.
    unit: Unit,
    form: Form,
}

/// What a header cell is.
#[derive(Debug, Clone, Copy)]
enum Column {
    /// The target position, and millimetres per value.
    Target(f64),
    Direction,
    Run,
    Readings(Readings),
    /// A figure the instrument's software computed from the runs (a mean, a spread, the
    /// reversal), or the conditions it recorded (temperatures, time): recomputed or not
    /// used, so not read.
    Ignored,
}

/// The words of a direction of approach, up (toward +) and down.
const UP: [&str; 8] = ["up", "fwd", "forward", "forwards", "↑", "+", "positive", "plus"];
const DOWN: [&str; 11] =
    ["down", "rev", "reverse", "bwd", "back", "backward", "backwards", "↓", "-", "negative", "minus"];
/// Words of a column the software computed from the runs, or of the conditions of the test.
const IGNORED: [&str; 21] = [
    "mean",
    "average",
    "averages",
    "avg",
    "std",
    "stdev",
    "sigma",
    "reversal",
    "range",
    "dead",
    "uncertainty",
    "repeatability",
    "accuracy",
    "temp",
    "temperature",
    "pressure",
    "humidity",
    "time",
    "date",
    "timestamp",
    "comp",
];
const LINEAR: [&str; 11] =
    ["linear", "positioning", "error", "errors", "deviation", "deviations", "dev", "devn", "err", "reading", "value"];
const ERRORS: [&str; 9] = ["linear", "positioning", "error", "errors", "deviation", "deviations", "dev", "devn", "err"];
const POSITIONS: [&str; 4] = ["position", "actual", "measured", "laser"];
const STRAIGHTNESS: [&str; 3] = ["straightness", "straight", "str"];
const ANGULAR: [&str; 6] = ["angular", "angle", "pitch", "yaw", "roll", "tilt"];

/// A direction of approach as a row or a column name writes it.
fn direction(word: &str) -> Option<bool> {
    let word = word.trim().to_lowercase();
    if UP.contains(&word.as_str()) {
        Some(true)
    } else if DOWN.contains(&word.as_str()) {
        Some(false)
    } else {
        None
    }
}

/// The unit of a column of `quantity`: its own, else the preamble's for such values.
fn reading_unit(file: &DataFile<'_>, i: usize, name: &ColumnName, quantity: Quantity) -> Result<Unit, DataError> {
    let angular = quantity == Quantity::Angular;
    let keys: &[&str] = if angular { &["angle_units", "angular_units"] } else { &["units", "unit"] };
    let unit = match name.unit {
        Some(unit) => unit,
        None => {
            let Some(entry) = file.meta_any(keys) else {
                let cell = &file.header[i].text;
                // A canonical name misspelt (`linear_mn`) is that, not a column with no unit.
                let canonical_like = cell.contains('_') && !cell.contains(' ');
                if let Some(near) = crate::toml_spans::nearest(cell, COLUMNS).filter(|_| canonical_like) {
                    let mut error =
                        file.cell_error(i, "unknown column", format!("the column `{cell}` is none a table has"));
                    error.unknown_column = Some(cell.clone());
                    return Err(error.with_hint(format!("did you mean `{near}`?")));
                }
                let example = if angular { "arcsec" } else { "um" };
                return Err(file.cell_error(i, "no unit", format!("the column `{cell}` has no unit")).with_hint(
                    format!(
                        "write it in the header, `{cell} ({example})`, or add a line `{}: {example}` above the header",
                        keys[0].replace('_', " ")
                    ),
                ));
            };
            Unit::parse(&entry.value).ok_or_else(|| {
                DataFile::meta_error(entry, "not a unit", format!("`{}` is no unit turnpass knows", entry.value))
                    .with_hint(UNITS_HINT)
            })?
        }
    };
    let fits = match quantity {
        Quantity::Angular => unit.radians().is_some() || unit == Unit::Ppm,
        Quantity::Linear => unit.mm().is_some() || unit == Unit::Ppm,
        _ => unit.mm().is_some(),
    };
    if !fits {
        let cell = &file.header[i].text;
        return Err(file
            .cell_error(
                i,
                "not a unit of this quantity",
                format!("`{cell}` is {}, given in {}", quantity.name(), unit.name()),
            )
            .with_hint(if angular {
                "an angle is in deg, rad, mrad, µrad or arcsec"
            } else {
                "a length is in mm, µm, nm or in (a linear error also in ppm of its target)"
            }));
    }
    Ok(unit)
}

const UNITS_HINT: &str = "lengths are mm, um (µm), nm or in; a linear error may be ppm of its target; angles deg, rad, \
                          mrad, urad (µrad) or arcsec";

/// Each header cell's meaning.
fn map_columns(file: &DataFile<'_>) -> Result<Vec<Column>, DataError> {
    let readings_said = match file.meta("readings") {
        None => None,
        Some(entry) => Some(match entry.value.to_lowercase().as_str() {
            "errors" | "error" | "deviations" | "deviation" => Form::Errors,
            "positions" | "position" => Form::Positions,
            _ => {
                return Err(DataFile::meta_error(
                    entry,
                    "not errors or positions",
                    "`readings` is `errors` or `positions`",
                )
                .with_hint("errors: measured − target; positions: what the laser measured"));
            }
        }),
    };
    let mut columns = Vec::with_capacity(file.header.len());
    for (i, cell) in file.header.iter().enumerate() {
        let name = column_name(&cell.text);
        let up = name.words.iter().find_map(|w| direction(w));
        let both_ways = name.words.iter().any(|w| direction(w) == Some(true))
            && name.words.iter().any(|w| direction(w) == Some(false));
        let numbered = !name.numbers().is_empty();
        let column = if name.words.is_empty() {
            None
        } else if name.has_any(&IGNORED) {
            Some(Column::Ignored)
        } else if name.has_any(&["target", "nominal", "commanded"]) && up.is_none() && !numbered {
            let unit = match name.unit {
                Some(unit) => Some(unit),
                None => file
                    .meta_any(&["target_units", "position_units"])
                    .map(|e| {
                        Unit::parse(&e.value).ok_or_else(|| {
                            DataFile::meta_error(e, "not a unit", format!("`{}` is no unit turnpass knows", e.value))
                                .with_hint(UNITS_HINT)
                        })
                    })
                    .transpose()?,
            };
            let Some(mm) = unit.and_then(Unit::mm) else {
                let message = match unit {
                    Some(unit) => format!("the target column `{}` is in {}, not a length", cell.text, unit.name()),
                    None => format!("the target column `{}` has no unit", cell.text),
                };
                return Err(file.cell_error(i, "no length unit", message).with_hint(format!(
                    "write it in the header, `{} (mm)`, or add a line `target units: mm` above the header",
                    cell.text
                )));
            };
            Some(Column::Target(mm))
        } else if (name.is(&["direction"]) || name.is(&["dir"]) || name.is(&["approach"])) && !numbered {
            Some(Column::Direction)
        } else if name.is(&["run"]) || name.is(&["run", "number"]) || name.is(&["run", "no"]) || name.is(&["cycle"]) {
            Some(Column::Run)
        } else if both_ways {
            return Err(file.cell_error(
                i,
                "both directions",
                format!("the column `{}` names both directions", cell.text),
            ));
        } else {
            let quantity = if name.has_any(&STRAIGHTNESS) {
                Some(if name.has("m1") {
                    Quantity::StraightnessM1
                } else if name.has("m2") {
                    Quantity::StraightnessM2
                } else {
                    Quantity::Straightness
                })
            } else if name.has_any(&ANGULAR) {
                Some(Quantity::Angular)
            } else if name.has_any(&LINEAR) || name.has_any(&POSITIONS) || up.is_some() || name.has("run") {
                Some(Quantity::Linear)
            } else {
                None
            };
            match quantity {
                None => None,
                Some(quantity) => {
                    let unit = reading_unit(file, i, &name, quantity)?;
                    let form = if quantity != Quantity::Linear || name.has_any(&ERRORS) {
                        Form::Errors
                    } else if name.has_any(&POSITIONS) {
                        Form::Positions
                    } else {
                        readings_said.unwrap_or(Form::Unsaid)
                    };
                    if form == Form::Positions && unit == Unit::Ppm {
                        return Err(file
                            .cell_error(i, "positions in ppm", format!("`{}` gives positions in ppm", cell.text))
                            .with_hint("a position is a length: mm, µm or in"));
                    }
                    let run = name.numbers().first().copied();
                    if up.is_none() && run.is_some() {
                        return Err(file
                            .cell_error(i, "no direction", format!("the column `{}` names a run but no direction", cell.text))
                            .with_hint(format!(
                                "ISO 230-2 numbers the runs j = 1, 2, … in each direction: write `Run {0} Fwd` and `Run {0} Rev` (or up/down, ↑/↓)",
                                run.unwrap_or(1)
                            )));
                    }
                    Some(Column::Readings(Readings { quantity, up, run, unit, form }))
                }
            }
        };
        match column {
            Some(column) => columns.push(column),
            None => {
                let mut error =
                    file.cell_error(i, "unknown column", format!("the column `{}` is none a table has", cell.text));
                error.unknown_column = Some(cell.text.clone());
                error.hint = Some(match crate::toml_spans::nearest(&cell.text, COLUMNS) {
                    Some(near) => format!("did you mean `{near}`?"),
                    None => "a table's columns are the target, the direction and run, and readings named by \
                             quantity (`error (um)`, `straightness (um)`, `pitch (arcsec)`) or by run and direction \
                             (`Run 1 Fwd (um)`); see docs/measurements.md"
                        .to_string(),
                });
                return Err(error);
            }
        }
    }
    check_layout(file, &columns)?;
    Ok(columns)
}

/// One target column; a direction column (long layout: a row per reading) or readings that
/// name their direction (wide layout: a row per target), not both; no column twice.
fn check_layout(file: &DataFile<'_>, columns: &[Column]) -> Result<(), DataError> {
    let count = |f: &dyn Fn(&Column) -> bool| columns.iter().filter(|c| f(c)).count();
    let second = |f: &dyn Fn(&Column) -> bool, what: &str| -> Result<(), DataError> {
        match columns.iter().enumerate().filter(|(_, c)| f(c)).nth(1) {
            Some((i, _)) => Err(file.cell_error(i, "second of this column", format!("a second {what} column"))),
            None => Ok(()),
        }
    };
    second(&|c| matches!(c, Column::Target(_)), "target")?;
    second(&|c| matches!(c, Column::Direction), "direction")?;
    second(&|c| matches!(c, Column::Run), "run")?;
    if count(&|c| matches!(c, Column::Target(_))) == 0 {
        return Err(file
            .header_error("this header", "the table has no target column")
            .with_hint("name the column of target positions `target_mm` or `Target (mm)`"));
    }
    let readings: Vec<(usize, Readings)> = columns
        .iter()
        .enumerate()
        .filter_map(|(i, c)| match c {
            Column::Readings(r) => Some((i, *r)),
            _ => None,
        })
        .collect();
    if readings.is_empty() {
        return Err(file.header_error("this header", "the table has no readings").with_hint(
            "a table's readings are linear positioning errors (`linear_mm`, `error (um)`, `Run 1 Fwd (um)`), \
             straightness or angular errors",
        ));
    }
    let direction_column = count(&|c| matches!(c, Column::Direction)) > 0;
    let wide = readings.iter().any(|(_, r)| r.up.is_some());
    if direction_column && wide {
        let (i, _) = readings.iter().find(|(_, r)| r.up.is_some()).copied().unwrap_or(readings[0]);
        return Err(file
            .cell_error(
                i,
                "a direction in its name",
                "this column names a direction, and the table has a direction column",
            )
            .with_hint(
                "a row per reading has a direction column; a row per target has a column per run and direction",
            ));
    }
    if !direction_column && !wide {
        return Err(file.header_error("this header", "the table has no direction of approach").with_hint(
            "give a `direction` column (up/down) for a row per reading, or a column per run and direction \
             (`Run 1 Fwd (um)`, `Run 1 Rev (um)`) for a row per target",
        ));
    }
    for (k, (i, r)) in readings.iter().enumerate() {
        if wide && r.up.is_none() {
            return Err(file.cell_error(*i, "no direction", "this column of readings names no direction").with_hint(
                "in a table with a row per target, each column of readings names its run and direction (`Run 1 Fwd`)",
            ));
        }
        if let Some((_, _)) = readings[..k]
            .iter()
            .find(|(_, o)| o.quantity == r.quantity && o.up == r.up && o.run.unwrap_or(1) == r.run.unwrap_or(1))
        {
            return Err(file.cell_error(*i, "second of this column", "a second column of the same readings"));
        }
    }
    Ok(())
}

/// A slide table and what its file's preamble says beside it.
pub struct TableFile {
    pub table: SlideTable,
    /// The preamble's `axis` (or `slide`): the slide it says it measured, `x` or `z`, with the
    /// line and span of the value.
    pub axis: Option<(char, usize, Span)>,
}

/// Read a slide's table (`read_file`, the preamble's axis left aside).
pub fn parse(text: &str) -> Result<SlideTable, DataError> {
    read_file(text).map(|file| file.table)
}

/// Read a slide's table in any of its layouts (the module documentation).
pub fn read_file(text: &str) -> Result<TableFile, DataError> {
    let mut file = DataFile::open(text)?;
    file.check_preamble(&PREAMBLE)?;
    let axis = match file.meta_any(&["axis", "slide"]) {
        None => None,
        Some(entry) => {
            let letter = entry.value.trim().to_lowercase();
            let letter = letter.strip_suffix(" axis").unwrap_or(&letter).trim();
            match letter {
                "x" => Some(('x', entry.line, entry.value_span)),
                "z" => Some(('z', entry.line, entry.value_span)),
                _ => {
                    return Err(DataFile::meta_error(
                        entry,
                        "not a slide",
                        format!("`{}` is no slide of a lathe", entry.value),
                    )
                    .with_hint("write `axis: x` or `axis: z`"));
                }
            }
        }
    };
    let columns = map_columns(&file)?;
    let target = columns.iter().position(|c| matches!(c, Column::Target(_))).unwrap_or(0);
    let target_mm = match columns[target] {
        Column::Target(mm) => mm,
        _ => 1.0,
    };
    let direction_column = columns.iter().position(|c| matches!(c, Column::Direction));
    let run_column = columns.iter().position(|c| matches!(c, Column::Run));
    let names: Vec<String> = file.header.iter().map(|c| c.text.clone()).collect();
    // Per quantity, per target (keyed by its exact bits, in order), the runs each way.
    let mut data: Vec<BTreeMap<OrderedTarget, Runs>> = (0..5).map(|_| BTreeMap::new()).collect();
    // Linear readings whose form the values decide: column, target (mm), up, value (mm).
    let mut unsaid: Vec<(usize, f64, bool, f64)> = Vec::new();
    // Each column's largest deviation, mm.
    let mut largest = vec![0.0f64; columns.len()];
    file.rows(|row| {
        let t = row.number(target, &names[target])? * target_mm;
        let row_up = match direction_column {
            Some(c) => {
                let text = row.text(c, &names[c])?;
                Some(direction(text).ok_or_else(|| {
                    row.error(c, "not a direction", format!("direction `{text}` is neither up nor down"))
                        .with_hint("write up or down (+ or -, forward or reverse, ↑ or ↓)")
                })?)
            }
            None => None,
        };
        if let Some(c) = run_column {
            row.number(c, &names[c])?;
        }
        for (c, column) in columns.iter().enumerate() {
            let Column::Readings(r) = column else { continue };
            let Some(v) = row.number_or_empty(c, &names[c])? else { continue };
            let up = r.up.or(row_up).unwrap_or(true);
            let value = match (r.quantity, r.unit, r.form) {
                (Quantity::Angular, Unit::Ppm, _) => v * 1e-6,
                (Quantity::Angular, unit, _) => v * unit.radians().unwrap_or(1.0),
                (_, Unit::Ppm, _) => v * 1e-6 * t,
                (_, unit, Form::Positions) => v * unit.mm().unwrap_or(1.0) - t,
                (Quantity::Linear, unit, Form::Unsaid) => {
                    unsaid.push((c, t, up, v * unit.mm().unwrap_or(1.0)));
                    continue;
                }
                (_, unit, _) => v * unit.mm().unwrap_or(1.0),
            };
            if r.quantity != Quantity::Angular {
                plausible(row, c, &names[c], value, r.unit)?;
                largest[c] = largest[c].max(value.abs());
            }
            let runs = data[r.quantity.index()].entry(OrderedTarget(t)).or_default();
            if up { runs.up.push(value) } else { runs.down.push(value) }
        }
        Ok(())
    })?;
    if let Some(errors) = resolve_form(&file, &unsaid)? {
        for (c, t, up, v) in unsaid {
            let runs = data[Quantity::Linear.index()].entry(OrderedTarget(t)).or_default();
            let value = if errors { v } else { v - t };
            largest[c] = largest[c].max(value.abs());
            if up { runs.up.push(value) } else { runs.down.push(value) }
        }
    }
    // Millimetres under a micrometre header read as nanometres: no laser table is that good.
    for (c, column) in columns.iter().enumerate() {
        let Column::Readings(r) = column else { continue };
        if matches!(r.unit, Unit::Um | Unit::Nm) && largest[c] > 0.0 && largest[c] < TOO_SMALL_MM {
            let cell = &names[c];
            let message = format!(
                "every reading of `{cell}` is below {} {} (the largest is {:.4} {}): they look like millimetres under a {} header",
                if r.unit == Unit::Nm { "50" } else { "0.05" },
                r.unit.name(),
                largest[c] / r.unit.mm().unwrap_or(1.0),
                r.unit.name(),
                r.unit.name()
            );
            return Err(file.cell_error(c, "a unit the values do not fit", message).with_hint(
                "write the unit the values are in (`linear_mm`, `Error (mm)`), or give the values in the unit the header says",
            ));
        }
    }
    let profile = |k: usize| build(&data[k]);
    let (straightness, by_reversal) = match (profile(1), profile(2), profile(3)) {
        (Some(s), _, _) => (Some(s), false),
        (None, Some(m1), Some(m2)) => (Some(reversal(&m1, &m2)), true),
        _ => (None, false),
    };
    let table = SlideTable {
        linear: profile(0),
        straightness,
        angular: profile(4),
        rows: file.rows_read(),
        straightness_by_reversal: by_reversal,
    };
    if table.linear.is_none() && table.straightness.is_none() && table.angular.is_none() {
        return Err(file.header_error("this header", "the table has no readings in its rows"));
    }
    Ok(TableFile { table, axis })
}

/// The largest deviation a table's reading may be, mm: a slide off by more is not measured
/// with a laser, and the reading is in another unit than its header says.
pub const LARGEST_DEVIATION_MM: f64 = 1.0;

/// Readings all smaller than this, mm (50 nm), under a µm or nm header are millimetres.
const TOO_SMALL_MM: f64 = 5e-5;

/// A deviation `value` (mm) of column `c` of `row` within [`LARGEST_DEVIATION_MM`].
fn plausible(row: &Row<'_>, c: usize, name: &str, value: f64, unit: Unit) -> Result<(), DataError> {
    if value.abs() <= LARGEST_DEVIATION_MM {
        return Ok(());
    }
    Err(row
        .error(c, "not a deviation", format!("`{name}` reads as a deviation of {value} mm, which no slide has"))
        .with_hint(format!(
            "check the column's unit (it reads as {}); a reading that is a position needs `readings: positions` or a \
             name that says so (`Run 1 Fwd position (mm)`)",
            unit.name()
        )))
}

/// Whether linear readings whose name and preamble say nothing are errors (`Some(true)`) or
/// positions, told by their values: an error is within 1 mm of zero, a position within 1 mm
/// of its target. When both fit (every target within 2 mm of zero) or neither, the file must
/// say. `None` when there are no such readings.
fn resolve_form(file: &DataFile<'_>, unsaid: &[(usize, f64, bool, f64)]) -> Result<Option<bool>, DataError> {
    let Some(&(column, ..)) = unsaid.first() else { return Ok(None) };
    let errors = unsaid.iter().all(|&(_, _, _, v)| v.abs() <= 1.0);
    let positions = unsaid.iter().all(|&(_, t, _, v)| (v - t).abs() <= 1.0);
    let name = &file.header[column].text;
    let hint = "say which with a line `readings: errors` (measured − target) or `readings: positions` above the header, or \
                name the column so (`Run 1 Fwd error (um)`)";
    match (errors, positions) {
        (true, false) => Ok(Some(true)),
        (false, true) => Ok(Some(false)),
        (true, true) => Err(file
            .cell_error(column, "errors or positions", format!("the readings of `{name}` may be errors or positions: every target lies within 2 mm of zero"))
            .with_hint(hint)),
        (false, false) => Err(file
            .cell_error(
                column,
                "neither errors nor positions",
                format!("the readings of `{name}` are neither errors (some exceed 1 mm) nor positions (some lie more than 1 mm from their targets)"),
            )
            .with_hint("check the column's unit; then say what its readings are: `readings: errors` or `readings: positions`")),
    }
}

#[derive(Default)]
struct Runs {
    up: Vec<f64>,
    down: Vec<f64>,
}

/// A target position as a map key: equal targets are read from equal text, so they have
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
