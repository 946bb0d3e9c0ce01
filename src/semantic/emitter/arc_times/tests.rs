//! Arcs handed to the other thread come back with the times and feeds the emitter gives
//! them itself, to the bit; the whole-program comparison (`tests/it/arc_times.rs`) would
//! also pass if no arc were ever handed over, so this test counts them.

use crate::dialect::{Dialect, DialectChoice, GCodeSystem};
use crate::machine::MachineSettings;
use crate::semantic::modal::{Modal, MotionMode, SpindleMode, ToolState};
use crate::semantic::{Machine, initial_frame};
use crate::syntax::ParseOptions;
use crate::toolpath::{Compensation, Xz};

use super::super::Emitter;
use super::time_arcs;

/// A metric modal state feeding `feed` per revolution (or per minute) under `spindle`.
fn modal(feed_per_rev: bool, feed: f64, spindle: SpindleMode, speed: f64) -> Modal {
    let machine = Machine::from_settings(&MachineSettings::default());
    let options = ParseOptions {
        dialect: DialectChoice::Fixed(Dialect::Fanuc),
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    let parsed = crate::syntax::parse(b"%\nG21\n%\n", &options);
    Modal {
        frame: initial_frame(&parsed.program, &machine),
        absolute: true,
        feed_per_rev,
        feed,
        spindle,
        speed,
        clamp: 3000.0,
        clamp_programmed: true,
        spindle_limit: 3000.0,
        motion: MotionMode::Linear,
        compensation: Compensation::Off,
        tool: ToolState { station: 1, offset: 1, nose_radius: 0.0, tip: 0, minor_edge_angle: None },
        shift: Xz::default(),
    }
}

/// Per-minute, fixed-rpm and constant-surface-speed arcs, each a quarter turn.
fn arcs(emitter: &mut Emitter) {
    let modes = [
        modal(false, 300.0, SpindleMode::Rpm, 1000.0),
        modal(true, 0.2, SpindleMode::Rpm, 1200.0),
        modal(true, 0.15, SpindleMode::SurfaceSpeed, 180.0),
    ];
    for (k, modal) in modes.iter().enumerate() {
        let r = 10.0 + k as f64;
        let centre = Xz::new(emitter.at.x - r, emitter.at.z);
        emitter.line(modal, Xz::new(emitter.at.x, emitter.at.z - 1.0), true);
        let centre = Xz::new(centre.x, centre.z - 1.0);
        emitter.arc(modal, Xz::new(centre.x, centre.z - r), centre, k % 2 == 0, true);
    }
}

#[test]
fn arcs_timed_beside_are_handed_over_and_come_back_the_same_to_the_bit() {
    let start = Xz::new(40.0, 5.0);
    let rapid = Xz::new(10_000.0, 10_000.0);
    let mut itself = Emitter::new(start, rapid, 8, usize::MAX);
    arcs(&mut itself);

    let mut beside = Emitter::new(start, rapid, 8, usize::MAX);
    let (sender, receiver) = std::sync::mpsc::channel();
    beside.time_arcs_beside(sender);
    arcs(&mut beside);
    let handed = beside.stop_timing_beside();
    let timed = time_arcs(receiver);
    assert_eq!(handed.moves.len(), 3, "every usable arc goes to the other thread");
    assert_eq!(timed.len(), 3);
    beside.chain_times(&handed, &timed);

    assert_eq!(beside.moves.len(), itself.moves.len());
    for (a, b) in beside.moves.iter().zip(&itself.moves) {
        assert_eq!(a.t_start.to_bits(), b.t_start.to_bits());
        assert_eq!(a.t_end.to_bits(), b.t_end.to_bits());
        assert_eq!(a.feed.to_bits(), b.feed.to_bits());
    }
    assert!(itself.moves.iter().all(|m| m.t_end > m.t_start), "every move takes time");
}
