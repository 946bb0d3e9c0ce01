//! Variables and expression evaluation: OSP common (`V1`), local (`FLAN`) and system
//! (`VTOFX[16]`) variables, Fanuc `#` variables, arithmetic, comparisons and functions.
//!
//! Values are `f64`. Trigonometric functions take and give degrees, as both controls do.
//! A user variable read before it is set, and a division by zero, are errors; a system
//! variable (`#5001`, `VTOFX[6]`) holds machine state the simulation does not have, so it
//! reads as 0 with a warning.

use std::collections::HashMap;

use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::dialect::Dialect;
use crate::source::Span;
use crate::syntax::{BinaryOp, ExprId, ExprKind, Program, UnaryOp, Variable};

/// Which variable: a number (`V12`, `#501`) or a name, with an index for OSP arrays.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum VarKey {
    Number(u32),
    Name(String),
    Indexed(String, i64),
}

impl VarKey {
    pub fn display(&self, dialect: Dialect) -> String {
        match (self, dialect) {
            (VarKey::Number(n), Dialect::Fanuc) => format!("#{n}"),
            (VarKey::Number(n), Dialect::Osp) => format!("V{n}"),
            (VarKey::Name(name), _) => name.clone(),
            (VarKey::Indexed(name, i), _) => format!("{name}[{i}]"),
        }
    }

    /// System variables hold machine state: Fanuc `#1000` and up, OSP `V` + letters.
    fn is_system(&self) -> bool {
        match self {
            VarKey::Number(n) => *n >= 1000,
            VarKey::Name(name) | VarKey::Indexed(name, _) => {
                let bytes = name.as_bytes();
                bytes.len() >= 3
                    && bytes[0] == b'V'
                    && bytes[1..].iter().all(u8::is_ascii_uppercase)
                    && !name.starts_with("VC")
            }
        }
    }
}

/// The variable store: globals plus one frame of locals per subprogram call.
#[derive(Debug, Default)]
pub struct Variables {
    globals: HashMap<VarKey, f64>,
    frames: Vec<HashMap<VarKey, f64>>,
}

impl Variables {
    /// OSP locals and Fanuc `#1`-`#33` belong to the current call level.
    fn is_local(key: &VarKey, dialect: Dialect) -> bool {
        match (key, dialect) {
            (VarKey::Number(n), Dialect::Fanuc) => (1..=33).contains(n),
            (VarKey::Name(name), Dialect::Osp) => !name.starts_with('V'),
            _ => false,
        }
    }

    pub fn get(&self, key: &VarKey, dialect: Dialect) -> Option<f64> {
        if Self::is_local(key, dialect)
            && let Some(frame) = self.frames.last()
        {
            return frame.get(key).copied();
        }
        self.globals.get(key).copied()
    }

    pub fn set(&mut self, key: VarKey, value: f64, dialect: Dialect) {
        if Self::is_local(&key, dialect)
            && let Some(frame) = self.frames.last_mut()
        {
            frame.insert(key, value);
            return;
        }
        self.globals.insert(key, value);
    }

    /// The store with the values the machine settings give its common variables
    /// (`[machine] variables`, `--var`): `#501` on Fanuc, `V12` or a name on OSP. A name that
    /// is no variable of the dialect is left out.
    pub fn from_machine(values: &[(String, f64)], dialect: Dialect) -> Variables {
        let mut variables = Variables::default();
        for (name, value) in values {
            let number = match dialect {
                Dialect::Fanuc => name.strip_prefix('#'),
                Dialect::Osp => name.strip_prefix('V'),
            }
            .and_then(|digits| digits.parse::<u32>().ok());
            let key = match (number, dialect) {
                (Some(n), _) => VarKey::Number(n),
                (None, Dialect::Osp) if name.bytes().all(|b| b.is_ascii_uppercase() || b.is_ascii_digit()) => {
                    VarKey::Name(name.clone())
                }
                _ => continue,
            };
            variables.set(key, *value, dialect);
        }
        variables
    }

    pub fn push_frame(&mut self) {
        self.frames.push(HashMap::new());
    }

    pub fn pop_frame(&mut self) {
        self.frames.pop();
    }
}

/// Evaluates expressions of one program against a variable store.
pub struct Evaluator<'p, 'src> {
    pub program: &'p Program<'src>,
    pub dialect: Dialect,
}

/// Why an evaluation failed; the caller turns it into a diagnostic on the expression.
pub type EvalResult<T> = Result<T, Diagnostic>;

impl Evaluator<'_, '_> {
    /// A common variable the control keeps in memory (`grammar/` `[machine_variables]`).
    fn machine_keeps(&self, key: &VarKey) -> bool {
        matches!(key, VarKey::Number(n) if self.program.config().tables().machine_variables.holds(*n))
    }

