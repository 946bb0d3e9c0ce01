//! Comments turnpass writes into its outputs: one block after the program's name line, in
//! the program's own comment style. The provenance comment of a compensated program is one
//! (`compensation/provenance.rs`); a program whose printed text alone would read as the other
//! dialect (the evidence was in the blocks an edit replaced: an OSP cycle's `DA=` word, expanded
//! into plain moves) carries the field that names its dialect, which `dialect::detect` reads as
//! deciding, so that `verify`, `simulate` or a second run read it as it was written.

use crate::dialect::Dialect;
use crate::dialect::tables::SemicolonRule;
use crate::syntax::{CommentKind, Program, Statement, WordKind};

use super::{Edits, NewBlock, NewWord};

/// The dialect a printing of `program` (`printed`) must name: `program`'s own, when the
/// printed text alone would be read as the other.
pub fn dialect_to_name(program: &Program<'_>, printed: &[u8]) -> Option<Dialect> {
    let dialect = program.config().dialect;
    (crate::dialect::detect::decide(printed, None, None).dialect != dialect).then_some(dialect)
}

/// The field that names `dialect` in a mark (`DIALECT OSP`), as `dialect::detect` reads it.
pub fn dialect_field(dialect: Dialect) -> &'static str {
    match dialect {
        Dialect::Osp => "DIALECT OSP",
        Dialect::Fanuc => "DIALECT FANUC",
    }
}

/// Record in `edits` the mark of an expanded program naming `dialect`:
/// `(TURNPASS 0.1.0 EXPANDED, DIALECT OSP)`.
pub fn insert_dialect_mark(program: &Program<'_>, edits: &mut Edits, dialect: Dialect) {
    // In capitals whatever the program's comments use, as the provenance comment's fields are.
    let text = format!("TURNPASS {} EXPANDED, {}", env!("CARGO_PKG_VERSION"), dialect_field(dialect));
    insert_after_name(program, edits, |_| text);
}

/// Record in `edits` a comment block whose text `text` gives (in upper case when asked:
/// older controls reject lower case even in comments), after the program's name line: the
/// first `O…` block among the blocks before the first statement (tape marks, the OSP header,
/// blank and comment lines), else the last tape mark or header among them, else at the top.
/// The name block is left as it is, its comment (`O1234 (SHAFT)`) included.
pub fn insert_after_name(program: &Program<'_>, edits: &mut Edits, text: impl FnOnce(bool) -> String) {
    let blocks = program.blocks();
    if blocks.is_empty() {
        return;
    }
    let leading = blocks.iter().take_while(|b| {
        matches!(b.statement, Statement::Empty | Statement::TapeMark | Statement::Header | Statement::ProgramName)
    });
    let mut anchor = None;
    for (index, block) in leading.enumerate() {
        match block.statement {
            Statement::ProgramName => {
                anchor = Some(index);
                break;
            }
            Statement::TapeMark | Statement::Header => anchor = Some(index),
            _ => {}
        }
    }
    let style = CommentStyle::of(program);
    let text = text(!style.lower_case);
    let word = if style.semicolon { NewWord::LineComment(format!(" {text}")) } else { NewWord::Comment(text) };
    let block = NewBlock::new(vec![word]);
    match anchor {
        Some(index) => edits.insert_after(index, block),
        None => edits.insert_before(0, block),
    }
}

/// How a program writes its comments.
struct CommentStyle {
    /// `; …` to the end of the line rather than `( … )`: the program writes only such
    /// comments, and its dialect reads them as comments.
    semicolon: bool,
    /// Some comment uses lower-case letters.
    lower_case: bool,
}

impl CommentStyle {
    fn of(program: &Program<'_>) -> CommentStyle {
        let (mut paren, mut semicolon, mut lower_case) = (false, false, false);
        for block in program.blocks() {
            for word in program.words_of(block) {
                let WordKind::Comment(kind) = word.kind else { continue };
                let body = comment_body(program.text(word.span));
                match kind {
                    CommentKind::Paren => paren = true,
                    // A bare `;` ending a block is an end of block, not a comment style.
                    CommentKind::Semicolon if !body.trim_ascii().is_empty() => semicolon = true,
                    CommentKind::Semicolon => {}
                }
                lower_case |= body.iter().any(u8::is_ascii_lowercase);
            }
        }
        let reads_semicolon = program.config().tables().lexical.semicolon == SemicolonRule::EndOfBlock;
        CommentStyle { semicolon: semicolon && !paren && reads_semicolon, lower_case }
    }
}

/// The text of comment `text` (as written, delimiters included) between its delimiters.
pub(crate) fn comment_body(text: &[u8]) -> &[u8] {
    match text {
        [b'(', body @ .., b')'] => body,
        [b'(', body @ ..] | [b';', body @ ..] => body,
        _ => text,
    }
}
