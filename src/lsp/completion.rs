//! Completion and signature help, read from the line being typed.
//!
//! While a block is being typed it rarely parses (`G71 P` has no value yet), so both read
//! the line's text around the cursor ([`LineContext`]) and take every fact from the dialect
//! tables of `grammar/`: the G and M codes of the file's dialect with their meaning, the
//! words a cycle's schema takes with their role and unit, and from the program the
//! sequence names (`names.rs`) a `P`/`Q`, a jump or a LAP call can name and its programs.

use std::collections::BTreeSet;

use lsp_types::{
    CompletionItem, CompletionItemKind, CompletionTextEdit, Documentation, MarkupContent, MarkupKind,
    ParameterInformation, ParameterLabel, SignatureHelp, SignatureInformation, TextEdit,
};

use crate::dialect::tables::{GKind, Schema, SequenceStyle};
use crate::dialect::{Address, Code, KeywordKind, Role, Tables};
use crate::machine::MachineSettings;
use crate::semantic::labels;
use crate::source::Span;
use crate::syntax::{Statement, WordKind};

use super::document::Document;
use super::names::{self, Use};
use super::roles;

/// The line around the cursor, as typed.
struct LineContext {
    /// The line's text up to the cursor.
    before: Vec<u8>,
    /// Where the token being typed starts, in `before`.
    token_start: usize,
    /// The document offset of the line's start.
    line_start: usize,
    /// The whole line's text.
    line: Vec<u8>,
}

impl LineContext {
    fn at(document: &Document, offset: usize) -> Option<LineContext> {
        let line = document.position_of(offset, false).line;
        let (line_start, text) = document.line(line)?;
        let cursor = offset.checked_sub(line_start)?.min(text.len());
        let before = text[..cursor].to_vec();
        let token_start = before.iter().rposition(|c| !(c.is_ascii_alphanumeric() || *c == b'.')).map_or(0, |p| p + 1);
        Some(LineContext { before, token_start, line_start, line: text.to_vec() })
    }

    fn token(&self) -> &[u8] {
        &self.before[self.token_start..]
    }

    /// The span the completion replaces: the token typed so far.
    fn token_span(&self) -> Span {
        let start = (self.line_start + self.token_start) as u32;
        Span::new(start, start + self.token().len() as u32)
    }

    /// The words of the line outside comments, as address letters and the text after them.
    fn words(&self) -> Vec<(Address, String)> {
        words_of(&self.line)
    }

    /// The word before the token (`GOTO`, `CALL`), upper case.
    fn previous_word(&self) -> String {
        let before = String::from_utf8_lossy(&self.before[..self.token_start]).into_owned();
        before.split_whitespace().last().unwrap_or("").to_string()
    }
}

/// The words of a line's text: letters (one, or two before `=`) and the value after them,
/// comments left out.
fn words_of(line: &[u8]) -> Vec<(Address, String)> {
    let mut words = Vec::new();
    let mut at = 0;
    while at < line.len() {
        let c = line[at];
        if c == b'(' {
            at += line[at..].iter().position(|&c| c == b')').map_or(line.len() - at, |p| p + 1);
            continue;
        }
        if c == b';' {
            break;
        }
        if !c.is_ascii_uppercase() {
            at += 1;
            continue;
        }
        let letters = line[at..].iter().take_while(|c| c.is_ascii_uppercase()).count();
        let (address, len) = if letters == 2 && line.get(at + 2) == Some(&b'=') {
            (Address::extended(line[at], line[at + 1]), 2)
        } else if letters == 1 {
            (Address::letter(c), 1)
        } else {
            // A name or a keyword (`GOTO`, `CALL`): not an address word.
            at += letters;
            continue;
        };
        let value_len = line[at + len..]
            .iter()
            .take_while(|c| c.is_ascii_alphanumeric() || matches!(c, b'.' | b'-' | b'+' | b'='))
            .count();
        words.push((address, String::from_utf8_lossy(&line[at + len..at + len + value_len]).into_owned()));
        at += len + value_len;
    }
    words
}

