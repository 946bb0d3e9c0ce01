//! Tool nose radius compensation (`G41`/`G42`/`G40`) with imaginary tip directions.
//!
//! Without compensation a lathe program describes the path of the tool's imaginary tip
//! (the reference point). With it, the program describes the part contour, and the control
//! moves the nose centre on a path offset by the nose radius `r` (left of the direction of
//! travel with `G41`, right with `G42`), so the reference point is the nose centre plus
//! `r` times the tip-direction vector:
//!
//! ```txt
//!   X ▲   2  6  1        tip 3 (outside turning toward the chuck): the imaginary tip is
//!     │   7  0  5        below and left of the nose centre, at (−r, −r) in (X, Z);
//!     │   3  8  4        tips 0 and 9 are the nose centre itself.
//!     └──────────▶ Z
//! ```
//!
//! Corners are joined the way a C-type control does: the offset elements (lines stay
//! lines, arcs stay concentric with radius `R ± r`) are cut or extended to where they meet.
//! The block that switches compensation on ends offset perpendicular to the next element;
//! the `G40` block leaves from the last offset point to its own uncompensated end. When two
//! offset elements do not meet within four nose radii of the corner (a very sharp outside
//! corner), the first ends at its own offset end and the next leaves from there: a small
//! departure from the control's extra corner vectors, noted here rather than hidden.
//!
//! The IR keeps both paths: `end` becomes the reference point, `contour` stays the
//! programmed point.

use crate::diagnostic::Diagnostic;
use crate::geometry;
use crate::toolpath::{Compensation, Motion, Toolpath, Xz};

use super::Machine;

/// Nose radius (mm) and tip direction by turret station and offset number.
#[derive(Debug, Clone, Default)]
pub struct ToolTable {
    entries: Vec<(u16, u16, f64, u8)>,
}

impl ToolTable {
    pub fn from_machine(machine: &Machine) -> ToolTable {
        let scale = machine.scale();
        ToolTable {
            entries: machine
                .tools
                .iter()
                .map(|t| (t.station as u16, t.offset.unwrap_or(t.station) as u16, t.nose_radius * scale, t.tip))
                .collect(),
        }
    }

    fn lookup(&self, station: u16, offset: u16) -> (f64, u8) {
        if offset == 0 {
            return (0.0, 0);
        }
        self.entries
            .iter()
            .find(|e| e.0 == station && e.1 == offset)
            .or_else(|| self.entries.iter().find(|e| e.0 == station))
            .map_or((0.0, 0), |e| (e.2, e.3))
    }
}

/// The imaginary tip's offset from the nose centre, in nose radii.
pub fn tip_vector(tip: u8) -> Xz {
    match tip {
        1 => Xz::new(1.0, 1.0),
        2 => Xz::new(1.0, -1.0),
        3 => Xz::new(-1.0, -1.0),
        4 => Xz::new(-1.0, 1.0),
        5 => Xz::new(0.0, 1.0),
        6 => Xz::new(1.0, 0.0),
        7 => Xz::new(0.0, -1.0),
        8 => Xz::new(-1.0, 0.0),
        _ => Xz::new(0.0, 0.0),
    }
}

/// An element of the nose-centre path.
#[derive(Debug, Clone, Copy)]
enum Element {
    Line { start: Xz, end: Xz },
    Arc { centre: Xz, radius: f64, start: Xz, end: Xz },
}

impl Element {
    fn start(&self) -> Xz {
        match *self {
            Element::Line { start, .. } | Element::Arc { start, .. } => start,
        }
    }

    fn end(&self) -> Xz {
        match *self {
            Element::Line { end, .. } | Element::Arc { end, .. } => end,
        }
    }

    fn set_start(&mut self, p: Xz) {
        match self {
            Element::Line { start, .. } | Element::Arc { start, .. } => *start = p,
        }
    }

    fn set_end(&mut self, p: Xz) {
        match self {
            Element::Line { end, .. } | Element::Arc { end, .. } => *end = p,
        }
    }
}

/// Apply compensation to every run of compensated moves.
pub fn apply(toolpath: &mut Toolpath, tools: &ToolTable, _diagnostics: &mut Vec<Diagnostic>) {
    let mut i = 0;
    while i < toolpath.moves.len() {
        if toolpath.moves[i].compensation == Compensation::Off {
            i += 1;
            continue;
        }
        let run_start = i;
        let (tool, offset) = (toolpath.moves[i].tool, toolpath.moves[i].offset);
        while i < toolpath.moves.len()
            && toolpath.moves[i].compensation == toolpath.moves[run_start].compensation
            && toolpath.moves[i].tool == tool
            && toolpath.moves[i].offset == offset
        {
            i += 1;
        }
        let (radius, tip) = tools.lookup(tool, offset);
        if radius > 0.0 {
            compensate_run(toolpath, run_start..i, radius, tip);
        }
    }
}

