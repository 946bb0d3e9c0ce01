//! A header cell read as words and a unit: `Target (mm)`, `Run 1 Fwd [µm]`, `linear_mm`,
//! `X diameter (in)`. The unit is the one in brackets, else the last word after an
//! underscore or a blank when it is a unit (`deviation_mm`, `Error um`); the words are the
//! rest, in lower case (`run1` is `run 1`; `m1` and `m2` stay whole, they name the two runs
//! of the reversal technique). The readers decide what the words mean.

/// A unit a measurement file may give its values in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    Mm,
    Um,
    Nm,
    Inch,
    /// Parts per million of the position: an error relative to the target (`µm/m`).
    Ppm,
    Deg,
    Rad,
    Mrad,
    Urad,
    Arcsec,
    /// Minutes of time.
    Min,
}

impl Unit {
    /// The unit a name writes (`mm`, `um`, `µm`, `micron`, `in`, `inch`, `ppm`, `um/m`, `deg`,
    /// `°`, `rad`, `mrad`, `urad`, `arcsec`, `"`, `min`), in any case.
    pub fn parse(text: &str) -> Option<Unit> {
        let text = text.trim().to_lowercase().replace(['µ', 'μ'], "u");
        Some(match text.as_str() {
            "mm" | "millimetre" | "millimetres" | "millimeter" | "millimeters" => Unit::Mm,
            "um" | "micron" | "microns" | "micrometre" | "micrometres" | "micrometer" | "micrometers" => Unit::Um,
            "nm" => Unit::Nm,
            "in" | "inch" | "inches" | "\"in\"" => Unit::Inch,
            "ppm" | "um/m" | "mm/km" => Unit::Ppm,
            "deg" | "degree" | "degrees" | "°" => Unit::Deg,
            "rad" | "radian" | "radians" => Unit::Rad,
            "mrad" => Unit::Mrad,
            "urad" => Unit::Urad,
            "arcsec" | "arc sec" | "arc-sec" | "sec" | "\"" | "″" => Unit::Arcsec,
            "min" | "minute" | "minutes" => Unit::Min,
            _ => return None,
        })
    }

    /// How the documentation writes it.
    pub fn name(self) -> &'static str {
        match self {
            Unit::Mm => "mm",
            Unit::Um => "µm",
            Unit::Nm => "nm",
            Unit::Inch => "in",
            Unit::Ppm => "ppm",
            Unit::Deg => "deg",
            Unit::Rad => "rad",
            Unit::Mrad => "mrad",
            Unit::Urad => "µrad",
            Unit::Arcsec => "arcsec",
            Unit::Min => "min",
        }
    }

    /// Millimetres per unit, for a length.
    pub fn mm(self) -> Option<f64> {
        Some(match self {
            Unit::Mm => 1.0,
            Unit::Um => 1e-3,
            Unit::Nm => 1e-6,
            Unit::Inch => 25.4,
            _ => return None,
        })
    }

    /// Radians per unit, for an angle.
    pub fn radians(self) -> Option<f64> {
        Some(match self {
            Unit::Deg => std::f64::consts::PI / 180.0,
            Unit::Rad => 1.0,
            Unit::Mrad => 1e-3,
            Unit::Urad => 1e-6,
            Unit::Arcsec => std::f64::consts::PI / 180.0 / 3600.0,
            _ => return None,
        })
    }
}

/// A header cell read as words and a unit.
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnName {
    /// The words, lower case, `µ` as `u`, numbers as words of their own.
    pub words: Vec<String>,
    pub unit: Option<Unit>,
    /// The unit's text as the cell writes it, for messages.
    pub unit_text: Option<String>,
}

impl ColumnName {
    pub fn has(&self, word: &str) -> bool {
        self.words.iter().any(|w| w == word)
    }

    pub fn has_any(&self, words: &[&str]) -> bool {
        self.words.iter().any(|w| words.contains(&w.as_str()))
    }

