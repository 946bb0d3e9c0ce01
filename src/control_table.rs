//! `turnpass table`: the part of a machine model that a control's own axis compensation
//! carries (its pitch-error table and backlash compensation, loaded once for every
//! program), written in the control's own format; and such a table read back, as the
//! machine runs with it loaded (`compensate`, `verify` and `report` with `--with-table`).
//!
//! Which part goes into the table is each effect's own answer
//! (`error_model::control::TablePart`): a function of one axis' own position (scale,
//! cyclic, a slide table's linear column) goes into that axis' pitch-error table, the play
//! of a drive into its backlash compensation; the rest (squareness and straightness, which
//! a per-axis table cannot hold; thermal growth, the tool, servo lag, reversal spikes)
//! stays for the program. The formats, with the control documentation each convention
//! comes from, are in `linuxcnc.rs`, `fanuc.rs` and `okuma.rs`; `docs/control-tables.md`
//! collects them.
//!
//! Positions: a table counts an axis' position in machine coordinates, from the machine's
//! zero (a Fanuc's reference position; a LinuxCNC joint's zero), in the machine's units,
//! X as a radius (the slide's own travel). `zero` is where that zero lies in the model's
//! frame; the table's written values are converted there and back, once each, here.

pub mod fanuc;
pub mod linuxcnc;
pub mod okuma;

use std::fmt::Write as _;

use crate::error_model::control::{AxisCompensation, Between, ControlCompensation, TablePart};
use crate::error_model::model_file::Axis;
use crate::error_model::{Effect, ErrorModel, Sample};
use crate::machine::Units;
use crate::semantic::frame::MM_PER_INCH;
use crate::source::Span;
use crate::toolpath::Xz;

/// A control whose axis compensation `table` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    Linuxcnc,
    Fanuc,
    Okuma,
}

impl Control {
    pub fn name(self) -> &'static str {
        match self {
            Control::Linuxcnc => "LinuxCNC",
            Control::Fanuc => "Fanuc",
            Control::Okuma => "Okuma OSP",
        }
    }

    /// Whether the control's own compensation carries `part`: each of them has a pitch-error
    /// table per axis and a backlash compensation, and none a table of one axis' error along
    /// another's travel in the form written here.
    pub fn carries(self, part: &TablePart) -> bool {
        matches!(part, TablePart::Pitch(_) | TablePart::Backlash(..))
    }

    /// Whether the table has a column for each direction of travel (LinuxCNC's forward and
    /// reverse; the rows for an Okuma give both). A Fanuc's standard pitch-error
    /// compensation has one (its bidirectional compensation is an option, parameter
    /// 3605#0, not written here): the mean of the two, the rest left to the program.
    pub fn bidirectional(self) -> bool {
        !matches!(self, Control::Fanuc)
    }

    /// How the control runs its correction between nodes.
    pub fn between(self) -> Between {
        match self {
            Control::Fanuc => Between::Steps,
            Control::Linuxcnc | Control::Okuma => Between::Linear,
        }
    }

    /// The most nodes one axis' table may have.
    pub fn max_nodes(self) -> usize {
        match self {
            Control::Linuxcnc => linuxcnc::MAX_ENTRIES,
            Control::Fanuc => fanuc::MAX_POINTS_PER_AXIS,
            Control::Okuma => okuma::MAX_ROWS,
        }
    }

    /// Whether the nodes must be equally spaced from the machine's zero (a Fanuc's
    /// compensation points; the rows for an Okuma, which a service engineer keys in by
    /// number). LinuxCNC takes any ascending positions.
    pub fn uniform(self) -> bool {
        !matches!(self, Control::Linuxcnc)
    }
}

