//! Write an example thermal log (`t_min,value`), one sample every 10 s, with seeded noise
//! (so each file is the same every time):
//!
//! * no argument: `examples/data/z-growth-log.csv`, the Z growth of the thesis lathe's
//!   spindle head, in mm, over four hours of warm-up at 1000 rpm and four of cool-down, on
//!   the first-order curves of the thesis' eq. 5.3–5.4 (τ 54.59 min warm, 81.97 min cool),
//!   scaled to 12 µm of growth, with 0.2 µm of gauge noise;
//! * `warm-up-only`: the same spindle warming up for six hours and no cool-down, the last
//!   two within 1.2 % of equilibrium (`tests/cases/diagnose/thermal/warm-up-only.csv`);
//! * `z-slide`: the thesis' Z slide temperature, in °F, over four hours of traverse at
//!   2.54 m/min and four of rest, on its eq. 5.5–5.6 (gain 6.12 °F, τ 92.59 min warm; 5.01 °F,
//!   τ 95.24 min cool), with 0.15 °F of noise (`tests/cases/diagnose/thermal/z-slide.csv`).
//!
//! `cargo run --example thermal_log [-- warm-up-only | z-slide] > FILE`
use std::fmt::Write as _;

use turnpass::diagnose::noise::Noise;

/// A first-order curve: gain, τ (minutes), offset.
type Curve = (f64, f64, f64);

/// `warm` for `minutes`, then (with `cool`) as long again cooling, from `warm`'s value at
/// the switch (its own gain when `continuous` is false, as the thesis fits each phase).
fn log(warm: Curve, cool: Option<(Curve, bool)>, minutes: u32, sigma: f64, seed: u64) -> String {
    let mut noise = Noise::new(seed);
    let mut out = String::from("t_min,value\n");
    let steps = minutes * 6;
    for step in 0..=steps {
        let t = f64::from(step) / 6.0;
        let y = warm.0 * (1.0 - (-t / warm.1).exp()) + warm.2 + noise.normal(sigma);
        let _ = writeln!(out, "{t:.4},{y:.7}");
    }
    let Some((cool, continuous)) = cool else { return out };
    let gain = if continuous { warm.0 * (1.0 - (-f64::from(minutes) / warm.1).exp()) } else { cool.0 };
    for step in 1..=steps {
        let t = f64::from(step) / 6.0;
        let y = gain * (-t / cool.1).exp() + cool.2 + noise.normal(sigma);
        let _ = writeln!(out, "{:.4},{y:.7}", f64::from(minutes) + t);
    }
    out
}

fn main() {
    let spindle = (0.012, 54.59, 0.0015);
    let out = match std::env::args().nth(1).as_deref() {
        None => log(spindle, Some(((0.0, 81.97, 0.0015), true)), 240, 0.0002, 5459),
        Some("warm-up-only") => log(spindle, None, 360, 0.0002, 5459),
        Some("z-slide") => log((6.12, 92.59, 64.53), Some(((5.01, 95.24, 65.28), false)), 240, 0.15, 9259),
        Some(other) => {
            eprintln!("thermal_log: unknown log `{other}` (warm-up-only or z-slide)");
            std::process::exit(2);
        }
    };
    print!("{out}");
}
