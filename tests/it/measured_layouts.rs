//! Measurements as instruments and CMM software write them: `tests/cases/measured/*.toml`.
//! Each case names a file (a layout of a ball bar trace, a CMM profile or an interferometer
//! table) and, when it must read, its canonical twin: the same readings in turnpass's own
//! layout (or `twin_lines` of it). The file must read to the twin's points (each value within
//! a nanometre or a nanoradian, angles within 1e-9 degree); the snapshot says what it read,
//! or the diagnostic of a file that must be refused (a case with no twin).

use std::path::Path;

use serde::Deserialize;

use turnpass::diagnose::measured::{self, Axis, KindName, Measured};
use turnpass::diagnostic::render::{RenderSource, render_plain};
use turnpass::diagnostic::{Diagnostic, DiagnosticKind};
use turnpass::error_model::interferometer::Profile;

use crate::support::{case_files, repo, with_snapshots};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Case {
    file: String,
    #[serde(default)]
    twin: Option<String>,
    /// The lines of the twin (header first, 1-based, inclusive) the file holds.
    #[serde(default)]
    twin_lines: Option<[usize; 2]>,
    #[serde(default)]
    kind: Option<String>,
    #[serde(default)]
    axis: Option<String>,
}

fn kind_of(case: &Case) -> (Option<KindName>, Option<Axis>) {
    let kind = case.kind.as_deref().map(|k| match k {
        "ballbar" => KindName::BallBar,
        "profile" => KindName::Profile,
        "table" => KindName::Table,
        other => panic!("unknown kind {other}"),
    });
    let axis = case.axis.as_deref().map(|a| if a == "x" { Axis::X } else { Axis::Z });
    (kind, axis)
}

/// The twin's text: its header and comments, then the lines asked for.
fn twin_text(case: &Case) -> String {
    let text = std::fs::read_to_string(repo().join(case.twin.as_deref().unwrap())).unwrap();
    match case.twin_lines {
        None => text,
        Some([first, last]) => {
            let lines: Vec<&str> = text.lines().collect();
            let mut out = lines[0].to_string() + "\n";
            for line in &lines[first - 1..last] {
                out.push_str(line);
                out.push('\n');
            }
            out
        }
    }
}

const LENGTH: f64 = 1e-9;

fn same_profile(what: &str, got: &Profile, want: &Profile) {
    assert_eq!(got.targets.len(), want.targets.len(), "{what}: targets");
    let pairs: [(&str, &Vec<f64>, &Vec<f64>); 5] = [
        ("targets", &got.targets, &want.targets),
        ("up", &got.up, &want.up),
        ("down", &got.down, &want.down),
        ("up_sigma", &got.up_sigma, &want.up_sigma),
        ("down_sigma", &got.down_sigma, &want.down_sigma),
    ];
    for (name, a, b) in pairs {
        for (i, (a, b)) in a.iter().zip(b.iter()).enumerate() {
            assert!((a - b).abs() <= LENGTH, "{what}: {name}[{i}] {a} against {b}");
        }
    }
    assert_eq!((&got.up_runs, &got.down_runs), (&want.up_runs, &want.down_runs), "{what}: runs");
}

/// The file's reading against its twin's, point by point.
fn same_points(name: &str, got: &Measured, want: &Measured) {
    assert_eq!(got.kind(), want.kind(), "{name}: kind");
    match (got, want) {
        (Measured::BallBar(a), Measured::BallBar(b)) => {
            assert_eq!(a.len(), b.len(), "{name}: rows");
            for (k, (a, b)) in a.iter().zip(b).enumerate() {
                let turn = (a.angle_deg - b.angle_deg).rem_euclid(360.0);
                assert!(
                    turn.min(360.0 - turn) <= 1e-9,
                    "{name}: row {k} angle {} against {}",
                    a.angle_deg,
                    b.angle_deg
                );
                assert!((a.deviation_mm - b.deviation_mm).abs() <= LENGTH, "{name}: row {k} deviation");
                assert_eq!(a.direction, b.direction, "{name}: row {k} direction");
            }
        }
        (Measured::Profile(a), Measured::Profile(b)) => {
            assert_eq!(a.len(), b.len(), "{name}: points");
            for (k, (a, b)) in a.iter().zip(b).enumerate() {
                assert!((a.x_mm - b.x_mm).abs() <= LENGTH, "{name}: point {k} x {} against {}", a.x_mm, b.x_mm);
                assert!((a.z_mm - b.z_mm).abs() <= LENGTH, "{name}: point {k} z {} against {}", a.z_mm, b.z_mm);
                assert_eq!((&a.part, a.start_min), (&b.part, b.start_min), "{name}: point {k} part");
            }
        }
        (Measured::Table { axis: a, table: ta }, Measured::Table { axis: b, table: tb }) => {
            assert_eq!(a, b, "{name}: slide");
            for (what, p, q) in
                [("linear", &ta.linear, &tb.linear), ("straightness", &ta.straightness, &tb.straightness)]
            {
                match (p, q) {
                    (Some(p), Some(q)) => same_profile(&format!("{name}: {what}"), p, q),
                    (None, None) => {}
                    _ => panic!("{name}: {what} in one and not the other"),
                }
            }
        }
        _ => unreachable!(),
    }
}