    fn name_of(&self, span: Span) -> String {
        String::from_utf8_lossy(self.program.text(span)).into_owned()
    }

    /// The variable an expression names (an assignment target).
    pub fn key(&self, id: ExprId, variables: &mut Variables, warnings: &mut Vec<Diagnostic>) -> EvalResult<VarKey> {
        let expr = self.program.expr(id);
        match expr.kind {
            ExprKind::Variable(Variable::Common(n)) => Ok(VarKey::Number(n)),
            ExprKind::Variable(Variable::Named) => Ok(VarKey::Name(self.name_of(expr.span))),
            ExprKind::Variable(Variable::Indexed { name, index }) => {
                let i = self.value(index, variables, warnings)?;
                Ok(VarKey::Indexed(self.name_of(name), i.round() as i64))
            }
            ExprKind::Variable(Variable::Hash { index }) => {
                let i = self.value(index, variables, warnings)?;
                if i < 0.0 || i.fract().abs() > 1e-9 || i > u32::MAX as f64 {
                    return Err(Diagnostic::error(DiagnosticKind::BadVariableNumber { value: i }, expr.span));
                }
                Ok(VarKey::Number(i as u32))
            }
            _ => Err(Diagnostic::error(DiagnosticKind::NotAVariable, expr.span)),
        }
    }

    /// The value of an expression.
    pub fn value(&self, id: ExprId, variables: &mut Variables, warnings: &mut Vec<Diagnostic>) -> EvalResult<f64> {
        let expr = self.program.expr(id);
        let span = expr.span;
        Ok(match expr.kind {
            ExprKind::Number(number) => number.to_f64(),
            ExprKind::Group(inner) => self.value(inner, variables, warnings)?,
            // `#0` is the Fanuc null variable: always vacant, read as 0.
            ExprKind::Variable(Variable::Hash { index }) if matches!(self.program.expr(index).kind, ExprKind::Number(n) if n.mantissa == 0) => {
                0.0
            }
            ExprKind::Variable(_) => {
                let key = self.key(id, variables, warnings)?;
                match variables.get(&key, self.dialect) {
                    Some(value) => value,
                    None if self.machine_keeps(&key) => {
                        // Fanuc reads a vacant variable as 0 in arithmetic.
                        warnings.push(Diagnostic::warning(
                            DiagnosticKind::MachineVariableUnknown { name: key.display(self.dialect) },
                            span,
                        ));
                        0.0
                    }
                    None if key.is_system() => {
                        warnings.push(Diagnostic::warning(
                            DiagnosticKind::SystemVariableUnknown { name: key.display(self.dialect) },
                            span,
                        ));
                        0.0
                    }
                    None => {
                        return Err(Diagnostic::error(
                            DiagnosticKind::UndefinedVariable { name: key.display(self.dialect) },
                            span,
                        ));
                    }
                }
            }
            ExprKind::Unary { op, operand } => {
                let v = self.value(operand, variables, warnings)?;
                match op {
                    UnaryOp::Minus => -v,
                    UnaryOp::Plus => v,
                    UnaryOp::Not => bool_value(v == 0.0),
                }
            }
            ExprKind::Binary { op, lhs, rhs } => {
                // Fanuc writes a two-argument arctangent as `ATAN[y]/[x]`.
                if op == BinaryOp::Div
                    && let ExprKind::Call { function, arg_count: 1, args } = self.program.expr(lhs).kind
                    && self.function_name(function) == "ATAN"
                {
                    let y = self.value(args[0], variables, warnings)?;
                    let x = self.value(rhs, variables, warnings)?;
                    return Ok(normalise_degrees(y.atan2(x).to_degrees()));
                }
                let a = self.value(lhs, variables, warnings)?;
                let b = self.value(rhs, variables, warnings)?;
                binary(op, a, b).ok_or_else(|| Diagnostic::error(DiagnosticKind::DivisionByZero, span))?
            }
            ExprKind::Call { function, args, arg_count } => {
                let name = self.function_name(function);
                let a = if arg_count > 0 { self.value(args[0], variables, warnings)? } else { 0.0 };
                let b = if arg_count > 1 { Some(self.value(args[1], variables, warnings)?) } else { None };
                call(&name, a, b).ok_or_else(|| {
                    Diagnostic::error(DiagnosticKind::FunctionDomain { function: name.clone(), argument: a }, span)
                })?
            }
        })
    }

    fn function_name(&self, index: u8) -> String {
        self.program.config().tables().expression.functions.get(index as usize).cloned().unwrap_or_default()
    }
}

fn bool_value(b: bool) -> f64 {
    if b { 1.0 } else { 0.0 }
}

