//! Where each sequence name and program name is, for jumps, calls, `P`/`Q` profiles and
//! LAP contours.
//!
//! Fanuc sequence numbers compare by value (`N01` is `N1`); OSP sequence names compare as
//! text (`N0123` is not `N123`). Names may repeat: a jump searches forward from where it is
//! and then from the top, as the controls do; a `P`/`Q` reference must name exactly one
//! block.

use std::collections::HashMap;

use crate::dialect::Dialect;
use crate::syntax::{Program, Statement, WordKind};

#[derive(Debug, Default)]
pub struct Labels {
    sequences: HashMap<String, Vec<usize>>,
    programs: HashMap<String, usize>,
    /// The sequence name a block that does not parse starts with, read from its text: a
    /// reference to it depends on the damaged block and is not checked.
    damaged: HashMap<String, usize>,
}

/// The key of a sequence name or label word: its value on Fanuc, its text on OSP.
pub fn key(dialect: Dialect, text: &[u8], number: Option<u32>) -> String {
    match (dialect, number) {
        (Dialect::Fanuc, Some(n)) => n.to_string(),
        _ => String::from_utf8_lossy(text.strip_prefix(b"N").unwrap_or(text)).into_owned(),
    }
}

/// The key of a program name (`O1234`, `:1234`, `OSUB`): its text after `O` or `:`, and on
/// Fanuc its value.
pub fn program_key(dialect: Dialect, text: &[u8]) -> String {
    // `o0001` on a control that reads lower case.
    let name =
        text.strip_prefix(b"O").or_else(|| text.strip_prefix(b"o")).or_else(|| text.strip_prefix(b":")).unwrap_or(text);
    let name = String::from_utf8_lossy(name).into_owned();
    match dialect {
        Dialect::Fanuc => name.parse::<u64>().map_or(name, |n| n.to_string()),
        Dialect::Osp => name,
    }
}

impl Labels {
    pub fn new(program: &Program<'_>) -> Labels {
        let dialect = program.config().dialect;
        let mut labels = Labels::default();
        for (index, block) in program.blocks().iter().enumerate() {
            if block.statement == Statement::Invalid {
                if let Some(key) = damaged_sequence(dialect, program.text(block.span)) {
                    labels.damaged.entry(key).or_insert(index);
                }
                continue;
            }
            for word in program.words_of(block) {
                match word.kind {
                    WordKind::Sequence { number } => {
                        labels.sequences.entry(key(dialect, program.text(word.span), number)).or_default().push(index);
                    }
                    WordKind::ProgramName => {
                        labels.programs.entry(program_key(dialect, program.text(word.span))).or_insert(index);
                    }
                    _ => {}
                }
            }
        }
        labels
    }

    /// Every block with this sequence key.
    pub fn blocks(&self, key: &str) -> &[usize] {
        self.sequences.get(key).map_or(&[], Vec::as_slice)
    }

    /// The jump target: the first block with this key after `from`, else the first from the top.
    pub fn jump(&self, key: &str, from: usize) -> Option<usize> {
        let blocks = self.blocks(key);
        blocks.iter().copied().find(|&b| b > from).or_else(|| blocks.first().copied())
    }

    /// The first block that does not parse and starts with this sequence key.
    pub fn damaged(&self, key: &str) -> Option<usize> {
        self.damaged.get(key).copied()
    }

    pub fn program(&self, key: &str) -> Option<usize> {
        self.programs.get(key).copied()
    }
}

/// The sequence key the text of a block that does not parse starts with (after blanks and a
/// block-delete slash): `N20 G01 X1O.` is block N20 whatever its other words say.
fn damaged_sequence(dialect: Dialect, text: &[u8]) -> Option<String> {
    let mut rest = text.trim_ascii_start();
    if let Some(after) = rest.strip_prefix(b"/") {
        rest = after.trim_ascii_start();
        let digits = rest.iter().take_while(|c| c.is_ascii_digit()).count();
        rest = rest[digits..].trim_ascii_start();
    }
    let name = rest.strip_prefix(b"N")?;
    match dialect {
        Dialect::Fanuc => {
            let digits = name.iter().take_while(|c| c.is_ascii_digit()).count();
            let number: u32 = std::str::from_utf8(&name[..digits]).ok()?.parse().ok()?;
            Some(number.to_string())
        }
        Dialect::Osp => {
            let length = name.iter().take_while(|c| c.is_ascii_alphanumeric()).count();
            (length > 0).then(|| String::from_utf8_lossy(&name[..length]).into_owned())
        }
    }
}
