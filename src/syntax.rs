//! The front end: program bytes to a typed, spanned AST.
//!
//! **Invariant: parsing never fails.** [`parse`] returns a [`Program`] and its diagnostics
//! for any input. A block that does not parse becomes an `Invalid` block with one
//! diagnostic, and the next block parses normally, because the newline is the
//! synchronisation point (and OSP `$` continuation lines join the block before them).
//!
//! **Invariant: blocks tile the source.** Block *i* covers its text, the bytes up to block
//! *i + 1* are exactly its line terminator, and everything after a tape's closing `%` is one
//! `Trailing` block. The printer copies untouched blocks byte for byte on that basis.

pub(crate) mod ast;
mod block;
mod classify;
mod expr;
mod lexer;
pub(crate) mod relocate;
pub mod spelling;
mod text;

pub use ast::{
    BinaryOp, Block, CodeLetter, Command, CommandId, CommentKind, Expr, ExprId, ExprKind, Number, NumberFlags, Param,
    Program, Statement, UnaryOp, Variable, Word, WordId, WordKind,
};
pub use text::Text;

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::detect::{self, Detection, Leaning};
use crate::dialect::{Control, Dialect, DialectChoice, DialectConfig, GCodeSystem, MachineKind};
use crate::source::Span;

use block::BlockParser;
use classify::Classifier;

/// How to read a program. There is no `Default`: the G-code system is a machine setting and
/// every caller must say where it came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ParseOptions {
    pub dialect: DialectChoice,
    pub gcode_system: GCodeSystem,
    /// `None` decides from the text (OSP lathe or machining centre).
    pub machine_kind: Option<MachineKind>,
    /// The Fanuc-compatible control (a machine setting, as the G-code system is).
    pub control: Control,
}

/// A parsed program with everything the front end found wrong with it.
#[derive(Debug, Clone)]
pub struct Parsed<'src> {
    pub program: Program<'src>,
    /// Sorted by position.
    pub diagnostics: Vec<Diagnostic>,
    pub detection: Detection,
}

impl Parsed<'_> {
    pub fn has_errors(&self) -> bool {
        self.diagnostics.iter().any(Diagnostic::is_error)
    }

    pub fn error_count(&self) -> usize {
        self.diagnostics.iter().filter(|d| d.is_error()).count()
    }
}

const BYTE_ORDER_MARK: &[u8] = b"\xEF\xBB\xBF";

/// Parse a program. Never fails; see the module documentation.
pub fn parse<'src>(source: &'src [u8], options: &ParseOptions) -> Parsed<'src> {
    let given = match options.dialect {
        DialectChoice::Fixed(dialect) => Some(dialect),
        DialectChoice::Auto => None,
    };
    let detection = detect::decide(source, given, options.machine_kind);
    let config = DialectConfig::new(detection.dialect, options.gcode_system, detection.machine_kind)
        .with_control(options.control);
    let mut diagnostics = detection_diagnostics(&detection);

    if source.len() >= u32::MAX as usize {
        diagnostics.push(Diagnostic::error(DiagnosticKind::SourceTooLarge, Span::new(0, 0)));
        let program = Program {
            source,
            config,
            blocks: Vec::new(),
            words: Vec::new(),
            later_words: Vec::new(),
            exprs: Vec::new(),
            commands: Vec::new(),
        };
        return Parsed { program, diagnostics, detection };
    }
    let split = if source.len() >= crate::parallel::tuning().parse_bytes { split_point(source) } else { None };
    let program = parse_lines(source, config, split, &mut diagnostics);
    diagnostics.sort_by_key(|d| (d.span.start, d.span.end));
    Parsed { program, diagnostics, detection }
}

/// Where a second run of lines may start near the middle of `source`: after a line feed,
/// before a line that is not an OSP `$` continuation (nor a `$…%` header). Every such place
/// starts a new block in a parse from the top, whatever the lines before it say.
fn split_point(source: &[u8]) -> Option<usize> {
    let middle = source.len() / 2;
    let mut from = middle;
    while let Some(at) = memchr::memchr(b'\n', source.get(from..)?) {
        let split = from + at + 1;
        match source.get(split) {
            None => return None,
            Some(b'$') => from = split,
            Some(_) => return Some(split),
        }
    }
    None
}

