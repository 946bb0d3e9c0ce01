//! What the benches share: the generated programs and medians of timed runs.

#![allow(dead_code)]

use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

/// `target/bench-data/`, where the benches keep their inputs.
pub fn data_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/bench-data");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `python3 ../shared/bench/gen_lathe.py target/bench-data/big-<megabytes>.nc <megabytes>`,
/// generated on first use.
pub fn generated(megabytes: &str) -> Vec<u8> {
    let path = data_dir().join(format!("big-{megabytes}.nc"));
    if !path.exists() {
        let script = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/bench/gen_lathe.py");
        assert!(
            script.is_file(),
            "the bench input generator is read in place from {}; it is missing",
            script.display()
        );
        let status = Command::new("python3").arg(&script).arg(&path).arg(megabytes).status().expect("python3 runs");
        assert!(status.success(), "gen_lathe.py failed");
    }
    std::fs::read(&path).unwrap()
}

/// `bytes` through the library's pipeline (`pipeline::analyse`: parse, lower, validate), ready
/// for the passes after lowering: how every bench that runs a program past lowering enters.
pub fn ready<'b>(bytes: &'b [u8], settings: &turnpass::pipeline::Settings) -> turnpass::pipeline::Ready<'b> {
    match turnpass::pipeline::analyse(bytes, settings).ready() {
        Ok(ready) => ready,
        Err(analysed) => panic!("the bench program has errors: {:?}", analysed.diagnostics.first()),
    }
}

/// The median of `times`.
pub fn median(times: &mut [f64]) -> f64 {
    times.sort_by(|a, b| a.total_cmp(b));
    times[times.len() / 2]
}

/// The median of `rounds` timed runs, in seconds.
pub fn median_seconds(mut run: impl FnMut(), rounds: usize) -> f64 {
    let mut times: Vec<f64> = (0..rounds)
        .map(|_| {
            let start = Instant::now();
            run();
            start.elapsed().as_secs_f64()
        })
        .collect();
    median(&mut times)
}
