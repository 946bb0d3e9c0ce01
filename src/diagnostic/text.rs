//! The words of each diagnostic, written for a machinist at the control: its stable code,
//! message, label and hint, all four in the one arm of its kind.

use std::borrow::Cow;

use super::DiagnosticKind;

/// What a diagnostic says.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Words {
    /// A stable identifier for tools and JSON output.
    pub code: &'static str,
    pub message: Cow<'static, str>,
    /// The short text under the primary label.
    pub label: Cow<'static, str>,
    /// What to do about it, where a guess is possible.
    pub hint: Option<Cow<'static, str>>,
}

impl DiagnosticKind {
    /// The code, message, label and hint of this diagnostic: one arm per kind, so a new
    /// kind is written in one place and the compiler asks for it.
    pub fn words(&self) -> Words {
        use DiagnosticKind::*;
        match self {
            InvalidCharacter { found } => Words {
                code: "invalid-character",
                message: format!("`{}` is not a character a block may contain", found.escape_debug()).into(),
                label: "not valid here".into(),
                hint: found.is_ascii_punctuation().then(|| {
                    format!(
                        "`{found}` often stands for a digit damaged in scanning or transfer; retype the word from the drawing"
                    )
                    .into()
                }),
            },
            NonAsciiByte { byte } => Words {
                code: "non-ascii-byte",
                message: format!("byte 0x{byte:02X} is not ASCII and is outside a comment").into(),
                label: "not valid here".into(),
                hint: Some("text in another encoding (Shift-JIS, Latin-1) must stay inside `( )` comments".into()),
            },
            LowerCaseLetter { found } => Words {
                code: "lower-case-letter",
                message: format!("lower-case `{found}` outside a comment").into(),
                label: "not valid here".into(),
                hint: Some(format!("write `{}`", found.to_ascii_uppercase()).into()),
            },
            TextOutsideComment { text } => Words {
                code: "text-outside-comment",
                message: format!("`{text}` reads as words, not as a block").into(),
                label: "not a block".into(),
                hint: Some(format!("a note belongs in a comment, `({text})`; the control rejects the line as it stands").into()),
            },
            LetterForDigit { found, digit } => Words {
                code: "letter-for-digit",
                message: format!("letter `{found}` inside a number").into(),
                label: format!("letter {found}").into(),
                hint: Some(format!("a misread `{digit}`? write `{digit}`").into()),
            },
            TapeLeader => Words {
                code: "tape-leader",
                message: "text before the program: a tape leader, which the control skips when the tape's `%` follows it".into(),
                label: "tape leader".into(),
                hint: Some("a note belongs in a comment `( … )`; a control that reads this file with no `%` after the line rejects it".into()),
            },
            DependsOnDamagedBlock { what } => Words {
                code: "depends-on-damaged-block",
                message: format!("not checked: {what} a block that does not parse").into(),
                label: "not checked".into(),
                hint: Some("fix the block's parse error; this is checked then".into()),
            },
            LeaderWithoutTape => Words {
                code: "not-a-block",
                message: "this line does not read as a block, and no `%` follows it to make it a tape leader the control skips".into(),
                label: "not a block".into(),
                hint: Some("put the text in a comment `( … )`, or a `%` line after it if it is a tape leader".into()),
            },
            NulByte => Words {
                code: "nul-byte",
                message: "NUL byte outside a comment".into(),
                label: "not valid here".into(),
                hint: Some("remove the NUL byte; it is often left by a tape punch or a bad transfer".into()),
            },
            NotText { byte, control_bytes, sampled, whole_file, utf16 } => Words {
                code: "not-text",
                message: format!(
                    "not a text program: {control_bytes} of its {}{sampled} bytes are control bytes",
                    if *whole_file { "" } else { "first " }
                )
                .into(),
                label: format!("first control byte, 0x{byte:02X}").into(),
                hint: Some(if *utf16 {
                    "the file looks like UTF-16 text: save it as ASCII or UTF-8 and read it again".into()
                } else {
                    "is this the program? an executable, an archive, a picture or a word processor's file is not read"
                        .into()
                }),
            },
            EmptyProgram => Words {
                code: "empty-program",
                message: "the program holds no block to run".into(),
                label: "nothing to run from here to the end".into(),
                hint: Some("is this the right file? a program has at least one block with words".into()),
            },
            DamagedNumber { text } => Words {
                code: "damaged-number",
                message: format!("the value in `{text}` is damaged").into(),
                label: "damaged value".into(),
                hint: Some("a digit was lost or misread in scanning (OCR) or transfer; characters such as `}` stand for damaged digits; retype the value from the drawing".into()),
            },
            MissingValue { address, suggestion } => Words {
                code: "missing-value",
                message: format!("`{address}` has no value").into(),
                label: "no value".into(),
                hint: Some(match suggestion {
                    Some(s) => format!("did you mean `{s}`?").into(),
                    None => format!("write a number after `{address}`, for example `{address}0.`").into(),
                }),
            },
            MissingDigits { address } => Words {
                code: "missing-digits",
                message: format!("the value of `{address}` has no digits").into(),
                label: "no digits".into(),
                hint: Some(format!("write the digits, for example `{address}0.5`").into()),
            },
            LetterOForZero { suggestion } => Words {
                code: "letter-o-for-zero",
                message: "letter `O` where a digit belongs".into(),
                label: "letter O".into(),
                hint: Some(format!("`O` typed for `0`? did you mean `{suggestion}`?").into()),
            },
            DecimalComma { suggestion } => Words {
                code: "decimal-comma",
                message: "a comma in a number; the control reads a decimal point".into(),
                label: "comma".into(),
                hint: Some(format!("a decimal comma? did you mean `{suggestion}`?").into()),
            },
            ZeroForLetterO { suggestion } => Words {
                code: "zero-for-letter-o",
                message: "digit `0` where the letter `O` of a program name belongs".into(),
                label: "digit 0".into(),
                hint: Some(format!("`0` typed for `O`? did you mean `{suggestion}`?").into()),
            },
            NumberOutOfRange { address, digits, max_digits } => Words {
                code: "number-out-of-range",
                message: format!("`{address}` has {digits} significant digits; it takes at most {max_digits}").into(),
                label: "too many digits".into(),
                hint: Some("check the decimal point and the unit of the value".into()),
            },
            NumberWithoutAddress { suggestion } => Words {
                code: "number-without-address",
                message: "a number with no address letter before it".into(),
                label: "no address".into(),
                hint: Some(match suggestion {
                    Some(s) => format!("missing `G`? did you mean `{s}`?").into(),
                    None => "every value needs an address letter".into(),
                }),
            },
            UnknownGCode { code, dialect, hint } => Words {
                code: "unknown-g-code",
                message: format!("{code} is not a G-code of the {dialect} dialect").into(),
                label: "unknown G-code".into(),
                hint: Some(match hint {
                    Some(h) => h.clone().into(),
                    None => "check the G-code system (A, B, C) and the dialect in the machine settings".into(),
                }),
            },
            MalformedCode { address } => Words {
                code: "malformed-code",
                message: format!("malformed `{address}` code").into(),
                label: "malformed code".into(),
                hint: Some(format!("`{address}` codes are whole numbers, at most with one decimal (`G12.1`)").into()),
            },
            MachiningCentreCode { code, meaning } => Words {
                code: "machining-centre-code",
                message: format!("{code} ({meaning}) is an OSP machining-centre code, not a lathe code").into(),
                label: "machining-centre code".into(),
                hint: Some("this program looks like a machining-centre program; check the dialect".into()),
            },
            ForeignWord { what, dialect, belongs_to } => Words {
                code: "foreign-word",
                message: format!("{what} belongs to the {belongs_to} dialect; this program is read as {dialect}").into(),
                label: format!("{belongs_to} syntax").into(),
                hint: Some(format!(
                "if the whole program is {belongs_to}, pass `--dialect {}`",
                if *belongs_to == "Okuma OSP" { "osp" } else { "fanuc" }
            ).into()),
            },
            UnknownStatement { name } => Words {
                code: "unknown-statement",
                message: format!("`{name}` is not an OSP statement or address").into(),
                label: "unknown name".into(),
                hint: Some("a variable needs `=` (`NAME=value`); an address with a value needs `=` before an expression (`X=NAME+1`)".into()),
            },
            ExtendedAddressNeedsEquals { name } => Words {
                code: "extended-address-needs-equals",
                message: format!("extended address `{name}` needs `=`").into(),
                label: "`=` missing".into(),
                hint: Some(format!("write `{name}=` before the value").into()),
            },
            MissingSpaceAfterSequence { name } => Words {
                code: "missing-space-after-sequence",
                message: format!("sequence name `{name}` runs into the next word").into(),
                label: "space needed here".into(),
                hint: Some(format!("OSP requires a space after the sequence name: `{name} …`").into()),
            },
            SequenceTooLong { max } => Words {
                code: "sequence-too-long",
                message: format!("sequence name longer than {max} characters").into(),
                label: "too long".into(),
                hint: Some("shorten the name or renumber the block".into()),
            },
            MissingSequenceName => Words {
                code: "missing-sequence-name",
                message: "`N` with no sequence name".into(),
                label: "no name".into(),
                hint: Some("write digits after `N`, or remove it".into()),
            },
            MisplacedSequence => Words {
                code: "misplaced-sequence",
                message: "sequence number after the start of the block".into(),
                label: "sequence number".into(),
                hint: Some("move the sequence number to the start of the block".into()),
            },
            InvalidProgramName { max } => Words {
                code: "invalid-program-name",
                message: format!("invalid program name (`O` and up to {max} characters)").into(),
                label: "program name".into(),
                hint: None,
            },
            ProgramNameNotAlone => Words {
                code: "program-name-not-alone",
                message: "the program-name block holds other words".into(),
                label: "more words after the program name".into(),
                hint: Some("put the other words on the next line".into()),
            },
            UnclosedComment => Words {
                code: "unclosed-comment",
                message: "comment not closed before the end of the block".into(),
                label: "comment starts here".into(),
                hint: Some("add `)`; a comment cannot continue on the next line".into()),
            },
            UnclosedBracket => Words {
                code: "unclosed-bracket",
                message: "`[` not closed before the end of the block".into(),
                label: "opened here".into(),
                hint: Some("add `]`".into()),
            },
            UnmatchedBracket => Words {
                code: "unmatched-bracket",
                message: "`]` with no `[` before it".into(),
                label: "unmatched".into(),
                hint: Some("remove the `]` or add the `[` it closes".into()),
            },
            ExpressionTooDeep { max } => Words {
                code: "expression-too-deep",
                message: format!("brackets nested more than {max} deep").into(),
                label: "too deep".into(),
                hint: Some("split the expression with a variable".into()),
            },
            MalformedExpression { expected } => Words {
                code: "malformed-expression",
                message: format!("malformed expression: expected {expected}").into(),
                label: "here".into(),
                hint: None,
            },
            MisplacedBlockDelete => Words {
                code: "misplaced-block-delete",
                message: "block delete `/` in the middle of a block".into(),
                label: "block delete".into(),
                hint: Some("put `/` at the start of the block or right after the sequence name".into()),
            },
            WordNotAllowed { command, address, allowed } => Words {
                code: "word-not-allowed",
                message: format!("{command} does not take `{address}`").into(),
                label: "not taken here".into(),
                hint: Some(if allowed.is_empty() {
                    "it takes no other words".into()
                } else {
                    format!("it takes {allowed}").into()
                }),
            },
            MissingWord { command, words } => Words {
                code: "missing-word",
                message: format!("{command} needs {words}").into(),
                label: "this command".into(),
                hint: None,
            },
            IntegerExpected(word) => {
                use crate::dialect::IntegerUnit as U;
                let super::CountedWord { command, address, written, unit, meant, control, elsewhere } = &**word;
                let counts = match unit {
                    U::Increments => "counts least increments of a length",
                    U::AngleIncrements => "counts thousandths of a degree",
                    U::Milliseconds => "counts milliseconds",
                    U::Sequence => "names a sequence number",
                    U::Count => "is a count",
                    U::Code => "packs digits into a code",
                };
                let mut hint = match (meant, unit) {
                    (Some((word, reading)), U::Milliseconds) => {
                        let seconds = reading.trim_end_matches(" s");
                        format!("write `{word}` ({reading}), or `X{seconds}` in seconds")
                    }
                    (Some((word, reading)), _) => format!("write `{word}` ({reading})"),
                    (None, U::Code) => format!("write the digits of `{written}` without the decimal point"),
                    (None, _) => format!("`{written}` is no whole number: write the value without a decimal point"),
                };
                // Where controls differ, which one's reading this is.
                let on = match elsewhere {
                    Some((other, reading)) => {
                        hint.push_str(&format!(
                            "; a {} control takes the point and reads `{written}` in {reading} (`control = \"{other}\"`)",
                            capitalised(other)
                        ));
                        format!(" on a {} control", capitalised(control))
                    }
                    None => String::new(),
                };
                Words {
                    code: "integer-expected",
                    message: format!("`{address}` in {command} {counts} and takes no decimal point{on}").into(),
                    label: "decimal point".into(),
                    hint: Some(hint.into()),
                }
            }
            DecimalPointUnverified { word, reading } => {
                let (command, written) = (&word.command, &word.written);
                let (word, meant) = word.meant.as_ref().map_or(("", ""), |(w, m)| (w.as_str(), m.as_str()));
                Words {
                code: "decimal-point-unverified",
                message: format!(
                    "`{written}` in {command} reads {reading} with its decimal point, where the control takes one; \
                     whether this control does is not verified"
                )
                .into(),
                label: format!("{reading} if the point is taken").into(),
                hint: Some(
                    format!(
                        "write `{word}` ({meant} in least increments), which reads the same on every control; \
                         one that refuses the point alarms at this block"
                    )
                    .into(),
                ),
            }
            }
            MissingDecimalPoint { word, readings } => {
                let (read, with_point) = &**readings;
                Words {
                code: "missing-decimal-point",
                message: format!(
                    "`{word}` has no decimal point, so the control counts least increments: it reads {read} here"
                )
                .into(),
                label: format!("{read}; `{word}.` is {with_point}").into(),
                hint: Some(format!("write `{word}.` for {with_point}").into()),
            }
            }
            DecimalInputUnset { count, word, readings } => {
                let (as_written, as_increments) = &**readings;
                Words {
                code: "decimal-input-unset",
                message: format!(
                    "{count} word{} without a decimal point read{} as the machine's decimal input says, which the settings \
                     do not give: `{word}` is {as_written} with calculator input (in force), {as_increments} on a \
                     control that counts least increments",
                    if *count == 1 { "" } else { "s" },
                    if *count == 1 { "s" } else { "" },
                )
                .into(),
                label: format!("{as_written} or {as_increments}").into(),
                hint: Some(
                    "set `decimal_input = \"calculator\"` or `\"increment\"` in the [machine] table of the model file \
                     (Fanuc parameter DPI), or give `--decimal-input`"
                        .into(),
                ),
            }
            }
            MissingPointCauses { cause, word, readings } => {
                let (read, with_point) = &**readings;
                let cause = cause.words();
                Words {
                    code: cause.code,
                    message: format!("{}: `{word}` has no decimal point and reads {read}", cause.message).into(),
                    label: format!("{read}; `{word}.` is {with_point}").into(),
                    hint: Some(format!("write `{word}.` for {with_point}").into()),
                }
            }
            ThreadHeightAsDiameter { word, depth_mm, passes } => Words {
                code: "thread-height-as-diameter",
                message: format!(
                    "`{word}` is the thread height as a diameter, as the OSP manual gives it (G71/G88: D, U and H \
                     are diameters): the {passes} pass{} cut {depth_mm:.3} mm deep",
                    if *passes == 1 { "" } else { "es" }
                )
                .into(),
                label: format!("{depth_mm:.3} mm deep").into(),
                hint: None,
            },
            ThreadHeightRadial { word, depth_mm, pitch_mm, meant } => {
                let full_mm = 2.0 * 0.6134 * pitch_mm;
                Words {
                code: "thread-height-radial",
                message: format!(
                    "`{word}` is the thread height as a diameter, so the thread is cut {depth_mm:.3} mm deep: about half \
                     of a 60° thread of pitch {} mm, whose height is {full_mm:.3} mm as a diameter",
                    short(*pitch_mm)
                )
                .into(),
                label: format!("{depth_mm:.3} mm deep").into(),
                hint: Some(
                    match meant {
                        Some(meant) => format!(
                            "OSP gives H, D and U as diameters (Fanuc's G76 height is radial): write `{meant}` for the \
                             full height, and D and U doubled likewise"
                        ),
                        None => "OSP gives H, D and U as diameters (Fanuc's G76 height is radial): double them".to_string(),
                    }
                    .into(),
                ),
            }
            }
            ConflictingCommands { first, second } => Words {
                code: "conflicting-commands",
                message: format!("{first} and {second} cannot share a block").into(),
                label: "second command".into(),
                hint: Some("split them into two blocks".into()),
            },
            DuplicateWord { address } => Words {
                code: "duplicate-word",
                message: format!("`{address}` appears twice in this block").into(),
                label: "second time".into(),
                hint: Some("remove one of them".into()),
            },
            AxisGivenTwice { position, distance, axis } => Words {
                code: "axis-given-twice",
                message: format!("`{position}` and `{distance}` both give the {axis} end point in this block").into(),
                label: "second end point".into(),
                hint: Some(
                    format!(
                        "keep one: `{position}` for the position, `{distance}` for the distance moved; controls \
                         differ on which wins (a `W` or `U` at the start of a block may be a misread `N`)"
                    )
                    .into(),
                ),
            },
            SemicolonInOsp => Words {
                code: "semicolon-in-osp",
                message: "`;` is not a comment on Okuma OSP".into(),
                label: "`;`".into(),
                hint: Some("use `( )` for comments on OSP".into()),
            },
            ByteOrderMark => Words {
                code: "byte-order-mark",
                message: "the file starts with a byte-order mark".into(),
                label: "byte-order mark".into(),
                hint: Some("most controls reject it; save the file without a BOM".into()),
            },
            SameModalGroup { first, second } => Words {
                code: "same-modal-group",
                message: format!("{first} and {second} are in the same modal group; the control keeps {second}").into(),
                label: "same group".into(),
                hint: None,
            },
            DialectConflict { chosen, other } => Words {
                code: "dialect-conflict",
                message: format!("the program shows features of both dialects; reading it as {chosen}, not {other}").into(),
                label: format!("evidence for {chosen}").into(),
                hint: Some("pass `--dialect osp` or `--dialect fanuc`, or set `dialect` in the machine settings".into()),
            },
            MachiningCentreProgram => Words {
                code: "machining-centre-program",
                message: "this is an OSP machining-centre program; only its syntax is checked".into(),
                label: "machining-centre evidence".into(),
                hint: None,
            },
            SourceTooLarge => Words {
                code: "source-too-large",
                message: "the program is 4 GiB or larger".into(),
                label: "too large".into(),
                hint: None,
            },
            ModelFile(problem) => problem.words(),
            DataInvalid { message, label, hint } => Words {
                code: "data-invalid",
                message: message.clone().into(),
                label: (*label).into(),
                hint: hint.clone().map(Into::into),
            },
            TooManyWords { max } => Words {
                code: "too-many-words",
                message: format!("the block has more than {max} words").into(),
                label: "this block".into(),
                hint: Some("no control reads a block this long; split it".into()),
            },
            OrphanContinuation => Words {
                code: "orphan-continuation",
                message: "continuation line with no block before it".into(),
                label: "`$`".into(),
                hint: Some("a `$` line continues the block on the line before it".into()),
            },
            NonFiniteMove => Words {
                code: "non-finite-move",
                message: "a move of this block has no finite position, feed or time".into(),
                label: "this block".into(),
                hint: None,
            },
            ArcEndOffCircle { start_radius, end_radius } => Words {
                code: "arc-end-off-circle",
                message: format!(
                "the arc's end is not on its circle: radius {start_radius:.4} mm at the start, {end_radius:.4} mm at the end"
            ).into(),
                label: "this block".into(),
                hint: Some("check the end point and the centre (I K) or radius of the arc".into()),
            },
            TimeGoesBack => Words {
                code: "time-goes-back",
                message: "a move of this block ends before it starts".into(),
                label: "this block".into(),
                hint: None,
            },
            RapidIntoStock { depth_mm, assumed: None } => Words {
                code: "rapid-into-stock",
                message: format!("this rapid move runs {depth_mm:.3} mm into the stock").into(),
                label: "a crash: the tool meets material at the rapid rate".into(),
                hint: Some("feed through material (G01), or move clear of the part first: retract in X, then move in Z".into()),
            },
            RapidIntoStock { depth_mm, assumed: Some(others) } => Words {
                code: "rapid-into-stock",
                message: format!(
                    "this rapid move would run {depth_mm:.3} mm into the stock, if the bar is the one assumed (the smallest \
                     bar holding every cut's start){}",
                    more_blocks(*others, "rapid moves")
                ).into(),
                label: "the deepest rapid through assumed material".into(),
                hint: Some("give the bar in the model file's [stock] table (or --stock) to check the rapids for real".into()),
            },
            CutTooDeep { depth_mm, max_mm, assumed } => Words {
                code: "cut-too-deep",
                message: format!(
                    "this cut engages {depth_mm:.3} mm of material, more than the tool's max_depth of {max_mm:.3} mm{}",
                    match assumed {
                        None => String::new(),
                        Some(others) => format!(" (in the assumed stock){}", more_blocks(*others, "cuts")),
                    }
                ).into(),
                label: "deeper than the tool takes".into(),
                hint: Some("take the material in more passes, or check the tool's max_depth in the tool table".into()),
            },
            PartModelStopped { rays, stamps } => Words {
                code: "part-model-stopped",
                message: format!(
                    "the part model stops here: the program asks more of it than its bound on work ({rays} ray visits in \
                     a run, {stamps} thread forms in a move); the moves from here on are not checked against the stock"
                ).into(),
                label: "not checked from here".into(),
                hint: Some("a program this large or this fine is checked in parts: split it at a tool change".into()),
            },
            OutsideTravel { x_mm, z_mm } => Words {
                code: "outside-travel",
                message: format!("the tool leaves the machine's travel at X{:.3} Z{z_mm:.3} (diameter, mm)", 2.0 * x_mm).into(),
                label: "this block".into(),
                hint: Some("check the coordinates, the work offset and the travel limits in the machine settings".into()),
            },
            NoseDoesNotFit { radius_mm, reason } => Words {
                code: "nose-does-not-fit",
                message: format!("the tool nose (radius {radius_mm:.3} mm) cannot follow the contour here: {reason}").into(),
                label: "the nose does not fit".into(),
                hint: Some("use a tool with a smaller nose radius, or open up the contour (a wider groove, a larger concave radius)".into()),
            },
            CompensationOnArc { cancel: false } => Words {
                code: "compensation-on-arc",
                message: "nose-radius compensation starts on an arc; the move is made straight".into(),
                label: "this arc".into(),
                hint: Some("switch compensation on (G41/G42) in a G00 or G01 block before the arc".into()),
            },
            CompensationOnArc { cancel: true } => Words {
                code: "compensation-on-arc",
                message: "nose-radius compensation ends on an arc; the move is made straight".into(),
                label: "this arc".into(),
                hint: Some("cancel compensation (G40) in a G00 or G01 block after the arc".into()),
            },
            HomeUnknown => Words {
                code: "home-unknown",
                message: "the machine settings give no home position; after this block, and after every later \
                            return to home, the toolpath resumes at the next programmed point".into(),
                label: "here".into(),
                hint: Some("set `home = { x = …, z = … }` in the [machine] table of the model file".into()),
            },
            UnknownStartPosition => Words {
                code: "unknown-start-position",
                message: "the machine settings give no home position; the toolpath starts at the first \
                                     programmed point, and after every return to home resumes at the next one".into(),
                label: "here".into(),
                hint: Some("set `home = { x = …, z = … }` in the [machine] table of the model file".into()),
            },
            LapContourNotClosed => Words {
                code: "lap-contour-not-closed",
                message: "LAP contour with no `G80` after it".into(),
                label: "contour start".into(),
                hint: Some("end the contour with a `G80` block".into()),
            },
            LapContourMissing { name } => Words {
                code: "lap-contour-missing",
                message: format!("no `G81`/`G82` contour block is named `{name}`").into(),
                label: "this call".into(),
                hint: Some("the call names the sequence name of the block that starts the contour, e.g. `G85 NLAP1 …` and `NLAP1 G81`".into()),
            },
            LapContourEmpty => Words {
                code: "lap-contour-empty",
                message: "the LAP contour has no move after its first block".into(),
                label: "contour".into(),
                hint: Some("define the contour with G00/G01/G02/G03 moves between `G81`/`G82` and `G80`".into()),
            },
            LapContourNotMonotonic { axis } => Words {
                code: "lap-contour-not-monotonic",
                message: format!(
                    "the contour turns back in {axis}; the LAP roughing cycle cuts along {axis} and cannot follow it"
                ).into(),
                label: "contour".into(),
                hint: Some("G85 and G86 need a contour that runs one way along the cut; rough the undercut with another cycle or by hand".into()),
            },
            LapStartInsideContour => Words {
                code: "lap-start-inside-contour",
                message: "the cycle starts inside the contour plus its allowance; the first pass would cut into the part".into(),
                label: "this call".into(),
                hint: Some("position the tool outside the stock before the call (above the largest diameter for outside turning)".into()),
            },
            LapWordOutOfRange { word, value, rule } => Words {
                code: "lap-word-out-of-range",
                message: format!("`{word}` is {value}; {rule}").into(),
                label: "this word".into(),
                hint: Some("D, DA=, DB= are depths per pass, greater than 0 (diameters on a G81 contour); U and W are allowances of 0 or more".into()),
            },
            LapConditionOrder { word, value, before, before_value, outside } => Words {
                code: "lap-condition-order",
                message: format!(
                "`{word}{value}` does not come after `{before}{before_value}` along the cut: {}",
                if *outside {
                    "outside, each change point must be smaller than the one before"
                } else {
                    "inside, each change point must be larger than the one before"
                }
            ).into(),
                label: "this word".into(),
                hint: Some("write the points in the order the cut meets them: start > XA= > XB= outside, start < XA= < XB= inside".into()),
            },
            LapConditionMisplaced { word, reason } => Words {
                code: "lap-condition-misplaced",
                message: format!("`{word}` does not apply here: {reason}").into(),
                label: "this word".into(),
                hint: None,
            },
            LapCallWord { command, address } => Words {
                code: "lap-call-word",
                message: format!("{command} cannot carry `{address}`; the control rejects it").into(),
                label: "not in a LAP call".into(),
                hint: Some("program S, T and M in a block before the LAP call".into()),
            },
            ProfileBackwards => Words {
                code: "profile-backwards",
                message: "the profile's end (`Q`) comes before its start (`P`)".into(),
                label: "this cycle".into(),
                hint: Some("`P` names the first block of the profile, `Q` the last".into()),
            },
            CycleNotSimulated { code } => Words {
                code: "cycle-not-simulated",
                message: format!("{code} is not simulated yet; its moves are missing from the toolpath").into(),
                label: "here".into(),
                hint: None,
            },
            NotExpandable { reason } => Words {
                code: "not-expandable",
                message: format!("this cycle is left as it is: {reason}").into(),
                label: "kept".into(),
                hint: None,
            },
            ManualRetract => Words {
                code: "manual-retract",
                message: "the cycle stops at the bottom of the hole for the operator to take the tool out by hand; the toolpath takes it straight out at the rapid rate".into(),
                label: "manual retract".into(),
                hint: None,
            },
            DrillPeckNotPositive => Words {
                code: "drill-peck-not-positive",
                message: "the depth of each peck is zero: the drill would never reach the bottom".into(),
                label: "peck depth".into(),
                hint: Some("give the depth of each peck (`Q`; on Haas `Q`, or `I` with `J` and `K`), or leave it out to drill in one feed".into()),
            },
            CorrectionTooLarge { shift_mm, max_mm } => Words {
                code: "correction-too-large",
                message: format!(
                "the machine model moves this block by {shift_mm:.4} mm, more than the {max_mm:.4} mm allowed; \
                 no compensated program is written"
            ).into(),
                label: format!("moved {:.1} µm", shift_mm * 1000.0).into(),
                hint: Some("check the machine model (units of its tables, signs of its effects) and the tool offsets; \
                 raise --max-shift only if the machine really is that far off".into()),
            },
            CompensatedOutsideTravel { x_mm, z_mm } => Words {
                code: "compensated-outside-travel",
                message: format!(
                "the compensated tool path leaves the machine's travel at X{:.4} Z{z_mm:.4} (diameter, mm); \
                 no compensated program is written",
                2.0 * x_mm
            ).into(),
                label: "this block".into(),
                hint: Some("move the part or the program away from the end of travel, or check the travel limits".into()),
            },
            CannotRewriteBlock { reason } => Words {
                code: "cannot-rewrite-block",
                message: format!("this block's motion must change for the machine model, but it cannot be rewritten: {reason}").into(),
                label: "this block".into(),
                hint: Some("write the block out for each time it runs (not in a subprogram or loop that runs it at \
                 different places), and without an automatic corner (`G75`/`G76`)".into()),
            },
            CycleNotCompensated { reason } => Words {
                code: "cycle-not-compensated",
                message: format!("this cycle stays as programmed and is not compensated: {reason}").into(),
                label: "not compensated".into(),
                hint: Some("program the thread passes as single-pass cycle blocks".into()),
            },
            AlreadyCompensated { model } => Words {
                code: "already-compensated",
                message: match model {
                    Some(model) => format!(
                        "this program is compensated already (for the machine model `{model}`): compensating it again \
                         takes the machine's errors out twice"
                    )
                    .into(),
                    None => "this program is compensated already: compensating it again \
                             takes the machine's errors out twice"
                        .into(),
                },
                label: "written by `turnpass compensate`".into(),
                hint: Some(
                    "compensate the nominal program (the one without this comment); give --force only if this \
                     program is to be compensated as it is"
                        .into(),
                ),
            },
            CompensationFailsCheck { deviation_mm, bound_mm, tolerance_mm, other_strategy } => Words {
                code: "compensation-fails-check",
                message: format!(
                    "the compensated program, read back and predicted on the model as `turnpass verify` predicts \
                     it, would cut this block {deviation_mm:.5} mm off the nominal part, more than the {bound_mm:.5} \
                     mm verify allows; no compensated program is written"
                )
                .into(),
                label: format!("off by {:.2} µm", deviation_mm * 1000.0).into(),
                hint: Some({
                    // The bound that accepts what was reached, on the micrometre above it.
                    let accepting = |mm: f64| (mm * 1000.0).ceil() / 1000.0;
                    let widen = format!(
                        "`--max-deviation {}` accepts this program if the part allows {deviation_mm:.5} mm",
                        accepting(*deviation_mm)
                    );
                    let strategy = match other_strategy {
                        Some((name, reached)) if reached <= bound_mm => {
                            format!("`--strategy {name}` meets the bound (largest {reached:.5} mm); or ")
                        }
                        Some((name, reached)) => format!(
                            "no --strategy meets the bound (the closest, `--strategy {name}`, reaches {reached:.5} \
                             mm); "
                        ),
                        None => String::new(),
                    };
                    if tolerance_mm > bound_mm {
                        format!(
                            "--tolerance {tolerance_mm} mm lets the written path stray further than verify allows: \
                             give a tolerance below {bound_mm:.5} mm; {strategy}{widen}"
                        )
                        .into()
                    } else {
                        format!(
                            "{strategy}{widen}; otherwise check the model, or run the program uncompensated \
                             (`compensate --report json` lists what each block reaches)"
                        )
                        .into()
                    }
                }),
            },
            ThreadLeadFailsCheck { lead_error_mm, bound_mm } => Words {
                code: "thread-lead-fails-check",
                message: format!(
                    "the compensated program, read back and predicted on the model as `turnpass verify` predicts \
                     it, would cut this thread with a lead that errs by {lead_error_mm:.5} mm over its length (the \
                     tool after each whole spindle turn along the axis from the helix of the programmed lead, placed \
                     to fit best), more than the {bound_mm:.5} mm verify allows; no compensated program is written"
                )
                .into(),
                label: format!("lead off by {:.2} µm over the thread", lead_error_mm * 1000.0).into(),
                hint: Some(
                    format!(
                        "each thread pass's lead is written for the slide's error along it: a kept thread \
                         cycle's lead word, a `G32` block's, an expanded cycle's thread moves' (a pass without a \
                         lead word of its own takes the one written before it); where the error is not uniform \
                         along the thread, a pass is written as consecutive thread blocks each with its own lead \
                         (Fanuc-compatible controls; a kept cycle cannot carry it, and OSP has no thread move to \
                         write), with --passes every pass, else only the passes that shape the finished thread; \
                         `--max-deviation {}` accepts this program if the thread allows {lead_error_mm:.5} mm",
                        (lead_error_mm * 1000.0 - 1e-9).ceil() / 1000.0
                    )
                    .into(),
                ),
            },
            CompensationChangesFeed => Words {
                code: "compensation-changes-feed",
                message: "the compensated program would cut this block with other feed or spindle words; no \
                          compensated program is written"
                    .into(),
                label: "this cut".into(),
                hint: Some("this is a defect of turnpass: please report it with the program and the model".into()),
            },
            CompensationLosesWord { word } => Words {
                code: "compensation-loses-word",
                message: format!(
                    "the compensated program would lose `{word}` here, or have it out of order, where verify checks \
                     every such word; no compensated program is written"
                )
                .into(),
                label: "this word".into(),
                hint: Some("this is a defect of turnpass: please report it with the program and the model".into()),
            },
            ProfileWordNotRun { word } => Words {
                code: "profile-word-not-run",
                message: format!(
                    "`{word}` is inside a profile that only a roughing cycle reads, so the control never runs it; \
                     the cycle must be written out to compensate it, and no written block can keep the word"
                )
                .into(),
                label: "never run".into(),
                hint: Some("move it out of the profile (before the cycle), or finish the profile with a G70 that runs \
                            it"
                .into()),
            },
            CompensationUnreadable { problem, nose_has_no_room } => Words {
                code: "compensation-unreadable",
                message: format!(
                    "the compensated program does not read back cleanly ({problem}); no compensated program is written"
                )
                .into(),
                label: "from here".into(),
                hint: Some(if *nose_has_no_room {
                    "the corrections move the contour where the nose has little room, and under nose-radius \
                     compensation (G41/G42) the control would refuse the moved contour: compensate the pass \
                     programmed for the tool's reference point (without G41/G42), or use a tool with a smaller nose \
                     radius"
                        .into()
                } else {
                    "this is a defect of turnpass: please report it with the program and the model".into()
                }),
            },
            CycleNeedsDepth => Words {
                code: "cycle-needs-depth",
                message: "the roughing cycle has no depth of cut".into(),
                label: "this cycle".into(),
                hint: Some("give the depth in a first block (`G71 U… R…`, `G72 W… R…`) or as `D` in the cycle block".into()),
            },
            MoveNeedsTooManySamples { samples, max } => Words {
                code: "move-needs-too-many-samples",
                message: format!(
                    "sampling this move takes {samples} samples at the spacing the model needs; turnpass samples \
                     a move at most {max} times"
                )
                .into(),
                label: "this move".into(),
                hint: Some("check the move's length and feed (a coordinate in the wrong unit or without its decimal \
                            point), or split it into shorter moves"
                    .into()),
            },
            PathNeedsTooManySamples { samples, max } => Words {
                code: "path-needs-too-many-samples",
                message: format!(
                    "plotting this program takes {samples} samples of its path at the spacing the model needs; a plot \
                     holds at most {max}"
                )
                .into(),
                label: "the samples pass the bound at this block".into(),
                hint: Some("plot a shorter program (its finishing passes), or check the moves' lengths and the \
                            cycles' depths of cut (a depth of one increment makes passes by the thousand)"
                    .into()),
            },
            ProgramCut => Words {
                code: "program-cut",
                message: "the text ends in the middle of a block, and the program has no end (M30, M02, M99): \
                          it looks cut off"
                    .into(),
                label: "the text ends here".into(),
                hint: Some("if the program is whole, end it with M30 (or M02) and a line break".into()),
            },
            DepthBelowIncrement { depth, increment } => Words {
                code: "depth-below-increment",
                message: format!(
                    "the depth of cut {depth} is less than the least increment {increment}: the control reads it as 0 \
                     and refuses the cycle"
                )
                .into(),
                label: "depth of cut".into(),
                hint: Some(format!("give a depth of at least {increment} (one increment)").into()),
            },
            EmptyProfile => Words {
                code: "empty-profile",
                message: "the profile named by `P`/`Q` has no moves".into(),
                label: "this cycle".into(),
                hint: None,
            },
            ProfileReverses { axis } => Words {
                code: "profile-reverses",
                message: format!("the profile turns back in {axis}; the roughing cycle cannot cut it").into(),
                label: "the profile turns back here".into(),
                hint: Some("split the profile, or rough the undercut with another cycle (G73)".into()),
            },
            ProfileNotMonotonic { axis } => Words {
                code: "profile-not-monotonic",
                message: format!("the profile is not monotonic in {axis}, which a Type I roughing cycle requires").into(),
                label: "the profile turns back here".into(),
                hint: Some("a Type II cycle allows pockets: name both X and Z (e.g. `W0`) in the profile's first block".into()),
            },
            StartOnWrongSide { x, z, axis, address, allowance, extreme } => {
                let (start, word) = (format!("X{} Z{}", short(*x), short(*z)), format!("{address}{}", short(*allowance)));
                let message = match (axis, *allowance < 0.0) {
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
                };
                let target = short(extreme + allowance);
                let extreme = short(*extreme);
                let example = if *axis == 'X' { format!("G00 X{target} Z{}", short(*z)) } else { format!("G00 X{} Z{target}", short(*x)) };
                let (place, bound, smallest, other) = match (axis, *allowance < 0.0) {
                    ('X', true) => ("an inside cut starts inside the bore", "or less", "smallest", "positive for an outside cut"),
                    ('X', false) => ("an outside cut starts outside the part", "or more", "largest", "negative for an inside cut"),
                    (_, true) => ("a cut from the -Z side starts behind the profile", "or less", "smallest", "positive for a cut from the +Z side"),
                    (_, false) => ("a cut from the +Z side starts in front of the profile", "or more", "largest", "negative for a cut from the -Z side"),
                };
                Words {
                    code: "start-on-wrong-side",
                    message: message.into(),
                    label: "this cycle".into(),
                    hint: Some(
                        format!(
                            "{place}: move the start point to {axis}{target} {bound} (the profile's {smallest} {axis}, \
                             {axis}{extreme}, with the allowance {word}), e.g. `{example}` before the cycle; \
                             or write {address} {other}"
                        )
                        .into(),
                    ),
                }
            }
            CycleNeedsDivisions => Words {
                code: "cycle-needs-divisions",
                message: "the pattern-repeating cycle has no number of passes".into(),
                label: "this cycle".into(),
                hint: Some("give the number of passes as `R` in a first block (`G73 U… W… R3`) \
                 or as `D` in the cycle block".into()),
            },
            GrooveStepMissing { axis } => Words {
                code: "groove-step-missing",
                message: format!("the groove is wider than one plunge but the cycle has no step in {axis} between plunges").into(),
                label: "this cycle".into(),
                hint: Some(format!(
                "give the step in {axis} (`Q` of G75 or `P` of G74 in least increments, Haas `K`/`I`), \
                 or end the groove where it starts"
            ).into()),
            },
            CycleTooManyPasses { passes, max } => Words {
                code: "cycle-too-many-passes",
                message: format!("this cycle would run {passes} passes; turnpass simulates at most {max}").into(),
                label: "this cycle".into(),
                hint: Some("check the depth of cut, step or number of passes".into()),
            },
            ThreadHeightBelowFirstDepth { height_mm, first_depth_mm } => Words {
                code: "thread-height-below-first-depth",
                message: format!(
                "the thread height ({height_mm:.4} mm) is smaller than the first depth of cut ({first_depth_mm:.4} mm)"
            ).into(),
                label: "thread height".into(),
                hint: Some("the height (`P` of the second G76 block, Haas `K`) is the full thread depth; \
                 the first depth (`Q`, Haas `D`) must not exceed it".into()),
            },
            ThreadLeadNotPositive => Words {
                code: "thread-lead-not-positive",
                message: "the thread lead is zero or negative".into(),
                label: "lead".into(),
                hint: Some("give the lead as a positive `F` (or `E`)".into()),
            },
            LeadShrinksToNothing => Words {
                code: "lead-shrinks-to-nothing",
                message: "the thread's lead shrinks to nothing before its end: the control stops with an alarm \
                 where it does"
                    .into(),
                label: "lead shrinks to nothing".into(),
                hint: Some("make the lead change smaller, the thread shorter or the starting lead larger: a lead \
                 that starts at L and shrinks by C every turn lasts L²/(2C) along the thread"
                    .into()),
            },
            ThreadOfNoLength => Words {
                code: "thread-of-no-length",
                message: "the thread has no length along its axis: each pass plunges to its depth and backs out \
                 at the thread's feed, and no thread is cut"
                    .into(),
                label: "thread of no length".into(),
                hint: Some("give the thread's end along its axis (`Z` or `W` for a thread along Z, `X` or `U` \
                 on a face)"
                    .into()),
            },
            ThreadParametersInvalid { word } => Words {
                code: "thread-parameters-invalid",
                message: format!("`{word}` is not a threading parameter this control takes").into(),
                label: "this word".into(),
                hint: Some("`G76 P` takes six digits: finishing passes 01-99, chamfer 00-99 (tenths of the lead), \
                 tool angle 80, 60, 55, 30, 29 or 00; Haas `P` is 1-4 and `A` 0-120".into()),
            },
            MissingSequence { number } => Words {
                code: "missing-sequence",
                message: format!("no block has sequence number N{number}").into(),
                label: "names no block".into(),
                hint: Some(format!("number the block this word means `N{number}`, or correct the number").into()),
            },
            DuplicateSequence { number, count } => Words {
                code: "duplicate-sequence",
                message: format!("{count} blocks have sequence number N{number}").into(),
                label: "names several blocks".into(),
                hint: Some("P and Q must each name exactly one block; renumber the others".into()),
            },
            RunawayProgram { blocks, moves, passes } => Words {
                code: "runaway-program",
                message: format!("the program ran {blocks} blocks ({moves} moves) without ending").into(),
                label: match passes {
                    Some(passes) => format!("this jump ran {passes} times").into(),
                    None => "here".into(),
                },
                hint: Some("check the loop's condition and the variables it changes".into()),
            },
            EndlessLoop { passes } => Words {
                code: "endless-loop",
                message: "this jump closes a loop that never ends".into(),
                label: format!("taken {passes} times, each time with the same variables, modes and position").into(),
                hint: Some(
                    "a control repeats this loop forever; change a variable its condition reads inside the loop \
                     (a counter: `V1=V1+1`, `#1=#1+1`), or end it another way"
                        .into(),
                ),
            },
            UnmatchedLoop { number } => Words {
                code: "unmatched-loop",
                message: format!("`DO{number}` has no `END{number}`").into(),
                label: "loop start".into(),
                hint: None,
            },
            MissingLabel { name } => Words {
                code: "missing-label",
                message: format!("no block is labelled `{name}`").into(),
                label: "jump".into(),
                hint: None,
            },
            MissingProgram { name } => Words {
                code: "missing-program",
                message: format!(
                    "`{name}` is not in this file; the control runs it from its memory and its moves are not simulated"
                ).into(),
                label: "call".into(),
                hint: Some("to simulate its moves, add the subprogram to the file".into()),
            },
            CallsTooDeep { max } => Words {
                code: "calls-too-deep",
                message: format!("subprogram calls nest deeper than {max}").into(),
                label: "here".into(),
                hint: Some("a subprogram probably calls itself".into()),
            },
            NoFeed => Words {
                code: "no-feed",
                message: "a feed move with no feed rate (or no spindle speed for feed per revolution)".into(),
                label: "no feed".into(),
                hint: Some("program F before the first feed move (and S for feed per revolution)".into()),
            },
            ArcRadiusTooSmall { radius_mm, half_chord_mm } => Words {
                code: "arc-radius-too-small",
                message: format!(
                "the arc radius {radius_mm:.4} mm cannot reach the end point (half the chord is {half_chord_mm:.4} mm)"
            ).into(),
                label: "this arc".into(),
                hint: Some("check the end point and the radius; R must be at least half the chord".into()),
            },
            ArcWithoutCentre => Words {
                code: "arc-without-centre",
                message: "the arc has neither a centre (`I`/`K`) nor a radius".into(),
                label: "this arc".into(),
                hint: Some("add `I`/`K` (centre from the start point) or the radius".into()),
            },
            ArcCentreMismatch { start_radius_mm, end_radius_mm } => Words {
                code: "arc-centre-mismatch",
                message: format!("the centre is {start_radius_mm:.4} mm from the start but {end_radius_mm:.4} mm from the end").into(),
                label: "this arc".into(),
                hint: Some("check `I`/`K`: they give the centre measured from the start point, I as a radius".into()),
            },
            CornerWithoutNextLine => Words {
                code: "corner-without-next-line",
                message: "the automatic corner has no straight move after it; the corner is left sharp".into(),
                label: "corner".into(),
                hint: None,
            },
            CornerDoesNotFit { size_mm, word } => Words {
                code: "corner-does-not-fit",
                message: format!("a {size_mm:.3} mm corner does not fit between these lines").into(),
                label: "corner".into(),
                hint: Some(format!("make `{word}` smaller than both lines").into()),
            },
            NotAllowedInProfile => Words {
                code: "not-allowed-in-profile",
                message: "a finishing profile may hold only moves and modal words".into(),
                label: "inside the profile".into(),
                hint: None,
            },
            ThreadRoughDepthBelowFirstCut { rough_depth, first_depth } => Words {
                code: "thread-rough-depth-below-first-cut",
                message: format!(
                "with infeed pattern 1 the depth to rough, H − U = {}, is less than the first cut D = {}",
                short(*rough_depth),
                short(*first_depth)
            ).into(),
                label: "deeper than H − U".into(),
                hint: Some("make `D` at most `H − U`, or choose infeed pattern 2 or 3 (`M74`, `M75`)".into()),
            },
            ThreadAllowanceOverHeight { height, allowance } => Words {
                code: "thread-allowance-over-height",
                message: format!(
                "the finishing allowance {} is larger than the thread height H = {}",
                short(*allowance),
                short(*height)
            ).into(),
                label: "larger than H".into(),
                hint: Some("the allowance must be at most the thread height `H`".into()),
            },
            InfeedAngleOutOfRange { angle } => Words {
                code: "infeed-angle-out-of-range",
                message: format!("the infeed angle B = {}° is outside 0 ≤ B < 180", short(*angle)).into(),
                label: "infeed angle".into(),
                hint: Some("`B` is the tool's included angle: 60 for metric threads, 55 for Whitworth, 0 for radial infeed".into()),
            },
            ThreadDepthNotPositive { address } => Words {
                code: "thread-depth-not-positive",
                message: match address {
                    'H' => "the thread height `H` is not positive".into(),
                    _ => format!("the thread cycle's first depth of cut `{address}` is not positive").into(),
                },
                label: "not positive".into(),
                hint: Some(format!("give `{address}` as a positive diameter, for example `{address}0.4`").into()),
            },
            TooManyPasses { passes, max } => Words {
                code: "too-many-passes",
                message: format!("this cycle would cut {passes} passes; the simulation stops at {max}").into(),
                label: "this cycle".into(),
                hint: Some("check `D` against the thread height `H`".into()),
            },
            InfeedPatternApproximated => Words {
                code: "infeed-pattern-approximated",
                message: "with D² < H² − (H − U)² the control chooses its own pass depths for infeed pattern 3; simulated with D·√n".into(),
                label: "pattern 3".into(),
                hint: Some("a larger first depth `D` (D² ≥ H² − (H − U)²) makes the pass depths the documented D·√n".into()),
            },
            CycleNeedsShift { shift, axis } => Words {
                code: "cycle-needs-shift",
                message: format!("the cycle ends at another {axis} than it starts, and has no `{shift}` to step there").into(),
                label: "off the start line".into(),
                hint: Some(format!("give the shift per pass `{shift}`, or start the cycle on the end line").into()),
            },
            ThreadContourNotStraight => Words {
                code: "thread-contour-not-straight",
                message: "a continuous thread contour may hold only straight thread elements after its approach".into(),
                label: "in the thread contour".into(),
                hint: Some("cut the thread with G71/G72, or split the contour at the arc".into()),
            },
            BadVariableNumber { value } => Words {
                code: "bad-variable-number",
                message: format!("{value} is not a variable number").into(),
                label: "variable".into(),
                hint: None,
            },
            NotAVariable => Words {
                code: "not-a-variable",
                message: "only a variable can be assigned".into(),
                label: "variable".into(),
                hint: None,
            },
            SystemVariableUnknown { name } => Words {
                code: "system-variable-unknown",
                message: format!("{name} holds machine state the simulation does not have; read as 0").into(),
                label: "variable".into(),
                hint: None,
            },
            UndefinedVariable { name } => Words {
                code: "undefined-variable",
                message: format!("{name} is used before it is set").into(),
                label: "variable".into(),
                hint: Some("set it earlier in the program or pass it in the call".into()),
            },
            MachineVariableUnknown { name } => Words {
                code: "machine-variable-unknown",
                message: format!("{name} is a common variable the machine keeps; the program reads it before setting it, so its value comes from the machine").into(),
                label: "value from the machine".into(),
                hint: Some(format!("it is read as vacant (0 in arithmetic); give its value in the model file, `[machine] variables = {{ \"{name}\" = 350.0 }}`, or on the command line, `--var '{name}=350'`").into()),
            },
            SurfaceSpeedUnclamped { max_rpm, assumed } => Words {
                code: "surface-speed-unclamped",
                message: format!(
                    "constant surface speed with no `G50 S` clamp: toward the centre the spindle runs at the machine's maximum, {max_rpm:.0} rpm{}",
                    if *assumed { " (assumed: the settings give no `max_spindle_rpm`)" } else { "" }
                )
                .into(),
                label: "spindle at its maximum".into(),
                hint: Some("program the clamp before `G96` (`G50 S2000`; `G92 S` in G-code systems B and C)".into()),
            },
            ThreadUnderSurfaceSpeed => Words {
                code: "thread-under-surface-speed",
                message: "a thread cut under constant surface speed (`G96`): the spindle speed changes with the diameter of each pass".into(),
                label: "thread under G96".into(),
                hint: Some("cut threads at a constant spindle speed: `G97 S…` before the thread".into()),
            },
            ImplausibleFeed { feed, per_revolution, inch } => {
                let unit = match (per_revolution, inch) {
                    (true, false) => "mm/rev",
                    (true, true) => "in/rev",
                    (false, false) => "mm/min",
                    (false, true) => "in/min",
                };
                Words {
                    code: "implausible-feed",
                    message: format!("a feed of {feed} {unit} is far outside what lathes cut at").into(),
                    label: "implausible feed".into(),
                    hint: Some(if *per_revolution {
                        "is this a feed per minute? program `G98` (`G94` in G-code systems B and C) before it".into()
                    } else {
                        "is this a feed per revolution? program `G99` (`G95` in G-code systems B and C) before it".into()
                    }),
                }
            }
            ThreadStartAngleNotKept { degrees } => Words {
                code: "thread-start-angle-not-kept",
                message: format!("this repeat of the thread cycle writes no start angle: it starts at the spindle's index, not {degrees}° past it as the block before did").into(),
                label: "no `Q`".into(),
                hint: Some(format!("the start angle (`Q`) holds for its own block only; to cut this pass on the same start, write `Q{}` on it", (degrees * 1000.0).round()).into()),
            },
            CycleSelectedAlone { code } => Words {
                code: "cycle-selected",
                message: format!("`{code}` with no `X`/`Z` selects its single cycle without running it; blocks with only `X`/`Z` after it run the cycle").into(),
                label: "cycle selected".into(),
                hint: Some(format!("if `{code}` means something else on this control (absolute positions, feed per minute), it uses another G-code system: set `gcode_system` in the machine settings").into()),
            },
            CycleOutOfPlane { code } => Words {
                code: "cycle-out-of-plane",
                message: format!("{code} drills along X with a live tool, off the XZ plane of the turned part; its moves are left out of the toolpath").into(),
                label: "side drilling".into(),
                hint: None,
            },
            DivisionByZero => Words {
                code: "division-by-zero",
                message: "division by zero".into(),
                label: "this value".into(),
                hint: None,
            },
            FunctionDomain { function, argument } => Words {
                code: "function-domain",
                message: format!("{function} is not defined at {argument}").into(),
                label: "this value".into(),
                hint: None,
            },
        }
    }

    /// A stable identifier for tools and JSON output.
    pub fn code(&self) -> &'static str {
        self.words().code
    }

    pub fn message(&self) -> String {
        self.words().message.into_owned()
    }

    /// The short text under the primary label.
    pub fn label(&self) -> String {
        self.words().label.into_owned()
    }

    pub fn hint(&self) -> Option<String> {
        self.words().hint.map(Cow::into_owned)
    }
}

/// A program value as a machinist writes it: up to four decimals, no trailing zeros.
/// A name with its first letter in upper case (`Haas`).
fn capitalised(name: &str) -> String {
    let mut chars = name.chars();
    chars.next().map_or(String::new(), |first| first.to_uppercase().chain(chars).collect())
}

fn short(value: f64) -> String {
    let text = format!("{value:.4}");
    let text = if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.') } else { &text };
    if text == "-0" { "0".to_string() } else { text.to_string() }
}

/// How many more blocks an assumed-stock finding stands for: said once for the run, at the
/// deepest.
fn more_blocks(others: u32, what: &str) -> String {
    match others {
        0 => String::new(),
        1 => format!("; one other block's {what} would too, less deep"),
        n => format!("; {n} other blocks' {what} would too, less deep"),
    }
}
