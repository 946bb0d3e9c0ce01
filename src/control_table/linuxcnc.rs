//! LinuxCNC's joint compensation: a compensation file per joint (`[JOINT_n] COMP_FILE`,
//! `COMP_FILE_TYPE`), or the joint's `BACKLASH`, in the machine's INI file.
//!
//! The conventions, from LinuxCNC's documentation (`docs/src/config/ini-config.adoc`,
//! "[JOINT_<num>] Sections") and from the code that loads and applies the file (read at
//! commit 5c41560e of github.com/LinuxCNC/linuxcnc):
//!
//! * One line per node, `nominal forward reverse`, separated by blanks, in machine units,
//!   nominals ascending ("Compensation files must start with the smallest nominal and be in
//!   ascending order"; `src/emc/motion/command.c`, `EMCMOT_SET_JOINT_COMP`, refuses an entry
//!   that does not increase: "compensation values must increase").
//! * `COMP_FILE_TYPE = 0`: the second and third values are the actual positions when
//!   moving in + and in −; the loader converts them to corrections `nominal − actual`
//!   (`usrmotLoadComp`, `src/emc/motion/usrmotintf.cc`). `COMP_FILE_TYPE = 1`: they are the
//!   corrections themselves. The motion controller adds the correction of the direction
//!   the joint's commanded velocity has, interpolated linearly between nodes and held
//!   beyond the first and last, to the commanded position (`compute_screw_comp`,
//!   `src/emc/motion/control.c`: `motor-pos-cmd = pos-cmd + backlash-filt`), keeping the
//!   last one while the joint stands still. A missing `COMP_FILE_TYPE` is 0
//!   (`src/emc/ini/inijoint.cc`).
//! * At most 256 nodes per joint (`EMCMOT_COMP_SIZE`, `src/emc/motion/motion.h`; the
//!   documentation: "the limit inside LinuxCNC is for 256 triplets per joint").
//! * The loader stops at the first line that does not hold three numbers (`sscanf` in
//!   `usrmotLoadComp`), so the file has no header and no comment: what the file is, is said
//!   in the INI text written beside it.
//! * "If `COMP_FILE` is specified for a joint, `BACKLASH` is not used": the play is in the
//!   difference of the forward and reverse columns. A joint with no pitch error gets
//!   `BACKLASH` alone, of which the controller adds half in the direction of motion.
//! * The correction is stored in single precision (`emcmot_comp_entry_t`), and a change of
//!   it (a reversal) is ramped in at half the joint's velocity and acceleration limits
//!   (`compute_screw_comp`), so a take-up is not instantaneous; the model takes it so.
//! * The joints of a lathe are X and Z, in that order, as LinuxCNC's sample lathe
//!   configuration has them (`configs/sim/axis/lathe.ini`: `KINEMATICS = trivkins
//!   coordinates=xz`, `JOINTS = 2`); a `[KINS]` section read back says otherwise.
//!
//! The INI text also holds a `[TURNPASS]` section (LinuxCNC reads no key of it) with the
//! units and the machine's zero in the model's frame, which `--with-table` reads back.

use std::fmt::Write as _;

use super::{Loaded, ReadError, Table, axis_compensation, line_span, mm_per_unit, number, units_name};
use crate::error_model::control::{AxisCompensation, Between, ControlCompensation, Node};
use crate::error_model::model_file::Axis;
use crate::machine::Units;
use crate::source::Span;
use crate::toolpath::Xz;

/// The most nodes a joint's compensation file may hold (`EMCMOT_COMP_SIZE`).
pub const MAX_ENTRIES: usize = 256;

/// Decimals of a written position and correction: a tenth of a nanometre in mm, a
/// hundred-millionth of an inch.
fn places(units: Units) -> usize {
    if units == Units::Inch { 8 } else { 7 }
}

/// The joint of each axis: X is joint 0, Z joint 1 (trivkins `coordinates=xz`).
fn joint(axis: Axis) -> usize {
    match axis {
        Axis::X => 0,
        Axis::Z => 1,
    }
}

