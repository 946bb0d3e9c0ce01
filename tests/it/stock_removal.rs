//! Property tests of the Fanuc roughing cycles `G71` (turning) and `G72` (facing) on
//! generated profiles: Type I (monotonic: flats, tapers, chamfers, walls, convex and concave
//! quarter arcs) and, for `G71`, Type II (the P block names X and Z; pockets with falling
//! tapers, walls and arcs); outside and inside turning, facing from either side, profiles
//! running toward -Z or +Z (-X or +X when facing); random depth Δd, retract e, allowances
//! U/W, start point, `G00` or `G01` P block, two-block or one-block form, and the Haas exit
//! line at the end of the profile.
//!
//! The geometry is generated in a canonical frame (`u` across the cut, pointing to the start
//! point A; `v` along it, the profile running toward smaller `v`), written as a program and
//! lowered; the checks read the moves back into that frame and compare them with the
//! generated shape, never with the implementation's own geometry:
//!
//! - (a) no move of the roughing cycle, rapid or feed, sampled along its length, enters the
//!   profile shifted by the allowance;
//! - (b) no rapid passes through stock that no earlier level has cut: the stock is the box
//!   below A's level, behind the profile's start and A, in front of the profile's end, above
//!   the shifted profile; a level cut removes what lies above it over its length;
//! - (c) the last cutting moves are exactly the shifted profile, approached as the P block
//!   moves, and the cycle ends at A;
//! - (d) at every point along the cut the levels over it step down from A by at most Δd
//!   each, the last within Δd of the shifted profile;
//! - (e) `G70 P Q` then runs the P block and exactly the profile, and returns to A.

use proptest::prelude::*;
use turnpass::machine::ModelFile;
use turnpass::pipeline::Settings;
use turnpass::semantic::LowerOptions;
use turnpass::toolpath::{Motion, Move, Xz};

use crate::canonical::{Element, Uv};
use crate::moves::{cycle_moves, samples};
use crate::simulate::parse_options;
use crate::support::analyse;

const TOLERANCE: f64 = 1e-6;

/// The shape a roughing cycle cuts to, in the canonical frame: the profile shifted by the
/// allowance, from the end of the P block's move to the end of the shape (the exit left out).
struct Shape {
    elements: Vec<Element>,
}

impl Shape {
    fn first(&self) -> Uv {
        self.elements[0].start
    }

    fn last(&self) -> Uv {
        self.elements[self.elements.len() - 1].end
    }

    /// The highest `u` of the shape at `v` (the top of a wall), or none outside its span.
    fn envelope(&self, v: f64) -> Option<f64> {
        self.elements.iter().filter_map(|e| e.u_at(v)).reduce(f64::max)
    }

    /// Whether `p` lies strictly inside the part: below the shape within its span, or below
    /// the shape's end beyond it, and not on the shape (a point on a wall is on the boundary).
    fn inside(&self, p: Uv) -> bool {
        let below = if p.v < self.last().v { p.u < self.last().u } else { self.envelope(p.v).is_some_and(|u| p.u < u) };
        below && self.elements.iter().all(|e| e.distance(p) > TOLERANCE)
    }
}

/// Which cycle and which side: `G71` turns along Z, `G72` faces along X; `outside` puts A on
/// the side of larger X (larger Z when facing); `toward_minus` runs the profile toward -Z
/// (toward -X when facing).
#[derive(Debug, Clone, Copy)]
struct Setup {
    facing: bool,
    outside: bool,
    toward_minus: bool,
}

#[derive(Debug, Clone)]
struct Case {
    setup: Setup,
    type_ii: bool,
    /// The start point A.
    start: Uv,
    /// Where the P block goes.
    first: Uv,
    /// The profile's shape, from `first`.
    elements: Vec<Element>,
    /// The Haas exit: a rapid at the end of the profile, back to the start point's plane.
    exit: Option<Uv>,
    g01_first: bool,
    one_block: bool,
    depth: f64,
    retract: f64,
    /// The allowance in the canonical frame, toward A and against the cut.
    du: f64,
    dv: f64,
    /// Offsets of the canonical frame in the program (see `point`).
    offset_u: f64,
    offset_v: f64,
}

impl Case {
    fn sign_u(&self) -> f64 {
        if self.setup.outside { 1.0 } else { -1.0 }
    }

    fn sign_v(&self) -> f64 {
        if self.setup.toward_minus { 1.0 } else { -1.0 }
    }

