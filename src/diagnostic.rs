//! The crate's one diagnostic type: a kind, a span and a severity.
//!
//! Every pass reports problems as [`Diagnostic`] values; none of them formats text for a
//! terminal. The code, message, label and hint are derived from the kind, in one arm per
//! kind (`text.rs`), so a test can match on the kind and a renderer can show the words. Rendering (codespan-reporting, JSON, plain text
//! for snapshots) lives in [`render`], the only module that imports codespan-reporting.

pub(crate) mod fix;
pub(crate) mod model_file;
pub mod render;
mod text;

use std::fmt;

use crate::source::{NotText, Span};

pub use fix::Fix;
pub use model_file::ModelProblem;
pub use text::Words;

/// How many diagnostics of a program are shown where a long list costs more than it helps:
/// a language-server publish (unless the editor says otherwise) and the commands other than
/// `check`, which lists them all. The first ones, and how many more there are, are what a
/// machinist can act on; a program read with the wrong settings can have one on every block.
pub const SHOWN_DIAGNOSTICS: usize = 200;

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    Note,
    Warning,
    Error,
}

impl Severity {
    pub fn as_str(self) -> &'static str {
        match self {
            Severity::Note => "note",
            Severity::Warning => "warning",
            Severity::Error => "error",
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    pub severity: Severity,
    pub kind: DiagnosticKind,
    /// The offending text; the primary label goes here.
    pub span: Span,
    /// Secondary labels, such as the blocks on the other side of a dialect conflict.
    pub related: Vec<(Span, String)>,
    /// How many more times the run found the same problem at the same place (a block in a
    /// loop, a subprogram called again): one diagnostic per block, with a count, so that
    /// neither output nor memory follows the number of repeats (`merge_repeats`).
    pub repeats: u32,
}

impl Diagnostic {
    pub fn error(kind: DiagnosticKind, span: Span) -> Diagnostic {
        Diagnostic { severity: Severity::Error, kind, span, related: Vec::new(), repeats: 0 }
    }

    pub fn warning(kind: DiagnosticKind, span: Span) -> Diagnostic {
        Diagnostic { severity: Severity::Warning, kind, span, related: Vec::new(), repeats: 0 }
    }

    pub fn note(kind: DiagnosticKind, span: Span) -> Diagnostic {
        Diagnostic { severity: Severity::Note, kind, span, related: Vec::new(), repeats: 0 }
    }

    pub fn with_related(mut self, span: Span, label: impl Into<String>) -> Diagnostic {
        self.related.push((span, label.into()));
        self
    }

    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    /// Its code, message, label and hint (`DiagnosticKind::words`).
    pub fn words(&self) -> Words {
        self.kind.words()
    }

    pub fn code(&self) -> &'static str {
        self.kind.code()
    }

    pub fn message(&self) -> String {
        self.kind.message()
    }

    pub fn label(&self) -> String {
        self.kind.label()
    }

    pub fn hint(&self) -> Option<String> {
        self.kind.hint()
    }

    /// What a renderer says of the repeats (`repeats`), when there are any.
    pub fn repeats_note(&self) -> Option<String> {
        let n = self.repeats;
        (n > 0).then(|| {
            format!(
                "found {n} more time{} as the run comes back to this place; shown once",
                if n == 1 { "" } else { "s" }
            )
        })
    }
}

/// Merge the diagnostics of `list` that repeat one before them (the same kind at the same
/// span, with the same severity) into that one, counting them in its `repeats`: the first
/// keeps its words and place, the rest go. Passes that run a block many times (the
/// interpreter in a loop, the toolpath's checks of every move) merge as they go, so that a
/// loop that leaves the travel four million times is one diagnostic, not four million.
pub fn merge_repeats(list: &mut Vec<Diagnostic>) {
    type Key = (Span, std::mem::Discriminant<DiagnosticKind>, Severity);
    let mut first: std::collections::HashMap<Key, usize> = std::collections::HashMap::new();
    let mut kept = 0;
    for k in 0..list.len() {
        let key = (list[k].span, std::mem::discriminant(&list[k].kind), list[k].severity);
        match first.get(&key) {
            Some(&at) => list[at].repeats = list[at].repeats.saturating_add(list[k].repeats.saturating_add(1)),
            None => {
                first.insert(key, kept);
                list.swap(kept, k);
                kept += 1;
            }
        }
    }
    list.truncate(kept);
}

