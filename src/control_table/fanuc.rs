//! A Fanuc's pitch-error compensation data and backlash parameter, as a parameter tape.
//!
//! What the manuals at hand say (each read as an excerpt of a public copy; none could be
//! read whole):
//!
//! * Parameter 1851, "Backlash compensating value for each axis": word axis, detection
//!   unit, −9999 to +9999; "When the machine moves in a direction opposite to the
//!   reference position return direction after the power is turned on, the first backlash
//!   compensation is performed" (FANUC Series 0i/0i Mate Model C Parameter Manual,
//!   B-64120EN/01, p. 116). The model's machine starts as after a reference return in +.
//! * Parameters 3620 (number of the compensation point of the reference position), 3621
//!   and 3622 (the farthest points in − and in +), 3623 (magnification), 3624 (interval
//!   between points), 3605#0 (bidirectional compensation, an option), 3626 and 3627 (its
//!   points and the value at the reference position when approached the other way) (FANUC
//!   Technical Report A-77810E, Series 16i/18i-MA/TA Bidirectional Pitch Error
//!   Compensation, 2000).
//! * The value of each point is an increment: the compensation is output at the point that
//!   corresponds to each section between compensation positions, and the absolute
//!   compensation is their sum from the reference position ("Pitch error compensation
//!   amount (absolute value)"; for a rotary axis, "if the sum of the compensation value
//!   from 61 to 68 is not zero, the pitch error per rotation accumulates") (FANUC Series
//!   0i-PB Parameter Manual, B-63980EN/01, p. 100).
//!
//! What those excerpts do not settle, and this file therefore assumes (the output says it
//! is unverified): the tape's syntax (`N<parameter> A<axis> P<value>`, pitch data at
//! `N10000` plus the point number, between `%` lines, comments in parentheses); that X is
//! axis 1 and Z axis 2; that point `n` stands at `reference + (n − 3620)·interval` and its
//! value is the increment from point `n − 1` to it, output when the machine reaches it
//! (a staircase, held between points, zero at the reference position); the interval in
//! detection units; a value of at most ±7 per point times the magnification; at most
//! 1024 points (0 to 1023), half of them per axis here; X in radius. A service engineer
//! checks them against the machine's own parameter manual before loading.

use std::fmt::Write as _;

use super::{Loaded, ReadError, Table, axis_compensation, line_span, mm_per_unit, number, units_name};
use crate::error_model::control::{Between, ControlCompensation};
use crate::error_model::model_file::Axis;
use crate::machine::Units;
use crate::toolpath::Xz;

/// The most compensation points an axis gets here: half of the 1024 point numbers.
pub const MAX_POINTS_PER_AXIS: usize = 512;

/// The largest value of one point, before the magnification.
pub const MAX_POINT_VALUE: i64 = 7;

/// The first data number of the pitch-error points.
pub const DATA_BASE: i64 = 10000;

/// Why the output is marked unverified (module documentation).
pub const UNVERIFIED: &str = "the Fanuc tape's syntax, its point numbering and staircase, the interval's unit, the \
     ±7 range of a point, X as axis 1 in radius and Z as axis 2 are our reading of the manuals' excerpts at hand, \
     not checked against a whole Fanuc manual or a control: check them against the machine's parameter manual";

/// The parameter-axis index of each axis.
fn axis_index(axis: Axis) -> usize {
    match axis {
        Axis::X => 1,
        Axis::Z => 2,
    }
}

/// One axis' data as written: the parameters and the points' increments.
struct AxisData {
    axis: Axis,
    backlash: i64,
    /// Present for an axis with a pitch table.
    pitch: Option<Pitch>,
}

/// An axis' pitch-error parameters and points.
struct Pitch {
    /// 3620: the point of the reference position.
    reference: i64,
    /// 3621, 3622: the farthest points in − and in +.
    first: i64,
    last: i64,
    /// 3623.
    magnification: i64,
    /// 3624, detection units.
    interval: i64,
    /// The points' values, from `first`.
    points: Vec<i64>,
}

fn data(table: &Table) -> Vec<AxisData> {
    let unit = table.options.unit;
    let mut next_number: i64 = 0;
    let mut out = Vec::new();
    for axis_table in &table.axes {
        let backlash = (axis_table.backlash / unit).round() as i64;
        if axis_table.positions.is_empty() {
            out.push(AxisData { axis: axis_table.axis, backlash, pitch: None });
            continue;
        }
        let reference = axis_table.positions.iter().position(|p| p.abs() < axis_table.spacing * 1e-6).unwrap_or(0);
        let values = &axis_table.forward;
        let relative: Vec<f64> = values.iter().map(|v| (v - values[reference]) / unit).collect();
        let increments = |magnification: f64| -> Vec<i64> {
            let absolute: Vec<i64> = relative.iter().map(|v| (v / magnification).round() as i64).collect();
            (0..absolute.len()).map(|k| if k == 0 { 0 } else { absolute[k] - absolute[k - 1] }).collect()
        };
        let largest = increments(1.0).iter().map(|v| v.abs()).max().unwrap_or(0);
        let mut magnification = ((largest as f64) / MAX_POINT_VALUE as f64).ceil().max(1.0) as i64;
        while increments(magnification as f64).iter().any(|v| v.abs() > MAX_POINT_VALUE) {
            magnification += 1;
        }
        let points = increments(magnification as f64);
        let first = next_number;
        next_number += points.len() as i64;
        let interval = (axis_table.spacing / unit).round() as i64;
        out.push(AxisData {
            axis: axis_table.axis,
            backlash,
            pitch: Some(Pitch {
                reference: first + reference as i64,
                first,
                last: first + points.len() as i64 - 1,
                magnification,
                interval,
                points,
            }),
        });
    }
    out
}