/// The G code of the line with a schema (a cycle, a LAP call, a dwell): its code, kind and
/// meaning.
fn command_code(tables: &'static Tables, words: &[(Address, String)]) -> Option<(Code, GKind, &'static str)> {
    words.iter().filter(|(a, _)| *a == Address::G).find_map(|(_, value)| {
        let code = parse_code(value)?;
        let info = tables.g(code)?;
        info.schema?;
        Some((code, info.kind, info.meaning.as_str()))
    })
}

fn parse_code(value: &str) -> Option<Code> {
    let (major, minor) = value.split_once('.').unwrap_or((value, "0"));
    if major.is_empty() || !major.bytes().all(|c| c.is_ascii_digit()) || minor.len() != 1 {
        return None;
    }
    let major: u16 = major.parse().ok()?;
    let minor: u16 = minor.parse().ok()?;
    (major <= 999).then(|| Code(major * 10 + minor))
}

/// The completions at byte `offset`.
pub fn completion(document: &Document, offset: usize, settings: &MachineSettings) -> Vec<CompletionItem> {
    let Some(context) = LineContext::at(document, offset) else { return Vec::new() };
    let tables = document.config().tables();
    let token = String::from_utf8_lossy(context.token()).into_owned();
    let words = context.words();
    let command = command_code(tables, &words);
    let previous = context.previous_word();
    let keyword = tables.keyword(previous.as_bytes()).map(|(_, info)| info.kind);
    let item = |label: String, kind: CompletionItemKind, detail: String| CompletionItem {
        label: label.clone(),
        kind: Some(kind),
        detail: Some(detail),
        text_edit: Some(CompletionTextEdit::Edit(TextEdit {
            range: document.range(context.token_span()),
            new_text: label,
        })),
        ..CompletionItem::default()
    };

    // A jump's target: `GOTO ` on either dialect, `IF [...] ` on OSP.
    if keyword == Some(KeywordKind::Goto) || (previous.ends_with(']') && context.line.starts_with(b"IF")) {
        // OSP jumps name the block with its `N` (`GOTO NAT00`), Fanuc's by number (`GOTO 10`).
        let letter = if tables.lexical.sequence == SequenceStyle::Osp { "N" } else { "" };
        return sequences(document, |_| true)
            .into_iter()
            .map(|(written, block)| (format!("{letter}{written}"), block))
            .filter(|(written, _)| written.starts_with(&token))
            .map(|(written, block)| item(written, CompletionItemKind::REFERENCE, block))
            .collect();
    }
    if matches!(keyword, Some(KeywordKind::Call | KeywordKind::ModalCall)) {
        return programs(document)
            .into_iter()
            .filter(|(name, _)| name.starts_with(&token))
            .map(|(name, block)| item(name, CompletionItemKind::MODULE, block))
            .collect();
    }
    let mut letters = token.bytes().take_while(u8::is_ascii_uppercase);
    let (first, second) = (letters.next(), letters.next());
    let rest_is_number = token.bytes().skip(1).all(|c| c.is_ascii_digit() || c == b'.');
    match (first, second) {
        (Some(b'G'), None) if rest_is_number => return g_codes(tables, &token, &item),
        (Some(b'M'), None) if rest_is_number => return m_codes(tables, &token, &item),
        (Some(b'N'), _) if command.is_some_and(|(_, kind, _)| kind == GKind::LapCall) => {
            // The contour names a LAP call can name: the blocks that start a contour.
            return sequences(document, |n| n.contour)
                .into_iter()
                .map(|(written, block)| (format!("N{written}"), block))
                .filter(|(written, _)| written.starts_with(&token))
                .map(|(written, block)| item(written, CompletionItemKind::REFERENCE, block))
                .collect();
        }
        (Some(letter @ (b'P' | b'Q')), None) if rest_is_number => {
            let role = command.and_then(|(code, _, _)| {
                let schema = tables.schema(tables.g(code)?.schema?);
                schema.forms.iter().find_map(|f| f.role_of(Address::letter(letter)))
            });
            let returns = words.iter().any(|(a, v)| {
                *a == Address::M && v.parse::<u16>().is_ok_and(|m| tables.m_functions.subprogram_return.contains(&m))
            });
            if matches!(role, Some(Role::ProfileStart | Role::ProfileEnd)) || (letter == b'P' && returns) {
                return sequences(document, |n| n.key.bytes().all(|c| c.is_ascii_digit()))
                    .into_iter()
                    .map(|(written, block)| (format!("{}{written}", letter as char), block))
                    .filter(|(written, _)| written.starts_with(&token))
                    .map(|(written, block)| item(written, CompletionItemKind::REFERENCE, block))
                    .collect();
            }
        }
        _ => {}
    }
    // A cycle's words, the ones the block does not have yet.
    if let Some((code, _, meaning)) = command
        && token.bytes().all(|c| c.is_ascii_uppercase())
        && token.len() <= 2
    {
        let present: BTreeSet<Address> = words.iter().map(|(a, _)| *a).collect();
        let Some(schema) = tables.g(code).and_then(|g| g.schema).map(|id| tables.schema(id)) else { return Vec::new() };
        let dialect = tables.config.dialect;
        let mut seen = BTreeSet::new();
        let mut items = Vec::new();
        // The forms the block can still be: those that take every word it has.
        let fits =
            |form: &&crate::dialect::Form| present.iter().all(|a| *a == Address::G || form.role_of(*a).is_some());
        for form in schema.forms.iter().filter(fits) {
            for (address, role) in &form.words {
                if present.contains(address) || !seen.insert(*address) || !address.name().starts_with(&token) {
                    continue;
                }
                let (role_meaning, unit) = roles::describe(*role);
                let unit = roles::word_unit_text(form, *address, unit, settings, dialect, true);
                let detail = format!("{}: {role_meaning} ({unit})", roles::role_name(*role));
                let mut completion = item(address.name(), CompletionItemKind::PROPERTY, detail);
                completion.documentation = Some(Documentation::String(format!(
                    "{} of {} ({meaning}), form `{}`",
                    roles::role_name(*role),
                    code.display('G'),
                    form.name
                )));
                items.push(completion);
            }
        }
        return items;
    }
    Vec::new()
}

