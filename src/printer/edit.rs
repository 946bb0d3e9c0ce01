//! The AST edit API: replace, insert and delete blocks.
//!
//! Later passes never rebuild a program. They record edits against the parsed program, and
//! the printer copies every block nobody touched byte for byte and writes the new blocks in
//! the program's own style ([`super::style::ProgramStyle`]).

use std::collections::BTreeMap;

use crate::dialect::{Address, Code};
use crate::syntax::{CodeLetter, Number, WordId};

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
}

impl Edits {
    pub fn new() -> Edits {
        Edits::default()
    }

    pub fn is_empty(&self) -> bool {
        self.blocks.is_empty()
    }

    /// Replace block `index` with `blocks` (in order).
    pub fn replace(&mut self, index: usize, blocks: Vec<NewBlock>) {
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

    pub fn delete(&mut self, index: usize) {
        self.replace(index, Vec::new());
    }

    pub fn insert_before(&mut self, index: usize, block: NewBlock) {
        self.blocks.entry(index).or_default().before.push(block);
    }

    pub fn insert_after(&mut self, index: usize, block: NewBlock) {
        self.blocks.entry(index).or_default().after.push(block);
    }

    /// Whether block `index` is replaced or deleted.
    pub fn touches(&self, index: usize) -> bool {
        self.blocks.get(&index).is_some_and(|e| e.replacement.is_some())
    }

    /// The edits of block `first` and after, in block order.
    pub(crate) fn from(&self, first: usize) -> impl Iterator<Item = (usize, &BlockEdit)> {
        self.blocks.range(first..).map(|(&index, edit)| (index, edit))
    }
}
