use super::*;

#[test]
fn columns_count_utf16_units() {
    let line = "(30°) X𝑥1".as_bytes();
    // `(30` is 3 bytes, `°` 2 bytes and 1 unit, `𝑥` 4 bytes and 2 units.
    assert_eq!(column_of(line, 3, false), 3);
    assert_eq!(column_of(line, 5, false), 4);
    assert_eq!(column_of(line, 4, false), 3, "inside `°`, rounded down");
    assert_eq!(column_of(line, 4, true), 4, "inside `°`, rounded up");
    let x = line.iter().position(|&b| b == b'X').unwrap();
    assert_eq!(column_of(line, x + 1 + 4, false), 9);
    assert_eq!(column_of(line, 100, false), 10);
    assert_eq!(offset_of(line, 4), 5);
    assert_eq!(offset_of(line, 8), x + 1, "inside the surrogate pair of `𝑥`");
    assert_eq!(offset_of(line, 9), x + 5);
    assert_eq!(offset_of(line, 99), line.len());
}

#[test]
fn invalid_bytes_count_one_unit_per_sequence() {
    let line = b"A\xB0B";
    assert_eq!(column_of(line, 2, false), 2);
    assert_eq!(offset_of(line, 2), 2);
    assert_eq!(offset_of(line, 1), 1);
}

#[test]
fn terminators_come_off() {
    assert_eq!(without_terminator(b"X1\r\n"), b"X1");
    assert_eq!(without_terminator(b"X1\r"), b"X1");
    assert_eq!(without_terminator(b"X1"), b"X1");
}
