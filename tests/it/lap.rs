//! Property tests of the OSP LAP cycles on generated contours, longitudinal (`G81`) and
//! transverse (`G82`): lines, tapers, pockets, walls and quarter arcs, with random depth,
//! allowances, start point and first block (`G00` or `G01`, naming one axis or both).
//!
//! The geometry is generated in the canonical frame of the cycles (`u` across the cut,
//! pointing to the start point; `v` along it, the contour running toward smaller `v`) and
//! written as a program; the checks read the moves back into that frame and compare them
//! with the generated shape, never with the implementation's own geometry:
//!
//! - `G85`: no move (rapid or feed, sampled along its length) enters the contour offset by
//!   the allowance; the last cutting moves are exactly that offset contour; the tool ends
//!   at the start point.
//! - `G86`: on a contour without pockets, no move enters the finished contour (its passes
//!   close in on the contour along the infeed line and may run inside the Z allowance near a
//!   shoulder; on the falling side of a pocket even a contour translated by (U, W) dips into
//!   the part, so pockets are left out of this check); the last pass is the offset contour;
//!   the tool ends at the start point.
//! - `G87`: the approach and then exactly the contour; the tool stays at the contour's end.
//! - `G85` and `G86`: pass N starts at M-P195's infeed point, `Xp = Xs − N·D` on the line
//!   from the start point to the contour's start plus allowance (`Zp`); `G86`'s last pass
//!   starts at that contour start.

use proptest::prelude::*;
use turnpass::dialect::{Dialect, DialectChoice, GCodeSystem};
use turnpass::machine::ModelFile;
use turnpass::pipeline::Settings;
use turnpass::semantic::LowerOptions;
use turnpass::syntax::ParseOptions;
use turnpass::toolpath::{Motion, Move, Xz};

use crate::canonical::{Element, Uv};
use crate::moves::{cycle_moves, samples};
use crate::support::analyse;

#[derive(Debug, Clone)]
struct Case {
    transverse: bool,
    elements: Vec<Element>,
    start: Uv,
    /// The first block names both axes (the start lies `lead` further back along the cut).
    lead: f64,
    g01_first: bool,
    depth: f64,
    u_word: f64,
    w_word: f64,
    /// Some element falls toward the axis along the cut.
    pockets: bool,
}

impl Case {
    /// The allowance in the canonical frame: U is a diameter in X, W a length in Z.
    fn allowance(&self) -> (f64, f64) {
        if self.transverse { (self.w_word, self.u_word / 2.0) } else { (self.u_word / 2.0, self.w_word) }
    }

    fn contour_start(&self) -> Uv {
        self.elements[0].start
    }

    /// M-P195's infeed points, canonical: levels `D` apart (a diameter for `G81`) from the
    /// start point while they stay above the contour start plus allowance, on the line from
    /// the start point to that contour start.
    fn infeed_points(&self) -> Vec<Uv> {
        let (du, dv) = self.allowance();
        let (a, c) = (self.start, Uv { u: self.contour_start().u + du, v: self.contour_start().v + dv });
        let step = if self.transverse { self.depth } else { self.depth / 2.0 };
        (1..)
            .map(|k| a.u - k as f64 * step)
            .take_while(|&u| u > c.u + 1e-9)
            .map(|u| Uv { u, v: c.v + (a.v - c.v) * (u - c.u) / (a.u - c.u) })
            .collect()
    }

    /// Program words for a canonical point: X as a diameter.
    fn xz(&self, p: Uv) -> (f64, f64) {
        if self.transverse { (2.0 * p.v, p.u) } else { (2.0 * p.u, p.v) }
    }

    fn to_uv(&self, p: Xz) -> Uv {
        if self.transverse { Uv { u: p.z, v: p.x } } else { Uv { u: p.x, v: p.z } }
    }

