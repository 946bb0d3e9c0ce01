//! `turnpass table MODEL --control linuxcnc|fanuc|okuma -o OUT`: the part of a machine model
//! the control's own axis compensation carries, in the control's format; and
//! `--with-table FILE` of `compensate`, `verify`, `report` and `plot`: the machine with such
//! a table loaded (`turnpass::control_table`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, ValueEnum};

use turnpass::compensation::provenance::{SHA256_DIGITS, model_sha256};
use turnpass::control_table::{self, Control, Header, Loaded, Options, ReadError};
use turnpass::diagnostic::{Diagnostic, DiagnosticKind};
use turnpass::error_model::ErrorModel;
use turnpass::error_model::control::TablePart;
use turnpass::error_model::model_file::ModelSpec;
use turnpass::machine::{MachineSettings, Units};
use turnpass::semantic::Machine;
use turnpass::toolpath::Xz;

use super::common::{
    CliError, check_output, display_name, folder_of, load_error_model, read_input, rendered, write_file,
};
use super::numbers::{self, within};
use super::streams;

#[derive(Args)]
pub struct TableArgs {
    /// The machine model file (TOML).
    pub model: PathBuf,
    /// The control whose tables to write: linuxcnc (INI keys and a compensation file per
    /// joint), fanuc (a parameter tape; unverified), okuma (plain rows to key in).
    #[arg(long, value_enum)]
    pub control: ControlArg,
    /// The file to write: LinuxCNC's INI keys (its compensation files go beside it, NAME-x.comp
    /// and NAME-z.comp), the Fanuc tape, or the Okuma rows.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// The units of the table (default: the model's [machine] units, else mm).
    #[arg(long, value_enum)]
    pub units: Option<UnitsArg>,
    /// LinuxCNC's COMP_FILE_TYPE: 0 (nominal, forward and reverse positions) or 1 (nominal and
    /// the corrections added moving forward and in reverse).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(0..=1))]
    pub comp_file_type: u8,
    /// The X travel the table covers, machine units, X as programmed (default: the model's
    /// [machine] travel).
    #[arg(long, value_name = "LO,HI", allow_hyphen_values = true, value_parser = pair)]
    pub x: Option<(f64, f64)>,
    /// The Z travel the table covers, machine units (default: the model's [machine] travel).
    #[arg(long, value_name = "LO,HI", allow_hyphen_values = true, value_parser = pair)]
    pub z: Option<(f64, f64)>,
    /// Where the machine coordinates' zero lies in the program's coordinates, machine units,
    /// X as programmed (default: the model's [machine] home, the reference position; else the
    /// program's zero).
    #[arg(long, value_name = "X,Z", allow_hyphen_values = true, value_parser = pair)]
    pub zero: Option<(f64, f64)>,
    /// The spacing of the table's nodes, mm (default: as wide as follows the model within the
    /// tolerance, and within the control's count of nodes).
    #[arg(long, value_name = "MM", value_parser = within(numbers::SPACING_MM))]
    pub spacing: Option<f64>,
    /// How closely the table follows the model between its nodes, mm (default: half the
    /// least increment).
    #[arg(long, allow_negative_numbers = true, value_name = "MM", value_parser = within(numbers::TOLERANCE_MM))]
    pub tolerance: Option<f64>,
    /// The control's least step of a correction, machine units: a Fanuc's detection unit,
    /// the rows' rounding for an Okuma (default: the least increment).
    #[arg(long, value_name = "UNIT", value_parser = within(numbers::DETECTION_UNIT))]
    pub detection_unit: Option<f64>,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum ControlArg {
    Linuxcnc,
    Fanuc,
    Okuma,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum UnitsArg {
    Mm,
    Inch,
}

/// `A,B`: two finite numbers.
fn pair(text: &str) -> Result<(f64, f64), String> {
    let (a, b) = text.split_once(',').ok_or_else(|| format!("`{text}` is not two numbers A,B"))?;
    let number = |t: &str| numbers::POSITION.parse(t.trim()).map_err(|e| format!("`{}`: {e}", t.trim()));
    Ok((number(a)?, number(b)?))
}

pub fn run(args: TableArgs) -> Result<ExitCode, CliError> {
    check_output(Some(&args.output))?;
    let path = &args.model;
    let text =
        std::fs::read_to_string(path).map_err(|source| CliError::Read { path: path.display().to_string(), source })?;
    let model = load_error_model(path, &text)?;
    let (spec, _) = super::common::model_spec(path, &text)?;
    // Only a slide table whose linear column the control's table would carry matters.
    let has_linear = |axis: char| {
        model.tables.as_ref().is_some_and(|t| if axis == 'X' { t.x.linear.is_some() } else { t.z.linear.is_some() })
    };
    let taken: Vec<Taken> = how_taken(&spec).into_iter().filter(|t| has_linear(t.axis)).collect();
    if let Some(on) = taken.iter().find(|t| t.on) {
        return Err(CliError::Usage(format!(
            "table: the {} slide table of {} was taken with the control's {} compensation on: it holds what the \
             control's loaded table leaves, not the slide's error, and a table made of it would replace the loaded \
             one with that remainder; take the table with the compensation off ({} = \"off\") for the control's \
             table, or compensate the programs with this model as it is",
            on.axis,
            path.display(),
            on.what,
            on.key
        )));
    }
    let settings = turnpass::machine::ModelFile::from_toml(&text).map(|f| f.machine).unwrap_or_default();
    let machine = Machine::from_settings(&settings);
    let units = match args.units {
        Some(UnitsArg::Mm) => Units::Mm,
        Some(UnitsArg::Inch) => Units::Inch,
        None => machine.units,
    };
    let control = match args.control {
        ControlArg::Linuxcnc => Control::Linuxcnc,
        ControlArg::Fanuc => Control::Fanuc,
        ControlArg::Okuma => Control::Okuma,
    };
    // Positions as the [machine] table writes them: machine units, X as programmed.
    let x_mm = |x: f64| if machine.diameter_programming { x / 2.0 } else { x } * machine.scale();
    let z_mm = |z: f64| z * machine.scale();
    let range = [
        args.x
            .map(|(a, b)| (x_mm(a).min(x_mm(b)), x_mm(a).max(x_mm(b))))
            .or(machine.limits.map(|l| (l.x_min, l.x_max))),
        args.z
            .map(|(a, b)| (z_mm(a).min(z_mm(b)), z_mm(a).max(z_mm(b))))
            .or(machine.limits.map(|l| (l.z_min, l.z_max))),
    ];
    let zero = match args.zero {
        Some((x, z)) => Xz::new(x_mm(x), z_mm(z)),
        None => default_zero(&settings),
    };
    let header = Header {
        version: turnpass::compensation::provenance::VERSION.to_string(),
        model: settings.name.clone().unwrap_or_else(|| display_name(path)),
        model_sha256: model_digest(path, &text)?,
    };
    let unit = args.detection_unit.unwrap_or(machine.increment) * machine.scale() / control_table::mm_per_unit(units);
    let options = Options {
        control,
        units,
        zero,
        range,
        tolerance_mm: args.tolerance.unwrap_or(machine.increment * machine.scale() / 2.0),
        spacing_mm: args.spacing,
        // LinuxCNC keeps a float; the rows for an Okuma are given to a tenth of a micrometre
        // unless a step is asked for; a Fanuc counts detection units.
        unit: match control {
            Control::Linuxcnc => 0.0,
            Control::Okuma if args.detection_unit.is_none() => 0.0,
            _ => unit,
        },
        linuxcnc_type: args.comp_file_type,
        header,
    };
    let table = control_table::build(&model, &options).map_err(|e| CliError::Usage(format!("table: {}", e.0)))?;
    if table.axes.is_empty() {
        return Err(CliError::Usage(format!(
            "table: the model {} has nothing a {} table carries (no error of an axis' own position, no backlash); \
             compensate the programs instead",
            path.display(),
            control.name()
        )));
    }
    let stem = args.output.file_stem().map_or_else(|| "table".to_string(), |s| s.to_string_lossy().into_owned());
    let written = table.write(|axis| format!("{stem}-{}.comp", axis.letter().to_ascii_lowercase()));
    let loaded = table.loaded().map_err(|e| {
        CliError::Usage(format!("table: the table written does not read back ({}): a bug of turnpass", e.message))
    })?;
    let dir = folder_of(&args.output);
    // The files beside first: the main file, which names them, is whole only once they are.
    for (name, text) in &written.beside {
        write_file(&dir.join(name), text.as_bytes())?;
    }
    write_file(&args.output, written.main.as_bytes())?;
    let mut summary = table.summary(&model, &loaded);
    for unsaid in taken.iter().filter(|t| !t.said) {
        summary.push_str(&format!(
            "table: note: the {} slide table does not say whether it was taken with the control's compensation \
             off, as a table for the control's own is ({} = \"off\" in its [[axis_table]])\n",
            unsaid.axis, unsaid.key
        ));
    }
    summary.push_str(&format!("table: wrote {}", args.output.display()));
    for (name, _) in &written.beside {
        summary.push_str(&format!(", {}", dir.join(name).display()));
    }
    summary.push('\n');
    streams::err(summary);
    Ok(ExitCode::SUCCESS)
}

/// How a slide table with a linear column was taken: with the control's pitch-error or
/// backlash compensation on (`on`, naming which), and whether it says so at all.
struct Taken {
    axis: char,
    on: bool,
    said: bool,
    what: &'static str,
    key: &'static str,
}

/// How each slide table of `spec` was taken (`[[axis_table]]`'s `pitch_error_compensation`
/// and `backlash_compensation`): a control's table is made from a table taken with them off,
/// the slide's whole error.
fn how_taken(spec: &ModelSpec) -> Vec<Taken> {
    use turnpass::error_model::model_file::Switch;
    let mut out = Vec::new();
    for table in &spec.axis_table {
        let axis = table.axis.letter();
        let (pitch, backlash) = (table.pitch_error_compensation, table.backlash_compensation);
        if pitch == Some(Switch::On) {
            out.push(Taken { axis, on: true, said: true, what: "pitch-error", key: "pitch_error_compensation" });
        } else if backlash == Some(Switch::On) {
            out.push(Taken { axis, on: true, said: true, what: "backlash", key: "backlash_compensation" });
        } else {
            out.push(Taken {
                axis,
                on: false,
                said: pitch.is_some(),
                what: "pitch-error",
                key: "pitch_error_compensation",
            });
        }
    }
    out
}

/// The model position of the machine's zero when none is given: the reference position
/// (`[machine] home`, from which a Fanuc numbers its compensation points), else the
/// program's zero.
fn default_zero(settings: &MachineSettings) -> Xz {
    Machine::from_settings(settings).home.unwrap_or(Xz::new(0.0, 0.0))
}

/// The first digits of the SHA-256 of the model at `path` (its text `text`) and its tables.
fn model_digest(path: &Path, text: &str) -> Result<String, CliError> {
    let (spec, dir) = super::common::model_spec(path, text)?;
    let mut tables = Vec::new();
    for file in spec.axis_table.iter().filter_map(|table| table.file.as_ref().map(|file| file.get_ref().as_str())) {
        let table = dir.join(file);
        tables.push(
            std::fs::read(&table).map_err(|source| CliError::Read { path: table.display().to_string(), source })?,
        );
    }
    let mut digest = model_sha256(text.as_bytes(), tables.iter().map(Vec::as_slice));
    digest.truncate(SHA256_DIGITS);
    Ok(digest)
}

/// A control table the machine runs with (`--with-table`).
pub struct WithTable {
    pub path: PathBuf,
    pub loaded: Loaded,
    /// The first digits of the SHA-256 of its file and the files it names.
    pub sha256: String,
}

/// `model` on a machine with the control's table at `path` loaded, read with the settings
/// `settings` (units and the machine's zero the file does not state).
pub fn with_table(
    path: &Path,
    settings: &MachineSettings,
    model: &ErrorModel,
    command: &str,
) -> Result<(ErrorModel, WithTable), CliError> {
    let main_bytes = read_input(path)?;
    let main = String::from_utf8(main_bytes.clone())
        .map_err(|_| CliError::Usage(format!("--with-table {}: not a text file", path.display())))?;
    let dir = folder_of(path).to_path_buf();
    let mut beside_texts: Vec<(String, Vec<u8>)> = Vec::new();
    let beside = |name: &str| -> Result<String, String> {
        let file = dir.join(name);
        let bytes = std::fs::read(&file).map_err(|e| format!("{}: {e}", file.display()))?;
        let text = String::from_utf8(bytes.clone()).map_err(|_| format!("{}: not a text file", file.display()))?;
        beside_texts.push((name.to_string(), bytes));
        Ok(text)
    };
    let machine = Machine::from_settings(settings);
    let loaded = match control_table::read(None, &main, beside, machine.units, default_zero(settings)) {
        Ok(loaded) => loaded,
        Err(error) => return Err(table_unreadable(path, &main, &beside_texts, error, command)),
    };
    let mut digest = model_sha256(&main_bytes, beside_texts.iter().map(|(_, b)| b.as_slice()));
    digest.truncate(SHA256_DIGITS);
    let combined = model.with_control(loaded.compensation.clone());
    Ok((combined, WithTable { path: path.to_path_buf(), loaded, sha256: digest }))
}

/// A table file that does not read: its problem at its file, line and column.
fn table_unreadable(
    path: &Path,
    main: &str,
    beside: &[(String, Vec<u8>)],
    error: ReadError,
    command: &str,
) -> CliError {
    let (name, text) = match &error.file {
        Some(file) => {
            let text = beside.iter().find(|(n, _)| n == file).map_or_else(Vec::new, |(_, b)| b.clone());
            (folder_of(path).join(file).display().to_string(), text)
        }
        None => (path.display().to_string(), main.as_bytes().to_vec()),
    };
    let kind = DiagnosticKind::DataInvalid { message: error.message, label: error.label, hint: error.hint };
    let mut out = rendered(&name, &text, &[Diagnostic::error(kind, error.span)]);
    out.extend_from_slice(
        format!("{command}: the control table {} does not read; nothing is done\n", path.display()).as_bytes(),
    );
    CliError::Rejected(out)
}

/// What goes where on a machine with `with` loaded: the terms of `model` (the machine
/// without it) the table works on and those the program compensates, in a line.
pub fn split_summary(model: &ErrorModel, with: &WithTable) -> String {
    let control = with.loaded.control;
    let placements = control_table::placements(model, control);
    let listed = |in_table: bool| -> String {
        let list: Vec<&str> = placements
            .iter()
            .filter(|p| (p.in_table && with_axis(&with.loaded, &p.part)) == in_table)
            .map(|p| p.name.as_str())
            .collect();
        if list.is_empty() { "nothing".to_string() } else { list.join(", ") }
    };
    format!(
        "the machine runs with the {} table {} (sha256 {}) loaded: it works on {}; the program compensates {}",
        control.name(),
        with.path.display(),
        with.sha256,
        listed(true),
        listed(false)
    )
}

/// Whether the loaded table has the axis of `part`.
fn with_axis(loaded: &Loaded, part: &TablePart) -> bool {
    match part {
        TablePart::Pitch(axis) => loaded.compensation.axis(*axis).is_some_and(|a| !a.nodes.is_empty()),
        TablePart::Backlash(axis, _) => loaded.compensation.axis(*axis).is_some_and(|a| a.backlash != 0.0),
        _ => false,
    }
}
