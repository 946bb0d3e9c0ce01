use super::*;
use crate::compensation::test_support::lower_program;
use crate::error_model::sampling::sample_toolpath;
use crate::semantic::nose_radius::ToolTable;

/// The sample of `toolpath` on the move ending at `end` with the parameter `param`.
fn sample_at(toolpath: &Toolpath, end: Xz, param: f64) -> PathSample {
    let samples = sample_toolpath(toolpath, &ToolTable::default(), 0.254);
    *samples
        .iter()
        .find(|s| toolpath.moves[s.move_index].end.distance(end) < 1e-9 && (s.param - param).abs() < 1e-9)
        .expect("a sample there")
}

#[test]
fn a_point_is_measured_against_its_own_pass_not_a_later_one_beside_it() {
    // Pass one along x 10 (diameter 20) from z 0 to z −10, back by rapids, pass two along
    // x 10.003: a point 2 µm off pass one is 1 µm from pass two.
    let (lowered, _) =
        lower_program("G21 G99\nG97 S1000 M03\nG00 X20. Z0.\nG01 Z-10. F0.2\nG00 X30.\nZ0.\nX20.006\nG01 Z-10.\n");
    let toolpath = &lowered.toolpath;
    let sample = sample_at(toolpath, Xz::new(10.0, -10.0), 0.5);
    assert!(sample.cutting && sample.nominal.distance(Xz::new(10.0, -5.0)) < 1e-9);
    let p = Xz::new(10.002, -5.0);
    let local = LocalPath::new(toolpath).distance(&sample, p).unwrap();
    assert!((local - 0.002).abs() < 1e-9, "{local}");
    let whole = (toolpath.moves.iter().enumerate())
        .filter(|(_, m)| m.cutting)
        .map(|(k, m)| distance_to_move(p, toolpath.start_of(k), m))
        .fold(f64::INFINITY, f64::min);
    assert!((whole - 0.001).abs() < 1e-9, "{whole}");
}

#[test]
fn a_point_that_slid_past_a_corner_is_measured_against_the_next_move() {
    // A turn along x 10 to z −10, then a face up to x 12: the last point of the turn,
    // predicted 3 µm beyond the corner and 2 µm in front of the face, is on the face's
    // surface within 2 µm (3.6 µm from the turn's end).
    let (lowered, _) = lower_program("G21 G99\nG97 S1000 M03\nG00 X20. Z0.\nG01 Z-10. F0.2\nX24.\n");
    let toolpath = &lowered.toolpath;
    let sample = sample_at(toolpath, Xz::new(10.0, -10.0), 1.0);
    let p = Xz::new(10.003, -10.002);
    let local = LocalPath::new(toolpath).distance(&sample, p).unwrap();
    assert!((local - 0.002).abs() < 1e-9, "{local}");
}

#[test]
fn a_sample_that_does_not_cut_has_no_deviation() {
    let (lowered, _) = lower_program("G21 G99\nG97 S1000 M03\nG00 X20. Z0.\nG01 Z-10. F0.2\n");
    let toolpath = &lowered.toolpath;
    let sample = sample_at(toolpath, Xz::new(10.0, 0.0), 1.0);
    assert!(!sample.cutting);
    assert_eq!(LocalPath::new(toolpath).distance(&sample, Xz::new(10.001, 0.0)), None);
}

#[test]
fn the_reach_counts_an_arcs_whole_circle_and_a_lines_end() {
    // The test machine starts at radius 100, z 50. From x 300 z 2 (radius 150) to z −80,
    // then a G02 of radius 5 to x 310 (radius 155) z −85 about x 155 z −80 (the centre
    // that turns it clockwise): the circle reaches radius 160 and z 85.
    let lines = "G21 G99\nG97 S1000 M03\nG00 X300. Z2.\nG01 Z-80. F0.2\n";
    let (lowered, _) = lower_program(&format!("{lines}G02 X310. Z-85. R5.\n"));
    assert_eq!(lowered.toolpath.start, Xz::new(100.0, 50.0));
    let centre = lowered.toolpath.moves[2].centre;
    assert!(centre.distance(Xz::new(155.0, -80.0)) < 1e-9, "{centre:?}");
    assert_eq!(LocalPath::new(&lowered.toolpath).reach(), Xz::new(160.0, 85.0));
    // Before the arc the line's end is the farthest.
    let (lowered, _) = lower_program(lines);
    assert_eq!(LocalPath::new(&lowered.toolpath).reach(), Xz::new(150.0, 80.0));
}

#[test]
fn an_original_that_deviates_by_nothing_has_no_improvement_ratio() {
    // A rounding error of the measure divided into a real deviation is a wild figure
    // (-4.8e17 % was printed): below a nanometre there is nothing to improve.
    let nothing = Figures::of([1e-19, 0.0, 2e-19]);
    let something = Figures::of([0.0005, 0.0004]);
    assert_eq!(nothing.improvement_percent(&something), None);
    assert_eq!(nothing.improvement_percent(&nothing), None);
    assert_eq!(Figures::of([0.002]).improvement_percent(&Figures::of([0.001])), Some(50.0));
    assert_eq!(Figures::of([0.001]).improvement_percent(&Figures::of([0.002])), Some(-100.0));
}
