use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

use proptest::prelude::*;

use super::path::{CornerKind, Curve, Problem, classify, corner_arc, offset, offset_chain, turn_angle};
use super::*;
use crate::geometry;
use crate::source::Span;
use crate::toolpath::{Limits, validate};

const LEFT: f64 = 1.0;
const RIGHT: f64 = -1.0;
const WEST: Xz = Xz::new(0.0, -1.0);
const NORTH: Xz = Xz::new(1.0, 0.0);

fn close(a: Xz, b: Xz, tolerance: f64) -> bool {
    a.distance(b) <= tolerance
}

fn line(start: Xz, end: Xz) -> Curve {
    Curve::Line { start, end }
}

fn unit(x: f64, z: f64) -> Xz {
    let n = x.hypot(z);
    Xz::new(x / n, z / n)
}

// ----- corners -----

#[test]
fn outside_turning_with_g42_classifies_steps_up_as_concave_and_shoulder_tops_as_convex() {
    // Along -Z with the nose above (G42): a chamfer up and away is a turn toward the tool,
    // and the chamfer's top, where the path turns back along -Z, turns away from it.
    let chamfer = unit(1.0, -1.0);
    assert_eq!(classify(WEST, chamfer, 0.4, RIGHT), CornerKind::Concave);
    assert_eq!(classify(chamfer, WEST, 0.4, RIGHT), CornerKind::Convex);
    // A face up the shoulder (+X) then on along -Z: the shoulder's outer edge is convex.
    assert_eq!(classify(WEST, NORTH, 0.4, RIGHT), CornerKind::Concave);
    assert_eq!(classify(NORTH, WEST, 0.4, RIGHT), CornerKind::Convex);
    // The other side of the path swaps them.
    assert_eq!(classify(WEST, chamfer, 0.4, LEFT), CornerKind::Convex);
    assert_eq!(classify(chamfer, WEST, 0.4, LEFT), CornerKind::Concave);
}

#[test]
fn a_straight_join_is_tangent_and_a_reversal_is_convex_on_either_side() {
    assert_eq!(classify(WEST, WEST, 0.4, RIGHT), CornerKind::Tangent);
    // A turn that moves the offset point by far less than a micrometre is still tangent ...
    let hair = unit(1e-9, -1.0);
    assert_eq!(classify(WEST, hair, 0.4, RIGHT), CornerKind::Tangent);
    // ... and one that moves it by more is a real corner.
    let small = unit(1e-5, -1.0);
    assert_eq!(classify(WEST, small, 0.4, RIGHT), CornerKind::Concave);
    assert_eq!(classify(WEST, small, 0.4, LEFT), CornerKind::Convex);
    let back = Xz::new(0.0, 1.0);
    assert_eq!(classify(WEST, back, 0.4, RIGHT), CornerKind::Convex);
    assert_eq!(classify(WEST, back, 0.4, LEFT), CornerKind::Convex);
    assert!((turn_angle(WEST, NORTH) + FRAC_PI_2).abs() < 1e-12, "-Z then +X turns right (clockwise)");
}

#[test]
fn the_corner_arc_rolls_round_the_corner_with_the_nose_radius() {
    // The top of a 45° chamfer at (15, -25) under G42 with r = 0.4 (the shoulder of the
    // case nose-radius-g42.nc): from 0.4 mm off the chamfer to 0.4 mm above the corner,
    // turning left (G03) through 45°.
    let corner = Xz::new(15.0, -25.0);
    let arc = corner_arc(corner, unit(1.0, -1.0), WEST, 0.4, RIGHT);
    let Curve::Arc { start, end, centre, ccw } = arc else { panic!("{arc:?}") };
    let h = 0.4 / 2f64.sqrt();
    assert!(close(start, Xz::new(15.0 + h, -25.0 + h), 1e-12), "{start:?}");
    assert!(close(end, Xz::new(15.4, -25.0), 1e-12), "{end:?}");
    assert_eq!(centre, corner);
    assert!(ccw);
    assert!((geometry::sweep(start, end, centre, ccw) - FRAC_PI_4).abs() < 1e-12);
    assert!((arc.length() - 0.4 * FRAC_PI_4).abs() < 1e-12);
    // With the tool on the left the same corner shape turns clockwise.
    let mirrored = corner_arc(corner, WEST, unit(1.0, -1.0), 0.4, LEFT);
    assert!(matches!(mirrored, Curve::Arc { ccw: false, .. }));
    // A reversal goes half way round.
    let reversal = corner_arc(corner, WEST, Xz::new(0.0, 1.0), 0.4, RIGHT);
    let Curve::Arc { start, end, centre, ccw } = reversal else { panic!() };
    assert!(close(start, Xz::new(15.4, -25.0), 1e-12) && close(end, Xz::new(14.6, -25.0), 1e-12));
    assert!((geometry::sweep(start, end, centre, ccw) - PI).abs() < 1e-12);
    // Through the end of the cut (-Z side), not back through the material.
    assert!(geometry::angle_within(Xz::new(15.0, -25.4), start, end, centre, ccw));
}

