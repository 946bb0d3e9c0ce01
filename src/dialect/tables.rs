//! The dialect tables of `grammar/*.toml`, compiled once into lookup structures.
//!
//! The TOML files are the normative statement of each dialect; this module only reads them.
//! Lookups on the parser's hot path (address letters, G-codes) are array indexes.

use std::collections::{BTreeMap, HashMap};
use std::fmt;
use std::sync::OnceLock;

use serde::Deserialize;

use super::address::parse_code;
pub use super::address::{Address, Code};
use super::{Control, Dialect, DialectConfig, GCodeSystem, MachineKind};

const FANUC_TOML: &str = include_str!("../../grammar/fanuc.toml");
const OSP_TOML: &str = include_str!("../../grammar/osp.toml");

/// How a value of an address reads (decimal point meaning, canonical format).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AddressKind {
    /// A length: decimal point meaningful, scaled by the least increment when absent on
    /// least-increment controls.
    Length,
    Feed,
    Angle,
    Speed,
    Tool,
    Code,
    /// A count, a sequence number or a value in least increments: no decimal point.
    Integer,
    /// Depends on the command.
    Number,
}

#[derive(Debug, Clone, Deserialize)]
pub struct AddressSpec {
    pub kind: AddressKind,
    #[serde(default = "default_max_digits")]
    pub max_digits: usize,
    pub meaning: String,
}

fn default_max_digits() -> usize {
    8
}

/// The typed role of a word in a command, as the schemas of `grammar/` name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    AllowanceX,
    AllowanceZ,
    BottomRelief,
    Chamfer,
    ConditionDepthA,
    ConditionDepthB,
    ConditionFeedA,
    ConditionFeedB,
    ConditionXA,
    ConditionXB,
    ConditionZA,
    ConditionZB,
    ContourFeed,
    ContourName,
    CornerSize,
    DepthOfCut,
    Divisions,
    DwellMilliseconds,
    DwellSeconds,
    EndC,
    EndOffset,
    EndX,
    EndY,
    EndZ,
    Feed,
    FinishAllowance,
    FirstDepth,
    IncrementalC,
    IncrementalX,
    IncrementalY,
    IncrementalZ,
    InfeedAngle,
    InfeedMode,
    InfeedPattern,
    Lead,
    LeadChange,
    MaxSpindleSpeed,
    MinDepth,
    NoReturn,
    OffsetGroup,
    PeckDepth,
    /// Haas `G83 J`: how much each peck is shorter than the one before.
    PeckReduction,
    PeckRetract,
    Phase,
    ProfileEnd,
    ProfileStart,
    ReferenceNumber,
    /// A drilling cycle's R point: Fanuc `R`, the signed distance from the initial level;
    /// Haas `R`, the plane's position.
    RPoint,
    Relief,
    ReliefX,
    ReliefZ,
    Retract,
    /// A drilling cycle's `K`: how many times it runs (Fanuc).
    Repeats,
    RoughAllowanceX,
    RoughAllowanceZ,
    ShiftAngle,
    ShiftX,
    ShiftZ,
    Speed,
    StartShift,
    Starts,
    StepX,
    StepZ,
    Taper,
    TaperAngle,
    ThreadChamfer,
    ThreadHeight,
    ThreadParameters,
    ThreadsPerInch,
    Tool,
    ToolAngle,
    ToolGroup,
    TypeIi,
    WorkCoordinateNumber,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ModalGroup {
    Motion,
    OneShot,
    Plane,
    Units,
    Distance,
    FeedMode,
    SpindleMode,
    NoseRadius,
    WorkOffset,
    Polar,
    StrokeCheck,
    SpindleCheck,
    PathMode,
    MacroModal,
    Drilling,
    ReturnLevel,
    Turret,
    Droop,
    Corner,
    Lap,
    ToolLength,
    CssTurret,
    SpindleSelect,
    LiveToolCycle,
}

/// What a G-code does to the block it is in; the statement of a block follows from it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GKind {
    Motion,
    ThreadMove,
    Cycle,
    LapCall,
    LapMarker,
    Dwell,
    OneShot,
    Modal,
    Corner,
}

