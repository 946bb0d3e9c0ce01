//! The part model on small programs whose finished part is known by hand.

use crate::dialect::{DialectChoice, GCodeSystem};
use crate::machine::{AxisPair, MachineSettings, StockSettings, ToolSettings};
use crate::pipeline::{Settings, analyse};
use crate::semantic::LowerOptions;
use crate::syntax::ParseOptions;
use crate::toolpath::Xz;

use super::*;

fn tool(station: u32, nose: f64, tip: u8) -> ToolSettings {
    ToolSettings {
        station,
        offset: None,
        x: 0.0,
        z: 0.0,
        nose_radius: nose,
        tip,
        minor_edge_angle: None,
        kind: None,
        angle: None,
        diameter: None,
        width: None,
        max_depth: None,
    }
}

/// How the tests read a program: system A, home at X200 Z50, with `tools`.
fn settings_with(tools: Vec<ToolSettings>) -> (ParseOptions, MachineSettings) {
    let options = ParseOptions {
        dialect: DialectChoice::Auto,
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    (options, MachineSettings { home: Some(AxisPair { x: 200.0, z: 50.0 }), tool: tools, ..Default::default() })
}

fn run_on(program: &str, tools: Vec<ToolSettings>, stock: Option<StockSettings>) -> (PartRun, Vec<Diagnostic>) {
    let (options, settings) = settings_with(tools);
    let settings = Settings::new(options, &settings, LowerOptions::new(false)).with_part(PartCheck { stock });
    let analysed = analyse(program.as_bytes(), &settings);
    let diagnostics = analysed.diagnostics.clone();
    (analysed.part.expect("the program lowers and validates"), diagnostics)
}

/// The moves of `program` (with `tools`, on an assumed bar) that keep clear of its finished
/// part (`clearance.rs`), with their ends.
fn clear_moves(program: &str, tools: Vec<ToolSettings>) -> Vec<Xz> {
    let (options, settings) = settings_with(tools);
    let analysed = analyse(program.as_bytes(), &Settings::new(options, &settings, LowerOptions::new(false)));
    let program = match analysed.ready() {
        Ok(program) => program,
        Err(analysed) => panic!("the test program does not lower cleanly: {:?}", analysed.diagnostics),
    };
    let toolpath = program.valid();
    let found = clearance::clearance(toolpath, &program.machine, None).expect("a bar is assumed");
    let moves = &toolpath.toolpath().moves;
    (0..moves.len()).filter(|&k| found.is_clear(k)).map(|k| moves[k].end).collect()
}

/// Roughing at X44 (radius 22) to Z-29.8 and out at feed, then finishing at X40 (radius 20)
/// to Z-30 and up the shoulder; `rough_x` is the roughing pass's diameter.
fn rough_and_finish(rough_x: &str) -> String {
    format!(
        "G18 G21 G40 G99\nT0101\nG97 S500 M03\nG00 X46. Z2.\nG01 X{rough_x} Z0.5 F0.3\nG01 Z-29.8\nG01 X46.\n\
         G00 Z2.\nG00 X40. Z2.\nG01 Z-30. F0.1\nG01 X48.\nG00 X60. Z50.\nM30\n"
    )
}

#[test]
fn a_roughing_pass_above_the_finishing_pass_is_clear_and_the_finishing_pass_is_not() {
    // The roughing pass keeps 2 mm of the finished diameter and its retract at feed keeps
    // clear too; the finishing pass and the face it climbs do not.
    let ends = clear_moves(&rough_and_finish("44."), vec![tool(1, 0.4, 3)]);
    assert!(ends.contains(&Xz::new(22.0, -29.8)), "the roughing pass: {ends:?}");
    assert!(ends.contains(&Xz::new(23.0, -29.8)), "its retract: {ends:?}");
    assert!(!ends.contains(&Xz::new(20.0, -30.0)), "the finishing pass: {ends:?}");
    assert!(!ends.contains(&Xz::new(24.0, -30.0)), "the shoulder: {ends:?}");
}

#[test]
fn a_pass_closer_to_the_finished_surface_than_the_clearance_is_not_clear() {
    // The roughing pass leaves 0.05 mm on the radius: it comes within the clearance.
    let ends = clear_moves(&rough_and_finish("40.1"), vec![tool(1, 0.4, 3)]);
    assert!(!ends.contains(&Xz::new(20.05, -29.8)), "{ends:?}");
}

#[test]
fn a_tool_whose_side_the_table_does_not_give_keeps_clear_of_nothing() {
    // The part model guesses its side from its first cut, which a boring bar facing out
    // from its bore gets wrong: none of its moves is taken as clear.
    assert!(!clear_moves(&rough_and_finish("44."), vec![tool(1, 0.4, 3)]).is_empty());
    assert_eq!(clear_moves(&rough_and_finish("44."), vec![tool(1, 0.4, 0)]), Vec::new());
}

#[test]
fn a_thread_infeed_pass_half_the_clearance_deeper_than_the_final_is_not_clear() {
    // Four passes of an M24x2 thread with a 60° insert, the last to X21.546: the flanks of
    // a pass keep half its depth short of the final pass's from the finished thread's, so
    // the passes 0.827 and 0.377 mm short on the radius keep clear and the one 0.077 mm
    // short does not, nor does the final pass.
    let mut threading = tool(1, 0.1, 8);
    threading.kind = Some(crate::machine::ToolKind::Threading);
    threading.angle = Some(60.0);
    let program = "G18 G21 G40 G99\nT0101\nG97 S500 M03\nG00 X30. Z5.\nX23.2\nG32 Z-30. F2.\nG00 X30.\nZ5.\n\
                   X22.3\nG32 Z-30.\nG00 X30.\nZ5.\nX21.7\nG32 Z-30.\nG00 X30.\nZ5.\nX21.546\nG32 Z-30.\n\
                   G00 X30.\nZ5.\nG00 X60. Z50.\nM30\n";
    let ends = clear_moves(program, vec![threading]);
    let passes: Vec<Xz> = ends.iter().copied().filter(|end| end.z == -30.0).collect();
    assert_eq!(passes, vec![Xz::new(11.6, -30.0), Xz::new(11.15, -30.0)], "{ends:?}");
}

const BAR: StockSettings = StockSettings { diameter: 50.0, length: 60.0, front: Some(0.0), bore: None };

#[test]
fn a_turned_diameter_is_the_pass_radius_everywhere_it_ran() {
    let program = "O1\nT0101\nG99 G97 S1000 M03\nG00 X52. Z2.\nG01 X40. F0.2\nG01 Z-30.\nG00 X52.\nG00 Z2.\nM30\n";
    let (run, diagnostics) = run_on(program, vec![tool(1, 0.8, 3)], Some(BAR));
    assert!(diagnostics.is_empty(), "{diagnostics:?}");
    let part = run.part.unwrap();
    let mut seen = 0;
    for p in part.surface().filter(|p| p.normal.x > 0.99 && p.at.z < -1.0 && p.at.z > -29.0) {
        assert!((p.at.x - 20.0).abs() < 1e-9, "{p:?}");
        seen += 1;
    }
    assert!(seen > 100, "{seen}");
    assert!(part.contains(Xz::new(19.9, -10.0)) && !part.contains(Xz::new(20.1, -10.0)));
    assert!(part.contains(Xz::new(24.9, -31.5)), "the shoulder stays");
}

#[test]
fn a_rapid_into_the_bar_is_an_error_with_its_depth_and_a_note_on_an_assumed_bar() {
    let program = "O1\nT0101\nG00 X52. Z2.\nG00 X46. Z-10.\nG00 X60.\nM30\n";
    let (_, diagnostics) = run_on(program, vec![tool(1, 0.8, 3)], Some(BAR));
    let crash: Vec<_> =
        diagnostics.iter().filter(|d| matches!(d.kind, DiagnosticKind::RapidIntoStock { .. })).collect();
    // The rapid in, 2 mm deep, and the rapid back out through the same material.
    assert_eq!(crash.len(), 2, "{diagnostics:?}");
    assert!(crash[0].is_error());
    match crash[0].kind {
        DiagnosticKind::RapidIntoStock { depth_mm, .. } => assert!((depth_mm - 2.0).abs() < 1e-9, "{depth_mm}"),
        _ => unreachable!(),
    }
    let cut = "O1\nT0101\nG99 G97 S1000 M03\nG00 X52. Z2.\nG01 X40. F0.2\nG01 Z-30.\nG00 X36. Z-10.\nM30\n";
    let (_, diagnostics) = run_on(cut, vec![tool(1, 0.8, 3)], None);
    let crash: Vec<_> =
        diagnostics.iter().filter(|d| matches!(d.kind, DiagnosticKind::RapidIntoStock { .. })).collect();
    assert!(!crash.is_empty() && crash.iter().all(|d| d.severity == crate::diagnostic::Severity::Note), "{crash:?}");
}

#[test]
fn a_thread_stamps_its_form_once_per_lead() {
    // An OD thread, lead 2, one pass 1.2 mm deep (radius) with a 60° insert of nose 0.1.
    let mut thread = tool(1, 0.1, 8);
    thread.kind = Some(crate::machine::ToolKind::Threading);
    let program = "O1\nT0101\nG97 S500 M03\nG00 X52. Z4.\nX47.6\nG32 Z-20. F2.\nG00 X52.\nZ4.\nM30\n";
    let (run, _) = run_on(program, vec![thread], Some(BAR));
    let part = run.part.unwrap();
    // The groove bottoms at z = 4 - 2k, radius 23.8; crests at the bar's 25.
    for k in 3..=11 {
        let z = 4.0 - 2.0 * k as f64;
        assert!(!part.contains(Xz::new(23.85, z)), "groove at {z}");
        assert!(part.contains(Xz::new(24.9, z + 1.0)), "crest at {}", z + 1.0);
    }
}

#[test]
fn a_part_shaped_without_measuring_rapids_is_the_part_stepped_with_them() {
    // A rapid into the bar (which measures and removes nothing), cuts, and two thread passes
    // with rapids between: the rapids end the first pass, so the second stamps from its own
    // start, not on from the first's turns.
    let mut thread = tool(2, 0.1, 8);
    thread.kind = Some(crate::machine::ToolKind::Threading);
    let program = "O1\nT0101\nG99 G97 S1000 M03\nG00 X52. Z2.\nG00 X46. Z-10.\nG00 X52.\nZ2.\n\
                   G01 X44. F0.2\nG01 Z-30.\nG00 X52.\nZ2.\nT0202\nG97 S500\nG00 X52. Z4.\nX42.6\n\
                   G32 Z-20.7 F2.\nG00 X52.\nZ4.3\nX42.2\nG32 Z-20.7 F2.\nG00 X52.\nZ4.\nM30\n";
    let options = ParseOptions {
        dialect: DialectChoice::Auto,
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    let settings = MachineSettings {
        home: Some(AxisPair { x: 200.0, z: 50.0 }),
        tool: vec![tool(1, 0.8, 3), thread],
        ..Default::default()
    };
    let settings = Settings::new(options, &settings, LowerOptions::new(false));
    let analysed = analyse(program.as_bytes(), &settings);
    let crate::pipeline::Lowering::Valid(lowered) = &analysed.lowering else { panic!("{:?}", analysed.diagnostics) };
    let toolpath = &lowered.toolpath;
    let stock = Stock::from_settings(&BAR, &analysed.machine);
    let (mut stepped, mut shaped) = (
        removal::Removal::new(stock, &analysed.machine, toolpath.moves.len()),
        removal::Removal::new(stock, &analysed.machine, toolpath.moves.len()),
    );
    let mut rapids_met = 0.0;
    for (index, m) in toolpath.moves.iter().enumerate() {
        let outcome = stepped.step_move(toolpath.start_of(index), m, index).expect("within the bound");
        if m.motion == crate::toolpath::Motion::Rapid {
            rapids_met += outcome.met;
        }
        shaped.shape_move(toolpath.start_of(index), m, index).expect("within the bound");
    }
    assert!(rapids_met > 0.0, "a rapid meets the bar");
    stepped.end_thread().expect("within the bound");
    shaped.end_thread().expect("within the bound");
    assert_eq!(stepped.dexels.along_z, shaped.dexels.along_z);
    assert_eq!(stepped.dexels.along_x, shaped.dexels.along_x);
}