fn compensate_run(toolpath: &mut Toolpath, run: std::ops::Range<usize>, r: f64, tip: u8) {
    let side = if toolpath.moves[run.start].compensation == Compensation::Left { 1.0 } else { -1.0 };
    // The contour elements of the run (dwells keep their place and are skipped).
    let geometric: Vec<usize> = run.clone().filter(|&k| toolpath.moves[k].motion != Motion::Dwell).collect();
    if geometric.is_empty() {
        return;
    }
    // Offset each element except the start-up move, which ends where the next one begins.
    let mut elements: Vec<(usize, Element)> = Vec::new();
    for &k in geometric.iter().skip(1) {
        let start = toolpath.start_of(k);
        let m = toolpath.moves[k];
        let contour_start = if k == 0 { toolpath.start } else { toolpath.moves[k - 1].contour };
        let _ = start;
        elements.push((k, offset_element(contour_start, m.contour, m.centre, m.motion, r, side)));
    }
    // Join neighbours.
    for pair in 1..elements.len() {
        let corner = toolpath.moves[elements[pair - 1].0].contour;
        let (a, b) = (elements[pair - 1].1, elements[pair].1);
        match meet(a, b, corner, r) {
            Some(p) => {
                elements[pair - 1].1.set_end(p);
                elements[pair].1.set_start(p);
            }
            None => {
                let p = a.end();
                elements[pair].1.set_start(p);
            }
        }
    }
    let shift = tip_vector(tip);
    let reference = |p: Xz| Xz::new(p.x + shift.x * r, p.z + shift.z * r);
    // The start-up move ends where the first offset element starts (or at its own offset
    // end when it is the only move of the run).
    let first = geometric[0];
    let startup_end = match elements.first() {
        Some((_, element)) => element.start(),
        None => {
            let m = toolpath.moves[first];
            let contour_start = if first == 0 { toolpath.start } else { toolpath.moves[first - 1].contour };
            offset_element(contour_start, m.contour, m.centre, m.motion, r, side).end()
        }
    };
    let startup_arc = toolpath.moves[first].is_arc();
    toolpath.moves[first].end = reference(startup_end);
    if startup_arc {
        // An arc cannot start compensation on these controls; keep it as a straight move.
        toolpath.moves[first].motion = Motion::Feed;
        toolpath.moves[first].centre = Xz::new(f64::NAN, f64::NAN);
    }
    for (k, element) in elements {
        let m = &mut toolpath.moves[k];
        m.end = reference(element.end());
        if let Element::Arc { centre, .. } = element {
            m.centre = reference(centre);
        }
    }
    // Dwells inside the run stand where the previous move ended.
    for k in run {
        if toolpath.moves[k].motion == Motion::Dwell {
            let at = toolpath.start_of(k);
            toolpath.moves[k].end = at;
        }
    }
}

fn offset_element(start: Xz, end: Xz, centre: Xz, motion: Motion, r: f64, side: f64) -> Element {
    match motion {
        Motion::Cw | Motion::Ccw => {
            let ccw = motion == Motion::Ccw;
            let radius = start.distance(centre);
            // The left of a counter-clockwise arc is its inside.
            let inward = if ccw { side } else { -side };
            let new_radius = (radius - inward * r).max(1e-9);
            let a0 = geometry::angle(start, centre);
            let a1 = geometry::angle(end, centre);
            Element::Arc {
                centre,
                radius: new_radius,
                start: geometry::on_circle(centre, new_radius, a0),
                end: geometry::on_circle(centre, new_radius, a1),
            }
        }
        _ => {
            let n = geometry::left_normal(start, end);
            let d = Xz::new(n.x * r * side, n.z * r * side);
            Element::Line { start: Xz::new(start.x + d.x, start.z + d.z), end: Xz::new(end.x + d.x, end.z + d.z) }
        }
    }
}

/// Where two offset elements meet near the contour corner, if within four nose radii.
fn meet(a: Element, b: Element, corner: Xz, r: f64) -> Option<Xz> {
    if a.end().distance(b.start()) < 1e-9 {
        return Some(a.end());
    }
    let candidates: Vec<Xz> = match (a, b) {
        (Element::Line { start: a0, end: a1 }, Element::Line { start: b0, end: b1 }) => {
            geometry::line_line(a0, a1, b0, b1).into_iter().collect()
        }
        (Element::Line { start, end }, Element::Arc { centre, radius, .. })
        | (Element::Arc { centre, radius, .. }, Element::Line { start, end }) => {
            geometry::line_circle(start, end, centre, radius)
                .into_iter()
                .map(|t| Xz::new(start.x + (end.x - start.x) * t, start.z + (end.z - start.z) * t))
                .collect()
        }
        (Element::Arc { centre: c1, radius: r1, .. }, Element::Arc { centre: c2, radius: r2, .. }) => {
            geometry::circle_circle(c1, r1, c2, r2)
        }
    };
    candidates
        .into_iter()
        .filter(|p| p.distance(corner) <= 4.0 * r)
        .min_by(|p, q| p.distance(corner).total_cmp(&q.distance(corner)))
}
