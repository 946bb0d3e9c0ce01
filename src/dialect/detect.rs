//! `--dialect auto`: decide the dialect from the text, and say why.
//!
//! A light scan over every line collects evidence (an Okuma `$…%` header, LAP calls, named
//! variables; Fanuc `#` variables, two-block G71 with P/Q, U/W moves, R arcs …). Strong
//! features weigh more than weak ones. When both sides have evidence the larger score wins
//! and the parser reports a warning naming the blocks on each side.
//!
//! The scan runs before parsing because the block grammar depends on the dialect (`NAT00`
//! is a label on OSP and an error on Fanuc).

use std::fmt;

use crate::source::{LineIndex, Span};

use super::{Dialect, MachineKind};

/// What pointed where.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Feature {
    OspHeader,
    AlphanumericSequence,
    LapCall,
    NamedVariable,
    EqualsValue,
    OspKeyword,
    IfWithoutGoto,
    SixDigitTool,
    HashVariable,
    TwoBlockRoughing,
    IncrementalMove,
    ArcRadiusR,
    ColonProgramNumber,
    PackedSequence,
    SubprogramCall,
    WorkOffset,
    ToolChange,
    ToolLengthOffset,
    HolePattern,
    MachiningCentreName,
    /// A comment turnpass writes into its outputs, naming the dialect they were read and
    /// written in (`(TURNPASS … DIALECT OSP)`): written where the text alone would read as
    /// the other, so it decides.
    MarkedOsp,
    MarkedFanuc,
}

impl Feature {
    /// Which way the feature points: a dialect, or (for OSP) the machining-centre kind.
    pub fn leaning(self) -> Leaning {
        use Feature::*;
        match self {
            OspHeader | AlphanumericSequence | LapCall | NamedVariable | EqualsValue | OspKeyword | IfWithoutGoto
            | SixDigitTool | MarkedOsp => Leaning::Dialect(Dialect::Osp),
            HashVariable | TwoBlockRoughing | IncrementalMove | ArcRadiusR | ColonProgramNumber | PackedSequence
            | SubprogramCall | WorkOffset | MarkedFanuc => Leaning::Dialect(Dialect::Fanuc),
            ToolChange | ToolLengthOffset | HolePattern | MachiningCentreName => Leaning::MachiningCentre,
        }
    }

    fn weight(self) -> u32 {
        use Feature::*;
        match self {
            // Above anything the rest of a program can add up to (20 of each feature count).
            MarkedOsp | MarkedFanuc => 10_000,
            OspHeader | LapCall | NamedVariable | OspKeyword | HashVariable | TwoBlockRoughing | ColonProgramNumber => {
                10
            }
            AlphanumericSequence | IfWithoutGoto | EqualsValue | PackedSequence => 5,
            _ => 2,
        }
    }

