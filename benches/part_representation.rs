//! The part model's representation chosen by measurement (issue 24): the same removal on a
//! representative job, by the dexels `turnpass::part` uses and by exact 2-D Boolean
//! operations on profiles with arcs (`cavalier_contours`, the maintained crate for polyline
//! offsets and Booleans with arcs), timed by criterion, with how exactly each places the
//! finished surface printed first.
//!
//! The job: a stepped shaft of chamfer, tapers, and convex and concave R3 arcs on a Ø42 bar,
//! roughed with `G71` (1.5 mm a pass) and finished with `G70`, on a turning tool of nose
//! radius 0.8 mm (tip 3). The dexels run the whole part model (`part::run`: the nose and
//! the insert behind it, the crash and depth checks); the Boolean side subtracts only the
//! region the nose sweeps (a capsule for a line, an annular sector with round ends for an
//! arc), each move from the part left so far, which is the least the exact representation
//! has to do.
//!
//! Exactness is measured the same way on both: every point of the finished surface the
//! representation gives (the dexels' interval ends the `G70` cut; the Boolean result's
//! vertices and the midpoint of each of its segments, arcs as arcs) that lies within 0.01 mm
//! of the nose envelope of the `G70` pass, and its distance along the normal from that
//! envelope, computed here (a nose radius from the nose-centre path of lines and arcs).
//!
//! `cargo bench --bench part_representation` (criterion's options after `--`).

#![allow(clippy::disallowed_methods, clippy::unwrap_used, clippy::expect_used)]

use cavalier_contours::polyline::{BooleanOp, PlineCreation, PlineSource, PlineSourceMut, Polyline};
use criterion::{Criterion, criterion_group, criterion_main};

use turnpass::dialect::{Dialect, DialectChoice, GCodeSystem};
use turnpass::machine::{MachineSettings, StockSettings, ToolKind, ToolSettings};
use turnpass::part::PartCheck;
use turnpass::part::tool::{self, Orientation, Tool};
use turnpass::pipeline::{Ready, Settings};
use turnpass::semantic::LowerOptions;
use turnpass::syntax::ParseOptions;
use turnpass::toolpath::{Motion, Xz};

mod support;

const PROGRAM: &str = "%
O0100
G99 G97 S1000 M03 T0101
G00 X44. Z2.
G71 U1.5 R0.5
G71 P100 Q200 U0.4 W0.1 F0.25
N100 G00 X12.
G01 Z0. F0.1
X16. Z-2.
Z-12.
G02 X22. Z-15. R3.
G01 Z-22.
G03 X28. Z-25. R3.
G01 X32. Z-35.
Z-45.
G02 X38. Z-48. R3.
G01 Z-60.
N200 X44.
G70 P100 Q200
G00 X100. Z50.
M30
%
";

const NOSE: f64 = 0.8;
const STOCK: StockSettings = StockSettings { diameter: 42.0, length: 80.0, front: Some(1.0), bore: None };

