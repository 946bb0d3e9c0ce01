//! New blocks written to text as a pass makes them.
//!
//! A compensated program replaces nearly every motion block of the program, often with two
//! or three blocks each. Kept as lists of words until printing, they were several small
//! allocations per block and several times the memory of their text; a [`BlockWriter`]
//! writes each replacement once, in the program's style, into one buffer, and
//! [`Edits::replace_written`](super::Edits::replace_written) hands the text to the printer.
//! The text is what the printer writes for the same words (`write_word`), so a block comes
//! out the same whichever way it was given.

use crate::dialect::{Address, Code};
use crate::syntax::{CodeLetter, Number, Program};

use super::style::ProgramStyle;
use super::{NewBlock, NewWord, write_address_number, write_code, write_copy, write_sequence, write_word};

/// Writes replacement blocks to text in a program's style.
pub struct BlockWriter<'p, 'src> {
    program: &'p Program<'src>,
    style: ProgramStyle,
    text: Vec<u8>,
    /// The next word starts its line (no separator before it).
    line_start: bool,
}

/// The text of one replacement in its writer's buffer: one or more blocks, each but the
/// last followed by the program's line ending (the last takes the replaced block's own).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WrittenText {
    start: usize,
    end: usize,
}

impl WrittenText {
    pub(crate) fn of(self, text: &[u8]) -> &[u8] {
        text.get(self.start..self.end).unwrap_or_default()
    }

    pub(crate) fn shifted(self, offset: usize) -> WrittenText {
        WrittenText { start: self.start + offset, end: self.end + offset }
    }
}

/// Where a replacement starts in the writer's buffer (`BlockWriter::begin`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mark(usize);

impl<'p, 'src> BlockWriter<'p, 'src> {
    /// A writer in `program`'s style (`ProgramStyle::infer`).
    pub fn new(program: &'p Program<'src>) -> BlockWriter<'p, 'src> {
        BlockWriter::with_style(program, ProgramStyle::infer(program))
    }

    /// A writer in `style`, inferred from `program` already.
    pub fn with_style(program: &'p Program<'src>, style: ProgramStyle) -> BlockWriter<'p, 'src> {
        // A compensated program's new blocks are about as long as the program: huge pages
        // where there is that much to write.
        let text = crate::memory::huge_page_vec(program.source().len());
        BlockWriter { program, style, text, line_start: true }
    }

    /// Start a replacement; what follows is its first block.
    pub fn begin(&mut self) -> Mark {
        self.line_start = true;
        Mark(self.text.len())
    }

    /// End the replacement's current block and start its next one.
    pub fn next_block(&mut self) {
        self.text.extend_from_slice(self.style.line_ending.as_bytes());
        self.line_start = true;
    }

    /// The next word of the current block.
    pub fn word(&mut self, word: &NewWord) {
        write_word(&mut self.text, self.program, &self.style, word, &mut self.line_start);
    }

    /// A code word of the current block (`NewWord::Code`), given as its parts, as `number`.
    pub fn code(&mut self, letter: CodeLetter, code: Code) {
        self.separate();
        write_code(&mut self.text, letter, code.major(), code.minor(), self.style.two_digit_codes);
    }

    /// A number word of the current block (`NewWord::Number`), given as its parts: the
    /// rewrite writes millions, and a word built first to be taken apart here cost more
    /// than writing it.
    pub fn number(&mut self, address: Address, number: Number) {
        self.separate();
        write_address_number(&mut self.text, self.program, &self.style, address, number);
    }

    /// Word `id` of the program as it was written (`NewWord::Copy`).
    pub fn copy(&mut self, id: u32) {
        self.separate();
        self.line_start = write_copy(&mut self.text, self.program, id);
    }

    /// The separator before the next word of the current block, unless it starts the line.
    fn separate(&mut self) {
        if !self.line_start {
            self.text.extend_from_slice(self.style.word_separator().as_bytes());
        }
        self.line_start = false;
    }

    /// `block`'s sequence name and words as the current block (which has no words yet).
    pub fn block(&mut self, block: &NewBlock) {
        if let Some(sequence) = &block.sequence {
            write_sequence(&mut self.text, &self.style, sequence);
        }
        for word in &block.words {
            self.word(word);
        }
    }

    /// End the replacement begun at `mark`: its text.
    pub fn finish(&mut self, mark: Mark) -> WrittenText {
        WrittenText { start: mark.0, end: self.text.len() }
    }

    /// Forget the replacement written last, `written`.
    pub fn discard(&mut self, written: WrittenText) {
        if written.end == self.text.len() {
            self.text.truncate(written.start);
        }
        self.line_start = true;
    }

    /// `written` without its last block (one whose words the block after it now writes);
    /// a replacement of one block is left as it is.
    pub fn without_last_block(&self, written: WrittenText) -> WrittenText {
        let ending = self.style.line_ending.as_bytes();
        let text = written.of(&self.text);
        match text.windows(ending.len()).rposition(|w| w == ending) {
            Some(at) => WrittenText { start: written.start, end: written.start + at },
            None => written,
        }
    }

    /// The text of a replacement this writer wrote.
    pub fn text(&self, written: WrittenText) -> &[u8] {
        written.of(&self.text)
    }

    /// The style it writes in.
    pub fn style(&self) -> &ProgramStyle {
        &self.style
    }

    pub(crate) fn into_parts(self) -> (ProgramStyle, Vec<u8>) {
        (self.style, self.text)
    }
}
