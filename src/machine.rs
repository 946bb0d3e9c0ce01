//! Machine settings: the `[machine]` table of a machine model file.
//!
//! The G-code system and the decimal-point rule are properties of the machine, never
//! guessed from a program, so they come from here (or from the command line).
//! This module parses text; finding and reading the file is the binary's job. Every number
//! is checked against the range beside its field when the table is read: a least increment
//! of 0 or a NaN home would otherwise reach the compensation.

use serde::{Deserialize, Serialize};

use crate::bounds::{Invalid, Key, Range, Reason};
use crate::diagnostic::Diagnostic;
use crate::dialect::{DecimalInput, Dialect, GCodeSystem};
use crate::toml_spans::{Document, Problems, Step};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    Mm,
    Inch,
}

/// The `[machine]` table. Every field is optional; the caller supplies what is missing from
/// the command line or the documented defaults.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MachineSettings {
    pub name: Option<String>,
    pub dialect: Option<Dialect>,
    pub gcode_system: Option<GCodeSystem>,
    /// The Fanuc-compatible control (`fanuc`, `haas`, `denford`; `crate::dialect::Control`).
    pub control: Option<crate::dialect::Control>,
    pub decimal_input: Option<DecimalInput>,
    /// Units of a program that does not select them.
    pub units: Option<Units>,
    pub diameter_programming: Option<bool>,
    /// Least input increment in the machine's units (0.001 mm, 0.0001 in): a power of ten
    /// within `LEAST_INCREMENT`.
    pub least_increment: Option<f64>,
    /// The reference position `G28` returns to, in the machine's units with X as the
    /// machine programs it (a diameter on diameter-programmed lathes); within `POSITION`.
    pub home: Option<AxisPair>,
    /// Travel limits of the tool reference point, same convention as `home`; within
    /// `POSITION`, each minimum below its maximum.
    pub travel: Option<Travel>,
    /// Rapid traverse rate of each axis, machine units per minute; within `RAPID_RATE`.
    pub rapid_rate: Option<AxisPair>,
    /// The spindle's top speed, rpm; constant surface speed never exceeds it. Within
    /// `SPINDLE_RPM`.
    pub max_spindle_rpm: Option<f64>,
    /// The block-delete switch: `true` skips blocks that start with `/`.
    pub block_delete: Option<bool>,
    /// The lead of each axis' ball screw, mm (a property of the screw, so in millimetres
    /// whatever the machine's units): the period of its cyclic error (`diagnose`), within
    /// the range of that effect's `pitch`.
    pub ball_screw_pitch_mm: Option<ScrewPitch>,
    /// The tool table.
    #[serde(default)]
    pub tool: Vec<ToolSettings>,
    /// Values of the common variables the machine keeps (`"#501" = 350.0` on Fanuc,
    /// `"V12" = 4.0` on OSP), for programs that read them before setting them.
    #[serde(default)]
    pub variables: std::collections::BTreeMap<String, f64>,
}

/// An X and a Z value.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisPair {
    pub x: f64,
    pub z: f64,
}

/// The ball-screw lead of each axis, mm; either may be unknown.
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScrewPitch {
    pub x: Option<f64>,
    pub z: Option<f64>,
}

#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Travel {
    pub x_min: f64,
    pub x_max: f64,
    pub z_min: f64,
    pub z_max: f64,
}