/// Parse every line of `source`, adding the parser's diagnostics to `diagnostics` in the
/// order of the lines. With a `split`, the lines from there on are parsed on a second
/// thread beside the lines before it, and the two runs are joined: the program and the
/// diagnostics are those of one run from the top (`split` must be a place `split_point`
/// gives).
pub(crate) fn parse_lines<'src>(
    source: &'src [u8],
    config: DialectConfig,
    split: Option<usize>,
    diagnostics: &mut Vec<Diagnostic>,
) -> Program<'src> {
    // Lines average 20-30 bytes in real and generated programs: the block arena has room
    // for all of them, the second run's included.
    let block_capacity = source.len() / 16 + 1;
    let (mut program, end) = match split {
        None => {
            let run = Run::parse(source, 0, config, Tape::Before, block_capacity);
            diagnostics.extend(run.diagnostics);
            (run.program, run.end)
        }
        Some(split) => {
            // The second run assumes the tape is open where it starts, as it is in every
            // program with a `%` at its top; the first run says whether it was.
            let (first, second) = crate::parallel::join(
                || Run::parse(&source[..split], 0, config, Tape::Before, block_capacity),
                || Run::parse(source, split, config, Tape::Open, 1),
            );
            let mut program = first.program;
            program.source = source;
            diagnostics.extend(first.diagnostics);
            match first.end {
                // The tape closed in the first run: the rest of the text is trailing.
                end @ (Tape::Closed, _) => (program, end),
                (tape, _) => {
                    // Before the tape the lines parse as inside it up to the first tape mark,
                    // which opens the tape rather than closing it; a second run that met one
                    // is parsed again from the right state.
                    // Before any program text the second run's lines may be a leader.
                    let reparse = tape == Tape::Before || (tape == Tape::Unmarked && second.end.0 == Tape::Closed);
                    let second = if reparse { Run::parse(source, split, config, tape, 1) } else { second };
                    diagnostics.extend(second.diagnostics);
                    program.append(second.program);
                    (program, second.end)
                }
            }
        }
    };
    if let (Tape::Closed, Some(next)) = end
        && next < source.len()
    {
        // Controls stop reading at the closing `%`; keep the rest verbatim.
        let span = Span::new(next as u32, source.len() as u32);
        program.blocks.push(ast::Block { span, statement: ast::Statement::Trailing, first_word: 0, word_count: 0 });
    }
    // Growth doubles the arenas; give back what the program does not use.
    program.blocks.shrink_to_fit();
    program.words.shrink_to_fit();
    program.later_words.shrink_to_fit();
    program.exprs.shrink_to_fit();
    program
}

impl Program<'_> {
    /// Put the blocks of `later`, a run of the lines after ours over the same source (its
    /// spans already index it), behind ours: its ids move past ours, its words stay in the
    /// arena it filled.
    fn append(&mut self, later: Program<'_>) {
        let bases = relocate::Bases {
            offset: 0,
            word: (self.words.len() + self.later_words.len()) as u32,
            expr: self.exprs.len() as u32,
            command: self.commands.len() as u32,
        };
        self.blocks.extend(later.blocks.iter().map(|b| relocate::block(b, bases)));
        self.exprs.extend(later.exprs.iter().map(|e| relocate::expr(e, bases)));
        self.commands.extend(later.commands.iter().map(|c| relocate::command(c, bases)));
        let mut words = later.words;
        // Only expression ids inside words move, and none do when ours hold no expression.
        if bases.expr > 0 {
            for word in &mut words {
                word.kind = relocate::word(word.kind, bases);
            }
        }
        if self.later_words.is_empty() {
            self.later_words = words;
        } else {
            self.later_words.extend(words);
        }
    }
}

/// The lines of a source from a line start on, parsed into arenas of their own.
struct Run<'src> {
    /// Spans index the whole source; word, expression and command ids count from the run's
    /// first.
    program: Program<'src>,
    /// In the order of the lines.
    diagnostics: Vec<Diagnostic>,
    /// The tape after the run, and where the text after a closing `%` starts.
    end: (Tape, Option<usize>),
}

impl<'src> Run<'src> {
    /// Parse the lines of `source` from `from` on, from the tape state `tape`.
    fn parse(source: &'src [u8], from: usize, config: DialectConfig, tape: Tape, block_capacity: usize) -> Run<'src> {
        // Words average 6-8 bytes in real and generated programs; reserving a little more
        // than that avoids regrowth (which would lose the huge-page advice); what is not used
        // is never touched, and is given back at the end.
        let blocks = crate::memory::huge_page_vec(block_capacity.max((source.len() - from) / 16 + 1));
        let words = crate::memory::huge_page_vec((source.len() - from) / 6 + 1);
        let mut program = Program::empty(source, config, blocks, words);
        let mut diagnostics = Vec::new();
        let end = Builder::new(&mut program, &mut diagnostics, from == 0).run(tape, from);
        Run { program, diagnostics, end }
    }
}

/// Where the tape stands at a line: before its opening `%` (or `$…%` header) with nothing
/// but a leader so far, before it after program text, inside it, or after its closing `%`
/// (or a DOS end-of-file Ctrl-Z), where controls stop reading.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Tape {
    #[default]
    Before,
    /// Program text began with no `%` before it: no leader can follow.
    Unmarked,
    Open,
    Closed,
}

