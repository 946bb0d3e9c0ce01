//! The rows for an Okuma OSP: Okuma does not publish the format or the reading of its
//! pitch-error compensation (it is set by Okuma's service from their own tools), so this is
//! the table as plain per-axis rows a service engineer can key in: each point's number,
//! its machine position and the correction the control must add to the command there in
//! each direction, in micrometres, and each axis' backlash. `--with-table` does not read it
//! back: how OSP interpolates and switches the values is not published, so no check of a
//! program on a machine with it loaded can be made. The residual `table` prints assumes a
//! linear interpolation between rows and says so.

use std::fmt::Write as _;

use super::{Loaded, Table, axis_compensation, mm_per_unit, number, units_name};
use crate::error_model::control::{Between, ControlCompensation};
use crate::error_model::model_file::Axis;

/// The first line of the rows, by which `--with-table` knows them.
pub const FIRST_LINE: &str = "# turnpass: axis compensation rows for an Okuma OSP";

/// The most rows per axis written: a bound of ours (Okuma publishes none), which keeps the
/// keying in to an afternoon.
pub const MAX_ROWS: usize = 1000;

/// Why `--with-table` refuses the rows.
pub const NOT_READ: &str = "Okuma does not publish how OSP applies its pitch-error compensation, so turnpass cannot \
     check a program on a machine with these rows loaded: compensate without --with-table, or for a control whose \
     format is published";

/// Why the residual `table` prints is not verified.
pub const UNVERIFIED: &str =
    "Okuma does not publish how OSP applies these rows: the residual assumes it interpolates linearly between them";

pub fn write(table: &Table) -> super::Written {
    let options = &table.options;
    let units = units_name(options.units);
    let scale = mm_per_unit(options.units);
    let micrometres = |v: f64| v * scale * 1000.0;
    // The rows are rounded to the control's least step, when one is given.
    let step = if options.unit > 0.0 { micrometres(options.unit) } else { 0.1 };
    // Rounded to the step, and a rounded zero written without its sign.
    let round = |um: f64| (um / step).round() * step + 0.0;
    let places = decimals(step);
    let header = &options.header;
    let mut out = String::new();
    let _ = writeln!(out, "{FIRST_LINE}");
    let _ = writeln!(
        out,
        "# turnpass {}, machine model {} (SHA-256 {}).",
        header.version, header.model, header.model_sha256
    );
    let _ = writeln!(
        out,
        "# Okuma does not publish its pitch-error compensation format: key these in as OSP's service\n\
         # screens ask. position: machine coordinates in {units} from the machine's zero, X a radius;\n\
         # forward_um, reverse_um: the correction the control adds to the command there moving in + and in -\n\
         # (a negative value shortens the move), micrometres; backlash_um: the play the control takes up at\n\
         # each reversal. The correction is what the model's errors call for, not relative to any point."
    );
    let _ = writeln!(out, "axis,point,position_{units},forward_um,reverse_um");
    for axis_table in &table.axes {
        for (k, position) in axis_table.positions.iter().enumerate() {
            let _ = writeln!(
                out,
                "{},{k},{},{:.places$},{:.places$}",
                axis_table.axis.letter(),
                number(*position, 6),
                round(micrometres(axis_table.forward[k])),
                round(micrometres(axis_table.reverse[k])),
            );
        }
    }
    let _ = writeln!(out, "axis,backlash_um");
    for axis_table in &table.axes {
        let _ = writeln!(out, "{},{:.places$}", axis_table.axis.letter(), round(micrometres(axis_table.backlash)));
    }
    super::Written { main: out, beside: Vec::new() }
}

/// The decimals that show a step of `step` micrometres.
fn decimals(step: f64) -> usize {
    let mut places = 0;
    while places < 4 && (step * 10f64.powi(places as i32)).fract().abs() > 1e-9 {
        places += 1;
    }
    places
}

/// The rows as if OSP ran linearly between them: the residual `table` prints.
pub fn loaded(table: &Table) -> Loaded {
    let options = &table.options;
    let scale = mm_per_unit(options.units);
    let step = if options.unit > 0.0 { options.unit } else { 0.0001 / scale };
    let round = |v: f64| (v / step).round() * step;
    let mut compensation = ControlCompensation::default();
    for axis_table in &table.axes {
        let nodes: Vec<(f64, f64, f64)> = axis_table
            .positions
            .iter()
            .enumerate()
            .map(|(k, &m)| (m, round(axis_table.forward[k]), round(axis_table.reverse[k])))
            .collect();
        let zero = match axis_table.axis {
            Axis::X => options.zero.x,
            Axis::Z => options.zero.z,
        };
        let axis = Some(axis_compensation(&nodes, Between::Linear, round(axis_table.backlash), scale, zero));
        match axis_table.axis {
            Axis::X => compensation.x = axis,
            Axis::Z => compensation.z = axis,
        }
    }
    Loaded { control: super::Control::Okuma, compensation, unverified: Some(UNVERIFIED) }
}
