use super::follow::Follower;
use super::*;
use crate::compensation::deviation::distance_to_move;
use crate::compensation::test_support::lower_program;
use crate::error_model::effects::*;
use crate::error_model::sampling::PathSample;
use crate::error_model::sampling::sample_toolpath;
use crate::semantic::Lowered;
use crate::toolpath::Validated;
use crate::toolpath::{Motion, Xz};

/// The closest cutting move of the whole of `toolpath` to `p`, by looking at every move.
fn brute_force(toolpath: &Toolpath, p: Xz) -> f64 {
    (toolpath.moves.iter().enumerate())
        .filter(|(_, m)| m.cutting && m.motion != Motion::Dwell)
        .map(|(k, m)| distance_to_move(p, toolpath.start_of(k), m))
        .fold(f64::INFINITY, f64::min)
}

/// A point a few micrometres off `sample`, different for each sample (a model's errors).
fn predicted(index: usize, sample: &PathSample) -> Xz {
    let angle = index as f64 * 2.399_963;
    let size = 0.002 + 0.008 * ((index * 7919) % 101) as f64 / 100.0;
    Xz::new(sample.nominal.x + size * angle.sin(), sample.nominal.z + size * angle.cos())
}

/// Every cutting sample of `compensated` followed along `original` and measured, against the
/// brute-force closest point of the whole of `original`.
fn followed_and_brute_force(original: &Validated<Lowered>, compensated: &Validated<Lowered>) -> Vec<(f64, f64)> {
    let compact = super::compact(original.valid(), &ToolTable::default());
    let (original, compensated) = (&original.toolpath, &compensated.toolpath);
    let path = Original::new(&compact);
    let mut follower = Follower::new(&path);
    let samples = sample_toolpath(compensated, &ToolTable::default(), 0.254);
    let cutting = samples.iter().enumerate().filter(|(_, s)| s.cutting);
    let pairs: Vec<_> = cutting
        .map(|(i, s)| {
            let p = predicted(i, s);
            (follower.measure(s.nominal, p).expect("a distance").distance, brute_force(original, p))
        })
        .collect();
    assert!(pairs.len() > 20, "{}", pairs.len());
    pairs
}

fn assert_equal(pairs: &[(f64, f64)]) {
    for (i, (followed, brute)) in pairs.iter().enumerate() {
        assert!((followed - brute).abs() < 1e-9, "point {i}: followed {followed}, whole path {brute}");
    }
}

/// Passes piled up over the same square millimetre in the generator's style: short feeds
/// back and forth across each other, arcs through them, the tool away and back by rapids,
/// each pass crossing the others again and again. Radius programming is not needed: X is
/// a diameter, so the square is 2 mm of diameter by 1 mm of Z.
const PILED: &str = "\
G21 G99
G97 S1000 M03
G00 X22. Z1.
G01 X20. Z0. F0.1
X21.6 Z-0.8
X20.2 Z-0.3
G02 X21.8 Z-0.2 R0.9
G01 X20.4 Z-0.9
G00 X24. Z1.
X21.9 Z0.1
G01 X20.1 Z-0.6
G03 X21.5 Z-0.95 R0.8
G01 X20.05 Z-0.05
X21.95 Z-0.5
G00 X24. Z1.
M30
";

/// The same passes as `PILED` as a compensated program writes them: every point moved by a
/// few micrometres, and one feed cut in two where a correction changes along it.
const PILED_COMPENSATED: &str = "\
G21 G99
G97 S1000 M03
G00 X22.006 Z0.997
G01 X20.004 Z-0.002 F0.1
X20.805 Z-0.402
X21.598 Z-0.803
X20.206 Z-0.301
G02 X21.802 Z-0.203 R0.9
G01 X20.397 Z-0.904
G00 X24. Z1.
X21.903 Z0.098
G01 X20.104 Z-0.603
G03 X21.497 Z-0.951 R0.8
G01 X20.053 Z-0.047
X21.956 Z-0.502
G00 X24. Z1.
M30
";

