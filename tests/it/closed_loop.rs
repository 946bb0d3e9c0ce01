//! The closed loop on simulation: the thesis' two programs (clean versions) compensated for
//! a model with several effects (`examples/machines/thesis-several-effects.toml`), every
//! strategy, then `verify`: the predicted RMS deviation from the nominal part before and
//! after. `arcs` and `densify` must cut it by 90 % or bring it to the quantisation floor,
//! increment/√12, where that is higher (these programs are in inch: 0.0001 in gives
//! 0.733 µm, 15 % of their uncompensated deviation, so the floor is what they can reach).
//!
//! `cargo test --release --test it closed_loop -- --nocapture` prints the table the README
//! quotes.

use std::process::Command;

use crate::support::repo;

const MODEL: &str = "examples/machines/thesis-several-effects.toml";
const PROGRAMS: [&str; 2] = ["examples/programs/thesis-o2005-arc.nc", "examples/programs/thesis-o2012-turn-face.nc"];
const STRATEGIES: [&str; 6] = ["auto", "circle", "semicircle", "quadrant", "arcs", "densify"];
/// The thesis programs' least increment, 0.0001 in, over √12.
const FLOOR_MM: f64 = 0.00254 / 3.464_101_615_137_754_6;

fn run(args: &[&str]) -> (i32, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_turnpass")).args(args).current_dir(repo()).output().unwrap();
    (output.status.code().unwrap(), String::from_utf8_lossy(&output.stdout).into_owned())
}

#[test]
fn compensation_brings_the_predicted_deviation_down_to_the_floor() {
    let dir = std::env::temp_dir().join(format!("turnpass-closed-loop-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut table = String::from(
        "| program | strategy | tolerance | RMS before µm | RMS after µm | max after µm | improvement |\n|---|---|---|---|---|---|---|\n",
    );
    for program in PROGRAMS {
        for strategy in STRATEGIES {
            for tolerance in [None, Some("0.0003")] {
                let out = dir.join("compensated.nc");
                let out = out.to_str().unwrap();
                let mut args = vec!["compensate", program, "--model", MODEL, "--strategy", strategy, "-o", out];
                if let Some(t) = tolerance {
                    args.extend(["--tolerance", t]);
                }
                assert_eq!(run(&args).0, 0, "{program} {strategy}");
                let (code, json) = run(&["verify", program, out, "--model", MODEL, "--format", "json"]);
                assert!(code == 0 || code == 1, "{json}");
                let value: serde_json::Value = serde_json::from_str(&json).unwrap();
                assert_eq!(value["violations"].as_array().map(Vec::len), Some(0), "{program} {strategy}: words lost");
                let deviation = &value["deviation"];
                let before = deviation["before"]["rms_mm"].as_f64().unwrap();
                let after = deviation["after"]["rms_mm"].as_f64().unwrap();
                let max = deviation["after"]["max_mm"].as_f64().unwrap();
                let improvement = deviation["improvement_percent"].as_f64().unwrap();
                assert!(after < before, "{program} {strategy}: {after} ≥ {before}");
                if tolerance.is_some() && (strategy == "arcs" || strategy == "densify") {
                    let target = (0.1 * before).max(FLOOR_MM);
                    assert!(after <= target, "{program} {strategy}: RMS {after} above {target}");
                }
                let name = program.rsplit('/').next().unwrap();
                table.push_str(&format!(
                    "| {name} | {strategy} | {} | {:.2} | {:.2} | {:.2} | {improvement:.1} % |\n",
                    tolerance.map_or("default (1.27 µm)".to_string(), |t| format!(
                        "{} µm",
                        t.parse::<f64>().unwrap() * 1000.0
                    )),
                    before * 1000.0,
                    after * 1000.0,
                    max * 1000.0
                ));
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    eprintln!("quantisation floor {:.3} µm\n{table}", FLOOR_MM * 1000.0);
}
