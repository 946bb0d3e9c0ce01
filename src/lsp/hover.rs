//! Hover: what the word under the cursor means in this program's dialect.
//!
//! Everything comes from the dialect tables of `grammar/`: a G code's meaning in this
//! dialect and G-code system (`G71` is a compound thread cycle on OSP and stock removal on
//! Fanuc), an M code's meaning, an address's meaning, and for a command (cycle, LAP call,
//! dwell, one-shot) the schema form the block matched, with each word's role, meaning and
//! unit (`roles.rs`).

use std::fmt::Write as _;

use lsp_types::{Hover, HoverContents, MarkupContent, MarkupKind};

use crate::dialect::tables::{KeywordKind, Place};
use crate::dialect::{Address, AddressKind, DecimalInput, Dialect, Form, Tables};
use crate::machine::{MachineSettings, Units};
use crate::syntax::{CodeLetter, Command, Number, Statement, Word, WordId, WordKind};

use super::document::{BlockRef, Document};
use super::roles::{self, Unit};

/// The hover for the word at byte `offset`, if there is a word there; in plain text when
/// `plain` (a client that asks for it shows Markdown's `**` and table pipes as they are).
pub fn hover(document: &Document, offset: usize, settings: &MachineSettings, plain: bool) -> Option<Hover> {
    let block = document.block_at(offset)?;
    let (id, word) = block.word_at(offset)?;
    let tables = document.config().tables();
    let text = String::from_utf8_lossy(block.text(word.span)).into_owned();
    let markdown = describe(&Context { block, tables, settings }, id, word, &text)?;
    let contents = if plain {
        MarkupContent { kind: MarkupKind::PlainText, value: plain_text(&markdown) }
    } else {
        MarkupContent { kind: MarkupKind::Markdown, value: markdown }
    };
    Some(Hover { contents: HoverContents::Markup(contents), range: Some(document.range(block.absolute(word.span))) })
}

/// The hover's Markdown as plain text: no emphasis or code marks; a table's rows as lines
/// of their cells, `X10.: end_x, X of the end point (mm)`.
pub fn plain_text(markdown: &str) -> String {
    let mut out = Vec::new();
    for line in markdown.lines() {
        let line = line.replace("**", "").replace('`', "");
        let Some(row) = line.strip_prefix('|') else {
            out.push(line);
            continue;
        };
        let cells: Vec<&str> = row.trim_end_matches('|').split('|').map(str::trim).collect();
        if cells.iter().all(|c| c.chars().all(|ch| ch == '-')) || cells.first() == Some(&"word") {
            continue;
        }
        match cells.as_slice() {
            [word, role, meaning, unit] => out.push(format!("{word}: {role}, {meaning} ({unit})")),
            _ => out.push(cells.join(", ")),
        }
    }
    out.join("\n")
}

struct Context<'a> {
    block: BlockRef<'a>,
    tables: &'static Tables,
    settings: &'a MachineSettings,
}

impl Context<'_> {
    fn dialect(&self) -> &'static str {
        dialect_name(self.tables)
    }

    /// The block's command and its schema form, when the block is one.
    fn command(&self) -> Option<(&Command, &'static Form)> {
        let command = self.block.command()?;
        let form = self.tables.schema(command.schema).forms.get(command.form as usize)?;
        Some((command, form))
    }
}

fn dialect_name(tables: &Tables) -> &'static str {
    match tables.config.dialect {
        Dialect::Osp => "OSP",
        Dialect::Fanuc => "Fanuc",
    }
}