    pub fn description(self) -> &'static str {
        use Feature::*;
        match self {
            OspHeader => "`$NAME.MIN%` file header",
            AlphanumericSequence => "alphanumeric sequence name (`NAT00`)",
            LapCall => "LAP call (`G85 N…`)",
            NamedVariable => "named variable assignment (`NAME=`)",
            EqualsValue => "word with `=` value (`X=…`)",
            OspKeyword => "`CALL`, `RTS` or `MODIN`",
            IfWithoutGoto => "`IF [...] N…` jump",
            SixDigitTool => "six-digit tool word (`T010101`)",
            HashVariable => "`#` macro variable",
            TwoBlockRoughing => "G71/G72/G73 with P and Q",
            IncrementalMove => "`U`/`W` incremental move",
            ArcRadiusR => "arc with `R` radius",
            ColonProgramNumber => "`:` program number",
            PackedSequence => "sequence number packed against a word (`N1G0`)",
            SubprogramCall => "`M98 P` subprogram call",
            WorkOffset => "G54-G59 work offset",
            ToolChange => "`M6` tool change",
            ToolLengthOffset => "`G56 … H` tool length offset",
            HolePattern => "hole pattern statement (`BHC`, `LAA` …)",
            MachiningCentreName => "machining-centre control named in a comment",
            MarkedOsp | MarkedFanuc => "turnpass's comment naming the dialect its output was written in",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Leaning {
    Dialect(Dialect),
    MachiningCentre,
}

/// A feature, how often it occurs, and where it occurs first.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Evidence {
    pub feature: Feature,
    pub count: u32,
    pub first: Span,
}

impl Evidence {
    /// One line of `check --verbose`: how often, what, and where first.
    fn describe(&self, lines: &LineIndex) -> String {
        format!(
            "    {} × {}, first at line {}\n",
            self.count,
            self.feature.description(),
            lines.position(self.first.start).0
        )
    }
}

/// How the dialect was chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Choice {
    /// Given on the command line or in the machine settings.
    Given,
    /// Decided from the evidence.
    Detected,
    /// No evidence either way: the default.
    Default,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Detection {
    pub dialect: Dialect,
    pub machine_kind: MachineKind,
    pub choice: Choice,
    pub evidence: Vec<Evidence>,
}

impl Detection {
    pub fn score(&self, dialect: Dialect) -> u32 {
        self.evidence
            .iter()
            .filter(|e| e.feature.leaning() == Leaning::Dialect(dialect))
            .map(|e| e.feature.weight() * e.count.min(20))
            .sum()
    }

    /// Evidence for `leaning`, strongest first.
    pub fn evidence_for(&self, leaning: Leaning) -> Vec<&Evidence> {
        let mut list: Vec<&Evidence> = self.evidence.iter().filter(|e| e.feature.leaning() == leaning).collect();
        list.sort_by_key(|e| (std::cmp::Reverse(e.feature.weight()), e.first.start));
        list
    }

    /// Whether the evidence points both ways (no conflict where turnpass's mark decides).
    pub fn is_conflicted(&self) -> bool {
        let marked = self.evidence.iter().any(|e| matches!(e.feature, Feature::MarkedOsp | Feature::MarkedFanuc));
        self.choice == Choice::Detected
            && !marked
            && !self.evidence_for(Leaning::Dialect(Dialect::Osp)).is_empty()
            && !self.evidence_for(Leaning::Dialect(Dialect::Fanuc)).is_empty()
    }

    /// The explanation `check --verbose` prints.
    pub fn explain(&self, lines: &LineIndex) -> String {
        let mut out = String::new();
        let how = match self.choice {
            Choice::Given => "given by option or machine settings",
            Choice::Detected => "detected from the text",
            Choice::Default => "no evidence either way; the default",
        };
        out.push_str(&format!("dialect: {} ({how})\n", self.dialect));
        for dialect in [Dialect::Osp, Dialect::Fanuc] {
            let list = self.evidence_for(Leaning::Dialect(dialect));
            if list.is_empty() {
                continue;
            }
            out.push_str(&format!("  {} evidence (score {}):\n", dialect, self.score(dialect)));
            for e in list {
                out.push_str(&e.describe(lines));
            }
        }
        if self.dialect == Dialect::Osp {
            let list = self.evidence_for(Leaning::MachiningCentre);
            let kind = if self.machine_kind == MachineKind::MachiningCentre { "machining centre" } else { "lathe" };
            out.push_str(&format!("machine: {kind}\n"));
            for e in list {
                out.push_str(&e.describe(lines));
            }
        }
        out
    }
}

impl fmt::Display for Feature {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.description())
    }
}

/// Whether a line is an Okuma `$NAME.EXT%` header.
pub fn is_osp_header(line: &[u8]) -> bool {
    let Some(rest) = line.strip_prefix(b"$") else { return false };
    let name_len = rest.iter().take_while(|c| c.is_ascii_alphanumeric() || matches!(c, b'_' | b'-')).count();
    if name_len == 0 {
        return false;
    }
    let Some(rest) = rest[name_len..].strip_prefix(b".") else { return false };
    let ext_len = rest.iter().take_while(|c| c.is_ascii_alphanumeric()).count();
    if ext_len == 0 || ext_len > 3 {
        return false;
    }
    let Some(rest) = rest[ext_len..].strip_prefix(b"%") else { return false };
    rest.iter().all(|c| matches!(c, b' ' | b'\t'))
}