    fn program(&self) -> String {
        let mut out = String::from("$PROP.MIN%\nNLAP1 ");
        out.push_str(if self.transverse { "G82\n" } else { "G81\n" });
        let (x0, z0) = self.xz(self.contour_start());
        let code = if self.g01_first { "G01" } else { "G00" };
        let feed = if self.g01_first { " F0.2" } else { "" };
        match (self.lead > 0.0, self.transverse) {
            (true, _) => out.push_str(&format!("{code} X{x0:.3} Z{z0:.3}{feed}\n")),
            (false, false) => out.push_str(&format!("{code} X{x0:.3}{feed}\n")),
            (false, true) => out.push_str(&format!("{code} Z{z0:.3}{feed}\n")),
        }
        for e in &self.elements {
            let (x, z) = self.xz(e.end);
            match e.arc {
                None => out.push_str(&format!("G01 X{x:.3} Z{z:.3} F0.1\n")),
                Some((c, _)) => {
                    let (s, c, end) = (self.point(e.start), self.point(c), self.point(e.end));
                    let ccw = (s.z - c.z) * (end.x - c.x) - (s.x - c.x) * (end.z - c.z) > 0.0;
                    let (i, k) = (c.x - s.x, c.z - s.z);
                    out.push_str(&format!(
                        "{} X{x:.3} Z{z:.3} I{i:.3} K{k:.3} F0.1\n",
                        if ccw { "G03" } else { "G02" }
                    ));
                }
            }
        }
        let (xs, zs) = self.xz(self.start);
        let (d, u, w) = (self.depth, self.u_word, self.w_word);
        out.push_str("G80\nG50 S2000\n");
        out.push_str(&format!("G00 X{xs:.3} Z{zs:.3} T010101\nG97 S800 M03\n"));
        out.push_str(&format!("G85 NLAP1 D{d:.3} F0.3 U{u:.3} W{w:.3}\n"));
        out.push_str(&format!("G86 NLAP1 D{d:.3} F0.3 U{u:.3} W{w:.3}\n"));
        out.push_str("G87 NLAP1\nM02\n");
        out
    }

    /// A canonical point in the toolpath frame (X as a radius).
    fn point(&self, p: Uv) -> Xz {
        if self.transverse { Xz::new(p.v, p.u) } else { Xz::new(p.u, p.v) }
    }
}

/// A generated contour: from its start point, steps of six kinds, then a wall up to above
/// everything so that the contour ends at its highest point (the return runs along it).
fn case() -> impl Strategy<Value = Case> {
    let step = (0u8..6, 1u32..20, 1u32..20);
    (
        any::<bool>(),
        10u32..40,
        prop::collection::vec(step, 1..7),
        1u32..20,
        // Never equal to an allowance: a start exactly on the offset first wall cuts nothing.
        prop::sample::select(vec![0.0, 0.7, 2.0, 5.0]),
        any::<bool>(),
        1u32..17,
        prop::sample::select(vec![0.0, 0.2, 0.4, 1.0]),
        prop::sample::select(vec![0.0, 0.1, 0.3]),
    )
        .prop_map(|(transverse, u0, steps, extra, lead, g01_first, depth, u_word, w_word)| {
            let mut at = Uv { u: u0 as f64 / 2.0, v: 100.0 };
            let mut elements = Vec::new();
            if lead == 0.0 {
                // The start point lies in the plane where the contour starts: a contour that
                // rose right there would put the face in the start's plane, which no program
                // does; begin with a stretch along the cut, as a contour in front of a face.
                elements.push(Element { start: at, end: Uv { u: at.u, v: at.v - 1.0 }, arc: None });
                at.v -= 1.0;
            }
            for (kind, a, b) in steps {
                let (a, b) = (a as f64 / 2.0, b as f64 / 2.0);
                let (end, arc) = match kind {
                    0 => (Uv { u: at.u, v: at.v - a }, None),
                    1 => (Uv { u: at.u + a / 2.0, v: at.v - b }, None),
                    2 => (Uv { u: (at.u - a).max(2.0), v: at.v - b }, None),
                    3 => (Uv { u: at.u + a, v: at.v }, None),
                    4 => (Uv { u: at.u + a, v: at.v - a }, Some((Uv { u: at.u, v: at.v - a }, true))),
                    _ => (Uv { u: at.u + a, v: at.v - a }, Some((Uv { u: at.u + a, v: at.v }, false))),
                };
                if (end.u - at.u).abs() + (end.v - at.v).abs() > 0.0 {
                    elements.push(Element { start: at, end, arc });
                }
                at = end;
            }
            if at.v >= 100.0 {
                // A contour must reach along the cut to be roughed along it.
                elements.push(Element { start: at, end: Uv { u: at.u, v: at.v - 2.0 }, arc: None });
                at.v -= 2.0;
            }
            let top = elements.iter().flat_map(|e| [e.start.u, e.end.u]).fold(at.u, f64::max);
            elements.push(Element { start: at, end: Uv { u: top + 1.0, v: at.v }, arc: None });
            let pockets = elements.iter().any(|e| e.end.u < e.start.u);
            let first = elements[0].start;
            let allowance_u = if transverse { w_word } else { u_word / 2.0 };
            let start = Uv { u: top + 1.0 + allowance_u + extra as f64 / 2.0, v: first.v + lead };
            Case { transverse, elements, start, lead, g01_first, depth: depth as f64 / 2.0, u_word, w_word, pockets }
        })
}