fn describe(context: &Context<'_>, id: WordId, word: &Word, text: &str) -> Option<String> {
    let tables = context.tables;
    let dialect = context.dialect();
    Some(match word.kind {
        WordKind::Code { letter: CodeLetter::G, code } => g_code(context, id, code),
        WordKind::Code { letter: CodeLetter::M, code } => {
            let meaning = tables.m_meaning(code.major()).unwrap_or("no meaning in the tables (machine-specific)");
            let mut out = format!("**{text}** ({dialect}): {meaning}");
            if let Some(line) = parameter_line(context, id, word, text) {
                out.push_str(&format!("\n\n{line}"));
            }
            out
        }
        WordKind::Number { address, number } => {
            let mut out = match parameter_line(context, id, word, text) {
                Some(line) => line,
                None => address_line(context, address, text),
            };
            if let Some(line) = as_read(context, address, number, text) {
                out.push_str(&format!("\n\n{line}"));
            }
            out
        }
        WordKind::Expr { address, .. } => match parameter_line(context, id, word, text) {
            Some(line) => line,
            None => address_line(context, address, text),
        },
        WordKind::Sequence { .. } => {
            let mut out = format!("**{text}**: sequence name");
            if let Some((command, _)) = context.command()
                && matches!(context.block.block().statement, Statement::LapMarker(_))
                && let Some(code) = context.block.word(command.code_word)
            {
                let code_text = String::from_utf8_lossy(context.block.text(code.span));
                out.push_str(&format!(" of a LAP contour block (`{code_text}`); `G85`–`G88 N…` name it"));
            }
            out
        }
        WordKind::Label { .. } => match parameter_line(context, id, word, text) {
            Some(line) => line,
            None => format!("**{text}**: jump target, the block with this sequence name"),
        },
        WordKind::ProgramName => format!("**{text}**: program name; `CALL`/`M98 P` name it"),
        WordKind::ProgramRef => format!("**{text}**: the program this block calls"),
        WordKind::Keyword { index } => {
            let name = tables.keyword_name(index as usize);
            format!("**{name}** ({dialect}): {}", keyword_meaning(tables.keyword_info(index as usize).kind))
        }
        WordKind::Header => format!("**{text}**: Okuma file header (program file name)"),
        WordKind::TapeMark => "**%**: tape mark; the control reads from the first to the second".to_string(),
        WordKind::BlockDelete { level } => {
            format!("**{text}**: block delete (level {level}); the block is skipped when the switch is on")
        }
        WordKind::OptionalSkip { .. } => "**/**: the rest of the block is skipped when block delete is on".to_string(),
        WordKind::Assign { .. } => format!("**{text}**: variable assignment"),
        WordKind::Operand { .. } | WordKind::Comment(_) | WordKind::Verbatim => return None,
    })
}

fn g_code(context: &Context<'_>, id: WordId, code: crate::dialect::Code) -> String {
    let tables = context.tables;
    let dialect = context.dialect();
    let name = code.display('G');
    let Some(info) = tables.g(code) else {
        let mut out = format!("**{name}** ({dialect}): not a G code of this dialect");
        if let Some(elsewhere) = tables.g_elsewhere(code) {
            let place = match elsewhere.place {
                Place::GCodeSystem(system) => format!("G-code system {system:?}"),
                Place::OspMachiningCentre => "OSP machining centres".to_string(),
                Place::OspLathe => "OSP lathes".to_string(),
            };
            out.push_str(&format!("; on {place} it is {}", elsewhere.meaning));
        }
        if let Some(hint) = tables.foreign_g(code) {
            out.push_str(&format!("\n\n{hint}"));
        }
        return out;
    };
    let mut out = format!("**{name}** ({dialect}): {}", info.meaning);
    if let Some(note) = &info.note {
        out.push_str(&format!(" ({note})"));
    }
    let Some((command, form)) = context.command() else { return out };
    if id != command.code_word {
        return out;
    }
    let _ = write!(out, "\n\nForm `{}`; takes {}.", form.name, form.allowed_list());
    if !command.params.is_empty() {
        out.push_str("\n\n| word | role | meaning | unit |\n|---|---|---|---|");
        for param in &command.params {
            let Some(param_word) = context.block.word(param.word) else { continue };
            let param_text = String::from_utf8_lossy(context.block.text(param_word.span));
            let (meaning, unit) = roles::describe(param.role);
            let unit = unit_of(context, form, param_word, unit);
            let _ = write!(out, "\n| `{param_text}` | `{}` | {meaning} | {unit} |", roles::role_name(param.role));
        }
    }
    out
}

/// "`U0.4`: `allowance_x` of `G71` — …", when the word is a parameter of the block's command.
fn parameter_line(context: &Context<'_>, id: WordId, word: &Word, text: &str) -> Option<String> {
    let (command, form) = context.command()?;
    let param = command.params.iter().find(|p| p.word == id)?;
    let code = context.block.word(command.code_word)?;
    let code_text = String::from_utf8_lossy(context.block.text(code.span));
    let meaning = match code.kind {
        WordKind::Code { code, .. } => context.tables.g(code).map_or("", |g| g.meaning.as_str()),
        _ => "",
    };
    let (role_meaning, unit) = roles::describe(param.role);
    let unit = unit_of(context, form, word, unit);
    Some(format!(
        "**{text}**: `{}` of `{code_text}` ({}: {meaning})\n\n{role_meaning}; unit: {unit}",
        roles::role_name(param.role),
        context.dialect()
    ))
}