pub fn write(table: &Table, beside: impl Fn(Axis) -> String) -> super::Written {
    let options = &table.options;
    let units = options.units;
    let scale = mm_per_unit(units);
    let places = places(units);
    let mut ini = String::new();
    let header = &options.header;
    let _ = writeln!(
        ini,
        "# turnpass {}: LinuxCNC joint compensation for the machine model {} (SHA-256 {}).",
        header.version, header.model, header.model_sha256
    );
    let _ = writeln!(
        ini,
        "# Merge the [JOINT_n] keys below into the machine's INI file (joint 0 is X, joint 1 is Z, as with\n\
         # KINEMATICS = trivkins coordinates=xz). Positions are joint positions in machine units ({}), X a\n\
         # radius. With COMP_FILE a joint's BACKLASH is not used: the play is the difference of the forward\n\
         # and reverse columns (LinuxCNC's ini-config documentation, [JOINT_<num>] Sections).",
        units_name(units)
    );
    for placement in &table.placements {
        let whereto = if placement.in_table { "table" } else { "program" };
        let _ = writeln!(ini, "#   {} -> {whereto}", placement.name);
    }
    let _ = writeln!(ini, "\n[TURNPASS]");
    let _ = writeln!(ini, "# For turnpass --with-table; LinuxCNC reads no key of this section.");
    let _ = writeln!(ini, "LINEAR_UNITS = {}", units_name(units));
    let _ = writeln!(ini, "# The model position of the joints' zero, machine units, X a radius.");
    let _ = writeln!(ini, "ZERO_X = {}", number(options.zero.x / scale, places));
    let _ = writeln!(ini, "ZERO_Z = {}", number(options.zero.z / scale, places));
    let mut files = Vec::new();
    for axis_table in &table.axes {
        let _ = writeln!(ini, "\n[JOINT_{}]", joint(axis_table.axis));
        if axis_table.positions.is_empty() {
            let _ = writeln!(ini, "BACKLASH = {}", number(axis_table.backlash, places));
            continue;
        }
        let name = beside(axis_table.axis);
        let _ = writeln!(ini, "COMP_FILE = {name}");
        let _ = writeln!(ini, "COMP_FILE_TYPE = {}", options.linuxcnc_type);
        let mut text = String::new();
        let half = axis_table.backlash / 2.0;
        for (k, &nominal) in axis_table.positions.iter().enumerate() {
            // The corrections the controller adds, with half the play in each direction.
            let (forward, reverse) = (axis_table.forward[k] + half, axis_table.reverse[k] - half);
            let (second, third) =
                if options.linuxcnc_type == 0 { (nominal - forward, nominal - reverse) } else { (forward, reverse) };
            let _ = writeln!(text, "{:.places$} {:.places$} {:.places$}", nominal, second, third, places = places);
        }
        files.push((name, text));
    }
    super::Written { main: ini, beside: files }
}

/// An INI file: its sections' keys and values, with the line each is on.
struct Ini<'t> {
    entries: Vec<(String, String, &'t str, usize)>,
}

impl<'t> Ini<'t> {
    fn parse(text: &'t str) -> Ini<'t> {
        let mut entries = Vec::new();
        let mut section = String::new();
        for (k, line) in text.lines().enumerate() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') || line.starts_with(';') {
                continue;
            }
            if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
                section = name.trim().to_ascii_uppercase();
            } else if let Some((key, value)) = line.split_once('=') {
                entries.push((section.clone(), key.trim().to_ascii_uppercase(), value.trim(), k + 1));
            }
        }
        Ini { entries }
    }

    /// The first value of `key` in `section`, and its line (LinuxCNC's `IniFile::Find`
    /// takes the first).
    fn get(&self, section: &str, key: &str) -> Option<(&'t str, usize)> {
        self.entries.iter().find(|(s, k, _, _)| s == section && k == key).map(|(_, _, v, line)| (*v, *line))
    }
}

