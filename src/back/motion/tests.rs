//! The codes the back end writes come from the tables, and are the ones each control runs.

use super::*;
use crate::dialect::{GCodeSystem, MachineKind};

fn configurations() -> [(DialectConfig, &'static str); 5] {
    let fanuc = |system| DialectConfig::new(Dialect::Fanuc, system, MachineKind::Lathe);
    [
        (fanuc(GCodeSystem::A), "Fanuc A"),
        (fanuc(GCodeSystem::B), "Fanuc B"),
        (fanuc(GCodeSystem::C), "Fanuc C"),
        (DialectConfig::new(Dialect::Osp, GCodeSystem::A, MachineKind::Lathe), "OSP lathe"),
        (DialectConfig::new(Dialect::Osp, GCodeSystem::A, MachineKind::MachiningCentre), "OSP machining centre"),
    ]
}

#[test]
fn every_configuration_has_the_motion_compensation_and_dwell_codes_of_its_control() {
    let g = |code| Some(Code::whole(code));
    for (config, name) in configurations() {
        let codes = Codes::of_config(config);
        let plain = [Kind::Rapid, Kind::Feed, Kind::Cw, Kind::Ccw].map(|kind| codes.motion(kind));
        assert_eq!(plain, [g(0), g(1), g(2), g(3)], "{name}");
        let thread = match (config.dialect, config.gcode_system) {
            (Dialect::Osp, _) => None,
            (Dialect::Fanuc, GCodeSystem::A) => g(32),
            (Dialect::Fanuc, _) => g(33),
        };
        assert_eq!(codes.motion(Kind::Thread), thread, "{name}");
        let compensation = [Compensation::Off, Compensation::Left, Compensation::Right].map(|c| codes.compensation(c));
        assert_eq!(compensation, [g(40), g(41), g(42)], "{name}");
        // A dwell's time in seconds: `G04 X` on Fanuc (of `X`, `U` and `P`, the first the
        // schema lists), `G04 F` on OSP.
        let (seconds, radius) = match config.dialect {
            Dialect::Fanuc => (Address::X, Address::R),
            Dialect::Osp => (Address::F, Address::L),
        };
        assert_eq!(codes.dwell, Some((Code::whole(4), seconds)), "{name}");
        assert_eq!(codes.radius_address, radius, "{name}");
    }
}

#[test]
fn the_kind_of_every_motion_code_is_its_function() {
    for (config, name) in configurations() {
        let codes = Codes::of_config(config);
        for kind in Kind::ALL {
            if let Some(code) = codes.motion(kind) {
                assert_eq!(codes.kind_of(code), Some(kind), "{name}: {kind:?}");
            }
        }
        assert_eq!(codes.kind_of(Code::whole(4)), None, "{name}");
    }
}

/// A dwell is written in its control's form, to the millisecond; F and S where they change.
#[test]
fn a_dwell_and_the_modal_words_of_written_blocks() {
    use crate::syntax::{ParseOptions, parse};
    for (dialect, seconds) in [(Dialect::Fanuc, Address::X), (Dialect::Osp, Address::F)] {
        let options = ParseOptions {
            dialect: crate::dialect::DialectChoice::Fixed(dialect),
            gcode_system: GCodeSystem::A,
            machine_kind: None,
            control: Default::default(),
        };
        let parsed = parse(b"", &options);
        let mut writer = MotionWriter::new(Codes::of(&parsed.program), Vec::new());
        let frame = crate::semantic::Frame {
            dialect,
            inch: false,
            diameter: true,
            decimal_input: crate::dialect::DecimalInput::Calculator,
            increment: 0.001,
        };
        let grid = Grid::of(frame, Xz::default());
        let mut modal = Modal::new(Compensation::Off, 1000.0);
        let line = Move {
            motion: Motion::Feed,
            compensation: Compensation::Off,
            cutting: true,
            threading: false,
            per_revolution: true,
            tool: 1,
            offset: 1,
            end: Xz::new(20.0, -5.0),
            centre: Xz::new(f64::NAN, f64::NAN),
            contour: Xz::new(20.0, -5.0),
            feed: 200.0,
            f_word: 0.2,
            s_word: 1000.0,
            rpm: 1000.0,
            phase: 0.0,
            t_start: 0.0,
            t_end: 1.5,
            source: crate::source::Span::SYNTHETIC,
            cycle: crate::source::Span::SYNTHETIC,
        };
        let dwell = Move { motion: Motion::Dwell, ..line };
        let number = |address, mantissa, scale| NewWord::Number(address, Number::new(mantissa, scale, true));
        let code = |code| NewWord::Code(CodeLetter::G, Code::whole(code));
        writer.move_block(&mut modal, &grid, false, (Xz::new(25.0, 0.0), &line), None);
        let expected =
            [code(1), number(Address::X, 40_000, 3), number(Address::Z, -5_000, 3), number(Address::F, 2, 1)];
        assert_eq!(writer.take_words(), expected, "{dialect}");
        writer.move_block(&mut modal, &grid, false, (Xz::new(20.0, -5.0), &dwell), None);
        assert_eq!(writer.take_words(), [code(4), number(seconds, 1_500, 3)], "{dialect}");
        // The same move again: no code, F or S to write.
        writer.move_block(&mut modal, &grid, false, (Xz::new(20.0, -5.0), &line), None);
        assert_eq!(writer.take_words(), expected[1..3], "{dialect}");
        let after = ModalAfter { motion: Some(Motion::Rapid), f_word: 0.3, s_word: 1000.0 };
        // A next block that writes its own motion code and F needs neither put back.
        let given = super::GivenNext { motion: true, feed: true, speed: false };
        assert!(writer.restore(&mut modal.clone(), &after, given).is_none(), "{dialect}");
        let restore = writer.restore(&mut modal, &after, super::GivenNext::default());
        assert_eq!(restore.motion, Some(super::Kind::Rapid), "{dialect}");
        assert_eq!(restore.feed, Some(Number::new(3, 1, true)), "{dialect}");
        assert_eq!(writer.take_words(), [code(0), number(Address::F, 3, 1)], "{dialect}");
    }
}
