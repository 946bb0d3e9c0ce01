//! The AST edit API: replace, insert and delete blocks.
//!
//! Later passes never rebuild a program. They record edits against the parsed program, and
//! the printer copies every block nobody touched byte for byte and writes the new blocks in
//! the program's own style ([`super::style::ProgramStyle`]).
//!
//! A pass that replaces most blocks of a long program (a compensated program rewrites nearly
//! every motion block) writes its replacements to text as it makes them, with a
//! [`BlockWriter`](super::BlockWriter), and hands them over with [`Edits::replace_written`]:
//! the same text the printer would write for the same words, without a list of words per
//! block kept until printing.

use std::collections::BTreeMap;

use crate::dialect::{Address, Code};
use crate::syntax::{CodeLetter, Number, WordId};

use super::style::ProgramStyle;
use super::written::{BlockWriter, WrittenText};

/// A word of a new block.
#[derive(Debug, Clone, PartialEq)]
pub enum NewWord {
    /// `G01`, `M08`, written as the program writes codes.
    Code(CodeLetter, Code),
    /// An address and an exact value, written in the program's number style.
    Number(Address, Number),
    /// An original word, copied as written.
    Copy(WordId),
    /// A `( … )` comment; the text goes between the parentheses.
    Comment(String),
    /// A `;` comment to the end of the line (Fanuc programs that write their comments so);
    /// the text goes after the `;`.
    LineComment(String),
    /// `%`, the tape mark that opens or closes a program.
    TapeMark,
}

/// A block to write.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct NewBlock {
    /// The sequence name, written as given (`N20`, `NLAP1`).
    pub sequence: Option<String>,
    pub words: Vec<NewWord>,
}

impl NewBlock {
    pub fn new(words: Vec<NewWord>) -> NewBlock {
        NewBlock { sequence: None, words }
    }
}

/// What happens around and to one original block.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct BlockEdit {
    pub before: Vec<NewBlock>,
    /// `Some(blocks)` replaces the block (an empty list deletes it).
    pub replacement: Option<Vec<NewBlock>>,
    pub after: Vec<NewBlock>,
}

/// Edits against one parsed program, keyed by block index.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Edits {
    pub(crate) blocks: BTreeMap<usize, BlockEdit>,
    pub(crate) written: Written,
}

/// Replacements written as text (`replace_written`).
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Written {
    /// The style they were written in, the program's (`replace_written`, `write_in`): the
    /// printer writes its own new blocks in it too rather than infer it again.
    pub style: Option<ProgramStyle>,
    pub text: Vec<u8>,
    /// Each replaced block and its replacement's text, in block order, one per block. A
    /// block here prints this text in place of any `replacement` of its `BlockEdit`; the
    /// blocks that edit inserts before or after it still print.
    pub blocks: Vec<(usize, WrittenText)>,
}

impl Written {
    /// Where block `index` is in `blocks`.
    fn find(&self, index: usize) -> Result<usize, usize> {
        self.blocks.binary_search_by_key(&index, |&(block, _)| block)
    }
}

impl Edits {
    pub fn new() -> Edits {
        Edits::default()
    }

    pub fn is_empty(&self) -> bool {
        self.blocks.is_empty() && self.written.blocks.is_empty()
    }

    /// Replace block `index` with `blocks` (in order).
    pub fn replace(&mut self, index: usize, blocks: Vec<NewBlock>) {
        // The last replacement given wins, a written one too.
        if let Ok(at) = self.written.find(index) {
            self.written.blocks.remove(at);
        }
        self.blocks.entry(index).or_default().replacement = Some(blocks);
    }

    /// `replace` for each of `replacements`, in one go: when there are no edits yet and the
    /// indices come in order (a compensated program's motion blocks), the map is built in
    /// bulk rather than block by block.
    pub fn replace_all(&mut self, replacements: Vec<(usize, Vec<NewBlock>)>) {
        let edit = |blocks| BlockEdit { replacement: Some(blocks), ..BlockEdit::default() };
        if self.blocks.is_empty() {
            self.blocks = replacements.into_iter().map(|(index, blocks)| (index, edit(blocks))).collect();
        } else {
            for (index, blocks) in replacements {
                self.replace(index, blocks);
            }
        }
    }

    /// Replace each of `replacements`' blocks with the blocks `writer` wrote for it
    /// (`BlockWriter::finish`), as `replace` would with the same blocks as words; a later
    /// replacement of the same block wins.
    pub fn replace_written(&mut self, writer: BlockWriter<'_, '_>, replacements: Vec<(usize, WrittenText)>) {
        let (style, text) = writer.into_parts();
        let written = &mut self.written;
        let mut replacements = replacements;
        if written.text.is_empty() && written.blocks.is_empty() {
            written.text = text;
        } else {
            let offset = written.text.len();
            written.text.extend_from_slice(&text);
            for (_, replacement) in &mut replacements {
                *replacement = replacement.shifted(offset);
            }
        }
        written.style.get_or_insert(style);
        if written.blocks.is_empty() {
            written.blocks = replacements;
        } else {
            written.blocks.append(&mut replacements);
        }
        // They mostly come in block order already; a stable sort keeps the later of two
        // replacements of one block after the earlier, and that one is kept.
        if !written.blocks.is_sorted_by_key(|&(block, _)| block) {
            written.blocks.sort_by_key(|&(block, _)| block);
        }
        written.blocks.dedup_by(|later, earlier| {
            let same = later.0 == earlier.0;
            if same {
                earlier.1 = later.1;
            }
            same
        });
    }

    /// Write the new blocks in `style`, the program's (`ProgramStyle::infer`), which the caller
    /// has inferred already, rather than infer it again when printing.
    pub(crate) fn write_in(&mut self, style: ProgramStyle) {
        self.written.style = Some(style);
    }

    pub fn delete(&mut self, index: usize) {
        self.replace(index, Vec::new());
    }

    pub fn insert_before(&mut self, index: usize, block: NewBlock) {
        self.blocks.entry(index).or_default().before.push(block);
    }

    /// Drop the last of the blocks that replace block `index` (a block whose words another
    /// block now writes).
    pub fn drop_last_block(&mut self, index: usize) {
        if let Some(BlockEdit { replacement: Some(blocks), .. }) = self.blocks.get_mut(&index) {
            blocks.pop();
        }
    }

    pub fn insert_after(&mut self, index: usize, block: NewBlock) {
        self.blocks.entry(index).or_default().after.push(block);
    }

    /// Whether block `index` is replaced or deleted.
    pub fn touches(&self, index: usize) -> bool {
        self.blocks.get(&index).is_some_and(|e| e.replacement.is_some()) || self.written.find(index).is_ok()
    }

    /// The edits of block `first` and after, in block order.
    pub(crate) fn from(&self, first: usize) -> impl Iterator<Item = (usize, &BlockEdit)> {
        self.blocks.range(first..).map(|(&index, edit)| (index, edit))
    }

    /// The written replacements of block `first` and after, in block order, with their text.
    pub(crate) fn written_from(&self, first: usize) -> impl Iterator<Item = (usize, &[u8])> {
        let start = self.written.blocks.partition_point(|&(block, _)| block < first);
        let written = &self.written;
        written
            .blocks
            .get(start..)
            .unwrap_or_default()
            .iter()
            .map(|&(block, replacement)| (block, replacement.of(&written.text)))
    }
}
