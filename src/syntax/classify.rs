//! What a block does: its [`Statement`], and for commands with a word schema (cycles, LAP
//! calls, dwells, one-shots) the typed parameters.
//!
//! The block's own words decide; modal state is the semantic pass's business. A bare `X2.0`
//! is a `Motion` here even when the modal command is a single cycle.

use crate::diagnostic::{CountedWord, Diagnostic, DiagnosticKind};
use crate::dialect::roles;
use crate::dialect::tables::{KeywordKind, Place};
use crate::dialect::{
    Address, Control, Dialect, Form, GFunction, GInfo, GKind, IntegerUnit, MachineKind, ModalGroup, Tables,
};

use super::ast::{CodeLetter, Command, CommandId, Param, Statement, Word, WordId, WordKind};
use super::spelling;

pub(super) struct Classifier<'a> {
    pub tables: &'static Tables,
    pub commands: &'a mut Vec<Command>,
    pub warnings: &'a mut Vec<Diagnostic>,
    /// Scratch space for the block's G-codes, reused from block to block.
    pub codes: &'a mut Vec<(usize, &'static GInfo)>,
}

/// Addresses that move the tool when a block has no explicit motion G-code.
fn is_axis(dialect: Dialect, address: Address) -> bool {
    match dialect {
        Dialect::Fanuc => matches!(
            address,
            Address::X | Address::Y | Address::Z | Address::U | Address::V | Address::W | Address::C | Address::H
        ),
        // On OSP, U and W are allowances, never moves.
        Dialect::Osp => matches!(address, Address::X | Address::Y | Address::Z | Address::C),
    }
}

/// Addresses that make a block with an explicit motion G-code a move (end point, centre,
/// radius, angle, or the escape vector of an OSP `G40 G01 K1`).
fn is_motion_word(dialect: Dialect, address: Address) -> bool {
    is_axis(dialect, address) || matches!(address, Address::I | Address::K | Address::R | Address::L | Address::A)
}

/// A Fanuc block that gives an axis both as a position and as a distance (`X` and `U`, `Z` and
/// `W`, `Y` and `V`, `C` and `H`) is refused: the lathe manuals at hand do not say which one a
/// control takes, other controls refuse redundant absolute and incremental programming of one
/// axis (Beckhoff TwinCAT CNC by default, channel parameter P-CHAN-00116), and such a block is
/// most often a misread word (`W110` for `N110`). Refusing it keeps simulate, compensate and the
/// canonical form, which reorders words, from choosing for the programmer.
fn axis_given_twice(words: &[Word], seen_letters: u32) -> Result<(), Diagnostic> {
    const PAIRS: [(u8, u8, char); 4] = [(b'X', b'U', 'X'), (b'Z', b'W', 'Z'), (b'Y', b'V', 'Y'), (b'C', b'H', 'C')];
    let bit = |letter: u8| 1u32 << (letter - b'A');
    for (position, distance, axis) in PAIRS {
        if seen_letters & bit(position) == 0 || seen_letters & bit(distance) == 0 {
            continue;
        }
        let is_either =
            |w: &&Word| word_address(w).and_then(|a| a.as_letter()).is_some_and(|l| l == position || l == distance);
        let Some(second) = words.iter().filter(is_either).nth(1) else { continue };
        let name = |letter: u8| char::from(letter).to_string();
        return Err(Diagnostic::error(
            DiagnosticKind::AxisGivenTwice { position: name(position), distance: name(distance), axis },
            second.span,
        ));
    }
    Ok(())
}