fn settings() -> Settings {
    let machine = MachineSettings {
        dialect: Some(Dialect::Fanuc),
        home: Some(turnpass::machine::AxisPair { x: 200.0, z: 50.0 }),
        tool: vec![ToolSettings {
            station: 1,
            offset: None,
            x: 0.0,
            z: 0.0,
            nose_radius: NOSE,
            tip: 3,
            minor_edge_angle: None,
            kind: Some(ToolKind::Turning),
            angle: None,
            diameter: None,
            width: None,
            max_depth: None,
        }],
        ..MachineSettings::default()
    };
    let options = ParseOptions {
        dialect: DialectChoice::Fixed(Dialect::Fanuc),
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    Settings::new(options, &machine, LowerOptions::new(false))
}

/// A cutting move's nose-centre path: start, end, and for an arc its centre and sense.
#[derive(Debug, Clone, Copy)]
struct Path {
    start: Xz,
    end: Xz,
    arc: Option<(Xz, bool)>,
}

/// The nose-centre paths of the feed moves, and of the `G70`'s.
fn paths(ready: &Ready<'_>) -> (Vec<Path>, Vec<Path>) {
    let toolpath = &ready.lowered.toolpath;
    let g70 = ready.lowered.expansions.last().unwrap().moves.clone();
    let shape = Tool::new(tool::entry(&ready.machine, 1, 1), &ready.machine, Orientation::Outside, 100.0);
    let shift = |q: Xz| Xz::new(q.x + shape.centre_offset.x, q.z + shape.centre_offset.z);
    let (mut all, mut finishing) = (Vec::new(), Vec::new());
    for (i, m) in toolpath.moves.iter().enumerate() {
        if !matches!(m.motion, Motion::Feed | Motion::Cw | Motion::Ccw) {
            continue;
        }
        let path = Path {
            start: shift(toolpath.start_of(i)),
            end: shift(m.end),
            arc: m.is_arc().then(|| (shift(m.centre), m.motion == Motion::Ccw)),
        };
        all.push(path);
        if g70.contains(&i) {
            finishing.push(path);
        }
    }
    (all, finishing)
}

/// The angle of `p` about `c` (from +Z toward +X, as the toolpath's arcs count it).
fn angle(p: Xz, c: Xz) -> f64 {
    (p.x - c.x).atan2(p.z - c.z)
}

/// The signed sweep of an arc path, positive counter-clockwise.
fn sweep(path: &Path) -> f64 {
    let (c, ccw) = path.arc.unwrap();
    let tau = std::f64::consts::TAU;
    let (a0, a1) = (angle(path.start, c), angle(path.end, c));
    if ccw { (a1 - a0).rem_euclid(tau) } else { -(a0 - a1).rem_euclid(tau) }
}

/// The distance from `p` to a nose-centre path.
fn distance(p: Xz, path: &Path) -> f64 {
    match path.arc {
        None => {
            let (a, b) = (path.start, path.end);
            let (dx, dz) = (b.x - a.x, b.z - a.z);
            let l2 = dx * dx + dz * dz;
            let s = if l2 > 0.0 { (((p.x - a.x) * dx + (p.z - a.z) * dz) / l2).clamp(0.0, 1.0) } else { 0.0 };
            p.distance(Xz::new(a.x + s * dx, a.z + s * dz))
        }
        Some((c, _)) => {
            let total = sweep(path);
            let along = if total >= 0.0 {
                (angle(p, c) - angle(path.start, c)).rem_euclid(std::f64::consts::TAU)
            } else {
                (angle(path.start, c) - angle(p, c)).rem_euclid(std::f64::consts::TAU)
            };
            if along <= total.abs() {
                (p.distance(c) - path.start.distance(c)).abs()
            } else {
                p.distance(path.start).min(p.distance(path.end))
            }
        }
    }
}

/// The worst distance from the finishing envelope of the points within 0.01 mm of it, and
/// how many there were.
fn worst_on_envelope(points: impl Iterator<Item = Xz>, finishing: &[Path]) -> (f64, usize) {
    let (mut worst, mut count) = (0.0f64, 0);
    for p in points {
        let d = finishing.iter().map(|f| distance(p, f)).fold(f64::INFINITY, f64::min) - NOSE;
        if d.abs() < 0.01 {
            worst = worst.max(d.abs());
            count += 1;
        }
    }
    (worst, count)
}

// The Boolean side works in cavalier's (x, y) = the toolpath's (z, x), where its
// counter-clockwise is the toolpath's (the angle from +Z toward +X grows).

/// The region a nose of radius `r` sweeps along `path`, counter-clockwise.
fn swept(path: &Path, r: f64) -> Polyline<f64> {
    let mut pline = Polyline::with_capacity(4, true);
    match path.arc {
        None => {
            let (a, b) = (path.start, path.end);
            let length = a.distance(b);
            if length < 1e-12 {
                pline.add(a.z - r, a.x, 1.0);
                pline.add(a.z + r, a.x, 1.0);
                return pline;
            }
            // The left normal of the travel in (z, x).
            let (dz, dx) = ((b.z - a.z) / length, (b.x - a.x) / length);
            let (nz, nx) = (-dx, dz);
            pline.add(a.z - r * nz, a.x - r * nx, 0.0);
            pline.add(b.z - r * nz, b.x - r * nx, 1.0);
            pline.add(b.z + r * nz, b.x + r * nx, 0.0);
            pline.add(a.z + r * nz, a.x + r * nx, 1.0);
        }
        Some((c, _)) => {
            // Counter-clockwise from the start of the counter-clockwise sense.
            let total = sweep(path);
            let (from, span) = if total >= 0.0 { (angle(path.start, c), total) } else { (angle(path.end, c), -total) };
            let radius = path.start.distance(c);
            let at = |a: f64, rr: f64| (c.z + rr * a.cos(), c.x + rr * a.sin());
            let bulge = (span / 4.0).tan();
            let (o0, o1) = (at(from, radius + r), at(from + span, radius + r));
            let (i0, i1) = (at(from, radius - r), at(from + span, radius - r));
            pline.add(o0.0, o0.1, bulge);
            pline.add(o1.0, o1.1, 1.0);
            pline.add(i1.0, i1.1, -bulge);
            pline.add(i0.0, i0.1, 1.0);
        }
    }
    pline
}

/// The stock less every sweep, in turn: the pieces of material left.
fn boolean_removal(paths: &[Path]) -> Vec<Polyline<f64>> {
    let (front, back, outer) = (1.0, 1.0 - STOCK.length, STOCK.diameter / 2.0);
    let mut stock = Polyline::with_capacity(4, true);
    stock.add(back, 0.0, 0.0);
    stock.add(front, 0.0, 0.0);
    stock.add(front, outer, 0.0);
    stock.add(back, outer, 0.0);
    let mut pieces = vec![stock];
    for path in paths {
        let cut = swept(path, NOSE);
        let mut next = Vec::with_capacity(pieces.len());
        for piece in &pieces {
            let result = piece.boolean(&cut, BooleanOp::Not);
            next.extend(result.pos_plines.into_iter().map(|p| p.pline));
        }
        pieces = next;
    }
    pieces
}

/// The points of a Boolean result the exactness is measured at: each vertex and the midpoint
/// of each segment (on the arc for an arc), as (x, z).
fn boolean_points(pieces: &[Polyline<f64>]) -> Vec<Xz> {
    let mut out = Vec::new();
    for piece in pieces {
        for (v1, v2) in piece.iter_segments() {
            out.push(Xz::new(v1.y, v1.x));
            let mid = cavalier_contours::polyline::seg_midpoint(v1, v2);
            out.push(Xz::new(mid.y, mid.x));
        }
    }
    out
}

fn representation(c: &mut Criterion) {
    let settings = settings().with_part(PartCheck { stock: Some(STOCK) });
    let ready = support::ready(PROGRAM.as_bytes(), &settings);
    let (all, finishing) = paths(&ready);
    let check = PartCheck { stock: Some(STOCK) };

    let run = turnpass::part::run(ready.valid(), &ready.machine, &check);
    let part = run.part.unwrap();
    // The dexels know which move cut each point: those of the `G70`.
    let g70 = ready.lowered.expansions.last().unwrap().moves.clone();
    let finished = part.surface().filter(|s| s.cut_by.is_some_and(|i| g70.contains(&i))).map(|s| s.at);
    let (dexel_worst, dexel_count) = worst_on_envelope(finished, &finishing);
    let pieces = boolean_removal(&all);
    let vertices: usize = pieces.iter().map(|p| p.vertex_count()).sum();
    let (boolean_worst, boolean_count) = worst_on_envelope(boolean_points(&pieces).into_iter(), &finishing);
    println!("\nturnpass-bench: part removal of a G71 + G70 shaft ({} cutting moves, nose {NOSE} mm)", all.len());
    println!(
        "dexels (rays {:.4} mm apart): {dexel_count} finished surface points, worst {dexel_worst:.2e} mm from the \
         finishing envelope",
        part.spacing()
    );
    println!(
        "cavalier_contours: {} pieces, {vertices} vertices; {boolean_count} points, worst {boolean_worst:.2e} mm from \
         the finishing envelope",
        pieces.len()
    );

    let mut group = c.benchmark_group("part_removal");
    group.bench_function("dexels (nose and insert, part::run)", |b| {
        b.iter(|| turnpass::part::run(std::hint::black_box(ready.valid()), &ready.machine, &check))
    });
    group.bench_function("cavalier_contours (nose only, Boolean NOT)", |b| {
        b.iter(|| boolean_removal(std::hint::black_box(&all)))
    });
    group.finish();
}

criterion_group!(benches, representation);
criterion_main!(benches);
