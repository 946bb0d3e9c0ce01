//! What each typed role of a cycle word means, and in which unit it is written, for hovers.
//!
//! The schemas in `grammar/` give every word of a command its [`Role`]; this table says in
//! words what the role is, for a machinist reading the program. Units are those of the
//! program as written (the semantic pass converts them in `semantic/frame.rs`).

use crate::dialect::{Dialect, Role};
use crate::machine::{MachineSettings, Units};

/// How a role's value reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    /// A length in program units.
    Length,
    /// An X length as programmed: a diameter on a diameter-programmed lathe.
    XLength,
    Feed,
    /// A thread lead (length per revolution).
    Lead,
    Angle,
    Count,
    /// A sequence number or name that the word refers to.
    Sequence,
    Seconds,
    Milliseconds,
    /// Spindle speed, or surface speed under constant surface speed.
    Speed,
    Rpm,
    /// A selection: a code, a tool, packed digits, an M code.
    Code,
    /// Present (or 1) to select a variant.
    Flag,
}

/// A role's meaning and unit.
pub fn describe(role: Role) -> (&'static str, Unit) {
    use Role::*;
    match role {
        AllowanceX => ("finishing allowance in X", Unit::XLength),
        AllowanceZ => ("finishing allowance in Z", Unit::Length),
        BottomRelief => ("relief at the bottom of the cut", Unit::Length),
        Chamfer => ("thread chamfer (run-out) length", Unit::Length),
        ConditionDepthA => ("depth of cut after condition-change point A", Unit::Length),
        ConditionDepthB => ("depth of cut after condition-change point B", Unit::Length),
        ConditionFeedA => ("feed after condition-change point A", Unit::Feed),
        ConditionFeedB => ("feed after condition-change point B", Unit::Feed),
        ConditionXA => ("X of condition-change point A", Unit::XLength),
        ConditionXB => ("X of condition-change point B", Unit::XLength),
        ConditionZA => ("Z of condition-change point A", Unit::Length),
        ConditionZB => ("Z of condition-change point B", Unit::Length),
        ContourFeed => ("feed along the contour in roughing", Unit::Feed),
        ContourName => ("the sequence name of the contour's G81/G82 block", Unit::Sequence),
        CornerSize => ("size of the automatic chamfer or rounding", Unit::Length),
        DepthOfCut => ("depth of cut of each roughing pass", Unit::Length),
        Divisions => ("number of roughing passes", Unit::Count),
        DwellMilliseconds => ("dwell", Unit::Milliseconds),
        DwellSeconds => ("dwell", Unit::Seconds),
        EndC => ("C-axis end position", Unit::Angle),
        EndOffset => ("tool offset at the end of the cycle", Unit::Code),
        EndX => ("X of the end point", Unit::XLength),
        EndY => ("Y of the end point", Unit::Length),
        EndZ => ("Z of the end point", Unit::Length),
        Feed => ("feed rate", Unit::Feed),
        FinishAllowance => ("finishing allowance (depth of the finishing pass)", Unit::Length),
        FirstDepth => ("depth of the first cut", Unit::Length),
        IncrementalC => ("C-axis distance", Unit::Angle),
        IncrementalX => ("X distance from the start", Unit::XLength),
        IncrementalY => ("Y distance from the start", Unit::Length),
        IncrementalZ => ("Z distance from the start", Unit::Length),
        InfeedAngle => ("infeed angle", Unit::Angle),
        InfeedMode => ("infeed mode (which flank the tool follows)", Unit::Code),
        InfeedPattern => ("infeed pattern (constant depth or constant cutting amount)", Unit::Code),
        Lead => ("thread lead", Unit::Lead),
        LeadChange => ("lead change per revolution", Unit::Lead),
        MaxSpindleSpeed => ("spindle speed limit", Unit::Rpm),
        MinDepth => ("minimum depth of cut", Unit::Length),
        NoReturn => ("no return to the start point after the cycle", Unit::Flag),
        OffsetGroup => ("tool offset group", Unit::Code),
        PeckDepth => ("depth of each peck", Unit::Length),
        PeckReduction => ("how much shorter each peck is than the one before", Unit::Length),
        PeckRetract => ("retract between pecks", Unit::Length),
        Phase => ("thread start angle", Unit::Angle),
        ProfileEnd => ("sequence number of the finishing profile's last block", Unit::Sequence),
        ProfileStart => ("sequence number of the finishing profile's first block", Unit::Sequence),
        ReferenceNumber => ("reference point number", Unit::Count),
        Repeats => ("how many times the cycle runs", Unit::Count),
        RPoint => ("R point: where the feed starts (Fanuc: from the initial level; Haas: its position)", Unit::Length),
        Relief => ("clearance before each plunge", Unit::Length),
        ReliefX => ("total stock in X to remove (relief distance)", Unit::Length),
        ReliefZ => ("total stock in Z to remove (relief distance)", Unit::Length),
        Retract => ("retract after each pass", Unit::Length),
        RoughAllowanceX => ("roughing allowance in X", Unit::XLength),
        RoughAllowanceZ => ("roughing allowance in Z", Unit::Length),
        ShiftAngle => ("shift angle between thread starts", Unit::Angle),
        ShiftX => ("shift between plunges in X", Unit::XLength),
        ShiftZ => ("shift between plunges in Z", Unit::Length),
        Speed => ("spindle speed", Unit::Speed),
        StartShift => ("shift of the start point", Unit::Length),
        Starts => ("number of thread starts", Unit::Count),
        StepX => ("step between plunges in X", Unit::Length),
        StepZ => ("step between plunges in Z", Unit::Length),
        Taper => ("taper: radius difference from start to end", Unit::Length),
        TaperAngle => ("taper angle", Unit::Angle),
        ThreadChamfer => ("thread chamfering on or off", Unit::Code),
        ThreadHeight => ("thread height", Unit::Length),
        ThreadParameters => ("finishing passes, chamfer and tool angle, two digits each", Unit::Code),
        ThreadsPerInch => ("threads per inch", Unit::Count),
        Tool => ("tool", Unit::Code),
        ToolAngle => ("tool (thread) angle", Unit::Angle),
        ToolGroup => ("tool group", Unit::Code),
        TypeIi => ("Type II roughing (pockets) when 1", Unit::Flag),
        WorkCoordinateNumber => ("work coordinate system number", Unit::Count),
    }
}