/// Bytes the scan can pass over without looking: digits, `.`, `-`, `+` and blanks.
static QUIET: [bool; 256] = {
    let mut table = [false; 256];
    let mut c = b'0';
    while c <= b'9' {
        table[c as usize] = true;
        c += 1;
    }
    table[b'.' as usize] = true;
    table[b'-' as usize] = true;
    table[b'+' as usize] = true;
    table[b' ' as usize] = true;
    table[b'\t' as usize] = true;
    table
};

struct Collector {
    evidence: Vec<Evidence>,
}

impl Collector {
    fn add(&mut self, feature: Feature, start: usize, end: usize) {
        match self.evidence.iter_mut().find(|e| e.feature == feature) {
            Some(e) => e.count += 1,
            None => self.evidence.push(Evidence { feature, count: 1, first: Span::new(start as u32, end as u32) }),
        }
    }
}

/// Scan the whole source for evidence.
pub fn scan(source: &[u8]) -> Vec<Evidence> {
    let mut collector = Collector { evidence: Vec::new() };
    let mut pos = 0;
    while pos < source.len() {
        let (end, next) = match memchr::memchr2(b'\n', b'\r', &source[pos..]) {
            Some(i) => {
                let at = pos + i;
                let next = if source[at] == b'\r' && source.get(at + 1) == Some(&b'\n') { at + 2 } else { at + 1 };
                (at, next)
            }
            None => (source.len(), source.len()),
        };
        scan_line(source, pos, end, &mut collector);
        pos = next;
    }
    collector.evidence
}

