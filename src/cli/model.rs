//! `turnpass model report M`: the ISO 230-2 figures of a model's slide tables and its
//! parametric effects.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Subcommand};

use turnpass::error_model::report::report;

use super::common::{
    CliError, Format, model_problems, model_spec, read_input_text, read_table, rendered, write_output,
};
use super::streams;

#[derive(Subcommand)]
pub enum ModelCommand {
    /// ISO 230-2 figures per slide table (A, E, M, B, R, mean reversal) and the effects.
    Report(ReportArgs),
}

#[derive(Args)]
pub struct ReportArgs {
    /// The machine model file (TOML).
    pub model: PathBuf,
    #[arg(long, value_enum, default_value = "human")]
    pub format: Format,
}

pub fn run(command: ModelCommand) -> Result<ExitCode, CliError> {
    match command {
        ModelCommand::Report(args) => {
            let path = &args.model;
            let text = read_input_text(path)?;
            let (spec, dir) = model_spec(path, &text)?;
            let report = report(&spec, |file| read_table(&dir, file)).map_err(|e| model_problems(path, &text, e))?;
            let (_, warnings) =
                spec.build_with_warnings(|file| read_table(&dir, file)).map_err(|e| model_problems(path, &text, e))?;
            streams::err(rendered(&path.display().to_string(), text.as_bytes(), &warnings));
            let out = match args.format {
                Format::Human => format!("machine model {}\n{report}", path.display()),
                Format::Json => serde_json::to_string_pretty(&report).unwrap_or_default() + "\n",
            };
            write_output(None, turnpass::source::escape_controls(&out).as_bytes())?;
            Ok(ExitCode::SUCCESS)
        }
    }
}