/// What `table` is asked for.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    pub control: Control,
    /// The machine units the table is written in.
    pub units: Units,
    /// Where the machine coordinates' zero lies in the model's frame, mm (X a radius).
    pub zero: Xz,
    /// The model positions each axis' table covers, mm (X a radius), X then Z.
    pub range: [Option<(f64, f64)>; 2],
    /// How closely the table follows what it carries between its nodes, mm.
    pub tolerance_mm: f64,
    /// The spacing of the nodes, mm, when one is asked for.
    pub spacing_mm: Option<f64>,
    /// The control's least step of a correction, machine units (a Fanuc's detection unit;
    /// the rows for an Okuma are rounded to it); zero for none (LinuxCNC keeps a float).
    pub unit: f64,
    /// LinuxCNC's `COMP_FILE_TYPE` (0: positions, 1: corrections).
    pub linuxcnc_type: u8,
    /// What the written header says made the table.
    pub header: Header,
}

/// What made a table: the tool and the model, for the header of what is written.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Header {
    pub version: String,
    pub model: String,
    /// The first hex digits of the SHA-256 of the model file and its tables.
    pub model_sha256: String,
}

/// Where one part of the model goes.
#[derive(Debug, Clone, PartialEq)]
pub struct Placement {
    /// The effect's kind, or the slide table's column (`X slide table, linear_mm`).
    pub name: String,
    pub part: TablePart,
    /// Whether the control's table carries it (else the program does).
    pub in_table: bool,
}

/// One axis' table, in machine coordinates and units.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisTable {
    pub axis: Axis,
    /// Node positions, machine units, ascending (none for an axis with only its backlash).
    pub positions: Vec<f64>,
    /// The correction added to the command at each node moving in + and in −, machine units,
    /// the backlash apart.
    pub forward: Vec<f64>,
    pub reverse: Vec<f64>,
    /// The node spacing, machine units (uniform tables; LinuxCNC's also hold the slide
    /// table's targets).
    pub spacing: f64,
    /// The backlash compensation, machine units.
    pub backlash: f64,
    /// The spacing was widened to keep within the control's count of nodes.
    pub widened: bool,
}

/// A model's table for a control.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    pub placements: Vec<Placement>,
    /// X, then Z, each when the table carries something of it.
    pub axes: Vec<AxisTable>,
    pub options: Options,
}

/// A file of a table as written.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    /// The main file: what `-o` names, and what `--with-table` reads.
    pub main: String,
    /// Files beside it (LinuxCNC's compensation file of each joint): the name the main
    /// file gives it, and its text.
    pub beside: Vec<(String, String)>,
}

/// A table that cannot be made, in words.
#[derive(Debug, Clone, PartialEq)]
pub struct TableError(pub String);

/// A table file that does not read as the control would load it: the file (the main
/// file, or one it names), where, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct ReadError {
    /// The name the main file gives the file, or `None` for the main file.
    pub file: Option<String>,
    pub span: Span,
    pub label: &'static str,
    pub message: String,
    pub hint: Option<String>,
}

/// A control table read back: what the control does to each axis, in the model's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Loaded {
    pub control: Control,
    pub compensation: ControlCompensation,
    /// What the reading assumes that no manual at hand confirms, to be said with every
    /// figure made with it.
    pub unverified: Option<&'static str>,
}

/// Millimetres per machine unit.
pub fn mm_per_unit(units: Units) -> f64 {
    if units == Units::Inch { MM_PER_INCH } else { 1.0 }
}

/// Where each term of `model` goes for `control`: every effect, and each slide table's
/// columns.
pub fn placements(model: &ErrorModel, control: Control) -> Vec<Placement> {
    let mut out = Vec::new();
    if let Some(tables) = &model.tables {
        for (axis, slide) in [(Axis::X, &tables.x), (Axis::Z, &tables.z)] {
            let name = |column: &str| format!("{} slide table, {column}", axis.letter());
            if slide.linear.is_some() {
                let part = TablePart::Pitch(axis);
                out.push(Placement { name: name("linear_mm"), in_table: control.carries(&part), part });
            }
            if slide.straightness.is_some() {
                // The X slide's straightness is its deviation in Z, and the Z slide's in X.
                let across = if axis == Axis::X { Axis::Z } else { Axis::X };
                let part = TablePart::CrossAxis(across);
                out.push(Placement { name: name("straightness"), in_table: false, part });
            }
            if slide.angular.is_some() {
                let part = TablePart::Program(
                    "an angular error, which moves the tool by its Abbe offset and the other slide's angle",
                );
                out.push(Placement { name: name("angular_deg"), in_table: false, part });
            }
        }
    }
    for effect in &model.effects {
        let part = effect.control_table();
        out.push(Placement { name: effect.name().to_string(), in_table: control.carries(&part), part });
    }
    out
}

