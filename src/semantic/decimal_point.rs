//! Where a decimal point changes what a word says: the words a control counts in least
//! increments, and the missing point.
//!
//! - A cycle word that counts least increments of a length (`integer` in `grammar/`: the
//!   `P`/`Q` of `G74`–`G76`, `G76`'s `Q` minimum depth) written with a decimal point is refused
//!   by the control: an error at the word, with the value meant at the block's units
//!   (`G76 P0.92` is `P920` at 0.001 mm, `dialect::roles::meant`), and the cycle does not run.
//!   The parse reports the words whose value meant needs no units (milliseconds, sequence
//!   numbers, counts); these need the frame, which only this pass knows.
//! - A word that counts least increments but that a control may take with a point too
//!   (`point_unverified`: the peck `Q` of Fanuc's `G83`/`G87`) is read as a length with one,
//!   and warned of with both readings.
//! - **The missing point.** On a control set for least-increment input (`decimal_input =
//!   "increment"`, Fanuc parameter DPI = 0) a length or a feed per revolution written
//!   without a decimal point counts least increments: `X32` is 0.032 mm, `X32.` 32 mm, and
//!   a program written wholly in increments says `X32000`. Such a word is warned of where
//!   its reading is implausible in its place, by the physics of turning, not by the style
//!   of the program:
//!   - an **X or Z position** (a move's or a cycle's end point, absolute) or a **feed per
//!     revolution** whose reading lies further below the program's scale than its reading
//!     with a point lies from it, by more than half the gap between the two readings: at
//!     least `10^(3g/4)` below the program's scale of that quantity, where `10^g` is the gap
//!     (1000 for 0.001 mm, 10 000 for 0.0001 in), so 178 times below in mm and 1000 times
//!     in inch. The scale is the upper quartile of the words of that quantity written with
//!     a point, which say unambiguously what size the part is (its size rather than its
//!     clearances and chamfers, which are more numerous). A program written wholly in
//!     increments has no such word: nothing in it says its words mean other than they read,
//!     and only the next rule applies to it;
//!   - a **distance, radius or cut parameter** (`U`/`W` moves, `I`/`K`, an arc's `R`, a
//!     corner `,C`/`,R`, depths of cut, allowances, retracts) whose reading is under
//!     [`CUTTING_EDGE_MM`] (radially), or a **feed per revolution** under that much per
//!     revolution: less than a cutting edge's radius, no cut, step or chip the tool can make.
//!
//!   Each such word is one warning, at the word, with both readings and the fix. The words
//!   are judged when the run is over, against the scale of the whole program; an error of a
//!   profile or a corner that one of them causes is moved onto it (`slip_scope`).
//!   Where the settings do not give `decimal_input` (calculator input, the default, is in
//!   force), the words that would be warned of under increment input are counted and said
//!   once, with both readings of the first.

use std::collections::HashSet;

use crate::diagnostic::{CountedWord, Diagnostic, DiagnosticKind, Severity};
use crate::dialect::{Address, AddressKind, DecimalInput, Dialect, IntegerUnit, Role, roles};
use crate::source::Span;
use crate::syntax::{Command, Number, Word, WordKind};

use super::block::word_address;
use super::interpreter::Interpreter;

/// A cutting edge's radius, mm: the hone of a turning insert is 0.01 to 0.05 mm. A cut,
/// allowance, step or corner smaller than it is nothing the tool can make, and a feed per
/// revolution smaller than it leaves a chip thinner than the edge is round: the edge
/// ploughs and rubs instead of cutting.
pub const CUTTING_EDGE_MM: f64 = 0.01;

/// What a word without a decimal point is judged as.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Quantity {
    /// An absolute X position (as programmed: a diameter on a diameter machine).
    X,
    /// An absolute Z position.
    Z,
    FeedPerRev,
    /// A distance, radius or cut parameter, radial mm.
    Small,
}

/// Magnitudes of one quantity, as a histogram of four bins an octave (0.075 of a decade),
/// read from the bits of the value rather than a logarithm (a long program has millions of
/// such words): its upper quartile is the program's scale of that quantity, in fixed memory
/// whatever its size.
#[derive(Debug, Clone)]
struct Scale {
    bins: Vec<u64>,
}

/// Bins an octave, and the octaves kept: 2⁻³⁰ to 2³⁴ mm (10⁻⁹ to 10¹⁰), the rest clamped.
const BINS_PER_OCTAVE: i64 = 4;
const LOWEST_OCTAVE: i64 = -30;
const OCTAVES: i64 = 64;

impl Default for Scale {
    fn default() -> Scale {
        Scale { bins: vec![0; (OCTAVES * BINS_PER_OCTAVE) as usize] }
    }
}