impl Classifier<'_> {
    fn command_name(&self, info: &GInfo) -> String {
        format!("{} ({})", info.code.display('G'), info.meaning)
    }

    /// Another Fanuc-compatible control whose form of the same command takes `address`
    /// with a decimal point (`point_reads` in `grammar/`), and the unit it reads it in then.
    fn point_taken_elsewhere(
        &self,
        info: &GInfo,
        form: &Form,
        address: Address,
    ) -> Option<(&'static str, &'static str)> {
        let config = self.tables.config;
        if config.dialect != Dialect::Fanuc {
            return None;
        }
        Control::ALL.into_iter().filter(|c| *c != config.control).find_map(|control| {
            let tables = config.with_control(control).tables();
            let schema = tables.schema(tables.g(info.code)?.schema?);
            let role = schema.forms.iter().find(|f| f.name == form.name)?.role_with_point(address)?;
            Some((control.name(), roles::unit_word(roles::describe(role).1)))
        })
    }

    pub fn classify(&mut self, words: &[Word], first_word: WordId) -> Result<Statement, Diagnostic> {
        // The G-codes of the block, with their table entries.
        let mut codes = std::mem::take(self.codes);
        codes.clear();
        let result = self.classify_with(words, first_word, &mut codes);
        *self.codes = codes;
        result
    }

    fn classify_with(
        &mut self,
        words: &[Word],
        first_word: WordId,
        codes: &mut Vec<(usize, &'static GInfo)>,
    ) -> Result<Statement, Diagnostic> {
        let tables = self.tables;
        let dialect = tables.config.dialect;
        let machining_centre = tables.config.machine_kind == MachineKind::MachiningCentre && dialect == Dialect::Osp;
        let mut keyword: Option<KeywordKind> = None;
        let mut has_assign = false;
        let mut has_other = false;
        let (mut has_axis, mut has_motion_word, mut has_tool, mut has_speed) = (false, false, false, false);
        let mut program_name = false;
        let mut tape_mark = false;
        let mut first_significant: Option<usize> = None;
        let mut seen_letters: u32 = 0;
        let mut duplicate: Option<usize> = None;
        let mut has_extended = false;

        for (i, word) in words.iter().enumerate() {
            match word.kind {
                WordKind::Code { letter: CodeLetter::G, code } => {
                    match tables.g(code) {
                        Some(info) => codes.push((i, info)),
                        None => self.unknown_g(word, code, machining_centre)?,
                    }
                    first_significant.get_or_insert(i);
                }
                WordKind::Code { letter: CodeLetter::M, .. } => {
                    has_other = true;
                    first_significant.get_or_insert(i);
                }
                WordKind::Number { address, .. } | WordKind::Expr { address, .. } => {
                    match address.as_letter() {
                        Some(letter) => {
                            let bit = 1u32 << (letter - b'A');
                            if seen_letters & bit != 0 && duplicate.is_none() {
                                duplicate = Some(i);
                            }
                            seen_letters |= bit;
                        }
                        None => has_extended = true,
                    }
                    has_axis |= is_axis(dialect, address);
                    has_motion_word |= is_motion_word(dialect, address);
                    has_tool |= address == Address::T;
                    has_speed |= address == Address::S;
                    has_other = true;
                    first_significant.get_or_insert(i);
                }
                WordKind::Keyword { index } => {
                    keyword.get_or_insert(tables.keyword_info(index as usize).kind);
                    first_significant.get_or_insert(i);
                }
                WordKind::Assign { .. } => {
                    has_assign = true;
                    first_significant.get_or_insert(i);
                }
                WordKind::ProgramName => program_name = true,
                WordKind::TapeMark => tape_mark = true,
                WordKind::Label { .. } | WordKind::ProgramRef | WordKind::Operand { .. } | WordKind::Verbatim => {
                    has_other = true;
                }
                WordKind::Sequence { .. }
                | WordKind::BlockDelete { .. }
                | WordKind::OptionalSkip { .. }
                | WordKind::Header
                | WordKind::Comment(_) => {}
            }
        }

        if program_name && dialect == Dialect::Osp && first_significant.is_some() {
            let word = &words[first_significant.unwrap_or(0)];
            return Err(Diagnostic::error(DiagnosticKind::ProgramNameNotAlone, word.span));
        }

        // The same address twice in a block is an alarm, except in hole patterns, which repeat
        // their words (`LAA … I25 I76 I25`), and in machining-centre programs.
        let relaxed = machining_centre || keyword == Some(KeywordKind::Pattern);
        if !relaxed {
            if let Some(i) = duplicate {
                let address = word_address(&words[i]).map_or_else(String::new, |a| a.name());
                return Err(Diagnostic::error(DiagnosticKind::DuplicateWord { address }, words[i].span));
            }
            if has_extended {
                self.check_duplicates(words, false)?;
            }
            // A macro call's words are its arguments, not end points.
            let macro_call = codes
                .iter()
                .any(|(_, info)| info.function == Some(GFunction::MacroCall) || info.group == ModalGroup::MacroModal);
            if dialect == Dialect::Fanuc && !macro_call {
                axis_given_twice(words, seen_letters)?;
            }
        }

        if let Some(kind) = keyword {
            return Ok(match kind {
                KeywordKind::Graphics => Statement::Graphics,
                KeywordKind::Pattern => Statement::Pattern,
                _ => Statement::Control,
            });
        }

        // The command that names the block, and conflicts between commands.
        let primary = codes.iter().copied().max_by_key(|(_, info)| info.kind.rank());
        if codes.len() > 1 {
            self.check_code_conflicts(words, codes)?;
        }

        if let Some((index, info)) = primary
            && info.kind.rank() >= 3
            && let Some(schema) = info.schema
        {
            let id = self.command(words, first_word, index, info, schema)?;
            return Ok(match info.kind {
                GKind::Cycle => Statement::Cycle(id),
                GKind::LapCall => Statement::LapCall(id),
                GKind::LapMarker => Statement::LapMarker(id),
                GKind::Dwell => Statement::Dwell(id),
                _ => Statement::OneShot(id),
            });
        }

        // Modal codes with a schema (OSP `G75`/`G76` corners need `L`, `G15` needs `H`) check
        // their words without becoming the block's command.
        for &(index, info) in codes.iter() {
            if info.kind.rank() < 3
                && let Some(schema) = info.schema
            {
                let schema = tables.schema(schema);
                if let Some(form) = schema.forms.iter().find(|f| f.matches(|a| present(words, a))) {
                    self.check_required(words, index, info, form)?;
                }
            }
        }

        let explicit_motion = primary.map(|(_, info)| info.kind);
        let statement = match explicit_motion {
            Some(GKind::ThreadMove) => Statement::ThreadMove,
            Some(GKind::Motion) if has_motion_word => Statement::Motion,
            Some(GKind::Cycle) if has_axis => Statement::Motion,
            _ if has_axis => Statement::Motion,
            _ if has_assign && !has_other && codes.is_empty() => Statement::Assignment,
            _ if has_tool => Statement::ToolCall,
            _ if has_speed || codes.iter().any(|(_, info)| info.group == ModalGroup::SpindleMode) => Statement::Spindle,
            _ if has_other || has_assign || !codes.is_empty() => Statement::Settings,
            _ if program_name => Statement::ProgramName,
            _ if tape_mark => Statement::TapeMark,
            _ => Statement::Empty,
        };
        Ok(statement)
    }

    fn unknown_g(&mut self, word: &Word, code: crate::dialect::Code, machining_centre: bool) -> Result<(), Diagnostic> {
        let tables = self.tables;
        let text = code.display('G');
        if let Some(elsewhere) = tables.g_elsewhere(code) {
            match elsewhere.place {
                Place::OspMachiningCentre => {
                    return Err(Diagnostic::error(
                        DiagnosticKind::MachiningCentreCode { code: text, meaning: elsewhere.meaning.clone() },
                        word.span,
                    ));
                }
                Place::GCodeSystem(system) => {
                    let hint = format!(
                        "{text} is {} in G-code system {system:?}; this machine is set to system {:?} (`gcode_system` in the machine settings)",
                        elsewhere.meaning, tables.config.gcode_system
                    );
                    return Err(Diagnostic::error(
                        DiagnosticKind::UnknownGCode {
                            code: text,
                            dialect: tables.config.dialect.name(),
                            hint: Some(hint),
                        },
                        word.span,
                    ));
                }
                Place::OspLathe => {}
            }
        }
        let hint = tables.foreign_g(code).map(str::to_string);
        let diagnostic = Diagnostic::error(
            DiagnosticKind::UnknownGCode { code: text, dialect: tables.config.dialect.name(), hint },
            word.span,
        );
        if machining_centre {
            // Only the syntax of machining-centre programs is checked, against a small table.
            self.warnings.push(Diagnostic { severity: crate::diagnostic::Severity::Warning, ..diagnostic });
            return Ok(());
        }
        Err(diagnostic)
    }

    /// Two commands in one block (`G71 G70`), or two codes of one modal group (`G00 G01`).
    fn check_code_conflicts(&mut self, words: &[Word], codes: &[(usize, &'static GInfo)]) -> Result<(), Diagnostic> {
        let primary_schema = codes.iter().max_by_key(|(_, info)| info.kind.rank()).and_then(|(_, info)| info.schema);
        for (n, &(i, first)) in codes.iter().enumerate() {
            for &(j, second) in &codes[n + 1..] {
                let allowed_inside = primary_schema.is_some_and(|schema| {
                    let schema = self.tables.schema(schema);
                    schema.forms.iter().any(|form| {
                        form.g_words.iter().any(|g| *g == second.code.display('G') || *g == first.code.display('G'))
                    })
                });
                if first.kind.rank() >= 3 && second.kind.rank() >= 3 && !allowed_inside {
                    return Err(Diagnostic::error(
                        DiagnosticKind::ConflictingCommands {
                            first: first.code.display('G'),
                            second: second.code.display('G'),
                        },
                        words[j].span,
                    ));
                }
                if first.group == second.group && first.group != ModalGroup::OneShot && first.code != second.code {
                    let span = words[j].span.merge(words[i].span);
                    self.warnings.push(Diagnostic::warning(
                        DiagnosticKind::SameModalGroup {
                            first: first.code.display('G'),
                            second: second.code.display('G'),
                        },
                        span,
                    ));
                }
            }
        }
        Ok(())
    }

    /// The same address twice in one block. Linear in the block's length (a bit per letter),
    /// since a single line may hold millions of words.
    fn check_duplicates(&self, words: &[Word], relaxed: bool) -> Result<(), Diagnostic> {
        if relaxed {
            return Ok(());
        }
        let mut letters: u32 = 0;
        let mut extended: Vec<Address> = Vec::new();
        for word in words {
            let Some(address) = word_address(word) else { continue };
            let seen = match address.as_letter() {
                Some(letter) => {
                    let bit = 1u32 << (letter - b'A');
                    let seen = letters & bit != 0;
                    letters |= bit;
                    seen
                }
                None => {
                    let seen = extended.contains(&address);
                    if !seen {
                        extended.push(address);
                    }
                    seen
                }
            };
            if seen {
                return Err(Diagnostic::error(DiagnosticKind::DuplicateWord { address: address.name() }, word.span));
            }
        }
        Ok(())
    }

    /// Match the block's words against the command's schema and record their roles.
    fn command(
        &mut self,
        words: &[Word],
        first_word: WordId,
        code_index: usize,
        info: &'static GInfo,
        schema_id: crate::dialect::SchemaId,
    ) -> Result<CommandId, Diagnostic> {
        let tables = self.tables;
        let schema = tables.schema(schema_id);
        let present = |address: Address| {
            words.iter().any(|w| {
                word_address(w) == Some(address) || (address == Address::N && matches!(w.kind, WordKind::Label { .. }))
            })
        };
        let Some((form_index, form)) = schema.forms.iter().enumerate().find(|(_, f)| f.matches(present)) else {
            return Err(Diagnostic::error(
                DiagnosticKind::MissingWord { command: self.command_name(info), words: "its words".into() },
                words[code_index].span,
            ));
        };
        let command = || self.command_name(info);
        let mut params = Vec::new();
        let lap = matches!(info.kind, GKind::LapCall | GKind::LapMarker);
        for (i, word) in words.iter().enumerate() {
            let id = first_word + i as WordId;
            match word.kind {
                WordKind::Number { address, number } => {
                    if let Some(role) = form.role_of(address) {
                        // A point that makes the word another role (a Haas dwell `P0.3`, seconds).
                        let role = form.role_with_point(address).filter(|_| number.has_point()).unwrap_or(role);
                        let unit = IntegerUnit::of(role);
                        // A count of increments depends on the units in force, which the
                        // semantic pass knows (`G20`/`G21` may change them): it reports
                        // those, with the value meant.
                        if form.takes_integer(address) && number.has_point() && !unit.needs_frame() {
                            let meant = roles::meant(unit, number.to_f64(), None)
                                .map(|(count, reading)| (format!("{}{count}", address.name()), reading));
                            let kind = DiagnosticKind::IntegerExpected(Box::new(CountedWord {
                                command: command(),
                                address: address.name(),
                                written: format!("{}{}", address.name(), spelling::plain(number)),
                                unit,
                                meant,
                                control: self.tables.config.control.name(),
                                elsewhere: self.point_taken_elsewhere(info, form, address),
                            }));
                            return Err(Diagnostic::error(kind, word.span));
                        }
                        params.push(Param { role, word: id });
                    } else if !form.any_words && !self.allowed_outside_schema(info.kind, address) {
                        return Err(self.not_allowed(info, form, address, word));
                    }
                }
                WordKind::Expr { address, .. } => {
                    if let Some(role) = form.role_of(address) {
                        params.push(Param { role, word: id });
                    } else if !form.any_words && !self.allowed_outside_schema(info.kind, address) {
                        return Err(self.not_allowed(info, form, address, word));
                    }
                }
                WordKind::Code { letter: CodeLetter::M, code } => {
                    if let Some(role) = form.m_role(code.major()) {
                        params.push(Param { role, word: id });
                    } else if lap && !form.any_words {
                        return Err(self.not_allowed(info, form, Address::M, word));
                    }
                }
                WordKind::Code { letter: CodeLetter::G, code } if i != code_index => {
                    let inside = form.g_words.iter().any(|g| *g == code.display('G'));
                    if lap && !inside && !form.any_words {
                        return Err(self.not_allowed(info, form, Address::G, word));
                    }
                }
                WordKind::Label { .. } => match form.labels {
                    Some(role) => params.push(Param { role, word: id }),
                    None if form.any_words => {}
                    None => return Err(self.not_allowed(info, form, Address::N, word)),
                },
                _ => {}
            }
        }
        self.check_required(words, code_index, info, form)?;
        self.commands.push(Command {
            code_word: first_word + code_index as WordId,
            schema: schema_id,
            form: form_index as u8,
            params,
        });
        Ok((self.commands.len() - 1) as CommandId)
    }

    /// The words a form requires (`required`), and one of each `required_any` group.
    fn check_required(&self, words: &[Word], code_index: usize, info: &GInfo, form: &Form) -> Result<(), Diagnostic> {
        let missing: Vec<String> =
            form.required.iter().filter(|&&a| !present(words, a)).map(|a| format!("`{a}`")).collect();
        if !missing.is_empty() {
            return Err(Diagnostic::error(
                DiagnosticKind::MissingWord { command: self.command_name(info), words: missing.join(" and ") },
                words[code_index].span,
            ));
        }
        for group in &form.required_any {
            if !group.iter().any(|&a| present(words, a)) {
                let names: Vec<String> = group.iter().map(|a| format!("`{a}`")).collect();
                return Err(Diagnostic::error(
                    DiagnosticKind::MissingWord {
                        command: self.command_name(info),
                        words: format!("one of {}", names.join(", ")),
                    },
                    words[code_index].span,
                ));
            }
        }
        Ok(())
    }

    /// Words a command block may carry besides its schema's: M codes with most commands, and
    /// feed, speed and tool words with one-shots (`G28 U0 W0 T0100`, `G53 X0 Z0 T00`).
    fn allowed_outside_schema(&self, kind: GKind, address: Address) -> bool {
        match kind {
            GKind::OneShot | GKind::Dwell => matches!(address, Address::F | Address::S | Address::T),
            _ => false,
        }
    }

    fn not_allowed(&self, info: &GInfo, form: &crate::dialect::Form, address: Address, word: &Word) -> Diagnostic {
        // The control rejects spindle, tool and M words in a LAP call (M-P204); say so, since
        // the usual fix is to move them to the block before, not to drop them.
        if info.kind == GKind::LapCall && matches!(address, Address::S | Address::T | Address::M) {
            return Diagnostic::error(
                DiagnosticKind::LapCallWord { command: self.command_name(info), address: address.name() },
                word.span,
            );
        }
        Diagnostic::error(
            DiagnosticKind::WordNotAllowed {
                command: self.command_name(info),
                address: address.name(),
                allowed: form.allowed_list(),
            },
            word.span,
        )
    }
}

/// Whether the block has a word with this address (an `N` operand counts as `N`).
fn present(words: &[Word], address: Address) -> bool {
    words.iter().any(|w| {
        word_address(w) == Some(address) || (address == Address::N && matches!(w.kind, WordKind::Label { .. }))
    })
}

fn word_address(word: &Word) -> Option<Address> {
    match word.kind {
        WordKind::Number { address, .. } | WordKind::Expr { address, .. } => Some(address),
        _ => None,
    }
}