/// Ctrl-Z, the end-of-file mark of DOS text files.
const END_OF_FILE: u8 = 0x1A;

/// A run of whole lines parsed on its own, with spans, word, expression and command indexes
/// relative to the run. The language server keeps a program as such runs so that an edit
/// re-parses only the lines it touched (`crate::lsp::document`).
#[derive(Debug, Clone, Default)]
pub(crate) struct Part {
    pub blocks: Vec<Block>,
    pub words: Vec<Word>,
    pub exprs: Vec<Expr>,
    pub commands: Vec<Command>,
    /// In the order the parser reported them (not sorted).
    pub diagnostics: Vec<Diagnostic>,
    /// The tape after the run.
    pub tape: Tape,
    /// Where the text after the closing `%` starts, when the run holds that `%`. The run's
    /// blocks stop there; the `Trailing` block is the caller's, since it runs to the end of
    /// the program.
    pub trailing_from: Option<usize>,
}

/// Parse `text`, a run of whole lines (it ends after a line terminator, or at the end of the
/// program, and does not start inside an OSP `$` continuation), as `parse` would parse them
/// in place: `tape` is the tape state before the run, `document_start` says whether the run
/// starts the program (where a byte-order mark may stand). Dialect detection is the caller's.
pub(crate) fn parse_part(text: &[u8], config: DialectConfig, tape: Tape, document_start: bool) -> Part {
    // The same reservations as `parse`, for the same reason: no regrowth while parsing.
    let blocks = Vec::with_capacity(text.len() / 16 + 1);
    let mut program = Program::empty(text, config, blocks, Vec::with_capacity(text.len() / 6 + 1));
    let mut diagnostics = Vec::new();
    let (tape, trailing_from) = Builder::new(&mut program, &mut diagnostics, document_start).run(tape, 0);
    program.blocks.shrink_to_fit();
    program.words.shrink_to_fit();
    Part {
        blocks: program.blocks,
        words: program.words,
        exprs: program.exprs,
        commands: program.commands,
        diagnostics,
        tape,
        trailing_from,
    }
}

/// The warnings and notes the dialect decision itself gives (conflicting evidence, an OSP
/// machining-centre program).
pub(crate) fn detection_diagnostics(detection: &Detection) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    if detection.is_conflicted() {
        let chosen = detection.dialect;
        let other = if chosen == Dialect::Osp { Dialect::Fanuc } else { Dialect::Osp };
        let ours = detection.evidence_for(Leaning::Dialect(chosen));
        let theirs = detection.evidence_for(Leaning::Dialect(other));
        if let Some(first) = ours.first() {
            let mut diagnostic = Diagnostic::warning(
                DiagnosticKind::DialectConflict { chosen: chosen.name(), other: other.name() },
                first.first,
            );
            for e in ours.iter().skip(1).take(2) {
                diagnostic =
                    diagnostic.with_related(e.first, format!("{}: {}", chosen.name(), e.feature.description()));
            }
            for e in theirs.iter().take(3) {
                diagnostic = diagnostic.with_related(e.first, format!("{}: {}", other.name(), e.feature.description()));
            }
            out.push(diagnostic);
        }
    }
    if detection.dialect == Dialect::Osp && detection.machine_kind == MachineKind::MachiningCentre {
        let evidence = detection.evidence_for(Leaning::MachiningCentre);
        if let Some(first) = evidence.first() {
            let mut diagnostic = Diagnostic::note(DiagnosticKind::MachiningCentreProgram, first.first);
            for e in evidence.iter().skip(1).take(3) {
                diagnostic = diagnostic.with_related(e.first, e.feature.description());
            }
            out.push(diagnostic);
        }
    }
    out
}

struct Builder<'p, 'src> {
    program: &'p mut Program<'src>,
    diagnostics: &'p mut Vec<Diagnostic>,
    warnings: Vec<Diagnostic>,
    codes: Vec<(usize, &'static crate::dialect::GInfo)>,
    /// The source starts the program, so a byte-order mark at its offset 0 is one.
    document_start: bool,
}

/// The lines of a source, from one SIMD pass over its line terminators. A line ends at LF, CR
/// LF, or a CR no LF follows.
struct Lines<'s> {
    source: &'s [u8],
    /// Over the source from `from` on.
    terminators: memchr::Memchr2<'s>,
    from: usize,
    pos: usize,
    peeked: Option<(usize, usize, usize)>,
}

