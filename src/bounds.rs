//! The range a number read from a model file or a command-line flag must lie in.
//!
//! Every number a user gives is checked when it is read: a NaN, an infinity or a value no
//! machine has (a least increment of 0, a warm-up of 10³⁰⁰ mm) would otherwise flow into
//! the compensation, which then does nothing or writes a damaged program and reports
//! success. Each quantity keeps its range beside its definition (an effect's in its own
//! file, the machine settings' in `machine.rs`, the flags' in the CLI); this module only
//! says what a range is and how a value fails it.

use std::fmt;

/// A range of plausible values: `min ≤ value ≤ max`, or `min < value ≤ max` when the lower
/// end is open (a length that must be more than zero).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    pub min: f64,
    pub max: f64,
    /// Whether `min` itself is excluded.
    pub open_min: bool,
    /// The unit the values are in, for messages ("mm", "min", "" for none).
    pub unit: &'static str,
}

impl Range {
    /// `min ≤ value ≤ max`.
    pub const fn closed(min: f64, max: f64, unit: &'static str) -> Range {
        Range { min, max, open_min: false, unit }
    }

    /// `0 < value ≤ max`: a size that must be more than nothing.
    pub const fn positive(max: f64, unit: &'static str) -> Range {
        Range { min: 0.0, max, open_min: true, unit }
    }

    /// `−limit ≤ value ≤ limit`: an error of either sign.
    pub const fn magnitude(limit: f64, unit: &'static str) -> Range {
        Range { min: -limit, max: limit, open_min: false, unit }
    }

    /// `value` if it lies in the range.
    pub fn check(&self, value: f64) -> Result<f64, OutOfRange> {
        let below = if self.open_min { value <= self.min } else { value < self.min };
        if !value.is_finite() || below || value > self.max {
            return Err(OutOfRange { value, range: *self });
        }
        Ok(value)
    }

    /// Read `text` as a number in the range (a command-line value).
    pub fn parse(&self, text: &str) -> Result<f64, String> {
        let value = text.trim().parse::<f64>().map_err(|_| format!("`{text}` is not a number"))?;
        self.check(value).map_err(|e| e.to_string())
    }
}

/// A value as a message shows it: in full, or with an exponent when it is very large or
/// very small (`1e300` rather than three hundred digits).
pub fn show(value: f64) -> String {
    if value != 0.0 && value.is_finite() && !(1e-6..1e7).contains(&value.abs()) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}

impl fmt::Display for Range {
    /// "more than 0 and at most 1 mm", "from -1 to 1 mm".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let unit = if self.unit.is_empty() { String::new() } else { format!(" {}", self.unit) };
        let (min, max) = (show(self.min), show(self.max));
        if self.open_min {
            write!(f, "more than {min} and at most {max}{unit}")
        } else {
            write!(f, "from {min} to {max}{unit}")
        }
    }
}

/// A value outside its range, or not a finite number at all.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutOfRange {
    pub value: f64,
    pub range: Range,
}

impl fmt::Display for OutOfRange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let value = show(self.value);
        if self.value.is_finite() {
            write!(f, "{value} is out of range: a value must be {}", self.range)
        } else {
            write!(f, "{value} is not a finite number: a value must be {}", self.range)
        }
    }
}

/// One step of the path to a value in a model file: a key of a table, or an element of an
/// array (0-based).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Key {
    Name(&'static str),
    Index(usize),
}

/// Why a value of a model file is refused.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reason {
    OutOfRange(OutOfRange),
    /// A rule between values, or on a value's form (`x_min` below `x_max`; a least
    /// increment that is a power of ten): what the rule asks for.
    Rule(&'static str),
}

/// A value of a model file that is refused, and where it is: the path from the table that
/// checked it (an effect's parameters, `[machine]`) to the value.
#[derive(Debug, Clone, PartialEq)]
pub struct Invalid {
    pub path: Vec<Key>,
    pub reason: Reason,
}

impl Invalid {
    /// `self` with `outer` in front of its path (the table that holds the checked one).
    pub fn within(mut self, outer: &[Key]) -> Invalid {
        self.path.splice(0..0, outer.iter().copied());
        self
    }
}

impl Range {
    /// Check `value`, the value of `key`.
    pub fn check_key(&self, key: &'static str, value: f64) -> Result<(), Invalid> {
        self.check(value).map(|_| ()).map_err(|e| Invalid { path: vec![Key::Name(key)], reason: Reason::OutOfRange(e) })
    }

    /// Check an optional `value` of `key`.
    pub fn check_option(&self, key: &'static str, value: Option<f64>) -> Result<(), Invalid> {
        value.map_or(Ok(()), |v| self.check_key(key, v))
    }

    /// Check every element of the array `key`.
    pub fn check_each(&self, key: &'static str, values: &[f64]) -> Result<(), Invalid> {
        for (index, &value) in values.iter().enumerate() {
            self.check(value).map_err(|e| Invalid {
                path: vec![Key::Name(key), Key::Index(index)],
                reason: Reason::OutOfRange(e),
            })?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_refuse_non_finite_values_and_honour_their_open_end() {
        let size = Range::positive(1.0, "mm");
        assert_eq!(size.check(0.5), Ok(0.5));
        assert_eq!(size.check(1.0), Ok(1.0));
        for bad in [0.0, -0.1, 1.01, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(size.check(bad).is_err(), "{bad}");
        }
        let error = Range::magnitude(1.0, "mm");
        assert_eq!(error.check(-1.0), Ok(-1.0));
        assert_eq!(error.check(0.0), Ok(0.0));
        assert!(error.check(1e300).is_err());
        assert_eq!(
            error.check(1e300).unwrap_err().to_string(),
            "1e300 is out of range: a value must be from -1 to 1 mm"
        );
        assert_eq!(size.parse(" 0.25"), Ok(0.25));
        assert_eq!(
            size.parse("nan").unwrap_err(),
            "NaN is not a finite number: a value must be more than 0 and at most 1 mm"
        );
        assert_eq!(size.parse("x").unwrap_err(), "`x` is not a number");
        assert_eq!(error.check(2.0).unwrap_err().to_string(), "2 is out of range: a value must be from -1 to 1 mm");
    }
}
