#![allow(clippy::disallowed_methods, clippy::unwrap_used)]
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let mut best = f64::MAX;
    for _ in 0..7 {
        let start = std::time::Instant::now();
        let e = turnpass::dialect::detect::scan(&bytes);
        std::hint::black_box(e);
        best = best.min(start.elapsed().as_secs_f64());
    }
    println!("scan: {:.1} ms, {:.0} MB/s", best * 1e3, bytes.len() as f64 / 1e6 / best);
}