impl<'s> Lines<'s> {
    /// The lines of `source` from `from`, a line start, on.
    fn new(source: &'s [u8], from: usize) -> Lines<'s> {
        let terminators = memchr::memchr2_iter(b'\n', b'\r', source.get(from..).unwrap_or_default());
        Lines { source, terminators, from, pos: from, peeked: None }
    }

    /// The next line as (start, end of text, start of the following line).
    fn next_line(&mut self) -> Option<(usize, usize, usize)> {
        if let Some(line) = self.peeked.take() {
            return Some(line);
        }
        let start = self.pos;
        if start >= self.source.len() {
            return None;
        }
        // The LF of a CR LF pair was consumed with its CR; skip it here.
        let at = loop {
            match self.terminators.next().map(|at| at + self.from) {
                Some(at) if at < start => continue,
                other => break other,
            }
        };
        let (end, next) = match at {
            Some(at) => {
                let next =
                    if self.source[at] == b'\r' && self.source.get(at + 1) == Some(&b'\n') { at + 2 } else { at + 1 };
                (at, next)
            }
            None => (self.source.len(), self.source.len()),
        };
        self.pos = next;
        Some((start, end, next))
    }

    fn unread(&mut self, line: (usize, usize, usize)) {
        self.peeked = Some(line);
    }
}

impl<'p, 'src> Builder<'p, 'src> {
    fn new(program: &'p mut Program<'src>, diagnostics: &'p mut Vec<Diagnostic>, document_start: bool) -> Self {
        Builder { program, diagnostics, warnings: Vec::new(), codes: Vec::new(), document_start }
    }
}

impl<'src> Builder<'_, 'src> {
    /// Parse every line from the line start `from` on, from the tape state `tape`. Returns the
    /// tape state at the end and, when a closing `%` stopped the run, where the text after
    /// its line starts.
    fn run(&mut self, tape: Tape, from: usize) -> (Tape, Option<usize>) {
        let source = self.program.source;
        let tables = self.program.config.tables();
        let osp = self.program.config.dialect == Dialect::Osp;
        let mut lines = Lines::new(source, from);
        let mut tape_open = match tape {
            Tape::Before | Tape::Unmarked => false,
            Tape::Open => true,
            Tape::Closed => return (Tape::Closed, None),
        };
        // A tape leader is a Fanuc tape's; an OSP file's first line is its `$…%` header.
        let mut leader_possible = tape == Tape::Before && !osp;
        while let Some((start, mut end, mut next)) = lines.next_line() {
            let mut line = &source[start..end];
            if self.has_byte_order_mark(start) {
                line = &line[BYTE_ORDER_MARK.len()..];
            }
            if line.first() == Some(&b'$') && detect::is_osp_header(line) {
                self.header(start, end, osp);
                tape_open = true;
                continue;
            }
            // OSP: lines that start with `$` continue this block.
            if tables.lexical.continuation {
                while let Some(following) = lines.next_line() {
                    let text = &source[following.0..following.1];
                    if text.first() != Some(&b'$') || detect::is_osp_header(text) {
                        lines.unread(following);
                        break;
                    }
                    end = following.1;
                    next = following.2;
                }
            }
            // Ctrl-Z (0x1A) ends a DOS text file: it and what follows are not program text.
            if line.first() == Some(&END_OF_FILE) {
                return (Tape::Closed, Some(start));
            }
            // A tape mark is `%` as the first thing on its line (blanks allowed before it).
            let tape_mark = line.iter().find(|&&c| c != b' ' && c != b'\t') == Some(&b'%');
            self.block(start, end);
            if tape_mark {
                if tape_open {
                    return (Tape::Closed, Some(next));
                }
                tape_open = true;
            } else if !tape_open && leader_possible {
                leader_possible = self.leader_line(start, line);
            }
        }
        let tape = match (tape_open, leader_possible) {
            (true, _) => Tape::Open,
            (false, true) => Tape::Before,
            (false, false) => Tape::Unmarked,
        };
        (tape, None)
    }