#[test]
fn arcs_offset_concentrically_and_a_concave_arc_tighter_than_the_nose_does_not_fit() {
    // G02 from (15, -40) to (20, -45) about (20, -40), nose above (G42): the nose runs inside.
    let arc =
        Curve::Arc { start: Xz::new(15.0, -40.0), end: Xz::new(20.0, -45.0), centre: Xz::new(20.0, -40.0), ccw: false };
    let (path, fits) = offset(arc, 0.4, RIGHT);
    assert!(fits);
    assert!(close(path.start(), Xz::new(15.4, -40.0), 1e-12) && close(path.end(), Xz::new(20.0, -44.6), 1e-12));
    let (outside, _) = offset(arc, 0.4, LEFT);
    assert!((outside.radius() - 5.4).abs() < 1e-12);
    let (_, fits) = offset(arc, 5.5, RIGHT);
    assert!(!fits);
    let (exact, fits) = offset(arc, 5.0, RIGHT);
    assert!(fits && exact.radius() < 1e-12);
}

/// The contour of nose-radius-g42.nc from its first cut on (radius, mm).
fn g42_contour() -> Vec<Curve> {
    vec![
        line(Xz::new(10.0, 2.0), Xz::new(10.0, -20.0)),
        line(Xz::new(10.0, -20.0), Xz::new(15.0, -25.0)),
        line(Xz::new(15.0, -25.0), Xz::new(15.0, -40.0)),
        Curve::Arc { start: Xz::new(15.0, -40.0), end: Xz::new(20.0, -45.0), centre: Xz::new(20.0, -40.0), ccw: false },
        line(Xz::new(20.0, -45.0), Xz::new(25.0, -45.0)),
    ]
}

#[test]
fn the_g42_case_cuts_back_the_concave_corner_rolls_round_the_convex_one_and_joins_tangents() {
    let offsets = offset_chain(&g42_contour(), 0.4, RIGHT);
    let h = 0.4 / 2f64.sqrt();
    // Concave: the lines 0.4 above Z- and 0.4 off the chamfer cross at Z = -20 + 0.4 tan 22.5°.
    let meet = Xz::new(10.4, -20.0 + 0.4 * (PI / 8.0).tan());
    assert!(close(offsets[0].path.end(), meet, 1e-12), "{:?}", offsets[0].path);
    assert!(close(offsets[1].path.start(), meet, 1e-12));
    assert!(offsets[1].lead_in.is_none());
    // Convex: the chamfer's path ends perpendicular at its top, the arc takes over.
    assert!(close(offsets[1].path.end(), Xz::new(15.0 + h, -25.0 + h), 1e-12));
    let lead_in = offsets[2].lead_in.expect("a corner arc");
    assert!(
        close(lead_in.start(), Xz::new(15.0 + h, -25.0 + h), 1e-12)
            && close(lead_in.end(), Xz::new(15.4, -25.0), 1e-12)
    );
    assert!(close(offsets[2].path.start(), Xz::new(15.4, -25.0), 1e-12));
    // Tangent: line into arc and arc into line share their offset points exactly.
    assert!(offsets[3].lead_in.is_none() && offsets[4].lead_in.is_none());
    assert!(close(offsets[2].path.end(), Xz::new(15.4, -40.0), 1e-12));
    assert!(close(offsets[3].path.start(), Xz::new(15.4, -40.0), 1e-12));
    assert!(close(offsets[3].path.end(), Xz::new(20.0, -44.6), 1e-12));
    assert!(close(offsets[4].path.end(), Xz::new(25.0, -44.6), 1e-12));
    assert!(offsets.iter().all(|o| o.problem.is_none()));
}

#[test]
fn a_groove_narrower_than_the_nose_is_a_problem_on_its_bottom() {
    // Down a 0.6 mm wide groove and up again, nose (r 0.4) above: the walls leave no room.
    let contour = [
        line(Xz::new(10.0, 0.0), Xz::new(10.0, -5.0)),
        line(Xz::new(10.0, -5.0), Xz::new(8.0, -5.0)),
        line(Xz::new(8.0, -5.0), Xz::new(8.0, -5.6)),
        line(Xz::new(8.0, -5.6), Xz::new(10.0, -5.6)),
        line(Xz::new(10.0, -5.6), Xz::new(10.0, -10.0)),
    ];
    let offsets = offset_chain(&contour, 0.4, RIGHT);
    assert_eq!(offsets[2].problem, Some(Problem::UsedUp));
    // A groove wide enough passes.
    let wide = [
        line(Xz::new(10.0, 0.0), Xz::new(10.0, -5.0)),
        line(Xz::new(10.0, -5.0), Xz::new(8.0, -5.0)),
        line(Xz::new(8.0, -5.0), Xz::new(8.0, -5.8)),
        line(Xz::new(8.0, -5.8), Xz::new(10.0, -5.8)),
        line(Xz::new(10.0, -5.8), Xz::new(10.0, -10.0)),
    ];
    assert!(offset_chain(&wide, 0.4, RIGHT).iter().all(|o| o.problem.is_none()));
}

#[test]
fn null_elements_stand_where_the_nose_is() {
    let p = Xz::new(10.0, -5.0);
    let contour = [line(p, p), line(p, Xz::new(10.0, -10.0)), line(Xz::new(10.0, -10.0), Xz::new(10.0, -10.0))];
    let offsets = offset_chain(&contour, 0.5, RIGHT);
    assert!(close(offsets[0].path.end(), Xz::new(10.5, -5.0), 1e-12));
    assert!(close(offsets[2].path.start(), Xz::new(10.5, -10.0), 1e-12));
}

