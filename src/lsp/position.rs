//! Columns in UTF-16 code units, as the Language Server Protocol counts them.
//!
//! turnpass spans are byte offsets. A line's bytes are UTF-8 in the editor's text, and
//! programs hold non-ASCII text often enough (`°` in comments, OCR damage, Shift-JIS that
//! the editor decoded): `°` is two bytes and one UTF-16 unit, `𝑥` four bytes and two units.
//! A span may also start or end inside a character (the parser reports a non-ASCII byte as
//! one byte), so a start rounds down and an end rounds up to the character's edges: the
//! editor underlines the whole character. A byte sequence that is not UTF-8 counts as one
//! unit per invalid sequence, as the replacement character the editor would show.

/// The UTF-16 column of byte `offset` in `line` (the line's text, without its terminator);
/// an offset inside a character counts it when `round_up`. Offsets past the end count the
/// whole line.
pub fn column_of(line: &[u8], offset: usize, round_up: bool) -> u32 {
    let offset = offset.min(line.len());
    if line[..offset].is_ascii() {
        // The common case, and the only one where the offset cannot fall inside a character.
        return offset as u32;
    }
    let mut units = 0u32;
    let mut at = 0usize;
    for chunk in line.utf8_chunks() {
        for c in chunk.valid().chars() {
            let end = at + c.len_utf8();
            if end > offset {
                if round_up && at < offset {
                    units += c.len_utf16() as u32;
                }
                return units;
            }
            units += c.len_utf16() as u32;
            at = end;
        }
        let invalid = chunk.invalid().len();
        if invalid > 0 {
            let end = at + invalid;
            if end > offset {
                if round_up && at < offset {
                    units += 1;
                }
                return units;
            }
            units += 1;
            at = end;
        }
    }
    units
}

/// The byte offset in `line` of UTF-16 column `column`. A column inside a surrogate pair
/// goes to the start of its character; a column past the end goes to the end of the line,
/// as the protocol asks.
pub fn offset_of(line: &[u8], column: u32) -> usize {
    let column = column as usize;
    if column <= line.len() && line[..column].is_ascii() {
        return column;
    }
    let mut units = 0usize;
    let mut at = 0usize;
    for chunk in line.utf8_chunks() {
        for c in chunk.valid().chars() {
            let next = units + c.len_utf16();
            if next > column {
                return at;
            }
            units = next;
            at += c.len_utf8();
        }
        if !chunk.invalid().is_empty() {
            if units + 1 > column {
                return at;
            }
            units += 1;
            at += chunk.invalid().len();
        }
    }
    line.len()
}

/// The length of a line's text: `line` without its final LF, CR LF or CR.
pub fn without_terminator(line: &[u8]) -> &[u8] {
    let line = line.strip_suffix(b"\n").unwrap_or(line);
    line.strip_suffix(b"\r").unwrap_or(line)
}

#[cfg(test)]
mod tests;