impl Scale {
    fn add(&mut self, mm: f64) {
        if !(mm.is_finite() && mm > 0.0) {
            return;
        }
        // The exponent, and the top two bits of the mantissa: a quarter of an octave.
        let bits = mm.to_bits();
        let exponent = ((bits >> 52) & 0x7ff) as i64 - 1023;
        let quarter = ((bits >> 50) & 0b11) as i64;
        let bin = ((exponent - LOWEST_OCTAVE) * BINS_PER_OCTAVE + quarter).clamp(0, OCTAVES * BINS_PER_OCTAVE - 1);
        self.bins[bin as usize] += 1;
    }

    /// The magnitude a quarter of those added reach or exceed (the middle of its bin), if any
    /// was added: the size of the part rather than of its clearances and chamfers, which
    /// are more numerous.
    fn upper_quartile(&self) -> Option<f64> {
        let total: u64 = self.bins.iter().sum();
        if total == 0 {
            return None;
        }
        let mut seen = 0;
        for (i, count) in self.bins.iter().enumerate() {
            seen += count;
            if 4 * seen >= 3 * total {
                let (octave, quarter) = (i as i64 / BINS_PER_OCTAVE + LOWEST_OCTAVE, i as i64 % BINS_PER_OCTAVE);
                return Some(2f64.powi(octave as i32) * (1.0 + (quarter as f64 + 0.5) / BINS_PER_OCTAVE as f64));
            }
        }
        None
    }
}

/// A word written without a decimal point whose reading as increments is judged at the end.
#[derive(Debug, Clone, Copy)]
struct Candidate {
    span: Span,
    address: Address,
    number: Number,
    quantity: Quantity,
    /// The least increment, program units, and whether they are inches.
    increment: f64,
    inch: bool,
    /// The value is a diameter (its radial share is half of it).
    diameter: bool,
}

impl Candidate {
    /// Its reading in least increments, and as written, program units (`0.032`, `32`).
    fn counted(&self) -> f64 {
        self.number.mantissa as f64 * self.increment
    }

    fn counted_mm(&self) -> f64 {
        self.counted().abs() * if self.inch { super::frame::MM_PER_INCH } else { 1.0 }
    }

    /// `10^g`: how many increments make a program unit.
    fn gap(&self) -> f64 {
        1.0 / self.increment
    }

    /// The word as written (`X32`).
    fn written(&self) -> String {
        format!("{}{}", self.address.name(), crate::syntax::spelling::plain(self.number))
    }

    /// Its reading in least increments and with a point, with their unit (`0.032 mm`,
    /// `32 mm`).
    fn readings(&self) -> (String, String) {
        let unit = match (self.inch, self.quantity == Quantity::FeedPerRev) {
            (false, false) => "mm",
            (true, false) => "in",
            (false, true) => "mm/rev",
            (true, true) => "in/rev",
        };
        (format!("{} {unit}", roles::short(self.counted())), format!("{} {unit}", roles::short(self.number.to_f64())))
    }
}

/// Words seen, one bit a byte of the source where a word starts: a word read again (a loop,
/// a profile read by two cycles) is judged once, in memory that follows the program.
#[derive(Debug, Default)]
struct Seen {
    bits: Vec<u64>,
}

impl Seen {
    /// Mark the word at `offset`; whether it was not marked before.
    fn insert(&mut self, offset: u32) -> bool {
        let (word, bit) = (offset as usize / 64, offset % 64);
        if word >= self.bits.len() {
            self.bits.resize(word + 1, 0);
        }
        let fresh = self.bits[word] & (1 << bit) == 0;
        self.bits[word] |= 1 << bit;
        fresh
    }
}

/// What this module has said and seen: words said once (a loop, a profile read by two
/// cycles), the program's scales, the words to judge, and the errors a word may have caused.
#[derive(Debug, Default)]
pub struct Said {
    words: HashSet<u32>,
    /// The check of missing points runs (a Fanuc program, increment input or none given).
    active: Option<bool>,
    scales: [Scale; 3],
    candidates: Vec<Candidate>,
    judged: Seen,
    /// Errors of a profile or a corner (their span) and the source range whose words decide
    /// them: a word there that reads implausibly is the likelier cause.
    scopes: Vec<(Span, u32, u32)>,
}

