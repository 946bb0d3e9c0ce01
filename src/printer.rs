//! The printer: a program back to text, changing only what was edited. The back end
//! (`crate::back`) writes the blocks of moves; the printer puts every new block into the
//! program's text.
//!
//! **Invariant: untouched blocks print byte-identical.** [`print`] copies every block that no
//! edit replaced, with its own line terminator, straight from the source; only the blocks in
//! [`Edits`] are written anew, in the program's [`ProgramStyle`]. With no edits the output is
//! the input, whatever its encoding, line endings or damage.
//!
//! [`canonical::print_canonical`] is the other mode: every parsed block rewritten in one
//! normal form (`fmt --canonical`).

pub mod canonical;
pub(crate) mod edit;
pub mod mark;
pub(crate) mod style;
pub(crate) mod written;

pub use crate::syntax::Text;
pub use canonical::{CanonicalOptions, print_canonical};
pub use edit::{Edits, NewBlock, NewWord};
pub use style::ProgramStyle;
pub use written::{BlockWriter, WrittenText};

use crate::dialect::{Address, AddressKind, Dialect};
use crate::syntax::{CodeLetter, Number, Program};

use crate::syntax::spelling::{Style as NumberStyle, write_number, write_whole};
use style::WholeNumbers;

/// The errors of `text`, a printing of `program` with edits, read back as `program` was
/// read (its dialect, G-code system and machine kind). A pass that writes new blocks checks
/// its output with this before it reports success: a coordinate it computed can need more
/// digits than the control reads (a cycle's point past `Z99999999.`), and a program that
/// does not read is no output. Only the edited blocks can hold an error: the others are the
/// program's own, which read without one.
pub fn unreadable(program: &Program<'_>, text: &[u8]) -> Vec<crate::diagnostic::Diagnostic> {
    let mut diagnostics = crate::syntax::parse(text, &read_back_options(program)).diagnostics;
    diagnostics.retain(crate::diagnostic::Diagnostic::is_error);
    diagnostics
}

/// How a printing of `program` is read back: as `program` was read. With `--dialect auto`,
/// the evidence of the dialect may have been in the blocks an edit replaced.
pub fn read_back_options(program: &Program<'_>) -> crate::syntax::ParseOptions {
    let config = program.config();
    crate::syntax::ParseOptions {
        dialect: crate::dialect::DialectChoice::Fixed(config.dialect),
        gcode_system: config.gcode_system,
        machine_kind: Some(config.machine_kind),
        control: config.control,
    }
}

/// Print `program` with `edits` applied.
pub fn print(program: &Program<'_>, edits: &Edits) -> Vec<u8> {
    let source = program.source();
    // The new blocks written ahead replace blocks of about their length or shorter.
    let expected = source.len() + source.len() / 16 + edits.written.text.len();
    let mut out = crate::memory::huge_page_vec(expected);
    if edits.is_empty() {
        for (index, block) in program.blocks().iter().enumerate() {
            let next = program.blocks().get(index + 1).map_or(source.len(), |b| b.span.start as usize);
            out.extend_from_slice(&source[block.span.start as usize..next]);
        }
        return out;
    }
    // Replacements written ahead (`Edits::replace_written`) were written in the program's
    // style, which they carry.
    let style = edits.written.style.clone().unwrap_or_else(|| ProgramStyle::infer(program));
    print_blocks(program, edits, &style, 0..program.blocks().len(), &mut out);
    out
}

/// Print the blocks `range` with `edits` applied, appending to `out`.
fn print_blocks(
    program: &Program<'_>,
    edits: &Edits,
    style: &ProgramStyle,
    range: std::ops::Range<usize>,
    out: &mut Vec<u8>,
) {
    let mut writer = Writer { program, style, out, open_line: false, text: Vec::new() };
    let first = range.start;
    // The edits come in block order: walk them beside the blocks rather than look each up.
    let mut pending = edits.from(first).peekable();
    let mut written = edits.written_from(first).peekable();
    for (index, block) in program.blocks().get(range).unwrap_or_default().iter().enumerate() {
        let index = first + index;
        let edit = pending.next_if(|&(at, _)| at == index).map(|(_, edit)| edit);
        if let Some(edit) = edit {
            for new in &edit.before {
                writer.new_line(new);
            }
        }
        let written = written.next_if(|&(at, _)| at == index).map(|(_, text)| text);
        match (written, edit.and_then(|e| e.replacement.as_ref())) {
            (Some(text), _) => writer.written(text, program.terminator(index)),
            (None, None) => writer.original(block.span.range(), program.terminator(index)),
            (None, Some(replacement)) => {
                for (k, new) in replacement.iter().enumerate() {
                    if k + 1 == replacement.len() {
                        writer.start_line();
                        writer.block_text(new);
                        writer.end_with(program.terminator(index));
                    } else {
                        writer.new_line(new);
                    }
                }
            }
        }
        if let Some(edit) = edit {
            for new in &edit.after {
                writer.new_line(new);
            }
        }
    }
}

/// Print `program` with `edits` applied, as text (lossy where the source is not UTF-8).
pub fn print_string(program: &Program<'_>, edits: &Edits) -> String {
    String::from_utf8_lossy(&print(program, edits)).into_owned()
}

struct Writer<'w, 'p, 'src> {
    program: &'p Program<'src>,
    style: &'w ProgramStyle,
    out: &'w mut Vec<u8>,
    /// The last line written has no terminator yet (the source's last line had none).
    open_line: bool,
    /// The text of the new block being written (kept for the next one's).
    text: Vec<u8>,
}