// ----- runs of moves -----

fn tools(r: f64, tip: u8) -> ToolTable {
    ToolTable { entries: vec![(1, 1, r, tip), (2, 2, 2.0 * r, tip)] }
}

fn setup(r: f64, tip: u8) -> Setup {
    Setup { tools: tools(r, tip), rapid: Xz::new(8000.0, 12000.0), mm_per_unit: 1.0 }
}

/// A move as the emitter makes it: the contour, feed 0.1 mm/rev at 1200 rpm (120 mm/min),
/// time from the contour length.
fn emitted(from: Xz, motion: Motion, to: Xz, centre: Xz, compensation: Compensation, t: &mut f64) -> Move {
    let length = match motion {
        Motion::Cw | Motion::Ccw => geometry::arc_length(from, to, centre, motion == Motion::Ccw),
        Motion::Dwell => 0.0,
        _ => from.distance(to),
    };
    let (feed, seconds) = match motion {
        Motion::Rapid => (0.0, ((to.x - from.x).abs() / 8000.0).max((to.z - from.z).abs() / 12000.0) * 60.0),
        Motion::Dwell => (0.0, 0.5),
        _ => (120.0, length / 120.0 * 60.0),
    };
    let t_start = *t;
    *t += seconds;
    Move {
        motion,
        compensation,
        cutting: !matches!(motion, Motion::Rapid | Motion::Dwell),
        threading: false,
        per_revolution: true,
        tool: 1,
        offset: 1,
        end: to,
        centre: if motion.is_arc() { centre } else { NAN_POINT },
        contour: to,
        feed,
        f_word: 0.1,
        s_word: 1200.0,
        rpm: 1200.0,
        phase: 0.0,
        t_start,
        t_end: *t,
        source: Span::new(0, 1),
        cycle: Span::SYNTHETIC,
    }
}

/// A toolpath: a rapid start-up from `approach` to the contour's start under `side`, the
/// contour, and a G40 rapid back to `approach`.
fn program(approach: Xz, contour: &[Curve], side: f64) -> Toolpath {
    let compensation = if side > 0.0 { Compensation::Left } else { Compensation::Right };
    let mut t = 0.0;
    let mut moves = Vec::new();
    let first = contour.first().map_or(approach, |c| c.start());
    moves.push(emitted(approach, Motion::Rapid, first, NAN_POINT, compensation, &mut t));
    for c in contour {
        let (motion, centre) = match *c {
            Curve::Line { .. } => (Motion::Feed, NAN_POINT),
            Curve::Arc { centre, ccw, .. } => (if ccw { Motion::Ccw } else { Motion::Cw }, centre),
        };
        moves.push(emitted(c.start(), motion, c.end(), centre, compensation, &mut t));
    }
    let last = contour.last().map_or(approach, |c| c.end());
    moves.push(emitted(last, Motion::Rapid, approach, NAN_POINT, Compensation::Off, &mut t));
    Toolpath { start: approach, moves }
}

fn g42_program() -> Toolpath {
    program(Xz::new(15.0, 5.0), &g42_contour(), RIGHT)
}

#[test]
fn the_g42_case_gets_one_corner_arc_timed_at_the_feed_and_the_clock_stays_continuous() {
    let mut toolpath = g42_program();
    let before = toolpath.clone();
    let mut diagnostics = Vec::new();
    let map = apply(&mut toolpath, &setup(0.4, 3), &mut diagnostics);
    assert!(diagnostics.is_empty(), "{diagnostics:?}");
    assert_eq!(toolpath.moves.len(), before.moves.len() + 1);
    // The arc leads into the move along Z-40 (old index 3, now 4).
    let arc = toolpath.moves[3];
    assert_eq!(arc.motion, Motion::Ccw);
    assert_eq!(arc.contour, Xz::new(15.0, -25.0));
    let h = 0.4 / 2f64.sqrt();
    // Reference point = nose centre + 0.4 (-1, -1) for tip 3.
    assert!(close(toolpath.start_of(3), Xz::new(15.0 + h - 0.4, -25.0 + h - 0.4), 1e-12));
    assert!(close(arc.end, Xz::new(15.0, -25.4), 1e-12));
    assert!(close(arc.centre, Xz::new(14.6, -25.4), 1e-12));
    assert!((arc.feed - 120.0).abs() < 1e-12 && arc.rpm == 1200.0);
    let seconds = 0.4 * FRAC_PI_4 / 120.0 * 60.0;
    assert!((arc.t_end - arc.t_start - seconds).abs() < 1e-12);
    assert_eq!(arc.t_start, before.moves[2].t_end);
    for k in 1..toolpath.moves.len() {
        assert_eq!(toolpath.moves[k].t_start, toolpath.moves[k - 1].t_end, "move {k}");
    }
    assert!((toolpath.duration() - before.duration() - seconds).abs() < 1e-12);
    // The programmed moves keep their own durations and feeds.
    for (old, new) in [(2usize, 2usize), (3, 4), (4, 5)] {
        let (a, b) = (before.moves[old], toolpath.moves[new]);
        assert!(((a.t_end - a.t_start) - (b.t_end - b.t_start)).abs() < 1e-12 && a.feed == b.feed);
    }
    assert_eq!(map.range(0..3), 0..3);
    assert_eq!(map.range(3..4), 3..5, "the corner arc belongs to the move it leads into");
    assert_eq!(map.range(4..7), 5..8);
    assert_eq!(map.range(7..7), 8..8);
    assert!(validate(&toolpath, None).is_ok());
}