#[test]
fn passes_piled_up_over_each_other_are_measured_against_the_closest_of_them() {
    let (original, _) = lower_program(PILED);
    let (compensated, _) = lower_program(PILED_COMPENSATED);
    let pairs = followed_and_brute_force(&original, &compensated);
    // The test means something only if some points are closer to another pass than to
    // their own: the brute-force closest of those is another pass, and it must be found.
    let compact = super::compact(original.valid(), &ToolTable::default());
    let path = Original::new(&compact);
    let samples = sample_toolpath(&original.toolpath, &ToolTable::default(), 0.254);
    let elsewhere = (samples.iter().enumerate().filter(|(_, s)| s.cutting))
        .filter(|&(i, s)| {
            let p = predicted(i, s);
            let own = path.distance(p, s.move_index);
            brute_force(&original.toolpath, p) < own - 1e-6
        })
        .count();
    assert!(elsewhere > 0);
    assert_equal(&pairs);
}

/// Roughing passes 0.5 mm apart in diameter, each 20 mm long and up 0.2 mm at its end,
/// away and back by rapids, then a finishing contour with an arc below them all: no pass
/// comes within 0.1 mm of another (a model's errors are micrometres), and the walk must
/// cross the rapids and keep up with a compensated program that writes the long feeds in
/// pieces.
fn roughing(compensated: bool) -> String {
    let mut text = String::from("G21 G99\nG97 S1000 M03\nG00 X42. Z2.\n");
    let shift = if compensated { 0.006 } else { 0.0 };
    for pass in 0..12 {
        let x = 40.0 - 0.5 * pass as f64;
        text.push_str(&format!("G00 X{:.3} Z1.\nG01 Z0. F0.2\n", x + shift));
        if compensated {
            text.push_str("Z-7.003\nZ-13.997\n");
        }
        text.push_str(&format!("Z-20.\nX{:.3}\nG00 X42. Z1.\n", x + 0.2 + shift));
    }
    text.push_str(&format!(
        "G00 X30. Z1.\nG01 X{:.3} Z0.\nG03 X{:.3} Z-1.5 R1.5\nG01 Z-20.\nX{:.3}\nG00 X50. Z50.\nM30\n",
        30.0 + shift,
        33.0 + shift,
        34.0 + shift
    ));
    text
}

#[test]
fn passes_that_keep_their_distance_are_measured_as_the_whole_path_measures_them() {
    let (original, _) = lower_program(&roughing(false));
    let (compensated, _) = lower_program(&roughing(true));
    assert_equal(&followed_and_brute_force(&original, &compensated));
}

#[test]
fn a_point_that_strays_from_the_original_is_measured_against_the_whole_path() {
    // Half-way along its first pass the compensated program cuts out to 3 mm above every
    // pass of the original and back: no candidate of the walk comes within the shift
    // there, the whole path answers, and the walk picks up the pass again where it returns.
    let original = roughing(false);
    let strayed = roughing(true).replacen("Z-13.997\n", "X46.006\nZ-13.997\nX40.006\n", 1);
    let (original, _) = lower_program(&original);
    let (compensated, _) = lower_program(&strayed);
    let pairs = followed_and_brute_force(&original, &compensated);
    assert!(pairs.iter().any(|&(_, brute)| brute > 1.0));
    assert_equal(&pairs);
}

#[test]
fn a_program_verified_against_itself_deviates_as_much_before_as_after() {
    let (lowered, machine) = lower_program(PILED);
    let tools = ToolTable::from_machine(&machine);
    let model = ErrorModel {
        tables: None,
        effects: vec![
            Effect::ToolOffsetX(ToolOffsetX { d: 0.004, axis: X }),
            Effect::BacklashZ(BacklashZ { b: 0.003, axis: Z }),
        ],
        start_min: 0.0,
        control: None,
    };
    let figures = deviation(lowered.valid(), lowered.valid(), &tools, &model, &Sampling::every_mm(0.254));
    assert!(figures.before.max_mm > 0.001, "{figures:?}");
    assert_eq!(figures.before, figures.after);
}

/// A pass, then 0.05 mm above it the way back in two feeds: every point of the way back is
/// within the shift of the first pass, which comes earlier (the generator's zigzags do this,
/// an arc and the feeds back beside it). `shift` moves the compensated program's X.
fn there_and_back(shift: f64, pieces: bool) -> String {
    let middle = if pieces { "Z-3.\nZ-9.\n" } else { "" };
    format!(
        "G21 G99\nG97 S1000 M03\nG00 X{a:.3} Z1.\nG01 Z0. F0.2\n{middle}Z-12.\nX{b:.3}\nZ-6.\nZ1.\nG00 X50. Z5.\nM30\n",
        a = 20.0 + shift,
        b = 20.1 + shift
    )
}