fn scan_line(source: &[u8], start: usize, end: usize, out: &mut Collector) {
    let line = &source[start..end];
    if line.first() == Some(&b'$') && is_osp_header(line) {
        out.add(Feature::OspHeader, start, end);
        return;
    }
    let first_token = line.iter().position(|c| !matches!(c, b' ' | b'\t' | b'/')).unwrap_or(line.len());
    let mut motion: Option<u32> = None;
    let mut cycle: Option<u32> = None;
    let (mut has_uw, mut has_r, mut has_p, mut has_q, mut has_label, mut has_any_g) =
        (false, false, false, false, false, false);
    let n = line.len();
    let mut i = first_token;
    while i < n {
        // Digits, points, signs and blanks carry no evidence: jump to the next byte that might.
        match line[i..].iter().position(|&b| !QUIET[b as usize]) {
            Some(skip) => i += skip,
            None => break,
        }
        let c = line[i];
        let at = start + i;
        let first = i == first_token;
        match c {
            b'(' => {
                let close = line[i..].iter().position(|&b| b == b')').map_or(n, |p| i + p + 1);
                let text = &line[i..close];
                if let Some(feature) = marked_dialect(&text[1..]) {
                    out.add(feature, at, start + close);
                }
                if let Some(p) = text.windows(3).position(|w| w == b"OSP") {
                    let digits = text[p + 3..].iter().take_while(|c| c.is_ascii_digit()).count();
                    if digits > 0 && text.get(p + 3 + digits) == Some(&b'M') {
                        out.add(Feature::MachiningCentreName, at, start + close);
                    }
                }
                i = close;
                continue;
            }
            b';' => {
                if let Some(feature) = marked_dialect(&line[i + 1..]) {
                    out.add(feature, at, end);
                }
                break;
            }
            b'#' => out.add(Feature::HashVariable, at, at + 1),
            b':' if first => out.add(Feature::ColonProgramNumber, at, at + 1),
            b'A'..=b'Z' => {
                let next = line.get(i + 1).copied().unwrap_or(b' ');
                if next.is_ascii_uppercase() {
                    i += scan_name(line, i, first, start, out);
                    continue;
                }
                if next == b'=' {
                    out.add(Feature::EqualsValue, at, at + 2);
                }
                if matches!(c, b'G' | b'M' | b'T' | b'N' | b'V') {
                    let mut digits = 0;
                    let mut number: u32 = 0;
                    while let Some(&d) = line.get(i + 1 + digits) {
                        if !d.is_ascii_digit() {
                            break;
                        }
                        number = number.saturating_mul(10).saturating_add((d - b'0') as u32);
                        digits += 1;
                    }
                    let number = (digits > 0).then_some(number);
                    let word_end = at + 1 + digits;
                    match c {
                        b'V' if digits > 0 && line.get(i + 1 + digits) == Some(&b'=') => {
                            out.add(Feature::NamedVariable, at, word_end)
                        }
                        b'N' if first && digits > 0 && line.get(i + 1 + digits).is_some_and(u8::is_ascii_uppercase) => {
                            out.add(Feature::PackedSequence, at, word_end)
                        }
                        b'N' if !first => has_label = true,
                        b'G' => {
                            has_any_g = true;
                            match number {
                                Some(n @ 0..=3) => motion = Some(n),
                                Some(56) if line.contains(&b'H') => out.add(Feature::ToolLengthOffset, at, word_end),
                                Some(54..=59) => out.add(Feature::WorkOffset, at, word_end),
                                Some(n @ (70..=76 | 85..=88 | 90 | 92 | 94)) => cycle = Some(n),
                                _ => {}
                            }
                        }
                        b'T' if digits == 6 => out.add(Feature::SixDigitTool, at, word_end),
                        b'M' if number == Some(6) => out.add(Feature::ToolChange, at, word_end),
                        b'M' if number == Some(98) && line.contains(&b'P') => {
                            out.add(Feature::SubprogramCall, at, word_end)
                        }
                        _ => {}
                    }
                    i += 1 + digits;
                    continue;
                }
                match c {
                    b'U' | b'W' => has_uw = true,
                    b'R' => has_r = true,
                    b'P' => has_p = true,
                    b'Q' => has_q = true,
                    _ => {}
                }
            }
            _ => {}
        }
        i += 1;
    }
    if cycle.is_none() && has_uw && (motion.is_some() || !has_any_g) {
        out.add(Feature::IncrementalMove, start, end);
    }
    if matches!(motion, Some(2 | 3)) && has_r {
        out.add(Feature::ArcRadiusR, start, end);
    }
    match cycle {
        Some(71..=73) if has_p && has_q => out.add(Feature::TwoBlockRoughing, start, end),
        Some(85..=88) if has_label => out.add(Feature::LapCall, start, end),
        _ => {}
    }
}

/// The dialect a comment's body names when it is turnpass's mark: it starts with `TURNPASS`
/// and one of its comma-separated fields is `DIALECT OSP` or `DIALECT FANUC` (in either case,
/// as the comment follows the program's).
fn marked_dialect(body: &[u8]) -> Option<Feature> {
    let body = body.trim_ascii_start();
    if !body.get(..8).is_some_and(|head| head.eq_ignore_ascii_case(b"turnpass")) {
        return None;
    }
    body.split(|&b| b == b',' || b == b')').find_map(|field| {
        let field = field.trim_ascii();
        let value = field.get(..8).filter(|head| head.eq_ignore_ascii_case(b"dialect ")).map(|_| &field[8..])?;
        match value.trim_ascii() {
            value if value.eq_ignore_ascii_case(b"osp") => Some(Feature::MarkedOsp),
            value if value.eq_ignore_ascii_case(b"fanuc") => Some(Feature::MarkedFanuc),
            _ => None,
        }
    })
}