    /// A canonical point in the toolpath frame (X as a radius).
    fn point(&self, p: Uv) -> Xz {
        let across = self.offset_u + self.sign_u() * p.u;
        let along = self.offset_v + self.sign_v() * p.v;
        if self.setup.facing { Xz::new(along, across) } else { Xz::new(across, along) }
    }

    fn to_uv(&self, p: Xz) -> Uv {
        let (across, along) = if self.setup.facing { (p.z, p.x) } else { (p.x, p.z) };
        Uv { u: (across - self.offset_u) * self.sign_u(), v: (along - self.offset_v) * self.sign_v() }
    }

    /// The allowance words: U a diameter in X, W a length in Z, signed as the side demands.
    fn allowance_words(&self) -> (f64, f64) {
        let (across, along) = (self.du * self.sign_u(), self.dv * self.sign_v());
        if self.setup.facing { (2.0 * along, across) } else { (2.0 * across, along) }
    }

    fn shape(&self) -> Shape {
        Shape { elements: self.elements.iter().map(|e| e.shifted(self.du, self.dv)).collect() }
    }

    fn code(&self) -> &'static str {
        if self.setup.facing { "G72" } else { "G71" }
    }

    fn words(&self, p: Uv) -> (f64, f64) {
        let xz = self.point(p);
        (2.0 * xz.x, xz.z)
    }

    /// Whether an arc element runs counter-clockwise (`G03`: the angle of the point about the
    /// centre, atan2(x - cx, z - cz), increasing); its quarter sweep is less than a half turn.
    fn ccw(&self, e: &Element) -> bool {
        let Some((c, _)) = e.arc else { return false };
        let (s, c, end) = (self.point(e.start), self.point(c), self.point(e.end));
        (s.z - c.z) * (end.x - c.x) - (s.x - c.x) * (end.z - c.z) > 0.0
    }

    fn program(&self) -> String {
        let code = self.code();
        let (xa, za) = self.words(self.start);
        let mut out = format!("G21 G99\nG97 S500 M03\nG00 X{xa:.3} Z{za:.3}\n");
        let (u, w) = self.allowance_words();
        let depth_word = if self.setup.facing { 'W' } else { 'U' };
        if self.one_block {
            out.push_str(&format!("{code} P10 Q20 U{u:.3} W{w:.3} D{:.3} F0.25\n", self.depth));
        } else {
            out.push_str(&format!("{code} {depth_word}{:.3} R{:.3}\n", self.depth, self.retract));
            out.push_str(&format!("{code} P10 Q20 U{u:.3} W{w:.3} F0.25\n"));
        }
        let (x0, z0) = self.words(self.first);
        let motion = if self.g01_first { "G01" } else { "G00" };
        let feed = if self.g01_first { " F0.2" } else { "" };
        match (self.type_ii, self.setup.facing) {
            (true, _) => out.push_str(&format!("N10 {motion} X{x0:.3} Z{z0:.3}{feed}\n")),
            (false, false) => out.push_str(&format!("N10 {motion} X{x0:.3}{feed}\n")),
            (false, true) => out.push_str(&format!("N10 {motion} Z{z0:.3}{feed}\n")),
        }
        let last = self.elements.len() - usize::from(self.exit.is_none());
        for (i, e) in self.elements.iter().enumerate() {
            let label = if i == last { "N20 " } else { "" };
            let (x, z) = self.words(e.end);
            let line = match e.arc {
                None => format!("G01 X{x:.3} Z{z:.3} F0.1"),
                Some((c, _)) => {
                    let (s, c) = (self.point(e.start), self.point(c));
                    let (i, k) = (c.x - s.x, c.z - s.z);
                    format!("{} X{x:.3} Z{z:.3} I{i:.3} K{k:.3} F0.1", if self.ccw(e) { "G03" } else { "G02" })
                }
            };
            out.push_str(&format!("{label}{line}\n"));
        }
        if let Some(exit) = self.exit {
            let (x, z) = self.words(exit);
            out.push_str(&if self.setup.facing { format!("N20 G00 X{x:.3}\n") } else { format!("N20 G00 Z{z:.3}\n") });
        }
        out.push_str("G70 P10 Q20\nM30\n");
        out
    }
}

