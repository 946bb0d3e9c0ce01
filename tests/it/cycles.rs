//! Properties of the Fanuc multi-pass cycles `G73`-`G76`, checked on the toolpath of
//! generated programs (lowered the way `simulate` lowers them, on a metric machine with
//! calculator decimal input): what every pass must satisfy whatever the parameters.

use proptest::prelude::*;
use turnpass::machine::ModelFile;
use turnpass::pipeline::Settings;
use turnpass::semantic::LowerOptions;
use turnpass::toolpath::{Motion, Move, Toolpath, Xz};

use crate::simulate::parse_options;
use crate::support::ready;

pub const MACHINE: &str = r#"
[machine]
dialect = "fanuc"
units = "mm"
decimal_input = "calculator"
home = { x = 400.0, z = 200.0 }
"#;

const TOLERANCE: f64 = 1e-6;

/// The toolpath of `program`, which must lower without errors.
fn lower(program: &str) -> Toolpath {
    let settings = ModelFile::from_toml(MACHINE).unwrap().machine;
    let settings = Settings::new(parse_options(&settings), &settings, LowerOptions::new(false));
    ready(program.as_bytes(), &settings).lowered.into_inner().toolpath
}

/// The moves after the first one (the rapid to the cycle's start point A).
fn cycle_moves(toolpath: &Toolpath) -> &[Move] {
    toolpath.moves.get(1..).unwrap_or(&[])
}

fn close(a: Xz, b: Xz) -> bool {
    (a.x - b.x).abs() <= TOLERANCE && (a.z - b.z).abs() <= TOLERANCE
}

/// `G76` parameters in the control's units: micrometres for the `P`/`Q` words.
#[derive(Debug, Clone)]
struct Threading {
    height_um: u32,
    first_um: u32,
    min_um: u32,
    allowance_um: u32,
    finishing: u32,
    angle: u32,
    lead_centi: u32,
    root_diameter: u32,
    end_z: u32,
}