/// A run of letters at `i` (`NAT00`, `CALL`, `FLAN=`, `IF`): records its evidence and returns
/// its length.
fn scan_name(line: &[u8], i: usize, first: bool, start: usize, out: &mut Collector) -> usize {
    let at = start + i;
    let name_len = line[i..].iter().take_while(|c| c.is_ascii_uppercase() || c.is_ascii_digit()).count();
    let name = &line[i..i + name_len];
    let after = line.get(i + name_len).copied();
    if first && name[0] == b'N' && name_len <= 5 {
        out.add(Feature::AlphanumericSequence, at, at + name_len);
        return name_len;
    }
    match name {
        b"CALL" | b"RTS" | b"MODIN" | b"MODOUT" => out.add(Feature::OspKeyword, at, at + name_len),
        b"BHC" | b"LAA" | b"SQRX" | b"SQRY" | b"GRDX" | b"GRDY" | b"DMDX" | b"DMDY" => {
            out.add(Feature::HolePattern, at, at + name_len)
        }
        _ if name.starts_with(b"IF") && !name[2..].iter().any(u8::is_ascii_uppercase) => {
            if let Some(close) = line[i..].iter().rposition(|&b| b == b']') {
                let tail = &line[i + close + 1..];
                let tail = &tail[tail.iter().take_while(|c| **c == b' ').count()..];
                if tail.first() == Some(&b'N') {
                    out.add(Feature::IfWithoutGoto, at, at + 2);
                }
            }
        }
        _ if after == Some(b'=') => out.add(Feature::NamedVariable, at, at + name_len),
        _ if after == Some(b'[') => {
            let assigned = line[i + name_len..]
                .iter()
                .position(|&b| b == b']')
                .is_some_and(|p| line.get(i + name_len + p + 1) == Some(&b'='));
            if assigned {
                out.add(Feature::NamedVariable, at, at + name_len);
            }
        }
        _ => {}
    }
    name_len
}

/// Decide the dialect (when not given) and, for OSP, the machine kind.
pub fn decide(source: &[u8], given: Option<Dialect>, kind: Option<MachineKind>) -> Detection {
    let evidence = if scan_needed(given, kind) { scan(source) } else { Vec::new() };
    decide_from(evidence, given, kind)
}

/// Whether deciding needs the evidence of [`scan`]. The scan costs a pass over the text; it is
/// skipped when there is nothing to decide (a Fanuc program has no machine kind to tell apart).
pub fn scan_needed(given: Option<Dialect>, kind: Option<MachineKind>) -> bool {
    given.is_none() || (given == Some(Dialect::Osp) && kind.is_none())
}

/// Add the evidence of a later stretch of the same text (its spans already in the text's
/// offsets) to `into`: what a scan of both stretches together would have found.
pub fn merge_evidence(into: &mut Vec<Evidence>, later: impl IntoIterator<Item = Evidence>) {
    for evidence in later {
        match into.iter_mut().find(|e| e.feature == evidence.feature) {
            Some(e) => e.count = e.count.saturating_add(evidence.count),
            None => into.push(evidence),
        }
    }
}

/// [`decide`] from evidence already collected (empty when [`scan_needed`] is false).
pub fn decide_from(evidence: Vec<Evidence>, given: Option<Dialect>, kind: Option<MachineKind>) -> Detection {
    let mut detection =
        Detection { dialect: Dialect::Fanuc, machine_kind: MachineKind::Lathe, choice: Choice::Default, evidence };
    match given {
        Some(dialect) => {
            detection.dialect = dialect;
            detection.choice = Choice::Given;
        }
        None => {
            let osp = detection.score(Dialect::Osp);
            let fanuc = detection.score(Dialect::Fanuc);
            if osp > 0 || fanuc > 0 {
                detection.choice = Choice::Detected;
                detection.dialect = if osp > fanuc { Dialect::Osp } else { Dialect::Fanuc };
            }
        }
    }
    detection.machine_kind = match kind {
        Some(kind) => kind,
        // One machining-centre feature can occur on a lathe (a Y-axis turret uses G56-like
        // words on some controls); two different ones are a machining-centre program.
        None if detection.dialect == Dialect::Osp && detection.evidence_for(Leaning::MachiningCentre).len() >= 2 => {
            MachineKind::MachiningCentre
        }
        None => MachineKind::Lathe,
    };
    detection
}

#[cfg(test)]
mod tests;