pub fn write(table: &Table) -> super::Written {
    let options = &table.options;
    let scale = mm_per_unit(options.units);
    let mut tape = String::from("%\n");
    let header = &options.header;
    let _ = writeln!(tape, "(TURNPASS {} FANUC PITCH ERROR AND BACKLASH DATA, UNVERIFIED)", header.version);
    let _ = writeln!(tape, "(MODEL {}, SHA256 {})", printable(&header.model), header.model_sha256.to_ascii_uppercase());
    let _ = writeln!(
        tape,
        "(UNITS {}, DETECTION UNIT {}, ZERO X {} Z {})",
        units_name(options.units).to_ascii_uppercase(),
        number(options.unit, 8),
        number(options.zero.x / scale, 8),
        number(options.zero.z / scale, 8)
    );
    let data = data(table);
    let parameter = |number: u32, value: &dyn Fn(&AxisData) -> Option<i64>| -> String {
        let mut line = format!("N{number}");
        for axis in &data {
            if let Some(v) = value(axis) {
                let _ = write!(line, " A{} P{v}", axis_index(axis.axis));
            }
        }
        line
    };
    let _ = writeln!(tape, "{}", parameter(1851, &|a| Some(a.backlash)));
    if data.iter().any(|a| a.pitch.is_some()) {
        let _ = writeln!(tape, "{}", parameter(3620, &|a| a.pitch.as_ref().map(|p| p.reference)));
        let _ = writeln!(tape, "{}", parameter(3621, &|a| a.pitch.as_ref().map(|p| p.first)));
        let _ = writeln!(tape, "{}", parameter(3622, &|a| a.pitch.as_ref().map(|p| p.last)));
        let _ = writeln!(tape, "{}", parameter(3623, &|a| a.pitch.as_ref().map(|p| p.magnification)));
        let _ = writeln!(tape, "{}", parameter(3624, &|a| a.pitch.as_ref().map(|p| p.interval)));
        for axis in &data {
            if let Some(pitch) = &axis.pitch {
                for (k, value) in pitch.points.iter().enumerate() {
                    let _ = writeln!(tape, "N{} P{value}", DATA_BASE + pitch.first + k as i64);
                }
            }
        }
    }
    tape.push_str("%\n");
    super::Written { main: tape, beside: Vec::new() }
}

/// A name as a tape comment may hold it: letters, digits, blanks and `- . _ /`.
fn printable(name: &str) -> String {
    let kept: String =
        name.chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || matches!(c, '-' | '.' | '_' | '/') {
                    c.to_ascii_uppercase()
                } else {
                    ' '
                }
            })
            .collect();
    kept.split_whitespace().collect::<Vec<_>>().join(" ")
}

