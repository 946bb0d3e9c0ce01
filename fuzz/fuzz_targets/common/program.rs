//! Lathe programs built from blocks and cycles (`arbitrary`), so that the fuzzer's inputs get
//! past the parser: nearly every input is a program that parses, and most of them run, with
//! cycles, subprogram calls, loops, tool-nose compensation and unit changes among their
//! blocks. A few words in each program are left to chance (a raw word from a list, numbers
//! of every size), so that what the control rejects is reached too.

use std::fmt::Write as _;

use arbitrary::{Arbitrary, Result, Unstructured};

/// A number as a program writes it: mostly of a lathe's sizes, sometimes at the edges.
#[derive(Debug, Clone, Copy)]
pub struct Value(pub f64);

impl<'a> Arbitrary<'a> for Value {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        let value = match u.int_in_range(0..=15u8)? {
            // Whole and decimal millimetres of a lathe's part.
            0..=7 => f64::from(u.int_in_range(-2000..=2000i32)?) / 10.0,
            8..=10 => f64::from(u.int_in_range(-200_000..=200_000i32)?) / 1000.0,
            // Small: depths, feeds, allowances, down to below any increment.
            11 | 12 => f64::from(u.int_in_range(0..=5000u32)?) / 1e6,
            13 => 0.0,
            // Large, and the extremes a number can be written as.
            14 => f64::from(u.int_in_range(-99_999_999..=99_999_999i32)?),
            _ => *u.choose(&[1e-9, 1e-300, 1e300, 99_999_999.0, -99_999_999.0, 0.5, 0.0001])?,
        };
        Ok(Value(value))
    }
}

impl std::fmt::Display for Value {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = self.0;
        if v != 0.0 && v.abs() < 1e-4 {
            // Written out as a control reads it, not in exponent form.
            write!(f, "{v:.9}")
        } else if v.abs() >= 1e12 {
            write!(f, "{v:.0}")
        } else if v.fract() == 0.0 {
            write!(f, "{v:.0}.")
        } else {
            write!(f, "{v}")
        }
    }
}

/// A feed per revolution or per minute.
#[derive(Debug, Clone, Copy)]
pub struct Feed(pub f64);

impl<'a> Arbitrary<'a> for Feed {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        Ok(Feed(match u.int_in_range(0..=7u8)? {
            0..=5 => f64::from(u.int_in_range(1..=600u32)?) / 1000.0,
            6 => f64::from(u.int_in_range(1..=5000u32)?),
            _ => Value::arbitrary(u)?.0,
        }))
    }
}

/// A small whole number (counts, repetitions, station numbers).
#[derive(Debug, Clone, Copy, Arbitrary)]
pub enum Count {
    Small(u8),
    Large(u32),
}

impl Count {
    fn get(self) -> u64 {
        match self {
            Count::Small(n) => u64::from(n % 12),
            Count::Large(n) => u64::from(n),
        }
    }
}

#[derive(Debug, Clone, Copy, Arbitrary)]
pub enum ProfileMove {
    Line { x: Option<Value>, z: Option<Value> },
    Arc { ccw: bool, x: Value, z: Value, r: Value },
    Chamfer { x: Value, z: Value },
}

#[derive(Debug, Clone, Arbitrary)]
pub enum Block {
    Rapid {
        x: Option<Value>,
        z: Option<Value>,
    },
    Line {
        x: Option<Value>,
        z: Option<Value>,
        f: Option<Feed>,
    },
    Incremental {
        u: Option<Value>,
        w: Option<Value>,
    },
    Arc {
        ccw: bool,
        x: Value,
        z: Value,
        centre: ArcCentre,
        f: Option<Feed>,
    },
    Dwell {
        seconds: Value,
    },
    Tool {
        station: u8,
        offset: u8,
    },
    Spindle {
        surface: bool,
        speed: Value,
        clamp: Option<Value>,
    },
    FeedMode {
        per_rev: bool,
    },
    Units {
        inch: bool,
    },
    Absolute {
        absolute: bool,
    },
    NoseRadius {
        side: u8,
    },
    Home,
    Shift {
        x: Value,
        z: Value,
    },
    StockRemoval(StockRemoval),
    PatternRepeat {
        relief_x: Value,
        relief_z: Value,
        divisions: Count,
        u: Value,
        w: Value,
        profile: Vec<ProfileMove>,
        f: Feed,
    },
    Finishing,
    Peck {
        face: bool,
        x: Value,
        z: Value,
        peck: Value,
        step: Value,
        retract: Value,
        f: Feed,
    },
    Thread {
        x: Value,
        z: Value,
        taper: Value,
        height: Value,
        first: Value,
        lead: Value,
        finishes: u8,
        chamfer: u8,
        angle: u8,
        min: Value,
    },
    Single {
        kind: u8,
        x: Value,
        z: Value,
        taper: Option<Value>,
        f: Feed,
    },
    Call {
        repeat: Count,
        body: Vec<SimpleBlock>,
    },
    Loop {
        times: Count,
        body: Vec<SimpleBlock>,
    },
    Variable {
        number: u8,
        value: Value,
    },
    Raw(RawWord),
}

