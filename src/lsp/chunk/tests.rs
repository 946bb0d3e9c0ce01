use super::*;

#[test]
fn boundaries_keep_cr_lf_pairs_and_continuations_together() {
    let text = b"G00\r\nX1\r$A\nZ2\n";
    assert!(!is_boundary(text, 4), "between CR and LF");
    assert!(is_boundary(text, 5));
    assert!(!is_boundary(text, 8), "before a `$` line");
    assert!(is_boundary(text, 11));
    let lengths = split(text, 0..text.len(), 1);
    assert_eq!(lengths, vec![5, 6, 3]);
    assert_eq!(lengths.iter().sum::<usize>(), text.len());
}

#[test]
fn line_starts_follow_every_terminator() {
    assert_eq!(line_starts(b"A\r\nB\rC\nD"), vec![0, 3, 5, 7]);
    assert_eq!(line_starts(b"A\n"), vec![0]);
    assert_eq!(line_starts(b""), vec![0]);
}