/// One tool of the table: `[[machine.tool]]`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolSettings {
    /// Turret station (`T04xx` selects station 4).
    pub station: u32,
    /// Offset number; the station's number when absent (`T0404`).
    pub offset: Option<u32>,
    /// Geometry offset, machine units, X as programmed; within `POSITION`.
    #[serde(default)]
    pub x: f64,
    #[serde(default)]
    pub z: f64,
    /// Nose radius, machine units; within `NOSE_RADIUS`.
    #[serde(default)]
    pub nose_radius: f64,
    /// Imaginary tip direction 0-9 (3 for an outside turning tool cutting toward the chuck).
    #[serde(default)]
    pub tip: u8,
    /// Minor cutting edge angle, degrees, for the roughness estimate (eq. 9.1 of the
    /// thesis); within `MINOR_EDGE_ANGLE`.
    pub minor_edge_angle: Option<f64>,
    /// What the tool is (`turning` when absent): the shape the part model cuts with.
    pub kind: Option<ToolKind>,
    /// A threading insert's included angle, degrees (60 for ISO and UN threads when
    /// absent); within `THREAD_ANGLE`. Only for `kind = "threading"`.
    pub angle: Option<f64>,
    /// A drill's diameter, machine units; within `TOOL_SIZE`. Needed by `kind = "drill"`.
    pub diameter: Option<f64>,
    /// A grooving or part-off insert's width, machine units, at least twice its nose
    /// radius; within `TOOL_SIZE`. Without it the insert cuts as a round nose.
    pub width: Option<f64>,
    /// The deepest cut the tool takes, machine units: a feed move that engages more gets a
    /// warning; within `TOOL_SIZE`.
    pub max_depth: Option<f64>,
}

/// What a tool of the table is, for the part model: the shape it cuts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ToolKind {
    /// A turning or boring insert: a round nose (the nose radius) on an insert behind it.
    #[default]
    Turning,
    /// A grooving or part-off insert: `width` wide, its corners rounded by the nose radius.
    Grooving,
    /// A threading insert: a V of `angle` rounded by the nose radius.
    Threading,
    /// A drill on the spindle axis: a cylinder of `diameter`.
    Drill,
}

/// The `[stock]` table of a model file: the bar a program starts from, in the machine's
/// units. `diameter` and `bore` are diameters whatever the machine programs (a bar is
/// bought by its diameter).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StockSettings {
    /// The bar's outer diameter; within `STOCK_SIZE`.
    pub diameter: f64,
    /// Its length from the front face toward the chuck; within `STOCK_SIZE`.
    pub length: f64,
    /// The Z of its front face (0 when absent); within `POSITION`.
    pub front: Option<f64>,
    /// The diameter of a bore through it (a tube); within `STOCK_SIZE`, below `diameter`.
    pub bore: Option<f64>,
}

/// Plausible stock sizes, machine units: more than nothing, at most 10,000.
pub const STOCK_SIZE: Range = Range::positive(10_000.0, "");
/// Plausible tool sizes (drill diameter, insert width, depth of cut), machine units: more
/// than nothing, at most 500.
pub const TOOL_SIZE: Range = Range::positive(500.0, "");
/// Plausible thread forms: an included angle from 10 to 120 degrees (29° ACME to 80° PG).
pub const THREAD_ANGLE: Range = Range::closed(10.0, 120.0, "degrees");

impl StockSettings {
    /// The `[stock]` table of `document`, read and checked; none without one.
    pub fn read(document: &Document<'_>) -> Result<Option<StockSettings>, Vec<Diagnostic>> {
        let table = [Step::from("stock")];
        let Some(stock) = document.read::<StockSettings>(&table).map_err(|d| vec![d])? else { return Ok(None) };
        let mut problems: Vec<Diagnostic> = stock.check().iter().map(|bad| document.invalid(&table, bad)).collect();
        problems.sort_by_key(|d| d.span.start);
        if problems.is_empty() { Ok(Some(stock)) } else { Err(problems) }
    }

    /// Every value outside its range or breaking a rule, with its key.
    pub fn check(&self) -> Vec<Invalid> {
        let mut problems = Vec::new();
        let results = [
            STOCK_SIZE.check_key("diameter", self.diameter),
            STOCK_SIZE.check_key("length", self.length),
            POSITION.check_option("front", self.front),
            STOCK_SIZE.check_option("bore", self.bore),
        ];
        problems.extend(results.into_iter().filter_map(Result::err));
        if let Some(bore) = self.bore
            && bore >= self.diameter
        {
            let rule = Reason::Rule("a bore is smaller than the bar's diameter");
            problems.push(Invalid { path: vec![Key::Name("bore")], reason: rule });
        }
        problems
    }