/// A block inside a subprogram or loop body (no nesting of its own).
#[derive(Debug, Clone, Copy, Arbitrary)]
pub enum SimpleBlock {
    Rapid { x: Option<Value>, z: Option<Value> },
    Line { x: Option<Value>, z: Option<Value>, f: Option<Feed> },
    Incremental { u: Option<Value>, w: Option<Value> },
    Arc { ccw: bool, x: Value, z: Value, r: Value },
}

#[derive(Debug, Clone, Copy, Arbitrary)]
pub enum ArcCentre {
    Radius(Value),
    Centre(Value, Value),
}

#[derive(Debug, Clone, Arbitrary)]
pub struct StockRemoval {
    pub facing: bool,
    pub one_block: bool,
    pub type_ii: bool,
    pub depth: Value,
    pub retract: Option<Value>,
    pub u: Value,
    pub w: Value,
    pub f: Option<Feed>,
    pub approach: ProfileMove,
    pub profile: Vec<ProfileMove>,
}

/// Words a program may hold that the generator does not build itself.
#[derive(Debug, Clone, Copy, Arbitrary)]
pub enum RawWord {
    Picked(u8),
    Code { letter: u8, value: Value },
}

const RAW: [&str; 24] = [
    "M30",
    "M02",
    "M99",
    "G28 U0 W0",
    "G53 X0 Z0",
    "G40",
    "G04 P1000",
    "G50 S1500",
    "G96 S200",
    "G97 S800",
    "/G01 X10.",
    "(COMMENT)",
    "%",
    "GOTO 10",
    "IF [#1 GT 3] GOTO 20",
    "#1=#1+1",
    "G00 X[#1*2]",
    "M98 P9999",
    "G70 P1 Q2",
    "G71 U1. R0.5",
    "G41 G01 X0 Z0 F0.1",
    "N10",
    "N20 G00",
    "G01 X1.E3",
];

#[derive(Debug, Clone, Arbitrary)]
pub struct Program {
    pub inch: bool,
    pub start: (Value, Value),
    pub blocks: Vec<Block>,
}

/// Writes a program's text: numbered blocks, profiles with sequence numbers, subprograms
/// after the main program's end.
struct Writer {
    text: String,
    sequence: u32,
    subprograms: Vec<(u32, Vec<SimpleBlock>)>,
    last_profile: Option<(u32, u32)>,
}

impl Writer {
    fn line(&mut self, block: impl AsRef<str>) {
        self.text.push_str(block.as_ref());
        self.text.push('\n');
    }

    fn next_sequence(&mut self) -> u32 {
        self.sequence += 10;
        self.sequence
    }

    fn profile(&mut self, approach: &ProfileMove, moves: &[ProfileMove], feed: Option<Feed>) -> (u32, u32) {
        let p = self.next_sequence();
        let mut first = format!("N{p} ");
        match approach {
            ProfileMove::Line { x, z } => {
                first.push_str("G00");
                axes(&mut first, *x, *z);
            }
            other => profile_move(&mut first, other),
        }
        self.line(first);
        let mut q = p;
        for (i, m) in moves.iter().take(12).enumerate() {
            q = self.next_sequence();
            let mut block = format!("N{q} ");
            profile_move(&mut block, m);
            if i == 0
                && let Some(f) = feed
            {
                let _ = write!(block, " F{}", f.0);
            }
            self.line(block);
        }
        self.last_profile = Some((p, q));
        (p, q)
    }

    fn simple(&mut self, block: &SimpleBlock) {
        let mut text = String::new();
        match block {
            SimpleBlock::Rapid { x, z } => {
                text.push_str("G00");
                axes(&mut text, *x, *z);
            }
            SimpleBlock::Line { x, z, f } => {
                text.push_str("G01");
                axes(&mut text, *x, *z);
                if let Some(f) = f {
                    let _ = write!(text, " F{}", f.0);
                }
            }
            SimpleBlock::Incremental { u, w } => {
                text.push_str("G01");
                if let Some(u) = u {
                    let _ = write!(text, " U{u}");
                }
                if let Some(w) = w {
                    let _ = write!(text, " W{w}");
                }
            }
            SimpleBlock::Arc { ccw, x, z, r } => {
                let _ = write!(text, "{} X{x} Z{z} R{r}", if *ccw { "G03" } else { "G02" });
            }
        }
        self.line(text);
    }
}

fn axes(text: &mut String, x: Option<Value>, z: Option<Value>) {
    if let Some(x) = x {
        let _ = write!(text, " X{x}");
    }
    if let Some(z) = z {
        let _ = write!(text, " Z{z}");
    }
}

