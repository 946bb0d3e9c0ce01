//! The front of every pass that works on a lowered program: parse → lower → validate, in
//! one place.
//!
//! [`analyse`] parses a program, lowers it on a machine and validates its toolpath, whatever
//! the parse found; what it gives back says how far the program got ([`Lowering`]) with
//! every diagnostic of the three steps in program order. The passes after lowering
//! (`expand`, `simulation`, `compensation` and `verify`, `diagnose`, the plots) take only
//! the validated program (`Validated<Lowered>`, its `ValidToolpath`, or a [`Ready`]
//! program), so none runs on a toolpath that broke the IR's invariants. The command line (`check`'s full check among it), `compensate`'s
//! read-back of what it writes, the tests and the benches enter here; the language server,
//! which parses incrementally, lowers and validates its assembled program through
//! [`semantic_diagnostics`].

use crate::diagnostic::Diagnostic;
use crate::machine::MachineSettings;
use crate::part::{self, PartCheck, PartRun};
use crate::semantic::{self, LowerOptions, Lowered, Machine};
use crate::syntax::{self, ParseOptions, Parsed, Program};
use crate::toolpath::{ValidToolpath, Validated};

/// How a program is read and run.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    pub parse: ParseOptions,
    pub machine: Machine,
    pub lower: LowerOptions,
    /// Run the part model on the valid toolpath (`check`, `simulate`, the language server):
    /// its crashes and deep cuts join the diagnostics.
    pub part: Option<PartCheck>,
}

impl Settings {
    /// A program read with `parse` and run with `lower` on the machine `machine` describes.
    pub fn new(parse: ParseOptions, machine: &MachineSettings, lower: LowerOptions) -> Settings {
        Settings { parse, machine: Machine::from_settings(machine), lower, part: None }
    }

    /// These settings with the part model run on `check`'s stock.
    pub fn with_part(self, check: PartCheck) -> Settings {
        Settings { part: Some(check), ..self }
    }
}

/// A program parsed, lowered and validated, as far as it got.
#[derive(Debug, Clone)]
pub struct Analysed<'src> {
    pub parsed: Parsed<'src>,
    pub machine: Machine,
    pub lowering: Lowering,
    /// Every diagnostic: the parse's, the lowering's and the validation's (and the part
    /// model's), in program order.
    pub diagnostics: Vec<Diagnostic>,
    /// The part model's run, when the settings ask for it and the toolpath is valid.
    pub part: Option<PartRun>,
}

/// How far a parsed program got.
#[derive(Debug, Clone)]
pub enum Lowering {
    /// The semantic pass does not lower it (an OSP machining-centre program:
    /// `semantic::lowers`); only its syntax was checked.
    NotLowered,
    /// Lowered, but its toolpath did not validate (the problems are among the diagnostics).
    Invalid(Lowered),
    /// Lowered, its toolpath validated.
    Valid(Validated<Lowered>),
}

impl<'src> Analysed<'src> {
    /// The lowered program, valid or not (none when it was not lowered).
    pub fn lowered(&self) -> Option<&Lowered> {
        match &self.lowering {
            Lowering::NotLowered => None,
            Lowering::Invalid(lowered) => Some(lowered),
            Lowering::Valid(lowered) => Some(lowered),
        }
    }

    /// How many of the diagnostics are errors.
    pub fn error_count(&self) -> usize {
        self.diagnostics.iter().filter(|d| d.is_error()).count()
    }

    /// The program ready for the passes after lowering: lowered, its toolpath valid, and no
    /// error anywhere (a block in error was skipped, so the toolpath is of a run the control
    /// does not make). Otherwise the analysis comes back as it was.
    pub fn ready(self) -> Result<Ready<'src>, Box<Analysed<'src>>> {
        if self.error_count() > 0 {
            return Err(Box::new(self));
        }
        match self.lowering {
            Lowering::Valid(lowered) => {
                Ok(Ready { parsed: self.parsed, lowered, machine: self.machine, part: self.part })
            }
            lowering => Err(Box::new(Analysed { lowering, ..self })),
        }
    }
}

/// A program with no error, lowered, its toolpath validated: what the passes after
/// lowering take.
#[derive(Debug, Clone)]
pub struct Ready<'src> {
    pub parsed: Parsed<'src>,
    pub lowered: Validated<Lowered>,
    pub machine: Machine,
    /// The part model's run, when the settings asked for it.
    pub part: Option<PartRun>,
}

impl Ready<'_> {
    /// The parsed program.
    pub fn program(&self) -> &Program<'_> {
        &self.parsed.program
    }

    /// The validated toolpath.
    pub fn valid(&self) -> ValidToolpath<'_> {
        self.lowered.valid()
    }
}

/// Parse `source`, lower it and validate its toolpath (see the module documentation).
pub fn analyse<'src>(source: &'src [u8], settings: &Settings) -> Analysed<'src> {
    let parsed = syntax::parse(source, &settings.parse);
    let (lowering, diagnostics, part) = lower_and_validate(&parsed, settings);
    Analysed { parsed, machine: settings.machine.clone(), lowering, diagnostics, part }
}

/// Lower `parsed` and validate its toolpath, whatever the parse found; every diagnostic,
/// the parse's included, in program order.
fn lower_and_validate(parsed: &Parsed<'_>, settings: &Settings) -> (Lowering, Vec<Diagnostic>, Option<PartRun>) {
    let (lowering, found, part) =
        lower_program(&parsed.program, &settings.machine, &settings.lower, settings.part.as_ref());
    let mut diagnostics = parsed.diagnostics.clone();
    diagnostics.extend(found);
    diagnostics.sort_by_key(|d| d.span.start);
    (lowering, diagnostics, part)
}

/// Lower `program` and validate its toolpath against the machine's travel limits, and with
/// `part` run the part model on a valid toolpath: how far it got, and the lowering's
/// diagnostics, the toolpath's problems and the part model's findings (not the parse's).
fn lower_program(
    program: &Program<'_>,
    machine: &Machine,
    options: &LowerOptions,
    part: Option<&PartCheck>,
) -> (Lowering, Vec<Diagnostic>, Option<PartRun>) {
    if !semantic::lowers(program) {
        return (Lowering::NotLowered, Vec::new(), None);
    }
    let lowered = semantic::lower(program, machine, options);
    let mut diagnostics = lowered.diagnostics.clone();
    let mut run = None;
    let lowering = match Validated::new(lowered, machine.limits) {
        Ok(valid) => {
            // A run with an error skipped the block in error: its part is not one the control
            // makes, so the part model judges only a clean run (as `simulate` prints one).
            if let Some(check) = part.filter(|_| !diagnostics.iter().any(Diagnostic::is_error)) {
                let found = part::run(valid.valid(), machine, check);
                diagnostics.extend(found.diagnostics.iter().cloned());
                run = Some(found);
            }
            Lowering::Valid(valid)
        }
        Err((lowered, problems)) => {
            diagnostics.extend(problems);
            Lowering::Invalid(lowered)
        }
    };
    (lowering, diagnostics, run)
}

/// What lowering and validation (and with `part` the part model) find in `program` beyond
/// its parse, in program order (none for a program the semantic pass does not lower): the
/// language server's semantic diagnostics, the same `analyse` gives `check` and `simulate`.
pub fn semantic_diagnostics(
    program: &Program<'_>,
    machine: &Machine,
    options: &LowerOptions,
    part: Option<&PartCheck>,
) -> Vec<Diagnostic> {
    let (_, mut diagnostics, _) = lower_program(program, machine, options, part);
    diagnostics.sort_by_key(|d| d.span.start);
    diagnostics
}