fn g_codes(
    tables: &Tables,
    token: &str,
    item: &dyn Fn(String, CompletionItemKind, String) -> CompletionItem,
) -> Vec<CompletionItem> {
    tables
        .g_infos()
        .iter()
        .filter(|g| typed_matches(g.code, 'G', token))
        .map(|g| {
            let kind = match g.kind {
                GKind::Cycle | GKind::LapCall => CompletionItemKind::FUNCTION,
                _ => CompletionItemKind::KEYWORD,
            };
            let detail = match &g.note {
                Some(note) => format!("{} ({note})", g.meaning),
                None => g.meaning.clone(),
            };
            item(g.code.display('G'), kind, detail)
        })
        .collect()
}

fn m_codes(
    tables: &Tables,
    token: &str,
    item: &dyn Fn(String, CompletionItemKind, String) -> CompletionItem,
) -> Vec<CompletionItem> {
    tables
        .m_codes()
        .into_iter()
        .filter(|(code, _)| typed_matches(Code::whole(*code), 'M', token))
        .map(|(code, meaning)| item(Code::whole(code).display('M'), CompletionItemKind::KEYWORD, meaning.to_string()))
        .collect()
}

/// Whether a code is one the typed token can start: `G7` starts `G71`, `G1` starts `G01`
/// and `G12.1` (machinists leave out the leading zero).
fn typed_matches(code: Code, letter: char, token: &str) -> bool {
    let shown = code.display(letter);
    let short = if code.minor() == 0 {
        format!("{letter}{}", code.major())
    } else {
        format!("{letter}{}.{}", code.major(), code.minor())
    };
    shown.starts_with(token) || short.starts_with(token)
}