fn profile_move(text: &mut String, m: &ProfileMove) {
    match m {
        ProfileMove::Line { x, z } => {
            text.push_str("G01");
            axes(text, *x, *z);
        }
        ProfileMove::Arc { ccw, x, z, r } => {
            let _ = write!(text, "{} X{x} Z{z} R{r}", if *ccw { "G03" } else { "G02" });
        }
        ProfileMove::Chamfer { x, z } => {
            let _ = write!(text, "G01 X{x} Z{z}");
        }
    }
}

impl Program {
    /// The program as Fanuc-compatible text.
    pub fn text(&self) -> String {
        let mut w = Writer { text: String::new(), sequence: 0, subprograms: Vec::new(), last_profile: None };
        w.line("%");
        w.line("O0001");
        w.line(if self.inch { "G20 G99" } else { "G21 G99" });
        w.line("T0101");
        w.line("G97 S800 M03");
        w.line(format!("G00 X{} Z{}", self.start.0, self.start.1));
        for block in self.blocks.iter().take(40) {
            self.block(&mut w, block);
        }
        w.line("G00 X200. Z100.");
        w.line("M30");
        let subprograms = std::mem::take(&mut w.subprograms);
        for (number, body) in subprograms {
            w.line(format!("O{number}"));
            for b in body.iter().take(8) {
                w.simple(b);
            }
            w.line("M99");
        }
        w.line("%");
        w.text
    }

    fn block(&self, w: &mut Writer, block: &Block) {
        match block {
            Block::Rapid { x, z } => w.simple(&SimpleBlock::Rapid { x: *x, z: *z }),
            Block::Line { x, z, f } => w.simple(&SimpleBlock::Line { x: *x, z: *z, f: *f }),
            Block::Incremental { u, w: dw } => w.simple(&SimpleBlock::Incremental { u: *u, w: *dw }),
            Block::Arc { ccw, x, z, centre, f } => {
                let mut text = format!("{} X{x} Z{z}", if *ccw { "G03" } else { "G02" });
                match centre {
                    ArcCentre::Radius(r) => {
                        let _ = write!(text, " R{r}");
                    }
                    ArcCentre::Centre(i, k) => {
                        let _ = write!(text, " I{i} K{k}");
                    }
                }
                if let Some(f) = f {
                    let _ = write!(text, " F{}", f.0);
                }
                w.line(text);
            }
            Block::Dwell { seconds } => w.line(format!("G04 X{seconds}")),
            Block::Tool { station, offset } => w.line(format!("T{:02}{:02}", station % 13, offset % 13)),
            Block::Spindle { surface, speed, clamp } => {
                if let Some(clamp) = clamp {
                    w.line(format!("G50 S{clamp}"));
                }
                w.line(format!("{} S{speed} M03", if *surface { "G96" } else { "G97" }));
            }
            Block::FeedMode { per_rev } => w.line(if *per_rev { "G99" } else { "G98" }),
            Block::Units { inch } => w.line(if *inch { "G20" } else { "G21" }),
            Block::Absolute { absolute } => w.line(if *absolute { "G90" } else { "G91" }),
            Block::NoseRadius { side } => w.line(["G40", "G41", "G42"][usize::from(side % 3)]),
            Block::Home => w.line("G28 U0. W0."),
            Block::Shift { x, z } => w.line(format!("G50 X{x} Z{z}")),
            Block::StockRemoval(cycle) => {
                let code = if cycle.facing { "G72" } else { "G71" };
                let after = w.sequence + 10;
                // The profile's numbers are known before it is written: P and Q name them.
                let count = cycle.profile.len().min(12) as u32;
                let (p, q) = (after, after + 10 * count);
                let feed = cycle.f.map(|f| format!(" F{}", f.0)).unwrap_or_default();
                if cycle.one_block {
                    let r = if cycle.type_ii { " R1" } else { "" };
                    w.line(format!("{code} P{p} Q{q} U{} W{} D{}{feed}{r}", cycle.u, cycle.w, cycle.depth));
                } else {
                    let retract = cycle.retract.map(|e| format!(" R{e}")).unwrap_or_default();
                    let depth_word = if cycle.facing { "W" } else { "U" };
                    w.line(format!("{code} {depth_word}{}{retract}", cycle.depth));
                    w.line(format!("{code} P{p} Q{q} U{} W{}{feed}", cycle.u, cycle.w));
                }
                let approach = if cycle.type_ii {
                    match cycle.approach {
                        ProfileMove::Line { x, z } => {
                            ProfileMove::Line { x: x.or(Some(Value(0.0))), z: z.or(Some(Value(0.0))) }
                        }
                        other => other,
                    }
                } else {
                    cycle.approach
                };
                w.profile(&approach, &cycle.profile, None);
            }
            Block::PatternRepeat { relief_x, relief_z, divisions, u, w: dw, profile, f } => {
                let after = w.sequence + 10;
                let count = profile.len().min(12) as u32;
                w.line(format!("G73 U{relief_x} W{relief_z} R{}", divisions.get()));
                w.line(format!("G73 P{after} Q{} U{u} W{dw} F{}", after + 10 * count, f.0));
                let approach = ProfileMove::Line { x: Some(Value(20.0)), z: None };
                w.profile(&approach, profile, None);
            }
            Block::Finishing => match w.last_profile {
                Some((p, q)) => w.line(format!("G70 P{p} Q{q}")),
                None => w.line("G70 P1 Q2"),
            },
            Block::Peck { face, x, z, peck, step, retract, f } => {
                let code = if *face { "G74" } else { "G75" };
                w.line(format!("{code} R{retract}"));
                let increments = |v: Value| (v.0.abs() * 1000.0).round();
                w.line(format!("{code} X{x} Z{z} P{} Q{} F{}", increments(*step), increments(*peck), f.0));
            }
            Block::Thread { x, z, taper, height, first, lead, finishes, chamfer, angle, min } => {
                let angles = [0, 29, 30, 55, 60, 80];
                w.line(format!(
                    "G76 P{:02}{:02}{:02} Q{} R{}",
                    finishes % 10,
                    chamfer % 100,
                    angles[usize::from(angle % 6)],
                    (min.0.abs() * 1000.0).round(),
                    first.0.abs().min(1.0)
                ));
                w.line(format!(
                    "G76 X{x} Z{z} R{taper} P{} Q{} F{}",
                    (height.0.abs() * 1000.0).round(),
                    (first.0.abs() * 1000.0).round(),
                    lead.0
                ));
            }
            Block::Single { kind, x, z, taper, f } => {
                let code = ["G90", "G92", "G94"][usize::from(kind % 3)];
                let taper = taper.map(|r| format!(" R{r}")).unwrap_or_default();
                w.line(format!("{code} X{x} Z{z}{taper} F{}", f.0));
            }
            Block::Call { repeat, body } => {
                let number = 9000 + w.subprograms.len() as u32;
                w.line(format!("M98 P{number} L{}", repeat.get()));
                w.subprograms.push((number, body.clone()));
            }
            Block::Loop { times, body } => {
                w.line("#100=0");
                w.line(format!("WHILE [#100 LT {}] DO1", times.get()));
                for b in body.iter().take(6) {
                    w.simple(b);
                }
                w.line("#100=#100+1");
                w.line("END1");
            }
            Block::Variable { number, value } => w.line(format!("#{}={value}", 100 + u32::from(*number % 50))),
            Block::Raw(RawWord::Picked(i)) => w.line(RAW[usize::from(*i) % RAW.len()]),
            Block::Raw(RawWord::Code { letter, value }) => {
                let letters = b"GMXZUWIKRFSTPQDLN";
                w.line(format!("{}{value}", char::from(letters[usize::from(*letter) % letters.len()])))
            }
        }
    }
}

