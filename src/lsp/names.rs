//! Sequence names and the words that refer to them, for definition, references, rename
//! and renumbering.
//!
//! A block's sequence name (`N20`, `NAT00`) is a definition; `P20`/`Q30` of a cycle (its
//! profile), the contour name of a LAP call (`G85 N0207`), the target of a jump (`GOTO
//! NAT00`, Fanuc `GOTO 100`) and of a Fanuc return (`M99 P100`) refer to one. Names compare
//! as the semantic pass compares them (`semantic::labels`): by value on Fanuc, as text on
//! OSP.
//!
//! **A block with a typo keeps its name.** A block that does not parse loses its words, but
//! the name at its start is still the name the control jumps to: it is read from the text
//! (`N20 G01 X1O.` is still `N20`), so that `P20` reaches the block with the typo in it.

use crate::dialect::{Address, Dialect, GFunction, KeywordKind, Role, Tables};
use crate::semantic::labels;
use crate::source::Span;
use crate::syntax::{CodeLetter, ExprKind, Statement, Word, WordId, WordKind};

use super::document::{BlockRef, Document};

/// What a name's word does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Use {
    /// A block's own sequence name.
    Definition,
    /// `P`/`Q` of a cycle: the first and last block of its profile.
    Profile,
    /// The contour name of a LAP call.
    Contour,
    /// The target of `GOTO`, `IF … GOTO`, `M99 P`.
    Jump,
}

/// A sequence name or a reference to one.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Name {
    pub key: String,
    pub use_: Use,
    /// The name as written after its letter: `20` of `N20` and `P20`, `AT00` of `NAT00`,
    /// `100` of `GOTO 100`. Rename and renumbering replace this text.
    pub name: Span,
    /// The whole word.
    pub word: Span,
    /// The block it is in.
    pub block: Span,
    /// The block starts a LAP contour (`NLAP1 G81`).
    pub contour: bool,
}

/// The name or reference at byte `offset`, if the word there is one.
pub fn at(document: &Document, offset: usize) -> Option<Name> {
    let block = document.block_at(offset)?;
    if block.block().statement == Statement::Invalid {
        return leading(document, &block).filter(|n| n.word.start as usize <= offset && offset <= n.word.end as usize);
    }
    let (id, word) = block.word_at(offset)?;
    name_of(document, &block, id, word)
}

/// Every name and reference of the program, in order.
pub fn all(document: &Document) -> Vec<Name> {
    let mut names = Vec::new();
    for block in document.blocks() {
        if block.block().statement == Statement::Invalid {
            names.extend(leading(document, &block));
            continue;
        }
        let first = block.block().first_word;
        for (index, word) in block.words().iter().enumerate() {
            names.extend(name_of(document, &block, first + index as WordId, word));
        }
    }
    names
}

/// The definitions a reference (or a definition) names, as the control finds them: every
/// block with the name for a profile, the first after the word (else the first from the
/// top) for a jump, the same among contour blocks for a LAP call.
pub fn definitions<'n>(names: &'n [Name], of: &Name) -> Vec<&'n Name> {
    let named: Vec<&Name> = names.iter().filter(|n| n.use_ == Use::Definition && n.key == of.key).collect();
    let after_or_first = |candidates: Vec<&'n Name>| -> Vec<&'n Name> {
        let after = candidates.iter().copied().find(|n| n.block.start > of.block.start);
        after.or_else(|| candidates.first().copied()).into_iter().collect()
    };
    match of.use_ {
        Use::Definition | Use::Profile => named,
        Use::Jump => after_or_first(named),
        Use::Contour => {
            let contours: Vec<&Name> = named.iter().copied().filter(|n| n.contour).collect();
            // No contour block has the name: show what has it; the diagnostic says the rest.
            if contours.is_empty() { named } else { after_or_first(contours) }
        }
    }
}

