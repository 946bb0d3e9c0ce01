//! The LinuxCNC table, checked by LinuxCNC's own motion controller (Debian package
//! `linuxcnc-uspace`, run as a POSIX non-realtime simulator with no display; through
//! `support::external`: skipped by hand without it, a failure under `TURNPASS_CI`).
//!
//! `turnpass table` writes the joint compensation of `tests/cases/control_table/linuxcnc-run/
//! model.toml` (screw scale and cyclic errors on both slides, a Z interferometer table
//! measured both ways, the play of both drives, and a squareness the table cannot carry);
//! its `[JOINT_n]` keys go into the simulator's INI file; LinuxCNC runs `part.ngc` (moves
//! over both axes' travel with reversals, large and small) while `halsampler` records, every
//! servo period (1 ms), each joint's commanded position (`pos-cmd`), the correction the
//! controller computes from the table (`backlash-corr`), the correction after its ramp
//! (`backlash-filt`) and what it sends the drive (`motor-pos-cmd`).
//!
//! Then, sample by sample:
//!
//! 1. the correction LinuxCNC computes from the file equals the one turnpass reads from the
//!    same file (`control_table::read`, the reading `--with-table` uses), at the commanded
//!    position and direction;
//! 2. where the model's machine lands when driven by LinuxCNC's `motor-pos-cmd` equals
//!    where turnpass predicts the machine with the table loaded lands for the commanded
//!    position (`ErrorModel::with_control`, the model `compensate`, `verify` and `report`
//!    run on), outside the moments the controller ramps a reversal's change of correction
//!    in (at half the joint's velocity and acceleration limits, `compute_screw_comp`), which
//!    turnpass takes as instantaneous; those ramps are counted and measured.
//!
//! `cargo test --release --test it linuxcnc -- --nocapture` prints the figures.

use std::path::Path;
use std::process::Command;

use turnpass::control_table::{self, Control};
use turnpass::error_model::model_file::ModelSpec;
use turnpass::error_model::{ErrorModel, Tracker};
use turnpass::machine::Units;
use turnpass::toolpath::Xz;

use crate::support::{external, repo, with_snapshots};

const CASE: &str = "tests/cases/control_table/linuxcnc-run";

/// The INI text with the `[JOINT_n]` keys of `snippet` (what `turnpass table` wrote) put
/// under the same sections of `template`, and its `[TURNPASS]` section appended: the merge
/// the written file asks its reader to make.
fn merged(template: &str, snippet: &str) -> String {
    let mut sections: Vec<(String, Vec<String>)> = Vec::new();
    for line in snippet.lines().map(str::trim) {
        if line.starts_with('[') {
            sections.push((line.to_string(), Vec::new()));
        } else if !line.is_empty()
            && !line.starts_with('#')
            && let Some(last) = sections.last_mut()
        {
            last.1.push(line.to_string());
        }
    }
    let mut out = String::new();
    for line in template.lines() {
        out.push_str(line);
        out.push('\n');
        if let Some((_, keys)) = sections.iter().find(|(name, _)| name == line.trim()) {
            for key in keys {
                out.push_str(key);
                out.push('\n');
            }
        }
    }
    for (name, keys) in sections.iter().filter(|(name, _)| !template.contains(name.as_str())) {
        out.push_str(&format!("\n{name}\n"));
        for key in keys {
            out.push_str(key);
            out.push('\n');
        }
    }
    out
}

/// One servo period's values: per joint, the commanded position, the correction, its ramped
/// value and the drive's command, mm, and the commanded velocity, mm/s.
#[derive(Debug, Clone, Copy)]
struct Period {
    tag: u64,
    command: [f64; 2],
    correction: [f64; 2],
    ramped: [f64; 2],
    drive: [f64; 2],
    velocity: [f64; 2],
}

fn periods(text: &str) -> Vec<Period> {
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|line| {
            let v: Vec<f64> = line.split_whitespace().map(|w| w.parse().unwrap()).collect();
            assert_eq!(v.len(), 11, "a sample line: {line}");
            Period {
                tag: v[0] as u64,
                drive: [v[1], v[5]],
                command: [v[2], v[6]],
                correction: [v[3], v[7]],
                ramped: [v[4], v[8]],
                velocity: [v[9], v[10]],
            }
        })
        .collect()
}

