//! The typed, spanned AST of a program.
//!
//! A [`Program`] is a list of [`Block`]s that tile the source: block *i* covers its text, the
//! bytes up to block *i + 1* are exactly one line terminator, and the last block runs to the
//! end of the source or to its final terminator. Printing an untouched block is therefore
//! a copy of its bytes, which is what makes `fmt` lossless.
//!
//! Nodes live in flat arenas owned by the program (words, expressions, typed command
//! parameters) and refer to each other by index, so a block costs a few dozen bytes and the
//! parser allocates only when an arena grows.
//!
//! ```txt
//! source:  N20G0X0\nG3X2.5Z-1.25R1.2498F.008\n
//! blocks:  [0..7) Motion     [8..33) Motion
//! words:   N20 G0 X0 | G3 X2.5 Z-1.25 R1.2498 F.008
//! ```

use std::fmt;

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::{Address, Code, DialectConfig, Role, SchemaId};
use crate::source::Span;

/// Index of a word in [`Program::words`].
pub type WordId = u32;
/// Index of an expression node in [`Program::exprs`].
pub type ExprId = u32;
/// Index of a typed command in [`Program::commands`].
pub type CommandId = u32;

/// An exact decimal as written: `mantissa × 10^-scale`, with the spelling details a printer
/// needs to write it back the same way.
///
/// Packed to 4-byte alignment so that a word holding a number is 24 bytes, not 32: the AST
/// budget is 150 bytes per block on a 50 MB program. Fields are read by value.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
#[repr(C, packed(4))]
pub struct Number {
    pub mantissa: i64,
    /// Digits after the decimal point.
    pub scale: u8,
    pub flags: NumberFlags,
}

/// How a number was spelled.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct NumberFlags(u8);

impl NumberFlags {
    pub const POINT: NumberFlags = NumberFlags(1);
    pub const PLUS: NumberFlags = NumberFlags(2);
    /// Minus sign written (keeps `-0.` distinct from `0.`).
    pub const MINUS: NumberFlags = NumberFlags(4);
    /// No digit before the point (`.075`).
    pub const NO_INTEGER_DIGITS: NumberFlags = NumberFlags(8);
    /// Leading zeros before the first significant digit (`S0600`, `N01`).
    pub const LEADING_ZEROS: NumberFlags = NumberFlags(16);

    pub fn contains(self, other: NumberFlags) -> bool {
        self.0 & other.0 == other.0
    }

    pub fn insert(&mut self, other: NumberFlags) {
        self.0 |= other.0;
    }
}

impl Number {
    /// Whether the value is a whole number. A scale past what `i64` can hold as a power of
    /// ten (19 places and more) is whole only for a zero mantissa: every non-zero mantissa
    /// is smaller than that power.
    pub fn is_whole(&self) -> bool {
        let (mantissa, scale) = (self.mantissa, self.scale);
        // A last digit other than zero decides most numbers with decimals without the
        // division by a power of ten that is not a constant (the printer asks of millions).
        scale == 0
            || (mantissa % 10 == 0
                && Number::power_of_ten(scale).map_or(mantissa == 0, |p| mantissa.unsigned_abs() % p == 0))
    }

    /// `10^scale` for every scale whose power fits `u64`; a larger power is above every
    /// mantissa. A table rather than `u64::pow`, whose loop showed in profiles.
    pub fn power_of_ten(scale: u8) -> Option<u64> {
        const POWERS: [u64; 20] = {
            let mut powers = [1; 20];
            let mut n = 1;
            while n < 20 {
                powers[n] = powers[n - 1] * 10;
                n += 1;
            }
            powers
        };
        POWERS.get(usize::from(scale)).copied()
    }

    pub fn new(mantissa: i64, scale: u8, has_point: bool) -> Number {
        let mut flags = NumberFlags::default();
        if has_point {
            flags.insert(NumberFlags::POINT);
        }
        if mantissa < 0 {
            flags.insert(NumberFlags::MINUS);
        }
        Number { mantissa, scale, flags }
    }

