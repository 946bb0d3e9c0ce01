use super::*;

thread_local! {
    /// Bytes of a text that `RecordLines` looked at on this thread.
    static LOOKED_AT: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

pub(crate) fn count_looked_at(bytes: usize) {
    LOOKED_AT.with(|n| n.set(n.get() + bytes));
}

/// The bytes `RecordLines` looked at on this thread since the last call.
pub(crate) fn take_looked_at() -> usize {
    LOOKED_AT.with(|n| n.replace(0))
}

/// Two targets, two runs each way: every ISO 230-2 figure worked by hand.
const TABLE: &str = "\
# A small ISO 230-2 style table: deviations in mm.
target_mm,direction,run,linear_mm
0,up,1,0.001
0,up,2,0.003
0,down,1,-0.001
0,down,2,-0.001
100,up,1,0.004
100,up,2,0.004
100,down,1,0.000
100,down,2,0.002
";

#[test]
fn iso_230_2_figures_by_hand() {
    let table = parse(TABLE).unwrap();
    let p = table.linear.as_ref().unwrap();
    assert_eq!(p.targets, vec![0.0, 100.0]);
    // Means: 0 up 0.002, down −0.001; 100 up 0.004, down 0.001.
    assert!((p.up[0] - 0.002).abs() < 1e-12 && (p.down[1] - 0.001).abs() < 1e-12);
    // σ of (0.001, 0.003) is √2 · 0.001.
    assert!((p.up_sigma[0] - 2f64.sqrt() * 0.001).abs() < 1e-12);
    let r = report(p);
    // E: max(0.004) − min(−0.001) = 0.005. M: means 0.0005 and 0.0025 → 0.002.
    assert!((r.systematic - 0.005).abs() < 1e-12);
    assert!((r.mean_range - 0.002).abs() < 1e-12);
    // B_i = 0.003 at both targets.
    assert!((r.reversal.unwrap() - 0.003).abs() < 1e-12 && (r.mean_reversal.unwrap() - 0.003).abs() < 1e-12);
    // A: max(x̄ + 2s) = 0.004 + 0 or 0.002 + 2√2·0.001 = 0.004828…; min(x̄ − 2s) at 100 down:
    // 0.001 − 2√2·0.001 = −0.001828…; also 0 down: −0.001 − 0. So A = 0.006657…
    let two_s = 2.0 * 2f64.sqrt() * 0.001;
    assert!((r.accuracy.unwrap() - ((0.002 + two_s) - (0.001 - two_s))).abs() < 1e-12);
    // R_i = 2s↑ + 2s↓ + |B|: at 0, 2√2·0.001 + 0 + 0.003; at 100, 0 + 2√2·0.001 + 0.003.
    assert!((r.repeatability.unwrap() - (two_s + 0.003)).abs() < 1e-12);
    assert!(r.not_measured.is_empty());
}

#[test]
fn the_model_uses_the_mean_of_the_direction_of_travel_and_interpolates() {
    let table = parse(TABLE).unwrap();
    assert!((table.linear(50.0, 1) - 0.003).abs() < 1e-12);
    assert!((table.linear(50.0, -1) - 0.0).abs() < 1e-12);
    // Held at the end values beyond the targets.
    assert!((table.linear(-10.0, 1) - 0.002).abs() < 1e-12);
    assert!((table.linear(500.0, -1) - 0.001).abs() < 1e-12);
}

#[test]
fn straightness_from_two_reversed_runs_is_half_their_difference() {
    let table =
        parse("target_mm,direction,straightness_m1_mm,straightness_m2_mm\n0,up,0.001,0.003\n50,up,-0.002,0.004\n")
            .unwrap();
    let s = table.straightness.unwrap();
    assert_eq!(s.up, vec![0.001, 0.003]);
}

#[test]
fn bad_tables_are_refused_with_the_line() {
    assert!(matches!(parse("target_mm,linear_mm\n0,1\n"), Err(TableError::MissingColumn { name: "direction", .. })));
    assert!(matches!(parse("target_mm,direction\n0,up\n"), Err(TableError::NoErrors { .. })));
    assert!(matches!(parse("target_mm,direction,linear_mm\n0,sideways,1\n"), Err(TableError::Row { line: 2, .. })));
    assert!(matches!(parse("target_mm,direction,linear_mm\n0,up,abc\n"), Err(TableError::Row { line: 2, .. })));
    assert!(matches!(parse("target_mm,direction,angular_deg\n"), Err(TableError::Empty)));
}

#[test]
fn unknown_and_repeated_columns_are_refused_at_their_header_cell() {
    let text = "# X slide\ntarget_mm, direction,linear_um\n0,up,0.001\n";
    let Err(error) = parse(text) else { panic!("a misspelt column was accepted") };
    let TableError::UnknownColumn { line, span, ref name, suggestion } = error else { panic!("{error:?}") };
    assert_eq!((line, name.as_str(), suggestion), (2, "linear_um", Some("linear_mm")));
    assert_eq!(&text[span.start as usize..span.end as usize], "linear_um");
    assert_eq!(error.span(text), span);
    let text = "target_mm,direction,\"linear_mm\",linear_mm\n0,up,0.001,0.002\n";
    let Err(error) = parse(text) else { panic!("a repeated column was accepted") };
    let TableError::DuplicateColumn { span, .. } = error else { panic!("{error:?}") };
    assert_eq!(span, Span::new(32, 41));
    assert_eq!(&text[32..41], "linear_mm");
    // A row's error covers the value that does not read.
    let text = "target_mm,direction,linear_mm\n0,up,abc\n";
    let error = parse(text).unwrap_err();
    assert_eq!(error.span(text), Span::new(35, 38));
}

#[test]
fn row_errors_name_the_line_past_blank_and_comment_lines() {
    let text = "target_mm,direction,linear_mm\n0,up,0.001\n\n# a remark\n5,up,abc\n";
    assert_eq!(parse(text).unwrap_err().to_string(), "line 5: `abc` is not a number in column linear_mm");
}

/// ISO 230-2 figures a table cannot give are not measured, not zero: B without the other
/// direction, A and R without two runs (one run each way would make R read |B|).
#[test]
fn figures_a_table_cannot_give_are_not_measured() {
    let one_way =
        parse("target_mm,direction,run,linear_mm\n0,up,1,0.001\n0,up,2,0.003\n100,up,1,0.004\n100,up,2,0.004\n")
            .unwrap();
    let r = report(one_way.linear.as_ref().unwrap());
    assert_eq!((r.reversal, r.mean_reversal), (None, None));
    assert_eq!(r.not_measured.get("reversal"), Some(&ONE_DIRECTION));
    // One direction, two runs: R is its 4s, A its x̄ ± 2s.
    let four_s = 4.0 * 2f64.sqrt() * 0.001;
    assert!((r.repeatability.unwrap() - four_s).abs() < 1e-12);
    assert!(r.accuracy.is_some());

    let each_way_once =
        parse("target_mm,direction,linear_mm\n0,up,0.001\n0,down,-0.002\n100,up,0.004\n100,down,0.003\n").unwrap();
    let r = report(each_way_once.linear.as_ref().unwrap());
    assert!((r.reversal.unwrap() - 0.003).abs() < 1e-12 && (r.mean_reversal.unwrap() - 0.002).abs() < 1e-12);
    assert_eq!((r.accuracy, r.repeatability), (None, None));
    assert_eq!(r.not_measured.get("repeatability"), Some(&ONE_RUN));
    assert!((r.systematic - 0.006).abs() < 1e-12);
}
