//! The plots of the bundled examples read back as a person reads them, from their SVG
//! (`tests/cases/plots/plots.toml`): a path plot at true scale (a millimetre of Z as long
//! as one of X, by the tick labels; a circle drawn round), its magnification stated and its
//! µm scale bar as long as it says, its legend above the data; a polar plot with its zero
//! circle round, its angles, directions and ring values labelled, its legend, test and ISO
//! 230-4 figures beside the trace; Okabe–Ito colours only. Each plot's structure (element
//! counts, labels, colours) is a snapshot.

use std::collections::BTreeMap;
use std::process::Command;

use serde::Deserialize;

use crate::support::{repo, with_snapshots};

#[derive(Deserialize)]
struct Cases {
    case: Vec<Case>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Case {
    name: String,
    kind: String,
    args: Vec<String>,
    #[serde(default)]
    round: bool,
    #[serde(default)]
    residual: bool,
    /// Commands run first, in order, each as `args` is (`{tmp}` the case's folder).
    #[serde(default)]
    before: Vec<Vec<String>>,
    /// The id of the figure to read from the HTML page `{out}` (a report), instead of `{out}`
    /// itself as an SVG.
    #[serde(default)]
    figure: Option<String>,
}

/// Okabe and Ito's colours and black: the only strokes a data line may have.
const PALETTE: [&str; 9] =
    ["#000000", "#E69F00", "#56B4E9", "#009E73", "#F0E442", "#0072B2", "#D55E00", "#CC79A7", "#808080"];

struct Text {
    x: f64,
    y: f64,
    anchor: String,
    text: String,
}

struct Line {
    stroke: String,
    width: String,
    points: Vec<(f64, f64)>,
}

struct Svg {
    texts: Vec<Text>,
    lines: Vec<Line>,
    counts: BTreeMap<String, usize>,
}

fn read_svg(source: &str) -> Svg {
    let document = roxmltree::Document::parse(source).expect("the plot is well-formed XML");
    let mut svg = Svg { texts: Vec::new(), lines: Vec::new(), counts: BTreeMap::new() };
    for node in document.descendants().filter(|n| n.is_element()) {
        let name = node.tag_name().name().to_string();
        *svg.counts.entry(name.clone()).or_default() += 1;
        let number = |attribute: &str| node.attribute(attribute).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.0);
        match name.as_str() {
            "text" => svg.texts.push(Text {
                x: number("x"),
                y: number("y"),
                anchor: node.attribute("text-anchor").unwrap_or("").to_string(),
                text: node.text().unwrap_or("").trim().to_string(),
            }),
            "polyline" => svg.lines.push(Line {
                stroke: node.attribute("stroke").unwrap_or("").to_uppercase(),
                width: node.attribute("stroke-width").unwrap_or("").to_string(),
                points: node
                    .attribute("points")
                    .unwrap_or("")
                    .split_whitespace()
                    .filter_map(|p| p.split_once(','))
                    .map(|(x, y)| (x.parse().unwrap(), y.parse().unwrap()))
                    .collect(),
            }),
            _ => {}
        }
    }
    svg
}

impl Svg {
    fn text(&self, wanted: &str) -> &Text {
        self.texts.iter().find(|t| t.text == wanted).unwrap_or_else(|| panic!("no label `{wanted}`"))
    }

    fn text_starting(&self, start: &str) -> &Text {
        self.texts.iter().find(|t| t.text.starts_with(start)).unwrap_or_else(|| panic!("no label starting `{start}`"))
    }

    /// The lines of data drawn in colour: not the black nominal, the grey grid or rapids,
    /// nor the legend's samples of the lines (horizontal, 28 pixels at most, dashed or not).
    fn coloured(&self) -> impl Iterator<Item = &Line> {
        let sample = |l: &Line| {
            let (x0, x1, y0, y1) = extents(l.points.iter().copied());
            y0 == y1 && x1 - x0 <= 28.0
        };
        self.lines.iter().filter(move |l| {
            l.stroke != "#000000" && l.stroke != "#808080" && PALETTE.contains(&l.stroke.as_str()) && !sample(l)
        })
    }
}

