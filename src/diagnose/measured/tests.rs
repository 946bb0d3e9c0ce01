use super::*;
use crate::measurement_file::tests::{take_looked_at, take_rows_read};

/// A trace of 2,000 rows is read in one pass over its text: the lines of its records are
/// counted on from each other, where a count from the top for each would look at about
/// 1,000 times the text.
#[test]
fn a_long_trace_is_read_in_one_pass() {
    let text = include_str!("../../../tests/cases/bounded/ballbar-2000-rows.csv");
    take_looked_at();
    let Measured::BallBar(rows) = read(text, None).unwrap() else { panic!("not a ball bar") };
    assert_eq!((rows.len(), rows[1999].line), (2000, 2003));
    let looked_at = take_looked_at();
    assert!(looked_at <= 2 * text.len(), "{looked_at} bytes looked at for a text of {}", text.len());
}

/// A file whose lines end in a lone CR reads as one with LF ends: its records are lines
/// (as the CSV reader and the program's line index count them), so a bad value is found
/// at its own line and cell.
#[test]
fn a_bad_value_is_found_in_a_file_of_lone_cr_line_ends() {
    let text = include_str!("../../../tests/cases/bounded/ballbar-cr-line-ends.csv");
    let error = read(text, None).unwrap_err();
    assert_eq!(&text[error.span.start as usize..error.span.end as usize], "0.00x9");
    assert_eq!(error.line, 4);
}

/// A bad row is reported when it is read: the rows after it are not read first.
#[test]
fn a_bad_row_ends_the_reading() {
    let text = include_str!("../../../tests/cases/bounded/ballbar-bad-row-early.csv");
    take_rows_read();
    let error = read(text, None).unwrap_err();
    assert_eq!((error.line, &text[error.span.start as usize..error.span.end as usize]), (4, "0.00O9"));
    assert_eq!(error.hint.as_deref(), Some("`O` typed for `0`? did you mean `0.0009`?"));
    let read = take_rows_read();
    assert!(read <= 2, "{read} records read (the header and the bad row are two)");
}

#[test]
fn a_ball_bar_trace_reads_with_its_lines_and_kind_from_the_header() {
    let text =
        "# QC10 run, 2024-05-02\nangle_deg,deviation_mm,direction\n0,0.0012,ccw\n1.0, -0.0004 ,CCW\n\n2,0.001,cw\n";
    let Measured::BallBar(rows) = read(text, None).unwrap() else { panic!("not a ball bar") };
    assert_eq!(rows.len(), 3);
    assert_eq!((rows[0].line, rows[1].line, rows[2].line), (3, 4, 6));
    assert_eq!(rows[1].direction, Direction::Ccw);
    assert_eq!(rows[2].direction, Direction::Cw);
    assert_eq!(rows[1].deviation_mm, -0.0004);
}

#[test]
fn a_profile_reads_with_parts_and_start_times() {
    let text = "part,start_min,x_mm,z_mm\nA,0,10.0,-1.0\nA,0,10.0,-2.0\nB,30,10.001,-1.0\n";
    let Measured::Profile(points) = read(text, Some(Kind::Profile)).unwrap() else { panic!("not a profile") };
    assert_eq!(points[2].part.as_deref(), Some("B"));
    assert_eq!(points[2].start_min, Some(30.0));
    let plain = read("x_mm,z_mm\n5,0\n", None).unwrap();
    assert_eq!(plain.kind(), Kind::Profile);
}

