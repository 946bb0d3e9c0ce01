//! The crate's one diagnostic type: a kind, a span and a severity.
//!
//! Every pass reports problems as [`Diagnostic`] values; none of them formats text for a
//! terminal. Messages, labels and hints are derived from the kind, so a test can match on the
//! kind and a renderer can show the words. Rendering (codespan-reporting, JSON, plain text
//! for snapshots) lives in [`render`], the only module that imports codespan-reporting.

pub mod render;

use std::fmt;

use crate::source::Span;

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
}

impl Diagnostic {
    pub fn error(kind: DiagnosticKind, span: Span) -> Diagnostic {
        Diagnostic { severity: Severity::Error, kind, span, related: Vec::new() }
    }

    pub fn warning(kind: DiagnosticKind, span: Span) -> Diagnostic {
        Diagnostic { severity: Severity::Warning, kind, span, related: Vec::new() }
    }

    pub fn note(kind: DiagnosticKind, span: Span) -> Diagnostic {
        Diagnostic { severity: Severity::Note, kind, span, related: Vec::new() }
    }

    pub fn with_related(mut self, span: Span, label: impl Into<String>) -> Diagnostic {
        self.related.push((span, label.into()));
        self
    }

    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
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
}

/// What went wrong. Variants carry the facts their message needs, never preformatted text,
/// except for suggestions that quote repaired source.
#[derive(Debug, Clone, PartialEq)]
pub enum DiagnosticKind {
    /// A byte that no block may contain outside a comment.
    InvalidCharacter { found: char },
    /// A byte that is not ASCII outside a comment (Shift-JIS, Latin-1, UTF-8 text).
    NonAsciiByte { byte: u8 },
    /// A lower-case letter outside a comment.
    LowerCaseLetter { found: char },
    /// A NUL byte outside a comment.
    NulByte,
    /// Scanning or transfer damage inside a number, as in `F. }0` from the thesis' appendix;
    /// `text` is the damaged word.
    DamagedNumber { text: String },
    /// An address with no value at all (`X` at the end of a block, `X SDIA-3`).
    MissingValue { address: String, suggestion: Option<String> },
    /// A sign or decimal point with no digits (`X.`, `Z-.`).
    MissingDigits { address: String },
    /// The letter `O` where a digit belongs (`G1O`, `XO.5`).
    LetterOForZero { suggestion: String },
    /// The digit `0` where the letter `O` belongs (`CALL 01000`).
    ZeroForLetterO { suggestion: String },
    /// More digits than the address takes, or more than an exact value can hold.
    NumberOutOfRange { address: String, digits: usize, max_digits: usize },
    /// A number with no address letter before it (`28 U0 W0`).
    NumberWithoutAddress { suggestion: Option<String> },
    /// A G-code the dialect does not have.
    UnknownGCode { code: String, dialect: &'static str, hint: Option<String> },
    /// A G or M code written with a fraction the dialect does not use (`G1.25`).
    MalformedCode { address: char },
    /// An OSP machining-centre code in a lathe program.
    MachiningCentreCode { code: String, meaning: String },
    /// A construct of the other dialect (`#1` on OSP, `XA=` or `V1` on Fanuc, `$` on Fanuc).
    ForeignWord { what: String, dialect: &'static str, belongs_to: &'static str },
    /// A name that is no OSP keyword and is not assigned (`BHX`).
    UnknownStatement { name: String },
    /// An OSP extended address used without `=`.
    ExtendedAddressNeedsEquals { name: String },
    /// OSP: the sequence name runs into the next word (`N100G00`).
    MissingSpaceAfterSequence { name: String },
    /// A sequence name longer than the dialect allows.
    SequenceTooLong { max: usize },
    /// `N` with no usable name after it.
    MissingSequenceName,
    /// A sequence number after the start of a Fanuc block.
    MisplacedSequence,
    /// An invalid program name (`O` block).
    InvalidProgramName { max: usize },
    /// OSP: an `O` block that holds more than the program name.
    ProgramNameNotAlone,
    /// A `(` comment with no `)` before the end of the block.
    UnclosedComment,
    /// A `[` with no matching `]`.
    UnclosedBracket,
    /// A `]` with no `[` before it.
    UnmatchedBracket,
    /// Brackets nested deeper than the parser's bound.
    ExpressionTooDeep { max: usize },
    /// An expression that does not parse (`[1+]`).
    MalformedExpression { expected: &'static str },
    /// A block-delete slash where the dialect does not allow one.
    MisplacedBlockDelete,
    /// A word a command does not take (`G70 U1`).
    WordNotAllowed { command: String, address: String, allowed: String },
    /// A word a command needs.
    MissingWord { command: String, words: String },
    /// A decimal point in a word that counts least increments or names a sequence (`P2.`).
    IntegerExpected { command: String, address: String },
    /// Two cycle or motion commands that cannot share a block.
    ConflictingCommands { first: String, second: String },
    /// The same address twice in one block.
    DuplicateWord { address: String },
    /// `;` in an OSP program, where it is not a comment.
    SemicolonInOsp,
    /// A UTF-8 byte-order mark at the start of the file.
    ByteOrderMark,
    /// Two G-codes of one modal group in one block; the control keeps the last.
    SameModalGroup { first: String, second: String },
    /// Auto-detection found evidence for both dialects.
    DialectConflict { chosen: &'static str, other: &'static str },
    /// The OSP program is for a machining centre; lathe cycles are not applied.
    MachiningCentreProgram,
    /// The source is too large to address with 32-bit offsets.
    SourceTooLarge,
    /// A block with more words than the AST holds per block.
    TooManyWords { max: usize },
    /// An OSP `$` continuation line with no block before it.
    OrphanContinuation,
    /// A move whose coordinates, feed or time are not finite numbers.
    NonFiniteMove,
    /// An arc whose end point is not on the circle through its start.
    ArcEndOffCircle { start_radius: f64, end_radius: f64 },
    /// A move that ends before it starts, or before the previous move ended.
    TimeGoesBack,
    /// A point of the toolpath outside the machine's travel.
    OutsideTravel { x_mm: f64, z_mm: f64 },
}

impl DiagnosticKind {
    /// A stable identifier for tools and JSON output.
    pub fn code(&self) -> &'static str {
        use DiagnosticKind::*;
        match self {
            InvalidCharacter { .. } => "invalid-character",
            NonAsciiByte { .. } => "non-ascii-byte",
            LowerCaseLetter { .. } => "lower-case-letter",
            NulByte => "nul-byte",
            DamagedNumber { .. } => "damaged-number",
            MissingValue { .. } => "missing-value",
            MissingDigits { .. } => "missing-digits",
            LetterOForZero { .. } => "letter-o-for-zero",
            ZeroForLetterO { .. } => "zero-for-letter-o",
            NumberOutOfRange { .. } => "number-out-of-range",
            NumberWithoutAddress { .. } => "number-without-address",
            UnknownGCode { .. } => "unknown-g-code",
            MalformedCode { .. } => "malformed-code",
            MachiningCentreCode { .. } => "machining-centre-code",
            ForeignWord { .. } => "foreign-word",
            UnknownStatement { .. } => "unknown-statement",
            ExtendedAddressNeedsEquals { .. } => "extended-address-needs-equals",
            MissingSpaceAfterSequence { .. } => "missing-space-after-sequence",
            SequenceTooLong { .. } => "sequence-too-long",
            MissingSequenceName => "missing-sequence-name",
            MisplacedSequence => "misplaced-sequence",
            InvalidProgramName { .. } => "invalid-program-name",
            ProgramNameNotAlone => "program-name-not-alone",
            UnclosedComment => "unclosed-comment",
            UnclosedBracket => "unclosed-bracket",
            UnmatchedBracket => "unmatched-bracket",
            ExpressionTooDeep { .. } => "expression-too-deep",
            MalformedExpression { .. } => "malformed-expression",
            MisplacedBlockDelete => "misplaced-block-delete",
            WordNotAllowed { .. } => "word-not-allowed",
            MissingWord { .. } => "missing-word",
            IntegerExpected { .. } => "integer-expected",
            ConflictingCommands { .. } => "conflicting-commands",
            DuplicateWord { .. } => "duplicate-word",
            SemicolonInOsp => "semicolon-in-osp",
            ByteOrderMark => "byte-order-mark",
            SameModalGroup { .. } => "same-modal-group",
            DialectConflict { .. } => "dialect-conflict",
            MachiningCentreProgram => "machining-centre-program",
            SourceTooLarge => "source-too-large",
            TooManyWords { .. } => "too-many-words",
            OrphanContinuation => "orphan-continuation",
            NonFiniteMove => "non-finite-move",
            ArcEndOffCircle { .. } => "arc-end-off-circle",
            TimeGoesBack => "time-goes-back",
            OutsideTravel { .. } => "outside-travel",
        }
    }

    pub fn message(&self) -> String {
        use DiagnosticKind::*;
        match self {
            InvalidCharacter { found } => {
                format!("`{}` is not a character a block may contain", found.escape_debug())
            }
            NonAsciiByte { byte } => format!("byte 0x{byte:02X} is not ASCII and is outside a comment"),
            LowerCaseLetter { found } => format!("lower-case `{found}` outside a comment"),
            NulByte => "NUL byte outside a comment".to_string(),
            DamagedNumber { text } => format!("the value in `{text}` is damaged"),
            MissingValue { address, .. } => format!("`{address}` has no value"),
            MissingDigits { address } => format!("the value of `{address}` has no digits"),
            LetterOForZero { .. } => "letter `O` where a digit belongs".to_string(),
            ZeroForLetterO { .. } => "digit `0` where the letter `O` of a program name belongs".to_string(),
            NumberOutOfRange { address, digits, max_digits } => {
                format!("`{address}` has {digits} significant digits; it takes at most {max_digits}")
            }
            NumberWithoutAddress { .. } => "a number with no address letter before it".to_string(),
            UnknownGCode { code, dialect, .. } => format!("{code} is not a G-code of the {dialect} dialect"),
            MalformedCode { address } => format!("malformed `{address}` code"),
            MachiningCentreCode { code, meaning } => {
                format!("{code} ({meaning}) is an OSP machining-centre code, not a lathe code")
            }
            ForeignWord { what, dialect, belongs_to } => {
                format!("{what} belongs to the {belongs_to} dialect; this program is read as {dialect}")
            }
            UnknownStatement { name } => format!("`{name}` is not an OSP statement or address"),
            ExtendedAddressNeedsEquals { name } => format!("extended address `{name}` needs `=`"),
            MissingSpaceAfterSequence { name } => {
                format!("sequence name `{name}` runs into the next word")
            }
            SequenceTooLong { max } => format!("sequence name longer than {max} characters"),
            MissingSequenceName => "`N` with no sequence name".to_string(),
            MisplacedSequence => "sequence number after the start of the block".to_string(),
            InvalidProgramName { max } => format!("invalid program name (`O` and up to {max} characters)"),
            ProgramNameNotAlone => "the program-name block holds other words".to_string(),
            UnclosedComment => "comment not closed before the end of the block".to_string(),
            UnclosedBracket => "`[` not closed before the end of the block".to_string(),
            UnmatchedBracket => "`]` with no `[` before it".to_string(),
            ExpressionTooDeep { max } => format!("brackets nested more than {max} deep"),
            MalformedExpression { expected } => format!("malformed expression: expected {expected}"),
            MisplacedBlockDelete => "block delete `/` in the middle of a block".to_string(),
            WordNotAllowed { command, address, .. } => format!("{command} does not take `{address}`"),
            MissingWord { command, words } => format!("{command} needs {words}"),
            IntegerExpected { command, address } => {
                format!("`{address}` in {command} takes an integer with no decimal point")
            }
            ConflictingCommands { first, second } => format!("{first} and {second} cannot share a block"),
            DuplicateWord { address } => format!("`{address}` appears twice in this block"),
            SemicolonInOsp => "`;` is not a comment on Okuma OSP".to_string(),
            ByteOrderMark => "the file starts with a byte-order mark".to_string(),
            SameModalGroup { first, second } => {
                format!("{first} and {second} are in the same modal group; the control keeps {second}")
            }
            DialectConflict { chosen, other } => {
                format!("the program shows features of both dialects; reading it as {chosen}, not {other}")
            }
            MachiningCentreProgram => "this is an OSP machining-centre program; only its syntax is checked".to_string(),
            SourceTooLarge => "the program is 4 GiB or larger".to_string(),
            TooManyWords { max } => format!("the block has more than {max} words"),
            OrphanContinuation => "continuation line with no block before it".to_string(),
            NonFiniteMove => "a move of this block has no finite position, feed or time".to_string(),
            ArcEndOffCircle { start_radius, end_radius } => format!(
                "the arc's end is not on its circle: radius {start_radius:.4} mm at the start, {end_radius:.4} mm at the end"
            ),
            TimeGoesBack => "a move of this block ends before it starts".to_string(),
            OutsideTravel { x_mm, z_mm } => {
                format!("the tool leaves the machine's travel at X{:.3} Z{z_mm:.3} (diameter, mm)", 2.0 * x_mm)
            }
        }
    }

    /// The short text under the primary label.
    pub fn label(&self) -> String {
        use DiagnosticKind::*;
        match self {
            InvalidCharacter { .. } | NonAsciiByte { .. } | NulByte | LowerCaseLetter { .. } => {
                "not valid here".to_string()
            }
            DamagedNumber { .. } => "damaged value".to_string(),
            MissingValue { .. } => "no value".to_string(),
            MissingDigits { .. } => "no digits".to_string(),
            LetterOForZero { .. } => "letter O".to_string(),
            ZeroForLetterO { .. } => "digit 0".to_string(),
            NumberOutOfRange { .. } => "too many digits".to_string(),
            NumberWithoutAddress { .. } => "no address".to_string(),
            UnknownGCode { .. } => "unknown G-code".to_string(),
            MalformedCode { .. } => "malformed code".to_string(),
            MachiningCentreCode { .. } => "machining-centre code".to_string(),
            ForeignWord { belongs_to, .. } => format!("{belongs_to} syntax"),
            UnknownStatement { .. } => "unknown name".to_string(),
            ExtendedAddressNeedsEquals { .. } => "`=` missing".to_string(),
            MissingSpaceAfterSequence { .. } => "space needed here".to_string(),
            SequenceTooLong { .. } => "too long".to_string(),
            MissingSequenceName => "no name".to_string(),
            MisplacedSequence => "sequence number".to_string(),
            InvalidProgramName { .. } => "program name".to_string(),
            ProgramNameNotAlone => "more words after the program name".to_string(),
            UnclosedComment => "comment starts here".to_string(),
            UnclosedBracket => "opened here".to_string(),
            UnmatchedBracket => "unmatched".to_string(),
            ExpressionTooDeep { .. } => "too deep".to_string(),
            MalformedExpression { .. } => "here".to_string(),
            MisplacedBlockDelete => "block delete".to_string(),
            WordNotAllowed { .. } => "not taken here".to_string(),
            MissingWord { .. } => "this command".to_string(),
            IntegerExpected { .. } => "decimal point".to_string(),
            ConflictingCommands { .. } => "second command".to_string(),
            DuplicateWord { .. } => "second time".to_string(),
            SemicolonInOsp => "`;`".to_string(),
            ByteOrderMark => "byte-order mark".to_string(),
            SameModalGroup { .. } => "same group".to_string(),
            DialectConflict { chosen, .. } => format!("evidence for {chosen}"),
            MachiningCentreProgram => "machining-centre evidence".to_string(),
            SourceTooLarge => "too large".to_string(),
            TooManyWords { .. } => "this block".to_string(),
            OrphanContinuation => "`$`".to_string(),
            NonFiniteMove | ArcEndOffCircle { .. } | TimeGoesBack | OutsideTravel { .. } => "this block".to_string(),
        }
    }

    pub fn hint(&self) -> Option<String> {
        use DiagnosticKind::*;
        match self {
            InvalidCharacter { found } if found.is_ascii_punctuation() => Some(format!(
                "`{found}` often stands for a digit damaged in scanning or transfer; retype the word from the drawing"
            )),
            InvalidCharacter { .. } => None,
            NonAsciiByte { .. } => {
                Some("text in another encoding (Shift-JIS, Latin-1) must stay inside `( )` comments".to_string())
            }
            LowerCaseLetter { found } => Some(format!("write `{}`", found.to_ascii_uppercase())),
            NulByte => Some("remove the NUL byte; it is often left by a tape punch or a bad transfer".to_string()),
            DamagedNumber { .. } => Some(
                "a digit was lost or misread in scanning (OCR) or transfer; characters such as `}` stand for damaged digits; retype the value from the drawing"
                    .to_string(),
            ),
            MissingValue { suggestion: Some(s), .. } => Some(format!("did you mean `{s}`?")),
            MissingValue { address, suggestion: None } => {
                Some(format!("write a number after `{address}`, for example `{address}0.`"))
            }
            MissingDigits { address } => Some(format!("write the digits, for example `{address}0.5`")),
            LetterOForZero { suggestion } => Some(format!("`O` typed for `0`? did you mean `{suggestion}`?")),
            ZeroForLetterO { suggestion } => Some(format!("`0` typed for `O`? did you mean `{suggestion}`?")),
            NumberOutOfRange { .. } => Some("check the decimal point and the unit of the value".to_string()),
            NumberWithoutAddress { suggestion: Some(s) } => Some(format!("missing `G`? did you mean `{s}`?")),
            NumberWithoutAddress { suggestion: None } => Some("every value needs an address letter".to_string()),
            UnknownGCode { hint: Some(h), .. } => Some(h.clone()),
            UnknownGCode { hint: None, .. } => {
                Some("check the G-code system (A, B, C) and the dialect in the machine settings".to_string())
            }
            MalformedCode { address } => Some(format!("`{address}` codes are whole numbers, at most with one decimal (`G12.1`)")),
            MachiningCentreCode { .. } => {
                Some("this program looks like a machining-centre program; check the dialect".to_string())
            }
            ForeignWord { belongs_to, .. } => Some(format!(
                "if the whole program is {belongs_to}, pass `--dialect {}`",
                if *belongs_to == "Okuma OSP" { "osp" } else { "fanuc" }
            )),
            UnknownStatement { .. } => Some(
                "a variable needs `=` (`NAME=value`); an address with a value needs `=` before an expression (`X=NAME+1`)"
                    .to_string(),
            ),
            ExtendedAddressNeedsEquals { name } => Some(format!("write `{name}=` before the value")),
            MissingSpaceAfterSequence { name } => {
                Some(format!("OSP requires a space after the sequence name: `{name} …`"))
            }
            SequenceTooLong { .. } => Some("shorten the name or renumber the block".to_string()),
            MissingSequenceName => Some("write digits after `N`, or remove it".to_string()),
            MisplacedSequence => Some("move the sequence number to the start of the block".to_string()),
            InvalidProgramName { .. } => None,
            ProgramNameNotAlone => Some("put the other words on the next line".to_string()),
            UnclosedComment => Some("add `)`; a comment cannot continue on the next line".to_string()),
            UnclosedBracket => Some("add `]`".to_string()),
            UnmatchedBracket => Some("remove the `]` or add the `[` it closes".to_string()),
            ExpressionTooDeep { .. } => Some("split the expression with a variable".to_string()),
            MalformedExpression { .. } => None,
            MisplacedBlockDelete => {
                Some("put `/` at the start of the block or right after the sequence name".to_string())
            }
            WordNotAllowed { allowed, .. } if !allowed.is_empty() => Some(format!("it takes {allowed}")),
            WordNotAllowed { .. } => Some("it takes no other words".to_string()),
            MissingWord { .. } => None,
            IntegerExpected { .. } => Some(
                "the value counts least increments (e.g. µm) or names a sequence number; remove the decimal point"
                    .to_string(),
            ),
            ConflictingCommands { .. } => Some("split them into two blocks".to_string()),
            DuplicateWord { .. } => Some("remove one of them".to_string()),
            SemicolonInOsp => Some("use `( )` for comments on OSP".to_string()),
            ByteOrderMark => Some("most controls reject it; save the file without a BOM".to_string()),
            SameModalGroup { .. } => None,
            DialectConflict { .. } => {
                Some("pass `--dialect osp` or `--dialect fanuc`, or set `dialect` in the machine settings".to_string())
            }
            MachiningCentreProgram => None,
            SourceTooLarge => None,
            TooManyWords { .. } => Some("no control reads a block this long; split it".to_string()),
            OrphanContinuation => Some("a `$` line continues the block on the line before it".to_string()),
            NonFiniteMove | TimeGoesBack => None,
            ArcEndOffCircle { .. } => Some("check the end point and the centre (I K) or radius of the arc".to_string()),
            OutsideTravel { .. } => Some("check the coordinates, the work offset and the travel limits in the machine settings".to_string()),
        }
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}[{}]: {}", self.severity.as_str(), self.code(), self.message())
    }
}
