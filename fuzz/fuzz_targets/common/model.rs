//! Machine models built from effects and slide tables (`arbitrary`), as model files: every
//! effect of the catalogue with parameters of every size, inside and outside their ranges
//! (a model file's numbers are checked when it is read, so most of them read, and the rest
//! are refusals to be made cleanly), and slide tables written inline.

use std::fmt::Write as _;

use arbitrary::{Arbitrary, Result, Unstructured};

/// A parameter: mostly of the size a machine has, sometimes anything.
#[derive(Debug, Clone, Copy)]
pub struct Parameter(pub f64);

impl<'a> Arbitrary<'a> for Parameter {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        Ok(Parameter(match u.int_in_range(0..=9u8)? {
            0..=5 => f64::from(u.int_in_range(-10_000..=10_000i32)?) / 1e6,
            6 | 7 => f64::from(u.int_in_range(-1000..=1000i32)?) / 10.0,
            8 => f64::from(u.int_in_range(0..=100_000u32)?),
            _ => *u.choose(&[0.0, 1e-12, 1e300, -1e300, 3.0e38, f64::EPSILON])?,
        }))
    }
}

impl std::fmt::Display for Parameter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // TOML wants a point or an exponent on a float.
        if self.0.fract() == 0.0 && self.0.abs() < 1e15 {
            write!(f, "{:.1}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

#[derive(Debug, Clone, Arbitrary)]
pub enum Effect {
    Backlash { z: bool, b: Parameter },
    Cyclic { z: bool, amp: Parameter, pitch: Parameter, phase: Parameter },
    NoseRadius { dr: Parameter },
    ReversalSpike { z: bool, h: Parameter, decay_mm: Parameter },
    Scale { z: bool, ppm: Parameter },
    ServoMismatch { dt_ms: Parameter },
    Squareness { urad: Parameter },
    Straightness { z: bool, coeffs: Vec<Parameter> },
    Thermal { z: bool, amp: Parameter, tau_min: Parameter },
    ToolOffset { z: bool, d: Parameter },
    ToolWear { um_per_m: Parameter },
}

#[derive(Debug, Clone, Arbitrary)]
pub struct TableRow {
    pub target: u16,
    pub up: bool,
    pub linear: Parameter,
    pub straightness: Parameter,
}

#[derive(Debug, Clone, Arbitrary)]
pub struct Model {
    pub start_min: Option<Parameter>,
    pub abbe_y_mm: Option<Parameter>,
    pub effects: Vec<Effect>,
    pub x_table: Vec<TableRow>,
    pub z_table: Vec<TableRow>,
}

fn axis(z: bool) -> char {
    if z { 'z' } else { 'x' }
}

impl Model {
    /// The model as a model file, on `machine` (a `[machine]` table).
    pub fn text(&self, machine: &str) -> String {
        let mut out = String::from(machine);
        if self.start_min.is_some() || self.abbe_y_mm.is_some() {
            out.push_str("[model]\n");
            if let Some(start) = self.start_min {
                let _ = writeln!(out, "start_min = {start}");
            }
            if let Some(abbe) = self.abbe_y_mm {
                let _ = writeln!(out, "abbe_y_mm = {abbe}");
            }
        }
        for (name, rows) in [('x', &self.x_table), ('z', &self.z_table)] {
            if rows.is_empty() {
                continue;
            }
            let _ = writeln!(
                out,
                "[[axis_table]]\naxis = \"{name}\"\ncsv = \"\"\"\ntarget_mm,direction,linear_mm,straightness_mm"
            );
            for row in rows.iter().take(40) {
                let direction = if row.up { "up" } else { "down" };
                let _ =
                    writeln!(out, "{},{direction},{},{}", f64::from(row.target) / 10.0, row.linear, row.straightness);
            }
            out.push_str("\"\"\"\n");
        }
        for effect in self.effects.iter().take(8) {
            out.push_str("[[effect]]\n");
            let _ = match effect {
                Effect::Backlash { z, b } => writeln!(out, "kind = \"backlash_{}\"\nb = {b}", axis(*z)),
                Effect::Cyclic { z, amp, pitch, phase } => {
                    writeln!(out, "kind = \"cyclic_{}\"\namp = {amp}\npitch = {pitch}\nphase = {phase}", axis(*z))
                }
                Effect::NoseRadius { dr } => writeln!(out, "kind = \"nose_radius\"\ndr = {dr}"),
                Effect::ReversalSpike { z, h, decay_mm } => {
                    writeln!(out, "kind = \"reversal_spike_{}\"\nh = {h}\ndecay_mm = {decay_mm}", axis(*z))
                }
                Effect::Scale { z, ppm } => writeln!(out, "kind = \"scale_{}\"\nppm = {ppm}", axis(*z)),
                Effect::ServoMismatch { dt_ms } => writeln!(out, "kind = \"servo_mismatch\"\ndt_ms = {dt_ms}"),
                Effect::Squareness { urad } => writeln!(out, "kind = \"squareness\"\nurad = {urad}"),
                Effect::Straightness { z, coeffs } => {
                    let list: Vec<String> = coeffs.iter().take(8).map(ToString::to_string).collect();
                    writeln!(out, "kind = \"straightness_{}\"\ncoeffs = [{}]", axis(*z), list.join(", "))
                }
                Effect::Thermal { z, amp, tau_min } => {
                    writeln!(out, "kind = \"thermal_{}\"\namp = {amp}\ntau_min = {tau_min}", axis(*z))
                }
                Effect::ToolOffset { z, d } => {
                    let key = if *z { "dz" } else { "dx" };
                    writeln!(out, "kind = \"tool_offset_{}\"\n{key} = {d}", axis(*z))
                }
                Effect::ToolWear { um_per_m } => writeln!(out, "kind = \"tool_wear\"\num_per_m = {um_per_m}"),
            };
        }
        out
    }
}