impl GKind {
    /// Which G-code names a block's statement when several share the block: a cycle outranks
    /// a one-shot, which outranks a plain motion.
    pub fn rank(self) -> u8 {
        match self {
            GKind::Cycle | GKind::LapCall | GKind::LapMarker => 5,
            GKind::Dwell => 4,
            GKind::OneShot => 3,
            GKind::ThreadMove => 2,
            GKind::Motion => 1,
            GKind::Modal | GKind::Corner => 0,
        }
    }
}

/// What a G-code does, whatever its number in a dialect or G-code system. The semantic pass
/// dispatches on this, so the numbers stay in `grammar/`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GFunction {
    Absolute,
    AtcHome,
    Ccw,
    ChamferCorner,
    CompensationLeft,
    CompensationOff,
    CompensationRight,
    CompoundThreadFace,
    CompoundThreadLongitudinal,
    CoordinateSetOrClamp,
    Cw,
    DiameterGrooving,
    /// A drilling cycle turnpass does not simulate (OSP live-tool and machining-centre
    /// cycles; `grammar/osp.toml` says why).
    Drilling,
    DrillingCancel,
    /// Fanuc system B/C `G98`/`G99`: a drilling cycle returns to the initial level, or to
    /// the R point.
    DrillReturnInitial,
    DrillReturnRPoint,
    /// Drilling, tapping and boring along Z on the face (`semantic/cycles/face_*.rs`), and
    /// along X on the side (`side_drilling.rs`).
    FaceDrilling,
    FaceTapping,
    FaceBoring,
    SideDrilling,
    Dwell,
    FacePeck,
    FacingCycle,
    FeedPerMinute,
    FeedPerRev,
    Finishing,
    Inch,
    Incremental,
    LapBlank,
    LapCondition,
    LapContourLongitudinal,
    LapContourTransverse,
    LapCopy,
    LapEnd,
    LapFinish,
    LapRough,
    LapThread,
    Linear,
    LocalShift,
    MachineCoordinates,
    MacroCall,
    Metric,
    MultipleThreading,
    OspFaceCutting,
    OspGrooving,
    PatternRepeat,
    Rapid,
    ReferenceCheck,
    ReferenceReturn,
    RoundCorner,
    Rpm,
    SecondReferenceReturn,
    StockRemovalFacing,
    StockRemovalTurning,
    SurfaceSpeed,
    Tapping,
    ThreadCycle,
    ThreadMove,
    ThreadSingle,
    /// OSP `G34`/`G35`: the single-pass thread cycle with a lead that grows (or shrinks) by
    /// `E` every revolution.
    ThreadSingleLeadIncreasing,
    ThreadSingleLeadDecreasing,
    /// OSP `G31`: the manual's other name for the `G33` cycle ("programmed in the same manner");
    /// a function of its own so that `expand` writes the usual `G33`.
    ThreadSingleAlias,
    ThreadSingleFace,
    TurningCycle,
    VariableLeadThreadMove,
    WorkOffset,
}

/// Whose the F and S words of a cycle block are (`feed_and_speed` of a cycle's `[[g]]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FeedAndSpeed {
    /// The modal feed and speed: the cycle cuts at them and they stay in effect after it
    /// (Fanuc `G70`–`G73`, the single cycles).
    Modal,
    /// The cycle's own (a thread lead, a grooving feed): the modal feed and speed stay as
    /// they were.
    Own,
}

