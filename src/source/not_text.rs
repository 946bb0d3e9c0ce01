//! Telling a program's text from a file that is not text (an executable, a compressed
//! archive, a picture, a program saved as UTF-16), so that such a file gets one diagnostic
//! instead of a parse that echoes its bytes.
//!
//! The rule: in the first [`SAMPLE_BYTES`] of the file, at least [`MIN_CONTROL_BYTES`] bytes,
//! and more than one in [`CONTROL_SHARE_DIVISOR`], are control bytes (below 0x20 other than
//! tab, line feed, vertical tab, form feed and carriage return, or 0x7F). A program has
//! almost none: a stray NUL or tape code left by a transfer is a diagnostic of the parse, and
//! text in another encoding (Shift-JIS, Latin-1) has bytes above 0x7F, not control bytes.
//! Compressed or random data has about one in nine, executables far more.

/// How much of the file the rule looks at.
pub const SAMPLE_BYTES: usize = 8192;
/// Fewer control bytes than this never make a file binary (a short program with a few tape
/// codes or a DOS end-of-file mark is text).
pub const MIN_CONTROL_BYTES: usize = 8;
/// More than one control byte in this many makes a file binary.
pub const CONTROL_SHARE_DIVISOR: usize = 20;

/// Why a file is not a text program (its diagnostic: `NotText::diagnostic`, in
/// `diagnostic.rs`, which sits above the source).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NotText {
    /// The first control byte: where the diagnostic points.
    pub offset: u32,
    pub byte: u8,
    /// Control bytes in the sample, the sample's length, and whether it is the whole file.
    pub control_bytes: usize,
    pub sampled: usize,
    pub whole_file: bool,
    /// The file looks like UTF-16 text (a byte-order mark, or NUL in every other byte).
    pub utf16: bool,
}

impl NotText {
    /// The part of the file a renderer may show: everything before the first control byte
    /// (text, by the rule) and that byte replaced by one that is not UTF-8, so that it shows
    /// as U+FFFD. Spans into the file keep their offsets; nothing after the byte is echoed.
    pub fn shown(&self, source: &[u8]) -> Vec<u8> {
        let mut shown = source[..self.offset as usize].to_vec();
        shown.push(0xFF);
        shown
    }
}

fn is_control(byte: u8) -> bool {
    (byte < 0x20 && !matches!(byte, b'\t' | b'\n' | 0x0B | 0x0C | b'\r')) || byte == 0x7F
}

/// `Some` when `source` is not a text program, by the rule above.
pub fn not_text(source: &[u8]) -> Option<NotText> {
    let sample = &source[..source.len().min(SAMPLE_BYTES)];
    let control_bytes = sample.iter().filter(|&&b| is_control(b)).count();
    if control_bytes < MIN_CONTROL_BYTES || control_bytes * CONTROL_SHARE_DIVISOR <= sample.len() {
        return None;
    }
    let offset = sample.iter().position(|&b| is_control(b))?;
    Some(NotText {
        offset: offset as u32,
        byte: sample[offset],
        control_bytes,
        sampled: sample.len(),
        whole_file: sample.len() == source.len(),
        utf16: looks_like_utf16(sample),
    })
}

/// A byte-order mark, or NUL in nearly every byte of one parity and in almost none of the
/// other (ASCII text saved as UTF-16).
fn looks_like_utf16(sample: &[u8]) -> bool {
    if sample.starts_with(&[0xFF, 0xFE]) || sample.starts_with(&[0xFE, 0xFF]) {
        return true;
    }
    let nul_at = |parity: usize| sample.iter().skip(parity).step_by(2).filter(|&&b| b == 0).count();
    let half = sample.len() / 2;
    let (even, odd) = (nul_at(0), nul_at(1));
    half > 0 && (odd * 10 >= half * 9 && even * 20 < half || even * 10 >= half * 9 && odd * 20 < half)
}
