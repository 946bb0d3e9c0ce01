use super::*;

fn feed(end: Xz) -> Move {
    Move {
        motion: Motion::Feed,
        compensation: Compensation::Off,
        cutting: true,
        threading: false,
        per_revolution: true,
        tool: 1,
        offset: 1,
        end,
        centre: Xz::new(f64::NAN, f64::NAN),
        contour: end,
        feed: 100.0,
        f_word: 100.0,
        s_word: 1000.0,
        rpm: 1000.0,
        phase: 0.0,
        t_start: 0.0,
        t_end: 1.0,
        source: Span::new(0, 1),
        cycle: Span::SYNTHETIC,
    }
}

#[test]
fn a_clean_path_validates() {
    let path = Toolpath { start: Xz::new(0.0, 0.0), moves: vec![feed(Xz::new(1.0, 0.0))] };
    assert!(validate(&path, None).is_ok());
}

#[test]
fn an_arc_whose_end_is_off_its_circle_is_rejected() {
    let mut arc = feed(Xz::new(2.0, 0.0));
    arc.motion = Motion::Ccw;
    arc.centre = Xz::new(0.0, 0.0);
    let path = Toolpath { start: Xz::new(1.0, 0.0), moves: vec![arc] };
    let problems = validate(&path, None).unwrap_err();
    assert!(matches!(problems[0].kind, DiagnosticKind::ArcEndOffCircle { .. }));
}

#[test]
fn travel_limits_catch_an_arc_bulging_out() {
    let mut arc = feed(Xz::new(0.0, -2.0));
    arc.motion = Motion::Ccw;
    arc.centre = Xz::new(0.0, -1.0);
    // From Z0 to Z-2 about Z-1 counter-clockwise bulges to X+1 at the top.
    let path = Toolpath { start: Xz::new(0.0, 0.0), moves: vec![arc] };
    let limits = Limits { x_min: -0.5, x_max: 0.5, z_min: -10.0, z_max: 10.0 };
    let problems = validate(&path, Some(limits)).unwrap_err();
    assert!(matches!(problems[0].kind, DiagnosticKind::OutsideTravel { .. }));
}

#[test]
fn non_finite_points_and_time_running_back_are_rejected() {
    let mut bad = feed(Xz::new(f64::NAN, 0.0));
    bad.t_end = 2.0;
    let mut back = feed(Xz::new(1.0, 0.0));
    back.t_start = 0.5;
    back.t_end = 0.4;
    let path = Toolpath { start: Xz::default(), moves: vec![bad, back] };
    let problems = validate(&path, None).unwrap_err();
    assert_eq!(problems.len(), 2);
}

#[test]
fn a_non_finite_move_does_not_set_the_time_the_next_must_not_run_back_from() {
    // The middle move is non-finite, so the move after it is checked against the time of
    // the move before it, and runs back from that one; so does the last move.
    let count = 11;
    let middle = count / 2;
    let mut moves: Vec<Move> = (0..count)
        .map(|k| {
            let mut m = feed(Xz::new(k as f64, 0.0));
            m.t_start = k as f64;
            m.t_end = k as f64 + 1.0;
            // A block of its own: the problems of one block are one diagnostic with repeats.
            m.source = Span::new(k as u32, k as u32 + 1);
            m
        })
        .collect();
    moves[middle].end.x = f64::NAN;
    moves[middle + 1].t_start = middle as f64 - 0.5;
    moves[middle + 1].t_end = middle as f64 - 0.25;
    moves[count - 1].t_end = 0.0;
    let path = Toolpath { start: Xz::default(), moves };
    let problems = validate(&path, None).unwrap_err();
    let kinds: Vec<_> = problems.iter().map(|d| d.kind.clone()).collect();
    assert_eq!(kinds, [DiagnosticKind::NonFiniteMove, DiagnosticKind::TimeGoesBack, DiagnosticKind::TimeGoesBack]);
}

#[test]
fn the_moves_of_one_block_give_one_diagnostic_with_its_repeats() {
    // A block run in a loop, each pass outside the travel: one diagnostic, the rest counted.
    let limits = Limits { x_min: -10.0, x_max: 10.0, z_min: -10.0, z_max: 10.0 };
    let moves: Vec<Move> = (0..10_000)
        .map(|k| Move { t_start: k as f64, t_end: k as f64 + 1.0, ..feed(Xz::new(20.0 + k as f64, 0.0)) })
        .collect();
    let path = Toolpath { start: Xz::default(), moves };
    let problems = validate(&path, Some(limits)).unwrap_err();
    assert_eq!(problems.len(), 1, "{:?}", &problems[..problems.len().min(3)]);
    assert!(matches!(problems[0].kind, DiagnosticKind::OutsideTravel { x_mm, .. } if x_mm == 20.0));
    assert_eq!(problems[0].repeats, 9_999);
}