    pub fn has_point(self) -> bool {
        self.flags.contains(NumberFlags::POINT)
    }

    pub fn is_negative(self) -> bool {
        self.flags.contains(NumberFlags::MINUS)
    }

    /// The value as `f64`, for geometry; the exact value stays in the mantissa.
    pub fn to_f64(self) -> f64 {
        // Up to 10^22 the powers of ten are exact in f64, and `powi` (which multiplies exact
        // powers whose products stay exact) gives those same values: the table only saves
        // the call, which every coordinate word pays.
        const POWERS_OF_TEN: [f64; 23] = [
            1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18,
            1e19, 1e20, 1e21, 1e22,
        ];
        let scale = self.scale;
        let divisor = POWERS_OF_TEN.get(scale as usize).copied().unwrap_or_else(|| 10f64.powi(scale as i32));
        self.mantissa as f64 / divisor
    }

    /// Significant digits as the address limits count them: the integer part without
    /// leading zeros, plus every digit after the point (`0.05` has 2, `12.5` has 3).
    pub fn significant_digits(self) -> usize {
        let mantissa = self.mantissa;
        let digits = if mantissa == 0 { 0 } else { mantissa.unsigned_abs().ilog10() as usize + 1 };
        digits.max(self.scale as usize)
    }

    /// The value if it is a whole number that fits `u32` (sequence numbers, codes, counts).
    pub fn as_whole(self) -> Option<u32> {
        if self.mantissa < 0 {
            return None;
        }
        let divisor = 10i64.checked_pow(self.scale as u32)?;
        if self.mantissa % divisor != 0 {
            return None;
        }
        u32::try_from(self.mantissa / divisor).ok()
    }
}

impl fmt::Debug for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", crate::printer::number::plain(*self))
    }
}

// The AST memory budget depends on these sizes; see `Program::heap_bytes`.
const _: () = assert!(std::mem::size_of::<Number>() == 12);
const _: () = assert!(std::mem::size_of::<Word>() == 24);
const _: () = assert!(std::mem::size_of::<Block>() == 24);
const _: () = assert!(std::mem::size_of::<Expr>() == 24);

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CommentKind {
    /// `( … )`
    Paren,
    /// `; …` to the end of the line.
    Semicolon,
}