/// One step of a profile from `at`, of kind `kind` with sizes `a` and `b` (mm): 0 flat,
/// 1 taper, 2 chamfer, 3 wall, 4 convex and 5 concave quarter arc, all rising; 6 falling
/// taper, 7 falling wall, 8 convex and 9 concave falling quarter arc (Type II pockets). A
/// falling step stops at `floor`.
fn step(at: Uv, kind: u8, a: f64, b: f64, floor: f64) -> Option<Element> {
    let down = a.min(at.u - floor);
    let line = |end: Uv| Some(Element::line(at, end));
    let arc = |end: Uv, centre: Uv, upper: bool| Some(Element { start: at, end, arc: Some((centre, upper)) });
    match kind {
        0 => line(Uv { u: at.u, v: at.v - a }),
        1 => line(Uv { u: at.u + a / 2.0, v: at.v - b }),
        2 => line(Uv { u: at.u + a, v: at.v - a }),
        3 => line(Uv { u: at.u + a, v: at.v }),
        4 => arc(Uv { u: at.u + a, v: at.v - a }, Uv { u: at.u, v: at.v - a }, true),
        5 => arc(Uv { u: at.u + a, v: at.v - a }, Uv { u: at.u + a, v: at.v }, false),
        _ if down <= 0.0 => None,
        6 => line(Uv { u: at.u - down, v: at.v - b }),
        7 => line(Uv { u: at.u - down, v: at.v }),
        8 => arc(Uv { u: at.u - down, v: at.v - down }, Uv { u: at.u - down, v: at.v }, true),
        _ => arc(Uv { u: at.u - down, v: at.v - down }, Uv { u: at.u, v: at.v - down }, false),
    }
}

fn case() -> impl Strategy<Value = Case> {
    let shape = (
        (any::<bool>(), any::<bool>(), any::<bool>(), any::<bool>()),
        4u32..40,
        prop::collection::vec((0u8..10, 1u32..20, 1u32..20), 1..12),
        prop::sample::select(vec![0.0, 1.0, 3.0]),
        prop::sample::select(vec![0.0, 0.5, 2.0]),
        any::<bool>(),
    );
    let cut = (
        (any::<bool>(), any::<bool>()),
        1u32..12,
        prop::sample::select(vec![0.0, 0.1, 0.3, 0.5, 1.0, 2.0, 5.0]),
        prop::sample::select(vec![0.0, 0.1, 0.25, 0.5]),
        prop::sample::select(vec![0.0, 0.05, 0.1, 0.3]),
        (prop::sample::select(vec![0.0, 0.5, 2.0, 5.0]), any::<bool>()),
    );
    (shape, cut).prop_map(|(((facing, outside, toward_minus, type_ii), u0, steps, wall, lead, with_exit), cut)| {
        let ((g01_first, one_block), depth, retract, du, dv, (extra, above_allowance)) = cut;
        // Type II is the G71 form whose P block names both axes.
        let type_ii = type_ii && !facing;
        let lead = if type_ii { lead } else { 0.0 };
        let start_v = 2.0;
        let first = Uv { u: f64::from(u0) / 2.0, v: start_v - lead };
        let mut at = first;
        let mut elements = Vec::new();
        if lead == 0.0 {
            // The start point lies in the plane where the profile starts: a profile that
            // rose right there would put a face in the start's plane, which no program
            // does; begin with a stretch along the cut, in front of the face.
            elements.push(Element::line(at, Uv { u: at.u, v: at.v - 1.0 }));
            at.v -= 1.0;
        }
        for (kind, a, b) in steps {
            let kind = if type_ii { kind } else { kind % 6 };
            if let Some(e) = step(at, kind, f64::from(a) / 2.0, f64::from(b) / 2.0, 1.0) {
                at = e.end;
                elements.push(e);
            }
        }
        let top = elements.iter().flat_map(|e| [e.start.u, e.end.u]).fold(at.u, f64::max) + wall;
        if top > at.u {
            elements.push(Element::line(at, Uv { u: top, v: at.v }));
        }
        // A may lie below the shifted end (`N20 X60` from X60 with U0.4) but never inside
        // the allowance where the profile starts.
        let start_u = (top + extra + if above_allowance { du } else { 0.0 }).max(first.u + du);
        // The Haas exit: back to the start's plane at the top, outside the stock.
        let exit = (with_exit && top + du >= start_u).then_some(Uv { u: top, v: start_v });
        let setup = Setup { facing, outside, toward_minus };
        let v_min = elements.iter().map(|e| e.end.v).fold(f64::INFINITY, f64::min);
        let (offset_u, offset_v) = if facing {
            // Z of A at ±1; X at least 1 mm (radius) everywhere.
            let offset_v = if toward_minus { 1.0 - v_min } else { start_v + dv + 1.0 };
            (if outside { 1.0 - start_u } else { start_u - 1.0 }, offset_v)
        } else {
            (if outside { 0.0 } else { start_u + 10.0 }, 0.0)
        };
        Case {
            setup,
            type_ii,
            start: Uv { u: start_u, v: start_v },
            first,
            elements,
            exit,
            g01_first,
            one_block,
            depth: f64::from(depth) / 2.0,
            retract: if one_block { 0.5 } else { retract },
            du,
            dv,
            offset_u,
            offset_v,
        }
    })
}