#[derive(Debug, Clone)]
pub struct GInfo {
    pub code: Code,
    pub group: ModalGroup,
    pub kind: GKind,
    pub schema: Option<SchemaId>,
    pub meaning: String,
    pub note: Option<String>,
    pub function: Option<GFunction>,
    /// Whose the block's F and S are; every `cycle` and `lap_call` code says (tested), no
    /// other code does.
    pub feed_and_speed: Option<FeedAndSpeed>,
    /// A drilling cycle's retract and peck (`drilling` in `grammar/`).
    pub drilling: Option<DrillingFacts>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SchemaId(pub u16);

/// Where a code this configuration lacks does exist.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Elsewhere {
    pub meaning: String,
    pub place: Place,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Place {
    GCodeSystem(GCodeSystem),
    OspMachiningCentre,
    OspLathe,
}

#[derive(Debug, Clone)]
pub struct Schema {
    pub name: String,
    pub forms: Vec<Form>,
}

/// One form of a command: which words select it, and the role of each word.
#[derive(Debug, Clone, Deserialize)]
pub struct Form {
    pub name: String,
    #[serde(default)]
    pub when_all: Vec<Address>,
    #[serde(default)]
    pub when_any: Vec<Address>,
    /// Each address and its role, in the order the schema lists them, which is also the
    /// order `fmt --canonical` writes them in.
    #[serde(default, deserialize_with = "ordered_map")]
    pub words: Vec<(Address, Role)>,
    #[serde(default)]
    pub integer: Vec<Address>,
    /// Words that count least increments without a decimal point, as `integer` words do,
    /// but that a control may also take with one (read then as a length, as written); which
    /// controls do is not verified, so a point is warned of with both readings.
    #[serde(default)]
    pub point_unverified: Vec<Address>,
    /// Words that play another role when written with a decimal point (a Haas dwell `P0.3`
    /// is seconds where `P300` is milliseconds).
    #[serde(default, deserialize_with = "ordered_map")]
    pub point_reads: Vec<(Address, Role)>,
    /// Lengths the control reads as diameters, beside `X` (the OSP thread cycles' `D`, `U`,
    /// `H`).
    #[serde(default)]
    pub diameter: Vec<Address>,
    #[serde(default)]
    pub required: Vec<Address>,
    #[serde(default)]
    pub required_any: Vec<Vec<Address>>,
    /// M codes that are parameters of the command (`M32` infeed mode in an OSP G71), by number.
    #[serde(default)]
    pub m_words: BTreeMap<String, Role>,
    #[serde(default)]
    pub g_words: Vec<String>,
    /// The role of an `N` operand (`G85 N0207`).
    #[serde(default)]
    pub labels: Option<Role>,
    /// Commands whose arguments are free (`G65 P9010 A1 B2`).
    #[serde(default)]
    pub any_words: bool,
}

/// A TOML table read as a list of pairs in document order.
fn ordered_map<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<Vec<(Address, Role)>, D::Error> {
    struct Visitor;
    impl<'de> serde::de::Visitor<'de> for Visitor {
        type Value = Vec<(Address, Role)>;
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str("a table of address = role")
        }
        fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
            let mut out = Vec::new();
            while let Some((address, role)) = map.next_entry::<Address, Role>()? {
                out.push((address, role));
            }
            Ok(out)
        }
    }
    deserializer.deserialize_map(Visitor)
}

impl Form {
    pub fn role_of(&self, address: Address) -> Option<Role> {
        self.words.iter().find(|(a, _)| *a == address).map(|(_, role)| *role)
    }

    /// Position of `address` in the schema's word list.
    pub fn position_of(&self, address: Address) -> Option<usize> {
        self.words.iter().position(|(a, _)| *a == address)
    }

    pub fn m_role(&self, m_code: u16) -> Option<Role> {
        self.m_words.iter().find(|(k, _)| k.parse::<u16>().ok() == Some(m_code)).map(|(_, r)| *r)
    }

    pub fn takes_integer(&self, address: Address) -> bool {
        self.integer.contains(&address)
    }

    /// Whether `address` counts least increments (or milliseconds, a sequence number…) when
    /// written without a decimal point: an `integer` or a `point_unverified` word.
    pub fn counts_without_point(&self, address: Address) -> bool {
        self.integer.contains(&address) || self.point_unverified.contains(&address)
    }

    /// The role `address` plays when written with a decimal point, where it differs.
    pub fn role_with_point(&self, address: Address) -> Option<Role> {
        self.point_reads.iter().find(|(a, _)| *a == address).map(|(_, role)| *role)
    }

    /// Whether the control reads `address` as a diameter.
    pub fn is_diameter(&self, address: Address) -> bool {
        self.diameter.contains(&address)
    }