/// The slope of position against value of numeric labels (pixels per unit).
fn slope(labels: &[(f64, f64)]) -> f64 {
    let n = labels.len() as f64;
    let (mv, mp) = (labels.iter().map(|l| l.0).sum::<f64>() / n, labels.iter().map(|l| l.1).sum::<f64>() / n);
    let sxy: f64 = labels.iter().map(|(v, p)| (v - mv) * (p - mp)).sum();
    let sxx: f64 = labels.iter().map(|(v, _)| (v - mv) * (v - mv)).sum();
    sxy / sxx
}

fn extents(points: impl Iterator<Item = (f64, f64)>) -> (f64, f64, f64, f64) {
    points.fold((f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY), |(a, b, c, d), (x, y)| {
        (a.min(x), b.max(x), c.min(y), d.max(y))
    })
}

fn check_path(case: &Case, svg: &Svg) {
    let numeric: Vec<(&Text, f64)> =
        svg.texts.iter().filter_map(|t| t.text.parse::<f64>().ok().map(|v| (t, v))).collect();
    // The main drawing's Z labels are the upper row of centred numbers; its X labels the
    // right-anchored numbers above that row.
    let row = numeric.iter().filter(|(t, _)| t.anchor == "middle").map(|(t, _)| t.y).fold(f64::INFINITY, f64::min);
    let z_labels: Vec<(f64, f64)> =
        numeric.iter().filter(|(t, _)| t.anchor == "middle" && t.y == row).map(|(t, v)| (*v, t.x)).collect();
    let x_labels: Vec<(f64, f64)> =
        numeric.iter().filter(|(t, _)| t.anchor == "end" && t.y < row).map(|(t, v)| (*v, t.y)).collect();
    assert!(z_labels.len() >= 3 && x_labels.len() >= 3, "{}: tick labels {z_labels:?} {x_labels:?}", case.name);
    let (across, up) = (slope(&z_labels), -slope(&x_labels));
    assert!(
        ((across - up) / across).abs() < 0.02,
        "{}: not at true scale: {across} px per mm of Z, {up} px per mm of X",
        case.name
    );
    // The magnification stated, and the scale bar as long as it says.
    let scale = svg.text_starting("scale: ");
    let (um, magnify) = scale
        .text
        .strip_prefix("scale: ")
        .and_then(|t| t.split_once(" µm of deviation (×"))
        .map(|(um, k)| (um.parse::<f64>().unwrap(), k.trim_end_matches(')').parse::<f64>().unwrap()))
        .unwrap_or_else(|| panic!("{}: scale label `{}`", case.name, scale.text));
    assert!(svg.texts.iter().any(|t| t.text.contains(&format!("magnified ×{magnify} "))), "{}", case.name);
    if let Some(given) = case.args.iter().position(|a| a == "--magnify") {
        assert_eq!(
            case.args[given + 1].parse::<f64>().unwrap(),
            magnify,
            "{}: the magnification given wins",
            case.name
        );
    }
    let bar = svg
        .lines
        .iter()
        .filter(|l| l.width == "2" && l.points.len() == 2 && l.points[0].1 == l.points[1].1)
        .find(|l| (l.points[0].1 - scale.y).abs() < 12.0 && l.points[0].0 > scale.x)
        .unwrap_or_else(|| panic!("{}: no scale bar beside `{}`", case.name, scale.text));
    let length = (bar.points[1].0 - bar.points[0].0).abs();
    let expected = um / 1000.0 * magnify * across;
    assert!(
        (length - expected).abs() <= 1.5 + 0.01 * expected,
        "{}: bar {length} px, {expected} px expected",
        case.name
    );
    for label in ["Z, nominal (mm)", "X, radius, nominal (mm)", "µm"] {
        svg.text(label);
    }
    if case.kind == "path" && !case.name.starts_with("diagnose") {
        svg.text("rapid");
        let subtitle = &svg.text_starting("deviation along the surface normal, magnified ×").text;
        assert!(subtitle.contains("rapids dashed, not magnified"), "{}: {subtitle}", case.name);
    }
    // The legend is above the data.
    let data_top = svg.coloured().flat_map(|l| l.points.iter().map(|p| p.1)).fold(f64::INFINITY, f64::min);
    let legend = if case.name.starts_with("diagnose") { "nominal surface" } else { "as programmed" };
    assert!(svg.text(legend).y + 8.0 < data_top, "{}: the legend overlaps the data", case.name);
    if case.round {
        // The nominal circle: its points all at one distance in pixels from its centre.
        let nominal: Vec<(f64, f64)> = svg
            .lines
            .iter()
            .filter(|l| l.stroke == "#000000" && l.width == "1" && l.points.len() > 30)
            .flat_map(|l| l.points.iter().copied())
            .filter(|p| p.1 < row)
            .collect();
        let (left, _, top, bottom) = extents(nominal.iter().copied());
        let radius = (bottom - top) / 2.0;
        let centre = (left + radius, top + radius);
        for p in nominal.iter().filter(|p| (p.1 - centre.1).abs() > 0.1 * radius) {
            let r = ((p.0 - centre.0).powi(2) + (p.1 - centre.1).powi(2)).sqrt();
            assert!(
                ((r - radius) / radius).abs() < 0.02,
                "{}: the circle is not round: {r} px, {radius} px",
                case.name
            );
        }
    }
}