impl Interpreter<'_, '_> {
    /// Check the decimal points of a cycle block's words: `false` when the control refuses
    /// the block (a point in a word it counts in least increments), which then does not run.
    pub(super) fn cycle_points_taken(&mut self, command: &Command) -> bool {
        let Some(form) = self.tables.schema(command.schema).forms.get(command.form as usize) else { return true };
        let frame = self.modal.frame;
        let mut taken = true;
        for param in &command.params {
            let word = *self.program.word(param.word);
            let WordKind::Number { address, number } = word.kind else { continue };
            if !number.has_point() || !form.counts_without_point(address) {
                continue;
            }
            let unit = IntegerUnit::of(param.role);
            if !unit.needs_frame() {
                continue;
            }
            let written = format!("{}{}", address.name(), crate::syntax::spelling::plain(number));
            let meant = |value: f64| {
                roles::meant(unit, value, Some((frame.increment, frame.scale())))
                    .map(|(count, reading)| (format!("{}{count}", address.name()), reading))
            };
            let counted = CountedWord {
                command: self.command_text(command),
                address: address.name(),
                written,
                unit,
                meant: meant(number.to_f64()),
                control: self.tables.config.control.name(),
                elsewhere: None,
            };
            if form.takes_integer(address) {
                self.diagnostics.push(Diagnostic::error(DiagnosticKind::IntegerExpected(Box::new(counted)), word.span));
                taken = false;
            } else if form.point_unverified.contains(&address)
                && counted.meant.is_some()
                && self.decimal_point.words.insert(word.span.start)
            {
                let unit_name = if frame.inch { "in" } else { "mm" };
                let reading = format!("{} {unit_name}", roles::short(number.to_f64()));
                self.warning(DiagnosticKind::DecimalPointUnverified { word: Box::new(counted), reading }, word.span);
            }
        }
        taken
    }

    /// "G76 (multiple threading cycle)", as the parse names a command in its messages.
    fn command_text(&self, command: &Command) -> String {
        match self.program.word(command.code_word).kind {
            WordKind::Code { code, .. } => match self.tables.g(code) {
                Some(info) => format!("{} ({})", code.display('G'), info.meaning),
                None => code.display('G'),
            },
            _ => String::new(),
        }
    }
}

impl Interpreter<'_, '_> {
    /// Whether the words without a decimal point are checked: a Fanuc program read with
    /// increment input, or with no `decimal_input` in the settings.
    fn checks_missing_points(&mut self) -> bool {
        if let Some(active) = self.decimal_point.active {
            return active;
        }
        let active = self.dialect == Dialect::Fanuc
            && (self.machine.decimal_input == DecimalInput::Increment || !self.machine.decimal_input_given);
        self.decimal_point.active = Some(active);
        active
    }

    /// Note the length and feed words of a motion block (a thread move's `F` is a lead, no
    /// feed).
    pub(super) fn observe_move_words(&mut self, words: &[Word], thread: bool) {
        if !self.checks_missing_points() {
            return;
        }
        for word in words {
            let Some(address) = word_address(word) else { continue };
            let quantity = match address {
                Address::X | Address::Z if !self.modal.absolute => Quantity::Small,
                Address::X => Quantity::X,
                Address::Z => Quantity::Z,
                Address::U | Address::W | Address::I | Address::K | Address::R => Quantity::Small,
                a if a == Address::comma(b'C') || a == Address::comma(b'R') => Quantity::Small,
                Address::F if !thread => {
                    self.observe_feed(word);
                    continue;
                }
                _ => continue,
            };
            let diameter = matches!(address, Address::X | Address::U);
            self.observe(word, quantity, diameter);
        }
    }

    /// Note a cycle block's lengths (end points, distances, depths, allowances) and feed.
    pub(super) fn observe_cycle_words(&mut self, command: &Command) {
        if !self.checks_missing_points() {
            return;
        }
        let Some(form) = self.tables.schema(command.schema).forms.get(command.form as usize) else { return };
        for param in &command.params {
            let word = *self.program.word(param.word);
            let Some(address) = word_address(&word) else { continue };
            if form.counts_without_point(address) {
                continue;
            }
            let (_, unit) = roles::describe(param.role);
            let quantity = match (param.role, unit) {
                (Role::EndX, _) if self.modal.absolute => Quantity::X,
                (Role::EndZ, _) if self.modal.absolute => Quantity::Z,
                (Role::Feed, _) => {
                    self.observe_feed(&word);
                    continue;
                }
                (_, roles::Unit::Length | roles::Unit::XLength) => Quantity::Small,
                _ => continue,
            };
            let diameter = unit == roles::Unit::XLength || form.is_diameter(address);
            self.observe(&word, quantity, diameter);
        }
    }

    /// Note an `F` word: a feed per revolution is judged.
    pub(super) fn observe_feed(&mut self, word: &Word) {
        if !self.checks_missing_points()
            || !self.modal.feed_per_rev
            || !self.tables.increment_input.feed_per_revolution_counts
        {
            return;
        }
        self.observe(word, Quantity::FeedPerRev, false);
    }