fn name_of(document: &Document, block: &BlockRef<'_>, id: WordId, word: &Word) -> Option<Name> {
    let config = document.config();
    let tables = config.tables();
    let dialect = config.dialect;
    let text = block.text(word.span);
    let whole = block.absolute(word.span);
    let block_span = block.absolute(block.block().span);
    let after_letter = Span::new(whole.start + 1, whole.end);
    let parameter = block.command().and_then(|c| c.params.iter().find(|p| p.word == id)).map(|p| p.role);
    let make = |key: String, use_: Use, name: Span| Name {
        key,
        use_,
        name,
        word: whole,
        block: block_span,
        contour: use_ == Use::Definition && starts_contour(block, tables),
    };
    match word.kind {
        WordKind::Sequence { number } => Some(make(labels::key(dialect, text, number), Use::Definition, after_letter)),
        WordKind::Label { number } => {
            let use_ = if matches!(block.block().statement, Statement::LapCall(_)) { Use::Contour } else { Use::Jump };
            Some(make(labels::key(dialect, text, number), use_, after_letter))
        }
        WordKind::Number { number, .. } if matches!(parameter, Some(Role::ProfileStart | Role::ProfileEnd)) => {
            digits_after_letter(text).then(|| make(whole_key(number.to_f64()), Use::Profile, after_letter))
        }
        WordKind::Number { address: Address::P, number } if returns_to_sequence(block, tables) => {
            digits_after_letter(text).then(|| make(whole_key(number.to_f64()), Use::Jump, after_letter))
        }
        WordKind::Operand { expr } if is_jump(block, tables) => match block.expr(expr) {
            Some(e) if matches!(e.kind, ExprKind::Number(_)) => {
                let ExprKind::Number(number) = e.kind else { return None };
                let span = block.absolute(e.span);
                Some(Name { name: span, ..make(whole_key(number.to_f64()), Use::Jump, span) })
            }
            _ => None,
        },
        _ => None,
    }
}

/// `P20`, not `P=V1` or `P 20`: a name rename can rewrite in place.
fn digits_after_letter(text: &[u8]) -> bool {
    text.len() > 1 && text[1..].iter().all(u8::is_ascii_digit)
}

/// The key of a sequence number given as a value (`P20`, `GOTO 100`), as the semantic pass
/// forms it.
pub(super) fn whole_key(value: f64) -> String {
    (value.round() as i64).to_string()
}

/// Whether the block returns to a sequence number (`M99 P100`).
fn returns_to_sequence(block: &BlockRef<'_>, tables: &Tables) -> bool {
    block.words().iter().any(|w| match w.kind {
        WordKind::Code { letter: CodeLetter::M, code } => tables.m_functions.subprogram_return.contains(&code.major()),
        _ => false,
    })
}

/// Whether the block jumps (`GOTO`, `IF … GOTO`), so that its number operand is a target.
pub(super) fn is_jump(block: &BlockRef<'_>, tables: &Tables) -> bool {
    block.words().iter().any(|w| match w.kind {
        WordKind::Keyword { index } => tables.keyword_info(index as usize).kind == KeywordKind::Goto,
        _ => false,
    })
}

/// The sequence name at the start of a block that does not parse: blanks, a block delete
/// (`/`, `/2`), blanks, `N` and the name (digits on Fanuc, letters and digits on OSP).
fn leading(document: &Document, block: &BlockRef<'_>) -> Option<Name> {
    let own = block.block().span;
    let text = block.text(own);
    let blanks = |from: usize| from + text[from..].iter().take_while(|&&c| c == b' ' || c == b'\t').count();
    let mut at = blanks(0);
    if text.get(at) == Some(&b'/') {
        at += 1 + text[at + 1..].iter().take_while(|c| c.is_ascii_digit()).count();
        at = blanks(at);
    }
    if text.get(at) != Some(&b'N') {
        return None;
    }
    let dialect = document.config().dialect;
    let name_len = text[at + 1..]
        .iter()
        .take_while(|c| if dialect == Dialect::Fanuc { c.is_ascii_digit() } else { c.is_ascii_alphanumeric() })
        .count();
    if name_len == 0 {
        return None;
    }
    let name = &text[at + 1..at + 1 + name_len];
    let number = if name.iter().all(u8::is_ascii_digit) {
        std::str::from_utf8(name).ok().and_then(|n| n.parse::<u32>().ok())
    } else {
        None
    };
    let start = own.start + at as u32;
    let word = block.absolute(Span::new(start, start + 1 + name_len as u32));
    Some(Name {
        key: labels::key(dialect, &text[at..at + 1 + name_len], number),
        use_: Use::Definition,
        name: Span::new(word.start + 1, word.end),
        word,
        block: block.absolute(own),
        contour: false,
    })
}

/// Whether the block starts a LAP contour (or blank): `G81`, `G82`, `G83`.
pub(super) fn starts_contour(block: &BlockRef<'_>, tables: &Tables) -> bool {
    matches!(block.block().statement, Statement::LapMarker(_))
        && block.words().iter().any(|w| match w.kind {
            WordKind::Code { letter: CodeLetter::G, code } => matches!(
                tables.g(code).and_then(|g| g.function),
                Some(GFunction::LapContourLongitudinal | GFunction::LapContourTransverse | GFunction::LapBlank)
            ),
            _ => false,
        })
}

/// Whether the block ends a LAP contour: `G80`.
pub(super) fn ends_contour(block: &BlockRef<'_>, tables: &Tables) -> bool {
    block.words().iter().any(|w| match w.kind {
        WordKind::Code { letter: CodeLetter::G, code } => {
            tables.g(code).and_then(|g| g.function) == Some(GFunction::LapEnd)
        }
        _ => false,
    })
}