/// A part figure: the path figure's checks, the half-section under it, the probed surface in
/// black, and each part's deviation along the surface with the points it was probed at.
fn check_part(case: &Case, svg: &Svg) {
    check_path(case, svg);
    for label in ["stock", "finished part", "nominal surface (probed)", "as programmed", "compensated"] {
        svg.text(label);
    }
    assert!(!svg.texts.iter().any(|t| t.text == "rapid"), "{}: a part figure has no rapids", case.name);
    let said = &svg.text_starting("the finished part each program cuts on the model, probed at ").text;
    let points: usize = said
        .strip_prefix("the finished part each program cuts on the model, probed at ")
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or(0);
    assert!(points > 100, "{}: `{said}`", case.name);
    svg.text("length along the probed nominal surface (mm)");
    svg.text_starting("deviation along the surface normal (µm, + material left");
    // The nominal surface drawn in black in the main drawing, and a line of each part's
    // colour (vermillion as programmed, blue compensated) in the drawing and in the strip.
    let nominal = svg.lines.iter().filter(|l| l.stroke == "#000000" && l.width == "1" && l.points.len() > 10).count();
    assert!(nominal > 0, "{}: no probed surface drawn", case.name);
    for colour in ["#D55E00", "#0072B2"] {
        let drawn = svg.coloured().filter(|l| l.stroke == colour).count();
        assert!(drawn >= 2, "{}: {drawn} lines of {colour}", case.name);
    }
}

/// The inline SVG of the figure `id` in an HTML page.
fn figure_in(page: &str, id: &str) -> String {
    let at = page.find(&format!("id=\"{id}\"")).unwrap_or_else(|| panic!("no figure `{id}` on the page"));
    let start = at + page[at..].find("<svg").expect("the figure holds an SVG");
    let end = start + page[start..].find("</svg>").expect("the SVG ends") + "</svg>".len();
    page[start..end].to_string()
}

