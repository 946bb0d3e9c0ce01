//! `turnpass report`: one self-contained HTML page for a compensation job, to read in any
//! browser and to send by mail: the programs and the model (names and SHA-256), `verify`'s
//! figures before and after and its verdict, the plots inline as SVG, and the edited blocks
//! as a diff (`diff.rs`).
//!
//! The page refers to nothing outside itself: its style sheet is in it, the plots are
//! inline SVG (without the namespace attribute, which HTML does not need), and it has no
//! script. Everything taken from a program or a file name is escaped.

pub(crate) mod diff;

use std::fmt::Write as _;

use sha2::{Digest, Sha256};

use crate::compensation::deviation::Figures;
use crate::compensation::verify::{Deviation, Measure};

/// A program the page names.
pub struct ProgramFile<'a> {
    pub name: &'a str,
    pub bytes: &'a [u8],
}

/// The model the page names.
pub struct ModelFile<'a> {
    pub file: &'a str,
    pub name: &'a str,
    pub sha256: &'a str,
}

/// A plot of the page: its anchor, its caption and its SVG, or why there is none.
pub struct Plot {
    pub id: &'static str,
    pub caption: String,
    pub svg: Result<String, String>,
}

/// Everything the page shows.
pub struct Page<'a> {
    pub version: &'a str,
    pub original: ProgramFile<'a>,
    pub compensated: ProgramFile<'a>,
    pub model: ModelFile<'a>,
    /// What the compensated program's provenance comment says it was made with.
    pub compensated_with: String,
    /// The start minute of the run and what set it.
    pub start: String,
    pub deviation: &'a Deviation,
    /// Which measure `deviation` is.
    pub measure: Measure,
    pub limit_mm: f64,
    pub words_checked: usize,
    pub violations: &'a [String],
    pub warnings: &'a [String],
    pub plots: Vec<Plot>,
}

