//! Write the example thermal log `examples/data/z-growth-log.csv` (`t_min,value`): the Z
//! growth of the thesis lathe's spindle head, in mm, logged every 10 s over four hours of
//! warm-up at 1000 rpm and four of cool-down, on the first-order curves of the thesis'
//! eq. 5.3–5.4 (τ 54.59 min warm, 81.97 min cool), scaled to 12 µm of growth, with 0.2 µm
//! of gauge noise (seeded, so the file is the same every time).
//!
//! `cargo run --example thermal_log > examples/data/z-growth-log.csv`
use std::fmt::Write as _;

use turnpass::diagnose::noise::Noise;

fn main() {
    let (gain, warm_tau, cool_tau, offset) = (0.012, 54.59, 81.97, 0.0015);
    let mut noise = Noise::new(5459);
    let mut out = String::from("t_min,value\n");
    for step in 0..=240 * 6 {
        let t = f64::from(step) / 6.0;
        let y = gain * (1.0 - (-t / warm_tau).exp()) + offset + noise.normal(0.0002);
        let _ = writeln!(out, "{t:.4},{y:.7}");
    }
    let peak = gain * (1.0 - (-240.0 / warm_tau).exp());
    for step in 1..=240 * 6 {
        let t = f64::from(step) / 6.0;
        let y = peak * (-t / cool_tau).exp() + offset + noise.normal(0.0002);
        let _ = writeln!(out, "{:.4},{y:.7}", 240.0 + t);
    }
    print!("{out}");
}