#[test]
fn linuxcnc_runs_the_table_turnpass_writes_as_turnpass_predicts() {
    let Some(linuxcnc) = external::program("linuxcnc", "linuxcnc-uspace") else { return };
    let Some(_) = external::program("halsampler", "linuxcnc-uspace") else { return };
    let case = repo().join(CASE);
    let dir = tempfile::tempdir().unwrap();
    for file in ["model.toml", "part.ngc", "core.hal", "tool.tbl", "ui.py"] {
        std::fs::copy(case.join(file), dir.path().join(file)).unwrap();
    }
    make_executable(&dir.path().join("ui.py"));
    let table = Command::new(env!("CARGO_BIN_EXE_turnpass"))
        .args(["table", "model.toml", "--control", "linuxcnc", "-o", "comp.ini"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(table.status.success(), "turnpass table: {}", String::from_utf8_lossy(&table.stderr));
    let snippet = std::fs::read_to_string(dir.path().join("comp.ini")).unwrap();
    let template = std::fs::read_to_string(case.join("lathe.ini")).unwrap();
    std::fs::write(dir.path().join("lathe.ini"), merged(&template, &snippet)).unwrap();

    // LinuxCNC's user-space realtime refuses to run as root without a user to fall back to,
    // and that user must be able to make its FIFO.
    let fifo = dir.path().join("fifo");
    std::fs::create_dir(&fifo).unwrap();
    let mut command = Command::new("timeout");
    command.arg("300").arg(&linuxcnc).args(["-r", "lathe.ini"]).current_dir(dir.path());
    command.env("RTAPI_FIFO_PATH", fifo.join("rtapi_fifo"));
    if is_root() {
        open_to_all(dir.path());
        open_to_all(&fifo);
        command.env("RTAPI_UID", "65534");
    }
    let run = command.output().unwrap();
    let log = String::from_utf8_lossy(&run.stdout).into_owned() + &String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "LinuxCNC did not run the program:\n{log}");
    assert!(!log.contains("compensation"), "LinuxCNC complained about the compensation file:\n{log}");
    let periods = periods(&std::fs::read_to_string(dir.path().join("samples.txt")).unwrap());
    assert!(periods.len() > 5_000, "{} samples", periods.len());
    assert!(periods.windows(2).all(|w| w[1].tag == w[0].tag + 1), "halsampler lost samples");

    // turnpass's reading of the same files.
    let read = |name: &str| std::fs::read_to_string(dir.path().join(name)).map_err(|e| e.to_string());
    let loaded = control_table::read(Some(Control::Linuxcnc), &snippet, read, Units::Mm, Xz::new(0.0, 0.0)).unwrap();
    let spec = ModelSpec::read(&std::fs::read_to_string(case.join("model.toml")).unwrap()).unwrap();
    let machine: ErrorModel = spec.build(|_| Err("no table files".to_string())).unwrap();
    let with_table = machine.with_control(loaded.compensation.clone());

    // 1. The correction, and the ramps. LinuxCNC picks the forward or reverse column by the
    // sign of the commanded velocity and keeps the correction while it is nought; turnpass's
    // model, by the direction the commanded position last moved in. The two differ for a few
    // periods where the controller's cubic interpolation brings a joint to a stop (its
    // velocity changes sign while the position rests within a nanometre): counted apart.
    let mut direction = [0i8; 2];
    let mut moved = [0i8; 2];
    let mut worst_correction: f64 = 0.0;
    let mut compared = 0usize;
    let mut ramping = vec![false; periods.len()];
    let mut disagree = vec![false; periods.len()];
    let mut worst_ramp: f64 = 0.0;
    for (k, period) in periods.iter().enumerate() {
        for joint in 0..2 {
            let velocity = period.velocity[joint];
            if velocity > 0.0 {
                direction[joint] = 1;
            } else if velocity < 0.0 {
                direction[joint] = -1;
            }
            if k > 0 {
                let step = period.command[joint] - periods[k - 1].command[joint];
                if step > 0.0 {
                    moved[joint] = 1;
                } else if step < 0.0 {
                    moved[joint] = -1;
                }
            }
            if (period.ramped[joint] - period.correction[joint]).abs() > 1e-9 {
                ramping[k] = true;
                worst_ramp = worst_ramp.max((period.ramped[joint] - period.correction[joint]).abs());
            }
            if direction[joint] == 0 {
                continue;
            }
            disagree[k] |= moved[joint] != direction[joint];
            let axis = if joint == 0 { &loaded.compensation.x } else { &loaded.compensation.z };
            let ours = axis.as_ref().unwrap().total(period.command[joint], direction[joint]);
            worst_correction = worst_correction.max((ours - period.correction[joint]).abs());
            compared += 1;
        }
    }
    let ramps: Vec<usize> = runs(&ramping);

    // 2. Where the machine lands: driven by LinuxCNC's drive commands, and as turnpass
    // predicts for the commanded positions on the machine with the table loaded. Both start
    // once both joints have moved (before, LinuxCNC's correction is nought, and the model's
    // machine starts as after a reference return).
    let Some(start) = periods.iter().position(|p| p.correction[0] != 0.0 && p.correction[1] != 0.0) else {
        panic!("the joints never moved")
    };
    let drive = |p: &Period| Xz::new(p.drive[0], p.drive[1]);
    let command = |p: &Period| Xz::new(p.command[0], p.command[1]);
    let mut real = Tracker::new(drive(&periods[start]), machine.play());
    let mut predicted = Tracker::new(command(&periods[start]), with_table.play());
    let (mut worst_outside, mut worst_inside, mut worst_left): (f64, f64, f64) = (0.0, 0.0, 0.0);
    let (mut outside, mut inside) = (0usize, 0usize);
    let at_rest = |tracker: &Tracker| tracker.sample(0.0, Xz::new(0.0, 0.0), 0, Xz::new(0.0, 0.0), Xz::new(0.0, 0.0));
    // Two seconds on: the model's machine has been pushed through its play in both axes.
    let settled = start + 2_000;
    for (k, period) in periods.iter().enumerate().skip(start) {
        real.advance(drive(period), 0, false);
        predicted.advance(command(period), 0, false);
        if k < settled {
            continue;
        }
        let lands = machine.actual(&at_rest(&real));
        let expected = with_table.actual(&at_rest(&predicted));
        let gap = lands.distance(expected);
        worst_left = worst_left.max(expected.distance(command(period)));
        if ramping[k] || disagree[k] {
            worst_inside = worst_inside.max(gap);
            inside += 1;
        } else {
            worst_outside = worst_outside.max(gap);
            outside += 1;
        }
    }
    let longest_ms = ramps.iter().max().copied().unwrap_or(0);
    let stops = runs(&disagree);
    eprintln!(
        "LinuxCNC round trip: {} servo periods (1 ms) of part.ngc sampled\n\
         1. correction: LinuxCNC's from the file vs turnpass's reading of it, {compared} joint samples: \
         largest difference {:.2e} mm\n\
         2. landing of the model's machine, LinuxCNC's drive commands vs turnpass's prediction with the table \
         loaded: largest difference {:.4} µm over {outside} periods outside the ramps; {} ramps of a reversal's \
         correction (longest {longest_ms} ms, largest ramp gap {:.2} µm) and {} stops where the commanded \
         velocity's sign is not the last step's ({} periods in all), {:.2} µm at most inside them \
         ({inside} periods); what the table leaves there (squareness, interpolation): at most {:.2} µm",
        periods.len(),
        worst_correction,
        worst_outside * 1000.0,
        ramps.len(),
        worst_ramp * 1000.0,
        stops.len(),
        stops.iter().sum::<usize>(),
        worst_inside * 1000.0,
        worst_left * 1000.0,
    );
    assert!(compared > 5_000);
    // halsampler prints six decimals: a nanometre.
    assert!(worst_correction < 2e-6, "LinuxCNC's correction differs from turnpass's reading by {worst_correction} mm");
    assert!(worst_outside < 5e-5, "the landings differ by {} µm outside the ramps", worst_outside * 1000.0);
    assert!(!ramps.is_empty() && longest_ms < 100, "ramps: {ramps:?}");
    let verdict = format!(
        "LinuxCNC loaded both compensation files and ran part.ngc.\n\
         Correction computed by LinuxCNC = turnpass's reading of the file, within 2e-6 mm: {}\n\
         Landing with LinuxCNC's drive commands = turnpass's prediction of the machine with the table, within \
         0.05 µm outside the ramps of a reversal: {}\n----- comp.ini\n{}",
        worst_correction < 2e-6,
        worst_outside < 5e-5,
        snippet.replace(env!("CARGO_PKG_VERSION"), "{version}")
    );
    with_snapshots("control_table", || insta::assert_snapshot!("linuxcnc-run", verdict));
}

/// The lengths of the runs of `true` in `flags`.
fn runs(flags: &[bool]) -> Vec<usize> {
    let mut out = Vec::new();
    let mut length = 0;
    for &flag in flags.iter().chain([false].iter()) {
        if flag {
            length += 1;
        } else if length > 0 {
            out.push(length);
            length = 0;
        }
    }
    out
}

fn is_root() -> bool {
    use std::os::unix::fs::MetadataExt;
    std::fs::metadata("/proc/self").is_ok_and(|m| m.uid() == 0)
}

fn open_to_all(path: &Path) {
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o1777)).unwrap();
}

fn make_executable(path: &Path) {
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755)).unwrap();
}
