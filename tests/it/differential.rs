//! Differential test against LinuxCNC's stand-alone interpreter `rs274` (Debian package
//! `linuxcnc-uspace`), on the subset both understand: G00–G03, U/W incremental words,
//! R and I/K arcs, inch and metric. It runs when `rs274` is on the PATH; without it the
//! test is skipped with a banner, and fails under CI, which installs it
//! (`support::external`).
//!
//! Each case under `tests/cases/differential/` is a Fanuc-form program. It is translated
//! word by word into LinuxCNC's form — `G18 G7` (XZ plane, diameter mode), `U` becomes
//! `X[#<_x>*2+u]` and `W` becomes `Z[#<_z>+w]`, so rs274 itself does the incremental
//! arithmetic — and rs274's canonical `STRAIGHT_TRAVERSE`/`STRAIGHT_FEED`/`ARC_FEED` calls
//! are compared with turnpass's moves: same kind, same end point and arc centre within
//! 0.0001 mm.
//!
//! G70/G71 are left out: the rs274 of Debian 12 (2.9.0~pre1) reads `G71 Q<sub> D<depth>`
//! with another pass rule. For the profile of `tests/cases/simulate/fanuc/g71-type1-outside.nc`
//! (`G0 X20`, `G1 Z-20`, `X40 Z-30`, `Z-50`, `X60`, from X60 Z2, `D2`) it steps 1 mm in
//! radius, ends the full-length passes at Z-48 instead of Z-50, and its `G70 Q1` starts
//! with a rapid to X20 Z-48; there is no common meaning to compare.

use std::fmt::Write as _;
use std::path::Path;
use std::process::Command;

use turnpass::dialect::{Address, DialectChoice, GCodeSystem};
use turnpass::machine::MachineSettings;
use turnpass::pipeline::{Ready, Settings};
use turnpass::semantic::LowerOptions;
use turnpass::syntax::{CodeLetter, ParseOptions, Program, WordKind};
use turnpass::toolpath::Motion;

use crate::support::{external, ready, repo};

#[derive(Debug, Clone, Copy, PartialEq)]
struct Point {
    motion: Motion,
    x: f64,
    z: f64,
    centre: Option<(f64, f64)>,
}

/// The case in LinuxCNC's form.
fn translate(program: &Program<'_>) -> String {
    let mut out = String::from("G18 G7 G90\n");
    for block in program.blocks() {
        let mut line = String::new();
        for word in program.words_of(block) {
            let text = String::from_utf8_lossy(program.text(word.span)).into_owned();
            let value = text.get(1..).unwrap_or("");
            match word.kind {
                WordKind::Code { letter: CodeLetter::G, code } => match code.0 / 10 {
                    0..=3 | 20 | 21 => line.push_str(&format!("G{} ", code.0 / 10)),
                    98 => line.push_str("G94 "),
                    99 => line.push_str("G95 "),
                    _ => {}
                },
                WordKind::Code { letter: CodeLetter::M, code } => match code.0 / 10 {
                    2 | 30 => line.push_str("M2 "),
                    3..=5 => line.push_str(&format!("M{} ", code.0 / 10)),
                    _ => {}
                },
                WordKind::Number { address, .. } => match address {
                    Address::X | Address::Z | Address::R | Address::I | Address::K | Address::F | Address::S => {
                        line.push_str(&text);
                        line.push(' ');
                    }
                    Address::U => line.push_str(&format!("X[#<_x>*2+[{value}]] ")),
                    Address::W => line.push_str(&format!("Z[#<_z>+[{value}]] ")),
                    _ => {}
                },
                _ => {}
            }
        }
        if !line.is_empty() {
            out.push_str(line.trim_end());
            out.push('\n');
        }
    }
    out
}

