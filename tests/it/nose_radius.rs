//! Nose-radius compensation through the whole semantic pass: generated Fanuc programs with
//! a compensated finishing pass outside any cycle, then G71 and G70 over a profile that
//! switches G42 on and off itself. Corner arcs inserted by compensation must leave every
//! cycle's expansion holding exactly that cycle's moves, and the toolpath valid.

use proptest::prelude::*;
use turnpass::pipeline::Settings;
use turnpass::semantic::LowerOptions;

use crate::simulate::{parse_options, settings_for};
use crate::support::{analyse, ready, repo};

/// One step of an outside profile toward the chuck: along -Z, up a face, or a chamfer up
/// and along, in whole tenths of a millimetre (X as a diameter).
fn step() -> impl Strategy<Value = (u32, u32)> {
    prop_oneof![(Just(0u32), 20u32..150), (20u32..80, Just(0u32)), (20u32..80, 20u32..80)]
}

/// The profile blocks from diameter 20 at Z0, numbered from N100 by tens, G42 on in the
/// first and G40 in the last. The steps end with a face up and a cut along -Z, so there is
/// at least one outside corner. Returns the blocks, the last sequence number and the
/// largest diameter.
fn profile(steps: &[(u32, u32)]) -> (String, u32, f64) {
    let (mut x, mut z) = (200u32, 0u32);
    let mut out = String::from("N100 G00 G42 X20.\nN110 G01 Z0. F0.1\n");
    let mut n = 110;
    for &(dx, dz) in steps.iter().chain([(20, 0), (0, 50)].iter()) {
        x += dx;
        z += dz;
        n += 10;
        out.push_str(&format!("N{n} X{:.1} Z-{:.1}\n", x as f64 / 10.0, z as f64 / 10.0));
    }
    n += 10;
    let top = (x + 40) as f64 / 10.0;
    out.push_str(&format!("N{n} G40 X{top:.1}\n"));
    (out, n, top)
}

fn program(plain: &[(u32, u32)], cycle: &[(u32, u32)]) -> String {
    let (pass, _, pass_top) = profile(plain);
    let (contour, last, cycle_top) = profile(cycle);
    let top = pass_top.max(cycle_top) + 4.0;
    // The same kind of pass outside any cycle, without sequence numbers.
    let pass = pass.lines().map(|l| l.split_once(' ').map_or(l, |(_, rest)| rest)).collect::<Vec<_>>().join("\n");
    format!(
        "%\nO0200\nG21 G99\nT0101\nG96 S150 M03\nG00 X{top:.1} Z5.\n{pass}\nG00 X{top:.1} Z5.\n\
         G71 U1. R0.5\nG71 P100 Q{last} U0.4 W0.1 F0.25\n{contour}G70 P100 Q{last}\nG00 X200. Z100.\nM30\n%\n"
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn corner_arcs_keep_every_expansion_on_its_own_moves(
        plain in prop::collection::vec(step(), 1..6),
        cycle in prop::collection::vec(step(), 1..6),
    ) {
        let source = program(&plain, &cycle);
        let case = repo().join("tests/cases/simulate/fanuc/nose-radius-g70-g42.nc");
        let settings = settings_for(&case);
        let with = |lower| Settings::new(parse_options(&settings), &settings, lower);
        // No error anywhere, and the toolpath validates.
        let compensated = analyse(source.as_bytes(), &with(LowerOptions::new(false)))
            .ready()
            .map_err(|analysed| TestCaseError::fail(format!("{source}\n{:?}", analysed.diagnostics)))?;
        let (parsed, lowered) = (&compensated.parsed, &compensated.lowered);
        let plain = LowerOptions { nose_radius_compensation: false, ..LowerOptions::new(false) };
        let plain_lowered = ready(source.as_bytes(), &with(plain)).lowered;
        // The outside corners (a face up, then along -Z) gain their arcs.
        prop_assert!(lowered.toolpath.moves.len() > plain_lowered.toolpath.moves.len());
        prop_assert_eq!(lowered.expansions.len(), 2);
        for expansion in &lowered.expansions {
            let span = parsed.program.block(expansion.block).span;
            let moves = &lowered.toolpath.moves[expansion.moves.clone()];
            prop_assert!(!moves.is_empty());
            prop_assert!(moves.iter().all(|m| m.cycle == span), "{source}");
            let count = lowered.toolpath.moves.iter().filter(|m| m.cycle == span).count();
            prop_assert_eq!(count, moves.len());
        }
    }
}
