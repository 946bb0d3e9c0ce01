use super::*;

#[test]
fn densify_keeps_one_line_for_straight_points_and_splits_a_bend() {
    let straight: Vec<Xz> = (1..=10).map(|i| Xz::new(10.0, -f64::from(i))).collect();
    let m = MovePoints { start: Xz::new(10.0, 0.0), points: &straight, nominal: NominalShape::Line };
    assert_eq!(densify(&m, 0.001, None), vec![Segment::Line { end: Xz::new(10.0, -10.0) }]);
    // A 5 µm bump in the middle: the chord from the start to the end misses it.
    let mut bent = straight.clone();
    bent[4].x += 0.005;
    let lines = densify(&MovePoints { points: &bent, ..m }, 0.001, None);
    assert!(lines.len() >= 2);
    let mut from = m.start;
    for s in &lines {
        from = s.end();
    }
    assert_eq!(from, Xz::new(10.0, -10.0));
    // Every point lies within the tolerance of the written lines.
    let mut a = m.start;
    let mut k = 0;
    for s in &lines {
        let b = s.end();
        while k < bent.len() && bent[k] != b {
            assert!(distance_to_chord(bent[k], a, b) <= 0.001);
            k += 1;
        }
        k += 1;
        a = b;
    }
}

#[test]
fn densify_at_a_step_writes_one_line_per_step() {
    let points: Vec<Xz> = (1..=100).map(|i| Xz::new(0.0, f64::from(i) * 0.254)).collect();
    let m = MovePoints { start: Xz::new(0.0, 0.0), points: &points, nominal: NominalShape::Line };
    let lines = densify(&m, 0.001, Some(2.54));
    assert_eq!(lines.len(), 10);
    assert!((lines[0].end().z - 2.54).abs() < 1e-9);
}
