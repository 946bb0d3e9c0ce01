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
