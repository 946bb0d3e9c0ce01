use super::*;
use crate::compensation::fit::{FitOptions, Strategy};
use crate::compensation::inverse::{InverseOptions, compensate_samples};
use crate::compensation::test_support::lower_program;
use crate::compensation::written::sample_ranges;
use crate::error_model::ErrorModel;
use crate::error_model::effects::*;
use crate::error_model::sampling::sample_toolpath;
use crate::semantic::Lowered;
use crate::semantic::nose_radius::ToolTable;

/// A diameter-programmed metric program: a rapid down to X40, a turn, up a shoulder to X50
/// (an X reversal after the rapid), back down to X40 (another), a turn.
const PROGRAM: &str = "\
G21 G99
G97 S1000 M03
G00 X40. Z2.
G01 Z-10. F0.2
X50.
X40. Z-15.
Z-30.
G00 X100. Z50.
M30
";

fn plans(effects: Vec<Effect>) -> (Lowered, Vec<MovePlan>) {
    plans_judged(effects, Judged::Every)
}

/// `plans`, leaving as written what `judged` does not judge.
fn plans_judged(effects: Vec<Effect>, judged: Judged) -> (Lowered, Vec<MovePlan>) {
    let (lowered, machine) = lower_program(PROGRAM);
    let tools = ToolTable::from_machine(&machine);
    let path = &lowered.toolpath;
    let samples = sample_toolpath(path, &tools, 0.25);
    let model = ErrorModel { tables: None, effects, start_min: 0.0, control: None };
    let fit = FitOptions { strategy: Strategy::Densify, tolerance_mm: 0.0005, step_mm: None };
    let inverse =
        InverseOptions { tolerance_mm: fit.tolerance_mm, dead_band_mm: fit.tolerance_mm, ..InverseOptions::default() };
    let compensated = compensate_samples(&samples, path.start, &model, &inverse);
    let ranges = sample_ranges(path.moves.len(), &samples);
    let writable = vec![true; path.moves.len()];
    // The program writes no arc: any arc written would take the centre form.
    let radius = vec![false; path.moves.len()];
    let input = PlanInput {
        toolpath: path,
        samples: &samples,
        commanded: &compensated.commanded,
        take_ups: &compensated.take_ups,
        ranges: &ranges,
        writable: &writable,
        radius: &radius,
        tools: &tools,
        judged,
    };
    let grid = crate::back::grid::Grid::new(&lowered.coordinates_at(0));
    let plans = plan_moves(&input, |_| grid, &PlanOptions { fit, play: model.play() });
    (lowered.into_inner(), plans)
}

#[test]
fn without_errors_every_move_keeps_its_programmed_form() {
    let (lowered, plans) = plans(Vec::new());
    for (m, plan) in lowered.toolpath.moves.iter().zip(&plans) {
        assert!(!plan.changed);
        assert_eq!(plan.segments.as_slice(), [nominal_segment(m, &ToolTable::default())]);
    }
}

#[test]
fn a_constant_offset_moves_every_end_and_each_line_stays_one_line() {
    let (lowered, plans) = plans(vec![
        Effect::ToolOffsetX(ToolOffsetX { d: 0.01, axis: X }),
        Effect::ToolOffsetZ(ToolOffsetZ { d: -0.005, axis: Z }),
    ]);
    for (m, plan) in lowered.toolpath.moves.iter().zip(&plans) {
        assert!(plan.changed);
        assert_eq!(plan.segments.len(), 1, "{m:?}");
        let end = plan.end();
        assert!((end.x - (m.end.x - 0.01)).abs() < 1e-9 && (end.z - (m.end.z + 0.005)).abs() < 1e-9);
    }
    // Each move starts where the previous written one ended.
    for pair in plans.windows(2) {
        assert_eq!(pair[1].start, pair[0].end());
    }
}

