//! Where spelled text goes: a `String` (the canonical form, `spelling::plain`), or the bytes
//! of a printed program (new blocks, `printer/written.rs`), which take the ASCII of codes,
//! addresses, numbers and copied words as it is, where a `String` takes it one character
//! at a time.

/// Text the printer appends to.
pub trait Text {
    fn push_str(&mut self, text: &str);

    /// Append `ascii`, which holds ASCII characters only (digits, letters, signs).
    fn push_ascii(&mut self, ascii: &[u8]);

    fn push_byte(&mut self, ascii: u8) {
        self.push_ascii(&[ascii]);
    }

    /// Append `bytes` copied from a program's source (a comment, a word kept as written):
    /// a printed program takes them byte for byte, whatever encoding they are in (a
    /// comment in Latin-1 stays Latin-1); a `String` takes them as UTF-8, each byte that
    /// is not a replacement character.
    fn push_source(&mut self, bytes: &[u8]) {
        self.push_str(&String::from_utf8_lossy(bytes));
    }
}

impl Text for String {
    fn push_str(&mut self, text: &str) {
        String::push_str(self, text);
    }

    fn push_ascii(&mut self, ascii: &[u8]) {
        self.extend(ascii.iter().map(|&byte| char::from(byte)));
    }

    fn push_byte(&mut self, ascii: u8) {
        self.push(char::from(ascii));
    }
}

impl Text for Vec<u8> {
    fn push_str(&mut self, text: &str) {
        self.extend_from_slice(text.as_bytes());
    }

    fn push_ascii(&mut self, ascii: &[u8]) {
        self.extend_from_slice(ascii);
    }

    fn push_byte(&mut self, ascii: u8) {
        self.push(ascii);
    }

    fn push_source(&mut self, bytes: &[u8]) {
        self.extend_from_slice(bytes);
    }
}