pub fn read(
    text: &str,
    mut beside: impl FnMut(&str) -> Result<String, String>,
    units: Units,
    zero: Xz,
) -> Result<Loaded, ReadError> {
    let ini = Ini::parse(text);
    let main_error = |line: usize, label: &'static str, message: String, hint: Option<String>| ReadError {
        file: None,
        span: line_span(text, line),
        label,
        message,
        hint,
    };
    let units = match ini.get("TURNPASS", "LINEAR_UNITS").or_else(|| ini.get("TRAJ", "LINEAR_UNITS")) {
        Some((value, line)) => match value.to_ascii_lowercase().as_str() {
            "mm" | "metric" | "millimeter" | "millimetre" => Units::Mm,
            "inch" | "in" | "imperial" => Units::Inch,
            _ => {
                return Err(main_error(
                    line,
                    "these units",
                    format!("LINEAR_UNITS `{value}` is not mm or inch"),
                    Some("LinuxCNC's linear units are mm (metric) or inch (imperial)".to_string()),
                ));
            }
        },
        None => units,
    };
    let scale = mm_per_unit(units);
    let mut zero = zero;
    for (key, axis) in [("ZERO_X", Axis::X), ("ZERO_Z", Axis::Z)] {
        if let Some((value, line)) = ini.get("TURNPASS", key) {
            let v = value
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| main_error(line, "this value", format!("{key} `{value}` is not a number"), None))?;
            match axis {
                Axis::X => zero.x = v * scale,
                Axis::Z => zero.z = v * scale,
            }
        }
    }
    let joints = joints_of(&ini, text)?;
    let mut compensation = ControlCompensation::default();
    for (axis, joint) in joints {
        let section = format!("JOINT_{joint}");
        let zero_axis = match axis {
            Axis::X => zero.x,
            Axis::Z => zero.z,
        };
        let axis_compensation = if let Some((file, _)) = ini.get(&section, "COMP_FILE") {
            let kind = match ini.get(&section, "COMP_FILE_TYPE") {
                None => 0,
                Some((value, line)) => match value.parse::<i64>() {
                    Ok(kind @ (0 | 1)) => kind as u8,
                    _ => {
                        return Err(main_error(
                            line,
                            "this value",
                            format!("COMP_FILE_TYPE `{value}` is not 0 or 1"),
                            Some(
                                "0: nominal, forward and reverse positions; 1: nominal and the two corrections".into(),
                            ),
                        ));
                    }
                },
            };
            let comp = beside(file).map_err(|why| ReadError {
                file: None,
                span: ini.get(&section, "COMP_FILE").map_or(Span::new(0, 0), |(_, line)| line_span(text, line)),
                label: "this file",
                message: format!("cannot read the compensation file of joint {joint} ({}): {why}", axis.letter()),
                hint: None,
            })?;
            Some(
                comp_file(&comp, kind, scale, zero_axis)
                    .map_err(|e| ReadError { file: Some(file.to_string()), ..e })?,
            )
        } else if let Some((value, line)) = ini.get(&section, "BACKLASH") {
            let b =
                value.parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| {
                    main_error(line, "this value", format!("BACKLASH `{value}` is not a number"), None)
                })?;
            (b != 0.0).then(|| axis_compensation(&[], Between::Linear, b, scale, zero_axis))
        } else {
            None
        };
        match axis {
            Axis::X => compensation.x = axis_compensation,
            Axis::Z => compensation.z = axis_compensation,
        }
    }
    Ok(Loaded { control: super::Control::Linuxcnc, compensation, unverified: None })
}

/// Which joint is each axis: `[KINS] KINEMATICS = trivkins coordinates=…` gives joint k the
/// k-th letter (trivkins' rule); without it, X is joint 0 and Z joint 1.
fn joints_of(ini: &Ini<'_>, text: &str) -> Result<Vec<(Axis, usize)>, ReadError> {
    let Some((kinematics, line)) = ini.get("KINS", "KINEMATICS") else {
        return Ok(vec![(Axis::X, 0), (Axis::Z, 1)]);
    };
    let mut words = kinematics.split_whitespace();
    if words.next() != Some("trivkins") {
        return Err(ReadError {
            file: None,
            span: line_span(text, line),
            label: "these kinematics",
            message: format!("KINEMATICS `{kinematics}`: turnpass reads the joints of trivkins, a lathe's kinematics"),
            hint: None,
        });
    }
    let coordinates = words.find_map(|w| w.strip_prefix("coordinates=")).unwrap_or("xyzabcuvw").to_ascii_lowercase();
    let mut out = Vec::new();
    for (axis, letter) in [(Axis::X, 'x'), (Axis::Z, 'z')] {
        if let Some(joint) = coordinates.chars().position(|c| c == letter) {
            out.push((axis, joint));
        }
    }
    Ok(out)
}

