use super::*;
use crate::back::motion::{Codes, MotionWriter};
use crate::compensation::test_support::{analysed, ready};
use crate::dialect::{DialectChoice, GCodeSystem};
use crate::printer::{BlockWriter, Edits, print_string};
use crate::syntax::{ParseOptions, parse};
use crate::toolpath::Motion;

/// An arc by radius and an incremental arc by centre, after a line.
const PROGRAM: &str = "\
G21 G99
G97 S1000 M03
G00 X40. Z2.
G01 Z-10. F0.2
G02 X50. Z-15. R5.
G03 U10. W-5. I0 K-5.
G01 W-5.
M30
";

/// Rewrite the block of move `index` for a plan of one arc about the move's centre moved by
/// `centre_by`, from the same start, to its end moved by `end_by` and then onto the new
/// circle; the printed program, the arc it lowers to, and the planned arc.
fn rewrite_arc(index: usize, end_by: Xz, centre_by: Xz) -> (String, crate::toolpath::Move, Segment) {
    let original = ready(PROGRAM);
    let (program, lowered, machine) = (original.program(), &original.lowered, &original.machine);
    let m = lowered.toolpath.moves[index];
    let start = lowered.toolpath.start_of(index);
    let centre = Xz::new(m.centre.x + centre_by.x, m.centre.z + centre_by.z);
    let radius = start.distance(centre);
    let moved = Xz::new(m.end.x + end_by.x, m.end.z + end_by.z);
    let end = crate::geometry::on_circle(centre, radius, crate::geometry::angle(moved, centre));
    let segment = Segment::Arc { end, centre, ccw: m.motion == Motion::Ccw };
    let (segments, words) = (vec![segment].into(), Default::default());
    let plan = MovePlan { start, segments, changed: true, jumps: 0, lead_in: false, words };
    let block = program.blocks().iter().position(|b| b.span == m.source).unwrap();
    let mark = lowered.coordinates_at(index);
    let tools = crate::semantic::nose_radius::ToolTable::from_machine(machine);
    let codes = Codes::of(program);
    let context = BlockContext {
        program,
        codes,
        block,
        mark,
        grid: Grid::new(&mark),
        radius_arcs: true,
        tools: &tools,
        lead: None,
        piece_leads: &[],
        restore_lead: false,
        inherited: None,
        taper: None,
        carried: Default::default(),
    };
    let mut writer = MotionWriter::new(codes, BlockWriter::new(program));
    let (text, _) = context.rewrite(&m, start, &plan, &mut writer).unwrap();
    let mut edits = Edits::new();
    edits.replace_written(writer.out, vec![(block, text)]);
    let text = print_string(program, &edits);
    let relowered = ready(&text).lowered.toolpath.moves[index];
    (text, relowered, segment)
}

#[test]
fn an_arc_by_radius_keeps_its_radius_form_and_lands_on_the_rounded_end() {
    let (text, arc, segment) = rewrite_arc(2, Xz::new(0.0031, -0.0022), Xz::new(0.001, 0.0015));
    let line = text.lines().nth(4).unwrap();
    assert_eq!(line, "G02 X50.006 Z-14.999 R5.001");
    let Segment::Arc { end, centre, .. } = segment else { unreachable!() };
    // X rounds on the diameter grid (0.0005 mm in radius), Z on 0.001 mm: the end lands
    // within half of each of its planned place.
    assert!((arc.end.x - end.x).abs() <= 0.00025 + 1e-9 && (arc.end.z - end.z).abs() <= 0.0005 + 1e-9, "{end:?}");
    // The control's centre from the rounded radius is within an increment of the planned one.
    assert!(arc.centre.distance(centre) < 0.001, "{:?} against {centre:?}", arc.centre);
}

#[test]
fn an_incremental_arc_by_centre_keeps_u_w_i_k() {
    let (text, arc, segment) = rewrite_arc(3, Xz::new(-0.0012, 0.0008), Xz::new(-0.002, 0.0));
    let line = text.lines().nth(5).unwrap();
    assert!(line.starts_with("G03 U") && line.contains(" W") && line.contains(" I") && line.contains(" K"), "{line}");
    let Segment::Arc { end, centre, .. } = segment else { unreachable!() };
    assert!(arc.end.distance(end) < 0.0006, "{:?} against {end:?}", arc.end);
    assert!(arc.centre.distance(centre) < 0.001, "{:?} against {centre:?}", arc.centre);
    // The line after it is untouched and, being incremental, now starts from the new end.
    assert_eq!(text.lines().nth(6), Some("G01 W-5."));
}

/// Rewrite the `G02` block (block 4) of `program` as two lines; the four lines from it on.
fn arc_as_lines(program: &str) -> Vec<String> {
    let ready = ready(program);
    let (program, lowered) = (ready.program(), &ready.lowered);
    let m = lowered.toolpath.moves[2];
    let start = lowered.toolpath.start_of(2);
    let mid = Xz::new(22.0, -13.5);
    let segments = vec![Segment::Line { end: mid }, Segment::Line { end: m.end }].into();
    let plan = MovePlan { start, segments, changed: true, jumps: 0, lead_in: false, words: Default::default() };
    let mark = lowered.coordinates_at(2);
    let tools = crate::semantic::nose_radius::ToolTable::from_machine(&ready.machine);
    let codes = Codes::of(program);
    let context = BlockContext {
        program,
        codes,
        block: 4,
        mark,
        grid: Grid::new(&mark),
        radius_arcs: true,
        tools: &tools,
        lead: None,
        piece_leads: &[],
        restore_lead: false,
        inherited: None,
        taper: None,
        carried: Default::default(),
    };
    let mut writer = MotionWriter::new(codes, BlockWriter::new(program));
    let (text, _) = context.rewrite(&m, start, &plan, &mut writer).unwrap();
    let mut edits = Edits::new();
    edits.replace_written(writer.out, vec![(4, text)]);
    let text = print_string(program, &edits);
    text.lines().skip(4).take(4).map(str::to_string).collect()
}

