//! Reading a lowered toolpath back in the property tests: the moves of one cycle call, and
//! points along a move to probe it against a shape.

use turnpass::geometry;
use turnpass::source::LineIndex;
use turnpass::syntax::Program;
use turnpass::toolpath::{Motion, Move, Xz};

/// `count + 1` points along a move from `from` to its end, both ends included; arcs are
/// followed along their sweep.
pub fn samples(from: Xz, m: &Move, count: usize) -> Vec<Xz> {
    (0..=count)
        .map(|i| {
            let t = i as f64 / count as f64;
            if m.is_arc() {
                let ccw = m.motion == Motion::Ccw;
                let sweep = geometry::sweep(from, m.end, m.centre, ccw);
                let a = geometry::angle(from, m.centre) + if ccw { sweep * t } else { -sweep * t };
                geometry::on_circle(m.centre, from.distance(m.centre), a)
            } else {
                Xz::new(from.x + (m.end.x - from.x) * t, from.z + (m.end.z - from.z) * t)
            }
        })
        .collect()
}

/// The moves of the cycle called in block `line` (1-based source line), and where the tool
/// was before the first of them.
pub fn cycle_moves<'a>(program: &Program<'_>, moves: &'a [Move], line: usize) -> (Xz, Vec<&'a Move>) {
    let lines = LineIndex::new(program.source());
    let mut from = None;
    let mut out = Vec::new();
    let mut previous = Xz::new(f64::NAN, f64::NAN);
    for m in moves {
        if !m.cycle.is_synthetic() && lines.position(m.cycle.start).0 == line {
            from.get_or_insert(previous);
            out.push(m);
        }
        previous = m.end;
    }
    (from.unwrap_or(previous), out)
}
