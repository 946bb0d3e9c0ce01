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
    let mut column = 0;
    for (start, end, units) in characters(line) {
        if end > offset {
            if round_up && start < offset {
                column += units;
            }
            break;
        }
        column += units;
    }
    column
}

/// The byte offset in `line` of UTF-16 column `column`. A column inside a surrogate pair
/// goes to the start of its character; a column past the end goes to the end of the line,
/// as the protocol asks.
pub fn offset_of(line: &[u8], column: u32) -> usize {
    if (column as usize) <= line.len() && line[..column as usize].is_ascii() {
        return column as usize;
    }
    let mut units_before = 0;
    for (start, _, units) in characters(line) {
        if units_before + units > column {
            return start;
        }
        units_before += units;
    }
    line.len()
}

/// Each character of `line` as (start, end, UTF-16 units); a sequence that is not UTF-8 is
/// one character of one unit, as the replacement character an editor shows for it.
fn characters(line: &[u8]) -> impl Iterator<Item = (usize, usize, u32)> + '_ {
    let mut at = 0;
    line.utf8_chunks().flat_map(move |chunk| {
        let base = at;
        at += chunk.valid().len() + chunk.invalid().len();
        let valid =
            chunk.valid().char_indices().map(move |(i, c)| (base + i, base + i + c.len_utf8(), c.len_utf16() as u32));
        let invalid_start = base + chunk.valid().len();
        let invalid =
            (!chunk.invalid().is_empty()).then_some((invalid_start, invalid_start + chunk.invalid().len(), 1));
        valid.chain(invalid)
    })
}

/// The length of a line's text: `line` without its final LF, CR LF or CR.
pub fn without_terminator(line: &[u8]) -> &[u8] {
    let line = line.strip_suffix(b"\n").unwrap_or(line);
    line.strip_suffix(b"\r").unwrap_or(line)
}

#[cfg(test)]
mod tests;