#[test]
fn errors_name_the_line_and_the_fault() {
    let cases = [
        ("angle_deg,deviation_mm,direction\n0,0.001,ccw\n5,abc,ccw\n", "line 3: `deviation_mm` is `abc`"),
        ("angle_deg,deviation_mm,direction\n0,0.001,up\n", "line 2: `direction` is `up`"),
        ("angle_deg,deviaton_mm,direction\n", "line 1: unknown column `deviaton_mm`"),
        ("angle_deg,direction\n0,ccw\n", "line 1: the header has no `deviation_mm` column"),
        ("angle_deg,deviation_mm,direction\n", "line 1: the file has a header but no rows"),
        ("angle_deg,deviation_mm,direction\n0,25.0,ccw\n", "line 2: a ball bar deviation of 25 mm"),
        ("angle_deg,deviation_mm,direction\n0,,ccw\n", "line 2: no value for `deviation_mm`"),
        ("x_mm,z_mm\n1,2\n-3,4\n", "line 3: x_mm is -3"),
        ("x_mm,z_mm,part,start_min\n1,2,A,0\n1,3,A,5\n", "line 3: part A started at 0 min on line 2, not 5"),
        ("x_mm,z_mm\n1,inf\n", "line 2: `z_mm` is `inf`"),
        ("", "line 1: the file is empty"),
        ("a,b\n1,2\n", "line 1: the header names neither"),
    ];
    for (text, expected) in cases {
        let message = read(text, None).unwrap_err().to_string();
        assert!(message.starts_with(expected), "{message:?} should start with {expected:?}");
    }
    let message = read("x_mm,z_mm\n1,2\n", Some(Kind::BallBar)).unwrap_err().to_string();
    assert!(message.contains("unknown column `x_mm`"), "{message}");
}

#[test]
fn a_thermal_log_reads_and_refuses_times_that_go_back() {
    let (t, v) = read_thermal_log("t_min,value\n0,67.6\n0.5,67.9\n1.0,68.1\n").unwrap();
    assert_eq!((t.len(), v[2]), (3, 68.1));
    let message = read_thermal_log("t_min,value\n0,67.6\n0,67.9\n").unwrap_err().to_string();
    assert!(message.starts_with("line 3: t_min 0 does not come after"), "{message}");
    let message = read_thermal_log("time,value\n0,1\n").unwrap_err().to_string();
    assert!(message.starts_with("line 1: unknown column `time`"), "{message}");
}

/// Files in every layout, damaged at random: no reader panics, and an error names a line of
/// the text and a span inside it, on character boundaries.
mod damaged {
    use proptest::prelude::*;

    use super::*;

    const PIECES: [&str; 24] = [
        "Units: µm\n",
        "X: diameter\n",
        "Direction: cw\n",
        "Start angle: 90 deg\n",
        "Angle step: 1\n",
        "Axis: z\n",
        "Readings: positions\n",
        "Target (mm),Run 1 Fwd (um),Run 1 Rev (um)\n",
        "Target (in);Direction;Error (ppm)\n",
        "Point,X,Y,Z\n",
        "angle_deg,deviation_mm,direction\n",
        "x_mm,z_mm,part,start_min\n",
        "10,1.2,-2.1\n",
        "10;up;1,5\n",
        "P1,1.0,0.5,-2\n",
        "1,0.001,ccw\n",
        "# µ comment ↑\n",
        "\r\n",
        "\"q,uoted\",↓,é\n",
        "Run 2 ↑ [µm],(,[,)\n",
        ",,,\n",
        ":\n",
        "nan,inf,-0\n",
        "X (mm),Z (mm)\n",
    ];

    proptest! {
        #[test]
        fn damaged_files_are_refused_with_a_place_in_them(
            pieces in proptest::collection::vec(0..PIECES.len(), 0..12),
            cut in 0usize..400,
        ) {
            let mut text: String = pieces.iter().map(|&i| PIECES[i]).collect();
            let mut at = cut.min(text.len());
            while !text.is_char_boundary(at) {
                at -= 1;
            }
            text.truncate(at);
            for kind in [None, Some(KindName::BallBar), Some(KindName::Profile), Some(KindName::Table)] {
                for axis in [None, Some(Axis::X)] {
                    if let Err(error) = read_as(&text, kind, axis) {
                        let (start, end) = (error.span.start as usize, error.span.end as usize);
                        prop_assert!(start <= end && end <= text.len(), "{error:?} in {text:?}");
                        prop_assert!(text.is_char_boundary(start) && text.is_char_boundary(end), "{error:?}");
                        prop_assert!(error.line >= 1 && error.line <= text.lines().count() + 1, "{error:?}");
                    }
                }
            }
        }
    }
}
