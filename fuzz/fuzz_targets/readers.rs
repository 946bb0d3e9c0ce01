//! Fuzzes the readers of `diagnose` and `fit-thermal`: ball bar traces, CMM profiles,
//! interferometer tables and thermal logs (CSV).
//!
//! An input whose first byte is 0xFF is a structured table (rows of numbers, words and
//! damage under one of the readers' headers, built with `arbitrary`); any other input is a
//! file's text as it stands (the seeds: the CSV files of the repository). The first byte of
//! what is left chooses the reader. The target checks that no reader panics or hangs, that
//! an error names a line of the text and a span inside it (on a character boundary), and
//! that what reads has as many points as rows it read.
//!
//! ```sh
//! RUSTC_BOOTSTRAP=1 cargo fuzz run readers fuzz/corpus/readers -- -max_total_time=1800 -rss_limit_mb=2048 -max_len=65536 -jobs=1
//! ```

#![no_main]

use arbitrary::{Arbitrary, Unstructured};
use libfuzzer_sys::fuzz_target;
use turnpass::diagnose::measured::{self, Axis, Kind, Measured, MeasuredError};
use turnpass::error_model::interferometer;

#[derive(Debug, Arbitrary)]
enum Cell {
    Number(i32, u8),
    Word(u8),
    Empty,
    Text(String),
}

const WORDS: [&str; 12] = ["ccw", "cw", "up", "down", "CCW", "A", "nan", "inf", "-0", "1e400", "\"q,uoted\"", "0.00O9"];

const HEADERS: [&str; 12] = [
    "angle_deg,deviation_mm,direction",
    "x_mm,z_mm",
    "x_mm,z_mm,part,start_min",
    "target_mm,direction,linear_mm",
    "target_mm,direction,run,linear_mm,straightness_m1_mm,straightness_m2_mm",
    "t_min,value",
    "angle_deg,deviation_mm,direction,extra",
    "Target (mm),Run 1 Fwd (um),Run 1 Rev (um),Run 2 Fwd (um),Run 2 Rev (um)",
    "Units: µm\nAxis: X\nTarget (mm),Direction,Run,Error",
    "X: diameter\nUnits: mm\nPoint,X,Z",
    "Direction: clockwise\nStart angle: 0\nAngle step: 1\nUnits: um\nPoint,Deviation",
    "Name,X,Y,Z,I,J,K",
];

#[derive(Debug, Arbitrary)]
struct Table {
    header: u8,
    comments: Vec<(u8, bool)>,
    rows: Vec<Vec<Cell>>,
    crlf: bool,
}

impl Table {
    fn text(&self) -> String {
        let end = if self.crlf { "\r\n" } else { "\n" };
        let mut out = String::new();
        out.push_str(HEADERS[usize::from(self.header) % HEADERS.len()]);
        out.push_str(end);
        for (i, row) in self.rows.iter().take(400).enumerate() {
            if let Some((_, blank)) = self.comments.iter().find(|(at, _)| usize::from(*at) == i) {
                out.push_str(if *blank { "" } else { "# a comment" });
                out.push_str(end);
            }
            let cells: Vec<String> = row
                .iter()
                .take(8)
                .map(|cell| match cell {
                    Cell::Number(n, places) => format!("{}", f64::from(*n) / 10f64.powi(i32::from(places % 8))),
                    Cell::Word(w) => WORDS[usize::from(*w) % WORDS.len()].to_string(),
                    Cell::Empty => String::new(),
                    Cell::Text(t) => t.chars().take(12).collect(),
                })
                .collect();
            out.push_str(&cells.join(","));
            out.push_str(end);
        }
        out
    }
}

/// The lines of `text` as the readers split them: at LF, CR LF or a lone CR.
fn lines_of(text: &str) -> Vec<&str> {
    let mut lines = Vec::new();
    let mut rest = text;
    while let Some(end) = rest.find(['\n', '\r']) {
        lines.push(&rest[..end]);
        let skip = if rest[end..].starts_with("\r\n") { 2 } else { 1 };
        rest = &rest[end + skip..];
    }
    lines.push(rest);
    lines
}

/// An error names a line of `text` and a span inside it, on character boundaries.
fn check_error(text: &str, error: &MeasuredError) {
    let lines = lines_of(text).len();
    assert!(error.line >= 1 && error.line <= lines + 1, "line {} of {lines}: {error:?}", error.line);
    let (start, end) = (error.span.start as usize, error.span.end as usize);
    assert!(start <= end && end <= text.len(), "span {start}..{end} of {}: {error:?}", text.len());
    assert!(text.is_char_boundary(start) && text.is_char_boundary(end), "span off a character: {error:?}");
}

fuzz_target!(|data: &[u8]| {
    let (choice, text) = match data {
        [0xFF, choice, rest @ ..] => {
            let Ok(table) = Table::arbitrary(&mut Unstructured::new(rest)) else { return };
            (*choice, table.text())
        }
        [choice, rest @ ..] => match std::str::from_utf8(rest) {
            Ok(text) => (*choice, text.to_string()),
            Err(_) => return,
        },
        [] => return,
    };
    let kind = match choice % 5 {
        0 => None,
        1 => Some(Kind::BallBar),
        2 => Some(Kind::Profile),
        3 => Some(Kind::Table(Axis::X)),
        _ => {
            match measured::read_thermal_log(&text) {
                Ok((t, v)) => assert_eq!(t.len(), v.len()),
                Err(error) => check_error(&text, &error),
            }
            if let Err(error) = interferometer::parse(&text) {
                check_error(&text, &error);
            }
            return;
        }
    };
    match measured::read(&text, kind) {
        Ok(read) => {
            let rows = lines_of(&text)
                .into_iter()
                .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
                .count();
            if !matches!(read, Measured::Table { .. }) {
                assert!(read.len() < rows, "{} points from {rows} lines with the header", read.len());
            }
        }
        Err(error) => check_error(&text, &error),
    }
});