/// What the table carries of one axis: the error it corrects, at a model position and a
/// direction, mm.
struct Carried<'m> {
    axis: Axis,
    effects: Vec<&'m Effect>,
    linear: Option<&'m crate::error_model::interferometer::Profile>,
    backlash: f64,
}

impl Carried<'_> {
    fn has_pitch(&self) -> bool {
        !self.effects.is_empty() || self.linear.is_some()
    }

    /// The error the table carries at model position `p` moving in `direction`, mm.
    fn error(&self, p: f64, direction: i8) -> f64 {
        let at = match self.axis {
            Axis::X => Xz::new(p, 0.0),
            Axis::Z => Xz::new(0.0, p),
        };
        let s = Sample::at_rest(at, 0.0);
        let along = |d: Xz| match self.axis {
            Axis::X => d.x,
            Axis::Z => d.z,
        };
        let effects: f64 = self.effects.iter().map(|effect| along(effect.displacement(&s))).sum();
        effects + self.linear.map_or(0.0, |profile| profile.at(p, direction))
    }

    /// The correction that takes the error out at model position `p`: the command moved by
    /// `c` lands the slide where the error at `p + c` puts it, so `c = −error(p + c)`,
    /// solved by two steps from `−error(p)` (the error's slope is a few ppm).
    fn correction(&self, p: f64, direction: i8) -> f64 {
        let mut c = -self.error(p, direction);
        for _ in 0..2 {
            c = -self.error(p + c, direction);
        }
        c
    }

    /// The largest node spacing at which the correction, interpolated as `between` runs it,
    /// strays from the exact one by at most `tolerance` mm; infinite when any spacing does.
    fn spacing(&self, between: Between, tolerance: f64, reach: f64) -> f64 {
        let reach = match self.axis {
            Axis::X => Xz::new(reach, 0.0),
            Axis::Z => Xz::new(0.0, reach),
        };
        match between {
            // Linear between nodes: each effect's own sampling step for a straight chord.
            Between::Linear => {
                self.effects.iter().map(|effect| effect.spacing(tolerance, reach).mm).fold(f64::INFINITY, f64::min)
            }
            // A staircase misses by its slope times the step.
            Between::Steps => {
                let slope: f64 = self.effects.iter().map(|effect| effect.arc_terms(reach).gradient).sum();
                let slope = slope + self.linear.map_or(0.0, max_slope);
                if slope > 0.0 { tolerance / slope } else { f64::INFINITY }
            }
        }
    }
}

/// The steepest slope of a measured profile between its targets.
fn max_slope(profile: &crate::error_model::interferometer::Profile) -> f64 {
    let mut slope: f64 = 0.0;
    for values in [&profile.up, &profile.down] {
        for k in 1..profile.targets.len() {
            let span = profile.targets[k] - profile.targets[k - 1];
            if span > 0.0 {
                slope = slope.max(((values[k] - values[k - 1]) / span).abs());
            }
        }
    }
    slope
}