fn settings() -> Settings {
    let settings = ModelFile::from_toml(crate::cycles::MACHINE).unwrap().machine;
    let lower = LowerOptions { nose_radius_compensation: false, ..LowerOptions::new(false) };
    Settings::new(parse_options(&settings), &settings, lower)
}

fn close(a: Xz, b: Xz) -> bool {
    a.distance(b) < TOLERANCE
}

/// The moves `moves` follow `expected` exactly: the same end points, lines as feeds, arcs
/// about the same centres and in the same sense.
fn check_elements(case: &Case, moves: &[&Move], expected: &[Element], what: &str) -> Result<(), TestCaseError> {
    prop_assert_eq!(moves.len(), expected.len(), "{}: moves along the profile", what);
    for (m, e) in moves.iter().zip(expected) {
        let end = case.point(e.end);
        prop_assert!(close(m.end, end), "{}: {:?} ends at {:?}, expected {:?}", what, m.motion, m.end, end);
        match e.arc {
            None => prop_assert_eq!(m.motion, Motion::Feed, "{}", what),
            Some((c, _)) => {
                prop_assert_eq!(
                    m.motion,
                    if case.ccw(e) { Motion::Ccw } else { Motion::Cw },
                    "{}: the arc's sense",
                    what
                );
                let centre = case.point(c);
                prop_assert!(close(m.centre, centre), "{}: arc centre {:?}, expected {:?}", what, m.centre, centre);
            }
        }
    }
    Ok(())
}

/// A cut at one level: a feed along the cut, above the shape (not a feed that follows it).
#[derive(Debug, Clone, Copy)]
struct Level {
    u: f64,
    lo: f64,
    hi: f64,
}

impl Level {
    fn covers(&self, v: f64) -> bool {
        v >= self.lo - TOLERANCE && v <= self.hi + TOLERANCE
    }
}