/// The machines a program runs on: its settings as a model file's `[machine]` table.
pub const MACHINES: [&str; 4] = [
    r#"[machine]
dialect = "fanuc"
units = "mm"
decimal_input = "calculator"
home = { x = 200.0, z = 100.0 }
rapid_rate = { x = 8000.0, z = 12000.0 }
max_spindle_rpm = 3000
[[machine.tool]]
station = 1
nose_radius = 0.8
tip = 3
"#,
    r#"[machine]
dialect = "fanuc"
units = "inch"
least_increment = 0.0001
decimal_input = "increment"
home = { x = 6.0, z = 4.0 }
max_spindle_rpm = 3000
"#,
    r#"[machine]
dialect = "osp"
units = "mm"
home = { x = 300.0, z = 200.0 }
travel = { x_min = -10.0, x_max = 400.0, z_min = -500.0, z_max = 300.0 }
"#,
    "[machine]\n",
];

/// An input as the targets read it: a byte 0xFF first makes the rest a structured program;
/// any other input is a program's text as it stands (the seeds: the case files and the
/// corpus), so that mutation starts from real programs as well as built ones.
// Each target compiles the shared builders as its own module and uses a part of them.
#[allow(dead_code)]
pub fn program_text(data: &[u8]) -> Option<(Vec<u8>, &'static str)> {
    match data {
        [0xFF, machine, rest @ ..] => {
            let mut u = Unstructured::new(rest);
            let program = Program::arbitrary(&mut u).ok()?;
            Some((program.text().into_bytes(), MACHINES[usize::from(*machine) % 2]))
        }
        _ => Some((data.to_vec(), MACHINES[data.len() % MACHINES.len()])),
    }
}
