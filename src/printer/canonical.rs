//! `fmt --canonical`: every parsed block in one normal form.
//!
//! One word order (sequence, G-codes, contour label, axes, centre and radius, other
//! parameters, F S T, M codes, assignments, comments), one space between words, two-digit
//! codes, and a decimal point on every length, angle and feed. On a least-increment Fanuc
//! control a length written without a point counts increments, so `X105` becomes `X0.105`
//! at 0.001 mm: the normal form says what the machine reads. Invalid blocks, headers and the
//! text after the closing `%` are copied as they are. Printing the output again gives the
//! same output (idempotence is tested).
//!
//! Words after a Fanuc mid-block `/` stay after it: the slash skips them when block delete
//! is on, so moving a word across it would change the program.

use crate::dialect::{Address, AddressKind, DecimalInput, Dialect, Form, Tables};
use crate::syntax::{
    CodeLetter, CommentKind, ExprId, ExprKind, Number, NumberFlags, Program, Statement, UnaryOp, Variable, Word,
    WordKind,
};

use super::write_code;
use crate::syntax::spelling::{Style as NumberStyle, plain, write_number};

/// Machine settings the normal form depends on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CanonicalOptions {
    pub decimal_input: DecimalInput,
    /// Decimal places of the least increment (3 for 0.001 mm, 4 for 0.0001 in).
    pub increment_places: u8,
}

pub fn print_canonical(program: &Program<'_>, options: &CanonicalOptions) -> Vec<u8> {
    let source = program.source();
    let mut out = Vec::with_capacity(source.len());
    let mut line = String::new();
    for (index, block) in program.blocks().iter().enumerate() {
        match block.statement {
            Statement::Invalid | Statement::Trailing | Statement::Leader | Statement::Header => {
                out.extend_from_slice(block.span.text(source));
            }
            statement => {
                line.clear();
                let form = command_form(program, statement);
                write_continued_block(&mut line, program, block.span, program.words_of(block), form, options);
                out.extend_from_slice(line.as_bytes());
            }
        }
        out.extend_from_slice(program.terminator(index));
    }
    out
}