fn level_of(shape: &Shape, from: Uv, to: Uv) -> Option<Level> {
    let along = (from.u - to.u).abs() <= TOLERANCE && (from.v - to.v).abs() > TOLERANCE;
    let on_shape = (0..=8).all(|i| {
        let t = f64::from(i) / 8.0;
        let p = Uv { u: from.u, v: from.v + (to.v - from.v) * t };
        shape.elements.iter().any(|e| e.distance(p) <= TOLERANCE)
    });
    (along && !on_shape).then_some(Level { u: from.u, lo: from.v.min(to.v), hi: from.v.max(to.v) })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1024, ..ProptestConfig::default() })]

    #[test]
    fn g71_g72_rough_to_the_shifted_profile(case in case()) {
        let text = case.program();
        // No error anywhere, and the toolpath validates.
        let ready = analyse(text.as_bytes(), &settings())
            .ready()
            .map_err(|analysed| TestCaseError::fail(format!("{:?}\n{}", analysed.diagnostics, text)))?;
        let (parsed, lowered) = (&ready.parsed, &ready.lowered);

        let shape = case.shape();
        let a = case.start;
        let start = case.point(a);
        let call_line = text.lines().position(|l| l.contains("P10 Q20 U")).unwrap() + 1;
        let moves = &lowered.toolpath.moves;
        let (from, rough) = cycle_moves(&parsed.program, moves, call_line);
        prop_assert!(close(from, start), "the cycle starts at {:?}, not at A {:?}", from, start);
        prop_assert!(!rough.is_empty());

        // (c) The semi-finishing pass: the P block's move to the shifted start, then exactly
        // the shifted profile, then rapids back to A.
        let end = rough.iter().rposition(|m| m.motion != Motion::Rapid).map_or(0, |i| i + 1);
        let n = shape.elements.len();
        prop_assert!(end >= n, "{} cutting moves, fewer than the profile's {}\n{}", end, n, text);
        check_elements(&case, &rough[end - n..end], &shape.elements, "semi-finishing pass")?;
        // The tool is at the shifted start before the pass, by the P block's motion unless it
        // was there already.
        let position = |i: usize| if i == 0 { from } else { rough[i - 1].end };
        let semi_start = case.point(shape.first());
        prop_assert!(close(position(end - n), semi_start), "the pass starts at {:?}", position(end - n));
        let approached = end > n && !close(position(end - n - 1), semi_start);
        if approached {
            prop_assert_eq!(rough[end - n - 1].motion, if case.g01_first { Motion::Feed } else { Motion::Rapid });
        }
        let roughing = if approached { end - n - 1 } else { end - n };
        prop_assert!(rough[end..].iter().all(|m| m.motion == Motion::Rapid));
        prop_assert!(close(rough[rough.len() - 1].end, start), "the cycle ends at {:?}", rough[rough.len() - 1].end);

        // (a) and (b), move by move; the level cuts are gathered as they come.
        let front = a.v.min(shape.first().v);
        let stock = |p: Uv| {
            p.u < a.u - TOLERANCE
                && p.v < front - TOLERANCE
                && p.v > shape.last().v + TOLERANCE
                && shape.envelope(p.v).is_none_or(|floor| p.u > floor + TOLERANCE)
        };
        let mut levels: Vec<Level> = Vec::new();
        let mut at = from;
        for (i, m) in rough.iter().enumerate() {
            let finished = i >= end;
            for p in samples(at, m, 64) {
                let q = case.to_uv(p);
                prop_assert!(!shape.inside(q), "(a) a {:?} move to {:?} passes {:?}, inside\n{}", m.motion, m.end, q, text);
                if m.motion == Motion::Rapid && !finished {
                    let removed = levels.iter().any(|l| q.u >= l.u - TOLERANCE && l.covers(q.v));
                    prop_assert!(
                        !stock(q) || removed,
                        "(b) a rapid to {:?} passes {:?}, through stock no level has cut\n{}",
                        m.end, q, text
                    );
                }
            }
            if m.motion == Motion::Feed && i < roughing {
                levels.extend(level_of(&shape, case.to_uv(at), case.to_uv(m.end)));
            }
            at = m.end;
        }

        // (d) Over every point along the cut, levels Δd apart at most from A down to within
        // Δd of the shifted profile.
        let span = front - shape.last().v;
        for k in 0..=400 {
            let v = shape.last().v + span * (f64::from(k) + 0.5) / 401.0;
            let Some(floor) = shape.envelope(v) else { continue };
            let mut over: Vec<f64> = levels.iter().filter(|l| l.covers(v)).map(|l| l.u).collect();
            over.sort_by(|x, y| y.total_cmp(x));
            over.dedup_by(|x, y| (*x - *y).abs() <= TOLERANCE);
            let mut previous = a.u;
            for &u in &over {
                prop_assert!(previous - u <= case.depth + TOLERANCE, "(d) at v {}: levels {:?} from {}\n{}", v, over, a.u, text);
                previous = u;
            }
            prop_assert!(
                previous - floor <= case.depth + TOLERANCE,
                "(d) at v {}: the last level {} leaves more than Δd {} over the profile at {}\n{}",
                v, previous, case.depth, floor, text
            );
        }

        // (e) G70: the P block's move, exactly the profile, its exit at rapid, back to A.
        let g70_line = text.lines().position(|l| l.starts_with("G70")).unwrap() + 1;
        let (from, finish) = cycle_moves(&parsed.program, moves, g70_line);
        prop_assert!(close(from, start));
        // A rapid that goes nowhere is no move: the P block's, when A is where it goes.
        let approach = usize::from(case.g01_first || !close(start, case.point(case.first)));
        let count = approach + case.elements.len();
        prop_assert!(finish.len() >= count, "G70: {} moves", finish.len());
        if approach == 1 {
            prop_assert!(close(finish[0].end, case.point(case.first)));
            prop_assert_eq!(finish[0].motion, if case.g01_first { Motion::Feed } else { Motion::Rapid });
        }
        check_elements(&case, &finish[approach..count], &case.elements, "G70")?;
        prop_assert!(finish[count..].iter().all(|m| m.motion == Motion::Rapid));
        if let Some(exit) = case.exit {
            prop_assert!(finish.len() > count && close(finish[count].end, case.point(exit)), "G70: no exit");
        }
        prop_assert!(close(finish[finish.len() - 1].end, start), "G70 ends at {:?}", finish[finish.len() - 1].end);
    }
}