/// A word the control counts (least increments, milliseconds, a sequence number, a count)
/// written with a decimal point: the facts of `IntegerExpected` and
/// `DecimalPointUnverified`.
#[derive(Debug, Clone, PartialEq)]
pub struct CountedWord {
    /// The command, as messages name it (`G76 (multiple threading cycle)`), and the address.
    pub command: String,
    pub address: String,
    /// The word as written (`P0.92`).
    pub written: String,
    /// What the word counts.
    pub unit: crate::dialect::IntegerUnit,
    /// The word meant and what it reads as (`P920`, `0.92 mm`), when it can be told
    /// (`dialect::roles::meant`).
    pub meant: Option<(String, String)>,
    /// The control whose rule this is (`control` setting), and another that takes the
    /// point, with the unit it reads the word in then (a Haas reads a dwell `P0.3` in
    /// seconds).
    pub control: &'static str,
    pub elsewhere: Option<(&'static str, &'static str)>,
}

/// What went wrong. Variants carry the facts their message needs, never preformatted text,
/// except for suggestions that quote repaired source.
#[derive(Debug, Clone, PartialEq)]
pub enum DiagnosticKind {
    /// A byte that no block may contain outside a comment.
    InvalidCharacter {
        found: char,
    },
    /// A byte that is not ASCII outside a comment (Shift-JIS, Latin-1, UTF-8 text).
    NonAsciiByte {
        byte: u8,
    },
    /// A lower-case letter outside a comment.
    LowerCaseLetter {
        found: char,
    },
    /// A NUL byte outside a comment.
    NulByte,
    /// Words (`roughing pass`, `[BILLET X40 Z100`) outside a comment: a note or a
    /// simulator's directive, not a block.
    TextOutsideComment {
        text: String,
    },
    /// A letter inside a number that is a misread digit (`X4l.`: `l` for `1`).
    LetterForDigit {
        found: char,
        digit: char,
    },
    /// A line before the tape's first `%` and any program text: a tape leader, which the
    /// control skips (`syntax.rs`).
    TapeLeader,
    /// A check the semantic pass leaves out because what it checks is in a block that does
    /// not parse (its parse error says why): `what` names it.
    DependsOnDamagedBlock {
        what: &'static str,
    },
    /// A line the parser took for a tape leader with no `%` after the leader: the control
    /// reads it as a block (`semantic/interpreter.rs`).
    LeaderWithoutTape,
    /// A file that is not a text program (`source::not_text`): one diagnostic, on its first
    /// control byte, instead of a parse.
    NotText {
        byte: u8,
        control_bytes: usize,
        sampled: usize,
        whole_file: bool,
        utf16: bool,
    },
    /// A program with no block the control runs (empty, or only blank lines, comments, tape
    /// marks and its name).
    EmptyProgram,
    /// Scanning or transfer damage inside a number, as in `F. }0` from the thesis' appendix;
    /// `text` is the damaged word.
    DamagedNumber {
        text: String,
    },
    /// An address with no value at all (`X` at the end of a block, `X SDIA-3`).
    MissingValue {
        address: String,
        suggestion: Option<String>,
    },
    /// A sign or decimal point with no digits (`X.`, `Z-.`).
    MissingDigits {
        address: String,
    },
    /// The letter `O` where a digit belongs (`G1O`, `XO.5`).
    LetterOForZero {
        suggestion: String,
    },
    /// A comma between the digits of a number (`X20,5`): a decimal comma for the point.
    DecimalComma {
        suggestion: String,
    },
    /// The digit `0` where the letter `O` belongs (`CALL 01000`).
    ZeroForLetterO {
        suggestion: String,
    },
    /// More digits than the address takes, or more than an exact value can hold.
    NumberOutOfRange {
        address: String,
        digits: usize,
        max_digits: usize,
    },
    /// A number with no address letter before it (`28 U0 W0`).
    NumberWithoutAddress {
        suggestion: Option<String>,
    },
    /// A G-code the dialect does not have.
    UnknownGCode {
        code: String,
        dialect: &'static str,
        hint: Option<String>,
    },
    /// A G or M code written with a fraction the dialect does not use (`G1.25`).
    MalformedCode {
        address: char,
    },
    /// An OSP machining-centre code in a lathe program.
    MachiningCentreCode {
        code: String,
        meaning: String,
    },
    /// A construct of the other dialect (`#1` on OSP, `XA=` or `V1` on Fanuc, `$` on Fanuc).
    ForeignWord {
        what: String,
        dialect: &'static str,
        belongs_to: &'static str,
    },
    /// A name that is no OSP keyword and is not assigned (`BHX`).
    UnknownStatement {
        name: String,
    },
    /// An OSP extended address used without `=`.
    ExtendedAddressNeedsEquals {
        name: String,
    },
    /// OSP: the sequence name runs into the next word (`N100G00`).
    MissingSpaceAfterSequence {
        name: String,
    },
    /// A sequence name longer than the dialect allows.
    SequenceTooLong {
        max: usize,
    },
    /// `N` with no usable name after it.
    MissingSequenceName,
    /// A sequence number after the start of a Fanuc block.
    MisplacedSequence,
    /// An invalid program name (`O` block).
    InvalidProgramName {
        max: usize,
    },
    /// OSP: an `O` block that holds more than the program name.
    ProgramNameNotAlone,
    /// A `(` comment with no `)` before the end of the block.
    UnclosedComment,
    /// A `[` with no matching `]`.
    UnclosedBracket,
    /// A `]` with no `[` before it.
    UnmatchedBracket,
    /// Brackets nested deeper than the parser's bound.
    ExpressionTooDeep {
        max: usize,
    },
    /// An expression that does not parse (`[1+]`).
    MalformedExpression {
        expected: &'static str,
    },
    /// A block-delete slash where the dialect does not allow one.
    MisplacedBlockDelete,
    /// A word a command does not take (`G70 U1`).
    WordNotAllowed {
        command: String,
        address: String,
        allowed: String,
    },
    /// A word a command needs.
    MissingWord {
        command: String,
        words: String,
    },
    /// A decimal point in a word that counts least increments, milliseconds or passes, or
    /// names a sequence (`P2.`), which the control refuses.
    IntegerExpected(Box<CountedWord>),
    /// A word that counts least increments written with a decimal point, which some controls
    /// take (as a length) and others may refuse: not verified for this one (`G83 Q3.`).
    DecimalPointUnverified {
        /// The word, and its `meant`: the word without a point that reads the same
        /// everywhere.
        word: Box<CountedWord>,
        /// The reading with the point (`3 mm`).
        reading: String,
    },
    /// A length or feed word without a decimal point that counts least increments (increment
    /// input) and reads implausibly small in its place (`X32` is 0.032 mm).
    MissingDecimalPoint {
        /// The word as written (`X32`).
        word: String,
        /// Its reading here, and its reading with a point, with their unit (`0.032 mm`,
        /// `32 mm`).
        readings: Box<(String, String)>,
    },
    /// The settings do not give `decimal_input`, and `count` words without a decimal point
    /// would read implausibly if the control counted least increments: the first of them,
    /// read as written (calculator input, in force) and as increments.
    DecimalInputUnset {
        count: usize,
        word: String,
        /// Its reading as written and in least increments.
        readings: Box<(String, String)>,
    },
    /// An error of a profile or a corner that a word read without its decimal point explains:
    /// the error, said at the word.
    MissingPointCauses {
        cause: Box<DiagnosticKind>,
        word: String,
        /// Its reading here, and with a point.
        readings: Box<(String, String)>,
    },
    /// How an OSP longitudinal thread cycle's height reads: a diameter, so the passes cut
    /// half of it deep (said by `expand` at the call).
    ThreadHeightAsDiameter {
        word: String,
        depth_mm: f64,
        passes: usize,
    },
    /// An OSP thread height (a diameter) nearer the radial height of the thread's pitch
    /// than its height as a diameter: written as Fanuc's radial `G76` height.
    ThreadHeightRadial {
        word: String,
        /// The depth it cuts, and the pitch, mm.
        depth_mm: f64,
        pitch_mm: f64,
        /// The word with the height doubled (`H1.84`).
        meant: Option<String>,
    },
    /// Two cycle or motion commands that cannot share a block.
    ConflictingCommands {
        first: String,
        second: String,
    },
    /// The same address twice in one block.
    DuplicateWord {
        address: String,
    },
    /// An axis given both as a position and as a distance (`X` and `U`, `Z` and `W`) in one
    /// Fanuc block.
    AxisGivenTwice {
        position: String,
        distance: String,
        axis: char,
    },
    /// `;` in an OSP program, where it is not a comment.
    SemicolonInOsp,
    /// A UTF-8 byte-order mark at the start of the file.
    ByteOrderMark,
    /// Two G-codes of one modal group in one block; the control keeps the last.
    SameModalGroup {
        first: String,
        second: String,
    },
    /// Auto-detection found evidence for both dialects.
    DialectConflict {
        chosen: &'static str,
        other: &'static str,
    },
    /// The OSP program is for a machining centre; lathe cycles are not applied.
    MachiningCentreProgram,
    /// The source is too large to address with 32-bit offsets.
    SourceTooLarge,
    /// A machine model file or one of its axis tables that does not read, or holds a value
    /// out of range (`model_file.rs` has the words).
    ModelFile(Box<ModelProblem>),
    /// A header or row of a measurement or log (CSV) that does not read: what is wrong, and
    /// the label on the text it is about.
    DataInvalid {
        message: String,
        label: &'static str,
        hint: Option<String>,
    },
    /// A block with more words than the AST holds per block.
    TooManyWords {
        max: usize,
    },
    /// An OSP `$` continuation line with no block before it.
    OrphanContinuation,
    /// A move whose coordinates, feed or time are not finite numbers.
    NonFiniteMove,
    /// An arc whose end point is not on the circle through its start.
    ArcEndOffCircle {
        start_radius: f64,
        end_radius: f64,
    },
    /// A move that ends before it starts, or before the previous move ended.
    TimeGoesBack,
    /// A rapid move whose tool (its nose and the insert behind it) passes through material
    /// that is still there: a crash. `depth_mm` is how far into the material it goes.
    /// `assumed` when the stock was assumed (no `[stock]`), which makes it one note for the
    /// run at the deepest such rapid, holding how many other blocks do it too.
    RapidIntoStock {
        depth_mm: f64,
        assumed: Option<u32>,
    },
    /// A feed move that engages more material across its direction than the tool's
    /// `max_depth`; `assumed` as for [`DiagnosticKind::RapidIntoStock`].
    CutTooDeep {
        depth_mm: f64,
        max_mm: f64,
        assumed: Option<u32>,
    },
    /// The part model stopped at this block: the program asks more work of it than its
    /// bound (`rays` ray visits in a run, `stamps` thread forms in a move); the moves after
    /// it are not checked against the stock.
    PartModelStopped {
        rays: u64,
        stamps: u64,
    },
    /// A point of the toolpath outside the machine's travel.
    OutsideTravel {
        x_mm: f64,
        z_mm: f64,
    },
    /// The tool nose cannot follow the contour under nose-radius compensation: a concave arc
    /// tighter than the nose, or a groove or step too small for it.
    NoseDoesNotFit {
        radius_mm: f64,
        reason: &'static str,
    },
    /// Nose-radius compensation switched on (`G41`/`G42`) or off (`G40`) in an arc block;
    /// the arc is made a straight move.
    CompensationOnArc {
        cancel: bool,
    },
    /// `G28` and machine coordinates need the home position from the machine settings.
    HomeUnknown,
    /// No home in the settings, so the toolpath starts at the first programmed point.
    UnknownStartPosition,
    /// A LAP contour with no `G80` after it.
    LapContourNotClosed,
    /// A LAP call (`G85`-`G88`) names no `G81`/`G82` contour block.
    LapContourMissing {
        name: String,
    },
    /// A LAP contour with no move after its approach block.
    LapContourEmpty,
    /// A LAP roughing contour that turns back along the cutting direction.
    LapContourNotMonotonic {
        axis: char,
    },
    /// The AP start point lies inside the contour plus its allowance.
    LapStartInsideContour,
    /// A LAP call word with a value the control rejects (`D0`, `U-1`, too many passes).
    LapWordOutOfRange {
        word: String,
        value: f64,
        rule: &'static str,
    },
    /// `G84` condition-change points that do not follow the cut (outside: Xs > XA > XB).
    LapConditionOrder {
        word: String,
        value: f64,
        before: String,
        before_value: f64,
        outside: bool,
    },
    /// A `G84` condition-change word where it does not apply (`ZA=` on a `G81` contour).
    LapConditionMisplaced {
        word: String,
        reason: &'static str,
    },
    /// `S`, `T` or `M` in a LAP call block, which the control rejects.
    LapCallWord {
        command: String,
        address: String,
    },
    /// `Q` names a block before `P`.
    ProfileBackwards,
    /// A cycle the simulation does not expand yet.
    CycleNotSimulated {
        code: String,
    },
    /// `expand` leaves a cycle as it is: its moves have no plain-block form in this dialect
    /// (on OSP: thread moves that are not single-pass `G33` passes).
    NotExpandable {
        reason: &'static str,
    },
    /// Haas `G87`/`G88`: the operator takes the tool out of the hole by hand.
    ManualRetract,
    /// A drilling cycle's peck depth (`Q`, Haas `I`) of zero or less.
    DrillPeckNotPositive,
    /// `compensate`: the correction of a point of this block is larger than `--max-shift`.
    CorrectionTooLarge {
        shift_mm: f64,
        max_mm: f64,
    },
    /// `compensate`: a corrected point of this block lies outside the machine's travel.
    CompensatedOutsideTravel {
        x_mm: f64,
        z_mm: f64,
    },
    /// `compensate`: the block's motion must change but cannot be written back in place.
    CannotRewriteBlock {
        reason: &'static str,
    },
    /// `compensate`: a cycle whose motion changes can neither carry the correction in its
    /// own words nor be written out (`reason`), so it stays as programmed and its moves are
    /// not compensated.
    CycleNotCompensated {
        reason: &'static str,
    },
    /// `compensate`: the program carries a provenance comment, so it is a compensated
    /// program already; `model` is the model it names, when the comment reads.
    AlreadyCompensated {
        model: Option<String>,
    },
    /// A move that needs more samples than compensation holds for one move
    /// (`error_model::sampling::MAX_SAMPLES_PER_MOVE`) at the model's spacing.
    MoveNeedsTooManySamples {
        samples: usize,
        max: usize,
    },
    /// `plot`: the program's path needs more samples in all than a plot holds
    /// (`error_model::sampling::MAX_SAMPLES_PER_MOVE`, the most compensation holds at once),
    /// on the block whose move passes the bound.
    PathNeedsTooManySamples {
        samples: usize,
        max: usize,
    },
    /// The program runs off the end of its text, which ends in the middle of a block, with
    /// no program end: the text was cut (`Lowered::cut_off`).
    ProgramCut,
    /// `compensate`: the program it would write, read back and predicted on the model as
    /// `verify` predicts it, deviates from the nominal part here by more than `verify`
    /// allows.
    CompensationFailsCheck {
        deviation_mm: f64,
        bound_mm: f64,
        /// The tolerance the program was compensated to, mm.
        tolerance_mm: f64,
        /// The other `--strategy` whose program comes closest, and the largest deviation
        /// it reaches, mm (`None` where none was tried or none reads back).
        other_strategy: Option<(&'static str, f64)>,
    },
    /// `compensate`: the program it would write, read back and predicted on the model as
    /// `verify` predicts it, cuts this thread with a lead that errs over the thread's length
    /// by more than `verify` allows (`compensation::verify::lead`).
    ThreadLeadFailsCheck {
        lead_error_mm: f64,
        bound_mm: f64,
    },
    /// `compensate`: the program it would write cuts with other feed or spindle words than
    /// the original (a defect of turnpass, never of the program).
    CompensationChangesFeed,
    /// `compensate`: the program it would write loses this word of the original (an M code,
    /// T, comment, block-delete slash, program name or spindle speed), or has it out of
    /// order, as `verify` checks (a defect of turnpass, never of the program).
    CompensationLosesWord {
        word: String,
    },
    /// `compensate`: an M code or T word inside a profile that only a roughing cycle reads
    /// (no finishing cycle runs it): the control never runs it, and with the cycle written
    /// out no block is left to keep it on.
    ProfileWordNotRun {
        word: String,
    },
    /// `compensate`: the program it would write does not read back cleanly: a defect of
    /// turnpass, or (`nose_has_no_room`) a contour the corrections moved so that the tool
    /// nose no longer fits it under nose-radius compensation.
    CompensationUnreadable {
        problem: String,
        nose_has_no_room: bool,
    },
    /// A roughing cycle with no depth of cut (no first block, no `D`, or zero).
    CycleNeedsDepth,
    /// A roughing cycle's depth of cut below the least increment (program units): the
    /// control reads it as zero.
    DepthBelowIncrement {
        depth: f64,
        increment: f64,
    },
    /// A cycle whose profile has no moves.
    EmptyProfile,
    /// A roughing profile that turns back along the cutting direction (both types reject it).
    ProfileReverses {
        axis: char,
    },
    /// A Type I roughing profile that is not monotonic across the cut.
    ProfileNotMonotonic {
        axis: char,
    },
    /// A `G71`/`G72` whose profile fails because its start point lies on the other side of
    /// it than the sign of the allowance across the passes asks for (`U-1`, an inside
    /// allowance, from a start point outside the part): read from the start point's side,
    /// the profile turns back. From a start point on the allowance's side it would not.
    StartOnWrongSide {
        /// The start point as programmed (X as written, a diameter on a diameter lathe).
        x: f64,
        z: f64,
        /// The axis across the passes (`X` for `G71`, `Z` for `G72`), the allowance word
        /// along it (`U` or `W`) and that word's value.
        axis: char,
        address: char,
        allowance: f64,
        /// The profile's smallest value on that axis when the allowance is negative, its
        /// largest when positive: where the start point must lie beyond, allowance added.
        extreme: f64,
    },
    /// A `G73` with no number of passes (`R` of its first block, or `D`), or fewer than one.
    CycleNeedsDivisions,
    /// A `G74`/`G75` groove wider than one plunge with no step between plunges.
    GrooveStepMissing {
        axis: char,
    },
    /// A cycle whose parameters ask for more passes or pecks than turnpass simulates.
    CycleTooManyPasses {
        passes: u64,
        max: u64,
    },
    /// A `G76` thread height smaller than its first depth of cut.
    ThreadHeightBelowFirstDepth {
        height_mm: f64,
        first_depth_mm: f64,
    },
    /// A thread lead of zero or less.
    ThreadLeadNotPositive,
    /// A thread cycle whose thread has no length along its axis.
    ThreadOfNoLength,
    /// A variable-lead thread whose lead shrinks to nothing before its end.
    LeadShrinksToNothing,
    /// `G76 P(m)(r)(a)` digits, or a Haas `P`/`A`, outside what the control takes.
    ThreadParametersInvalid {
        word: String,
    },
    /// `P`/`Q` name a sequence number no block has.
    MissingSequence {
        number: String,
    },
    /// `P`/`Q` name a sequence number several blocks have.
    DuplicateSequence {
        number: String,
        count: usize,
    },
    /// More executed blocks or moves than the bounds: a loop that does not end. Reported
    /// at the jump back taken last, with how often it was taken, when there is one.
    RunawayProgram {
        blocks: u64,
        moves: usize,
        passes: Option<u64>,
    },
    /// A jump back that finds the run as it was at its last take (the same variables,
    /// modes and position): the loop it closes runs forever.
    EndlessLoop {
        passes: u64,
    },
    /// `WHILE … DOn` with no `ENDn`.
    UnmatchedLoop {
        number: u32,
    },
    /// A jump to a label no block has.
    MissingLabel {
        name: String,
    },
    /// A call of a program the file does not hold: a subprogram in the control's memory
    /// (a warning; the call's moves are missing from the toolpath, and the run goes on).
    MissingProgram {
        name: String,
    },
    /// Subprogram calls nested too deep.
    CallsTooDeep {
        max: usize,
    },
    /// A feed move with no feed (or no spindle speed under feed per revolution).
    NoFeed,
    /// An arc radius shorter than half the chord.
    ArcRadiusTooSmall {
        radius_mm: f64,
        half_chord_mm: f64,
    },
    /// An arc with neither a centre nor a radius.
    ArcWithoutCentre,
    /// An `I`/`K` centre whose distance to the end differs from its distance to the start.
    ArcCentreMismatch {
        start_radius_mm: f64,
        end_radius_mm: f64,
    },
    /// An automatic corner with no straight move after it.
    CornerWithoutNextLine,
    /// An automatic corner larger than the lines it joins.
    CornerDoesNotFit {
        size_mm: f64,
        /// The word that gives the size (`L`, `,C`, `,R`).
        word: &'static str,
    },
    /// A block a finishing profile may not hold.
    NotAllowedInProfile,
    /// OSP compound thread, infeed pattern 1 (`M73`, a constant depth `D` per pass): the
    /// depth to rough, `H − U`, is less than one pass, which the control rejects. Values in
    /// program units, as written (diameters).
    ThreadRoughDepthBelowFirstCut {
        rough_depth: f64,
        first_depth: f64,
    },
    /// OSP compound thread: the finishing allowance `U` (`W`) is larger than the thread
    /// height `H`, which the control rejects. Program units.
    ThreadAllowanceOverHeight {
        height: f64,
        allowance: f64,
    },
    /// OSP thread infeed (tool) angle `B` outside 0 ≤ B < 180 degrees.
    InfeedAngleOutOfRange {
        angle: f64,
    },
    /// OSP multi-pass thread with a first depth `D` or a height `H` that is not positive.
    ThreadDepthNotPositive {
        address: char,
    },
    /// A cycle that would cut more passes than the simulation runs (bounded work).
    TooManyPasses {
        passes: usize,
        max: usize,
    },
    /// OSP infeed pattern 3 where the control chooses its own pass depths (`D² < H² − (H − U)²`,
    /// which the manual leaves undocumented); the simulation uses the `D·√n` rule.
    InfeedPatternApproximated,
    /// An OSP grooving or face-cutting cycle whose end lies off the start line (`X` or `Z`
    /// differs from where the tool is) with no shift word to step there.
    CycleNeedsShift {
        shift: char,
        axis: char,
    },
    /// An OSP `G88` thread contour with an arc, or a rapid after its first thread element.
    ThreadContourNotStraight,
    /// `#[expr]` with a value that is no variable number.
    BadVariableNumber {
        value: f64,
    },
    /// An assignment to something that is not a variable.
    NotAVariable,
    /// A system variable the simulation has no value for.
    SystemVariableUnknown {
        name: String,
    },
    /// A variable read before it is set.
    UndefinedVariable {
        name: String,
    },
    /// A common variable the machine keeps (Fanuc `#500`–`#999`, OSP `V1`…) read before the
    /// program sets it and with no value in the settings: its value comes from the machine.
    MachineVariableUnknown {
        name: String,
    },
    /// Constant surface speed with no `G50`/`G92` clamp: the spindle speed is limited only by
    /// the machine's maximum (from the settings, or the documented default).
    SurfaceSpeedUnclamped {
        max_rpm: f64,
        assumed: bool,
    },
    /// A thread cut under constant surface speed: the spindle speed changes with the
    /// diameter, which the control's thread start does not follow on every pass.
    ThreadUnderSurfaceSpeed,
    /// A feed far outside what its mode makes plausible (`G98 F0.05`: 0.05 mm/min).
    ImplausibleFeed {
        feed: f64,
        per_revolution: bool,
        inch: bool,
    },
    /// A repeat of a `G92` thread whose call shifted its start angle (`Q`) writes none:
    /// the angle is the block's own, so this pass starts at the spindle's index.
    ThreadStartAngleNotKept {
        degrees: f64,
    },
    /// Fanuc system A: `G90` (`G94`) with no `X`/`Z` only selects the single cycle.
    CycleSelectedAlone {
        code: String,
    },
    /// A drilling cycle along X (a side hole, live tool): its motion is not in the XZ
    /// plane of a turned part, and the toolpath leaves it out.
    CycleOutOfPlane {
        code: String,
    },
    DivisionByZero,
    /// A function outside its domain (`SQRT[-1]`).
    FunctionDomain {
        function: String,
        argument: f64,
    },
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}[{}]: {}", self.severity.as_str(), self.code(), self.message())
    }
}

impl NotText {
    /// The one diagnostic of such a file, on its first control byte.
    pub fn diagnostic(&self) -> Diagnostic {
        let kind = DiagnosticKind::NotText {
            byte: self.byte,
            control_bytes: self.control_bytes,
            sampled: self.sampled,
            whole_file: self.whole_file,
            utf16: self.utf16,
        };
        Diagnostic::error(kind, Span::new(self.offset, self.offset + 1))
    }
}