    /// `diameter=50,length=120[,front=0][,bore=20]`, the form of `--stock`, checked as the
    /// table is.
    pub fn parse(text: &str) -> Result<StockSettings, String> {
        let mut values: [Option<f64>; 4] = [None; 4];
        const KEYS: [&str; 4] = ["diameter", "length", "front", "bore"];
        for item in text.split(',').map(str::trim).filter(|item| !item.is_empty()) {
            let (key, value) =
                item.split_once('=').ok_or_else(|| format!("`{item}` is not KEY=VALUE (keys: {})", KEYS.join(", ")))?;
            let slot = KEYS
                .iter()
                .position(|k| *k == key.trim())
                .ok_or_else(|| format!("`{}` is not a key of the stock (keys: {})", key.trim(), KEYS.join(", ")))?;
            let value: f64 = value.trim().parse().map_err(|_| format!("`{}` is not a number", value.trim()))?;
            values[slot] = Some(value);
        }
        let need = |slot: usize| values[slot].ok_or_else(|| format!("the stock needs `{}=`", KEYS[slot]));
        let stock = StockSettings { diameter: need(0)?, length: need(1)?, front: values[2], bore: values[3] };
        match stock.check().first() {
            None => Ok(stock),
            Some(bad) => {
                let key = match bad.path.first() {
                    Some(Key::Name(name)) => *name,
                    _ => "stock",
                };
                Err(match bad.reason {
                    Reason::OutOfRange(error) => format!("{key}: {error}"),
                    Reason::Rule(rule) => format!("{key}: {rule}"),
                })
            }
        }
    }
}

/// The rule of units of a model file, quoted where a key breaks it (`docs/error-model.md`,
/// "Units"): the settings are the control's, the error model is measured physics.
pub const UNITS_RULE: &str = "[machine] and its tool table are in the program's units (mm or inch) with X as the \
                              machine programs it (a diameter on a diameter-programmed lathe), as the control holds \
                              them; [model], [[axis_table]] and [[effect]] are measured displacements, in \
                              millimetres with X as a radius";

/// What a key's name says about its units when it names the other system than the table
/// it is in wants (an effect's `dx_dia`, `b_inch`, `units`): "a diameter", "inches",
/// "micrometres", or "units of its own". `None` for a name that says nothing of units.
pub fn names_other_units(key: &str) -> Option<&'static str> {
    let key = key.to_lowercase();
    if matches!(key.as_str(), "units" | "unit" | "diameter_programming") {
        return Some("units of its own");
    }
    if key.contains("µm") || key.contains("μm") {
        return Some("micrometres");
    }
    key.split(|c: char| !c.is_ascii_alphanumeric()).find_map(|word| match word {
        "dia" | "diam" | "diameter" | "diametral" => Some("a diameter"),
        "in" | "inch" | "inches" => Some("inches"),
        "um" | "micron" | "microns" | "micrometre" | "micrometres" | "micrometer" | "micrometers" => {
            Some("micrometres")
        }
        _ => None,
    })
}

/// Plausible least increments, in the machine's units: from a micrometre (or a millionth
/// of an inch) to 0.01 (the coarsest input system, IS-A), and a power of ten.
pub const LEAST_INCREMENT: Range = Range::closed(0.000_001, 0.01, "");
/// Plausible positions (home, travel limits, tool offsets), machine units: within ±100,000
/// (a hundred metres; lathes travel a few metres at most).
pub const POSITION: Range = Range::magnitude(100_000.0, "");
/// Plausible rapid rates, machine units per minute: more than nothing, at most 1,000,000.
pub const RAPID_RATE: Range = Range::positive(1_000_000.0, "units/min");
/// Plausible spindle limits: more than nothing, at most 200,000 rpm.
pub const SPINDLE_RPM: Range = Range::positive(200_000.0, "rpm");
/// Plausible nose radii, machine units: from 0 to 50 (round inserts reach 25 mm).
pub const NOSE_RADIUS: Range = Range::closed(0.0, 50.0, "");
/// Plausible minor cutting edge angles: from 0 to 90 degrees.
pub const MINOR_EDGE_ANGLE: Range = Range::closed(0.0, 90.0, "degrees");
/// Plausible ball screw leads, mm (and their fractions, for the harmonics of a cyclic
/// error: `error_model::effects::cyclic`).
pub const SCREW_PITCH: Range = Range::closed(0.1, 1_000.0, "mm");

