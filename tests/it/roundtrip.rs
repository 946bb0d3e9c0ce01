//! Property tests over a generated family of programs: parse → print is the identity, the
//! span invariants hold, and programs that parse cleanly have an idempotent canonical form
//! that parses cleanly too.
//!
//! The family mixes well-formed Fanuc and OSP blocks (packed and spaced words, sequence
//! names, comments, expressions, block delete, continuation lines) with damaged lines and
//! arbitrary bytes, joined by LF, CR LF and lone CR, with or without a final terminator.

use proptest::prelude::*;
use turnpass::dialect::{Dialect, DialectChoice, GCodeSystem};
use turnpass::printer::{CanonicalOptions, Edits, print, print_canonical};
use turnpass::syntax::{ParseOptions, parse};

use crate::support::check_spans;

fn number() -> impl Strategy<Value = String> {
    (any::<bool>(), 0u32..100_000, 0usize..5, any::<bool>()).prop_map(|(negative, digits, scale, point)| {
        let text = digits.to_string();
        let mut out = String::new();
        if negative {
            out.push('-');
        }
        if scale == 0 || scale >= text.len() {
            out.push_str(&text);
            if point {
                out.push('.');
            }
        } else {
            out.push_str(&text[..text.len() - scale]);
            out.push('.');
            out.push_str(&text[text.len() - scale..]);
        }
        out
    })
}

fn fanuc_word() -> impl Strategy<Value = String> {
    prop_oneof![
        (0u32..4).prop_map(|g| format!("G{g:02}")),
        prop::sample::select(vec!["G40", "G41", "G42", "G96", "G97", "G99", "G18", "G54"]).prop_map(str::to_string),
        (prop::sample::select(vec!['X', 'Z', 'U', 'W', 'I', 'K', 'R', 'F']), number())
            .prop_map(|(a, n)| format!("{a}{n}")),
        (prop::sample::select(vec!['S', 'T', 'M']), 0u32..100).prop_map(|(a, n)| format!("{a}{n:02}")),
        "[A-Z ]{0,12}".prop_map(|c| format!("({c})")),
        (1u32..600, number()).prop_map(|(v, n)| format!("X[#{v}+{n}]")),
    ]
}

fn osp_word() -> impl Strategy<Value = String> {
    prop_oneof![
        (0u32..4).prop_map(|g| format!("G{g:02}")),
        (prop::sample::select(vec!['X', 'Z', 'I', 'K', 'L', 'F', 'D', 'U', 'W']), number())
            .prop_map(|(a, n)| format!("{a}{n}")),
        ("[A-Z]{2}[A-Z0-9]{0,2}", number()).prop_map(|(v, n)| format!("X={v}+{n}")),
        prop::sample::select(vec!["TG=01", "OG=2", "M03", "M08", "T010101", "(COMMENT)", "XA=60", "V1=2"])
            .prop_map(str::to_string),
    ]
}

fn fanuc_block() -> impl Strategy<Value = String> {
    (
        any::<bool>(),
        prop::option::of(1u32..99_999),
        prop::collection::vec(fanuc_word(), 0..6),
        prop::sample::select(vec!["", " ", "\t"]),
    )
        .prop_map(|(delete, sequence, words, separator)| {
            let mut parts = Vec::new();
            if delete {
                parts.push("/".to_string());
            }
            if let Some(n) = sequence {
                parts.push(format!("N{n}"));
            }
            parts.extend(words);
            parts.join(separator)
        })
}

fn osp_block() -> impl Strategy<Value = String> {
    (prop::option::of("N[0-9]{4}|N[A-Z][A-Z0-9]{0,3}"), prop::collection::vec(osp_word(), 0..6), any::<bool>())
        .prop_map(|(sequence, words, continued)| {
            let mut parts: Vec<String> = sequence.into_iter().collect();
            parts.extend(words);
            let mut block = parts.join(" ");
            if continued {
                block.push_str("\n$ XB=40 DB=1");
            }
            block
        })
}

/// Text made of the characters that matter to the grammar, in any order.
fn noise() -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec(prop::sample::select(b"GXZNOV0123456789.-+[]#=()$;/% \tAIFLT}\x00\x93\xe9".to_vec()), 0..40)
}

pub fn line() -> impl Strategy<Value = Vec<u8>> {
    prop_oneof![
        4 => fanuc_block().prop_map(String::into_bytes),
        4 => osp_block().prop_map(String::into_bytes),
        2 => noise(),
        1 => prop::collection::vec(any::<u8>().prop_filter("no line break", |b| *b != b'\n' && *b != b'\r'), 0..30),
        1 => Just(b"%".to_vec()),
        1 => Just(b"$PROG.MIN%".to_vec()),
    ]
}

pub fn program() -> impl Strategy<Value = Vec<u8>> {
    (prop::collection::vec((line(), prop::sample::select(vec!["\n", "\r\n", "\r"])), 0..25), any::<bool>()).prop_map(
        |(lines, final_terminator)| {
            let mut out = Vec::new();
            let count = lines.len();
            for (i, (line, ending)) in lines.into_iter().enumerate() {
                out.extend_from_slice(&line);
                if i + 1 < count || final_terminator {
                    out.extend_from_slice(ending.as_bytes());
                }
            }
            out
        },
    )
}

pub fn options() -> impl Strategy<Value = ParseOptions> {
    (
        prop::sample::select(vec![
            DialectChoice::Auto,
            DialectChoice::Fixed(Dialect::Osp),
            DialectChoice::Fixed(Dialect::Fanuc),
        ]),
        prop::sample::select(vec![GCodeSystem::A, GCodeSystem::B, GCodeSystem::C]),
    )
        .prop_map(|(dialect, gcode_system)| ParseOptions {
            dialect,
            gcode_system,
            machine_kind: None,
            control: Default::default(),
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn parse_then_print_is_the_identity(source in program(), options in options()) {
        let parsed = parse(&source, &options);
        check_spans(&parsed);
        prop_assert_eq!(print(&parsed.program, &Edits::new()), source);
    }

    #[test]
    fn canonical_form_is_idempotent_and_clean(source in program(), options in options()) {
        let parsed = parse(&source, &options);
        let canonical_options = CanonicalOptions { decimal_input: Default::default(), increment_places: 3 };
        let canonical = print_canonical(&parsed.program, &canonical_options);
        // The normal form is for the machine the input was read for; weak detection
        // evidence (a packed `N99POPEN`) may disappear from it.
        let same_machine = ParseOptions {
            dialect: DialectChoice::Fixed(parsed.detection.dialect),
            machine_kind: Some(parsed.detection.machine_kind),
            ..options
        };
        let reparsed = parse(&canonical, &same_machine);
        check_spans(&reparsed);
        if parsed.error_count() == 0 {
            prop_assert_eq!(reparsed.error_count(), 0, "{}", String::from_utf8_lossy(&canonical));
            prop_assert_eq!(print_canonical(&reparsed.program, &canonical_options), canonical);
        }
    }
}