/// `text` with `&`, `<`, `>`, `"` and `'` escaped, for HTML text and attribute values.
pub fn escape(text: &str) -> String {
    let text = crate::source::escape_controls(text);
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// The SHA-256 of `bytes`, lower-case hex.
pub fn sha256(bytes: &[u8]) -> String {
    Sha256::digest(bytes).iter().map(|byte| format!("{byte:02x}")).collect()
}

const STYLE: &str = "
body { font-family: sans-serif; margin: 2em auto; max-width: 1240px; padding: 0 1em; color: #111; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; }
h2 { font-size: 1.25em; border-bottom: 1px solid #bbb; padding-bottom: 0.2em; margin-top: 1.6em; }
table { border-collapse: collapse; }
th, td { text-align: left; padding: 0.25em 0.8em 0.25em 0; vertical-align: top; }
td.number { text-align: right; font-variant-numeric: tabular-nums; }
code, .mono { font-family: monospace; }
.verdict { font-size: 1.2em; font-weight: bold; padding: 0.5em 0.8em; border-radius: 4px; display: inline-block; }
.verdict.ok { background: #d8f0e6; border: 2px solid #009e73; }
.verdict.violation { background: #fbe3d4; border: 2px solid #d55e00; }
figure { margin: 1em 0 2em 0; }
figure svg { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 0.95em; margin-top: 0.3em; }
table.diff { font-family: monospace; font-size: 0.9em; }
table.diff td { padding: 0 0.6em; white-space: pre-wrap; overflow-wrap: anywhere; }
table.diff td.line { color: #777; text-align: right; }
tr.removed td.text { background: #fbe3d4; }
tr.added td.text { background: #d6eaf5; }
tr.gap td { color: #777; }
";

/// The page.
pub fn html(page: &Page<'_>) -> String {
    let mut out = String::new();
    let title = format!("turnpass report: {}", page.compensated.name);
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{}</title>\n\
         <style>{STYLE}</style>\n</head>\n<body>\n",
        escape(&title)
    );
    let _ = writeln!(out, "<h1>Compensation report</h1>");
    let _ = writeln!(
        out,
        "<p>{} compensated as {}, checked by <code>turnpass verify</code> on the model below.</p>",
        code(page.original.name),
        code(page.compensated.name)
    );
    if page.violations.is_empty() {
        let _ = writeln!(out, "<p class=\"verdict ok\" id=\"verdict\">verify: ok</p>");
    } else {
        let _ = writeln!(
            out,
            "<p class=\"verdict violation\" id=\"verdict\">verify: {} violation{}</p>\n<ul class=\"violations\">",
            page.violations.len(),
            if page.violations.len() == 1 { "" } else { "s" }
        );
        for violation in page.violations {
            let _ = writeln!(out, "<li>{}</li>", escape(violation));
        }
        let _ = writeln!(out, "</ul>");
    }
    if !page.warnings.is_empty() {
        let _ = writeln!(out, "<ul class=\"warnings\">");
        for warning in page.warnings {
            let _ = writeln!(out, "<li>warning: {}</li>", escape(warning));
        }
        let _ = writeln!(out, "</ul>");
    }
    programs(&mut out, page);
    figures(&mut out, page);
    let _ = writeln!(out, "<h2>Plots</h2>");
    for plot in &page.plots {
        match &plot.svg {
            Ok(svg) => {
                let _ = writeln!(
                    out,
                    "<figure class=\"plot\" id=\"{}\">\n{}\n<figcaption>{}</figcaption>\n</figure>",
                    plot.id,
                    inline(svg),
                    escape(&plot.caption)
                );
            }
            Err(why) => {
                let _ = writeln!(out, "<p class=\"no-plot\">{}: not drawn: {}</p>", escape(&plot.caption), escape(why));
            }
        }
    }
    edited_blocks(&mut out, page);
    let _ = writeln!(out, "<p><small>Made by turnpass {}.</small></p>\n</body>\n</html>", escape(page.version));
    out
}

fn code(text: &str) -> String {
    format!("<code>{}</code>", escape(text))
}

fn programs(out: &mut String, page: &Page<'_>) {
    let _ = writeln!(out, "<h2>Programs and model</h2>\n<table id=\"programs\">");
    let mut row = |label: &str, value: String| {
        let _ = writeln!(out, "<tr><th>{}</th><td>{value}</td></tr>", escape(label));
    };
    for (label, program) in [("Original", &page.original), ("Compensated", &page.compensated)] {
        row(label, format!("{}<br><span class=\"mono\">sha256 {}</span>", code(program.name), sha256(program.bytes)));
    }
    row(
        "Model",
        format!(
            "{} ({})<br><span class=\"mono\">sha256 {}</span>",
            escape(page.model.name),
            code(page.model.file),
            escape(page.model.sha256)
        ),
    );
    row("Compensated with", escape(&page.compensated_with));
    row("Start of the run", escape(&page.start));
    let _ = writeln!(out, "</table>");
}

fn figures(out: &mut String, page: &Page<'_>) {
    let d = page.deviation;
    let _ = writeln!(
        out,
        "<h2>Predicted deviation from the nominal part</h2>\n<p>Measure: <strong>{}</strong> ({}), against the \
         nominal part of {}, as <code>turnpass verify</code>{} measures it, µm.</p>\n\
         <table id=\"figures\" data-measure=\"{}\">\n<tr><th></th><th>max</th><th>RMS</th><th>SSQ</th><th>points</th></tr>",
        match page.measure {
            Measure::Part => "the finished part",
            Measure::Passes => "pass by pass",
        },
        page.measure.describe(),
        code(page.original.name),
        if page.measure == Measure::Passes { " --passes" } else { "" },
        match page.measure {
            Measure::Part => "part",
            Measure::Passes => "passes",
        },
    );
    let row = |label: &str, f: &Figures| {
        format!(
            "<tr><th>{label}</th><td class=\"number\">{:.3}</td><td class=\"number\">{:.3}</td>\
             <td class=\"number\">{:.3}</td><td class=\"number\">{}</td></tr>\n",
            f.max_mm * 1000.0,
            f.rms_mm * 1000.0,
            f.ssq_mm * 1000.0,
            f.points
        )
    };
    out.push_str(&row("as programmed", &d.before));
    out.push_str(&row("compensated", &d.after));
    let _ = writeln!(
        out,
        "</table>\n<p>RMS improvement: <strong>{}</strong>. Largest deviation allowed: {:.3} µm. \
         Non-motion words checked: {}.</p>",
        crate::compensation::deviation::improvement_text(d.improvement_percent),
        page.limit_mm * 1000.0,
        page.words_checked
    );
}

fn edited_blocks(out: &mut String, page: &Page<'_>) {
    let diff = diff::diff(page.original.bytes, page.compensated.bytes);
    let _ = writeln!(
        out,
        "<h2>Edited blocks</h2>\n<p>{} lines differ between {} (−, line numbers on the left) and {} (+, on the right).</p>",
        diff.changed,
        code(page.original.name),
        code(page.compensated.name)
    );
    if diff.lines.is_empty() {
        return;
    }
    let _ = writeln!(out, "<table class=\"diff\" id=\"diff\">");
    for line in &diff.lines {
        let _ = match line {
            diff::Line::Same(a, b, text) => writeln!(
                out,
                "<tr class=\"same\"><td class=\"line\">{a}</td><td class=\"line\">{b}</td><td> </td><td class=\"text\">{}</td></tr>",
                escape(text)
            ),
            diff::Line::Removed(a, text) => writeln!(
                out,
                "<tr class=\"removed\"><td class=\"line\">{a}</td><td class=\"line\"></td><td>−</td><td class=\"text\">{}</td></tr>",
                escape(text)
            ),
            diff::Line::Added(b, text) => writeln!(
                out,
                "<tr class=\"added\"><td class=\"line\"></td><td class=\"line\">{b}</td><td>+</td><td class=\"text\">{}</td></tr>",
                escape(text)
            ),
            diff::Line::Gap => writeln!(
                out,
                "<tr class=\"gap\"><td class=\"line\">…</td><td class=\"line\">…</td><td></td><td></td></tr>"
            ),
        };
    }
    let _ = writeln!(out, "</table>");
    if diff.not_shown > 0 {
        let _ = writeln!(out, "<p>… and {} more changed lines, not shown.</p>", diff.not_shown);
    }
}

/// An SVG document as an element of the page: without the XML namespace attribute, which
/// HTML's parser supplies, so that the page names no address at all.
fn inline(svg: &str) -> String {
    svg.replacen(" xmlns=\"http://www.w3.org/2000/svg\"", "", 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escaping() {
        assert_eq!(escape("(<A&B> \"q\" 'r')"), "(&lt;A&amp;B&gt; &quot;q&quot; &#39;r&#39;)");
    }

    #[test]
    fn the_page_escapes_what_the_programs_hold_and_names_no_address() {
        let deviation = Deviation::default();
        let page = Page {
            version: "0.1.0",
            original: ProgramFile { name: "a<b>.nc", bytes: b"O1\n(<script>)\nG01 X1.\n" },
            compensated: ProgramFile { name: "c.nc", bytes: b"O1\n(<script>)\nG01 X1.001\n" },
            model: ModelFile { file: "m.toml", name: "M & N", sha256: "00" },
            compensated_with: "nothing".to_string(),
            start: "0 min".to_string(),
            deviation: &deviation,
            measure: Measure::Part,
            limit_mm: 0.002,
            words_checked: 1,
            violations: &["lost `M30`".to_string()],
            warnings: &[],
            plots: vec![Plot {
                id: "plot-path",
                caption: "path".to_string(),
                svg: Ok("<svg width=\"1\" height=\"1\" xmlns=\"http://www.w3.org/2000/svg\"></svg>".to_string()),
            }],
        };
        let html = html(&page);
        assert!(!html.contains("<script"), "{html}");
        assert!(html.contains("a&lt;b&gt;.nc") && html.contains("M &amp; N"));
        assert!(!html.contains("http"), "{html}");
        assert!(html.contains("verify: 1 violation<"));
        assert!(html.contains("G01 X1.001"));
        // The table says which measure it shows.
        assert!(html.contains("Measure: <strong>the finished part</strong>") && html.contains("data-measure=\"part\""));
        let passes = super::html(&Page { measure: Measure::Passes, ..page });
        assert!(passes.contains("Measure: <strong>pass by pass</strong>") && passes.contains("verify</code> --passes"));
    }
}
