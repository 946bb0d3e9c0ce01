//! A program parsed in two runs of lines on two threads is the program parsed in one run:
//! the same blocks, words, expressions, commands and diagnostics, wherever the second run
//! starts, whatever the tape state there.

use proptest::prelude::*;

use super::*;
use crate::dialect::GCodeSystem;

/// Lines that exercise what crosses from one run to the next: the tape (`%`, a `$…%`
/// header), OSP `$` continuations, labels and the sequence numbers `P`/`Q` name, cycle
/// commands, expressions and variables (whose ids move), and blocks that do not parse.
fn line() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![
        "%",
        " %",
        "% (END)",
        "$PROG.MIN%",
        "O1234 (BENCH)",
        "G00 X62.0 Z2.0 M08",
        "G01 X55.250 Z0.864 F0.117",
        "X52.282 Z-3.545",
        "G03 X41.436 Z-11.687 R11.644",
        "(ROUGH PASS 3)",
        "N10 G00 X20.",
        "G71 U1.5 R0.5",
        "G71 P10 Q20 U0.4 W0.1 F0.25",
        "G70 P10 Q20",
        "#1=[#2+1]",
        "X[#1+2.] Z-#3",
        "IF[#1GT2]GOTO10",
        "NAT00 G00 X=FLAN+5 Z=SIN[30]",
        "VC1=VC2*2",
        "$ X=1",
        "$",
        "CALL OSUB Q2",
        "G04 F5",
        "G1O",
        "X1.2.3",
        "M30",
        "",
    ])
}

fn program() -> impl Strategy<Value = Vec<u8>> {
    (prop::collection::vec((line(), prop::sample::select(vec!["\n", "\r\n", "\r"])), 0..30), any::<bool>()).prop_map(
        |(lines, byte_order_mark)| {
            let mut out = if byte_order_mark { BYTE_ORDER_MARK.to_vec() } else { Vec::new() };
            for (line, ending) in lines {
                out.extend_from_slice(line.as_bytes());
                out.extend_from_slice(ending.as_bytes());
            }
            out
        },
    )
}

/// Every place a second run may start: after a line feed, before a line that is no `$` line.
fn splits(source: &[u8]) -> impl Iterator<Item = usize> + '_ {
    (1..source.len()).filter(|&k| source[k - 1] == b'\n' && source[k] != b'$')
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn two_runs_parse_as_one(
        source in program(),
        dialect in prop::sample::select(vec![Dialect::Fanuc, Dialect::Osp]),
        gcode_system in prop::sample::select(vec![GCodeSystem::A, GCodeSystem::B]),
    ) {
        let config = DialectConfig::new(dialect, gcode_system, MachineKind::Lathe);
        let mut whole_diagnostics = Vec::new();
        let whole = parse_lines(&source, config, None, &mut whole_diagnostics);
        for split in splits(&source) {
            let mut diagnostics = Vec::new();
            let program = parse_lines(&source, config, Some(split), &mut diagnostics);
            prop_assert_eq!(format!("{program:?}"), format!("{whole:?}"), "split at {}", split);
            prop_assert_eq!(&diagnostics, &whole_diagnostics, "split at {}", split);
            for block in program.blocks() {
                prop_assert_eq!(program.words_of(block), whole.words_of(block));
                for id in block.word_ids() {
                    prop_assert_eq!(program.word(id), whole.word(id));
                }
            }
        }
    }
}

#[test]
fn the_second_run_starts_after_a_line_feed_and_not_on_a_continuation_line() {
    // The middle (byte 16) falls in the block's second `$` line, and the next line is
    // another: the second run starts after it.
    let source = b"G01 Z2.\n$ X3.\n$ Z4.\n$ X5.\r\nZ6.\n";
    assert_eq!(split_point(source), Some(27));
    assert_eq!(&source[27..], b"Z6.\n");
    assert_eq!(split_point(b"G00 X1.\nG01 Z2.\n$ X3.\n$ Z4."), None, "only continuation lines after the middle");
    assert_eq!(split_point(b"G00 X1.\nG01 Z2.\n"), None, "nothing after the last line feed");
}

#[test]
fn a_number_reads_as_the_same_f64_for_every_scale() {
    // The table of exact powers of ten in `to_f64` must give what `powi` gives.
    for scale in 0..=u8::MAX {
        for mantissa in [1, -7, 123_456_789, i64::MAX, i64::MIN] {
            let number = Number::new(mantissa, scale, true);
            let expected = mantissa as f64 / 10f64.powi(scale as i32);
            assert_eq!(number.to_f64().to_bits(), expected.to_bits(), "{mantissa} e-{scale}");
        }
    }
}

/// `Number::is_whole` answers for every scale a number can carry, those past an `i64` power
/// of ten included (the printer asked `10i64.pow(scale)`, which overflows from 19 places).
#[test]
fn whole_numbers_are_told_at_every_scale() {
    assert!(Number::new(1200, 2, true).is_whole());
    assert!(!Number::new(1250, 2, true).is_whole());
    assert!(Number::new(7, 0, false).is_whole());
    for scale in [18u8, 19, 40, 255] {
        assert!(Number::new(0, scale, true).is_whole(), "{scale}");
        assert!(!Number::new(i64::MAX, scale, true).is_whole(), "{scale}");
    }
}
