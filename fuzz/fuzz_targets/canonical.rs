//! Fuzzes the canonical printer (`fmt --canonical`) for validity and idempotence.
//!
//! Each input is parsed with dialect detection (G-code system A) and printed with
//! `printer::print_canonical` (calculator-style decimal input, three increment places). The
//! output is parsed again in the dialect and machine kind detected for the input: the normal
//! form is defined for one machine configuration, and weak detection evidence (a packed
//! `N99POPEN`) may legitimately disappear from it. If the first parse had no errors, the target
//! asserts that the canonical output also parses without errors and that printing it
//! canonically again gives the same bytes, so the normal form is a fixed point. Inputs that
//! already had errors are only checked for panics.
//!
//! Run it from the repository root. The machine has only a stable toolchain, so
//! `RUSTC_BOOTSTRAP=1` lets cargo-fuzz use the nightly flags it needs:
//!
//! ```sh
//! RUSTC_BOOTSTRAP=1 cargo fuzz run canonical -- -max_total_time=240 -rss_limit_mb=2048 -max_len=4096 -dict=fuzz/gcode.dict
//! ```

#![no_main]

use libfuzzer_sys::fuzz_target;
use turnpass::dialect::{Control, DecimalInput, DialectChoice, GCodeSystem};
use turnpass::printer::{CanonicalOptions, print_canonical};
use turnpass::syntax::{ParseOptions, parse};

/// Both parses detect the dialect and use G-code system A.
const OPTIONS: ParseOptions = ParseOptions {
    dialect: DialectChoice::Auto,
    gcode_system: GCodeSystem::A,
    machine_kind: None,
    control: Control::Fanuc,
};

/// The normal form for calculator-style decimal input at 0.001 mm.
const CANONICAL: CanonicalOptions = CanonicalOptions { decimal_input: DecimalInput::Calculator, increment_places: 3 };

fuzz_target!(|data: &[u8]| {
    let first = parse(data, &OPTIONS);
    let canonical = print_canonical(&first.program, &CANONICAL);
    let same_machine = ParseOptions {
        dialect: DialectChoice::Fixed(first.detection.dialect),
        machine_kind: Some(first.detection.machine_kind),
        ..OPTIONS
    };
    let second = parse(&canonical, &same_machine);
    if first.error_count() != 0 {
        return;
    }

    // A program without errors must stay without errors in its normal form.
    assert_eq!(
        second.error_count(),
        0,
        "the canonical output has errors the input did not have: {:?}\ncanonical output: {:?}",
        second.diagnostics.iter().filter(|d| d.is_error()).collect::<Vec<_>>(),
        String::from_utf8_lossy(&canonical),
    );

    // Printing the normal form canonically again must change nothing.
    let again = print_canonical(&second.program, &CANONICAL);
    assert!(
        again == canonical,
        "print_canonical is not idempotent\nfirst:  {:?}\nsecond: {:?}",
        String::from_utf8_lossy(&canonical),
        String::from_utf8_lossy(&again),
    );
});
