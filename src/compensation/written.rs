//! From commanded reference points to the points a program writes.
//!
//! The inverse gives, for each sample, the tool reference point to command. A block does
//! not always write the reference point: under nose-radius compensation (`G41`/`G42`) it
//! writes the programmed contour and the control offsets the tool by the nose radius. The
//! compensated program must stay a contour program there, so each contour point is moved
//! by the correction of its reference point, `contour + (commanded − nominal)`, and the
//! control's own offset then carries the tool to the commanded reference point. Without
//! compensation the contour is the reference point and this is just the commanded point.
//!
//! The contour point of a sample is the point of the programmed element at the same place
//! along it: the same fraction of a line, the same angle about an arc's centre. The nose
//! centre runs concentric with a contour arc and the reference point is the nose centre
//! plus the tip offset, so the reference point's arc (`Move.centre`) is the contour's arc
//! moved by that offset (`contour_centre`).

use crate::geometry;
use crate::semantic::nose_radius::{ToolTable, tip_vector};
use crate::toolpath::{Compensation, Motion, Move, Toolpath, Xz};

use crate::error_model::sampling::PathSample;

/// The samples of each move: `ranges[i]` indexes the samples of move `i` (empty for a
/// dwell). Samples come in move order from `sample_toolpath`.
#[cfg(test)]
pub fn sample_ranges(moves: usize, samples: &[PathSample]) -> Vec<std::ops::Range<usize>> {
    let mut ranges = vec![0..0; moves];
    let mut k = 0;
    while k < samples.len() {
        let index = samples[k].move_index;
        let start = k;
        while k < samples.len() && samples[k].move_index == index {
            k += 1;
        }
        if let Some(range) = ranges.get_mut(index) {
            *range = start..k;
        }
    }
    // A dwell (no samples) sits at the end of the previous move's samples.
    let mut at = 0;
    for range in &mut ranges {
        if range.start == range.end {
            *range = at..at;
        } else {
            at = range.end;
        }
    }
    ranges
}

/// Where move `index` starts on the programmed contour.
pub fn contour_start(toolpath: &Toolpath, index: usize) -> Xz {
    index.checked_sub(1).and_then(|k| toolpath.moves.get(k)).map_or(toolpath.start, |m| m.contour)
}

/// Whether the move only turns the tool around a corner of the contour: nose-radius
/// compensation inserts such arcs, and the control makes them itself from the blocks on
/// either side, so they are never written.
pub fn is_corner_of_contour(m: &Move, contour_start: Xz) -> bool {
    m.compensation != Compensation::Off && m.contour.distance(contour_start) <= 1e-9
}

/// The centre of an arc's programmed contour (for a line, `Move.centre`, which is NaN).
pub fn contour_centre(m: &Move, tools: &ToolTable) -> Xz {
    if m.compensation == Compensation::Off || !m.is_arc() {
        return m.centre;
    }
    let (radius, tip) = tools.lookup(m.tool, m.offset);
    let tip = tip_vector(tip);
    Xz::new(m.centre.x - tip.x * radius, m.centre.z - tip.z * radius)
}

/// The contour point of a sample of move `m`.
pub fn contour_at(m: &Move, contour_start: Xz, sample: &PathSample, tools: &ToolTable) -> Xz {
    if m.compensation == Compensation::Off {
        return sample.nominal;
    }
    match m.motion {
        Motion::Cw | Motion::Ccw => {
            let centre = contour_centre(m, tools);
            let radius = m.contour.distance(centre);
            let angle = geometry::angle(sample.nominal, m.centre);
            if sample.param >= 1.0 { m.contour } else { geometry::on_circle(centre, radius, angle) }
        }
        _ => {
            let t = sample.param.clamp(0.0, 1.0);
            Xz::new(
                contour_start.x + (m.contour.x - contour_start.x) * t,
                contour_start.z + (m.contour.z - contour_start.z) * t,
            )
        }
    }
}

/// The correction of a sample: commanded − nominal.
pub fn offset(sample: &PathSample, commanded: Xz) -> Xz {
    Xz::new(commanded.x - sample.nominal.x, commanded.z - sample.nominal.z)
}

/// The point the program writes for a sample: its contour point (`contour_at`) moved by
/// its correction.
pub fn written_from(contour: Xz, sample: &PathSample, commanded: Xz) -> Xz {
    let d = offset(sample, commanded);
    Xz::new(contour.x + d.x, contour.z + d.z)
}

/// The reference point the control commands for a written point of a sample (the inverse
/// of `written_from`).
pub fn reference_point(m: &Move, contour_start: Xz, sample: &PathSample, written: Xz, tools: &ToolTable) -> Xz {
    reference_from(contour_at(m, contour_start, sample, tools), sample, written)
}

/// `reference_point` given the sample's contour point (`contour_at`).
pub fn reference_from(contour: Xz, sample: &PathSample, written: Xz) -> Xz {
    Xz::new(written.x + sample.nominal.x - contour.x, written.z + sample.nominal.z - contour.z)
}