/// The table of `model` for `options.control`.
pub fn build(model: &ErrorModel, options: &Options) -> Result<Table, TableError> {
    let control = options.control;
    let placements = placements(model, control);
    let scale = mm_per_unit(options.units);
    let mut axes = Vec::new();
    for (index, axis) in [Axis::X, Axis::Z].into_iter().enumerate() {
        let carried = carried(model, axis);
        if !carried.has_pitch() && carried.backlash == 0.0 {
            continue;
        }
        let backlash = carried.backlash / scale;
        if !carried.has_pitch() {
            let spacing = 0.0;
            axes.push(AxisTable {
                axis,
                positions: Vec::new(),
                forward: Vec::new(),
                reverse: Vec::new(),
                spacing,
                backlash,
                widened: false,
            });
            continue;
        }
        let Some((lo, hi)) = options.range[index] else {
            return Err(TableError(format!(
                "the model has errors of the {} axis' own position for the table, and no range for it: give the \
                 machine's travel ([machine] travel in the model, or --{} LO,HI)",
                axis.letter(),
                axis.letter().to_ascii_lowercase()
            )));
        };
        // Machine coordinates, machine units.
        let (mut m_lo, mut m_hi) = ((lo - zero_of(options, axis)) / scale, (hi - zero_of(options, axis)) / scale);
        if control == Control::Fanuc {
            // The points are numbered from the reference position, which the table holds.
            m_lo = m_lo.min(0.0);
            m_hi = m_hi.max(0.0);
        }
        let reach = lo.abs().max(hi.abs());
        let wanted = match options.spacing_mm {
            Some(spacing) => spacing,
            None => carried.spacing(control.between(), options.tolerance_mm, reach),
        } / scale;
        let targets: Vec<f64> = match (control.uniform(), carried.linear) {
            (false, Some(profile)) => profile
                .targets
                .iter()
                .map(|t| (t - zero_of(options, axis)) / scale)
                .filter(|m| (m_lo..=m_hi).contains(m))
                .collect(),
            _ => Vec::new(),
        };
        // A measured table is linear between its targets with a kink at each: a uniform
        // table running linearly between its nodes cuts a kink's corner by at most the
        // change of slope times a quarter of its spacing. (A staircase's spacing above
        // follows the table's steepest slope already.)
        let wanted = match (control.uniform() && control.between() == Between::Linear, carried.linear) {
            (true, Some(profile)) => wanted.min(4.0 * options.tolerance_mm / largest_kink(profile) / scale),
            _ => wanted,
        };
        let (positions, spacing, widened) = nodes(m_lo, m_hi, wanted, &targets, control.max_nodes());
        // A staircase holds a node's value up to the next node: the value of the middle of
        // that section misses the least.
        let staircase = control.between() == Between::Steps;
        let direction_values = |direction: i8| -> Vec<f64> {
            (0..positions.len())
                .map(|k| {
                    let m = match positions.get(k + 1) {
                        Some(next) if staircase => (positions[k] + next) / 2.0,
                        _ => positions[k],
                    };
                    carried.correction(m * scale + zero_of(options, axis), direction) / scale
                })
                .collect()
        };
        let (mut forward, mut reverse) = (direction_values(1), direction_values(-1));
        if !control.bidirectional() {
            for (f, r) in forward.iter_mut().zip(reverse.iter_mut()) {
                let mean = (*f + *r) / 2.0;
                (*f, *r) = (mean, mean);
            }
        }
        axes.push(AxisTable { axis, positions, forward, reverse, spacing, backlash, widened });
    }
    Ok(Table { placements, axes, options: options.clone() })
}

fn zero_of(options: &Options, axis: Axis) -> f64 {
    match axis {
        Axis::X => options.zero.x,
        Axis::Z => options.zero.z,
    }
}

/// The largest change of slope of a measured profile at one of its targets (none: zero).
fn largest_kink(profile: &crate::error_model::interferometer::Profile) -> f64 {
    let mut kink: f64 = 0.0;
    for values in [&profile.up, &profile.down] {
        let slopes: Vec<f64> = (1..profile.targets.len())
            .filter_map(|k| {
                let span = profile.targets[k] - profile.targets[k - 1];
                (span > 0.0).then(|| (values[k] - values[k - 1]) / span)
            })
            .collect();
        for pair in slopes.windows(2) {
            kink = kink.max((pair[1] - pair[0]).abs());
        }
    }
    kink
}