#[test]
fn an_arc_that_becomes_lines_loses_its_radius_and_puts_its_motion_code_back_where_the_next_block_runs_under_it() {
    // The next block writes its own `G03`: nothing to put back before it.
    assert_eq!(arc_as_lines(PROGRAM), ["G01 X44. Z-13.5", "X50. Z-15.", "G03 U10. W-5. I0 K-5.", "G01 W-5."]);
    // The next block is an arc under the modal `G02`: it is put back before it.
    let bare = PROGRAM.replace("G03 U10. W-5. I0 K-5.", "U10. W-5. R5.");
    assert_eq!(arc_as_lines(&bare), ["G01 X44. Z-13.5", "X50. Z-15.", "G02", "U10. W-5. R5."]);
    // A comment line between them runs nothing: the block after it decides.
    let commented = PROGRAM.replace("G03 U10.", "(NEXT ARC)\nG03 U10.");
    assert_eq!(arc_as_lines(&commented), ["G01 X44. Z-13.5", "X50. Z-15.", "(NEXT ARC)", "G03 U10. W-5. I0 K-5."]);
    // A block the operator may skip gives nothing: the code is put back.
    let skippable = PROGRAM.replace("G03 U10.", "/G03 U10.");
    assert_eq!(arc_as_lines(&skippable), ["G01 X44. Z-13.5", "X50. Z-15.", "G02", "/G03 U10. W-5. I0 K-5."]);
}

/// A line block takes the program's arc form whatever its words (an `R` there is a corner,
/// not a radius), and an arc block its own, the same as by reading its slots.
#[test]
fn writes_radius_reads_an_arc_blocks_own_form_and_gives_a_line_the_programs() {
    let source = "G00 X40. Z2.\nG01 X44. Z-10. R1. F0.2\nG02 X50. Z-15. R5.\nG03 X60. Z-20. I0 K-5.\nG01 Z-25. I1.\n";
    let options = ParseOptions {
        dialect: DialectChoice::Auto,
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    let parsed = parse(source.as_bytes(), &options);
    let program = &parsed.program;
    for program_radius_arcs in [false, true] {
        let forms: Vec<(bool, bool)> = (0..5)
            .map(|block| {
                let by_slots = |is_arc| {
                    let dialect = program.config().dialect;
                    let slots = program.words_of(program.block(block)).iter().filter_map(|word| match word.kind {
                        WordKind::Number { address, .. } | WordKind::Expr { address, .. } => {
                            slot(dialect, address, is_arc)
                        }
                        _ => None,
                    });
                    radius_form(slots).unwrap_or(program_radius_arcs)
                };
                assert_eq!(writes_radius(program, block, false, program_radius_arcs), by_slots(false));
                (
                    writes_radius(program, block, true, program_radius_arcs),
                    writes_radius(program, block, false, program_radius_arcs),
                )
            })
            .collect();
        let p = program_radius_arcs;
        assert_eq!(forms, vec![(p, p), (true, p), (true, p), (false, p), (false, p)]);
    }
}

/// The arc form `MotionBlocks` takes from the words read with the program's arc form is the
/// one `writes_radius` reads from the block, for motion blocks and for the others.
#[test]
fn the_arc_form_from_the_programs_tables_is_the_blocks_own() {
    let source = "G21 G99\nG97 S1000 M03\nG00 X40. Z2.\nG01 X44. Z-10. R1. F0.2\nG02 X50. Z-15. R5.\n\
                  G03 X60. Z-20. I0 K-5.\nG02 X70. Z-25. I5. K0 R5.\nG01 Z-30.\nG04 X1. R2.\nM30\n";
    // An arc with both a radius and a centre, and a dwell with an `R`, lower with errors:
    // only the blocks' words matter here.
    let analysed = analysed(source);
    let (program, lowered) = (&analysed.parsed.program, analysed.lowered().unwrap());
    let tools = crate::semantic::nose_radius::ToolTable::from_machine(&analysed.machine);
    let motion = super::super::MotionBlocks::new(program, lowered, &tools);
    for block in 0..program.blocks().len() {
        for is_arc in [false, true] {
            let expected = writes_radius(program, block, is_arc, motion.radius_arcs);
            assert_eq!(motion.writes_radius(block, is_arc), expected, "block {block}, arc {is_arc}");
        }
    }
    // The words were read for the motion blocks, not for the others.
    assert_eq!(motion.arc_words[4], crate::printer::style::BlockArcWords::Radius);
    assert_eq!(motion.arc_words[5], crate::printer::style::BlockArcWords::Centre);
    assert_eq!(motion.arc_words[6], crate::printer::style::BlockArcWords::Radius);
    assert_eq!(motion.arc_words[8], crate::printer::style::BlockArcWords::NotRead);
}
