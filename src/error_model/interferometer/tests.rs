use super::*;

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
    let message = |text: &str| parse(text).unwrap_err().to_string();
    assert!(message("target_mm,linear_mm\n0,1\n").starts_with("line 1: the table has no direction of approach"));
    assert!(message("target_mm,direction\n0,up\n").starts_with("line 1: the table has no readings"));
    assert!(message("target_mm,direction,linear_mm\n0,sideways,1\n").starts_with("line 2: direction `sideways`"));
    assert!(message("target_mm,direction,linear_mm\n0,up,abc\n").starts_with("line 2: `linear_mm` is `abc`"));
    assert!(message("target_mm,direction,angular_deg\n").starts_with("line 1: the file has a header but no rows"));
}

#[test]
fn unknown_and_repeated_columns_are_refused_at_their_header_cell() {
    let text = "# X slide\ntarget_mm, direction,linear_mn\n0,up,0.001\n";
    let Err(error) = parse(text) else { panic!("a misspelt column was accepted") };
    assert_eq!((error.line, error.unknown_column.as_deref()), (2, Some("linear_mn")));
    assert_eq!(error.hint.as_deref(), Some("did you mean `linear_mm`?"));
    assert_eq!(&text[error.span.start as usize..error.span.end as usize], "linear_mn");
    let text = "target_mm,direction,\"linear_mm\",linear_mm\n0,up,0.001,0.002\n";
    let Err(error) = parse(text) else { panic!("a repeated column was accepted") };
    assert_eq!(error.span, Span::new(32, 41));
    assert_eq!(&text[32..41], "linear_mm");
    // A row's error covers the value that does not read.
    let text = "target_mm,direction,linear_mm\n0,up,abc\n";
    assert_eq!(parse(text).unwrap_err().span, Span::new(35, 38));
}

#[test]
fn row_errors_name_the_line_past_blank_and_comment_lines() {
    let text = "target_mm,direction,linear_mm\n0,up,0.001\n\n# a remark\n5,up,abc\n";
    assert_eq!(parse(text).unwrap_err().to_string(), "line 5: `linear_mm` is `abc`, not a finite number");
}

/// The layouts laser software writes read to the readings of the canonical table: µm and
/// inches, a row per target with a column per run and direction, readings as positions.
#[test]
fn every_layout_reads_to_the_canonical_readings() {
    let canonical = parse(TABLE).unwrap();
    let layouts = [
        "target_mm,direction,run,linear_um\n0,up,1,1\n0,up,2,3\n0,down,1,-1\n0,down,2,-1\n100,up,1,4\n100,up,2,4\n100,down,1,0\n100,down,2,2\n",
        "Units: µm\nTarget (mm),Run 1 Fwd,Run 1 Rev,Run 2 Fwd,Run 2 Rev\n0,1,-1,3,-1\n100,4,0,4,2\n",
        "Target (in),Run 1 ↑ (in),Run 1 ↓ (in),Run 2 ↑ (in),Run 2 ↓ (in)\n0,0.00003937007874015748,-0.00003937007874015748,0.00011811023622047244,-0.00003937007874015748\n3.937007874015748,0.00015748031496062992,0,0.00015748031496062992,0.00007874015748031496\n",
        "readings: positions\nTarget (mm);Run 1 Fwd (mm);Run 1 Rev (mm);Run 2 Fwd (mm);Run 2 Rev (mm);Mean (mm)\n0;0,001;-0,001;0,003;-0,001;0\n100;100,004;100,000;100,004;100,002;0\n",
    ];
    for text in layouts {
        let table = parse(text).unwrap_or_else(|e| panic!("{e}\n{text}"));
        let (got, want) = (table.linear.as_ref().unwrap(), canonical.linear.as_ref().unwrap());
        assert_eq!(got.targets, want.targets, "{text}");
        for (a, b) in [(&got.up, &want.up), (&got.down, &want.down), (&got.up_sigma, &want.up_sigma)] {
            assert!(a.iter().zip(b).all(|(a, b)| (a - b).abs() < 1e-9), "{a:?} against {b:?}\n{text}");
        }
        assert_eq!((&got.up_runs, &got.down_runs), (&want.up_runs, &want.down_runs), "{text}");
    }
}

#[test]
fn unlabelled_readings_are_told_by_their_values_or_refused() {
    // Errors of a few micrometres on targets 100 mm apart.
    let errors = parse("Target (mm),Run 1 Fwd (um),Run 1 Rev (um)\n0,1,-1\n100,4,0\n").unwrap();
    assert!((errors.linear.unwrap().up[1] - 0.004).abs() < 1e-12);
    // Positions of the laser, in mm.
    let positions = parse("Target (mm),Run 1 Fwd (mm),Run 1 Rev (mm)\n0,0.001,-0.001\n100,100.004,100.0\n").unwrap();
    assert!((positions.linear.unwrap().up[1] - 0.004).abs() < 1e-9);
    // Targets within 2 mm of zero: both would fit.
    let error = parse("Target (mm),Run 1 Fwd (mm),Run 1 Rev (mm)\n0,0.001,-0.001\n0.5,0.504,0.5\n").unwrap_err();
    assert!(error.message.contains("may be errors or positions"), "{error}");
    assert!(error.hint.unwrap().contains("readings: errors"));
}

#[test]
fn a_column_or_unit_that_cannot_be_placed_says_what_would_place_it() {
    let error = parse("Target (mm),Run 1 Fwd,Run 1 Rev\n0,1,-1\n").unwrap_err();
    assert_eq!(error.message, "the column `Run 1 Fwd` has no unit");
    assert!(error.hint.unwrap().contains("`Run 1 Fwd (um)`"));
    let error = parse("Target,direction,error (um)\n0,up,1\n").unwrap_err();
    assert_eq!(error.message, "the target column `Target` has no unit");
    let error = parse("Target (mm),Run 1 (um),Run 2 (um)\n0,1,-1\n").unwrap_err();
    assert!(error.message.contains("names a run but no direction"), "{error}");
    let error = parse("Units: furlongs\nTarget (mm),Run 1 Fwd,Run 1 Rev\n0,1,-1\n").unwrap_err();
    assert_eq!((error.line, error.label), (1, "not a unit"));
    let error = parse("Target (mm),Run 1 Fwd (um),Run 1 Rev (um),Coolant\n0,1,-1,on\n").unwrap_err();
    assert_eq!(error.unknown_column.as_deref(), Some("Coolant"));
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