/// What the table carries of `axis`: its effects of the axis' own position, the slide
/// table's linear column, the drives' play.
fn carried(model: &ErrorModel, axis: Axis) -> Carried<'_> {
    let mut carried = Carried { axis, effects: Vec::new(), linear: None, backlash: 0.0 };
    for effect in &model.effects {
        match effect.control_table() {
            TablePart::Pitch(a) if a == axis => carried.effects.push(effect),
            TablePart::Backlash(a, b) if a == axis => carried.backlash += b,
            _ => {}
        }
    }
    if let Some(tables) = &model.tables {
        let slide = match axis {
            Axis::X => &tables.x,
            Axis::Z => &tables.z,
        };
        carried.linear = slide.linear.as_ref();
    }
    carried
}

/// The node positions over `lo..hi` (machine units): multiples of a spacing no wider than
/// `wanted` from the machine's zero, reaching just past both ends, with `targets` besides;
/// at most `max` of them (the spacing widened to fit, said by the last value). A spacing
/// that any spacing meets gives the two ends' multiples of the range.
fn nodes(lo: f64, hi: f64, wanted: f64, targets: &[f64], max: usize) -> (Vec<f64>, f64, bool) {
    let span = (hi - lo).max(f64::EPSILON);
    // Round the spacing down to a round number of the units (1, 2 or 5 times a power of
    // ten), so that the positions read as a service engineer keys them in.
    let mut spacing = round_down(wanted.min(span).max(span / 1e6));
    let mut widened = false;
    loop {
        let first = (lo / spacing).floor() as i64;
        let last = (hi / spacing).ceil() as i64;
        let count = (last - first + 1) as usize + targets.len();
        if count <= max {
            let mut positions: Vec<f64> = (first..=last).map(|k| k as f64 * spacing).collect();
            positions.extend_from_slice(targets);
            positions.sort_by(f64::total_cmp);
            // Two positions closer than a millionth of the spacing are one.
            positions.dedup_by(|a, b| (*a - *b).abs() < spacing * 1e-6);
            return (positions, spacing, widened);
        }
        spacing = round_up(spacing * 1.0001);
        widened = true;
    }
}

/// The largest 1, 2 or 5 times a power of ten at most `value`.
fn round_down(value: f64) -> f64 {
    let power = 10f64.powf(value.log10().floor());
    [5.0, 2.0, 1.0].into_iter().map(|m| m * power).find(|v| *v <= value * (1.0 + 1e-12)).unwrap_or(power)
}

/// The smallest 1, 2 or 5 times a power of ten at least `value`.
fn round_up(value: f64) -> f64 {
    let power = 10f64.powf(value.log10().floor());
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|m| m * power).find(|v| *v >= value * (1.0 - 1e-12)).unwrap_or(10.0 * power)
}

impl Table {
    /// The table in the control's format; `beside(axis)` names the file of an axis that has
    /// one of its own (LinuxCNC's compensation file of each joint).
    pub fn write(&self, beside: impl Fn(Axis) -> String) -> Written {
        match self.options.control {
            Control::Linuxcnc => linuxcnc::write(self, beside),
            Control::Fanuc => fanuc::write(self),
            Control::Okuma => okuma::write(self),
        }
    }

    /// What a control does with this table, in the model's frame, as `read` gives it back
    /// from what `write` wrote (for an Okuma, whose reading is not published, as if it ran
    /// linearly between rows).
    pub fn loaded(&self) -> Result<Loaded, ReadError> {
        let written = self.write(|axis| format!("{}.comp", axis.letter()));
        let beside = |name: &str| -> Result<String, String> {
            written.beside.iter().find(|(n, _)| n == name).map(|(_, text)| text.clone()).ok_or_else(|| name.to_string())
        };
        match self.options.control {
            Control::Okuma => Ok(okuma::loaded(self)),
            control => read(Some(control), &written.main, beside, self.options.units, self.options.zero),
        }
    }