    /// The words that are numbers.
    pub fn numbers(&self) -> Vec<u32> {
        self.words.iter().filter_map(|w| w.parse().ok()).collect()
    }

    /// Whether the words are exactly `words`, in any order.
    pub fn is(&self, words: &[&str]) -> bool {
        self.words.len() == words.len() && words.iter().all(|w| self.has(w))
    }
}

/// The words and unit of a header cell.
pub fn column_name(text: &str) -> ColumnName {
    let lower = text.trim().to_lowercase().replace(['µ', 'μ'], "u");
    let mut unit = None;
    let mut unit_text = None;
    let mut rest = String::new();
    // Brackets: a unit, or more words (`Run 1 (fwd)`).
    let mut chars = lower.char_indices().peekable();
    let mut plain_start = 0;
    while let Some((i, c)) = chars.next() {
        let close = match c {
            '(' => ')',
            '[' => ']',
            _ => continue,
        };
        let Some(end) = lower[i + 1..].find(close).map(|e| i + 1 + e) else { continue };
        rest.push_str(&lower[plain_start..i]);
        rest.push(' ');
        let inside = &lower[i + 1..end];
        match Unit::parse(inside) {
            Some(u) if unit.is_none() => {
                unit = Some(u);
                unit_text = Some(inside.trim().to_string());
            }
            _ => {
                rest.push_str(inside);
                rest.push(' ');
            }
        }
        plain_start = end + 1;
        while chars.peek().is_some_and(|(j, _)| *j <= end) {
            chars.next();
        }
    }
    rest.push_str(&lower[plain_start.min(lower.len())..]);
    let mut words: Vec<String> = Vec::new();
    for piece in rest.split(|c: char| !(c.is_alphanumeric() || matches!(c, '+' | '-' | '↑' | '↓' | '/' | '°'))) {
        if piece.is_empty() {
            continue;
        }
        // A piece of signs alone is a direction (`+`, `-`, `↑`); in words a sign joins them
        // (`counter-clockwise`, `run-1-fwd`).
        if piece.chars().all(|c| matches!(c, '+' | '-' | '↑' | '↓')) {
            words.push(piece.to_string());
            continue;
        }
        for part in piece.split(['-', '+']).filter(|p| !p.is_empty()) {
            // Arrows written against a word (`run 1↑`) are words of their own.
            let mut word = String::new();
            for c in part.chars() {
                if matches!(c, '↑' | '↓') {
                    words.extend(split_word(&std::mem::take(&mut word)));
                    words.push(c.to_string());
                } else {
                    word.push(c);
                }
            }
            words.extend(split_word(&word));
        }
    }
    // A unit as the last word (`target_mm`, `linear um`), when there was none in brackets and
    // other words remain.
    if unit.is_none()
        && words.len() >= 2
        && let Some(u) = words.last().and_then(|w| Unit::parse(w))
    {
        unit = Some(u);
        unit_text = words.pop();
    }
    ColumnName { words, unit, unit_text }
}

/// A word split where letters meet digits (`run1` is `run 1`, `r2` is `r 2`), but for the
/// reversal runs `m1` and `m2`, which stay whole; a word of signs or arrows stays whole.
fn split_word(word: &str) -> Vec<String> {
    if word.is_empty() {
        return Vec::new();
    }
    if word == "m1" || word == "m2" || !word.chars().any(|c| c.is_ascii_digit()) || word.parse::<f64>().is_ok() {
        return vec![word.to_string()];
    }
    let mut out = Vec::new();
    let mut current = String::new();
    let mut digits = false;
    for c in word.chars() {
        let is_digit = c.is_ascii_digit();
        if !current.is_empty() && is_digit != digits {
            out.push(std::mem::take(&mut current));
        }
        digits = is_digit;
        current.push(c);
    }
    if !current.is_empty() {
        out.push(current);
    }
    out
}
