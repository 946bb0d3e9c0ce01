//! Fuzzes `turnpass::syntax::parse` and the lossless printer with arbitrary bytes.
//!
//! Each input is parsed three times: with dialect detection (G-code system A), as Okuma OSP
//! (system A), and as Fanuc (system B). The inputs need not be UTF-8. For every parse the
//! target checks that the parser does not panic, that `printer::print` with no edits gives
//! back the input byte for byte, that the blocks tile the source (the first block starts at
//! offset 0 and every block but the last and a `Trailing` block is followed by exactly one
//! line terminator), that every word span lies inside its block span, and that no diagnostic
//! span ends past the end of the input.
//!
//! Run it from the repository root. The machine has only a stable toolchain, so
//! `RUSTC_BOOTSTRAP=1` lets cargo-fuzz use the nightly flags it needs:
//!
//! ```sh
//! RUSTC_BOOTSTRAP=1 cargo fuzz run parse -- -max_total_time=360 -rss_limit_mb=2048 -max_len=4096 -dict=fuzz/gcode.dict
//! ```

#![no_main]

use libfuzzer_sys::fuzz_target;
use turnpass::dialect::{Control, Dialect, DialectChoice, GCodeSystem};
use turnpass::printer::{Edits, print};
use turnpass::syntax::{ParseOptions, Statement, parse};

/// The three ways the target reads each input.
const OPTIONS: [ParseOptions; 3] = [
    ParseOptions {
        dialect: DialectChoice::Auto,
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Control::Fanuc,
    },
    ParseOptions {
        dialect: DialectChoice::Fixed(Dialect::Osp),
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Control::Fanuc,
    },
    ParseOptions {
        dialect: DialectChoice::Fixed(Dialect::Fanuc),
        gcode_system: GCodeSystem::B,
        machine_kind: None,
        control: Control::Fanuc,
    },
];

fuzz_target!(|data: &[u8]| {
    for options in &OPTIONS {
        check(data, options);
    }
});

/// Parses `data` with `options` and checks the parser's invariants.
fn check(data: &[u8], options: &ParseOptions) {
    let parsed = parse(data, options);
    let program = &parsed.program;

    // The printer with no edits must reproduce the input exactly.
    let printed = print(program, &Edits::new());
    assert!(printed == data, "print is not lossless under {options:?}");

    // The blocks must tile the source, starting at its first byte.
    let blocks = program.blocks();
    if !data.is_empty() {
        assert!(!blocks.is_empty(), "a non-empty input gave no blocks under {options:?}");
        assert_eq!(blocks[0].span.start, 0, "the first block does not start at 0 under {options:?}");
    }
    let last = blocks.len().saturating_sub(1);
    for (index, block) in blocks.iter().enumerate() {
        // Every word of a block must lie inside the block's text.
        for word in program.words_of(block) {
            assert!(
                block.span.contains(word.span),
                "word span {:?} lies outside block {index} span {:?} under {options:?}",
                word.span,
                block.span,
            );
        }

        // A `Trailing` block runs to the end of the input, so it has no terminator to check.
        if block.statement == Statement::Trailing {
            continue;
        }
        let terminator = program.terminator(index);
        let is_line_end = matches!(terminator, b"\n" | b"\r\n" | b"\r");
        let is_final = terminator.is_empty() && index == last;
        assert!(
            is_line_end || is_final,
            "block {index} of {} is followed by {terminator:?}, not one line terminator, under {options:?}",
            blocks.len(),
        );
    }

    // No diagnostic may point past the end of the input.
    for diagnostic in &parsed.diagnostics {
        assert!(
            diagnostic.span.end as usize <= data.len(),
            "diagnostic {:?} ends past the input ({} bytes) under {options:?}",
            diagnostic.span,
            data.len(),
        );
    }
}
