//! The numbers the command line takes: each flag's plausible range, and the one clap value
//! parser that checks a value against its range when it is read (a NaN, an infinity or an
//! absurd size is refused with exit 2 before any work; `turnpass::bounds`). A flag that
//! stands for a value of the model file (`--start-min`, `--parts`) takes that value's range.

use turnpass::bounds::Range;
use turnpass::error_model::model_file::START_MIN;

/// `compensate --tolerance`: more than nothing, at most 1 mm (a part held to a millimetre
/// needs no compensation).
pub const TOLERANCE_MM: Range = Range::positive(1.0, "mm");

/// `compensate --step` (densify): from 0.0001 mm, the finest least increment of a lathe
/// control, to 100 mm.
pub const STEP_MM: Range = Range::closed(0.0001, 100.0, "mm");

/// `compensate --max-shift`: more than nothing, at most 10 mm (a correction that large is a
/// wrong model, which the guard is there to catch).
pub const MAX_SHIFT_MM: Range = Range::positive(10.0, "mm");

/// `verify --max-deviation`: more than nothing, at most 10 mm.
pub const MAX_DEVIATION_MM: Range = Range::positive(10.0, "mm");

/// `synth --noise`, a gauge's standard deviation: from 0 to 1 mm.
pub const NOISE_MM: Range = Range::closed(0.0, 1.0, "mm");

/// `synth --glitch-mm`, the size of a probe's glitch: within ±1 mm.
pub const GLITCH_MM: Range = Range::magnitude(1.0, "mm");

/// `synth --spacing`, between CMM points: from 0.001 to 1,000 mm.
pub const SPACING_MM: Range = Range::closed(0.001, 1_000.0, "mm");

/// `synth --step-deg`, between ball bar rows: from 0.001 to 360 degrees.
pub const STEP_DEG: Range = Range::closed(0.001, 360.0, "degrees");

/// `synth --targets`, positions along a slide: within ±100,000 mm.
pub const TARGET_MM: Range = Range::magnitude(100_000.0, "mm");

/// `--start-min`, `--parts`, `fit-thermal --split-min`: minutes since a start, as the
/// model file's `start_min`.
pub const MINUTES: Range = START_MIN;

/// The value parser of a flag whose values must lie in `range`.
pub fn within(range: Range) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    move |text: &str| range.parse(text)
}

/// `table --x`, `--z`, `--zero`: positions of the machine, as the model file's `[machine]`
/// gives them (`home`, `travel`).
pub const POSITION: Range = turnpass::machine::POSITION;

/// `table --detection-unit`: a control's least step of a correction, from 0.000001 to 0.01
/// machine units, as a least increment.
pub const DETECTION_UNIT: Range = turnpass::machine::LEAST_INCREMENT;