/// What a file read to, for the snapshot: its kind, its size and its first points.
fn summary(case: &Case, measured: &Measured) -> String {
    let twin = match (&case.twin, case.twin_lines) {
        (Some(twin), Some([a, b])) => format!("{twin}, lines {a}-{b}"),
        (Some(twin), None) => twin.clone(),
        (None, _) => String::new(),
    };
    let mut out = format!("{}\nreads the same points as {twin}\n", case.file);
    match measured {
        Measured::BallBar(rows) => {
            out.push_str(&format!("ball bar trace, {} rows; the first three:\n", rows.len()));
            for r in rows.iter().take(3) {
                out.push_str(&format!(
                    "  line {}: {:.4} deg, {:.7} mm, {}\n",
                    r.line,
                    r.angle_deg,
                    r.deviation_mm,
                    r.direction.name()
                ));
            }
        }
        Measured::Profile(points) => {
            out.push_str(&format!("CMM profile, {} points (x a radius); the first three:\n", points.len()));
            for p in points.iter().take(3) {
                out.push_str(&format!("  line {}: x {:.7} z {:.7}\n", p.line, p.x_mm, p.z_mm));
            }
        }
        Measured::Table { axis, table } => {
            out.push_str(&format!("interferometer table of the {} slide, {} rows\n", axis.letter(), table.rows));
            if let Some(p) = &table.linear {
                for (i, t) in p.targets.iter().enumerate() {
                    out.push_str(&format!(
                        "  {t:>8.3} mm: up {:+.5} mm ({} runs), down {:+.5} mm ({} runs)\n",
                        p.up[i], p.up_runs[i], p.down[i], p.down_runs[i]
                    ));
                }
            }
        }
    }
    out
}

fn run(path: &Path) -> String {
    let case: Case = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let text = std::fs::read_to_string(repo().join(&case.file)).unwrap();
    let (kind, axis) = kind_of(&case);
    let result = measured::read_as(&text, kind, axis);
    match (&case.twin, result) {
        (Some(_), Ok(measured)) => {
            let twin = measured::read_as(
                &twin_text(&case),
                kind,
                axis.or(match &measured {
                    Measured::Table { axis, .. } => Some(*axis),
                    _ => None,
                }),
            )
            .unwrap();
            same_points(&case.file, &measured, &twin);
            summary(&case, &measured)
        }
        (Some(_), Err(error)) => panic!("{}: {error}", case.file),
        (None, Ok(_)) => panic!("{}: read, and it must be refused", case.file),
        (None, Err(error)) => {
            // The error's span lies in the file, forward, and on the line it names.
            let (start, end) = (error.span.start as usize, error.span.end as usize);
            assert!(start <= end && end <= text.len(), "{}: span {start}..{end}", case.file);
            let line = text.as_bytes()[..start].iter().filter(|&&b| b == b'\n').count() + 1;
            assert_eq!(
                line, error.line,
                "{}: the span starts on line {line}, the error names {}",
                case.file, error.line
            );
            let kind = DiagnosticKind::DataInvalid { message: error.message, label: error.label, hint: error.hint };
            render_plain(&RenderSource::new(&case.file, text.as_bytes()), &[Diagnostic::error(kind, error.span)])
        }
    }
}

#[test]
fn instrument_layouts_read_as_their_canonical_twins() {
    let cases = case_files(&repo().join("tests/cases/measured"), "toml");
    assert!(cases.len() >= 12, "{} cases", cases.len());
    with_snapshots("measured", || {
        for path in cases {
            let name = path.file_stem().unwrap().to_string_lossy().into_owned();
            insta::assert_snapshot!(name, run(&path));
        }
    });
}