#[test]
fn the_start_up_and_the_cancel_are_perpendicular_to_the_first_and_last_elements() {
    let mut toolpath = g42_program();
    apply(&mut toolpath, &setup(0.4, 0), &mut Vec::new());
    // Tip 0: the reference point is the nose centre.
    assert!(close(toolpath.moves[0].end, Xz::new(10.4, 2.0), 1e-12));
    let last = toolpath.moves.len() - 1;
    assert!(close(toolpath.start_of(last), Xz::new(25.0, -44.6), 1e-12));
    assert_eq!(toolpath.moves[last].end, Xz::new(15.0, 5.0));
}

#[test]
fn every_tip_direction_shifts_the_nose_centre_path_by_r_times_its_vector() {
    let centre = offset_chain(&g42_contour(), 0.4, RIGHT);
    for tip in 0..=9u8 {
        let mut toolpath = g42_program();
        apply(&mut toolpath, &setup(0.4, tip), &mut Vec::new());
        let v = tip_vector(tip);
        assert!((v.x.abs() <= 1.0) && (v.z.abs() <= 1.0));
        if tip == 0 || tip == 9 {
            assert_eq!(v, Xz::new(0.0, 0.0));
        } else {
            assert!(v.x != 0.0 || v.z != 0.0);
        }
        // The first cut ends at the concave crossing; its reference point is shifted.
        let expected = centre[0].path.end();
        let got = toolpath.moves[1].end;
        assert!(close(got, Xz::new(expected.x + 0.4 * v.x, expected.z + 0.4 * v.z), 1e-12), "tip {tip}");
    }
    // The figure in the module documentation: 3 is below and toward -Z, 1 above and toward +Z.
    assert_eq!(tip_vector(3), Xz::new(-1.0, -1.0));
    assert_eq!(tip_vector(1), Xz::new(1.0, 1.0));
    assert_eq!(tip_vector(8), Xz::new(-1.0, 0.0));
}

#[test]
fn a_start_up_straight_into_an_arc_ends_on_the_arcs_offset_circle() {
    // G41 G00 to (10, 0), then G03 to (15, -5) about (10, -5): the arc starts heading +X,
    // and the nose (left of a counter-clockwise arc: inside) runs on radius 4.6. The
    // start-up ends 0.4 in along the arc's radius at its start.
    let arc =
        Curve::Arc { start: Xz::new(10.0, 0.0), end: Xz::new(15.0, -5.0), centre: Xz::new(10.0, -5.0), ccw: true };
    let mut toolpath = program(Xz::new(20.0, 5.0), &[arc], LEFT);
    let mut diagnostics = Vec::new();
    apply(&mut toolpath, &setup(0.4, 0), &mut diagnostics);
    assert!(diagnostics.is_empty());
    assert!(close(toolpath.moves[0].end, Xz::new(10.0, -0.4), 1e-12), "{:?}", toolpath.moves[0].end);
    assert!(close(toolpath.moves[1].end, Xz::new(14.6, -5.0), 1e-12), "{:?}", toolpath.moves[1].end);
    assert_eq!(toolpath.moves[1].centre, Xz::new(10.0, -5.0));
    assert!(validate(&toolpath, None).is_ok());
}

#[test]
fn arcs_that_start_or_end_compensation_are_made_straight_with_a_warning() {
    let arc_in =
        Curve::Arc { start: Xz::new(12.0, 2.0), end: Xz::new(10.0, 0.0), centre: Xz::new(10.0, 2.0), ccw: true };
    let cut = line(Xz::new(10.0, 0.0), Xz::new(10.0, -10.0));
    let mut t = 0.0;
    let moves = vec![
        emitted(arc_in.start(), Motion::Ccw, arc_in.end(), Xz::new(10.0, 2.0), Compensation::Right, &mut t),
        emitted(cut.start(), Motion::Feed, cut.end(), NAN_POINT, Compensation::Right, &mut t),
        emitted(cut.end(), Motion::Cw, Xz::new(12.0, -12.0), Xz::new(12.0, -10.0), Compensation::Off, &mut t),
    ];
    let mut toolpath = Toolpath { start: arc_in.start(), moves };
    let mut diagnostics = Vec::new();
    apply(&mut toolpath, &setup(0.4, 3), &mut diagnostics);
    let kinds: Vec<_> = diagnostics.iter().map(|d| d.kind.clone()).collect();
    assert_eq!(
        kinds,
        vec![DiagnosticKind::CompensationOnArc { cancel: false }, DiagnosticKind::CompensationOnArc { cancel: true }]
    );
    assert!(toolpath.moves.iter().all(|m| m.motion == Motion::Feed));
    assert!(validate(&toolpath, None).is_ok());
}