#[test]
fn the_way_back_beside_a_pass_is_measured_against_itself_not_the_pass() {
    let (original, _) = lower_program(&there_and_back(0.0, false));
    let (compensated, _) = lower_program(&there_and_back(0.006, true));
    assert_equal(&followed_and_brute_force(&original, &compensated));
}

/// A provenance comment is not one of the program's words: a compensated program may carry
/// one the original does not (or the other way round, the original compensated with
/// `--force`), and neither counts it.
#[test]
fn a_provenance_comment_is_not_a_word_to_keep() {
    let options = crate::syntax::ParseOptions {
        dialect: crate::dialect::DialectChoice::Auto,
        gcode_system: crate::dialect::GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    let mark = "(TURNPASS 0.1.0 COMPENSATED, MODEL LATHE, SHA256 0123456789AB, TOLERANCE 0.0005 MM, \
                STRATEGY AUTO, START 30 MIN)";
    let plain = "O1004 (FACE)\nG21 G99\nT0101 (TOOL)\nG00 X20. Z2. M08\nM30\n";
    let marked = plain.replacen("(FACE)\n", &format!("(FACE)\n{mark}\n"), 1);
    let (plain, marked) =
        (crate::syntax::parse(plain.as_bytes(), &options), crate::syntax::parse(marked.as_bytes(), &options));
    for (original, compensated) in [(&marked, &plain), (&plain, &marked)] {
        let check = check_words(&Words::of(&original.program, &[]), &Words::of(&compensated.program, &[]));
        assert_eq!(check.missing, None);
        // O1004, (FACE), T0101, (TOOL), M08, M30.
        assert_eq!(check.checked, 6);
    }
}

/// Arcs of several sizes, tapers and faces, both slides reversing: a part for the sampling
/// test below.
const SHAPED: &str = "\
G21 G99
G97 S1000 M03
G00 X42. Z2.
G01 X20. Z0. F0.1
G03 X30. Z-5. R5.
G01 Z-20.
G02 X34. Z-22. R2.
G01 X40. Z-40.
G03 X40. Z-60. I0. K-10.
G01 X44. Z-61. F0.08
G02 X44. Z-70. I0. K-4.5
G01 X48.
Z-90.
G00 X60. Z2.
M30
";

/// `verify` samples a path as the model needs (`sampling`), not every few hundredths of a
/// millimetre: its figures stay within the sampling's promise of the densely sampled ones —
/// each chord between samples follows the model within a tenth of half the increment, so
/// the largest deviation and the RMS move by no more than that (here 0.05 µm), on a part of
/// arcs, tapers and reversals, for a model whose screw error peaks between a line's ends and
/// for one of play, warm-up and affine terms as well. Sampled every 3 mm instead, the first
/// misses its largest deviation by several times the promise.
#[test]
fn sampling_from_the_model_measures_as_dense_sampling_does() {
    let (lowered, machine) = lower_program(SHAPED);
    let tools = ToolTable::from_machine(&machine);
    let screw = vec![
        Effect::CyclicZ(CyclicZ { amp: 0.004, pitch: 5.0, phase: 0.3, axis: Z }),
        Effect::Squareness(Squareness { urad: 30.0 }),
    ];
    let mixed = vec![
        Effect::BacklashX(BacklashX { b: 0.004, axis: X }),
        Effect::Squareness(Squareness { urad: 30.0 }),
        Effect::ScaleZ(ScaleZ { ppm: 40.0, axis: Z }),
        Effect::CyclicZ(CyclicZ { amp: 0.002, pitch: 6.0, phase: 0.3, axis: Z }),
        Effect::ThermalZ(ThermalZ { amp: 0.008, tau_min: 2.0, axis: Z }),
    ];
    let increment = machine.increment * machine.scale();
    let promise = increment / 2.0 / 10.0;
    let toolpath = lowered.valid();
    for (name, effects) in [("screw", screw), ("mixed", mixed)] {
        let model = ErrorModel { tables: None, effects, start_min: 0.0, control: None };
        let figures = |sampling: &Sampling| deviation(toolpath, toolpath, &tools, &model, sampling).before;
        let sparse = figures(&sampling(&model, increment, &[&super::compact(toolpath, &tools)]));
        let dense = figures(&Sampling::every_mm(0.005));
        assert!(dense.max_mm > 0.003, "{name}: {dense:?}");
        assert!((sparse.max_mm - dense.max_mm).abs() <= promise, "{name}: sparse {sparse:?}\ndense {dense:?}");
        assert!((sparse.rms_mm - dense.rms_mm).abs() <= promise, "{name}: sparse {sparse:?}\ndense {dense:?}");
        if name == "screw" {
            let coarse = figures(&Sampling::every_mm(3.0));
            assert!((coarse.max_mm - dense.max_mm).abs() > 2.0 * promise, "{name}: coarse {coarse:?}\ndense {dense:?}");
        }
    }
}

/// A program of lines, arcs, a dwell, a G32 pass and a G92 cycle, with two tools.
const LINES_ARCS_THREADS: &str = "\
G21 G99
G97 S800 M03
T0101
G00 X40. Z2.
G01 X30. Z0. F0.2
G02 X34. Z-2. R2.
G01 Z-20.
G03 X40. Z-23. R3.
G04 X0.5
T0303
G00 X32. Z5.
G32 Z-15. F1.5
G00 X40.
G92 X29. Z-15. F1.5
X28.5
G00 X60. Z50.
M30
";

/// The part measure cuts a program's parts from its compact path (`CompactPath::as_move`):
/// every move reads back there as the toolpath holds it in every field the part model and
/// the part measure read, so the parts are the ones the full moves cut.
#[test]
fn a_compact_move_is_the_full_move_to_the_part_model() {
    let program = LINES_ARCS_THREADS;
    let (lowered, machine) = lower_program(program);
    let toolpath = lowered.valid().toolpath();
    let path = super::compact(lowered.valid(), &ToolTable::from_machine(&machine));
    assert_eq!(path.len(), toolpath.moves.len());
    assert!(toolpath.moves.iter().any(|m| m.threading) && toolpath.moves.iter().any(|m| m.is_arc()));
    for (k, full) in toolpath.moves.iter().enumerate() {
        let m = path.as_move(k).expect("a move of the path");
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
        assert_eq!(
            (m.motion, m.compensation, m.cutting, m.threading),
            (full.motion, full.compensation, full.cutting, full.threading),
            "move {k}"
        );
        assert_eq!((m.tool, m.offset, m.source), (full.tool, full.offset, full.source), "move {k}");
        assert_eq!(path.start_of(k), toolpath.start_of(k), "move {k}");
        assert!(same(m.end.x, full.end.x) && same(m.end.z, full.end.z), "move {k}");
        assert!(same(m.centre.x, full.centre.x) && same(m.centre.z, full.centre.z), "move {k}: {m:?}\n{full:?}");
        assert!(same(m.feed, full.feed) && same(m.t_start, full.t_start) && same(m.t_end, full.t_end), "move {k}");
        if full.threading {
            assert!(same(m.rpm, full.rpm), "move {k}: rpm {} against {}", m.rpm, full.rpm);
        }
    }
    assert_eq!(path.as_move(path.len()), None);
}

/// `compensate` cuts the original's nominal part once, for the clearance of its feed moves
/// (`part::clearance`), and its check takes that part: the part measure finds the same
/// figures from it as from its own cut of the original's compact path.
#[test]
fn the_finished_part_of_the_clearance_is_the_nominal_part_the_measure_cuts() {
    let program = LINES_ARCS_THREADS;
    let (lowered, machine) = lower_program(program);
    let tools = ToolTable::from_machine(&machine);
    let path = super::compact(lowered.valid(), &tools);
    let clearance = crate::part::clearance::clearance(lowered.valid(), &machine, None).expect("a bar is assumed");
    let model = ErrorModel {
        tables: None,
        effects: vec![Effect::ToolOffsetX(ToolOffsetX { d: 0.004, axis: X })],
        start_min: 0.0,
        control: None,
    };
    let sampling = Sampling::every_mm(0.254);
    let measure =
        |finished| part_deviation((&path, &path), &model, &sampling, &machine, PartFrom { stock: None, finished });
    let (own, given) = (measure(None), measure(Some(clearance.finished())));
    assert!(own.deviation.before.max_mm > 0.001 && !own.threads.is_empty(), "{:?}", own.deviation);
    assert_eq!(own, given);
}