    /// Whether the words present (by address) select this form.
    pub fn matches(&self, present: impl Fn(Address) -> bool) -> bool {
        self.when_all.iter().all(|&a| present(a))
            && (self.when_any.is_empty() || self.when_any.iter().any(|&a| present(a)))
    }

    /// The allowed addresses, for "it takes …" hints.
    pub fn allowed_list(&self) -> String {
        let mut names: Vec<String> = self.words.iter().map(|(a, _)| format!("`{a}`")).collect();
        if self.labels.is_some() {
            names.insert(0, "`N`".to_string());
        }
        names.join(", ")
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum KeywordKind {
    If,
    Goto,
    Then,
    While,
    Do,
    EndLoop,
    Call,
    Return,
    ModalCall,
    ModalCallEnd,
    Io,
    Schedule,
    Graphics,
    Pattern,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum KeywordArgs {
    #[default]
    Words,
    Verbatim,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MachineScope {
    Lathe,
    Mc,
}

#[derive(Debug, Clone, Deserialize)]
pub struct KeywordInfo {
    pub kind: KeywordKind,
    #[serde(default)]
    pub args: KeywordArgs,
    #[serde(default)]
    pub machine: Option<MachineScope>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SequenceStyle {
    Numeric,
    Osp,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SemicolonRule {
    EndOfBlock,
    NotAComment,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum VariableStyle {
    Hash,
    Osp,
}

#[derive(Debug, Clone, Deserialize)]
pub struct Lexical {
    pub sequence: SequenceStyle,
    pub sequence_max: usize,
    pub program_name: SequenceStyle,
    pub program_name_max: usize,
    pub semicolon: SemicolonRule,
    pub continuation: bool,
    pub variables: VariableStyle,
    pub space_before_value: bool,
    pub block_delete_levels: bool,
    pub mid_block_skip: bool,
}

#[derive(Debug, Clone, Deserialize)]
pub struct ExpressionRules {
    pub functions: Vec<String>,
    pub comparisons: Vec<String>,
    pub logic: Vec<String>,
    pub arithmetic_words: Vec<String>,
    pub max_depth: usize,
}

#[derive(Debug, Deserialize)]
struct RawG {
    code: Option<String>,
    a: Option<String>,
    b: Option<String>,
    c: Option<String>,
    group: ModalGroup,
    kind: GKind,
    schema: Option<String>,
    meaning: String,
    /// A remark for readers and hovers, kept out of diagnostics.
    note: Option<String>,
    function: Option<GFunction>,
    feed_and_speed: Option<FeedAndSpeed>,
    machine: Option<MachineScope>,
    /// The Fanuc-compatible controls the entry is for (all when absent).
    control: Option<Vec<Control>>,
    /// How a drilling cycle retracts and pecks.
    drilling: Option<DrillingFacts>,
}

/// What a drilling cycle does after it reaches the bottom of the hole, and how it pecks
/// (`drilling` of a `[[g]]` entry).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DrillingFacts {
    pub retract: DrillRetract,
    /// How `Q` pecks: back a little and on (`high_speed`), or out to the R point and back
    /// down (`full`); absent for a cycle that does not peck.
    pub peck: Option<DrillPeck>,
    /// `R` is the R plane's position (Haas), not the distance from the initial level
    /// (Fanuc).
    #[serde(default)]
    pub r_plane: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DrillRetract {
    /// Rapid out (drilling).
    Rapid,
    /// Out at the cutting feed (boring, reaming).
    Feed,
    /// The spindle reverses and the tap backs out at the feed it went in (tapping).
    Reverse,
    /// The spindle stops and the tool rapids out (Haas `G86`).
    SpindleStopRapid,
    /// The spindle stops and the operator jogs the tool out (Haas `G87`, `G88`).
    Manual,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DrillPeck {
    HighSpeed,
    Full,
}

/// What a Fanuc-compatible control accepts that a Fanuc does not (`[control.NAME]`).
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct ControlRules {
    /// Lower-case letters read as the upper-case ones (`o0001`, `t101`, `g01 x10.`).
    #[serde(default)]
    lower_case: bool,
}

#[derive(Debug, Deserialize)]
struct RawSchema {
    form: Vec<Form>,
}

#[derive(Debug, Deserialize)]
struct RawDialect {
    #[allow(dead_code)]
    dialect: Dialect,
    title: String,
    lexical: Lexical,
    address: BTreeMap<String, AddressSpec>,
    #[serde(default)]
    extended: BTreeMap<String, AddressSpec>,
    /// Fanuc comma addresses, keyed by their letter (`C` is `,C`).
    #[serde(default)]
    comma: BTreeMap<String, AddressSpec>,
    #[serde(default)]
    machine_variables: MachineVariables,
    #[serde(default)]
    increment_input: IncrementInput,
    #[serde(default)]
    thread_lead: ThreadLead,
    #[serde(default)]
    thread_move: ThreadMove,
    /// Keyed by the control's name (`haas`).
    #[serde(default)]
    control: BTreeMap<String, ControlRules>,
    expression: ExpressionRules,
    keywords: BTreeMap<String, KeywordInfo>,
    g: Vec<RawG>,
    m: BTreeMap<String, String>,
    #[serde(default)]
    foreign_g: BTreeMap<String, String>,
    m_functions: MFunctions,
    schema: BTreeMap<String, RawSchema>,
}

/// How a word without a decimal point reads on a control set for least-increment input
/// (`decimal_input = "increment"`), beside the lengths and angles, which count increments
/// (`[increment_input]`).
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IncrementInput {
    /// A feed per revolution (and a thread lead) counts least increments of a length per
    /// revolution (`G99 F250` is 0.25 mm/rev at 0.001 mm); a feed per minute is whole units.
    #[serde(default)]
    pub feed_per_revolution_counts: bool,
}

/// The digits a thread cycle's lead word takes, and the words that write a finer lead
/// (`[thread_lead]`): compensation writes a corrected lead with them.
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThreadLead {
    /// The decimals of the lead word (`F`) beyond the least increment's.
    #[serde(default)]
    pub decimals_beyond_increment: u8,
    /// A precise-lead word the thread cycles take instead of `F` (Fanuc-compatible `E`).
    #[serde(default)]
    pub precise: Option<PreciseLead>,
    /// A word that counts the threads `F` is the length of (OSP `J`: the lead is `F/J`).
    #[serde(default)]
    pub count: Option<Address>,
    /// Consecutive thread moves keep the spindle synchronisation from block to block, each at
    /// its own lead (continuous thread cutting): a thread pass may be written as several.
    #[serde(default)]
    pub continuous: bool,
    /// The word of a variable-lead thread move (Fanuc `G34`) that gives the lead's change
    /// every spindle turn.
    #[serde(default)]
    pub change: Option<Address>,
}

/// The words of a thread move block beyond its end and lead (`[thread_move]`).
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThreadMove {
    /// The word that starts the thread at an angle past the spindle's one-turn signal, a
    /// count of 0.001° (Fanuc-compatible `Q`): one start of a multi-start thread.
    #[serde(default)]
    pub start_angle: Option<Address>,
}

/// A precise-lead word and the decimals it takes beyond the least increment's.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PreciseLead {
    pub address: Address,
    pub decimals_beyond_increment: u8,
}

/// The common variables the control keeps in memory: a program may read them before it
/// sets them, and their values come from the machine.
#[derive(Debug, Clone, Default, Deserialize)]
pub struct MachineVariables {
    /// Inclusive ranges of variable numbers (`#500`–`#999`, OSP `V1`–`V200`).
    pub numbers: Vec<[u32; 2]>,
}

impl MachineVariables {
    pub fn holds(&self, number: u32) -> bool {
        self.numbers.iter().any(|[low, high]| (*low..=*high).contains(&number))
    }
}

/// The M codes the semantic pass acts on.
#[derive(Debug, Clone, Default, Deserialize)]
pub struct MFunctions {
    pub end: Vec<u16>,
    pub subprogram_call: Vec<u16>,
    pub subprogram_return: Vec<u16>,
    pub spindle_stop: Vec<u16>,
    /// OSP thread-end chamfering on / off (`M23`/`M22`), a mode kept from block to block.
    #[serde(default)]
    pub thread_chamfer_on: Vec<u16>,
    #[serde(default)]
    pub thread_chamfer_off: Vec<u16>,
    /// OSP compound thread cycles: the infeed mode (along one flank, zigzag, along the other
    /// flank) and the infeed pattern (1, 2, 3) written in the cycle block.
    #[serde(default)]
    pub infeed_one_flank: Vec<u16>,
    #[serde(default)]
    pub infeed_zigzag: Vec<u16>,
    #[serde(default)]
    pub infeed_other_flank: Vec<u16>,
    #[serde(default)]
    pub infeed_pattern_1: Vec<u16>,
    #[serde(default)]
    pub infeed_pattern_2: Vec<u16>,
    #[serde(default)]
    pub infeed_pattern_3: Vec<u16>,
}

/// The compiled tables of one dialect configuration.
#[derive(Debug)]
pub struct Tables {
    pub config: DialectConfig,
    pub title: String,
    pub lexical: Lexical,
    pub expression: ExpressionRules,
    letters: [Option<AddressSpec>; 26],
    /// The two-letter (OSP) and comma (Fanuc) addresses.
    extended: Vec<(Address, AddressSpec)>,
    /// The dialect has comma words (`,C`, `,R`, `,A`), so a comma ends a value.
    pub has_comma_words: bool,
    pub machine_variables: MachineVariables,
    pub increment_input: IncrementInput,
    pub thread_lead: ThreadLead,
    pub thread_move: ThreadMove,
    /// Lower-case letters read as upper-case ones (`[control.NAME] lower_case`).
    pub lower_case: bool,
    keywords: Vec<(String, KeywordInfo)>,
    g_index: Vec<u16>,
    g_infos: Vec<GInfo>,
    /// The code that performs each function (the lowest, when several do), found once: the
    /// printer and the passes that write blocks ask for every block they write.
    code_for: HashMap<GFunction, Code>,
    /// Codes this configuration lacks but a sibling has (another G-code system, or the other
    /// OSP machine kind), for hints.
    g_elsewhere: HashMap<Code, Elsewhere>,
    /// Codes of the other dialect, with a note on what to write instead.
    foreign_g: HashMap<Code, String>,
    m: HashMap<u16, String>,
    pub m_functions: MFunctions,
    schemas: Vec<Schema>,
}

impl Tables {
    pub fn address(&self, address: Address) -> Option<&AddressSpec> {
        if let Some(letter) = address.as_letter() {
            self.letters[(letter - b'A') as usize].as_ref()
        } else {
            self.extended.iter().find(|(a, _)| *a == address).map(|(_, spec)| spec)
        }
    }

    /// The digit limit of a one-letter address, or `None` if the dialect lacks the letter.
    #[inline]
    pub fn max_digits(&self, address: Address) -> Option<usize> {
        let letter = address.as_letter()?;
        self.letters[(letter - b'A') as usize].as_ref().map(|spec| spec.max_digits)
    }

    pub fn extended_address(&self, name: &[u8]) -> Option<Address> {
        if let [a, b] = name
            && a.is_ascii_uppercase()
            && b.is_ascii_uppercase()
        {
            let address = Address::extended(*a, *b);
            if self.extended.iter().any(|(x, _)| *x == address) {
                return Some(address);
            }
        }
        None
    }

    pub fn keyword(&self, name: &[u8]) -> Option<(usize, &KeywordInfo)> {
        let index = self.keywords.binary_search_by(|(k, _)| k.as_bytes().cmp(name)).ok()?;
        Some((index, &self.keywords[index].1))
    }

    pub fn keyword_name(&self, index: usize) -> &str {
        &self.keywords[index].0
    }

    pub fn keyword_info(&self, index: usize) -> &KeywordInfo {
        &self.keywords[index].1
    }

    pub fn g(&self, code: Code) -> Option<&GInfo> {
        let slot = *self.g_index.get(code.0 as usize)?;
        if slot == 0 { None } else { Some(&self.g_infos[slot as usize - 1]) }
    }

    /// The code that performs `function` in this configuration (the lowest, when several do).
    pub fn code_for(&self, function: GFunction) -> Option<Code> {
        self.code_for.get(&function).copied()
    }

    pub fn g_elsewhere(&self, code: Code) -> Option<&Elsewhere> {
        self.g_elsewhere.get(&code)
    }

    pub fn foreign_g(&self, code: Code) -> Option<&str> {
        self.foreign_g.get(&code).map(String::as_str)
    }

    pub fn m_meaning(&self, code: u16) -> Option<&str> {
        self.m.get(&code).map(String::as_str)
    }

    /// Every M code the tables give a meaning, in order (for completion).
    pub fn m_codes(&self) -> Vec<(u16, &str)> {
        let mut codes: Vec<(u16, &str)> = self.m.iter().map(|(code, meaning)| (*code, meaning.as_str())).collect();
        codes.sort_unstable_by_key(|(code, _)| *code);
        codes
    }

    pub fn schema(&self, id: SchemaId) -> &Schema {
        &self.schemas[id.0 as usize]
    }

    pub fn function_index(&self, name: &[u8]) -> Option<usize> {
        self.expression.functions.iter().position(|f| f.as_bytes() == name)
    }

    pub fn g_infos(&self) -> &[GInfo] {
        &self.g_infos
    }
}

/// The tables of a configuration, compiled on first use.
pub fn tables(config: DialectConfig) -> &'static Tables {
    // Fanuc: three G-code systems on each of three controls; OSP: lathe and machining centre.
    static CACHE: [OnceLock<Tables>; 11] = [const { OnceLock::new() }; 11];
    let (slot, normalised) = match config.dialect {
        Dialect::Fanuc => {
            let system = match config.gcode_system {
                GCodeSystem::A => 0,
                GCodeSystem::B => 1,
                GCodeSystem::C => 2,
            };
            let control = match config.control {
                Control::Fanuc => 0,
                Control::Haas => 1,
                Control::Denford => 2,
            };
            let normalised = DialectConfig::new(Dialect::Fanuc, config.gcode_system, MachineKind::Lathe)
                .with_control(config.control);
            (control * 3 + system, normalised)
        }
        Dialect::Osp => {
            let slot = if config.machine_kind == MachineKind::Lathe { 9 } else { 10 };
            (slot, DialectConfig::new(Dialect::Osp, GCodeSystem::A, config.machine_kind))
        }
    };
    CACHE[slot].get_or_init(|| compile(normalised))
}

fn compile(config: DialectConfig) -> Tables {
    let text = match config.dialect {
        Dialect::Fanuc => FANUC_TOML,
        Dialect::Osp => OSP_TOML,
    };
    // The grammar files are part of the program, not input; `tests::tables_load` proves
    // every configuration compiles, so a failure here is a build defect.
    #[allow(clippy::expect_used)]
    let raw: RawDialect = toml::from_str(text).expect("grammar TOML is valid (tested)");

    let mut letters: [Option<AddressSpec>; 26] = Default::default();
    for (name, spec) in &raw.address {
        if let [letter] = name.as_bytes() {
            letters[(letter - b'A') as usize] = Some(spec.clone());
        }
    }
    let mut extended: Vec<(Address, AddressSpec)> = raw
        .extended
        .iter()
        .filter_map(|(name, spec)| name.parse::<Address>().ok().map(|a| (a, spec.clone())))
        .collect();
    let has_comma_words = !raw.comma.is_empty();
    extended.extend(
        raw.comma
            .iter()
            .filter_map(|(name, spec)| format!(",{name}").parse::<Address>().ok().map(|a| (a, spec.clone()))),
    );

    let scope_applies = |machine: Option<MachineScope>| {
        matches!(
            (machine, config.machine_kind),
            (None, _)
                | (Some(MachineScope::Lathe), MachineKind::Lathe)
                | (Some(MachineScope::Mc), MachineKind::MachiningCentre)
        )
    };
    let mut keywords: Vec<(String, KeywordInfo)> = raw
        .keywords
        .iter()
        .filter(|(_, info)| scope_applies(info.machine))
        .map(|(name, info)| (name.clone(), info.clone()))
        .collect();
    keywords.sort_by(|a, b| a.0.cmp(&b.0));

    let schema_names: Vec<&String> = raw.schema.keys().collect();
    let schemas: Vec<Schema> =
        raw.schema.iter().map(|(name, s)| Schema { name: name.clone(), forms: s.form.clone() }).collect();

    let code_for = |g: &RawG, system: GCodeSystem| -> Option<String> {
        if let Some(code) = &g.code {
            return Some(code.clone());
        }
        match system {
            GCodeSystem::A => g.a.clone(),
            GCodeSystem::B => g.b.clone(),
            GCodeSystem::C => g.c.clone(),
        }
    };

    let mut g_index = vec![0u16; Code::MAX as usize + 1];
    let mut g_infos = Vec::new();
    let mut g_elsewhere = HashMap::new();
    for g in &raw.g {
        let on_this_control = g.control.as_ref().is_none_or(|controls| controls.contains(&config.control));
        let mine = if config.dialect == Dialect::Fanuc {
            code_for(g, config.gcode_system).filter(|_| on_this_control)
        } else if scope_applies(g.machine) {
            g.code.clone()
        } else {
            None
        };
        match mine {
            Some(text) => {
                let Ok((_, code)) = parse_code(&text) else { continue };
                let schema = g
                    .schema
                    .as_ref()
                    .and_then(|s| schema_names.iter().position(|n| *n == s))
                    .map(|i| SchemaId(i as u16));
                g_infos.push(GInfo {
                    code,
                    group: g.group,
                    kind: g.kind,
                    schema,
                    meaning: g.meaning.clone(),
                    note: g.note.clone(),
                    function: g.function,
                    feed_and_speed: g.feed_and_speed,
                    drilling: g.drilling,
                });
                g_index[code.0 as usize] = g_infos.len() as u16;
            }
            None => {
                // Remember where else this function lives, for hints on foreign codes.
                // A code of another control is no code of this one in another system: its
                // hint is `[foreign_g]`'s.
                let others: Vec<(String, Place)> = if config.dialect == Dialect::Fanuc && !on_this_control {
                    Vec::new()
                } else if config.dialect == Dialect::Fanuc {
                    [GCodeSystem::A, GCodeSystem::B, GCodeSystem::C]
                        .into_iter()
                        .filter_map(|s| code_for(g, s).map(|c| (c, Place::GCodeSystem(s))))
                        .collect()
                } else {
                    let place = match g.machine {
                        Some(MachineScope::Mc) => Place::OspMachiningCentre,
                        _ => Place::OspLathe,
                    };
                    g.code.iter().map(|c| (c.clone(), place)).collect()
                };
                for (text, place) in others {
                    if let Ok((_, code)) = parse_code(&text) {
                        g_elsewhere.entry(code).or_insert(Elsewhere { meaning: g.meaning.clone(), place });
                    }
                }
            }
        }
    }
    // A code that this configuration has is not "elsewhere".
    g_elsewhere.retain(|code, _| g_index[code.0 as usize] == 0);

    let foreign_g = raw
        .foreign_g
        .iter()
        .filter_map(|(name, note)| parse_code(name).ok().map(|(_, code)| (code, note.clone())))
        .collect();
    let m = raw
        .m
        .iter()
        .filter_map(|(name, meaning)| parse_code(name).ok().map(|(_, code)| (code.major(), meaning.clone())))
        .collect();

    let mut code_for: HashMap<GFunction, Code> = HashMap::new();
    for g in &g_infos {
        if let Some(function) = g.function {
            let code = code_for.entry(function).or_insert(g.code);
            if g.code.0 < code.0 {
                *code = g.code;
            }
        }
    }
    Tables {
        config,
        title: raw.title,
        lexical: raw.lexical,
        expression: raw.expression,
        letters,
        extended,
        has_comma_words,
        machine_variables: raw.machine_variables,
        increment_input: raw.increment_input,
        thread_lead: raw.thread_lead,
        thread_move: raw.thread_move,
        lower_case: raw.control.get(config.control.name()).is_some_and(|rules| rules.lower_case),
        keywords,
        g_index,
        g_infos,
        code_for,
        g_elsewhere,
        foreign_g,
        m,
        m_functions: raw.m_functions,
        schemas,
    }
}

#[cfg(test)]
mod tests;
