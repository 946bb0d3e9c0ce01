//! Properties of the Fanuc multi-pass cycles `G73`-`G76`, checked on the toolpath of
//! generated programs (lowered the way `simulate` lowers them, on a metric machine with
//! calculator decimal input): what every pass must satisfy whatever the parameters.

use proptest::prelude::*;
use turnpass::machine::ModelFile;
use turnpass::semantic::{self, LowerOptions, Machine};
use turnpass::syntax::parse;
use turnpass::toolpath::{Motion, Move, Toolpath, Xz};

use crate::simulate::parse_options;

const MACHINE: &str = r#"
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
    let parsed = parse(program.as_bytes(), &parse_options(&settings));
    assert_eq!(parsed.error_count(), 0, "{program}\n{:?}", parsed.diagnostics);
    let machine = Machine::from_settings(&settings);
    let lowered = semantic::lower(&parsed.program, &machine, &LowerOptions::new(false));
    let errors: Vec<String> = lowered.diagnostics.iter().filter(|d| d.is_error()).map(|d| d.to_string()).collect();
    assert!(errors.is_empty(), "{program}\n{errors:?}");
    lowered.toolpath
}

/// The moves after the first one (the rapid to the cycle's start point A).
fn cycle_moves(toolpath: &Toolpath) -> &[Move] {
    toolpath.moves.get(1..).unwrap_or(&[])
}

fn close(a: Xz, b: Xz) -> bool {
    (a.x - b.x).abs() <= TOLERANCE && (a.z - b.z).abs() <= TOLERANCE
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
