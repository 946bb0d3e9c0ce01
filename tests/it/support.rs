//! The test harness: reading cases, the AST dump, diagnostics rendering, span invariants,
//! and what a test needs from outside the repository (`external`).

use std::fmt::Write as _;
use std::path::PathBuf;

use turnpass::diagnostic::Diagnostic;
use turnpass::diagnostic::render::{RenderSource, render_plain};
use turnpass::dialect::{Address, DialectChoice, GCodeSystem, MachineKind};
use turnpass::printer::canonical::write_expr_string;
use turnpass::syntax::spelling::plain;
use turnpass::syntax::{ParseOptions, Parsed, Program, Statement, Word, WordKind};

pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The case files of a folder with the extension `extension`, in name order (the order of the
/// snapshots and of a report of failures).
pub fn case_files(dir: &std::path::Path, extension: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|error| panic!("{}: {error}", dir.display()))
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == extension))
        .collect();
    files.sort();
    files
}

/// Options from a first-line pragma comment, `(turnpass: dialect=osp gcode_system=B)`.
/// Without one, the dialect is detected and the G-code system is A.
pub fn options_for(source: &[u8]) -> ParseOptions {
    let mut options = ParseOptions {
        dialect: DialectChoice::Auto,
        gcode_system: GCodeSystem::A,
        machine_kind: None,
        control: Default::default(),
    };
    for (key, value) in pragma(source) {
        match (key.as_str(), value.as_str()) {
            ("dialect", value) => options.dialect = value.parse().unwrap(),
            ("gcode_system", value) => options.gcode_system = value.parse().unwrap(),
            ("control", value) => options.control = value.parse().unwrap(),
            ("machine", "lathe") => options.machine_kind = Some(MachineKind::Lathe),
            ("machine", "mc") => options.machine_kind = Some(MachineKind::MachiningCentre),
            ("decimal_input" | "increment_places", _) => {}
            _ => panic!("unknown pragma setting `{key}={value}`"),
        }
    }
    options
}

/// Canonical-form settings from the same pragma: `decimal_input=increment increment_places=4`.
pub fn canonical_options_for(source: &[u8]) -> turnpass::printer::CanonicalOptions {
    let mut options = turnpass::printer::CanonicalOptions {
        decimal_input: turnpass::dialect::DecimalInput::Calculator,
        increment_places: 3,
    };
    for (key, value) in pragma(source) {
        match (key.as_str(), value.as_str()) {
            ("decimal_input", "increment") => options.decimal_input = turnpass::dialect::DecimalInput::Increment,
            ("increment_places", places) => options.increment_places = places.parse().unwrap(),
            _ => {}
        }
    }
    options
}

fn pragma(source: &[u8]) -> Vec<(String, String)> {
    let first_line = source.split(|&c| c == b'\n' || c == b'\r').next().unwrap_or(b"");
    let text = String::from_utf8_lossy(first_line).into_owned();
    let Some(rest) = text.trim().strip_prefix("(turnpass:") else { return Vec::new() };
    rest.trim_end_matches(')')
        .split_whitespace()
        .filter_map(|s| s.split_once('=').map(|(k, v)| (k.to_string(), v.to_string())))
        .collect()
}

/// `source` through the library's pipeline (`pipeline::analyse`: parse, lower, validate),
/// its parse checked for the span invariants: how every test that runs a program past
/// parsing enters.
pub fn analyse<'s>(source: &'s [u8], settings: &turnpass::pipeline::Settings) -> turnpass::pipeline::Analysed<'s> {
    let analysed = turnpass::pipeline::analyse(source, settings);
    check_spans(&analysed.parsed);
    analysed
}

/// [`analyse`] for a program that must be ready for the passes after lowering (no error,
/// its toolpath valid); the test fails with the program and its diagnostics otherwise.
pub fn ready<'s>(source: &'s [u8], settings: &turnpass::pipeline::Settings) -> turnpass::pipeline::Ready<'s> {
    match analyse(source, settings).ready() {
        Ok(ready) => ready,
        Err(analysed) => panic!(
            "the program is not ready:\n{}\n{}",
            String::from_utf8_lossy(source),
            render("program", source, &analysed.diagnostics)
        ),
    }
}

