//! The repairs a hint names exactly: `O` typed for `0`, `l` for `1`, a decimal comma, a
//! missing `G`, `=` or space, a lower-case letter, a stray NUL or byte-order mark, an open
//! comment, a decimal point where the control counts (the value meant, computed from what the
//! word counts).
//!
//! A fix is made from the diagnostic's kind and checked against the text of its line: when
//! the text is not what the hint assumes (the program changed since), there is no fix, so an
//! editor never offers an edit that would damage the program. Hints that need judgement
//! (which of two duplicate words to keep, what a damaged value was) have none.

use crate::source::Span;

use super::{Diagnostic, DiagnosticKind};

/// A repair: what an editor's quick fix says and the edits it makes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Fix {
    pub title: String,
    /// Replacements of spans of the source (byte offsets) by text; an empty span inserts.
    pub edits: Vec<(Span, String)>,
}

impl Diagnostic {
    /// The fix of this diagnostic's hint, checked against `line`, the text of the line the
    /// diagnostic is on (without its terminator), which starts at byte `line_start`.
    pub fn fix(&self, line: &[u8], line_start: usize) -> Option<Fix> {
        let start = (self.span.start as usize).checked_sub(line_start)?;
        let end = (self.span.end as usize).checked_sub(line_start)?;
        let text = line.get(start..end)?;
        let after = &line[end..];
        let at = |from: usize, to: usize| Span::new((line_start + from) as u32, (line_start + to) as u32);
        let replace = |title: String, with: &str| Some(Fix { title, edits: vec![(self.span, with.to_string())] });
        use DiagnosticKind::*;
        match &self.kind {
            LetterOForZero { suggestion } if text == b"O" => {
                replace(format!("Write `{suggestion}` (the digit 0 for the letter O)"), "0")
            }
            LetterForDigit { found, digit } if text == found.to_string().as_bytes() => {
                replace(format!("Write `{digit}` for the misread `{found}`"), &digit.to_string())
            }
            DecimalComma { suggestion } if text == b"," => {
                replace(format!("Write `{suggestion}` (a decimal point for the comma)"), ".")
            }
            ZeroForLetterO { suggestion } if text == b"0" => {
                replace(format!("Write `{suggestion}` (the letter O for the digit 0)"), "O")
            }
            LowerCaseLetter { found } if text == found.to_string().as_bytes() => {
                let upper = found.to_ascii_uppercase().to_string();
                replace(format!("Write `{upper}`"), &upper)
            }
            NulByte if text == b"\0" => replace("Remove the NUL byte".to_string(), ""),
            ByteOrderMark if text == "\u{feff}".as_bytes() => replace("Remove the byte-order mark".to_string(), ""),
            NumberWithoutAddress { suggestion: Some(suggestion) }
                if suggestion.strip_prefix('G').is_some_and(|number| number.as_bytes() == text) =>
            {
                let edit = (at(start, start), "G".to_string());
                Some(Fix { title: format!("Write `{suggestion}`"), edits: vec![edit] })
            }
            MissingValue { address, suggestion: Some(suggestion) } => {
                // `X SDIA-3` → `X=SDIA-3`: the address, blanks, and the expression the
                // suggestion names, replaced by the suggestion.
                let expression = suggestion.strip_prefix(address.as_str())?.strip_prefix('=')?;
                let rest = line.get(start..)?.strip_prefix(address.as_bytes())?;
                let blanks = rest.iter().take_while(|&&c| c == b' ' || c == b'\t').count();
                rest[blanks..].starts_with(expression.as_bytes()).then_some(())?;
                let to = start + address.len() + blanks + expression.len();
                Some(Fix { title: format!("Write `{suggestion}`"), edits: vec![(at(start, to), suggestion.clone())] })
            }
            ExtendedAddressNeedsEquals { name } if text == name.as_bytes() => {
                // `XA 60` or `XA60` → `XA=60`.
                let blanks = after.iter().take_while(|&&c| c == b' ' || c == b'\t').count();
                after.get(blanks).filter(|c| c.is_ascii_digit() || matches!(c, b'.' | b'-' | b'+'))?;
                let edit = (at(end, end + blanks), "=".to_string());
                Some(Fix { title: format!("Write `{name}=`"), edits: vec![edit] })
            }
            MissingSpaceAfterSequence { name }
                if start >= name.len() && &line[start - name.len()..start] == name.as_bytes() =>
            {
                Some(Fix {
                    title: format!("Put a space after `{name}`"),
                    edits: vec![(at(start, start), " ".to_string())],
                })
            }
            UnclosedComment if text == b"(" => {
                let content = line.len() - line.iter().rev().take_while(|&&c| c == b' ' || c == b'\t').count();
                Some(Fix {
                    title: "Close the comment with `)`".to_string(),
                    edits: vec![(at(content, content), ")".to_string())],
                })
            }
            IntegerExpected(counted) if let Some((word, reading)) = &counted.meant => {
                let address = &counted.address;
                // `P0.92` → `P920`, `P100.` → `P100`: the word meant, computed from what
                // the address counts (`dialect::roles::meant`), in place of the word.
                text.starts_with(address.as_bytes()).then_some(())?;
                text.contains(&b'.').then_some(())?;
                replace(format!("Write `{word}` ({reading})"), word)
            }
            DecimalPointUnverified { word: counted, .. }
                if text == counted.written.as_bytes()
                    && let Some((word, reading)) = &counted.meant =>
            {
                replace(format!("Write `{word}` ({reading} in least increments)"), word)
            }
            MissingDecimalPoint { word, readings } | MissingPointCauses { word, readings, .. }
                if text == word.as_bytes() =>
            {
                let with_point = &readings.1;
                let edit = (at(end, end), ".".to_string());
                Some(Fix { title: format!("Write `{word}.` ({with_point})"), edits: vec![edit] })
            }
            ThreadHeightRadial { word, meant: Some(meant), .. } if text == word.as_bytes() => {
                replace(format!("Write `{meant}` (the height as a diameter)"), meant)
            }
            SemicolonInOsp if text == b";" => {
                let comment =
                    &after[..after.len() - after.iter().rev().take_while(|&&c| c == b' ' || c == b'\t').count()];
                if comment.iter().any(|&c| c == b'(' || c == b')') {
                    return None;
                }
                let written = format!("({})", String::from_utf8_lossy(comment).trim());
                let edit = (at(start, end + comment.len()), written.clone());
                Some(Fix { title: format!("Write the comment as `{written}`"), edits: vec![edit] })
            }
            // Every other kind's hint needs judgement (or there is none).
            _ => None,
        }
    }
}