pub fn read(text: &str, units: Units, zero: Xz) -> Result<Loaded, ReadError> {
    let error = |line: usize, label: &'static str, message: String, hint: Option<String>| ReadError {
        file: None,
        span: line_span(text, line),
        label,
        message,
        hint,
    };
    let mut header: Option<(Units, f64, Xz)> = None;
    let mut parameters: Vec<Parameter> = Vec::new();
    let mut points: Vec<(i64, i64, usize)> = Vec::new();
    for (k, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line == "%" {
            continue;
        }
        if let Some(comment) = line.strip_prefix('(').and_then(|c| c.strip_suffix(')')) {
            if let Some(rest) = comment.strip_prefix("UNITS ") {
                header = Some(read_header(rest).ok_or_else(|| {
                    error(k + 1, "this header", "the header's units, detection unit or zero do not read".into(), None)
                })?);
            }
            continue;
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        let number =
            words.first().and_then(|w| w.strip_prefix('N')).and_then(|n| n.parse::<i64>().ok()).ok_or_else(|| {
                error(k + 1, "this line", "a line of the tape is `N<number>` and its values".into(), None)
            })?;
        let mut values = Vec::new();
        let mut axis = 0usize;
        for word in &words[1..] {
            if let Some(a) = word.strip_prefix('A').and_then(|a| a.parse::<usize>().ok()) {
                axis = a;
            } else if let Some(v) = word.strip_prefix('P').and_then(|v| v.parse::<i64>().ok()) {
                values.push((axis, v));
            } else {
                return Err(error(k + 1, "this word", format!("`{word}` is neither A<axis> nor P<value>"), None));
            }
        }
        if number >= DATA_BASE {
            let value =
                values.first().map(|v| v.1).ok_or_else(|| error(k + 1, "this line", "no P value".into(), None))?;
            points.push((number - DATA_BASE, value, k + 1));
        } else {
            parameters.push(Parameter { number, values, line: k + 1 });
        }
    }
    let (units, unit, zero) = header.unwrap_or((units, 0.0, zero));
    if unit <= 0.0 {
        return Err(error(
            1,
            "this tape",
            "the tape does not say its detection unit: turnpass reads the tapes it writes, whose header says it".into(),
            Some("write the table with `turnpass table MODEL --control fanuc -o FILE`".into()),
        ));
    }
    let scale = mm_per_unit(units);
    let parameter = |number: i64, axis: usize| -> Option<i64> {
        parameters
            .iter()
            .find(|p| p.number == number)
            .and_then(|p| p.values.iter().find(|(a, _)| *a == axis).map(|(_, v)| *v))
    };
    let mut compensation = ControlCompensation::default();
    for axis in [Axis::X, Axis::Z] {
        let index = axis_index(axis);
        let zero_axis = match axis {
            Axis::X => zero.x,
            Axis::Z => zero.z,
        };
        let backlash = parameter(1851, index).unwrap_or(0) as f64 * unit;
        let mut nodes = Vec::new();
        if let (Some(reference), Some(first), Some(last), Some(magnification), Some(interval)) = (
            parameter(3620, index),
            parameter(3621, index),
            parameter(3622, index),
            parameter(3623, index),
            parameter(3624, index),
        ) {
            if !(first <= reference && reference <= last) || interval <= 0 || magnification <= 0 {
                let line = parameters.iter().find(|p| p.number == 3620).map_or(1, |p| p.line);
                return Err(error(
                    line,
                    "these parameters",
                    format!(
                        "axis {index}: the reference point {reference} must lie between the farthest points {first} \
                         and {last}, and the interval and magnification be above 0"
                    ),
                    None,
                ));
            }
            let value = |n: i64| points.iter().find(|(p, _, _)| *p == n).map_or(0, |p| p.1);
            let count = (last - first + 1) as usize;
            let mut absolute = vec![0i64; count];
            let at = |n: i64| (n - first) as usize;
            for n in reference + 1..=last {
                absolute[at(n)] = absolute[at(n - 1)] + value(n);
            }
            for n in (first..reference).rev() {
                absolute[at(n)] = absolute[at(n + 1)] - value(n + 1);
            }
            for n in first..=last {
                let position = (n - reference) as f64 * interval as f64 * unit;
                let correction = absolute[at(n)] as f64 * magnification as f64 * unit;
                nodes.push((position, correction, correction));
            }
        }
        if nodes.is_empty() && backlash == 0.0 {
            continue;
        }
        let compensated = axis_compensation(&nodes, Between::Steps, backlash, scale, zero_axis);
        match axis {
            Axis::X => compensation.x = Some(compensated),
            Axis::Z => compensation.z = Some(compensated),
        }
    }
    if let Some((n, _, line)) = points.iter().find(|(n, _, _)| !in_some_axis(*n, &parameter)) {
        return Err(error(*line, "this point", format!("point {n} belongs to no axis' range (3621 to 3622)"), None));
    }
    Ok(Loaded { control: super::Control::Fanuc, compensation, unverified: Some(UNVERIFIED) })
}

fn in_some_axis(n: i64, parameter: &impl Fn(i64, usize) -> Option<i64>) -> bool {
    [1, 2].iter().any(|&axis| match (parameter(3621, axis), parameter(3622, axis)) {
        (Some(first), Some(last)) => (first..=last).contains(&n),
        _ => false,
    })
}

/// A parameter line of the tape: its number, its values by axis (0 for none), its line.
struct Parameter {
    number: i64,
    values: Vec<(usize, i64)>,
    line: usize,
}

/// The header's `UNITS …, DETECTION UNIT …, ZERO X … Z …`, after `UNITS `.
fn read_header(rest: &str) -> Option<(Units, f64, Xz)> {
    let mut fields = rest.split(',').map(str::trim);
    let units = match fields.next()?.to_ascii_lowercase().as_str() {
        "mm" => Units::Mm,
        "inch" => Units::Inch,
        _ => return None,
    };
    let unit = fields.next()?.strip_prefix("DETECTION UNIT ")?.trim().parse::<f64>().ok().filter(|u| *u > 0.0)?;
    let zero = fields.next()?.strip_prefix("ZERO ")?;
    let words: Vec<&str> = zero.split_whitespace().collect();
    let [x_word, x, z_word, z] = words[..] else { return None };
    if x_word != "X" || z_word != "Z" {
        return None;
    }
    let scale = mm_per_unit(units);
    let (x, z) = (x.parse::<f64>().ok()?, z.parse::<f64>().ok()?);
    Some((units, unit, Xz::new(x * scale, z * scale)))
}
