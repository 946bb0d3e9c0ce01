use super::*;

thread_local! {
    /// Bytes of a text that `RecordLines` looked at on this thread.
    static LOOKED_AT: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
    /// Records the reader read on this thread.
    static ROWS_READ: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

pub(crate) fn count_looked_at(bytes: usize) {
    LOOKED_AT.with(|n| n.set(n.get() + bytes));
}

/// The bytes `RecordLines` looked at on this thread since the last call.
pub(crate) fn take_looked_at() -> usize {
    LOOKED_AT.with(|n| n.replace(0))
}

pub(crate) fn count_row_read() {
    ROWS_READ.with(|n| n.set(n.get() + 1));
}

/// The records read on this thread since the last call.
pub(crate) fn take_rows_read() -> usize {
    ROWS_READ.with(|n| n.replace(0))
}

#[test]
fn a_preamble_gives_keys_and_values_before_the_header() {
    let text = "Machine: Howa V40R\nUnits:,um,,\n# a remark\nStart Angle : 90\nTarget (mm),Run 1 Fwd (um)\n0,1\n";
    let mut file = DataFile::open(text).unwrap();
    assert_eq!(file.preamble.len(), 3);
    let units = file.meta("units").unwrap();
    assert_eq!((units.value.as_str(), units.line), ("um", 2));
    assert_eq!(&text[units.value_span.start as usize..units.value_span.end as usize], "um");
    assert_eq!(file.meta("start_angle").unwrap().value, "90");
    assert_eq!(file.header_line, 5);
    assert_eq!(file.header[1].text, "Run 1 Fwd (um)");
    let row = file.next_row().unwrap().unwrap();
    assert_eq!((row.line, row.number(1, "x").unwrap()), (6, 1.0));
}

#[test]
fn semicolons_separate_cells_when_the_header_has_no_comma_and_numbers_take_a_decimal_comma() {
    let text = "target;error (um)\n0;1,5\n100;-2,25\n";
    let mut file = DataFile::open(text).unwrap();
    assert_eq!(file.header.len(), 2);
    let mut values = Vec::new();
    file.rows(|row| {
        values.push(row.number(1, "error")?);
        Ok(())
    })
    .unwrap();
    assert_eq!(values, vec![1.5, -2.25]);
    let error = DataFile::open("a,b\n1,2\n").and_then(|mut f| {
        let row = f.next_row()?.unwrap();
        row.number(0, "a")?;
        Ok(())
    });
    assert!(error.is_ok());
}

#[test]
fn a_misspelt_preamble_key_is_refused_and_remarks_are_not() {
    let file = DataFile::open("Operator: J. Smith\nUntis: um\nx,y\n").unwrap();
    let error = file.check_preamble(&["units", "readings"]).unwrap_err();
    assert_eq!((error.line, error.hint.as_deref()), (2, Some("did you mean `units`?")));
    let file = DataFile::open("Operator: J. Smith\nx,y\n").unwrap();
    assert!(file.check_preamble(&["units"]).is_ok());
}

#[test]
fn column_names_give_words_and_units() {
    let name = column_name("Run 1 Fwd (µm)");
    assert_eq!((name.words.clone(), name.unit), (vec!["run".to_string(), "1".into(), "fwd".into()], Some(Unit::Um)));
    assert_eq!(column_name("target_mm").unit, Some(Unit::Mm));
    assert_eq!(column_name("target_mm").words, vec!["target".to_string()]);
    assert_eq!(column_name("straightness_m1_mm").words, vec!["straightness".to_string(), "m1".into()]);
    assert_eq!(column_name("run2-rev [in]").words, vec!["run".to_string(), "2".into(), "rev".into()]);
    assert_eq!(column_name("run2-rev [in]").unit, Some(Unit::Inch));
    assert_eq!(column_name("Error um/m").unit, Some(Unit::Ppm));
    assert_eq!(column_name("Run 1↑").words, vec!["run".to_string(), "1".into(), "↑".into()]);
    assert_eq!(column_name("x").unit, None);
    assert_eq!(column_name("Pitch (arcsec)").unit, Some(Unit::Arcsec));
}