fn threading() -> impl Strategy<Value = Threading> {
    (200u32..3000, 0.02f64..1.0, 0u32..150, 0.0f64..0.5, 1u32..4, 0usize..6, 50u32..300, 10u32..60, 5u32..50).prop_map(
        |(height_um, share, min_um, allowance_share, finishing, angle, lead_centi, root_diameter, end_z)| Threading {
            height_um,
            first_um: ((f64::from(height_um) * share) as u32).max(30),
            min_um,
            allowance_um: (f64::from(height_um) * allowance_share) as u32,
            finishing,
            angle: [0, 29, 30, 55, 60, 80][angle],
            lead_centi,
            root_diameter,
            end_z,
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    /// `G76`: the roughing depths increase strictly, never pass the height, start at the
    /// first depth (or the minimum, if larger), follow at least Δd·√n, step at least Δdmin
    /// until the last one lands on k − d; then m passes at k, the last ending at the root.
    #[test]
    fn g76_depths_climb_to_the_thread_height(t in threading()) {
        let height = f64::from(t.height_um) / 1000.0;
        let first = f64::from(t.first_um) / 1000.0;
        let min = f64::from(t.min_um) / 1000.0;
        let allowance = f64::from(t.allowance_um) / 1000.0;
        let root = f64::from(t.root_diameter) / 2.0;
        let start = Xz::new(root + height + 2.0, 3.0);
        let program = format!(
            "G21 G99\nG97 S500 M03\nG00 X{:.3} Z3.\nG76 P{:02}00{:02} Q{} R{:.3}\nG76 X{}. Z-{}. P{} Q{} F{:.2}\nM30\n",
            2.0 * start.x, t.finishing, t.angle, t.min_um, allowance, t.root_diameter, t.end_z, t.height_um,
            t.first_um, f64::from(t.lead_centi) / 100.0
        );
        let toolpath = lower(&program);
        let moves = cycle_moves(&toolpath);
        let threads: Vec<(Xz, &Move)> = moves
            .iter()
            .enumerate()
            .filter(|(_, m)| m.threading)
            .map(|(i, m)| (toolpath.start_of(i + 1), m))
            .collect();
        prop_assert!(threads.len() > t.finishing as usize);
        let flank = (f64::from(t.angle).to_radians() / 2.0).tan();
        let mut depths = Vec::new();
        for (from, m) in &threads {
            let depth = height - (m.end.x - root);
            // Straight thread: the pass stays at its depth; flank infeed shifts it toward A.
            prop_assert!((from.x - m.end.x).abs() <= TOLERANCE);
            prop_assert!((from.z - (3.0 + (height - depth) * flank)).abs() <= TOLERANCE, "{from:?} at {depth}");
            prop_assert!(depth <= height + TOLERANCE);
            depths.push(depth);
        }
        let (rough, finish) = depths.split_at(depths.len() - t.finishing as usize);
        prop_assert!(finish.iter().all(|d| (d - height).abs() <= TOLERANCE), "{finish:?}");
        let last = threads[threads.len() - 1].1;
        prop_assert!(close(last.end, Xz::new(root, -f64::from(t.end_z))));
        let limit = height - allowance;
        prop_assert!(!rough.is_empty());
        prop_assert!((rough[rough.len() - 1] - limit).abs() <= TOLERANCE, "{rough:?} to {limit}");
        prop_assert!((rough[0] - first.max(min).min(limit)).abs() <= TOLERANCE, "{rough:?}");
        for (n, pair) in rough.windows(2).enumerate() {
            prop_assert!(pair[1] > pair[0] + TOLERANCE, "{rough:?}");
            let is_last = n + 2 == rough.len();
            if !is_last {
                prop_assert!(pair[1] - pair[0] >= min - TOLERANCE, "{rough:?} min {min}");
                prop_assert!(pair[1] >= first * ((n + 2) as f64).sqrt() - TOLERANCE, "{rough:?}");
            }
        }
        // The first finishing pass removes exactly the allowance.
        prop_assert!((finish[0] - rough[rough.len() - 1] - allowance).abs() <= TOLERANCE);
    }
}

/// `G73` parameters: a profile of points (diameter, Z) with Z falling, relief, allowance.
#[derive(Debug, Clone)]
struct Pattern {
    points: Vec<(f64, f64)>,
    relief: (f64, f64),
    allowance: (f64, f64),
    divisions: u32,
}

fn pattern() -> impl Strategy<Value = Pattern> {
    (
        prop::collection::vec((10u32..60, 1u32..10), 2..6),
        (-5000i32..5000, -2000i32..2000),
        (-1000i32..1000, -500i32..500),
        1u32..7,
    )
        .prop_map(|(raw, relief, allowance, divisions)| {
            let mut z = 2.0;
            let points = raw
                .into_iter()
                .map(|(x, dz)| {
                    let point = (f64::from(x), z);
                    z -= f64::from(dz);
                    point
                })
                .collect();
            let milli = |v: i32| f64::from(v) / 1000.0;
            Pattern {
                points,
                relief: (milli(relief.0), milli(relief.1)),
                allowance: (milli(allowance.0), milli(allowance.1)),
                divisions,
            }
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    /// `G73`: pass k runs through every profile point shifted by the allowance plus the
    /// relief scaled by (d − k)/(d − 1), returns to A, and the last pass lies exactly on the
    /// profile plus the allowance.
    #[test]
    fn g73_passes_close_in_on_the_profile_plus_allowance(p in pattern()) {
        let start = Xz::new(50.0, 10.0);
        // A modal F before the cycle: reading a profile with no F of its own reports a
        // missing feed when the program has none yet (src/semantic/profile.rs:125).
        let mut program = format!(
            "G21 G99\nG97 S500 M03 F0.1\nG00 X100. Z10.\nG73 U{:.3} W{:.3} R{}\nG73 P10 Q20 U{:.3} W{:.3} F0.2\n",
            p.relief.0, p.relief.1, p.divisions, p.allowance.0, p.allowance.1
        );
        let last = p.points.len() - 1;
        for (i, (x, z)) in p.points.iter().enumerate() {
            let line = match i {
                0 => format!("N10 G00 X{x:.3} Z{z:.3}\n"),
                _ if i == last => format!("N20 G01 X{x:.3} Z{z:.3}\n"),
                _ => format!("G01 X{x:.3} Z{z:.3}\n"),
            };
            program.push_str(&line);
        }
        program.push_str("M30\n");
        let toolpath = lower(&program);
        let moves = cycle_moves(&toolpath);
        let allowance = Xz::new(p.allowance.0 / 2.0, p.allowance.1);
        let d = p.divisions;
        let mut i = 0;
        for k in 1..=d {
            let fraction = if d == 1 { 0.0 } else { f64::from(d - k) / f64::from(d - 1) };
            let offset = Xz::new(allowance.x + p.relief.0 * fraction, allowance.z + p.relief.1 * fraction);
            if k == d {
                prop_assert!(close(offset, allowance));
            }
            for (j, (x, z)) in p.points.iter().enumerate() {
                let m = &moves[i];
                let want = Xz::new(x / 2.0 + offset.x, z + offset.z);
                prop_assert!(close(m.end, want), "pass {k} point {j}: {:?} vs {want:?}", m.end);
                prop_assert_eq!(m.motion, if j == 0 { Motion::Rapid } else { Motion::Feed });
                i += 1;
            }
            // Back to A at rapid.
            while !close(moves[i].end, start) {
                prop_assert_eq!(moves[i].motion, Motion::Rapid);
                i += 1;
            }
            prop_assert_eq!(moves[i].motion, Motion::Rapid);
            i += 1;
        }
        prop_assert_eq!(i, moves.len());
    }
}

/// `G74`/`G75` parameters: start and end in diameter/Z mm, peck and step in micrometres.
#[derive(Debug, Clone)]
struct Groove {
    face: bool,
    start: (f64, f64),
    end: (f64, f64),
    peck_um: u32,
    step_um: u32,
    retract: f64,
    relief: f64,
}

fn groove() -> impl Strategy<Value = Groove> {
    (
        any::<bool>(),
        40u32..80,
        1u32..30,
        -20i32..20,
        -10i32..-2,
        0u32..12,
        300u32..5000,
        300u32..5000,
        0u32..1000,
        0u32..500,
    )
        .prop_map(|(face, x, depth_or_width, across, z, along, peck_um, step_um, retract, relief)| {
            let (x, z) = (f64::from(x), f64::from(z));
            // G75 pecks down in X and steps along Z; G74 pecks down in Z and steps across X.
            let end = if face {
                (x + 2.0 * f64::from(across), z - f64::from(depth_or_width))
            } else {
                (x - 2.0 * f64::from(depth_or_width.min(15)), z - f64::from(along))
            };
            Groove {
                face,
                start: (x, z),
                end,
                peck_um,
                step_um,
                retract: f64::from(retract) / 1000.0,
                relief: f64::from(relief) / 1000.0,
            }
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    /// `G74`/`G75`: no move goes past the end point (in depth, or in the stepping direction)
    /// or behind the start by more than the relief; the plunges reach the bottom from the
    /// start's step position to the end's, never further apart than the step; no feed is
    /// longer than a peck plus the retract; the cycle ends at A.
    #[test]
    fn g74_g75_stay_inside_and_cover_the_groove(g in groove()) {
        let code = if g.face { "G74" } else { "G75" };
        let (peck_word, step_word) = if g.face { ("Q", "P") } else { ("P", "Q") };
        let program = format!(
            "G21 G99\nG97 S500 M03\nG00 X{:.3} Z{:.3}\n{code} R{:.3}\n\
             {code} X{:.3} Z{:.3} {peck_word}{} {step_word}{} R{:.3} F0.1\nM30\n",
            g.start.0, g.start.1, g.retract, g.end.0, g.end.1, g.peck_um, g.step_um, g.relief
        );
        let toolpath = lower(&program);
        let moves = cycle_moves(&toolpath);
        // (depth, step) of a point: the depth axis is Z on the face, X on a diameter.
        let split = |p: Xz| if g.face { (p.z, p.x) } else { (p.x, p.z) };
        let start = split(Xz::new(g.start.0 / 2.0, g.start.1));
        let end = split(Xz::new(g.end.0 / 2.0, g.end.1));
        let (peck, step) = (f64::from(g.peck_um) / 1000.0, f64::from(g.step_um) / 1000.0);
        let down = (end.0 - start.0).signum();
        let across = if (end.1 - start.1).abs() > TOLERANCE { (end.1 - start.1).signum() } else { 0.0 };
        let mut bottoms = Vec::new();
        for (i, m) in moves.iter().enumerate() {
            let (depth, at) = split(m.end);
            // Depth: between the start level and the bottom.
            prop_assert!((depth - start.0) * down >= -TOLERANCE && (end.0 - depth) * down >= -TOLERANCE, "{m:?}");
            if across != 0.0 {
                prop_assert!((end.1 - at) * across >= -TOLERANCE, "past the end: {m:?}");
                prop_assert!((at - start.1) * across >= -g.relief - TOLERANCE, "behind the start: {m:?}");
            }
            if m.motion == Motion::Feed {
                let from = toolpath.start_of(i + 1);
                prop_assert!(from.distance(m.end) <= peck + g.retract + TOLERANCE);
                if (depth - end.0).abs() <= TOLERANCE {
                    bottoms.push(at);
                }
            }
        }
        prop_assert!(close(moves[moves.len() - 1].end, Xz::new(g.start.0 / 2.0, g.start.1)));
        prop_assert!((bottoms[0] - start.1).abs() <= TOLERANCE);
        prop_assert!((bottoms[bottoms.len() - 1] - end.1).abs() <= TOLERANCE);
        for pair in bottoms.windows(2) {
            prop_assert!((pair[1] - pair[0]).abs() <= step + TOLERANCE, "{bottoms:?}");
            prop_assert!((pair[1] - pair[0]) * across > 0.0, "{bottoms:?}");
        }
    }
}