#[test]
fn an_arc_after_a_run_under_a_tool_with_no_nose_radius_cancels_like_g40() {
    // G42 with T0101, then T0505 (not in the table) still in G42: its arc leaves from the
    // last offset point, so it is made straight.
    let mut t = 0.0;
    let mut moves = vec![
        emitted(Xz::new(15.0, 5.0), Motion::Rapid, Xz::new(10.0, 0.0), NAN_POINT, Compensation::Right, &mut t),
        emitted(Xz::new(10.0, 0.0), Motion::Feed, Xz::new(10.0, -10.0), NAN_POINT, Compensation::Right, &mut t),
        emitted(
            Xz::new(10.0, -10.0),
            Motion::Cw,
            Xz::new(12.0, -12.0),
            Xz::new(12.0, -10.0),
            Compensation::Right,
            &mut t,
        ),
    ];
    moves[2].tool = 5;
    moves[2].offset = 5;
    let mut toolpath = Toolpath { start: Xz::new(15.0, 5.0), moves };
    let mut diagnostics = Vec::new();
    apply(&mut toolpath, &setup(0.4, 0), &mut diagnostics);
    assert_eq!(diagnostics.len(), 1);
    assert_eq!(toolpath.moves[2].motion, Motion::Feed);
    assert!(validate(&toolpath, None).is_ok());
}

#[test]
fn a_tool_change_inside_compensation_starts_a_new_run_with_the_new_radius() {
    // T0101 (r 0.4) cuts along Z-10, then T0202 (r 0.8) in G42 goes on along -Z.
    let mut t = 0.0;
    let mut moves = vec![
        emitted(Xz::new(15.0, 5.0), Motion::Rapid, Xz::new(10.0, 0.0), NAN_POINT, Compensation::Right, &mut t),
        emitted(Xz::new(10.0, 0.0), Motion::Feed, Xz::new(10.0, -10.0), NAN_POINT, Compensation::Right, &mut t),
        emitted(Xz::new(10.0, -10.0), Motion::Rapid, Xz::new(12.0, -10.0), NAN_POINT, Compensation::Right, &mut t),
        emitted(Xz::new(12.0, -10.0), Motion::Feed, Xz::new(12.0, -20.0), NAN_POINT, Compensation::Right, &mut t),
        emitted(Xz::new(12.0, -20.0), Motion::Rapid, Xz::new(15.0, 5.0), NAN_POINT, Compensation::Off, &mut t),
    ];
    for m in &mut moves[2..4] {
        m.tool = 2;
        m.offset = 2;
    }
    let mut toolpath = Toolpath { start: Xz::new(15.0, 5.0), moves };
    apply(&mut toolpath, &setup(0.4, 0), &mut Vec::new());
    assert!(close(toolpath.moves[1].end, Xz::new(10.4, -10.0), 1e-12));
    // The new tool's start-up ends perpendicular to its first element with r 0.8.
    assert!(close(toolpath.moves[2].end, Xz::new(12.8, -10.0), 1e-12));
    assert!(close(toolpath.moves[3].end, Xz::new(12.8, -20.0), 1e-12));
}

#[test]
fn a_dwell_in_or_after_a_run_stands_at_the_offset_point() {
    let mut t = 0.0;
    let mut dwell =
        emitted(Xz::new(10.0, -10.0), Motion::Dwell, Xz::new(10.0, -10.0), NAN_POINT, Compensation::Off, &mut t);
    let mut moves = vec![
        emitted(Xz::new(15.0, 5.0), Motion::Rapid, Xz::new(10.0, 0.0), NAN_POINT, Compensation::Right, &mut t),
        emitted(Xz::new(10.0, 0.0), Motion::Feed, Xz::new(10.0, -10.0), NAN_POINT, Compensation::Right, &mut t),
    ];
    dwell.t_start = t;
    dwell.t_end = t + 0.5;
    t += 0.5;
    moves.push(dwell);
    moves.push(emitted(Xz::new(10.0, -10.0), Motion::Rapid, Xz::new(15.0, 5.0), NAN_POINT, Compensation::Off, &mut t));
    let mut toolpath = Toolpath { start: Xz::new(15.0, 5.0), moves };
    apply(&mut toolpath, &setup(0.4, 0), &mut Vec::new());
    assert!(close(toolpath.moves[2].end, Xz::new(10.4, -10.0), 1e-12));
}

#[test]
fn a_corner_arc_before_a_rapid_runs_at_the_slower_axis_rate() {
    // Along -Z, then a rapid straight up (+X) under G41 (nose below): a convex right angle.
    let mut t = 0.0;
    let moves = vec![
        emitted(Xz::new(5.0, 5.0), Motion::Rapid, Xz::new(10.0, 0.0), NAN_POINT, Compensation::Left, &mut t),
        emitted(Xz::new(10.0, 0.0), Motion::Feed, Xz::new(10.0, -10.0), NAN_POINT, Compensation::Left, &mut t),
        emitted(Xz::new(10.0, -10.0), Motion::Rapid, Xz::new(20.0, -10.0), NAN_POINT, Compensation::Left, &mut t),
        emitted(Xz::new(20.0, -10.0), Motion::Rapid, Xz::new(30.0, 5.0), NAN_POINT, Compensation::Off, &mut t),
    ];
    let mut toolpath = Toolpath { start: Xz::new(5.0, 5.0), moves };
    apply(&mut toolpath, &setup(0.5, 0), &mut Vec::new());
    let arc = toolpath.moves[2];
    assert_eq!(arc.motion, Motion::Cw);
    assert!(!arc.cutting);
    assert_eq!(arc.feed, 8000.0);
    assert!((arc.t_end - arc.t_start - 0.5 * FRAC_PI_2 / 8000.0 * 60.0).abs() < 1e-12);
    assert!(close(arc.end, Xz::new(10.0, -10.5), 1e-12));
}

