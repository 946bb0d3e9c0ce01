use super::*;

#[test]
fn line_index_handles_lf_crlf_and_lone_cr() {
    let src = b"G00\r\nG01\rG02\nG03";
    let index = LineIndex::new(src);
    assert_eq!(index.line_count(), 4);
    assert_eq!(index.position(0), (1, 1));
    assert_eq!(index.position(5), (2, 1));
    assert_eq!(index.position(9), (3, 1));
    assert_eq!(index.position(13), (4, 1));
    assert_eq!(index.position(14), (4, 2));
}

#[test]
fn display_text_maps_offsets_across_invalid_bytes() {
    // 0x82 0xA0 is Shift-JIS; neither byte starts valid UTF-8 here.
    let src = b"(\x82\xa0)X1";
    let display = DisplayText::new(src);
    assert!(display.text.contains('\u{FFFD}'));
    let x_source = 4;
    assert_eq!(&display.text[display.offset(x_source)..], "X1");
    assert_eq!(display.offset(0), 0);
}

#[test]
fn not_text_needs_enough_control_bytes_and_a_share_of_them() {
    // Seven control bytes never make a file binary, however short it is.
    assert_eq!(not_text(b"\x12G00 X1.\x14\n\0\0\0\0\x1a"), None);
    // Eight in a short file do; the diagnostic is on the first one.
    let found = not_text(b"G00 X1.\n\x01\x02\x03\x04\x05\x06\x07\x08").unwrap();
    assert_eq!((found.offset, found.byte, found.control_bytes, found.whole_file), (8, 1, 8, true));
    // One in twenty or fewer is text: a long program with a few NULs left by a transfer.
    let mut program = b"G01 X1.5 Z-2. F0.1\n".repeat(100);
    program[40..50].fill(0);
    assert_eq!(not_text(&program), None);
    // Text in another encoding has bytes above 0x7F, not control bytes.
    assert_eq!(not_text(&b"(\x83e\x83X\x83g \x93\xfa\x96\x7b)\nG00 X1.\n".repeat(50)), None);
    // Only the first 8 KiB count: a binary tail after a long program is not looked at.
    let mut tail = b"G01 X1.5 Z-2. F0.1\n".repeat(500);
    tail.extend(std::iter::repeat_n(0u8, 5000));
    assert_eq!(not_text(&tail), None);
}

#[test]
fn not_text_names_utf16() {
    let utf16: Vec<u8> = "O1000\nG00 X1.\n".encode_utf16().flat_map(u16::to_le_bytes).collect();
    assert!(not_text(&utf16).unwrap().utf16);
    assert!(!not_text(&[0x7F; 64]).unwrap().utf16);
}