/// The schema form of a command block, whose word list gives the canonical order.
fn command_form(program: &Program<'_>, statement: Statement) -> Option<&'static Form> {
    let id = match statement {
        Statement::Cycle(id)
        | Statement::LapCall(id)
        | Statement::LapMarker(id)
        | Statement::Dwell(id)
        | Statement::OneShot(id) => id,
        _ => return None,
    };
    let command = program.command(id);
    let tables: &'static Tables = program.config().tables();
    tables.schema(command.schema).forms.get(command.form as usize)
}

/// Sort key of a word in the normal form. In a command block the schema's own word order
/// comes first (`G71 P20 Q40 U0.4 W0.1 F0.3`, as machinists write it).
fn rank(word: &Word, form: Option<&Form>) -> (u8, u16) {
    if let (Some(form), WordKind::Number { address, .. } | WordKind::Expr { address, .. }) = (form, word.kind)
        && let Some(position) = form.position_of(address)
    {
        return (5, position as u16);
    }
    rank_plain(word)
}

fn rank_plain(word: &Word) -> (u8, u16) {
    match word.kind {
        WordKind::TapeMark | WordKind::Header => (0, 0),
        WordKind::ProgramName => (0, 1),
        WordKind::BlockDelete { .. } => (1, 0),
        WordKind::Sequence { .. } => (2, 0),
        WordKind::Code { letter: CodeLetter::G, .. } => (3, 0),
        WordKind::Label { .. } => (4, 0),
        WordKind::Number { address, .. } | WordKind::Expr { address, .. } => (5, 100 + address_order(address)),
        WordKind::Code { letter: CodeLetter::M, .. } => (6, 0),
        WordKind::Assign { .. } => (7, 0),
        WordKind::Comment(CommentKind::Paren) => (8, 0),
        WordKind::Comment(CommentKind::Semicolon) => (9, 0),
        // Keyword statements keep their order; see `write_block`.
        WordKind::Keyword { .. } | WordKind::Operand { .. } | WordKind::ProgramRef | WordKind::Verbatim => (3, 0),
        WordKind::OptionalSkip { .. } => (10, 0),
    }
}

/// Axes first (X U Y V Z W C H A B), then centre and radius (I J K R L), then the remaining
/// letters, the two-letter addresses, and F S T last.
fn address_order(address: Address) -> u16 {
    const ORDER: &[u8] = b"XUYVZWCHABIJKRLDEPQ";
    match address.as_letter() {
        Some(b'F') => 900,
        Some(b'S') => 901,
        Some(b'T') => 902,
        Some(letter) => match ORDER.iter().position(|&c| c == letter) {
            Some(p) => p as u16,
            None => 100 + letter as u16,
        },
        // A comma word belongs to the move: right after the coordinates and the centre.
        None if address.is_comma() => 50 + address.bytes().0[1] as u16,
        None => {
            let (bytes, _) = address.bytes();
            500 + (bytes[0] - b'A') as u16 * 26 + (bytes[1] - b'A') as u16
        }
    }
}

/// A block that may run over OSP `$` continuation lines: each line's words are put in order
/// on their own line, and the line break and `$` stay where they were (condition changes
/// of a LAP call belong on `$` lines).
fn write_continued_block(
    out: &mut String,
    program: &Program<'_>,
    span: crate::source::Span,
    words: &[Word],
    form: Option<&Form>,
    options: &CanonicalOptions,
) {
    let text = program.text(span);
    let mut from = 0;
    let mut line_start = span.start;
    loop {
        let rest = &text[(line_start - span.start) as usize..];
        let Some(line_break) = rest.iter().position(|&c| c == b'\n' || c == b'\r') else {
            write_block(out, program, &words[from..], form, options);
            return;
        };
        let line_end = line_start + line_break as u32;
        let until = words[from..].iter().position(|w| w.span.start >= line_end).map_or(words.len(), |p| from + p);
        write_block(out, program, &words[from..until], form, options);
        // Copy the line break and the `$` of the continuation line as they are.
        let after = &rest[line_break..];
        let dollar = after.iter().position(|&c| c == b'$').map_or(after.len(), |p| p + 1);
        out.push_str(&String::from_utf8_lossy(&after[..dollar]));
        out.push(' ');
        line_start = line_end + dollar as u32;
        from = until;
    }
}

fn write_block(
    out: &mut String,
    program: &Program<'_>,
    words: &[Word],
    form: Option<&Form>,
    options: &CanonicalOptions,
) {
    let keyword_statement = words.iter().any(|w| matches!(w.kind, WordKind::Keyword { .. }));
    // The comment that names a program (`O2012(Turn/Face)N1`) stays right after its name.
    let naming = words
        .windows(2)
        .find(|pair| {
            matches!(pair[0].kind, WordKind::ProgramName)
                && matches!(pair[1].kind, WordKind::Comment(CommentKind::Paren))
        })
        .map(|pair| pair[1].span);
    // Split at a mid-block skip: each part is ordered on its own.
    let split = words.iter().position(|w| matches!(w.kind, WordKind::OptionalSkip { .. })).unwrap_or(words.len());
    let mut first = true;
    for part in [&words[..split], &words[split..]] {
        let mut ordered: Vec<&Word> = part.iter().collect();
        if keyword_statement {
            ordered.sort_by_key(|w| match w.kind {
                WordKind::Comment(_) => rank_plain(w),
                _ => (rank_plain(w).0.min(3), 0),
            });
        } else {
            ordered.sort_by_key(|w| if Some(w.span) == naming { (0, 2) } else { rank(w, form) });
        }
        // The skip itself leads its part.
        ordered.sort_by_key(|w| !matches!(w.kind, WordKind::OptionalSkip { .. }));
        for word in ordered {
            if !first {
                out.push(' ');
            }
            first = false;
            write_word(out, program, word, form, options);
        }
    }
}

fn write_word(out: &mut String, program: &Program<'_>, word: &Word, form: Option<&Form>, options: &CanonicalOptions) {
    let tables = program.config().tables();
    let text = || String::from_utf8_lossy(program.text(word.span)).into_owned();
    match word.kind {
        WordKind::Sequence { number } => match (program.config().dialect, number) {
            (Dialect::Fanuc, Some(n)) => out.push_str(&format!("N{n}")),
            _ => out.push_str(&text()),
        },
        WordKind::BlockDelete { level } | WordKind::OptionalSkip { level } => {
            out.push('/');
            if level > 1 {
                out.push_str(&level.to_string());
            }
        }
        WordKind::TapeMark => out.push('%'),
        WordKind::Comment(CommentKind::Semicolon) => out.push_str(text().trim_end()),
        WordKind::Header
        | WordKind::ProgramName
        | WordKind::Comment(_)
        | WordKind::Label { .. }
        | WordKind::ProgramRef
        | WordKind::Verbatim => out.push_str(&text()),
        WordKind::Code { letter, code } => write_code(out, letter, code.major(), code.minor(), true),
        WordKind::Number { address, number } => {
            let kind = tables.address(address).map(|s| s.kind);
            // A command may take a count where the address is usually a length (`G73 R3`
            // divisions): its schema says so, and a point would make it an error.
            let integer = form.is_some_and(|f| f.counts_without_point(address));
            if !integer
                && matches!(
                    kind,
                    Some(AddressKind::Length | AddressKind::Angle | AddressKind::Feed | AddressKind::Speed)
                )
            {
                out.push_str(&address.name());
                if !address.is_letter() && !address.is_comma() {
                    out.push('=');
                }
                write_canonical_number(out, tables, address, number, options);
            } else {
                // Tool words, counts and codes keep their digits as written (`T0101`,
                // `P010060`): leading zeros carry meaning to the people who read them.
                out.extend(text().chars().filter(|c| !c.is_whitespace()));
            }
        }
        WordKind::Expr { address, expr } => {
            out.push_str(&address.name());
            if program.config().dialect == Dialect::Osp {
                out.push('=');
            }
            write_expr(out, program, expr);
        }
        WordKind::Keyword { index } => out.push_str(tables.keyword_name(index as usize)),
        WordKind::Operand { expr } => write_expr(out, program, expr),
        WordKind::Assign { target, value } => {
            write_expr(out, program, target);
            out.push('=');
            write_expr(out, program, value);
        }
    }
}

fn write_canonical_number(
    out: &mut String,
    tables: &Tables,
    address: Address,
    number: Number,
    options: &CanonicalOptions,
) {
    let kind = tables.address(address).map(|s| s.kind);
    match kind {
        Some(AddressKind::Length | AddressKind::Angle | AddressKind::Feed) => {
            let mut number = number;
            let increments =
                tables.config.dialect == Dialect::Fanuc && options.decimal_input == DecimalInput::Increment;
            if increments && !number.has_point() {
                if kind == Some(AddressKind::Feed) {
                    // A feed without a point counts the feed's own increment, which depends on
                    // the feed mode; writing a point would change the value, so keep it.
                    out.push_str(&plain(number));
                    return;
                }
                number.scale = number.scale.saturating_add(options.increment_places);
            }
            if number.mantissa == 0 {
                // `-0.` reads as zero; the normal form has one zero.
                number = Number::new(0, 0, true);
            }
            let style = NumberStyle { leading_zero: true, force_point: true, as_written: false, trim_zeros: true };
            write_number(out, number, style);
        }
        Some(AddressKind::Speed) => {
            let mut number = number;
            number.flags = NumberFlags::default();
            if number.mantissa < 0 {
                number.flags.insert(NumberFlags::MINUS);
            }
            let style = NumberStyle { leading_zero: true, force_point: false, as_written: false, trim_zeros: true };
            write_number(out, number, style);
        }
        _ => out.push_str(&plain(number)),
    }
}

/// An expression in normal form, as a string.
pub fn write_expr_string(program: &Program<'_>, id: ExprId) -> String {
    let mut out = String::new();
    write_expr(&mut out, program, id);
    out
}

/// An expression in normal form: symbols unspaced, word operators spaced, brackets kept.
pub(crate) fn write_expr(out: &mut String, program: &Program<'_>, id: ExprId) {
    let tables = program.config().tables();
    let expr = program.expr(id);
    match expr.kind {
        // Literals keep their spelling: `TL8=0609` names tool 06, offset 09.
        ExprKind::Number(number) if expr.span.is_synthetic() => out.push_str(&plain(number)),
        ExprKind::Number(_) => out.push_str(&String::from_utf8_lossy(program.text(expr.span))),
        ExprKind::Variable(variable) => match variable {
            Variable::Common(n) => out.push_str(&format!("V{n}")),
            Variable::Named => out.push_str(&String::from_utf8_lossy(program.text(expr.span))),
            Variable::Indexed { name, index } => {
                out.push_str(&String::from_utf8_lossy(program.text(name)));
                out.push('[');
                write_expr(out, program, index);
                out.push(']');
            }
            Variable::Hash { index } => {
                out.push('#');
                write_expr(out, program, index);
            }
        },
        ExprKind::Unary { op, operand } => {
            out.push_str(match op {
                UnaryOp::Minus => "-",
                UnaryOp::Plus => "+",
                UnaryOp::Not => "NOT ",
            });
            write_expr(out, program, operand);
        }
        ExprKind::Binary { op, lhs, rhs } => {
            write_expr(out, program, lhs);
            let xor = if program.config().dialect == Dialect::Osp { "EOR" } else { "XOR" };
            let symbol = op.symbol(xor);
            if op.is_word() {
                out.push(' ');
                out.push_str(symbol);
                out.push(' ');
            } else {
                out.push_str(symbol);
            }
            write_expr(out, program, rhs);
        }
        ExprKind::Call { function, args, arg_count } => {
            out.push_str(tables.expression.functions.get(function as usize).map_or("?", String::as_str));
            out.push('[');
            for (i, arg) in args.iter().take(arg_count as usize).enumerate() {
                if i > 0 {
                    out.push(',');
                }
                write_expr(out, program, *arg);
            }
            out.push(']');
        }
        ExprKind::Group(inner) => {
            out.push('[');
            write_expr(out, program, inner);
            out.push(']');
        }
    }
}
