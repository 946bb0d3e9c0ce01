//! The words of each diagnostic: stable codes, messages, labels and hints, written for a
//! machinist at the control.

use super::DiagnosticKind;

impl DiagnosticKind {
    /// A stable identifier for tools and JSON output.
    pub fn code(&self) -> &'static str {
        use DiagnosticKind::*;
        match self {
            InvalidCharacter { .. } => "invalid-character",
            NonAsciiByte { .. } => "non-ascii-byte",
            LowerCaseLetter { .. } => "lower-case-letter",
            NulByte => "nul-byte",
            NotText { .. } => "not-text",
            EmptyProgram => "empty-program",
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
            ModelFile(problem) => problem.code(),
            TooManyWords { .. } => "too-many-words",
            OrphanContinuation => "orphan-continuation",
            NonFiniteMove => "non-finite-move",
            ArcEndOffCircle { .. } => "arc-end-off-circle",
            TimeGoesBack => "time-goes-back",
            OutsideTravel { .. } => "outside-travel",
            NoseDoesNotFit { .. } => "nose-does-not-fit",
            CompensationOnArc { .. } => "compensation-on-arc",
            HomeUnknown => "home-unknown",
            UnknownStartPosition => "unknown-start-position",
            LapContourNotClosed => "lap-contour-not-closed",
            LapContourMissing { .. } => "lap-contour-missing",
            LapContourEmpty => "lap-contour-empty",
            LapContourNotMonotonic { .. } => "lap-contour-not-monotonic",
            LapStartInsideContour => "lap-start-inside-contour",
            LapWordOutOfRange { .. } => "lap-word-out-of-range",
            LapConditionOrder { .. } => "lap-condition-order",
            LapConditionMisplaced { .. } => "lap-condition-misplaced",
            LapCallWord { .. } => "lap-call-word",
            ProfileBackwards => "profile-backwards",
            CycleNotSimulated { .. } => "cycle-not-simulated",
            NotExpandable => "not-expandable",
            CorrectionTooLarge { .. } => "correction-too-large",
            CompensatedOutsideTravel { .. } => "compensated-outside-travel",
            CannotRewriteBlock { .. } => "cannot-rewrite-block",
            CycleNotCompensated => "cycle-not-compensated",
            AlreadyCompensated { .. } => "already-compensated",
            CompensationFailsCheck { .. } => "compensation-fails-check",
            CompensationUnreadable { .. } => "compensation-unreadable",
            CycleNeedsDepth => "cycle-needs-depth",
            EmptyProfile => "empty-profile",
            ProfileReverses { .. } => "profile-reverses",
            ProfileNotMonotonic { .. } => "profile-not-monotonic",
            StartOnWrongSide { .. } => "start-on-wrong-side",
            CycleNeedsDivisions => "cycle-needs-divisions",
            GrooveStepMissing { .. } => "groove-step-missing",
            CycleTooManyPasses { .. } => "cycle-too-many-passes",
            ThreadHeightBelowFirstDepth { .. } => "thread-height-below-first-depth",
            ThreadLeadNotPositive => "thread-lead-not-positive",
            ThreadParametersInvalid { .. } => "thread-parameters-invalid",
            MissingSequence { .. } => "missing-sequence",
            DuplicateSequence { .. } => "duplicate-sequence",
            RunawayProgram { .. } => "runaway-program",
            UnmatchedLoop { .. } => "unmatched-loop",
            MissingLabel { .. } => "missing-label",
            MissingProgram { .. } => "missing-program",
            CallsTooDeep { .. } => "calls-too-deep",
            NoFeed => "no-feed",
            ArcRadiusTooSmall { .. } => "arc-radius-too-small",
            ArcWithoutCentre => "arc-without-centre",
            ArcCentreMismatch { .. } => "arc-centre-mismatch",
            CornerWithoutNextLine => "corner-without-next-line",
            CornerDoesNotFit { .. } => "corner-does-not-fit",
            NotAllowedInProfile => "not-allowed-in-profile",
            ThreadRoughDepthBelowFirstCut { .. } => "thread-rough-depth-below-first-cut",
            ThreadAllowanceOverHeight { .. } => "thread-allowance-over-height",
            InfeedAngleOutOfRange { .. } => "infeed-angle-out-of-range",
            ThreadDepthNotPositive { .. } => "thread-depth-not-positive",
            TooManyPasses { .. } => "too-many-passes",
            InfeedPatternApproximated => "infeed-pattern-approximated",
            CycleNeedsShift { .. } => "cycle-needs-shift",
            ThreadContourNotStraight => "thread-contour-not-straight",
            BadVariableNumber { .. } => "bad-variable-number",
            NotAVariable => "not-a-variable",
            SystemVariableUnknown { .. } => "system-variable-unknown",
            UndefinedVariable { .. } => "undefined-variable",
            DivisionByZero => "division-by-zero",
            FunctionDomain { .. } => "function-domain",
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
            NotText { control_bytes, sampled, whole_file, .. } => format!(
                "not a text program: {control_bytes} of its {}{sampled} bytes are control bytes",
                if *whole_file { "" } else { "first " }
            ),
            EmptyProgram => "the program holds no block to run".to_string(),
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
            ModelFile(problem) => problem.message(),
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
            NoseDoesNotFit { radius_mm, reason } => {
                format!("the tool nose (radius {radius_mm:.3} mm) cannot follow the contour here: {reason}")
            }
            CompensationOnArc { cancel: false } => {
                "nose-radius compensation starts on an arc; the move is made straight".to_string()
            }
            CompensationOnArc { cancel: true } => {
                "nose-radius compensation ends on an arc; the move is made straight".to_string()
            }
            HomeUnknown => "the machine settings give no home position; after this block, and after every later \
                            return to home, the toolpath resumes at the next programmed point"
                .to_string(),
            UnknownStartPosition => "the machine settings give no home position; the toolpath starts at the first \
                                     programmed point, and after every return to home resumes at the next one"
                .to_string(),
            LapContourNotClosed => "LAP contour with no `G80` after it".to_string(),
            LapContourMissing { name } => format!("no `G81`/`G82` contour block is named `{name}`"),
            LapContourEmpty => "the LAP contour has no move after its first block".to_string(),
            LapContourNotMonotonic { axis } => {
                format!(
                    "the contour turns back in {axis}; the LAP roughing cycle cuts along {axis} and cannot follow it"
                )
            }
            LapStartInsideContour => {
                "the cycle starts inside the contour plus its allowance; the first pass would cut into the part"
                    .to_string()
            }
            LapWordOutOfRange { word, value, rule } => format!("`{word}` is {value}; {rule}"),
            LapConditionOrder { word, value, before, before_value, outside } => format!(
                "`{word}{value}` does not come after `{before}{before_value}` along the cut: {}",
                if *outside {
                    "outside, each change point must be smaller than the one before"
                } else {
                    "inside, each change point must be larger than the one before"
                }
            ),
            LapConditionMisplaced { word, reason } => format!("`{word}` does not apply here: {reason}"),
            LapCallWord { command, address } => format!("{command} cannot carry `{address}`; the control rejects it"),
            ProfileBackwards => "the profile's end (`Q`) comes before its start (`P`)".to_string(),
            CycleNotSimulated { code } => {
                format!("{code} is not simulated yet; its moves are missing from the toolpath")
            }
            NotExpandable => {
                "this cycle is left as it is: its thread moves have no plain-block form in this dialect".to_string()
            }
            CorrectionTooLarge { shift_mm, max_mm } => format!(
                "the machine model moves this block by {shift_mm:.4} mm, more than the {max_mm:.4} mm allowed; \
                 no compensated program is written"
            ),
            CompensatedOutsideTravel { x_mm, z_mm } => format!(
                "the compensated tool path leaves the machine's travel at X{:.4} Z{z_mm:.4} (diameter, mm); \
                 no compensated program is written",
                2.0 * x_mm
            ),
            CannotRewriteBlock { reason } => {
                format!("this block's motion must change for the machine model, but it cannot be rewritten: {reason}")
            }
            CycleNotCompensated => "this cycle stays as programmed and is not compensated: its thread passes have \
                                    no plain-block form in this dialect"
                .to_string(),
            AlreadyCompensated { model: Some(model) } => format!(
                "this program is compensated already (for the machine model `{model}`): compensating it again \
                 takes the machine's errors out twice"
            ),
            AlreadyCompensated { model: None } => "this program is compensated already: compensating it again \
                                                   takes the machine's errors out twice"
                .to_string(),
            CompensationFailsCheck { deviation_mm, bound_mm } => format!(
                "the compensated program, read back and predicted on the model as `turnpass verify` predicts it, \
                 would cut this block {deviation_mm:.5} mm off the nominal part, more than the {bound_mm:.5} mm \
                 verify allows; no compensated program is written"
            ),
            CompensationUnreadable { problem } => format!(
                "the compensated program does not read back cleanly ({problem}); no compensated program is written"
            ),
            CycleNeedsDepth => "the roughing cycle has no depth of cut".to_string(),
            EmptyProfile => "the profile named by `P`/`Q` has no moves".to_string(),
            ProfileReverses { axis } => format!("the profile turns back in {axis}; the roughing cycle cannot cut it"),
            ProfileNotMonotonic { axis } => {
                format!("the profile is not monotonic in {axis}, which a Type I roughing cycle requires")
            }
            StartOnWrongSide { x, z, axis, address, allowance, .. } => {
                let (start, word) = (format!("X{} Z{}", short(*x), short(*z)), format!("{address}{}", short(*allowance)));
                match (axis, *allowance < 0.0) {
                    ('X', true) => format!("the start point {start} lies outside the profile, but {word} is an inside allowance"),
                    ('X', false) => format!("the start point {start} lies inside the profile, but {word} is an outside allowance"),
                    (_, true) => format!(
                        "the start point {start} lies on the +{axis} side of the profile, \
                         but {word} is the allowance of a cut from the -{axis} side"
                    ),
                    (_, false) => format!(
                        "the start point {start} lies on the -{axis} side of the profile, \
                         but {word} is the allowance of a cut from the +{axis} side"
                    ),
                }
            }
            CycleNeedsDivisions => "the pattern-repeating cycle has no number of passes".to_string(),
            GrooveStepMissing { axis } => {
                format!("the groove is wider than one plunge but the cycle has no step in {axis} between plunges")
            }
            CycleTooManyPasses { passes, max } => {
                format!("this cycle would run {passes} passes; turnpass simulates at most {max}")
            }
            ThreadHeightBelowFirstDepth { height_mm, first_depth_mm } => format!(
                "the thread height ({height_mm:.4} mm) is smaller than the first depth of cut ({first_depth_mm:.4} mm)"
            ),
            ThreadLeadNotPositive => "the thread lead is zero or negative".to_string(),
            ThreadParametersInvalid { word } => format!("`{word}` is not a threading parameter this control takes"),
            MissingSequence { number } => format!("no block has sequence number N{number}"),
            DuplicateSequence { number, count } => format!("{count} blocks have sequence number N{number}"),
            RunawayProgram { blocks, moves } => {
                format!("the program ran {blocks} blocks ({moves} moves) without ending")
            }
            UnmatchedLoop { number } => format!("`DO{number}` has no `END{number}`"),
            MissingLabel { name } => format!("no block is labelled `{name}`"),
            MissingProgram { name } => {
                format!(
                    "`{name}` is not in this file; the control runs it from its memory and its moves are not simulated"
                )
            }
            CallsTooDeep { max } => format!("subprogram calls nest deeper than {max}"),
            NoFeed => "a feed move with no feed rate (or no spindle speed for feed per revolution)".to_string(),
            ArcRadiusTooSmall { radius_mm, half_chord_mm } => format!(
                "the arc radius {radius_mm:.4} mm cannot reach the end point (half the chord is {half_chord_mm:.4} mm)"
            ),
            ArcWithoutCentre => "the arc has neither a centre (`I`/`K`) nor a radius".to_string(),
            ArcCentreMismatch { start_radius_mm, end_radius_mm } => {
                format!("the centre is {start_radius_mm:.4} mm from the start but {end_radius_mm:.4} mm from the end")
            }
            CornerWithoutNextLine => {
                "the automatic corner has no straight move after it; the corner is left sharp".to_string()
            }
            CornerDoesNotFit { size_mm } => format!("a {size_mm:.3} mm corner does not fit between these lines"),
            NotAllowedInProfile => "a finishing profile may hold only moves and modal words".to_string(),
            ThreadRoughDepthBelowFirstCut { rough_depth, first_depth } => format!(
                "with infeed pattern 1 the depth to rough, H − U = {}, is less than the first cut D = {}",
                short(*rough_depth),
                short(*first_depth)
            ),
            ThreadAllowanceOverHeight { height, allowance } => format!(
                "the finishing allowance {} is larger than the thread height H = {}",
                short(*allowance),
                short(*height)
            ),
            InfeedAngleOutOfRange { angle } => {
                format!("the infeed angle B = {}° is outside 0 ≤ B < 180", short(*angle))
            }
            ThreadDepthNotPositive { address: 'H' } => "the thread height `H` is not positive".to_string(),
            ThreadDepthNotPositive { address } => format!("the thread cycle's first depth of cut `{address}` is not positive"),
            TooManyPasses { passes, max } => {
                format!("this cycle would cut {passes} passes; the simulation stops at {max}")
            }
            InfeedPatternApproximated => {
                "with D² < H² − (H − U)² the control chooses its own pass depths for infeed pattern 3; simulated with D·√n"
                    .to_string()
            }
            CycleNeedsShift { shift, axis } => {
                format!("the cycle ends at another {axis} than it starts, and has no `{shift}` to step there")
            }
            ThreadContourNotStraight => {
                "a continuous thread contour may hold only straight thread elements after its approach".to_string()
            }
            BadVariableNumber { value } => format!("{value} is not a variable number"),
            NotAVariable => "only a variable can be assigned".to_string(),
            SystemVariableUnknown { name } => {
                format!("{name} holds machine state the simulation does not have; read as 0")
            }
            UndefinedVariable { name } => format!("{name} is used before it is set"),
            DivisionByZero => "division by zero".to_string(),
            FunctionDomain { function, argument } => format!("{function} is not defined at {argument}"),
        }
    }

    /// The short text under the primary label.
    pub fn label(&self) -> String {
        use DiagnosticKind::*;
        match self {
            InvalidCharacter { .. } | NonAsciiByte { .. } | NulByte | LowerCaseLetter { .. } => {
                "not valid here".to_string()
            }
            NotText { byte, .. } => format!("first control byte, 0x{byte:02X}"),
            EmptyProgram => "nothing to run from here to the end".to_string(),
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
            ModelFile(problem) => problem.label(),
            TooManyWords { .. } => "this block".to_string(),
            OrphanContinuation => "`$`".to_string(),
            NonFiniteMove | ArcEndOffCircle { .. } | TimeGoesBack | OutsideTravel { .. } => "this block".to_string(),
            NoseDoesNotFit { .. } => "the nose does not fit".to_string(),
            CompensationOnArc { .. } => "this arc".to_string(),
            HomeUnknown
            | UnknownStartPosition
            | CycleNotSimulated { .. }
            | RunawayProgram { .. }
            | CallsTooDeep { .. } => "here".to_string(),
            LapContourNotClosed => "contour start".to_string(),
            LapContourMissing { .. } | LapStartInsideContour => "this call".to_string(),
            LapContourEmpty | LapContourNotMonotonic { .. } => "contour".to_string(),
            LapWordOutOfRange { .. } | LapConditionOrder { .. } | LapConditionMisplaced { .. } => {
                "this word".to_string()
            }
            LapCallWord { .. } => "not in a LAP call".to_string(),
            ProfileBackwards => "this cycle".to_string(),
            MissingSequence { .. } => "names no block".to_string(),
            DuplicateSequence { .. } => "names several blocks".to_string(),
            NotExpandable => "kept".to_string(),
            CorrectionTooLarge { shift_mm, .. } => format!("moved {:.1} µm", shift_mm * 1000.0),
            CompensatedOutsideTravel { .. } => "this block".to_string(),
            CannotRewriteBlock { .. } => "this block".to_string(),
            CycleNotCompensated => "not compensated".to_string(),
            AlreadyCompensated { .. } => "written by `turnpass compensate`".to_string(),
            CompensationFailsCheck { deviation_mm, .. } => format!("off by {:.2} µm", deviation_mm * 1000.0),
            CompensationUnreadable { .. } => "from here".to_string(),
            CycleNeedsDepth
            | EmptyProfile
            | ProfileReverses { .. }
            | ProfileNotMonotonic { .. }
            | StartOnWrongSide { .. } => "this cycle".to_string(),
            CycleNeedsDivisions | GrooveStepMissing { .. } | CycleTooManyPasses { .. } => "this cycle".to_string(),
            ThreadHeightBelowFirstDepth { .. } => "thread height".to_string(),
            ThreadLeadNotPositive => "lead".to_string(),
            ThreadParametersInvalid { .. } => "this word".to_string(),
            UnmatchedLoop { .. } => "loop start".to_string(),
            MissingLabel { .. } => "jump".to_string(),
            MissingProgram { .. } => "call".to_string(),
            NoFeed => "no feed".to_string(),
            ArcRadiusTooSmall { .. } | ArcWithoutCentre | ArcCentreMismatch { .. } => "this arc".to_string(),
            CornerWithoutNextLine | CornerDoesNotFit { .. } => "corner".to_string(),
            NotAllowedInProfile => "inside the profile".to_string(),
            ThreadRoughDepthBelowFirstCut { .. } => "deeper than H − U".to_string(),
            ThreadAllowanceOverHeight { .. } => "larger than H".to_string(),
            ThreadDepthNotPositive { .. } => "not positive".to_string(),
            TooManyPasses { .. } => "this cycle".to_string(),
            InfeedPatternApproximated => "pattern 3".to_string(),
            CycleNeedsShift { .. } => "off the start line".to_string(),
            InfeedAngleOutOfRange { .. } => "infeed angle".to_string(),
            ThreadContourNotStraight => "in the thread contour".to_string(),
            BadVariableNumber { .. } | NotAVariable | SystemVariableUnknown { .. } | UndefinedVariable { .. } => {
                "variable".to_string()
            }
            DivisionByZero | FunctionDomain { .. } => "this value".to_string(),
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
            NotText { utf16: true, .. } => {
                Some("the file looks like UTF-16 text: save it as ASCII or UTF-8 and read it again".to_string())
            }
            NotText { utf16: false, .. } => Some(
                "is this the program? an executable, an archive, a picture or a word processor's file is not read"
                    .to_string(),
            ),
            EmptyProgram => Some("is this the right file? a program has at least one block with words".to_string()),
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
            ModelFile(problem) => problem.hint(),
            TooManyWords { .. } => Some("no control reads a block this long; split it".to_string()),
            OrphanContinuation => Some("a `$` line continues the block on the line before it".to_string()),
            NonFiniteMove | TimeGoesBack => None,
            ArcEndOffCircle { .. } => Some("check the end point and the centre (I K) or radius of the arc".to_string()),
            OutsideTravel { .. } => Some("check the coordinates, the work offset and the travel limits in the machine settings".to_string()),
            NoseDoesNotFit { .. } => {
                Some("use a tool with a smaller nose radius, or open up the contour (a wider groove, a larger concave radius)".to_string())
            }
            CompensationOnArc { cancel: false } => {
                Some("switch compensation on (G41/G42) in a G00 or G01 block before the arc".to_string())
            }
            CompensationOnArc { cancel: true } => {
                Some("cancel compensation (G40) in a G00 or G01 block after the arc".to_string())
            }
            HomeUnknown | UnknownStartPosition => {
                Some("set `home = { x = …, z = … }` in the [machine] table of the model file".to_string())
            }
            LapContourNotClosed => Some("end the contour with a `G80` block".to_string()),
            LapContourMissing { .. } => Some(
                "the call names the sequence name of the block that starts the contour, e.g. `G85 NLAP1 …` and `NLAP1 G81`"
                    .to_string(),
            ),
            LapContourEmpty => Some("define the contour with G00/G01/G02/G03 moves between `G81`/`G82` and `G80`".to_string()),
            LapContourNotMonotonic { .. } => Some(
                "G85 and G86 need a contour that runs one way along the cut; rough the undercut with another cycle or by hand"
                    .to_string(),
            ),
            LapStartInsideContour => Some(
                "position the tool outside the stock before the call (above the largest diameter for outside turning)"
                    .to_string(),
            ),
            LapWordOutOfRange { .. } => Some(
                "D, DA=, DB= are depths per pass, greater than 0 (diameters on a G81 contour); U and W are allowances of 0 or more"
                    .to_string(),
            ),
            LapConditionOrder { .. } => Some(
                "write the points in the order the cut meets them: start > XA= > XB= outside, start < XA= < XB= inside"
                    .to_string(),
            ),
            LapConditionMisplaced { .. } => None,
            LapCallWord { .. } => Some("program S, T and M in a block before the LAP call".to_string()),
            ProfileBackwards => Some("`P` names the first block of the profile, `Q` the last".to_string()),
            CycleNotSimulated { .. } => None,
            NotExpandable => None,
            CorrectionTooLarge { .. } => Some(
                "check the machine model (units of its tables, signs of its effects) and the tool offsets; \
                 raise --max-shift only if the machine really is that far off"
                    .to_string(),
            ),
            CompensatedOutsideTravel { .. } => {
                Some("move the part or the program away from the end of travel, or check the travel limits".to_string())
            }
            CannotRewriteBlock { .. } => Some(
                "write the block out for each time it runs (not in a subprogram or loop that runs it at \
                 different places), and without an automatic corner (`G75`/`G76`)"
                    .to_string(),
            ),
            CycleNotCompensated => Some("program the thread passes as single-pass cycle blocks".to_string()),
            AlreadyCompensated { .. } => Some(
                "compensate the nominal program (the one without this comment); give --force only if this \
                 program is to be compensated as it is"
                    .to_string(),
            ),
            CompensationFailsCheck { .. } => Some(
                "turnpass cannot compensate this block on this model within the bound: try another --strategy or \
                 --tolerance, check the model, or run the program uncompensated; please report it with the program \
                 and the model"
                    .to_string(),
            ),
            CompensationUnreadable { .. } => {
                Some("this is a defect of turnpass: please report it with the program and the model".to_string())
            }
            CycleNeedsDepth => Some("give the depth in a first block (`G71 U… R…`, `G72 W… R…`) or as `D` in the cycle block".to_string()),
            EmptyProfile => None,
            ProfileReverses { .. } => Some("split the profile, or rough the undercut with another cycle (G73)".to_string()),
            ProfileNotMonotonic { .. } => Some(
                "a Type II cycle allows pockets: name both X and Z (e.g. `W0`) in the profile's first block".to_string(),
            ),
            StartOnWrongSide { x, z, axis, address, allowance, extreme } => {
                let target = short(extreme + allowance);
                let (word, extreme) = (format!("{address}{}", short(*allowance)), short(*extreme));
                let example = if *axis == 'X' { format!("G00 X{target} Z{}", short(*z)) } else { format!("G00 X{} Z{target}", short(*x)) };
                let (place, bound, smallest, other) = match (axis, *allowance < 0.0) {
                    ('X', true) => ("an inside cut starts inside the bore", "or less", "smallest", "positive for an outside cut"),
                    ('X', false) => ("an outside cut starts outside the part", "or more", "largest", "negative for an inside cut"),
                    (_, true) => ("a cut from the -Z side starts behind the profile", "or less", "smallest", "positive for a cut from the +Z side"),
                    (_, false) => ("a cut from the +Z side starts in front of the profile", "or more", "largest", "negative for a cut from the -Z side"),
                };
                Some(format!(
                    "{place}: move the start point to {axis}{target} {bound} (the profile's {smallest} {axis}, \
                     {axis}{extreme}, with the allowance {word}), e.g. `{example}` before the cycle; \
                     or write {address} {other}"
                ))
            }
            CycleNeedsDivisions => Some(
                "give the number of passes as `R` in a first block (`G73 U… W… R3`) \
                 or as `D` in the cycle block"
                    .to_string(),
            ),
            GrooveStepMissing { axis } => Some(format!(
                "give the step in {axis} (`Q` of G75 or `P` of G74 in least increments, Haas `K`/`I`), \
                 or end the groove where it starts"
            )),
            CycleTooManyPasses { .. } => Some("check the depth of cut, step or number of passes".to_string()),
            ThreadHeightBelowFirstDepth { .. } => Some(
                "the height (`P` of the second G76 block, Haas `K`) is the full thread depth; \
                 the first depth (`Q`, Haas `D`) must not exceed it"
                    .to_string(),
            ),
            ThreadLeadNotPositive => Some("give the lead as a positive `F` (or `E`)".to_string()),
            ThreadParametersInvalid { .. } => Some(
                "`G76 P` takes six digits: finishing passes 01-99, chamfer 00-99 (tenths of the lead), \
                 tool angle 80, 60, 55, 30, 29 or 00; Haas `P` is 1-4 and `A` 0-120"
                    .to_string(),
            ),
            MissingSequence { number } => Some(format!("number the block this word means `N{number}`, or correct the number")),
            DuplicateSequence { .. } => Some("P and Q must each name exactly one block; renumber the others".to_string()),
            RunawayProgram { .. } => Some("check the loop's condition and the variables it changes".to_string()),
            UnmatchedLoop { .. } => None,
            MissingLabel { .. } => None,
            MissingProgram { .. } => Some("to simulate its moves, add the subprogram to the file".to_string()),
            CallsTooDeep { .. } => Some("a subprogram probably calls itself".to_string()),
            NoFeed => Some("program F before the first feed move (and S for feed per revolution)".to_string()),
            ArcRadiusTooSmall { .. } => Some("check the end point and the radius; R must be at least half the chord".to_string()),
            ArcWithoutCentre => Some("add `I`/`K` (centre from the start point) or the radius".to_string()),
            ArcCentreMismatch { .. } => Some("check `I`/`K`: they give the centre measured from the start point, I as a radius".to_string()),
            CornerWithoutNextLine => None,
            CornerDoesNotFit { .. } => Some("make `L` smaller than both lines".to_string()),
            NotAllowedInProfile => None,
            ThreadRoughDepthBelowFirstCut { .. } => {
                Some("make `D` at most `H − U`, or choose infeed pattern 2 or 3 (`M74`, `M75`)".to_string())
            }
            ThreadAllowanceOverHeight { .. } => Some("the allowance must be at most the thread height `H`".to_string()),
            InfeedAngleOutOfRange { .. } => {
                Some("`B` is the tool's included angle: 60 for metric threads, 55 for Whitworth, 0 for radial infeed".to_string())
            }
            ThreadDepthNotPositive { address } => {
                Some(format!("give `{address}` as a positive diameter, for example `{address}0.4`"))
            }
            TooManyPasses { .. } => Some("check `D` against the thread height `H`".to_string()),
            InfeedPatternApproximated => {
                Some("a larger first depth `D` (D² ≥ H² − (H − U)²) makes the pass depths the documented D·√n".to_string())
            }
            CycleNeedsShift { shift, .. } => Some(format!("give the shift per pass `{shift}`, or start the cycle on the end line")),
            ThreadContourNotStraight => {
                Some("cut the thread with G71/G72, or split the contour at the arc".to_string())
            }
            BadVariableNumber { .. } | NotAVariable => None,
            SystemVariableUnknown { .. } => None,
            UndefinedVariable { .. } => Some("set it earlier in the program or pass it in the call".to_string()),
            DivisionByZero | FunctionDomain { .. } => None,
        }
    }
}

/// A program value as a machinist writes it: up to four decimals, no trailing zeros.
fn short(value: f64) -> String {
    let text = format!("{value:.4}");
    let text = if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.') } else { &text };
    if text == "-0" { "0".to_string() } else { text.to_string() }
}
