//! The edited blocks of a compensated program as a readable line diff against the
//! original: each change with a few unchanged lines around it, the line numbers of both.

use std::time::{Duration, Instant};

use similar::{ChangeTag, TextDiff};

/// Unchanged lines shown either side of a change.
const CONTEXT: usize = 2;
/// The diff of a long program stops after this many changed lines (the page says how many
/// more there are).
pub const SHOWN_CHANGES: usize = 400;
/// How long the diff may search for the fewest changes before it settles for more (a large
/// program rewritten throughout).
const SEARCH: Duration = Duration::from_secs(5);

/// One line of the diff.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Line {
    /// Unchanged, at these lines of the original and the compensated program (1-based).
    Same(usize, usize, String),
    /// Only in the original.
    Removed(usize, String),
    /// Only in the compensated program.
    Added(usize, String),
    /// Unchanged lines left out between two hunks.
    Gap,
}

/// The diff: its lines, how many lines changed in all, and how many of those are not shown.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Diff {
    pub lines: Vec<Line>,
    pub changed: usize,
    pub not_shown: usize,
}

/// The diff of `compensated` against `original` (both read as UTF-8, lossily).
pub fn diff(original: &[u8], compensated: &[u8]) -> Diff {
    let (old, new) = (String::from_utf8_lossy(original), String::from_utf8_lossy(compensated));
    let text = TextDiff::configure().deadline(Instant::now() + SEARCH).diff_lines(old.as_ref(), new.as_ref());
    let mut out = Diff::default();
    for (k, group) in text.grouped_ops(CONTEXT).iter().enumerate() {
        if k > 0 {
            out.lines.push(Line::Gap);
        }
        for op in group {
            for change in text.iter_changes(op) {
                let value = change.value().trim_end_matches(['\n', '\r']).to_string();
                let line = match (change.tag(), change.old_index(), change.new_index()) {
                    (ChangeTag::Equal, Some(a), Some(b)) => Line::Same(a + 1, b + 1, value),
                    (ChangeTag::Delete, Some(a), _) => Line::Removed(a + 1, value),
                    (ChangeTag::Insert, _, Some(b)) => Line::Added(b + 1, value),
                    _ => continue,
                };
                if !matches!(line, Line::Same(..)) {
                    out.changed += 1;
                    if out.changed > SHOWN_CHANGES {
                        out.not_shown += 1;
                        continue;
                    }
                } else if out.changed >= SHOWN_CHANGES {
                    continue;
                }
                out.lines.push(line);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_changed_block_between_unchanged_ones() {
        let original = b"O1\nG00 X10.\nG01 Z-5. F.1\nG01 X12.\nM30\n";
        let compensated = b"O1\nG00 X10.\nG01 Z-5.002 F.1\nG01 X12.\nM30\n";
        let d = diff(original, compensated);
        assert_eq!(d.changed, 2);
        assert_eq!(d.not_shown, 0);
        assert!(d.lines.contains(&Line::Removed(3, "G01 Z-5. F.1".to_string())));
        assert!(d.lines.contains(&Line::Added(3, "G01 Z-5.002 F.1".to_string())));
        assert!(d.lines.contains(&Line::Same(2, 2, "G00 X10.".to_string())));
    }

    #[test]
    fn identical_programs_have_no_diff() {
        assert_eq!(diff(b"O1\nM30\n", b"O1\nM30\n"), Diff::default());
    }
}