/// A word of a block. Every word has the span of its text; names (sequence names, program
/// names, variables) are read from the source through that span rather than copied.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Word {
    pub span: Span,
    pub kind: WordKind,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WordKind {
    /// `N0207`, `NLAP1`: the block's sequence name. `number` is its value when numeric.
    Sequence {
        number: Option<u32>,
    },
    /// `/` or `/2` at the start of the block.
    BlockDelete {
        level: u8,
    },
    /// Fanuc: `/` inside a block, which skips the rest of the block when block delete is on.
    OptionalSkip {
        level: u8,
    },
    /// `%` tape mark.
    TapeMark,
    /// `$NAME.MIN%` Okuma file header.
    Header,
    /// `O0137`, `O2005`, `:0100`, `OSTRT`: the program's name (text via the span).
    ProgramName,
    Comment(CommentKind),
    /// `G01`, `M03`: a code.
    Code {
        letter: CodeLetter,
        code: Code,
    },
    /// `X10.5`, `TG=01`: an address with a literal value.
    Number {
        address: Address,
        number: Number,
    },
    /// `X=FLAN+5` (OSP), `X[#1+2]`, `X#5`, `X-#5` (Fanuc): an address with an expression.
    Expr {
        address: Address,
        expr: ExprId,
    },
    /// An `N` name used as an operand: the contour of `G85 N0207`, the target of `GOTO NDTM`.
    Label {
        number: Option<u32>,
    },
    /// A program name used as an operand: `CALL OSUB`, `MODIN OINT1`.
    ProgramRef,
    /// `IF`, `GOTO`, `CALL`, `DEF`, … (index into the dialect's keyword table).
    Keyword {
        index: u16,
    },
    /// An expression operand of a keyword: the `[..]` of `IF`/`WHILE`, the target of a Fanuc
    /// `GOTO`, the loop number of `DO1`/`END1`.
    Operand {
        expr: ExprId,
    },
    /// `NAME=expr`, `V1=expr`, `#1=expr`, `VTOFX[16]=expr`.
    Assign {
        target: ExprId,
        value: ExprId,
    },
    /// Arguments kept as text (graphics statements such as `PT LF,LC,[0,0]`).
    Verbatim,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CodeLetter {
    G,
    M,
}

impl CodeLetter {
    pub fn as_char(self) -> char {
        match self {
            CodeLetter::G => 'G',
            CodeLetter::M => 'M',
        }
    }
}

/// An expression node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Expr {
    pub span: Span,
    pub kind: ExprKind,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ExprKind {
    Number(Number),
    Variable(Variable),
    Unary {
        op: UnaryOp,
        operand: ExprId,
    },
    Binary {
        op: BinaryOp,
        lhs: ExprId,
        rhs: ExprId,
    },
    /// A function call: `SIN[30]`, `ATAN2[A,B]`; `function` indexes the dialect's list.
    Call {
        function: u8,
        args: [ExprId; 2],
        arg_count: u8,
    },
    /// `[ … ]` grouping, kept so the printer writes the brackets back.
    Group(ExprId),
}

/// A variable reference. Names are read through the node's span.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Variable {
    /// OSP common variable `V12` (lathe).
    Common(u32),
    /// OSP named variable: local (`FLAN`), machining-centre common (`VC32`) or system (`VZOFZ`).
    Named,
    /// OSP indexed system variable `VTOFX[16]`; `name` spans the name before `[`.
    Indexed { name: Span, index: ExprId },
    /// Fanuc macro variable `#501`, `#[#1+2]`.
    Hash { index: ExprId },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnaryOp {
    Minus,
    Plus,
    Not,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinaryOp {
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    And,
    Or,
    Xor,
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
}

impl BinaryOp {
    pub fn symbol(self, xor_word: &'static str) -> &'static str {
        match self {
            BinaryOp::Add => "+",
            BinaryOp::Sub => "-",
            BinaryOp::Mul => "*",
            BinaryOp::Div => "/",
            BinaryOp::Mod => "MOD",
            BinaryOp::And => "AND",
            BinaryOp::Or => "OR",
            BinaryOp::Xor => xor_word,
            BinaryOp::Eq => "EQ",
            BinaryOp::Ne => "NE",
            BinaryOp::Gt => "GT",
            BinaryOp::Ge => "GE",
            BinaryOp::Lt => "LT",
            BinaryOp::Le => "LE",
        }
    }

    /// Binding strength: comparisons bind loosest, then `+ - OR XOR`, then `* / AND MOD`.
    pub fn precedence(self) -> u8 {
        match self {
            BinaryOp::Eq | BinaryOp::Ne | BinaryOp::Gt | BinaryOp::Ge | BinaryOp::Lt | BinaryOp::Le => 1,
            BinaryOp::Add | BinaryOp::Sub | BinaryOp::Or | BinaryOp::Xor => 2,
            BinaryOp::Mul | BinaryOp::Div | BinaryOp::And | BinaryOp::Mod => 3,
        }
    }

    /// Whether the operator is written as a word, which needs spaces around it.
    pub fn is_word(self) -> bool {
        !matches!(self, BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Div)
    }
}

/// A command with typed parameters: a canned cycle, a LAP call, a dwell, a one-shot such as
/// `G28` or `G50`. Its schema form (from `grammar/`) gave every word a [`Role`].
#[derive(Debug, Clone, PartialEq)]
pub struct Command {
    /// The G word that names the command.
    pub code_word: WordId,
    pub schema: SchemaId,
    /// Index of the chosen form in the schema.
    pub form: u8,
    pub params: Vec<Param>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Param {
    pub role: Role,
    pub word: WordId,
}

impl Command {
    /// The word playing `role`, if the block has one.
    pub fn param(&self, role: Role) -> Option<WordId> {
        self.params.iter().find(|p| p.role == role).map(|p| p.word)
    }
}

/// What a block does, decided from its own words. The words stay the full truth: a motion
/// block may also change tool, spindle and coolant.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Statement {
    /// Blank line, comment only, or a sequence name alone (an OSP label line such as `NAT00`).
    Empty,
    /// `%`, optionally with a program name on the same line.
    TapeMark,
    /// `$NAME.MIN%`.
    Header,
    /// `O1234`, `:0100`, `OSTRT`.
    ProgramName,
    /// `G00`–`G03`, or axis words under the modal motion (`X2.0`).
    Motion,
    /// Fanuc `G32`/`G33`: a thread-cutting move.
    ThreadMove,
    /// A canned cycle with typed parameters.
    Cycle(CommandId),
    /// An OSP LAP call (`G85 N0207 …`).
    LapCall(CommandId),
    /// An OSP LAP contour marker (`G81`, `G82`, `G83`, `G80`).
    LapMarker(CommandId),
    Dwell(CommandId),
    /// A one-shot command with words (`G28 U0 W0`, `G50 S1800`, `G53 X0`).
    OneShot(CommandId),
    /// A tool call and nothing that moves (`T0404`, `G00T0405` is a motion).
    ToolCall,
    /// Spindle speed or mode and nothing that moves (`G96S750M03`).
    Spindle,
    /// `IF`, `GOTO`, `CALL`, `RTS`, `MODIN`, `WHILE`, … (the keyword word tells which).
    Control,
    /// One or more assignments (`FLAN=318`, `VTOFX[16]=VTOFX[6]VTOFZ[16]=…`).
    Assignment,
    /// OSP graphics and similar pass-through statements (`DEF WORK`, `PT …`, `DRAW`).
    Graphics,
    /// OSP machining-centre hole pattern (`BHC …`).
    Pattern,
    /// Modal G-codes, M codes, F or other words that neither move nor call anything.
    Settings,
    /// Text that does not parse; printed back verbatim. The diagnostic says why.
    Invalid,
    /// Everything after the tape's closing `%` (or a DOS Ctrl-Z), which controls ignore;
    /// printed verbatim.
    Trailing,
    /// A line of a tape leader: text before the first `%` and any program text, which
    /// controls skip; printed verbatim.
    Leader,
}

/// One block: usually one line, several with OSP `$` continuation lines.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Block {
    /// The block's text without its line terminator.
    pub span: Span,
    pub statement: Statement,
    pub(crate) first_word: u32,
    pub(crate) word_count: u16,
}

impl Block {
    pub fn word_ids(&self) -> std::ops::Range<WordId> {
        self.first_word..self.first_word + self.word_count as u32
    }
}

/// A parsed program: blocks and the arenas they refer to, over the source they came from.
///
/// Only the parser builds a `Program`, so its spans are known to index its source and its
/// blocks to tile it; the printer relies on both.
#[derive(Clone)]
pub struct Program<'src> {
    pub(crate) source: &'src [u8],
    pub(crate) config: DialectConfig,
    pub(crate) blocks: Vec<Block>,
    pub(crate) words: Vec<Word>,
    /// The words after `words`, their ids going on from `words.len()`: a large program is
    /// parsed in two runs of lines on two threads, and the second run's words stay in the
    /// arena it filled rather than being copied behind the first's. A block's words lie in
    /// one arena. Empty for every other program.
    pub(crate) later_words: Vec<Word>,
    pub(crate) exprs: Vec<Expr>,
    pub(crate) commands: Vec<Command>,
}

/// The program as one list of words, however many arenas hold them: a program parsed in two
/// runs reads the same as one parsed in one.
impl std::fmt::Debug for Program<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        struct Words<'a>(&'a [Word], &'a [Word]);
        impl std::fmt::Debug for Words<'_> {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.debug_list().entries(self.0.iter().chain(self.1)).finish()
            }
        }
        f.debug_struct("Program")
            .field("source", &self.source)
            .field("config", &self.config)
            .field("blocks", &self.blocks)
            .field("words", &Words(&self.words, &self.later_words))
            .field("exprs", &self.exprs)
            .field("commands", &self.commands)
            .finish()
    }
}