/// The sequence names of the program that `keep` accepts, once each, as written after `N`,
/// with the text of the block that has the name.
fn sequences(document: &Document, keep: impl Fn(&names::Name) -> bool) -> Vec<(String, String)> {
    let mut seen = BTreeSet::new();
    names::all(document)
        .into_iter()
        .filter(|n| n.use_ == Use::Definition && keep(n))
        .filter_map(|n| {
            let written = String::from_utf8_lossy(&document.text_of(n.name)).into_owned();
            seen.insert(written.clone()).then(|| (written, block_text(document, n.block)))
        })
        .collect()
}

/// The program names of the file (`OSUB`, `O1000`), with their block.
fn programs(document: &Document) -> Vec<(String, String)> {
    let dialect = document.config().dialect;
    let mut seen = BTreeSet::new();
    let mut found = Vec::new();
    for block in document.blocks().filter(|b| b.block().statement == Statement::ProgramName) {
        for word in block.words().iter().filter(|w| matches!(w.kind, WordKind::ProgramName)) {
            let text = String::from_utf8_lossy(block.text(word.span)).into_owned();
            if seen.insert(labels::program_key(dialect, text.as_bytes())) {
                found.push((text, block_text(document, block.absolute(block.block().span))));
            }
        }
    }
    found
}

fn block_text(document: &Document, span: Span) -> String {
    String::from_utf8_lossy(&document.text_of(span)).trim().chars().take(60).collect()
}

/// Signature help in a cycle block whose schema has several forms (the two-block cycles
/// `G71`–`G76`, whose first and second blocks take different words): every form, the one
/// the block's words make active, and the word at the cursor.
pub fn signature_help(document: &Document, offset: usize, settings: &MachineSettings) -> Option<SignatureHelp> {
    let context = LineContext::at(document, offset)?;
    let tables = document.config().tables();
    let words = context.words();
    let (code, _, meaning) = command_code(tables, &words)?;
    let schema: &Schema = tables.schema(tables.g(code)?.schema?);
    if schema.forms.len() < 2 {
        return None;
    }
    let present: BTreeSet<Address> = words.iter().map(|(a, _)| *a).filter(|a| *a != Address::G).collect();
    let active = schema.forms.iter().position(|f| f.matches(|a| present.contains(&a))).unwrap_or(0);
    // The word at the cursor: the letters of the token being typed.
    let typing = words_of(&context.before).last().map(|(a, _)| *a);
    let dialect = tables.config.dialect;
    let name = code.display('G');
    let signatures = schema
        .forms
        .iter()
        .map(|form| {
            let mut label = name.clone();
            let mut parameters = Vec::new();
            for (address, role) in &form.words {
                label.push(' ');
                let start = label.encode_utf16().count() as u32;
                label.push_str(&format!("{}({})", address.name(), roles::role_name(*role)));
                let end = label.encode_utf16().count() as u32;
                let (role_meaning, unit) = roles::describe(*role);
                let unit = roles::word_unit_text(form, *address, unit, settings, dialect, true);
                parameters.push(ParameterInformation {
                    label: ParameterLabel::LabelOffsets([start, end]),
                    documentation: Some(Documentation::String(format!("{role_meaning}; unit: {unit}"))),
                });
            }
            let active_parameter =
                typing.and_then(|a| form.words.iter().position(|(address, _)| *address == a)).map(|p| p as u32);
            let required = if form.required.is_empty() {
                String::new()
            } else {
                let names: Vec<String> = form.required.iter().map(|a| format!("`{}`", a.name())).collect();
                format!("; needs {}", names.join(", "))
            };
            SignatureInformation {
                label,
                documentation: Some(Documentation::MarkupContent(MarkupContent {
                    kind: MarkupKind::Markdown,
                    value: format!("**{name}** ({}): {meaning}, form `{}`{required}", dialect.name(), form.name),
                })),
                parameters: Some(parameters),
                active_parameter,
            }
        })
        .collect::<Vec<_>>();
    let active_parameter = signatures[active].active_parameter;
    Some(SignatureHelp { signatures, active_signature: Some(active as u32), active_parameter })
}
