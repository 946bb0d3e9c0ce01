//! What each typed role of a cycle word means, and in which unit it is written.
//!
//! The schemas in `grammar/` give every word of a command its [`Role`]; this table says in
//! words what the role is, for a machinist reading the program (the language server's
//! hovers), and what a word of the role counts when the schema takes it without a decimal
//! point (`IntegerUnit`: the hint of `integer-expected` computes the value meant from it).

use super::Role;

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

/// What a word that the schema takes without a decimal point counts (`integer` in
/// `grammar/`), read from its role's unit: a length or an angle in least increments of the
/// program's units, milliseconds, a sequence number, a count, or the digits of a code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IntegerUnit {
    /// Least increments of a length (`G76 P920` is 0.920 mm at 0.001 mm).
    Increments,
    /// Least increments of an angle, 0.001° (`G92 Q` thread start angle).
    AngleIncrements,
    Milliseconds,
    Sequence,
    Count,
    /// Digits packed into a code (`G76 P010060`), or a selection: nothing to compute.
    Code,
}

impl IntegerUnit {
    /// What a word of `role` counts when it is written without a decimal point.
    pub fn of(role: Role) -> IntegerUnit {
        match describe(role).1 {
            Unit::Length | Unit::XLength => IntegerUnit::Increments,
            Unit::Angle => IntegerUnit::AngleIncrements,
            Unit::Milliseconds => IntegerUnit::Milliseconds,
            Unit::Sequence => IntegerUnit::Sequence,
            Unit::Count | Unit::Flag => IntegerUnit::Count,
            Unit::Feed | Unit::Lead | Unit::Seconds | Unit::Speed | Unit::Rpm | Unit::Code => IntegerUnit::Code,
        }
    }

    /// Whether the count depends on the program's units and least increment, which only the
    /// semantic pass knows (`G20`/`G21` may change them along the program).
    pub fn needs_frame(self) -> bool {
        matches!(self, IntegerUnit::Increments | IntegerUnit::AngleIncrements)
    }
}

/// The longest length a word counted in least increments can mean when it is written with
/// a decimal point, mm: these words are depths of cut, thread heights, pecks and steps
/// between plunges, none of which reaches an inch. A longer reading (`Q80.` as 80 mm) is
/// the count itself with a stray point (`Q80`, 80 increments).
pub const LONGEST_COUNTED_LENGTH_MM: f64 = 25.4;

/// The longest dwell a `P` written with a decimal point can mean, s: a dwell holds a cut
/// for a few revolutions, seconds at most. A longer reading (`P1000.` as 1000 s) is the
/// count of milliseconds itself with a stray point (`P1000`).
pub const LONGEST_DWELL_S: f64 = 60.0;

/// The value a word written with a decimal point (`value`, as written) was meant to give,
/// as the whole number to write in its place, and that number's reading in words. `length`
/// is the program's least increment and millimetres per program unit, for the units that
/// count increments (`needs_frame`). `None` when it cannot be told: a fraction of a
/// sequence number or a count, a code's digits.
pub fn meant(unit: IntegerUnit, value: f64, length: Option<(f64, f64)>) -> Option<(i64, String)> {
    let whole = |v: f64| (v - v.round()).abs() <= 1e-6 * v.abs().max(1.0);
    let stray_point = whole(value).then(|| value.round() as i64);
    match unit {
        IntegerUnit::Sequence => stray_point.map(|n| (n, format!("sequence number {n}"))),
        IntegerUnit::Count => stray_point.map(|n| (n, format!("{n}"))),
        IntegerUnit::Code => None,
        IntegerUnit::Milliseconds => {
            let ms = value * 1000.0;
            if value.abs() <= LONGEST_DWELL_S && whole(ms) {
                Some((ms.round() as i64, format!("{} s", short(value))))
            } else {
                stray_point.map(|n| (n, format!("{} s", short(n as f64 / 1000.0))))
            }
        }
        IntegerUnit::Increments | IntegerUnit::AngleIncrements => {
            let angle = unit == IntegerUnit::AngleIncrements;
            // An angle counts thousandths of a degree whatever the length units.
            let (increment, mm_per_unit) = if angle { (0.001, 1.0) } else { length? };
            let unit_name = if angle {
                "°"
            } else if mm_per_unit == 1.0 {
                " mm"
            } else {
                " in"
            };
            let reading = |count: i64| format!("{}{unit_name}", short(count as f64 * increment));
            let count = value / increment;
            let as_length = (angle || value.abs() * mm_per_unit <= LONGEST_COUNTED_LENGTH_MM) && whole(count);
            if as_length {
                let count = count.round() as i64;
                Some((count, reading(count)))
            } else {
                stray_point.map(|n| (n, reading(n)))
            }
        }
    }
}

/// A value with the digits it needs, up to six decimals (`0.92`, `3`, `0.0005`).
pub fn short(value: f64) -> String {
    let text = format!("{value:.6}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" { "0".to_string() } else { text.to_string() }
}

/// The unit in one word, for messages (`seconds`).
pub fn unit_word(unit: Unit) -> &'static str {
    match unit {
        Unit::Length | Unit::XLength => "length units",
        Unit::Feed => "feed units",
        Unit::Lead => "length per revolution",
        Unit::Angle => "degrees",
        Unit::Count => "a count",
        Unit::Sequence => "a sequence number",
        Unit::Seconds => "seconds",
        Unit::Milliseconds => "milliseconds",
        Unit::Speed | Unit::Rpm => "rpm",
        Unit::Code | Unit::Flag => "a code",
    }
}