#[test]
fn nothing_inserted_maps_every_range_to_itself() {
    let map = MoveMap::identity(4);
    assert_eq!(map.range(1..3), 1..3);
    assert_eq!(map.range(4..4), 4..4);
    assert_eq!(map.range(2..9), 2..4, "past the end maps to the end");
}

// ----- properties -----

/// The least distance from a point to a line segment or an arc.
fn point_distance(p: Xz, c: Curve) -> f64 {
    match c {
        Curve::Line { start, end } => {
            let d = end.distance(start);
            if d < 1e-15 {
                return p.distance(start);
            }
            let t =
                (((p.x - start.x) * (end.x - start.x) + (p.z - start.z) * (end.z - start.z)) / (d * d)).clamp(0.0, 1.0);
            p.distance(Xz::new(start.x + (end.x - start.x) * t, start.z + (end.z - start.z) * t))
        }
        Curve::Arc { start, end, centre, ccw } => {
            let radius = c.radius();
            let from_centre = p.distance(centre);
            if from_centre < 1e-15 {
                return radius;
            }
            if geometry::angle_within(p, start, end, centre, ccw) {
                (from_centre - radius).abs()
            } else {
                p.distance(start).min(p.distance(end))
            }
        }
    }
}

fn segment_point(start: Xz, end: Xz, t: f64) -> Xz {
    Xz::new(start.x + (end.x - start.x) * t, start.z + (end.z - start.z) * t)
}

/// The least distance between two curves, exactly: at a closest pair either one point is
/// an end point, or both are interior and the pair lies on a line through the centres
/// (perpendicular to both), or the curves cross.
fn curve_distance(a: Curve, b: Curve) -> f64 {
    let mut best = [
        point_distance(a.start(), b),
        point_distance(a.end(), b),
        point_distance(b.start(), a),
        point_distance(b.end(), a),
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min);
    match (a, b) {
        (Curve::Line { start: a0, end: a1 }, Curve::Line { start: b0, end: b1 }) => {
            if let Some(p) = geometry::line_line(a0, a1, b0, b1)
                && point_distance(p, a) < 1e-12
                && point_distance(p, b) < 1e-12
            {
                best = 0.0;
            }
        }
        (Curve::Line { start, end }, arc @ Curve::Arc { centre, .. })
        | (arc @ Curve::Arc { centre, .. }, Curve::Line { start, end }) => {
            let foot = {
                let d = end.distance(start).max(1e-15);
                let t = (((centre.x - start.x) * (end.x - start.x) + (centre.z - start.z) * (end.z - start.z))
                    / (d * d))
                    .clamp(0.0, 1.0);
                segment_point(start, end, t)
            };
            best = best.min(point_distance(foot, arc));
            for t in geometry::line_circle(start, end, centre, arc.radius()) {
                let p = segment_point(start, end, t);
                if (0.0..=1.0).contains(&t) && point_distance(p, arc) < 1e-12 {
                    best = 0.0;
                }
            }
        }
        (Curve::Arc { centre: c1, .. }, Curve::Arc { centre: c2, .. }) => {
            let u = geometry::direction(c1, c2);
            for (arc, c, other) in [(a, c1, b), (b, c2, a)] {
                for sign in [1.0, -1.0] {
                    let p = Xz::new(c.x + sign * arc.radius() * u.x, c.z + sign * arc.radius() * u.z);
                    if point_distance(p, arc) < 1e-12 {
                        best = best.min(point_distance(p, other));
                    }
                }
            }
            for p in geometry::circle_circle(c1, a.radius(), c2, b.radius()) {
                if point_distance(p, a) < 1e-12 && point_distance(p, b) < 1e-12 {
                    best = 0.0;
                }
            }
        }
    }
    best
}

#[test]
fn curve_distance_finds_interior_closest_points() {
    let arc = Curve::Arc { start: Xz::new(0.0, 5.0), end: Xz::new(0.0, -5.0), centre: Xz::new(0.0, 0.0), ccw: true };
    // The arc's top is at X5; a line at X7 is 2 away from it.
    assert!((curve_distance(line(Xz::new(7.0, -3.0), Xz::new(7.0, 3.0)), arc) - 2.0).abs() < 1e-12);
    // Radius 3 about (15, 0), the lower half: its bottom at X12 is 7 from the first arc's top.
    let other =
        Curve::Arc { start: Xz::new(15.0, 3.0), end: Xz::new(15.0, -3.0), centre: Xz::new(15.0, 0.0), ccw: false };
    assert!((curve_distance(arc, other) - 7.0).abs() < 1e-12);
    assert_eq!(
        curve_distance(line(Xz::new(0.0, 0.0), Xz::new(10.0, 0.0)), line(Xz::new(5.0, -1.0), Xz::new(5.0, 1.0))),
        0.0
    );
}