/// A joint's compensation file as LinuxCNC loads it (module documentation), in the model's
/// frame: `kind` its `COMP_FILE_TYPE`, `scale` mm per machine unit, `zero` the model position
/// of the joint's zero. The constant part of the reversal is the backlash compensation.
fn comp_file(text: &str, kind: u8, scale: f64, zero: f64) -> Result<AxisCompensation, ReadError> {
    let error = |line: usize, label: &'static str, message: String, hint: Option<String>| ReadError {
        file: None,
        span: line_span(text, line),
        label,
        message,
        hint,
    };
    // Trims as the motion controller keeps them: single precision, machine units.
    let mut nodes: Vec<(f64, f32, f32)> = Vec::new();
    let mut stopped: Option<usize> = None;
    for (k, line) in text.lines().enumerate() {
        let values: Vec<f64> = line.split_whitespace().take(3).map_while(|w| w.parse::<f64>().ok()).collect();
        if stopped.is_some() {
            if !line.trim().is_empty() {
                return Err(error(
                    stopped.unwrap_or(k + 1),
                    "LinuxCNC stops here",
                    "LinuxCNC stops reading the file at the first line without three numbers, so the lines after \
                     this one are not loaded"
                        .to_string(),
                    Some("remove the line, or the lines after it".to_string()),
                ));
            }
            continue;
        }
        let [nominal, second, third] = values[..] else {
            stopped = Some(k + 1);
            continue;
        };
        if [nominal, second, third].iter().any(|v| !v.is_finite()) {
            return Err(error(k + 1, "this line", "a value is not a finite number".to_string(), None));
        }
        if nodes.last().is_some_and(|(last, _, _)| nominal <= *last) {
            return Err(error(
                k + 1,
                "this nominal",
                "the nominal does not increase: LinuxCNC refuses the entry (\"compensation values must increase\")"
                    .to_string(),
                None,
            ));
        }
        if nodes.len() == MAX_ENTRIES {
            return Err(error(
                k + 1,
                "one too many",
                format!(
                    "more than {MAX_ENTRIES} entries: LinuxCNC refuses the rest (\"too many compensation entries\")"
                ),
                None,
            ));
        }
        let (forward, reverse) = if kind == 0 { (nominal - second, nominal - third) } else { (second, third) };
        nodes.push((nominal, forward as f32, reverse as f32));
    }
    if nodes.is_empty() {
        return Err(error(1, "here", "the file holds no node".to_string(), None));
    }
    // The play the controller takes up at every node: the constant part of the reversal.
    let backlash = nodes.iter().map(|&(_, f, r)| f64::from(f) - f64::from(r)).fold(f64::INFINITY, f64::min).max(0.0);
    let half = backlash / 2.0;
    let mut out: Vec<Node> = Vec::with_capacity(nodes.len());
    for (k, &(nominal, forward, reverse)) in nodes.iter().enumerate() {
        // The slopes as `EMCMOT_SET_JOINT_COMP` computes and keeps them.
        let (forward_slope, reverse_slope) = match nodes.get(k + 1) {
            Some(&(next, f, r)) => {
                let span = next - nominal;
                (
                    f64::from(((f64::from(f) - f64::from(forward)) / span) as f32),
                    f64::from(((f64::from(r) - f64::from(reverse)) / span) as f32),
                )
            }
            None => (0.0, 0.0),
        };
        out.push(Node {
            at: nominal * scale + zero,
            forward: (f64::from(forward) - half) * scale,
            reverse: (f64::from(reverse) + half) * scale,
            forward_slope,
            reverse_slope,
        });
    }
    Ok(AxisCompensation { nodes: out, between: Between::Linear, backlash: backlash * scale })
}
