//! `turnpass fit-thermal LOG.csv [--write-model M --axis x|z]`: the first-order warm-up and
//! cool-down curves of a thermal log (eq. 5.1–5.2 of the thesis), with standard errors;
//! the warm-up can be written into a model as `thermal_x` or `thermal_z`.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use turnpass::diagnose::measured::read_thermal_log;
use turnpass::diagnose::model_text::effect_table;
use turnpass::diagnose::report::value_with_sigma;
use turnpass::diagnose::thermal_fit::{FirstOrderFit, Split, fit_log_split};
use turnpass::error_model::Effect;
use turnpass::error_model::effects::{ThermalX, ThermalZ, X, Z};

use super::common::{
    AxisArg, CliError, Format, data_invalid, display_name, model_problems, model_spec, read_data_text, read_input_text,
    read_table, write_file, write_output,
};
use super::numbers::{self, within};
use super::streams;

#[derive(Args)]
pub struct FitThermalArgs {
    /// The log (CSV `t_min,value`): a warm-up, then (optionally) a cool-down.
    pub log: PathBuf,
    /// Append the warm-up curve to this model file (created if missing) as an [[effect]]
    /// of the axis --axis names; the log's values are then millimetres of growth.
    #[arg(long, value_name = "M", requires = "axis")]
    pub write_model: Option<PathBuf>,
    /// The axis the logged growth is along.
    #[arg(long, value_enum)]
    pub axis: Option<AxisArg>,
    /// Minutes from the start of the log at which the heat source stopped and the
    /// cool-down began (default: where the fit of both curves is best, or nowhere when the
    /// log has no cool-down).
    #[arg(long, allow_negative_numbers = true, value_name = "MIN", value_parser = within(numbers::MINUTES))]
    pub split_min: Option<f64>,
    #[arg(long, value_enum, default_value = "human")]
    pub format: Format,
}

fn curve(f: &FirstOrderFit) -> String {
    format!(
        "gain {}, τ {} min, offset {}; RMS {:.4} over {} samples",
        value_with_sigma(f.gain, Some(f.gain_sigma)),
        value_with_sigma(f.tau_min, Some(f.tau_sigma)),
        value_with_sigma(f.offset, Some(f.offset_sigma)),
        f.rms,
        f.samples
    )
}

pub fn run(args: FitThermalArgs) -> Result<ExitCode, CliError> {
    let name = display_name(&args.log);
    let text = read_data_text(&args.log)?;
    let (t, y) = read_thermal_log(&text).map_err(|e| data_invalid(&name, &text, e, "fit-thermal"))?;
    let fit = fit_log_split(&t, &y, args.split_min).map_err(|e| CliError::Data(format!("{name}: {e}")))?;
    let out = match args.format {
        Format::Json => serde_json::to_string_pretty(&fit).unwrap_or_default() + "\n",
        Format::Human => {
            let split = match fit.split {
                Split::Given => format!("warm-up until {:.1} min (given)", fit.split_min),
                Split::Fitted => format!("warm-up until {:.1} min (fitted)", fit.split_min),
                Split::None => format!("warm-up over the whole log ({:.1} min)", fit.split_min),
            };
            let mut out = format!("fit-thermal: {name}: {split}\n");
            out.push_str(&format!("  warm-up   (gain·(1 − e^(−t/τ)) + offset): {}\n", curve(&fit.warm)));
            match (&fit.cool, &fit.no_cool_down) {
                (Some(cool), _) => {
                    out.push_str(&format!("  cool-down (gain·e^(−t/τ) + offset):       {}\n", curve(cool)))
                }
                (None, Some(why)) => out.push_str(&format!("  no cool-down in the log: {why}\n")),
                (None, None) => out.push_str("  no cool-down in the log\n"),
            }
            out
        }
    };
    write_output(None, out.as_bytes())?;
    let (Some(path), Some(axis)) = (&args.write_model, args.axis) else { return Ok(ExitCode::SUCCESS) };
    let (amp, tau_min) = (fit.warm.gain, fit.warm.tau_min);
    let effect = match axis {
        AxisArg::X => Effect::ThermalX(ThermalX { amp, tau_min, axis: X }),
        AxisArg::Z => Effect::ThermalZ(ThermalZ { amp, tau_min, axis: Z }),
    };
    let original = match read_input_text(path) {
        Ok(text) => text,
        Err(CliError::Read { source, .. }) if source.kind() == std::io::ErrorKind::NotFound => String::new(),
        Err(error) => return Err(error),
    };
    let (spec, _) = model_spec(path, &original)?;
    if spec.effect.iter().any(|e| e.name() == effect.name()) {
        return Err(CliError::Usage(format!(
            "{} already has a {} effect: remove it, or write to another model file",
            path.display(),
            effect.name()
        )));
    }
    let mut written = original;
    if !written.is_empty() && !written.ends_with('\n') {
        written.push('\n');
    }
    if !written.is_empty() {
        written.push('\n');
    }
    written.push_str(&format!(
        "# Added by `turnpass fit-thermal` from {name}: the warm-up curve, amp {} mm, τ {} min\n\
         # (± one standard uncertainty); its offset {} is the cold reading, not growth.\n",
        value_with_sigma(fit.warm.gain, Some(fit.warm.gain_sigma)),
        value_with_sigma(fit.warm.tau_min, Some(fit.warm.tau_sigma)),
        value_with_sigma(fit.warm.offset, Some(fit.warm.offset_sigma)),
    ));
    if let Some(cool) = &fit.cool {
        written.push_str(&format!(
            "# The cool-down (τ {} min) is not in the model: its thermal effects are warm-up curves.\n",
            value_with_sigma(cool.tau_min, Some(cool.tau_sigma))
        ));
    }
    written.push_str(&effect_table(&effect));
    // The written model must load: the fitted curve is checked against its ranges.
    let (spec, dir) = model_spec(path, &written)?;
    spec.build(|file| read_table(&dir, file)).map_err(|e| model_problems(path, &written, e))?;
    write_file(path, written.as_bytes())?;
    streams::err_line(format_args!("fit-thermal: wrote {} into {}", effect.name(), path.display()));
    Ok(ExitCode::SUCCESS)
}
