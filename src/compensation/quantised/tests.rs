use super::*;
use crate::compensation::sampling::{PathSample, Sampling, sample_moves};
use crate::compensation::test_support::lower_program;
use crate::error_model::Spacing;
use crate::error_model::spacing::ArcTerms;

/// A sample's commanded point is found on the written path however many lines lie
/// between it and the sample before: `densify` writes twenty and more between two samples
/// an eighth of a turn apart on a 10 mm arc, and the walk once searched only sixteen
/// segments ahead, so the prediction measured the wrong line there.
#[test]
fn the_walk_reaches_a_sample_past_many_short_lines() {
    let (lowered, machine) =
        lower_program("G21 G99\nG97 S1000 M03\nG00 X40. Z2.\nG01 Z0 F0.2\nG03 X20. Z-10. R10.\nM30\n");
    let toolpath = &lowered.toolpath;
    let index = toolpath.moves.iter().position(|m| m.is_arc()).unwrap();
    let m = &toolpath.moves[index];
    let tools = ToolTable::from_machine(&machine);
    // Two samples on the quarter arc: its middle and its end.
    let sampling = Sampling {
        spacing: Spacing::ANY,
        arc: ArcTerms::default(),
        allowance: 1e-9,
        max_arc_radians: Sampling::MAX_ARC_RADIANS,
        play: Xz::new(0.0, 0.0),
    };
    let mut samples: Vec<PathSample> = Vec::new();
    sample_moves(toolpath, index..index + 1, &tools, &sampling, &mut samples);
    assert!(samples.len() >= 2, "{}", samples.len());
    // Written as 64 lines along the arc, on a 1 µm grid.
    let start = toolpath.start_of(index);
    let a0 = crate::geometry::angle(start, m.centre);
    let sweep = crate::geometry::sweep(start, m.end, m.centre, true);
    let radius = start.distance(m.centre);
    let segments: Vec<Segment> = (1..=64)
        .map(|i| Segment::Line { end: crate::geometry::on_circle(m.centre, radius, a0 + sweep * f64::from(i) / 64.0) })
        .collect();
    let grid = Grid::new(&lowered.coordinates_at(index));
    let mut rounded = Vec::new();
    quantise(&grid, start, &segments, &[], false, &mut rounded);
    let walk = Walk { m, contour_start: start, start: grid.round(start), segments: &rounded, tools: &tools };
    let ideal: Vec<Xz> = samples.iter().map(|s| s.nominal).collect();
    let mut out = ideal.clone();
    walk.follow(&samples, &ideal, 0..samples.len(), &mut Vec::new(), &mut out);
    // Each commanded point is within the lines' sagitta (R·(1 − cos(θ/2)), 0.75 µm) and
    // the rounding of the sample's own point on the path.
    for (p, s) in out.iter().zip(&samples) {
        assert!(p.distance(s.nominal) < 0.002, "{:?} at {}: {}", s.nominal, s.param, p.distance(s.nominal));
    }
}
