//! `turnpass verify ORIGINAL COMPENSATED`: the compensated program predicted on the model
//! against the original's nominal part, and its non-motion words against the original's.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use turnpass::compensation::program::SAMPLE_STEP_MM;
use turnpass::compensation::verify::{check_words, deviation};
use turnpass::semantic::nose_radius::ToolTable;
use turnpass::source::LineIndex;

use super::common::{
    CliError, Format, ReadArgs, RunArgs, display_name, model_source, read_program, read_program_bytes, ready,
    required_error_model, write_output,
};
use super::numbers::{self, within};
use super::streams;

#[derive(Args)]
pub struct VerifyArgs {
    /// The program as written for the part.
    pub original: PathBuf,
    /// The compensated program.
    pub compensated: PathBuf,
    /// Fail when the predicted deviation from the nominal part exceeds MM (default: twice
    /// the least increment).
    #[arg(long, allow_negative_numbers = true, value_name = "MM", value_parser = within(numbers::MAX_DEVIATION_MM))]
    pub max_deviation: Option<f64>,
    #[arg(long, value_enum, default_value = "human")]
    pub format: Format,
    #[command(flatten)]
    pub read: ReadArgs,
    #[command(flatten)]
    pub run: RunArgs,
    /// Also say where the machine settings and the model come from.
    #[arg(long, short)]
    pub verbose: bool,
}

pub fn verify(args: VerifyArgs) -> Result<ExitCode, CliError> {
    // Both programs run on the machine the original's settings name.
    let (original_bytes, resolved) = read_program(&args.original, &args.read)?;
    let compensated_bytes = read_program_bytes(&args.compensated)?;
    let model = required_error_model(&resolved, "verify")?;
    let (original_name, compensated_name) = (display_name(&args.original), display_name(&args.compensated));
    let mut messages = Vec::new();
    if args.verbose {
        messages.extend_from_slice(format!("verify: {}\n", model_source(&args.read, &resolved)).as_bytes());
    }
    let original = ready(&original_name, &original_bytes, &resolved, &args.run, "verify", &mut messages);
    let compensated = ready(&compensated_name, &compensated_bytes, &resolved, &args.run, "verify", &mut messages);
    let (original, compensated) = match (original, compensated) {
        (Ok(o), Ok(c)) => (o, c),
        (o, c) => {
            for text in [o.err(), c.err()].into_iter().flatten() {
                messages.extend(text);
            }
            streams::err(messages);
            return Ok(ExitCode::from(1));
        }
    };
    streams::err(messages);
    let tools = ToolTable::from_machine(&original.machine);
    let figures = deviation(&original.valid(), &compensated.valid(), &tools, &model, SAMPLE_STEP_MM);
    let words = check_words(&original.parsed.program, &compensated.parsed.program);
    let machine = &original.machine;
    let limit = args.max_deviation.unwrap_or(2.0 * machine.increment * machine.scale());
    let mut violations = Vec::new();
    if let Some(missing) = &words.missing {
        let line = LineIndex::new(&original_bytes).position(missing.span.start).0;
        violations.push(format!(
            "{compensated_name} lost `{}` ({original_name} line {line}), or has it out of order",
            missing.text
        ));
    }
    if figures.after.max_mm > limit {
        violations.push(format!(
            "the predicted deviation of {compensated_name} from the nominal part reaches {:.5} mm, more than {limit:.5} mm",
            figures.after.max_mm
        ));
    }
    let text = match args.format {
        Format::Json => {
            let value = serde_json::json!({
                "original": original_name,
                "compensated": compensated_name,
                "deviation": figures,
                "max_deviation_mm": limit,
                "words_checked": words.checked,
                "violations": violations,
            });
            serde_json::to_string_pretty(&value).unwrap_or_default() + "\n"
        }
        Format::Human => {
            let row = |label: &str, f: &turnpass::compensation::deviation::Figures| {
                format!("  {label:<16} {:>10.5} {:>10.5} {:>10.5} {:>8}\n", f.max_mm, f.rms_mm, f.ssq_mm, f.points)
            };
            let mut text = format!("predicted deviation from the nominal part of {original_name}, mm:\n");
            text.push_str(&format!("  {:<16} {:>10} {:>10} {:>10} {:>8}\n", "", "max", "RMS", "SSQ", "points"));
            text.push_str(&row("as programmed", &figures.before));
            text.push_str(&row("compensated", &figures.after));
            text.push_str(&format!("  RMS improvement: {:.1} %\n", figures.improvement_percent));
            text.push_str(&format!("non-motion words: {} checked\n", words.checked));
            for violation in &violations {
                text.push_str(&format!("violation: {violation}\n"));
            }
            if violations.is_empty() {
                text.push_str("ok\n");
            }
            text
        }
    };
    write_output(None, text.as_bytes())?;
    Ok(if violations.is_empty() { ExitCode::SUCCESS } else { ExitCode::from(1) })
}