impl<'src> Program<'src> {
    /// A program of `source` with no blocks yet, its block and word lists reserved by the
    /// caller (`parse` reserves them for the whole program, `parse_part` for one run).
    pub(crate) fn empty(source: &'src [u8], config: DialectConfig, blocks: Vec<Block>, words: Vec<Word>) -> Self {
        Program { source, config, blocks, words, later_words: Vec::new(), exprs: Vec::new(), commands: Vec::new() }
    }

    pub fn source(&self) -> &'src [u8] {
        self.source
    }

    pub fn config(&self) -> DialectConfig {
        self.config
    }

    pub fn blocks(&self) -> &[Block] {
        &self.blocks
    }

    /// A warning when no block holds anything the control runs (the file is empty, or holds
    /// only blank lines, comments, tape marks, a header and the program's name): `check`
    /// warns, and a command that writes a program from it refuses.
    pub fn nothing_to_run(&self) -> Option<Diagnostic> {
        let runs_nothing = self.blocks.iter().all(|block| {
            matches!(
                block.statement,
                Statement::Empty
                    | Statement::TapeMark
                    | Statement::Header
                    | Statement::ProgramName
                    | Statement::Trailing
            )
        });
        runs_nothing.then(|| Diagnostic::warning(DiagnosticKind::EmptyProgram, Span::new(0, 0)))
    }

    pub fn block(&self, index: usize) -> &Block {
        &self.blocks[index]
    }

    pub fn word(&self, id: WordId) -> &Word {
        let id = id as usize;
        match id.checked_sub(self.words.len()) {
            None => &self.words[id],
            Some(later) => &self.later_words[later],
        }
    }

    pub fn words_of(&self, block: &Block) -> &[Word] {
        let (start, end) = (block.first_word as usize, block.first_word as usize + block.word_count as usize);
        match start.checked_sub(self.words.len()) {
            None => &self.words[start..end],
            Some(later) => &self.later_words[later..end - self.words.len()],
        }
    }

    pub fn expr(&self, id: ExprId) -> &Expr {
        &self.exprs[id as usize]
    }

    pub fn command(&self, id: CommandId) -> &Command {
        &self.commands[id as usize]
    }

    /// The text of a span.
    pub fn text(&self, span: Span) -> &'src [u8] {
        span.text(self.source)
    }

    /// The bytes between a block's text and the next block: its line terminator, if any.
    pub fn terminator(&self, index: usize) -> &'src [u8] {
        let end = self.blocks[index].span.end as usize;
        let next = self.blocks.get(index + 1).map_or(self.source.len(), |b| b.span.start as usize);
        &self.source[end..next]
    }

    /// The block's sequence name word, if it has one.
    pub fn sequence(&self, block: &Block) -> Option<&Word> {
        self.words_of(block).iter().find(|w| matches!(w.kind, WordKind::Sequence { .. }))
    }

    /// The first word with this address and a literal value.
    pub fn number_of(&self, block: &Block, address: Address) -> Option<Number> {
        self.words_of(block).iter().find_map(|w| match w.kind {
            WordKind::Number { address: a, number } if a == address => Some(number),
            _ => None,
        })
    }

    /// Heap bytes held by the AST (not counting the source), for the memory budget.
    pub fn heap_bytes(&self) -> usize {
        self.blocks.capacity() * std::mem::size_of::<Block>()
            + (self.words.capacity() + self.later_words.capacity()) * std::mem::size_of::<Word>()
            + self.exprs.capacity() * std::mem::size_of::<Expr>()
            + self.commands.capacity() * std::mem::size_of::<Command>()
            + self.commands.iter().map(|c| c.params.capacity() * std::mem::size_of::<Param>()).sum::<usize>()
    }
}