impl Writer<'_, '_, '_> {
    fn start_line(&mut self) {
        if self.open_line {
            self.out.extend_from_slice(self.style.line_ending.as_bytes());
            self.open_line = false;
        }
    }

    fn original(&mut self, range: std::ops::Range<usize>, terminator: &[u8]) {
        self.start_line();
        self.out.extend_from_slice(&self.program.source()[range]);
        self.end_with(terminator);
    }

    /// A replacement written ahead (`WrittenText`): its blocks, the last ending as the
    /// replaced block did.
    fn written(&mut self, text: &[u8], terminator: &[u8]) {
        self.start_line();
        self.out.extend_from_slice(text);
        self.end_with(terminator);
    }

    fn end_with(&mut self, terminator: &[u8]) {
        self.out.extend_from_slice(terminator);
        self.open_line = terminator.is_empty();
    }

    fn new_line(&mut self, block: &NewBlock) {
        self.start_line();
        self.block_text(block);
        self.out.extend_from_slice(self.style.line_ending.as_bytes());
    }

    fn block_text(&mut self, block: &NewBlock) {
        self.text.clear();
        write_new_block(&mut self.text, self.program, self.style, block);
        self.out.extend_from_slice(&self.text);
    }
}

/// Write a new block in `style`.
pub fn write_new_block(out: &mut impl Text, program: &Program<'_>, style: &ProgramStyle, block: &NewBlock) {
    let mut line_start = true;
    if let Some(sequence) = &block.sequence {
        write_sequence(out, style, sequence);
    }
    for word in &block.words {
        write_word(out, program, style, word, &mut line_start);
    }
}

/// Write a new block's sequence name, at the start of its line.
fn write_sequence(out: &mut impl Text, style: &ProgramStyle, sequence: &str) {
    out.push_str(sequence);
    // OSP requires a blank after the sequence name.
    out.push_str(if style.dialect == Dialect::Osp { " " } else { style.word_separator() });
}

/// Write `word` of a new block, after a separator unless it starts the line (`line_start`,
/// which it then leaves as the next word needs it).
pub(crate) fn write_word(
    out: &mut impl Text,
    program: &Program<'_>,
    style: &ProgramStyle,
    word: &NewWord,
    line_start: &mut bool,
) {
    if !*line_start {
        out.push_str(style.word_separator());
    }
    *line_start = false;
    match word {
        NewWord::Code(letter, code) => write_code(out, *letter, code.major(), code.minor(), style.two_digit_codes),
        NewWord::Number(address, number) => write_address_number(out, program, style, *address, *number),
        NewWord::Copy(id) => *line_start = write_copy(out, program, *id),
        NewWord::Comment(text) => {
            out.push_byte(b'(');
            out.push_str(text);
            out.push_byte(b')');
        }
        NewWord::LineComment(text) => {
            out.push_byte(b';');
            out.push_str(text);
        }
        NewWord::TapeMark => out.push_byte(b'%'),
    }
}

/// Write word `id` of the program as it was written; whether the next word starts the line
/// (a block-delete slash is written against what follows it: `/N120`).
pub(crate) fn write_copy(out: &mut impl Text, program: &Program<'_>, id: u32) -> bool {
    let word = program.word(id);
    let text = program.text(word.span);
    if text.is_ascii() {
        out.push_ascii(text);
    } else {
        out.push_source(text);
    }
    matches!(word.kind, crate::syntax::WordKind::BlockDelete { .. })
}

pub(crate) fn write_code(out: &mut impl Text, letter: CodeLetter, major: u16, minor: u16, two_digits: bool) {
    let letter = match letter {
        CodeLetter::G => b'G',
        CodeLetter::M => b'M',
    };
    out.push_byte(letter);
    if two_digits && major < 10 {
        out.push_byte(b'0');
    }
    write_whole(out, u64::from(major));
    if minor != 0 {
        out.push_byte(b'.');
        write_whole(out, u64::from(minor));
    }
}

pub(crate) fn write_address_number(
    out: &mut impl Text,
    program: &Program<'_>,
    style: &ProgramStyle,
    address: Address,
    number: Number,
) {
    let (letters, length) = address.bytes();
    out.push_ascii(letters.get(..length).unwrap_or_default());
    if !address.is_letter() && !address.is_comma() {
        out.push_byte(b'=');
    }
    let kind = program.config().tables().address(address).map(|s| s.kind);
    match kind {
        Some(AddressKind::Length | AddressKind::Angle | AddressKind::Feed) => {
            let mut number = number;
            let is_length = kind != Some(AddressKind::Feed);
            if is_length
                && let Some(places) = style.fixed_decimals
                && number.scale < places
            {
                let extra = (places - number.scale) as u32;
                number.mantissa = number.mantissa.saturating_mul(10i64.saturating_pow(extra));
                number.scale = places;
            }
            let whole = number.is_whole();
            let fixed = is_length && style.fixed_decimals.is_some();
            let number_style = NumberStyle {
                leading_zero: !style.suppress_leading_zero,
                force_point: !(whole && style.whole_numbers == WholeNumbers::NoPoint && !fixed),
                as_written: false,
                trim_zeros: !fixed,
            };
            write_number(out, number, number_style);
            if whole && !fixed && style.whole_numbers == WholeNumbers::PointZero {
                out.push_byte(b'0');
            }
        }
        Some(AddressKind::Tool) => {
            let digits = number.mantissa.unsigned_abs().to_string();
            let width = if digits.len() <= 4 { 4 } else { 6 };
            out.push_str(&format!("{digits:0>width$}"));
        }
        _ => write_number(out, number, NumberStyle::AS_WRITTEN),
    }
}