    fn observe(&mut self, word: &Word, quantity: Quantity, diameter: bool) {
        let WordKind::Number { address, number } = word.kind else { return };
        if self.tables.address(address).is_none_or(|spec| !matches!(spec.kind, AddressKind::Length | AddressKind::Feed))
        {
            return;
        }
        let frame = self.modal.frame;
        let mm_per_unit = frame.scale();
        if number.has_point() {
            // The words written with a point say what size the part is.
            if let Some(scale) = match quantity {
                Quantity::X => Some(0),
                Quantity::Z => Some(1),
                Quantity::FeedPerRev => Some(2),
                Quantity::Small => None,
            } {
                self.decimal_point.scales[scale].add(number.to_f64().abs() * mm_per_unit);
            }
            return;
        }
        if number.mantissa == 0 || !self.decimal_point.judged.insert(word.span.start) {
            return;
        }
        self.decimal_point.candidates.push(Candidate {
            span: word.span,
            address,
            number,
            quantity,
            increment: frame.increment,
            inch: frame.inch,
            diameter: diameter && frame.diameter,
        });
    }

    /// The source range whose words decide the error just pushed with `span` (a profile's
    /// blocks, a corner and the line after it): a word there that reads implausibly is
    /// named as its cause.
    pub(super) fn slip_scope(&mut self, span: Span, from: u32, to: u32) {
        if self.decimal_point.active == Some(true) {
            self.decimal_point.scopes.push((span, from, to));
        }
    }

    /// Judge the words seen, against the scales of the whole program (the end of the run).
    pub(super) fn judge_missing_points(&mut self) {
        if self.decimal_point.active != Some(true) || self.decimal_point.candidates.is_empty() {
            return;
        }
        let said = &self.decimal_point;
        let scales =
            [said.scales[0].upper_quartile(), said.scales[1].upper_quartile(), said.scales[2].upper_quartile()];
        let implausible: Vec<Candidate> = said
            .candidates
            .iter()
            .filter(|c| {
                let counted = c.counted_mm();
                let below_scale =
                    |scale: Option<f64>| scale.is_some_and(|scale| counted <= scale * c.gap().powf(-0.75));
                match c.quantity {
                    Quantity::X => below_scale(scales[0]),
                    Quantity::Z => below_scale(scales[1]),
                    Quantity::FeedPerRev => counted < CUTTING_EDGE_MM || below_scale(scales[2]),
                    Quantity::Small => counted * if c.diameter { 0.5 } else { 1.0 } < CUTTING_EDGE_MM,
                }
            })
            .copied()
            .collect();
        if implausible.is_empty() {
            return;
        }
        let reading = Candidate::readings;
        if self.machine.decimal_input_given {
            // An error of a profile or a corner that a word in its scope explains points at
            // the word; the word's own warning is then said by the error.
            let mut explained = HashSet::new();
            let scopes = std::mem::take(&mut self.decimal_point.scopes);
            // Each error found by its span, and the nearest implausible word by a binary
            // search: a program may hold thousands of both.
            let mut errors = std::collections::HashMap::new();
            for (index, d) in self.diagnostics.iter().enumerate() {
                if d.severity == Severity::Error {
                    errors.entry(d.span).or_insert(index);
                }
            }
            let mut implausible = implausible;
            implausible.sort_by_key(|c| c.span.start);
            for (span, from, to) in scopes {
                let Some(&index) = errors.get(&span) else { continue };
                if matches!(self.diagnostics[index].kind, DiagnosticKind::MissingPointCauses { .. }) {
                    continue;
                }
                let inside = |c: &&Candidate| c.span.start >= from && c.span.end <= to;
                let k = implausible.partition_point(|c| c.span.start < span.start);
                let before = k.checked_sub(1).and_then(|i| implausible.get(i)).filter(inside);
                let after = implausible.get(k).filter(inside);
                let distance = |c: &Candidate| c.span.start.abs_diff(span.start).min(c.span.end.abs_diff(span.end));
                let nearest = before.into_iter().chain(after).min_by_key(|c| distance(c));
                let Some(cause) = nearest else { continue };
                let error = &self.diagnostics[index];
                let mut related = vec![(error.span, error.label())];
                related.extend(error.related.iter().cloned());
                let kind = DiagnosticKind::MissingPointCauses {
                    cause: Box::new(error.kind.clone()),
                    word: cause.written(),
                    readings: Box::new(reading(cause)),
                };
                self.diagnostics[index] =
                    Diagnostic { severity: Severity::Error, kind, span: cause.span, related, repeats: error.repeats };
                explained.insert(cause.span.start);
            }
            for c in implausible.iter().filter(|c| !explained.contains(&c.span.start)) {
                let kind = DiagnosticKind::MissingDecimalPoint { word: c.written(), readings: Box::new(reading(c)) };
                self.warning(kind, c.span);
            }
        } else if let Some(first) = implausible.iter().min_by_key(|c| c.span.start) {
            let (as_increments, as_written) = reading(first);
            let kind = DiagnosticKind::DecimalInputUnset {
                count: implausible.len(),
                word: first.written(),
                readings: Box::new((as_written, as_increments)),
            };
            self.diagnostics.push(Diagnostic::note(kind, first.span));
        }
    }
}