fn settings() -> Settings {
    let settings = ModelFile::from_toml(
        "[machine]\ndialect = \"osp\"\nunits = \"mm\"\nhome = { x = 500.0, z = 300.0 }\nmax_spindle_rpm = 3500\n",
    )
    .unwrap()
    .machine;
    let options = ParseOptions {
        dialect: DialectChoice::Fixed(Dialect::Osp),
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    Settings::new(options, &settings, LowerOptions { nose_radius_compensation: false, ..LowerOptions::new(false) })
}

/// Whether `p` lies strictly inside the region under `elements` (below the contour, within
/// its span along the cut). A point on a wall is on the boundary, not inside: the contour is
/// probed a hair either side along the cut, and the lower value counts (slopes here are at
/// most 40:1, so the probe moves the contour by far less than the tolerance).
fn inside(elements: &[Element], p: Uv) -> bool {
    let envelope = |v: f64| elements.iter().filter_map(|e| e.u_at(v)).fold(f64::NEG_INFINITY, f64::max);
    let floor = [p.v - 1e-9, p.v, p.v + 1e-9].into_iter().map(envelope).fold(f64::INFINITY, f64::min);
    p.u < floor - 1e-6
}

fn close(a: Xz, b: Xz) -> bool {
    a.distance(b) < 1e-6
}

/// The moves after the last feed that are not returns: the trailing cutting moves, `n` of them.
fn last_cut<'a>(moves: &[&'a Move], n: usize) -> Vec<&'a Move> {
    let end = moves.iter().rposition(|m| m.motion != Motion::Rapid).map_or(0, |i| i + 1);
    moves[end.saturating_sub(n)..end].to_vec()
}

fn check_elements(case: &Case, moves: &[&Move], expected: &[Element]) -> Result<(), TestCaseError> {
    prop_assert_eq!(moves.len(), expected.len(), "moves of the contour pass");
    for (m, e) in moves.iter().zip(expected) {
        prop_assert!(close(m.end, case.point(e.end)), "{:?} ends at {:?}, expected {:?}", m.motion, m.end, e.end);
        match e.arc {
            None => prop_assert_eq!(m.motion, Motion::Feed),
            Some((c, _)) => {
                prop_assert!(m.is_arc());
                prop_assert!(close(m.centre, case.point(c)), "arc centre {:?}, expected {:?}", m.centre, c);
            }
        }
    }
    Ok(())
}

/// Where the roughing passes start: `G85` passes are the feeds along the cut before the last
/// pass; a `G86` pass is a run of `n` contour moves, perhaps after a fed approach.
fn pass_starts(case: &Case, from: Xz, moves: &[&Move], n: usize, copy: bool) -> Vec<Uv> {
    let mut starts = Vec::new();
    let mut points = vec![from];
    points.extend(moves.iter().map(|m| m.end));
    let end = moves.iter().rposition(|m| m.motion != Motion::Rapid).map_or(0, |i| i + 1);
    if !copy {
        for (i, m) in moves[..end.saturating_sub(n)].iter().enumerate() {
            let (a, b) = (case.to_uv(points[i]), case.to_uv(m.end));
            if m.motion == Motion::Feed && (a.u - b.u).abs() < 1e-9 && (a.v - b.v).abs() > 1e-9 {
                starts.push(a);
            }
        }
        return starts;
    }
    let mut i = 0;
    while i < moves.len() {
        if moves[i].motion == Motion::Rapid {
            i += 1;
            continue;
        }
        let run = moves[i..].iter().take_while(|m| m.motion != Motion::Rapid).count();
        if run >= n {
            starts.push(case.to_uv(points[i + run - n]));
        }
        i += run;
    }
    starts
}