pub fn render(name: &str, source: &[u8], diagnostics: &[Diagnostic]) -> String {
    render_plain(&RenderSource::new(name, source), diagnostics)
}

/// The span invariants every parse must keep:
/// * blocks tile the source: the first starts at 0, the bytes between blocks are exactly one
///   line terminator (inside OSP continuations too), the last runs to the end or its
///   terminator, and only a `Trailing` block may hold several lines;
/// * every word lies inside its block, words are in order and do not overlap;
/// * every expression node lies inside the word that holds it;
/// * every command parameter names a word of its own block.
pub fn check_spans(parsed: &Parsed<'_>) {
    let program = &parsed.program;
    let source = program.source();
    let blocks = program.blocks();
    if source.is_empty() {
        assert!(blocks.is_empty());
        return;
    }
    assert_eq!(blocks[0].span.start, 0, "the first block starts at 0");
    for (index, block) in blocks.iter().enumerate() {
        assert!(block.span.start <= block.span.end && block.span.end as usize <= source.len());
        let terminator = program.terminator(index);
        let last = index + 1 == blocks.len();
        if block.statement != Statement::Trailing {
            assert!(
                matches!(terminator, b"\n" | b"\r\n" | b"\r") || (last && terminator.is_empty()),
                "block {index} ends with {terminator:?}"
            );
        }
        let mut previous_end = block.span.start;
        for word in program.words_of(block) {
            assert!(block.span.contains(word.span), "word {:?} outside block {:?}", word.span, block.span);
            assert!(word.span.start >= previous_end, "words overlap or are out of order in block {index}");
            assert!(word.span.start < word.span.end || matches!(word.kind, WordKind::Comment(_)), "empty word");
            previous_end = word.span.end;
            for expr in expr_ids(word) {
                check_expr(program, expr, word.span);
            }
        }
        let command = match block.statement {
            Statement::Cycle(id)
            | Statement::LapCall(id)
            | Statement::LapMarker(id)
            | Statement::Dwell(id)
            | Statement::OneShot(id) => Some(program.command(id)),
            _ => None,
        };
        if let Some(command) = command {
            let range = block.word_ids();
            assert!(range.contains(&command.code_word));
            for param in &command.params {
                assert!(range.contains(&param.word), "parameter outside its block");
            }
        }
    }
    for d in &parsed.diagnostics {
        assert!(d.span.end as usize <= source.len(), "diagnostic span out of the source");
    }
}

fn expr_ids(word: &Word) -> Vec<u32> {
    match word.kind {
        WordKind::Expr { expr, .. } | WordKind::Operand { expr } => vec![expr],
        WordKind::Assign { target, value } => vec![target, value],
        _ => Vec::new(),
    }
}

fn check_expr(program: &Program<'_>, id: u32, within: turnpass::source::Span) {
    use turnpass::syntax::{ExprKind, Variable};
    let expr = program.expr(id);
    assert!(within.contains(expr.span), "expression {:?} outside {:?}", expr.span, within);
    let children: Vec<u32> = match expr.kind {
        ExprKind::Unary { operand, .. } => vec![operand],
        ExprKind::Binary { lhs, rhs, .. } => vec![lhs, rhs],
        ExprKind::Call { args, arg_count, .. } => args[..arg_count as usize].to_vec(),
        ExprKind::Group(inner) => vec![inner],
        ExprKind::Variable(Variable::Indexed { index, .. } | Variable::Hash { index }) => vec![index],
        _ => Vec::new(),
    };
    for child in children {
        check_expr(program, child, expr.span);
    }
}