fn check_polar(case: &Case, svg: &Svg) {
    let zero = svg
        .lines
        .iter()
        .find(|l| l.stroke == "#000000" && l.width == "2" && l.points.len() > 100)
        .unwrap_or_else(|| panic!("{}: no zero circle", case.name));
    let (x0, x1, y0, y1) = extents(zero.points.iter().copied());
    let (w, h) = (x1 - x0, y1 - y0);
    assert!(((w - h) / w).abs() < 0.02, "{}: the zero circle is {w} × {h} px", case.name);
    for degrees in (30..360).step_by(30).filter(|d| *d != 90) {
        svg.text(&format!("{degrees}°"));
    }
    for label in ["0° +Z", "90° +X", "+Z", "+X", "0 µm", "Legend", "G, clockwise", "G, counter-clockwise", "G(b), both"]
        .into_iter()
        .chain(["H, hysteresis", "F, largest", "F, smallest"])
    {
        svg.text(label);
    }
    let division = svg.text_starting(if case.residual { "residual" } else { "radial deviation" });
    let per_ring = division.text.split([',', ';']).find_map(|part| part.trim().strip_suffix(" µm per ring")).unwrap();
    svg.text(&format!("+{per_ring} µm"));
    svg.text(&format!("-{per_ring} µm"));
    svg.text_starting("0 µm: ");
    if !case.residual {
        svg.text("radius 100.000 mm (X as a radius)");
        svg.text("feed 1000 mm/min");
        svg.text("direction counter-clockwise (G03), then clockwise (G02)");
    }
    // The legend and the figures are beside the trace, not over it.
    let (_, trace_right, _, _) = extents(svg.coloured().flat_map(|l| l.points.iter().copied()));
    for label in ["Legend", "G(b), both"] {
        assert!(svg.text(label).x > trace_right, "{}: `{label}` is over the trace", case.name);
    }
}

fn structure(svg: &Svg) -> String {
    let mut out = String::from("elements:\n");
    for (name, count) in &svg.counts {
        out.push_str(&format!("  {name} {count}\n"));
    }
    let mut colours: Vec<&str> = svg.lines.iter().map(|l| l.stroke.as_str()).collect();
    colours.sort_unstable();
    colours.dedup();
    out.push_str(&format!("line colours: {}\nlabels:\n", colours.join(" ")));
    for text in &svg.texts {
        out.push_str(&format!("  {}\n", text.text));
    }
    out
}

#[test]
fn plots_of_the_examples_read_at_a_glance() {
    let cases: Cases =
        toml::from_str(&std::fs::read_to_string(repo().join("tests/cases/plots/plots.toml")).unwrap()).unwrap();
    for case in &cases.case {
        let tmp = tempfile::tempdir().unwrap();
        let out = tmp.path().join(if case.figure.is_some() { "report.html" } else { "plot.svg" });
        let fill = |args: &[String]| -> Vec<String> {
            args.iter()
                .map(|a| a.replace("{out}", &out.to_string_lossy()).replace("{tmp}", &tmp.path().to_string_lossy()))
                .collect()
        };
        for args in case.before.iter().chain([&case.args]) {
            let output =
                Command::new(env!("CARGO_BIN_EXE_turnpass")).args(fill(args)).current_dir(repo()).output().unwrap();
            assert!(output.status.success(), "{}: {}", case.name, String::from_utf8_lossy(&output.stderr));
        }
        // The case's folder is named where a program in it is (a report's title): `{tmp}`.
        let written = std::fs::read_to_string(&out).unwrap().replace(&*tmp.path().to_string_lossy(), "{tmp}");
        let svg = read_svg(&match &case.figure {
            Some(id) => figure_in(&written, id),
            None => written,
        });
        for line in svg.lines.iter().filter(|l| l.width == "2") {
            assert!(
                PALETTE.contains(&line.stroke.as_str()),
                "{}: colour {} is not Okabe–Ito's",
                case.name,
                line.stroke
            );
        }
        match case.kind.as_str() {
            "path" => check_path(case, &svg),
            "polar" => check_polar(case, &svg),
            "part" => check_part(case, &svg),
            other => panic!("{}: unknown kind `{other}`", case.name),
        }
        with_snapshots("plots", || insta::assert_snapshot!(case.name.clone(), structure(&svg)));
    }
}