/// A machine model file. Only `[machine]` is read here; the error-model tables that later
/// passes add are left to them.
#[derive(Debug, Clone, Default)]
pub struct ModelFile {
    pub machine: MachineSettings,
    /// The `[stock]` table, when the file has one.
    pub stock: Option<StockSettings>,
}

impl ModelFile {
    /// The `[machine]` table of a model file's text, read and checked. The file's other
    /// tables are the error model's (`error_model::model_file`).
    pub fn from_toml(text: &str) -> Result<ModelFile, Problems> {
        let document = Document::parse(text).map_err(|d| Problems::new(text, vec![d]))?;
        let machine = MachineSettings::read(&document);
        let stock = StockSettings::read(&document);
        match (machine, stock) {
            (Ok(machine), Ok(stock)) => Ok(ModelFile { machine, stock }),
            (machine, stock) => {
                let mut problems: Vec<Diagnostic> = machine.err().into_iter().chain(stock.err()).flatten().collect();
                problems.sort_by_key(|d| d.span.start);
                Err(Problems::new(text, problems))
            }
        }
    }
}

impl MachineSettings {
    /// The block-delete switch in force: off unless the settings turn it on.
    pub fn block_delete_switch(&self) -> bool {
        self.block_delete.unwrap_or(false)
    }

    /// The `[machine]` table of `document` (the defaults without one), read and checked.
    pub fn read(document: &Document<'_>) -> Result<MachineSettings, Vec<Diagnostic>> {
        let table = [Step::from("machine")];
        let settings: MachineSettings = document.read(&table).map_err(|d| vec![d])?.unwrap_or_default();
        let mut problems: Vec<Diagnostic> = settings.check().iter().map(|bad| document.invalid(&table, bad)).collect();
        problems.sort_by_key(|d| d.span.start);
        if problems.is_empty() { Ok(settings) } else { Err(problems) }
    }