/// The constant offset of `a_constant_offset_moves_every_end_and_each_line_stays_one_line`.
fn offset() -> Vec<Effect> {
    vec![Effect::ToolOffsetX(ToolOffsetX { d: 0.01, axis: X }), Effect::ToolOffsetZ(ToolOffsetZ { d: -0.005, axis: Z })]
}

#[test]
fn the_last_rapid_ends_where_it_is_programmed_and_every_feed_stays_corrected() {
    let (judged, plans) = plans_judged(offset(), Judged::EveryFeed);
    let (_, corrected) = plans_judged(offset(), Judged::Every);
    let moves = &judged.toolpath.moves;
    let last = moves.len() - 1;
    assert_eq!(moves[last].motion, Motion::Rapid);
    assert!(!plans[last].changed);
    assert_eq!(plans[last].end(), moves[last].contour);
    // The first rapid starts the cut at the corrected point, and every feed is as corrected.
    assert_eq!(plans[..last], corrected[..last]);
}

#[test]
fn the_backlash_at_an_x_reversal_is_its_own_move_at_the_reversal_point() {
    let b = 0.006;
    let (lowered, plans) = plans(vec![Effect::BacklashX(BacklashX { b, axis: X })]);
    let moves = &lowered.toolpath.moves;
    // Move 3 (`X40. Z-15.`) reverses X after the shoulder went up.
    let reversal = 3;
    assert!(moves[reversal - 1].end.x > moves[reversal - 2].end.x && moves[reversal].end.x < moves[reversal - 1].end.x);
    let plan = &plans[reversal];
    assert_eq!(plan.jumps, 1);
    let Segment::Line { end: jump } = plan.segments[0] else { panic!("{:?}", plan.segments) };
    // A pure X move of the whole play, down, from where the shoulder ended.
    assert!((jump.z - plan.start.z).abs() < 1e-12);
    assert!((plan.start.x - jump.x - b).abs() < 1e-9, "{} -> {}", plan.start.x, jump.x);
    // The rest of the move does not jump again: it runs to the corrected end.
    assert!(plan.segments.len() >= 2);
    // The shoulder reversed X too; nothing else does (and rapids are never split).
    let jumps: Vec<usize> = plans.iter().map(|p| p.jumps).collect();
    assert_eq!(jumps, [0, 0, 1, 1, 0, 0]);
}

#[test]
fn an_arc_the_control_would_run_off_after_rounding_is_cut_until_each_piece_runs_on_it() {
    // 340° about X47.9651 Z-63.6953 (radius 13.5): I K from the rounded start leave the
    // rounded end radii apart, and over the 4.5 mm chord the control's centre moves along
    // the chord by several times that.
    let grid = Grid::new(&lower_program("G21 G99\nM30\n").0.coordinates_at(0));
    let (centre, radius) = (Xz::new(47.965_13, -63.695_27), 13.502_3);
    let on = |degrees: f64| crate::geometry::on_circle(centre, radius, degrees.to_radians());
    let (start, end) = (on(160.33), on(141.13));
    let whole = Segment::Arc { end, centre, ccw: true };
    let words = grid.arc_words(start, end, centre, true, false);
    assert!(grid.arc_gap(start, end, centre, true, words) > grid.increment_mm(), "{words:?}");
    let plan =
        MovePlan { start, segments: smallvec![whole], changed: true, jumps: 0, lead_in: false, words: SmallVec::new() };
    let mut settled = plan;
    settle_arcs(&mut settled, &grid, false);
    assert!(settled.segments.len() >= 2, "{:?}", settled.segments);
    assert_eq!(settled.end(), end);
    let mut from = start;
    for segment in &settled.segments {
        let Segment::Arc { end, centre: c, ccw: true } = *segment else { panic!("{segment:?}") };
        assert_eq!(c, centre);
        assert!((end.distance(centre) - radius).abs() < 1e-9);
        let words = grid.arc_words(from, end, c, true, false);
        assert!(grid.arc_gap(from, end, c, true, words) <= grid.increment_mm(), "{from:?} -> {end:?}");
        from = end;
    }
}