/// Comparisons are exact to a micro-unit, as a control compares values it has rounded.
fn equal(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9 * (1.0 + a.abs().max(b.abs()))
}

fn binary(op: BinaryOp, a: f64, b: f64) -> Option<f64> {
    Some(match op {
        BinaryOp::Add => a + b,
        BinaryOp::Sub => a - b,
        BinaryOp::Mul => a * b,
        BinaryOp::Div => {
            if b == 0.0 {
                return None;
            }
            a / b
        }
        BinaryOp::Mod => {
            if b == 0.0 {
                return None;
            }
            a % b
        }
        // Logic on truth values; on other integers Fanuc works bit by bit.
        BinaryOp::And => logic(a, b, |x, y| x && y, |x, y| x & y),
        BinaryOp::Or => logic(a, b, |x, y| x || y, |x, y| x | y),
        BinaryOp::Xor => logic(a, b, |x, y| x != y, |x, y| x ^ y),
        BinaryOp::Eq => bool_value(equal(a, b)),
        BinaryOp::Ne => bool_value(!equal(a, b)),
        BinaryOp::Gt => bool_value(a > b && !equal(a, b)),
        BinaryOp::Ge => bool_value(a > b || equal(a, b)),
        BinaryOp::Lt => bool_value(a < b && !equal(a, b)),
        BinaryOp::Le => bool_value(a < b || equal(a, b)),
    })
}

fn logic(a: f64, b: f64, truth: fn(bool, bool) -> bool, bits: fn(i64, i64) -> i64) -> f64 {
    let is_truth = |v: f64| v == 0.0 || v == 1.0;
    if is_truth(a) && is_truth(b) { bool_value(truth(a != 0.0, b != 0.0)) } else { bits(a as i64, b as i64) as f64 }
}

fn normalise_degrees(a: f64) -> f64 {
    if a < 0.0 { a + 360.0 } else { a }
}

/// A function of the dialects' lists; `None` outside its domain.
fn call(name: &str, a: f64, b: Option<f64>) -> Option<f64> {
    Some(match (name, b) {
        ("SIN", _) => a.to_radians().sin(),
        ("COS", _) => a.to_radians().cos(),
        ("TAN", _) => a.to_radians().tan(),
        ("ASIN", _) if a.abs() <= 1.0 => a.asin().to_degrees(),
        ("ACOS", _) if a.abs() <= 1.0 => a.acos().to_degrees(),
        ("ATAN", None) => a.atan().to_degrees(),
        ("ATAN" | "ATAN2", Some(x)) => normalise_degrees(a.atan2(x).to_degrees()),
        ("SQRT" | "SQR", _) if a >= 0.0 => a.sqrt(),
        ("ABS", _) => a.abs(),
        ("ROUND" | "RND" | "DROUND", _) => a.round(),
        ("FIX" | "DFIX", _) => a.floor(),
        ("FUP" | "DFUP", _) => a.ceil(),
        ("LN", _) if a > 0.0 => a.ln(),
        ("EXP", _) => a.exp(),
        ("POW", Some(x)) => a.powf(x),
        ("MOD", Some(x)) if x != 0.0 => a % x,
        ("BIN", _) => bcd_to_binary(a as i64) as f64,
        ("BCD", _) => binary_to_bcd(a as i64) as f64,
        ("ADP", _) => a,
        _ => return None,
    })
}

fn bcd_to_binary(mut v: i64) -> i64 {
    let (mut out, mut scale) = (0, 1);
    while v > 0 {
        out += (v & 0xF) * scale;
        scale *= 10;
        v >>= 4;
    }
    out
}

fn binary_to_bcd(mut v: i64) -> i64 {
    let (mut out, mut shift) = (0i64, 0);
    while v > 0 && shift < 60 {
        out |= (v % 10) << shift;
        shift += 4;
        v /= 10;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operators_and_functions() {
        assert_eq!(binary(BinaryOp::Div, 1.0, 0.0), None);
        assert_eq!(binary(BinaryOp::Eq, 0.1 + 0.2, 0.3), Some(1.0));
        assert_eq!(binary(BinaryOp::And, 1.0, 0.0), Some(0.0));
        assert_eq!(binary(BinaryOp::Or, 12.0, 3.0), Some(15.0));
        assert!((call("SIN", 30.0, None).unwrap() - 0.5).abs() < 1e-12);
        assert_eq!(call("SQRT", -1.0, None), None);
        assert_eq!(call("FIX", 2.7, None), Some(2.0));
        assert_eq!(call("ATAN", 1.0, Some(-1.0)), Some(135.0));
        assert_eq!(bcd_to_binary(0x25), 25);
        assert_eq!(binary_to_bcd(25), 0x25);
    }
}