    /// The summary: what went where, each axis' table and what it leaves of what it
    /// carries of `model` (the model it was made of), over its nodes' span.
    pub fn summary(&self, model: &ErrorModel, loaded: &Loaded) -> String {
        let mut out = String::new();
        let options = &self.options;
        let _ = writeln!(out, "what goes where ({}):", options.control.name());
        for placement in &self.placements {
            let destination = if placement.in_table { placement.part.destination() } else { program(&placement.part) };
            let _ = writeln!(out, "  {:<28} → {destination}", placement.name);
        }
        let units = units_name(options.units);
        let machine = model.with_control(loaded.compensation.clone());
        for table in &self.axes {
            let letter = table.axis.letter();
            if table.positions.is_empty() {
                let _ = writeln!(out, "{letter}: backlash {} {units}, no pitch-error table", number(table.backlash, 6));
                continue;
            }
            let (first, last) = (table.positions[0], table.positions[table.positions.len() - 1]);
            let _ = write!(
                out,
                "{letter}: {} nodes from {} to {} {units} (machine coordinates{}), spacing {} {units}{}",
                table.positions.len(),
                number(first, 4),
                number(last, 4),
                if table.axis == Axis::X { ", a radius" } else { "" },
                number(table.spacing, 6),
                if table.widened { " (widened to keep within the control's count)" } else { "" }
            );
            let _ = writeln!(out, ", backlash {} {units}", number(table.backlash, 6));
            let rest = Rest::of(&machine, table, options);
            let (mid, half) = ((rest.most + rest.least) / 2.0, (rest.most - rest.least) / 2.0);
            let _ = writeln!(
                out,
                "   what the loaded table leaves of the {letter} errors it works on: ±{} µm about {} µm over its \
                 nodes' span, in both directions (checked every {} {units}; the constant is the program's to \
                 compensate)",
                micrometres(half),
                micrometres(mid),
                number(check_step(table), 6),
            );
        }
        if let Some(why) = loaded.unverified {
            let _ = writeln!(out, "UNVERIFIED: {why}");
        }
        out
    }
}

/// `mm` in micrometres to two decimals, a rounded zero without its sign.
fn micrometres(mm: f64) -> String {
    let um = (mm * 1e5).round() / 100.0;
    format!("{:.2}", if um == 0.0 { 0.0 } else { um })
}

/// The step at which a table's residual is checked: a sixteenth of its spacing.
fn check_step(table: &AxisTable) -> f64 {
    table.spacing / 16.0
}

/// What a loaded table leaves of the errors of its axis that it works on, mm: the least and
/// the most, over its nodes' span in both directions. It is the term of the model with the
/// table loaded that `compensate`, `verify` and `report` evaluate (`ErrorModel::with_control`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rest {
    pub least: f64,
    pub most: f64,
}

impl Rest {
    pub fn of(machine: &ErrorModel, table: &AxisTable, options: &Options) -> Rest {
        let scale = mm_per_unit(options.units);
        let mut rest = Rest { least: f64::INFINITY, most: f64::NEG_INFINITY };
        let Some(term) = machine.control.as_ref() else { return Rest { least: 0.0, most: 0.0 } };
        let (Some(&first), Some(&last)) = (table.positions.first(), table.positions.last()) else {
            return Rest { least: 0.0, most: 0.0 };
        };
        let step = check_step(table);
        let count = ((last - first) / step).round().max(1.0) as usize;
        for k in 0..=count {
            let m = first + (last - first) * k as f64 / count as f64;
            for direction in [1i8, -1] {
                let p = m * scale + zero_of(options, table.axis);
                let at = match table.axis {
                    Axis::X => Xz::new(p, 0.0),
                    Axis::Z => Xz::new(0.0, p),
                };
                let s = Sample {
                    direction: crate::error_model::state::Signs { x: direction, z: direction },
                    ..Sample::at_rest(at, 0.0)
                };
                let d = term.displacement(&s);
                let r = match table.axis {
                    Axis::X => d.x,
                    Axis::Z => d.z,
                };
                rest.least = rest.least.min(r);
                rest.most = rest.most.max(r);
            }
        }
        rest
    }
}