/// One element of a generated contour: its start heading (radians from +Z toward +X) and
/// either a length or an arc's radius and signed sweep (positive counter-clockwise).
#[derive(Debug, Clone, Copy)]
enum Step {
    Line { heading: f64, length: f64 },
    Arc { heading: f64, radius: f64, sweep: f64 },
}

fn build(start: Xz, steps: &[Step]) -> Vec<Curve> {
    let mut at = start;
    let mut out = Vec::new();
    for step in steps {
        let curve = match *step {
            Step::Line { heading, length } => {
                let end = Xz::new(at.x + length * heading.sin(), at.z + length * heading.cos());
                line(at, end)
            }
            Step::Arc { heading, radius, sweep } => {
                let ccw = sweep > 0.0;
                let d = Xz::new(heading.sin(), heading.cos());
                // The centre is on the side the arc turns to.
                let n = path::tool_normal(d, if ccw { 1.0 } else { -1.0 });
                let centre = Xz::new(at.x + radius * n.x, at.z + radius * n.z);
                let end = geometry::on_circle(centre, radius, geometry::angle(at, centre) + sweep);
                Curve::Arc { start: at, end, centre, ccw }
            }
        };
        at = curve.end();
        out.push(curve);
    }
    out
}

/// Outside turning toward the chuck: every direction between +X (a face up) and -Z.
fn monotonic_steps(r: f64) -> impl Strategy<Value = Vec<Step>> {
    let step = (any::<bool>(), 0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64).prop_map(move |(arc, a, b, size)| {
        let h0 = FRAC_PI_2 + a * FRAC_PI_2;
        let h1 = FRAC_PI_2 + b * FRAC_PI_2;
        if arc && (h1 - h0).abs() > 0.25 {
            Step::Arc { heading: h0, radius: r * (4.0 + 16.0 * size), sweep: h1 - h0 }
        } else {
            Step::Line { heading: h0, length: r * (8.0 + 22.0 * size) }
        }
    });
    prop::collection::vec(step, 1..10)
}

/// Any direction: turns of up to 170° at the corners (sharp convex corners and narrow
/// concave ones), arcs of up to 90°.
fn random_steps(r: f64) -> impl Strategy<Value = Vec<Step>> {
    let step = (any::<bool>(), -1.0..1.0f64, -1.0..1.0f64, 0.0..1.0f64);
    prop::collection::vec(step, 1..10).prop_map(move |raw| {
        let mut heading = 0.0;
        raw.into_iter()
            .map(|(arc, jump, bend, size)| {
                heading += jump * 17.0 * PI / 18.0;
                let sweep = bend.signum() * (0.25 + bend.abs() * (FRAC_PI_2 - 0.25));
                let step = if arc {
                    Step::Arc { heading, radius: r * (3.0 + 12.0 * size), sweep }
                } else {
                    Step::Line { heading, length: r * (8.0 + 22.0 * size) }
                };
                if arc {
                    heading += sweep;
                }
                step
            })
            .collect()
    })
}

/// Whether the nose fits the contour everywhere, not only at each corner: elements that
/// are not neighbours stay more than a nose diameter apart, and no corner turns with its
/// arcs through more than a half turn one way (a hook whose arc comes back beside the
/// element before it, on the tool's side, leaves a sliver thinner than the nose).
fn clear_of_itself(contour: &[Curve], r: f64) -> bool {
    let sweep = |c: Curve| match c {
        Curve::Arc { start, end, centre, ccw } => {
            let s = geometry::sweep(start, end, centre, ccw);
            if ccw { s } else { -s }
        }
        Curve::Line { .. } => 0.0,
    };
    let no_hooks = contour.windows(2).all(|pair| {
        let turn = turn_angle(pair[0].end_tangent(), pair[1].start_tangent());
        let along = |s: f64| if s * turn > 0.0 { s } else { 0.0 };
        (turn + along(sweep(pair[0])) + along(sweep(pair[1]))).abs() < PI
    });
    no_hooks
        && (0..contour.len())
            .all(|i| (i + 2..contour.len()).all(|j| curve_distance(contour[i], contour[j]) > 2.0 * r + 1e-3))
}

/// The nose-centre path of the moves `range`: each move's curve, less the tip shift.
fn nose_path(toolpath: &Toolpath, range: Range<usize>, r: f64, tip: u8) -> Vec<Curve> {
    let v = tip_vector(tip);
    let back = |p: Xz| Xz::new(p.x - r * v.x, p.z - r * v.z);
    range
        .map(|k| {
            let (m, start) = (toolpath.moves[k], toolpath.start_of(k));
            match m.motion {
                Motion::Cw | Motion::Ccw => Curve::Arc {
                    start: back(start),
                    end: back(m.end),
                    centre: back(m.centre),
                    ccw: m.motion == Motion::Ccw,
                },
                _ => line(back(start), back(m.end)),
            }
        })
        .collect()
}