/// A compact, readable dump of the AST: one line per block.
pub fn dump(program: &Program<'_>) -> String {
    let tables = program.config().tables();
    let source = program.source();
    let lines = turnpass::source::LineIndex::new(source);
    let mut out = String::new();
    for block in program.blocks() {
        let line = lines.position(block.span.start).0;
        let statement = match block.statement {
            Statement::Cycle(_) => "Cycle",
            Statement::LapCall(_) => "LapCall",
            Statement::LapMarker(_) => "LapMarker",
            Statement::Dwell(_) => "Dwell",
            Statement::OneShot(_) => "OneShot",
            other => match other {
                Statement::Empty => "Empty",
                Statement::TapeMark => "TapeMark",
                Statement::Header => "Header",
                Statement::ProgramName => "ProgramName",
                Statement::Motion => "Motion",
                Statement::ThreadMove => "ThreadMove",
                Statement::ToolCall => "ToolCall",
                Statement::Spindle => "Spindle",
                Statement::Control => "Control",
                Statement::Assignment => "Assignment",
                Statement::Graphics => "Graphics",
                Statement::Pattern => "Pattern",
                Statement::Settings => "Settings",
                Statement::Invalid => "Invalid",
                Statement::Trailing => "Trailing",
                Statement::Leader => "Leader",
                _ => unreachable!(),
            },
        };
        let _ = write!(out, "{line:>4} {statement:<12}");
        for word in program.words_of(block) {
            out.push(' ');
            out.push_str(&word_text(program, word));
        }
        if let Statement::Cycle(id)
        | Statement::LapCall(id)
        | Statement::LapMarker(id)
        | Statement::Dwell(id)
        | Statement::OneShot(id) = block.statement
        {
            let command = program.command(id);
            let schema = tables.schema(command.schema);
            let form = &schema.forms[command.form as usize];
            let _ = write!(out, "  => {}/{}", schema.name, form.name);
            if !command.params.is_empty() {
                let params: Vec<String> = command
                    .params
                    .iter()
                    .map(|p| {
                        format!("{:?}={}", p.role, String::from_utf8_lossy(program.text(program.word(p.word).span)))
                    })
                    .collect();
                let _ = write!(out, " {{{}}}", params.join(", "));
            }
        }
        out.push('\n');
    }
    out
}

fn word_text(program: &Program<'_>, word: &Word) -> String {
    let text = || String::from_utf8_lossy(program.text(word.span)).into_owned();
    let tables = program.config().tables();
    match word.kind {
        WordKind::Sequence { .. } => format!("seq:{}", text()),
        WordKind::BlockDelete { level } => format!("delete/{level}"),
        WordKind::OptionalSkip { level } => format!("skip/{level}"),
        WordKind::TapeMark => "%".into(),
        WordKind::Header => format!("header:{}", text()),
        WordKind::ProgramName => format!("name:{}", text()),
        WordKind::Comment(_) => format!("comment:{}", text()),
        WordKind::Code { letter, code } => code.display(letter.as_char()),
        WordKind::Number { address, number } if number.flags.contains(turnpass::syntax::NumberFlags::LEADING_ZEROS) => {
            format!(
                "{}={}",
                address_name(address),
                text().trim_start_matches(|c: char| c.is_ascii_uppercase() || c == '=')
            )
        }
        WordKind::Number { address, number } => format!("{}={}", address_name(address), plain(number)),
        WordKind::Expr { address, expr } => {
            format!("{}=expr:{}", address_name(address), write_expr_string(program, expr))
        }
        WordKind::Label { .. } => format!("label:{}", text()),
        WordKind::ProgramRef => format!("ref:{}", text()),
        WordKind::Keyword { index } => format!("kw:{}", tables.keyword_name(index as usize)),
        WordKind::Operand { expr } => format!("operand:{}", write_expr_string(program, expr)),
        WordKind::Assign { target, value } => {
            format!("{}:={}", write_expr_string(program, target), write_expr_string(program, value))
        }
        WordKind::Verbatim => format!("verbatim:{:?}", text()),
    }
}

fn address_name(address: Address) -> String {
    address.name()
}