    /// Every value of the table that lies outside its range or breaks a rule, with its path
    /// in the table.
    pub fn check(&self) -> Vec<Invalid> {
        let mut problems = Vec::new();
        let mut push = |result: Result<(), Invalid>, outer: &[Key]| {
            if let Err(bad) = result {
                problems.push(bad.within(outer));
            }
        };
        if let Some(increment) = self.least_increment {
            let result = LEAST_INCREMENT.check_key("least_increment", increment).and_then(|()| {
                let power_of_ten = 10f64.powf(increment.log10().round());
                if (power_of_ten - increment).abs() <= increment * 1e-9 {
                    Ok(())
                } else {
                    let rule = Reason::Rule("a least increment is a power of ten (0.001, 0.0001)");
                    Err(Invalid { path: vec![Key::Name("least_increment")], reason: rule })
                }
            });
            push(result, &[]);
        }
        for (name, pair) in [("home", &self.home), ("rapid_rate", &self.rapid_rate)] {
            let Some(pair) = pair else { continue };
            let range = if name == "home" { POSITION } else { RAPID_RATE };
            push(range.check_key("x", pair.x), &[Key::Name(name)]);
            push(range.check_key("z", pair.z), &[Key::Name(name)]);
        }
        if let Some(travel) = &self.travel {
            let within = [Key::Name("travel")];
            for (key, value) in
                [("x_min", travel.x_min), ("x_max", travel.x_max), ("z_min", travel.z_min), ("z_max", travel.z_max)]
            {
                push(POSITION.check_key(key, value), &within);
            }
            for (key, min, max) in [("x_max", travel.x_min, travel.x_max), ("z_max", travel.z_min, travel.z_max)] {
                if min >= max {
                    let rule = Reason::Rule("a travel's maximum must lie above its minimum");
                    push(Err(Invalid { path: vec![Key::Name(key)], reason: rule }), &within);
                }
            }
        }
        push(SPINDLE_RPM.check_option("max_spindle_rpm", self.max_spindle_rpm), &[]);
        if let Some(pitch) = &self.ball_screw_pitch_mm {
            let within = [Key::Name("ball_screw_pitch_mm")];
            push(SCREW_PITCH.check_option("x", pitch.x), &within);
            push(SCREW_PITCH.check_option("z", pitch.z), &within);
        }
        for (name, value) in &self.variables {
            let named = name.strip_prefix('#').map_or_else(
                || {
                    name.bytes().next().is_some_and(|b| b.is_ascii_uppercase())
                        && name.bytes().all(|b| b.is_ascii_uppercase() || b.is_ascii_digit())
                },
                |digits| !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()),
            );
            if !named {
                let rule =
                    Reason::Rule("a variable is named as the program names it: `#501` (Fanuc), `V12` or a name (OSP)");
                push(Err(Invalid { path: vec![Key::Name("variables")], reason: rule }), &[]);
            } else if !value.is_finite() {
                let rule = Reason::Rule("a variable's value is a finite number");
                push(Err(Invalid { path: vec![Key::Name("variables")], reason: rule }), &[]);
            }
        }
        for (index, tool) in self.tool.iter().enumerate() {
            let within = [Key::Name("tool"), Key::Index(index)];
            push(POSITION.check_key("x", tool.x), &within);
            push(POSITION.check_key("z", tool.z), &within);
            push(NOSE_RADIUS.check_key("nose_radius", tool.nose_radius), &within);
            push(MINOR_EDGE_ANGLE.check_option("minor_edge_angle", tool.minor_edge_angle), &within);
            if tool.tip > 9 {
                let rule = Reason::Rule("an imaginary tip direction is 0 to 9");
                push(Err(Invalid { path: vec![Key::Name("tip")], reason: rule }), &within);
            }
            push(THREAD_ANGLE.check_option("angle", tool.angle), &within);
            push(TOOL_SIZE.check_option("diameter", tool.diameter), &within);
            push(TOOL_SIZE.check_option("width", tool.width), &within);
            push(TOOL_SIZE.check_option("max_depth", tool.max_depth), &within);
            let kind = tool.kind.unwrap_or_default();
            let rule = |key: &'static str, rule: &'static str| {
                Err(Invalid { path: vec![Key::Name(key)], reason: Reason::Rule(rule) })
            };
            if tool.angle.is_some() && kind != ToolKind::Threading {
                push(rule("angle", "an included angle is a threading insert's (kind = \"threading\")"), &within);
            }
            if tool.width.is_some() && kind != ToolKind::Grooving {
                push(rule("width", "a width is a grooving insert's (kind = \"grooving\")"), &within);
            }
            match (kind, tool.diameter) {
                (ToolKind::Drill, None) => push(rule("kind", "a drill needs its `diameter`"), &within),
                (ToolKind::Drill, Some(_)) | (_, None) => {}
                (_, Some(_)) => push(rule("diameter", "a diameter is a drill's (kind = \"drill\")"), &within),
            }
            if let Some(width) = tool.width
                && width < 2.0 * tool.nose_radius
            {
                push(rule("width", "an insert is at least twice its nose radius wide"), &within);
            }
        }
        problems
    }

    /// Decimal places of the least increment: 3 for 0.001, 4 for 0.0001.
    pub fn increment_places(&self) -> u8 {
        let increment = self.least_increment.unwrap_or(match self.units {
            Some(Units::Inch) => 0.0001,
            _ => 0.001,
        });
        increment_places(increment)
    }
}

/// The decimal places of a least increment in program units (3 for 0.001): how many times
/// it is scaled by ten before it is whole (at most nine).
pub fn increment_places(increment: f64) -> u8 {
    let mut places = 0u8;
    let mut scaled = increment;
    while places < 9 && (scaled - scaled.round()).abs() > 1e-9 {
        scaled *= 10.0;
        places += 1;
    }
    places
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn machine_table_reads_and_rejects_typos() {
        let file =
            ModelFile::from_toml("[machine]\ndialect = \"fanuc\"\ngcode_system = \"B\"\nleast_increment = 0.0001\n")
                .unwrap();
        assert_eq!(file.machine.gcode_system, Some(GCodeSystem::B));
        assert_eq!(file.machine.increment_places(), 4);
        assert!(ModelFile::from_toml("[machine]\ngcode_sytem = \"B\"\n").is_err());
    }
}