/// The unit in words, for this machine. `increments` says the word counts least increments
/// (a Fanuc length the schema writes without a decimal point, `G76 Q`).
pub fn unit_text(unit: Unit, settings: &MachineSettings, dialect: Dialect, increments: bool) -> String {
    let inch = settings.units == Some(Units::Inch);
    let length = if inch { "inch" } else { "mm" };
    let x_as = if settings.diameter_programming.unwrap_or(true) { "a diameter" } else { "a radius" };
    let increment = settings.least_increment.unwrap_or(if inch { 0.0001 } else { 0.001 });
    match unit {
        Unit::Length | Unit::XLength if increments && dialect == Dialect::Fanuc => {
            format!("least increments of {increment} {length}, no decimal point")
        }
        Unit::Length => length.to_string(),
        Unit::XLength => format!("{length}, X as {x_as}"),
        Unit::Feed => format!("{length} per revolution or per minute, as the feed mode says"),
        Unit::Lead => format!("{length} per revolution"),
        Unit::Angle => "degrees".to_string(),
        Unit::Count => "a count".to_string(),
        Unit::Sequence => "a sequence name".to_string(),
        Unit::Seconds => "seconds".to_string(),
        Unit::Milliseconds => "milliseconds".to_string(),
        Unit::Speed => format!("rpm, or {} under constant surface speed", if inch { "ft/min" } else { "m/min" }),
        Unit::Rpm => "rpm".to_string(),
        Unit::Code => "a selection, no unit".to_string(),
        Unit::Flag => "present to select".to_string(),
    }
}

/// The role's name as the schemas write it (`allowance_x`).
pub fn role_name(role: Role) -> String {
    let debug = format!("{role:?}");
    let mut name = String::with_capacity(debug.len() + 4);
    for (i, c) in debug.chars().enumerate() {
        if c.is_ascii_uppercase() {
            if i > 0 {
                name.push('_');
            }
            name.push(c.to_ascii_lowercase());
        } else {
            name.push(c);
        }
    }
    name
}

#[cfg(test)]
mod tests;