/// Run `body` with insta writing to `snapshots/<dir>`.
pub fn with_snapshots(dir: &str, body: impl FnOnce()) {
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path(repo().join("snapshots").join(dir));
    settings.set_prepend_module_to_snapshot(false);
    settings.set_omit_expression(true);
    settings.bind(body);
}

/// What some tests need from outside the repository: the third-party corpus of real programs
/// (`../shared/corpus/` beside the repository, or where `TURNPASS_CORPUS` points; read in
/// place, never copied into the repository) and programs installed on the machine
/// (LinuxCNC's `rs274`, Neovim). When one is missing, the test that needs it is skipped
/// with a banner on standard error that says what did not run and why; under CI
/// (`TURNPASS_CI` set, as `.ci/run` does) a missing one fails the test, so CI never passes
/// without running them.
pub mod external {
    use std::io::Write as _;
    use std::path::{Path, PathBuf};

    /// Set by `.ci/run`: everything external must be present.
    pub const CI_VARIABLE: &str = "TURNPASS_CI";
    /// The corpus directory when it is not `../shared/corpus/` (relative to the repository).
    pub const CORPUS_VARIABLE: &str = "TURNPASS_CORPUS";

    /// The corpus directory, or `None` (after the banner) when it is missing.
    pub fn corpus() -> Option<PathBuf> {
        corpus_at(&current_test())
    }

    /// As [`corpus`], for the part of the test that `part` names (a command case, the
    /// corpus half of a test).
    pub fn corpus_for(part: &str) -> Option<PathBuf> {
        corpus_at(&format!("{}, {part}", current_test()))
    }

    fn corpus_at(what: &str) -> Option<PathBuf> {
        let (dir, from) = match std::env::var_os(CORPUS_VARIABLE).filter(|v| !v.is_empty()) {
            Some(dir) => (super::repo().join(dir), CORPUS_VARIABLE),
            None => (super::repo().join("../shared/corpus"), "the default, ../shared/corpus"),
        };
        if dir.is_dir() {
            return Some(dir);
        }
        missing(
            what,
            &format!(
                "the third-party corpus of real lathe programs is not at {} ({from}); it is read in \
                 place, never copied into the repository (README, \"Tests\")",
                dir.display()
            ),
        )
    }

    /// The full path of `name` found on the PATH, or `None` (after the banner) when it is not
    /// there; `package` is the Debian package that provides it.
    pub fn program(name: &str, package: &str) -> Option<PathBuf> {
        let path = std::env::var_os("PATH").unwrap_or_default();
        if let Some(found) = std::env::split_paths(&path).map(|dir| dir.join(name)).find(|p| is_executable(p)) {
            return Some(found);
        }
        missing(
            &current_test(),
            &format!("`{name}` is not on the PATH (Debian: apt install {package}; .ci/run installs it)"),
        )
    }

    fn is_executable(path: &Path) -> bool {
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt as _;
            path.metadata().is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
        }
        #[cfg(not(unix))]
        {
            path.is_file()
        }
    }

    /// The test's name: libtest runs each test on a thread named after it.
    fn current_test() -> String {
        std::thread::current().name().unwrap_or("this test").to_string()
    }

    fn in_ci() -> bool {
        std::env::var_os(CI_VARIABLE).is_some_and(|v| !v.is_empty() && v != "0")
    }

    /// Fails under CI; otherwise writes the banner and says to skip. The banner goes to the
    /// process's standard error directly, past libtest's capture of `eprintln!`, so a plain
    /// `cargo test` shows it although the test is then reported as passed.
    fn missing<T>(what: &str, reason: &str) -> Option<T> {
        assert!(!in_ci(), "{what}: {reason}; {CI_VARIABLE} is set, so this is a failure, not a skip");
        let rule = "#".repeat(78);
        let banner = format!(
            "\n{rule}\n# SKIPPED: {what}\n#   Not run: {reason}.\n#   cargo reports the test as ok, but this was \
             not tested; under .ci/run ({CI_VARIABLE}=1) it is a failure.\n{rule}\n"
        );
        let _ = std::io::stderr().lock().write_all(banner.as_bytes());
        None
    }
}