/// rs274's motion calls, in mm and radius.
fn rs274_points(rs274: &Path, ngc: &str, name: &str) -> Vec<Point> {
    let dir = std::env::temp_dir().join(format!("turnpass-differential-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{name}.ngc"));
    std::fs::write(&path, ngc).unwrap();
    let output = Command::new(rs274).arg("-g").arg(&path).output().unwrap();
    let text = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(!text.contains("rror"), "rs274 rejected {name}:\n{text}\n{ngc}");
    let mut scale = 1.0;
    let mut points = Vec::new();
    for line in text.lines() {
        let Some((_, call)) = line.split_once("N..... ") else { continue };
        let (head, rest) = call.split_once('(').unwrap_or((call, ""));
        let args: Vec<f64> = rest.trim_end_matches(')').split(',').filter_map(|a| a.trim().parse().ok()).collect();
        match head {
            "USE_LENGTH_UNITS" => scale = if rest.contains("INCHES") { 25.4 } else { 1.0 },
            "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" => points.push(Point {
                motion: if head == "STRAIGHT_TRAVERSE" { Motion::Rapid } else { Motion::Feed },
                x: args[0] * scale,
                z: args[2] * scale,
                centre: None,
            }),
            // XZ plane: first axis Z, second X; rotation +1 counter-clockwise (G03).
            "ARC_FEED" => points.push(Point {
                motion: if args[4] > 0.0 { Motion::Ccw } else { Motion::Cw },
                x: args[1] * scale,
                z: args[0] * scale,
                centre: Some((args[3] * scale, args[2] * scale)),
            }),
            _ => {}
        }
    }
    std::fs::remove_file(&path).ok();
    points
}

fn turnpass_points(ready: &Ready<'_>) -> Vec<Point> {
    let lowered = &ready.lowered;
    let mut points = Vec::new();
    if !lowered.toolpath.moves.is_empty() {
        // The first move of a program with no home is where the tool arrives, as rs274's
        // first traverse from its origin is; both are compared from the first end point.
        points.push(Point {
            motion: Motion::Rapid,
            x: lowered.toolpath.start.x,
            z: lowered.toolpath.start.z,
            centre: None,
        });
    }
    for m in &lowered.toolpath.moves {
        points.push(Point {
            motion: m.motion,
            x: m.end.x,
            z: m.end.z,
            centre: m.is_arc().then_some((m.centre.x, m.centre.z)),
        });
    }
    points
}

fn same(a: &Point, b: &Point) -> bool {
    let close = |p: f64, q: f64| (p - q).abs() < 1e-4;
    a.motion == b.motion
        && close(a.x, b.x)
        && close(a.z, b.z)
        && match (a.centre, b.centre) {
            (Some(c), Some(d)) => close(c.0, d.0) && close(c.1, d.1),
            (None, None) => true,
            _ => false,
        }
}

/// Drop moves that go nowhere: rs274 emits them for blocks that restate the position.
fn moving(points: Vec<Point>) -> Vec<Point> {
    let mut out: Vec<Point> = Vec::new();
    for p in points {
        if let Some(last) = out.last()
            && p.centre.is_none()
            && (p.x - last.x).abs() < 1e-9
            && (p.z - last.z).abs() < 1e-9
        {
            continue;
        }
        out.push(p);
    }
    out
}

#[test]
fn agrees_with_linuxcnc_rs274() {
    let Some(rs274) = external::program("rs274", "linuxcnc-uspace") else { return };
    let dir = repo().join("tests/cases/differential");
    let mut cases: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    cases.sort();
    let mut report = String::new();
    for path in cases.iter().filter(|p| p.extension().is_some_and(|e| e == "nc")) {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let source = std::fs::read(path).unwrap();
        let options = ParseOptions {
            dialect: DialectChoice::Fixed(turnpass::dialect::Dialect::Fanuc),
            gcode_system: GCodeSystem::A,
            machine_kind: None,
            control: Default::default(),
        };
        let lower = LowerOptions { nose_radius_compensation: false, ..LowerOptions::new(false) };
        let ready = ready(&source, &Settings::new(options, &MachineSettings::default(), lower));
        let theirs = moving(rs274_points(&rs274, &translate(ready.program()), &name));
        let ours = moving(turnpass_points(&ready));
        assert!(ours.len() > 3, "{name}: too few moves to compare");
        assert_eq!(ours.len(), theirs.len(), "{name}: move counts differ\nours   {ours:?}\ntheirs {theirs:?}");
        for (i, (a, b)) in ours.iter().zip(&theirs).enumerate() {
            assert!(same(a, b), "{name}: move {i} differs: ours {a:?}, rs274 {b:?}");
        }
        let _ = writeln!(report, "{name}: {} moves agree", ours.len());
    }
    eprint!("{report}");
}