    /// Before the tape's first `%` and any program text: whether the block just parsed from
    /// `line` leaves a leader still possible. A line whose first word does not read (`PART
    /// 1234 REV B`, prose) is a tape leader, which a control skips: the block becomes a
    /// `Leader` and its error a note. A line that reads (or reads in part) starts the
    /// program text, and no leader follows it. Controls read a tape from its `%` on and
    /// ignore the leader before it (Rockwell 8520 9/Series lathe manual §10.1 "Leader
    /// Section"; Mitsubishi M700V programming manual §3.1, "label skip"); whether a `%`
    /// follows the leader is a fact of the whole text, which the semantic pass checks
    /// (`Interpreter::check_leader`), since a chunk of the language server sees only its
    /// own lines.
    fn leader_line(&mut self, start: usize, line: &[u8]) -> bool {
        let blanks = line.iter().position(|&c| c != b' ' && c != b'\t').unwrap_or(line.len());
        let first = start + blanks;
        // A letter with a value after it (`o0001`, `X1O.`) is a damaged word, not a leader.
        let looks_like_a_word = matches!(
            &line[blanks..],
            [letter, value, ..] if letter.is_ascii_alphabetic() && matches!(value, b'0'..=b'9' | b'-' | b'+' | b'.' | b'=' | b'[' | b'#')
        );
        let Some(block) = self.program.blocks.last_mut() else { return true };
        match block.statement {
            ast::Statement::Empty => true,
            ast::Statement::Invalid
                if !looks_like_a_word
                    && self.diagnostics.last().is_some_and(|d| d.is_error() && d.span.start as usize == first) =>
            {
                block.statement = ast::Statement::Leader;
                let span = block.span;
                self.diagnostics.pop();
                self.diagnostics.push(Diagnostic::note(DiagnosticKind::TapeLeader, span));
                true
            }
            _ => false,
        }
    }

    fn has_byte_order_mark(&self, start: usize) -> bool {
        start == 0 && self.document_start && self.program.source.starts_with(BYTE_ORDER_MARK)
    }

    fn push_block(&mut self, span: Span, statement: ast::Statement, first_word: u32, word_count: u16) {
        self.program.blocks.push(ast::Block { span, statement, first_word, word_count });
    }

    fn header(&mut self, start: usize, end: usize, osp: bool) {
        if self.has_byte_order_mark(start) {
            self.diagnostics.push(Diagnostic::warning(DiagnosticKind::ByteOrderMark, Span::new(0, 3)));
        }
        let span = Span::new(start as u32, end as u32);
        if osp {
            let first_word = self.program.words.len() as u32;
            let bom = if self.has_byte_order_mark(start) { 3 } else { 0 };
            let word = Span::new(span.start + bom, span.end);
            self.program.words.push(ast::Word { span: word, kind: WordKind::Header });
            self.push_block(span, ast::Statement::Header, first_word, 1);
        } else {
            self.diagnostics.push(Diagnostic::error(
                DiagnosticKind::ForeignWord {
                    what: "`$…%` header".into(), dialect: "Fanuc", belongs_to: "Okuma OSP"
                },
                span,
            ));
            self.push_block(span, ast::Statement::Invalid, self.program.words.len() as u32, 0);
        }
    }

    fn block(&mut self, start: usize, end: usize) {
        let source = self.program.source;
        let span = Span::new(start as u32, end as u32);
        let mut text = &source[start..end];
        if self.has_byte_order_mark(start) {
            self.diagnostics.push(Diagnostic::warning(DiagnosticKind::ByteOrderMark, Span::new(0, 3)));
            text = &text[3..];
        }
        let tables = self.program.config.tables();
        let first_word = self.program.words.len();
        let first_expr = self.program.exprs.len();
        let first_command = self.program.commands.len();
        self.warnings.clear();
        let result = {
            let mut parser = BlockParser {
                source,
                tables,
                words: &mut self.program.words,
                exprs: &mut self.program.exprs,
                warnings: &mut self.warnings,
            };
            parser.parse(text)
        }
        .and_then(|()| {
            let words = &self.program.words[first_word..];
            if words.len() > u16::MAX as usize {
                return Err(Diagnostic::error(DiagnosticKind::TooManyWords { max: u16::MAX as usize }, span));
            }
            let mut classifier = Classifier {
                tables,
                commands: &mut self.program.commands,
                warnings: &mut self.warnings,
                codes: &mut self.codes,
            };
            classifier.classify(words, first_word as u32)
        });
        match result {
            Ok(statement) => {
                let count = (self.program.words.len() - first_word) as u16;
                self.push_block(span, statement, first_word as u32, count);
                self.diagnostics.append(&mut self.warnings);
            }
            Err(diagnostic) => {
                self.program.words.truncate(first_word);
                self.program.exprs.truncate(first_expr);
                self.program.commands.truncate(first_command);
                self.push_block(span, ast::Statement::Invalid, first_word as u32, 0);
                self.diagnostics.push(diagnostic);
            }
        }
    }
}

#[cfg(test)]
mod tests;