fn unit_of(context: &Context<'_>, form: &Form, word: &Word, unit: Unit) -> String {
    let (address, increments) = match word.kind {
        WordKind::Number { address, number } => (Some(address), !number.has_point()),
        WordKind::Expr { address, .. } => (Some(address), false),
        _ => (None, false),
    };
    match address {
        Some(address) => {
            roles::word_unit_text(form, address, unit, context.settings, context.tables.config.dialect, increments)
        }
        None => roles::unit_text(unit, context.settings, context.tables.config.dialect, false),
    }
}

/// "`X10.5` (Fanuc): X position (diameter) or dwell (s); unit: mm", for a word outside a
/// command's schema.
fn address_line(context: &Context<'_>, address: Address, text: &str) -> String {
    let dialect = context.dialect();
    let Some(spec) = context.tables.address(address) else {
        return format!("**{text}** ({dialect}): `{address:?}` is no address of this dialect");
    };
    let unit = match spec.kind {
        AddressKind::Length => Some(Unit::Length),
        AddressKind::Feed => Some(Unit::Feed),
        AddressKind::Angle => Some(Unit::Angle),
        AddressKind::Speed => Some(Unit::Speed),
        AddressKind::Tool | AddressKind::Code => Some(Unit::Code),
        AddressKind::Integer | AddressKind::Number => None,
    };
    let unit = if address == Address::X && spec.kind == AddressKind::Length { Some(Unit::XLength) } else { unit };
    let mut out = format!("**{text}** ({dialect}): {}", spec.meaning);
    if let Some(unit) = unit {
        let unit = roles::unit_text(unit, context.settings, context.tables.config.dialect, false);
        out.push_str(&format!("; unit: {unit}"));
    }
    out
}

/// What a Fanuc length or feed word written without a decimal point reads as, when the
/// machine's decimal input decides it: least increments (`decimal_input = "increment"`), or
/// the default calculator input while the settings do not say.
fn as_read(context: &Context<'_>, address: Address, number: Number, text: &str) -> Option<String> {
    let tables = context.tables;
    if tables.config.dialect != Dialect::Fanuc || number.has_point() || number.mantissa == 0 {
        return None;
    }
    // A word the command counts (`G76 P920`) says so in its unit already.
    if context.command().is_some_and(|(_, form)| form.counts_without_point(address)) {
        return None;
    }
    let kind = tables.address(address)?.kind;
    if !matches!(kind, AddressKind::Length | AddressKind::Feed) {
        return None;
    }
    let settings = context.settings;
    let inch = settings.units == Some(Units::Inch);
    let unit = if inch { "in" } else { "mm" };
    let increment = settings.least_increment.unwrap_or(if inch { 0.0001 } else { 0.001 });
    let written = number.to_f64();
    let counted = number.mantissa as f64 * increment;
    let (counted, written) = (roles::short_value(counted), roles::short_value(written));
    let feed = kind == AddressKind::Feed;
    let as_increments = if feed {
        format!("{counted} {unit}/rev as a feed per revolution (a feed per minute reads {written} {unit}/min)")
    } else {
        format!("{counted} {unit}")
    };
    match settings.decimal_input {
        Some(DecimalInput::Increment) => Some(format!(
            "as read: {as_increments}; without a decimal point the control counts least increments \
             (`{text}.` is {written} {unit}{})",
            if feed { "/rev" } else { "" }
        )),
        None if !feed => Some(format!(
            "as read: {written} {unit}, with calculator input (the default: the settings do not give \
             `decimal_input`); {as_increments} on a control that counts least increments"
        )),
        _ => None,
    }
}

fn keyword_meaning(kind: KeywordKind) -> &'static str {
    match kind {
        KeywordKind::If => "conditional jump or assignment",
        KeywordKind::Goto => "jump to a sequence name",
        KeywordKind::Then => "the statement an `IF` runs",
        KeywordKind::While => "loop while the condition holds",
        KeywordKind::Do => "start of a `WHILE` loop",
        KeywordKind::EndLoop => "end of a `WHILE` loop",
        KeywordKind::Call => "subprogram call",
        KeywordKind::Return => "return from a subprogram",
        KeywordKind::ModalCall => "modal subprogram call (after every move)",
        KeywordKind::ModalCallEnd => "end of the modal subprogram call",
        KeywordKind::Io => "external output statement",
        KeywordKind::Schedule => "schedule program statement",
        KeywordKind::Graphics => "graphics statement, ignored by the machine's motion",
        KeywordKind::Pattern => "hole pattern statement (machining centre)",
    }
}
