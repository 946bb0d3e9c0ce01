//! `synth --kind profile` puts its points on the finished surface only: never on a rapid,
//! never on the move that brings the tool from the air to the surface (the approach: the
//! first feed move after a rapid, the move that switches `G42` on, a finishing cycle's move
//! from its start point to the profile's first point), each point on a move of the
//! contour the program finishes. Property-tested on generated turned profiles in the three
//! forms a finishing pass takes: plain moves, a run under `G42`, and `G71` + `G70`.
//!
//! This test checks the points against the program's own moves, as `synth` samples them
//! without a stock; with a stock, `part::synth_profile_points_lie_on_the_finished_part`
//! holds them to the finished part the part model leaves.

use proptest::prelude::*;

use turnpass::diagnose::forward::Nominal;
use turnpass::diagnose::measured::{Kind, Measured};
use turnpass::diagnose::synth::{SynthOptions, synth};
use turnpass::error_model::ErrorModel;
use turnpass::machine::MachineSettings;
use turnpass::toolpath::{Motion, Xz};

use crate::simulate::pipeline_settings;
use crate::support::analyse;

/// How far (mm) a point may be from a move and still be on it: the file's 7 decimals.
const ON: f64 = 1e-6;

/// One element of a turned profile, from the point before it: a line or a quarter arc,
/// out from the axis and toward the chuck (X up, Z down), in hundredths of a millimetre.
#[derive(Debug, Clone, Copy)]
enum Element {
    Line {
        dx: u32,
        dz: u32,
    },
    /// A quarter arc of radius `r`, convex (`G03` on this side of the part) or concave.
    Arc {
        r: u32,
        convex: bool,
    },
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Form {
    /// Plain feed moves after a rapid: the first is the approach.
    Plain,
    /// A run under `G42`: the move that switches it on is the approach.
    NoseCompensation,
    /// `G71` roughing and `G70` finishing: the profile's first block moves from the start
    /// point to the profile (the approach).
    FinishingCycle,
}

fn element() -> impl Strategy<Value = Element> {
    prop_oneof![
        (0u32..=800, 0u32..=1500)
            // At least the profile's 0.5 mm spacing long: a shorter surface gets no point.
            .prop_filter("a move", |&(dx, dz)| dx * dx + dz * dz >= 50 * 50)
            .prop_map(|(dx, dz)| Element::Line { dx, dz }),
        (100u32..=800, any::<bool>()).prop_map(|(r, convex)| Element::Arc { r, convex }),
    ]
}

fn form() -> impl Strategy<Value = Form> {
    prop_oneof![Just(Form::Plain), Just(Form::NoseCompensation), Just(Form::FinishingCycle)]
}

/// `value`, hundredths of a millimetre (not negative), as a number in mm.
fn mm(value: i64) -> String {
    format!("{}.{:02}", value / 100, value % 100)
}

fn word(letter: char, value: i64) -> String {
    let sign = if value < 0 { "-" } else { "" };
    let value = value.abs();
    format!("{letter}{sign}{}.{:02}", value / 100, value % 100)
}

/// The program: a rapid to a clearance point, the approach to the profile's start
/// `(x0, 0)`, the profile, a rapid away. Returns the program and the source lines of its
/// profile's moves (the finished surface).
fn program(form: Form, x0: u32, elements: &[Element]) -> (String, Vec<usize>) {
    let mut lines: Vec<String> = vec!["G21 G99".into(), "T0101".into(), "G97 S1000 M03".into()];
    let mut surface = Vec::new();
    let (mut x, mut z) = (i64::from(x0), 0i64);
    let mut profile: Vec<String> = Vec::new();
    for e in elements {
        match *e {
            Element::Line { dx, dz } => {
                x += i64::from(dx);
                z -= i64::from(dz);
                profile.push(format!("G01 {} {}", word('X', 2 * x), word('Z', z)));
            }
            Element::Arc { r, convex } => {
                let r = i64::from(r);
                x += r;
                z -= r;
                let code = if convex { "G03" } else { "G02" };
                profile.push(format!("{code} {} {} R{}", word('X', 2 * x), word('Z', z), mm(r)));
            }
        }
    }
    let top = x + 300;
    match form {
        Form::Plain => {
            lines.push(format!("G00 {} Z2.", word('X', 2 * (i64::from(x0) + 150))));
            lines.push(format!("G01 {} Z0. F0.1", word('X', 2 * i64::from(x0))));
            for p in profile {
                surface.push(lines.len() + 1);
                lines.push(p);
            }
            lines.push(format!("G00 {} Z5.", word('X', 2 * top)));
        }
        Form::NoseCompensation => {
            lines.push(format!("G00 {} Z2.", word('X', 2 * (i64::from(x0) + 150))));
            lines.push(format!("G42 G01 {} Z0. F0.1", word('X', 2 * i64::from(x0))));
            for p in profile {
                surface.push(lines.len() + 1);
                lines.push(p);
            }
            lines.push(format!("G40 G00 {} Z5.", word('X', 2 * top)));
        }
        Form::FinishingCycle => {
            lines.push(format!("G00 {} Z2.", word('X', 2 * top)));
            lines.push("G71 U1. R0.5".into());
            lines.push("G71 P10 Q20 U0.2 W0.05 F0.2".into());
            // The profile's first block moves from the start point to the profile's start.
            lines.push(format!("N10 G01 {} Z0. F0.1", word('X', 2 * i64::from(x0))));
            let count = profile.len();
            for (k, p) in profile.into_iter().enumerate() {
                let named = if k + 1 == count { format!("N20 {p}") } else { p };
                lines.push(named);
            }
            let g70 = lines.len() + 1;
            lines.push("G70 P10 Q20".into());
            // The cycle's moves all come from the G70 block: the surface is told by place.
            surface.push(g70);
            lines.push(format!("G00 {} Z5.", word('X', 2 * (top + 200))));
        }
    }
    lines.push("M30".into());
    (lines.join("\n") + "\n", surface)
}

/// The distance from `p` to move `i` of `path` (its contour: the programmed path).
fn distance_to(path: &turnpass::toolpath::Toolpath, i: usize, p: Xz) -> f64 {
    let m = &path.moves[i];
    let start = if i == 0 { path.start } else { path.moves[i - 1].contour };
    let end = m.contour;
    match m.motion {
        Motion::Cw | Motion::Ccw => {
            let centre = m.centre;
            let radius = start.distance(centre);
            let angle = |q: Xz| (q.x - centre.x).atan2(q.z - centre.z);
            // The arc's sweep from its start, in its direction; the point's angle on it.
            let sign = if m.motion == Motion::Ccw { 1.0 } else { -1.0 };
            let sweep = (sign * (angle(end) - angle(start))).rem_euclid(std::f64::consts::TAU);
            let at = (sign * (angle(p) - angle(start))).rem_euclid(std::f64::consts::TAU);
            if at <= sweep { (p.distance(centre) - radius).abs() } else { p.distance(start).min(p.distance(end)) }
        }
        _ => {
            let (dx, dz) = (end.x - start.x, end.z - start.z);
            let length2 = dx * dx + dz * dz;
            if length2 == 0.0 {
                return p.distance(start);
            }
            let t = (((p.x - start.x) * dx + (p.z - start.z) * dz) / length2).clamp(0.0, 1.0);
            p.distance(Xz::new(start.x + dx * t, start.z + dz * t))
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn synth_profile_points_lie_on_the_finished_surface_only(
        form in form(),
        x0 in 200u32..=1500,
        elements in proptest::collection::vec(element(), 1..5),
    ) {
        let (text, surface_lines) = program(form, x0, &elements);
        let settings = MachineSettings::default();
        let analysed = analyse(text.as_bytes(), &pipeline_settings(&settings, true));
        let ready = analysed.ready().unwrap_or_else(|a| panic!("{text}\n{:?}", a.diagnostics));
        let nominal = Nominal::new(ready.program(), &ready.lowered, &ready.machine);
        let options = SynthOptions { spacing_mm: 0.5, ..SynthOptions::default() };
        let Measured::Profile(points) = synth(&nominal, &ErrorModel::default(), Kind::Profile, &options).unwrap() else {
            panic!("not a profile")
        };
        let path = &nominal.toolpath;
        let line_of = |i: usize| nominal.move_lines[i];
        // The profile's moves: those of its blocks (for the cycle, the G70's cutting moves
        // after the one that reaches the profile's start).
        let g70_moves: Vec<usize> = (0..path.moves.len()).filter(|&i| form == Form::FinishingCycle && surface_lines.contains(&line_of(i))).collect();
        let is_surface = |i: usize| match form {
            Form::FinishingCycle => g70_moves.iter().skip(1).any(|&k| k == i) && path.moves[i].cutting,
            _ => surface_lines.contains(&line_of(i)),
        };
        prop_assert!(!points.is_empty(), "no point on\n{text}");
        for p in &points {
            let at = Xz::new(p.x_mm, p.z_mm);
            let on_surface = (0..path.moves.len()).filter(|&i| is_surface(i)).any(|i| distance_to(path, i, at) <= ON);
            prop_assert!(on_surface, "x {} z {} (line {}) is on no move of the profile\n{text}", p.x_mm, p.z_mm, p.line);
            for i in (0..path.moves.len()).filter(|&i| !is_surface(i)) {
                let d = distance_to(path, i, at);
                prop_assert!(
                    d > ON,
                    "x {} z {} lies on move {i} (line {}, {:?}), which is no part of the finished surface\n{text}",
                    p.x_mm, p.z_mm, line_of(i), path.moves[i].motion
                );
            }
        }
    }
}