fn check_starts(found: &[Uv], expected: &[Uv], what: &str) -> Result<(), TestCaseError> {
    prop_assert_eq!(found.len(), expected.len(), "{}: passes start at {:?}, expected {:?}", what, found, expected);
    for (f, e) in found.iter().zip(expected) {
        prop_assert!(
            (f.u - e.u).abs() < 1e-6 && (f.v - e.v).abs() < 1e-6,
            "{}: a pass starts at {:?}, not {:?}",
            what,
            f,
            e
        );
    }
    Ok(())
}

fn check_no_entry(case: &Case, from: Xz, moves: &[&Move], region: &[Element], what: &str) -> Result<(), TestCaseError> {
    let mut at = from;
    for m in moves {
        for p in samples(at, m, 16) {
            let q = case.to_uv(p);
            prop_assert!(!inside(region, q), "{what}: a {:?} move to {:?} passes {:?}, inside", m.motion, m.end, q);
        }
        at = m.end;
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 160, ..ProptestConfig::default() })]

    #[test]
    fn lap_cycles_keep_to_the_contour(case in case()) {
        let text = case.program();
        // No error anywhere, and the toolpath validates.
        let ready = analyse(text.as_bytes(), &settings())
            .ready()
            .map_err(|analysed| TestCaseError::fail(format!("{:?}\n{}", analysed.diagnostics, text)))?;
        let (parsed, lowered) = (&ready.parsed, &ready.lowered);

        let start = case.point(case.start);
        let (du, dv) = case.allowance();
        let offset: Vec<Element> = case.elements.iter().map(|e| e.shifted(du, dv)).collect();
        let call_line = text.lines().position(|l| l.starts_with("G85")).unwrap() + 1;
        let moves = &lowered.toolpath.moves;

        // G85: outside the offset contour all the way, its last pass on it, back at A.
        let (from, rough) = cycle_moves(&parsed.program, moves, call_line);
        prop_assert!(!rough.is_empty());
        check_no_entry(&case, from, &rough, &offset, "G85")?;
        check_elements(&case, &last_cut(&rough, offset.len()), &offset)?;
        let infeed = case.infeed_points();
        check_starts(&pass_starts(&case, from, &rough, offset.len(), false), &infeed, "G85")?;
        prop_assert!(close(rough.last().unwrap().end, start), "G85 ends at {:?}", rough.last().unwrap().end);

        // G86: outside the finished contour, its last pass on the offset contour, back at A.
        let (from, copy) = cycle_moves(&parsed.program, moves, call_line + 1);
        if !case.pockets {
            check_no_entry(&case, from, &copy, &case.elements, "G86")?;
        }
        check_elements(&case, &last_cut(&copy, offset.len()), &offset)?;
        let mut copy_starts = infeed.clone();
        copy_starts.push(offset[0].start);
        check_starts(&pass_starts(&case, from, &copy, offset.len(), true), &copy_starts, "G86")?;
        prop_assert!(close(copy.last().unwrap().end, start));

        // G87: the approach, then exactly the contour, ending there.
        let (_, finish) = cycle_moves(&parsed.program, moves, call_line + 2);
        let cut = last_cut(&finish, case.elements.len() + 1);
        let approach = cut[0];
        prop_assert_eq!(approach.motion, if case.g01_first { Motion::Feed } else { Motion::Rapid });
        prop_assert!(close(approach.end, case.point(case.contour_start())));
        check_elements(&case, &cut[1..], &case.elements)?;
        prop_assert!(close(finish.last().unwrap().end, case.point(case.elements.last().unwrap().end)));
    }
}