fn program(part: &TablePart) -> String {
    match part {
        TablePart::Program(why) => format!("the program: {why}"),
        TablePart::CrossAxis(axis) => {
            format!(
                "the program: along {} as a function of the other axis, which a per-axis table cannot hold",
                axis.letter()
            )
        }
        other => format!("the program ({} not written for this control)", other.destination()),
    }
}

pub fn units_name(units: Units) -> &'static str {
    if units == Units::Inch { "inch" } else { "mm" }
}

/// `value` with at most `places` decimals, no trailing zeros.
pub fn number(value: f64, places: usize) -> String {
    let text = format!("{value:.places$}");
    let text = if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.') } else { &text };
    if text == "-0" { "0".to_string() } else { text.to_string() }
}

/// A control table read from its main file's text `main` (and the files it names, through
/// `beside`), as the control loads it: `control` when known, else told from the text.
/// Units and zero that the file does not state are `units` and `zero`.
pub fn read(
    control: Option<Control>,
    main: &str,
    beside: impl FnMut(&str) -> Result<String, String>,
    units: Units,
    zero: Xz,
) -> Result<Loaded, ReadError> {
    let control = match control {
        Some(control) => control,
        None => detect(main).ok_or_else(|| ReadError {
            file: None,
            span: Span::new(0, 0),
            label: "this file",
            message: "not a control table turnpass reads: a LinuxCNC INI file with [JOINT_n] sections, or a Fanuc \
                      pitch-error tape turnpass wrote"
                .to_string(),
            hint: Some("write one with `turnpass table MODEL --control linuxcnc|fanuc -o FILE`".to_string()),
        })?,
    };
    match control {
        Control::Linuxcnc => linuxcnc::read(main, beside, units, zero),
        Control::Fanuc => fanuc::read(main, units, zero),
        Control::Okuma => Err(ReadError {
            file: None,
            span: Span::new(0, 0),
            label: "this file",
            message: okuma::NOT_READ.to_string(),
            hint: None,
        }),
    }
}

/// Which control's table `text` is: a LinuxCNC INI file has `[JOINT_n]` sections, a Fanuc
/// tape starts with `%` and numbers its data with `N`, the rows for an Okuma carry their
/// header.
fn detect(text: &str) -> Option<Control> {
    let lines = || text.lines().map(str::trim).filter(|l| !l.is_empty());
    if lines().any(|l| l.to_ascii_uppercase().starts_with("[JOINT_")) {
        Some(Control::Linuxcnc)
    } else if text.starts_with(okuma::FIRST_LINE) {
        Some(Control::Okuma)
    } else if lines().next() == Some("%") {
        Some(Control::Fanuc)
    } else {
        None
    }
}

/// The span of line `line` (1-based) of `text`, its line break left out.
pub fn line_span(text: &str, line: usize) -> Span {
    let mut start = 0usize;
    for (k, l) in text.split_inclusive('\n').enumerate() {
        if k + 1 == line {
            let len = l.trim_end_matches(['\n', '\r']).len();
            return Span::new(start as u32, (start + len) as u32);
        }
        start += l.len();
    }
    Span::new(text.len() as u32, text.len() as u32)
}

/// An axis' compensation in the model's frame from its nodes in machine coordinates and
/// units (`positions`, corrections `forward` and `reverse` with the backlash in them),
/// the constant reversal part taken out as the backlash compensation (the play it takes
/// up: `ErrorModel::with_control`).
pub fn axis_compensation(
    nodes: &[(f64, f64, f64)],
    between: Between,
    backlash: f64,
    scale: f64,
    zero: f64,
) -> AxisCompensation {
    let points: Vec<(f64, f64, f64)> =
        nodes.iter().map(|&(m, f, r)| (m * scale + zero, f * scale, r * scale)).collect();
    AxisCompensation::new(&points, between, backlash * scale)
}