/// The checks every compensated contour must pass; `Err` when compensation reported that
/// the nose does not fit (the property is about the contours it accepts).
fn check(contour: &[Curve], r: f64, tip: u8, side: f64, groups: &[usize]) -> Result<(), TestCaseError> {
    let first = contour[0];
    let d = first.start_tangent();
    let n = path::tool_normal(d, side);
    let approach =
        Xz::new(first.start().x + 6.0 * r * n.x - 6.0 * r * d.x, first.start().z + 6.0 * r * n.z - 6.0 * r * d.z);
    let mut toolpath = program(approach, contour, side);
    // Cycles: consecutive groups of moves, each with its own call block.
    let mut expansions = Vec::new();
    let mut at = 0;
    for (g, &size) in groups.iter().enumerate() {
        let end = (at + size).min(toolpath.moves.len());
        let span = Span::new(100 * (g as u32 + 1), 100 * (g as u32 + 1) + 5);
        for m in &mut toolpath.moves[at..end] {
            m.cycle = span;
        }
        expansions.push((span, at..end));
        at = end;
    }
    let before = toolpath.clone();
    let mut diagnostics = Vec::new();
    let map = apply(&mut toolpath, &setup(r, tip), &mut diagnostics);
    prop_assume!(!diagnostics.iter().any(|d| matches!(d.kind, DiagnosticKind::NoseDoesNotFit { .. })));
    prop_assert!(diagnostics.is_empty(), "{diagnostics:?}");

    let valid = validate(&toolpath, Some(Limits { x_min: -1e6, x_max: 1e6, z_min: -1e6, z_max: 1e6 }));
    prop_assert!(valid.is_ok(), "{:?}", valid.err());

    // The clock: continuous, and each inserted move takes its length at its feed.
    for k in 1..toolpath.moves.len() {
        prop_assert!((toolpath.moves[k].t_start - toolpath.moves[k - 1].t_end).abs() < 1e-9);
        prop_assert!(toolpath.moves[k].t_end >= toolpath.moves[k].t_start);
    }
    let inserted: Vec<usize> = (0..toolpath.moves.len())
        .filter(|&k| !(0..before.moves.len()).any(|o| map.range(o..o + 1).end - 1 == k))
        .collect();
    prop_assert_eq!(inserted.len(), toolpath.moves.len() - before.moves.len());
    for &k in &inserted {
        let m = toolpath.moves[k];
        let length = geometry::arc_length(toolpath.start_of(k), m.end, m.centre, m.motion == Motion::Ccw);
        prop_assert!(m.is_arc());
        prop_assert!((length / m.feed * 60.0 - (m.t_end - m.t_start)).abs() < 1e-9);
        prop_assert!(
            (length - r * geometry::sweep(toolpath.start_of(k), m.end, m.centre, m.motion == Motion::Ccw)).abs() < 1e-9
        );
    }

    // Expansions still hold exactly the moves of their cycle.
    for (span, old) in &expansions {
        let new = map.range(old.clone());
        prop_assert!(toolpath.moves[new.clone()].iter().all(|m| m.cycle == *span));
        let count = toolpath.moves.iter().filter(|m| m.cycle == *span).count();
        prop_assert_eq!(count, new.len());
    }

    // No gouge, and the nose touches every element.
    let cut = nose_path(&toolpath, 1..toolpath.moves.len() - 1, r, tip);
    for (i, piece) in cut.iter().enumerate() {
        for (j, element) in contour.iter().enumerate() {
            let d = curve_distance(*piece, *element);
            prop_assert!(d >= r - 1e-6, "piece {i} {piece:?} is {d} from element {j} {element:?}");
        }
    }
    for (j, element) in contour.iter().enumerate() {
        let d = cut.iter().map(|piece| curve_distance(*piece, *element)).fold(f64::INFINITY, f64::min);
        prop_assert!(d <= r + 1e-6, "element {j} {element:?} is never touched: {d}");
    }
    Ok(())
}

fn groups() -> impl Strategy<Value = Vec<usize>> {
    prop::collection::vec(0usize..5, 0..4)
}

proptest! {
    #[test]
    fn outside_turning_profiles_are_followed_without_gouging(
        (r, steps) in (0.2..1.6f64).prop_flat_map(|r| (Just(r), monotonic_steps(r))),
        tip in 0u8..=9,
        groups in groups(),
    ) {
        let contour = build(Xz::new(10.0, 0.0), &steps);
        // Outside turning accepts every such profile: the nose always fits.
        let mut toolpath = program(Xz::new(40.0, 10.0), &contour, RIGHT);
        let mut diagnostics = Vec::new();
        apply(&mut toolpath, &setup(r, tip), &mut diagnostics);
        prop_assert!(diagnostics.is_empty(), "{diagnostics:?}");
        check(&contour, r, tip, RIGHT, &groups)?;
    }

    #[test]
    fn random_contours_the_nose_fits_are_followed_without_gouging(
        (r, steps) in (0.2..1.6f64).prop_flat_map(|r| (Just(r), random_steps(r))),
        left in any::<bool>(),
        tip in 0u8..=9,
        groups in groups(),
    ) {
        let contour = build(Xz::new(10.0, 0.0), &steps);
        prop_assume!(clear_of_itself(&contour, r));
        check(&contour, r, tip, if left { LEFT } else { RIGHT }, &groups)?;
    }
}
