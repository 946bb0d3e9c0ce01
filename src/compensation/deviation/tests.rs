use super::*;
use crate::compensation::sampling::sample_toolpath;
use crate::compensation::test_support::lower_program;
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
    let whole = PathIndex::new(toolpath, |m| m.cutting).distance(p).unwrap();
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
