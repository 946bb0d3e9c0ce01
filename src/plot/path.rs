//! The path figure: the part's nominal path at true scale (Z and X at the same millimetres
//! per pixel), each series' deviation drawn along the surface normal and magnified by a
//! stated factor with a micrometre scale bar, rapids dashed and never magnified, the legend
//! in a row of its own above the drawing, and below it the deviation in micrometres along
//! the cutting length.

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::palette::{GREY, NOMINAL, PART};
use super::scale::{magnification, micrometres, nice_at_least, scale_bar_um};
use super::{Lines, PlotError, drawing};
use crate::toolpath::Xz;

/// A deviation along the surface normal at a point of the nominal path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct NormalDeviation {
    /// The point of the nominal path, and the unit normal there (from the part toward the tool).
    pub at: Xz,
    pub normal: Xz,
    /// Signed, mm: positive away from the part.
    pub mm: f64,
    /// Cutting length along the nominal path, mm.
    pub along_mm: f64,
}

/// One series: unbroken runs of deviations.
pub(crate) struct Series<'a> {
    pub label: &'a str,
    pub colour: RGBColor,
    pub runs: Vec<Vec<NormalDeviation>>,
}

pub(crate) struct PathFigure<'a> {
    pub title: &'a str,
    /// Some deviations are measured along the left of travel, the tool's side not being
    /// known there (`PathPoint::side`); the figure says so.
    pub side_unknown: bool,
    /// The nominal cutting path (solid) and the rapids (dashed, never magnified).
    pub nominal_label: &'a str,
    pub nominal: Lines,
    pub rapids: Lines,
    pub series: Vec<Series<'a>>,
    /// The magnification asked for; `None` chooses one (`scale::magnification`).
    pub magnify: Option<f64>,
    /// The part model's half-section under the paths, where it ran.
    pub section: Option<Section>,
    /// What the deviations' length runs along, for the strip under the drawing.
    pub along: Along,
    /// Lines said under the title, after the magnification's.
    pub notes: Vec<String>,
}

/// What a figure's deviations are laid out along: the cut (a path, pass by pass) or the
/// nominal surface (a finished part, probed).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Along {
    Cut,
    Surface,
}

impl Along {
    fn strip_title(self) -> &'static str {
        match self {
            Along::Cut => "deviation along the surface normal (µm, + away from the part), along the cut",
            Along::Surface => {
                "deviation along the surface normal (µm, + material left, − removed inside the part), along the surface"
            }
        }
    }

    fn axis(self) -> &'static str {
        match self {
            Along::Cut => "cutting length along the nominal path (mm)",
            Along::Surface => "length along the probed nominal surface (mm)",
        }
    }
}

/// The stock and the finished part the program cuts from it, in (Z, X) at true scale.
pub(crate) struct Section {
    /// The stock's outline, closed; drawn dashed.
    pub stock: Vec<(f64, f64)>,
    /// No `[stock]` or `--stock` gave it: the legend says it is assumed.
    pub stock_assumed: bool,
    /// The finished part's half-section polygons (`Part::outline`), filled.
    pub part: Vec<Vec<(f64, f64)>>,
}

/// The figure and the magnification it was drawn at.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawn {
    pub svg: String,
    pub magnify: f64,
}

const WIDTH: u32 = 1000;
/// The title's height, and each line under it.
pub(crate) const TITLE: u32 = 38;
pub(crate) const LINE: u32 = 20;
const LEGEND: u32 = 34;
const STRIP: u32 = 240;
const Y_LABELS: u32 = 72;
const X_LABELS: u32 = 46;
const MARGIN_LEFT: u32 = 10;
const MARGIN_RIGHT: u32 = 28;
const MARGIN_TOP: u32 = 10;
const MARGIN_BOTTOM: u32 = 6;
/// The drawing's height at true scale is held between these, pixels; the other axis's
/// range grows to keep the scale.
const MIN_HEIGHT: f64 = 260.0;
const MAX_HEIGHT: f64 = 640.0;

/// A (Z, X) rectangle.
#[derive(Debug, Clone, Copy)]
struct View {
    z: (f64, f64),
    x: (f64, f64),
}

impl View {
    fn of<'p>(points: impl IntoIterator<Item = &'p (f64, f64)>) -> Option<View> {
        let mut view = View { z: (f64::INFINITY, f64::NEG_INFINITY), x: (f64::INFINITY, f64::NEG_INFINITY) };
        for &(z, x) in points {
            if z.is_finite() && x.is_finite() {
                view.z = (view.z.0.min(z), view.z.1.max(z));
                view.x = (view.x.0.min(x), view.x.1.max(x));
            }
        }
        view.z.0.is_finite().then_some(view)
    }

    fn union(self, other: Option<View>) -> View {
        let Some(o) = other else { return self };
        View { z: (self.z.0.min(o.z.0), self.z.1.max(o.z.1)), x: (self.x.0.min(o.x.0), self.x.1.max(o.x.1)) }
    }

    fn size(&self) -> f64 {
        (self.z.1 - self.z.0).max(self.x.1 - self.x.0)
    }

    fn padded(self, pad: f64) -> View {
        View { z: (self.z.0 - pad, self.z.1 + pad), x: (self.x.0 - pad, self.x.1 + pad) }
    }

    /// The view grown about its centre to `width` × `height` mm.
    fn grown_to(self, width: f64, height: f64) -> View {
        let (cz, cx) = ((self.z.0 + self.z.1) / 2.0, (self.x.0 + self.x.1) / 2.0);
        View { z: (cz - width / 2.0, cz + width / 2.0), x: (cx - height / 2.0, cx + height / 2.0) }
    }
}

/// Draw the figure.
pub(crate) fn draw(figure: &PathFigure<'_>) -> Result<Drawn, PlotError> {
    let part = View::of(figure.nominal.iter().flatten()).ok_or(PlotError::NothingToPlot)?;
    let deviations = || figure.series.iter().flat_map(|s| s.runs.iter().flatten());
    let largest = deviations().map(|d| d.mm.abs()).filter(|d| d.is_finite()).fold(0.0, f64::max);
    let magnify = figure.magnify.unwrap_or_else(|| magnification(largest, part.size().max(1e-3)));
    let magnified: Vec<Lines> = figure
        .series
        .iter()
        .map(|s| {
            s.runs
                .iter()
                .map(|run| {
                    run.iter()
                        .map(|d| {
                            let r = magnify * d.mm;
                            (d.at.z + r * d.normal.z, d.at.x + r * d.normal.x)
                        })
                        .collect()
                })
                .collect()
        })
        .collect();
    let view = part.union(View::of(magnified.iter().flatten().flatten()));
    let view = match &figure.section {
        Some(section) => view.union(View::of(section.stock.iter().chain(section.part.iter().flatten()))),
        None => view,
    };
    let view = view.padded(0.06 * view.size().max(1e-3));

    // True scale: one millimetre is as many pixels across as up.
    let plot_width = f64::from(WIDTH - Y_LABELS - MARGIN_LEFT - MARGIN_RIGHT);
    let (span_z, span_x) = (view.z.1 - view.z.0, view.x.1 - view.x.0);
    let mut pixels_per_mm = plot_width / span_z;
    let mut plot_height = span_x * pixels_per_mm;
    if plot_height > MAX_HEIGHT {
        plot_height = MAX_HEIGHT;
        pixels_per_mm = MAX_HEIGHT / span_x;
    }
    let plot_height = plot_height.max(MIN_HEIGHT).round();
    let main_height = plot_height as u32 + MARGIN_TOP + MARGIN_BOTTOM + X_LABELS;
    let mut lines = vec![format!(
        "deviation along the surface normal, magnified ×{} (+ away from the part); Z and X at the same scale, axes in \
         nominal mm{}",
        micrometres(magnify),
        if figure.rapids.is_empty() { "" } else { "; rapids dashed, not magnified" }
    )];
    if figure.side_unknown {
        lines.push(
            "where the tool's side is not known (no nose-radius compensation, no tip direction), + is left of the \
             direction of travel"
                .to_string(),
        );
    }
    lines.extend(figure.notes.iter().cloned());
    let header_height = TITLE + LINE * lines.len() as u32 + 6;
    let mut entries = Vec::new();
    if let Some(section) = &figure.section {
        let stock = if section.stock_assumed { "stock (assumed)" } else { "stock" };
        entries.push(Entry { label: stock.to_string(), colour: GREY, dashed: true, width: 1 });
        entries.push(Entry { label: "finished part".to_string(), colour: PART, dashed: false, width: 10 });
    }
    entries.push(Entry { label: figure.nominal_label.to_string(), colour: NOMINAL, dashed: false, width: 1 });
    if !figure.rapids.is_empty() {
        entries.push(Entry { label: "rapid".to_string(), colour: GREY, dashed: true, width: 1 });
    }
    entries.extend(figure.series.iter().map(|s| Entry {
        label: s.label.to_string(),
        colour: s.colour,
        dashed: false,
        width: 2,
    }));
    // The scale bar shares the legend's row when both fit, else it has a row of its own.
    let legend_width: i32 = entries.iter().map(|e| 34 + text_width(&e.label, 14) + 22).sum();
    let (bar_um, bar_pixels) = scale_bar_length(magnify * pixels_per_mm / 1000.0);
    let bar_room = 10 + text_width(&scale_text(bar_um, magnify), 14) + bar_pixels;
    let fits = i32::try_from(Y_LABELS + MARGIN_LEFT).unwrap_or(0) + legend_width + bar_room
        <= i32::try_from(WIDTH - MARGIN_RIGHT).unwrap_or(0);
    let legend_rows = if fits { 1 } else { 2 };
    let height = header_height + LEGEND * legend_rows + main_height + STRIP;

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (WIDTH, height)).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        let (header, rest) = root.split_vertically(header_height);
        let (legend, rest) = rest.split_vertically(LEGEND * legend_rows);
        let (main, strip) = rest.split_vertically(main_height);

        let mut builder = ChartBuilder::on(&main);
        builder
            .margin_left(MARGIN_LEFT)
            .margin_right(MARGIN_RIGHT)
            .margin_top(MARGIN_TOP)
            .margin_bottom(MARGIN_BOTTOM)
            .x_label_area_size(X_LABELS)
            .y_label_area_size(Y_LABELS);
        // The plotting area's size in pixels, then the ranges that fill it at the scale.
        let probe = builder.build_cartesian_2d(0.0..1.0, 0.0..1.0).map_err(drawing)?;
        let (w, h) = probe.plotting_area().dim_in_pixel();
        let pixels_per_mm = pixels_per_mm.min(f64::from(w) / span_z).min(f64::from(h) / span_x);
        let view = view.grown_to(f64::from(w) / pixels_per_mm, f64::from(h) / pixels_per_mm);
        let mut chart = builder.build_cartesian_2d(view.z.0..view.z.1, view.x.0..view.x.1).map_err(drawing)?;
        chart
            .configure_mesh()
            .x_desc("Z, nominal (mm)")
            .y_desc("X, radius, nominal (mm)")
            .x_labels(10)
            .y_labels(((f64::from(h) / f64::from(w)) * 10.0).ceil().max(4.0) as usize)
            .light_line_style(GREY.mix(0.12))
            .bold_line_style(GREY.mix(0.35))
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 14))
            .draw()
            .map_err(drawing)?;
        if let Some(section) = &figure.section {
            for polygon in &section.part {
                chart.draw_series([Polygon::new(polygon.clone(), PART.filled())]).map_err(drawing)?;
            }
            let mut outline = section.stock.clone();
            outline.extend(section.stock.first().copied());
            for (a, b) in outline.windows(2).map(|w| (w[0], w[1])) {
                if let Some((a, b)) = clip(a, b, &view) {
                    chart.draw_series(DashedLineSeries::new([a, b], 3, 3, GREY.stroke_width(1))).map_err(drawing)?;
                }
            }
        }
        for line in &figure.rapids {
            for (a, b) in line.windows(2).map(|w| (w[0], w[1])) {
                if let Some((a, b)) = clip(a, b, &view) {
                    chart.draw_series(DashedLineSeries::new([a, b], 6, 5, GREY.stroke_width(1))).map_err(drawing)?;
                }
            }
        }
        for line in &figure.nominal {
            chart.draw_series(LineSeries::new(line.iter().copied(), NOMINAL.stroke_width(1))).map_err(drawing)?;
        }
        for (series, lines) in figure.series.iter().zip(&magnified) {
            for line in lines.iter().filter(|l| l.len() > 1) {
                chart
                    .draw_series(LineSeries::new(line.iter().copied(), series.colour.stroke_width(2)))
                    .map_err(drawing)?;
            }
        }

        header_text(&header, figure.title, &lines)?;
        legend_row(&legend, &entries)?;
        let pixels_per_um = magnify * pixels_per_mm / 1000.0;
        scale_bar(&legend, pixels_per_um, magnify, legend_rows)?;
        strip_chart(&strip, figure, largest)?;
        root.present().map_err(drawing)?;
    }
    Ok(Drawn { svg, magnify })
}

/// The deviation in micrometres against the cutting length along the path.
fn strip_chart(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    figure: &PathFigure<'_>,
    largest: f64,
) -> Result<(), PlotError> {
    let along = figure.series.iter().flat_map(|s| s.runs.iter().flatten()).map(|d| d.along_mm);
    let (first, last) = along.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    let (first, last) = if first.is_finite() && last > first { (first, last) } else { (0.0, 1.0) };
    let limit = nice_at_least(largest * 1000.0 * 1.1, 0.1);
    let (title_area, chart_area) = area.split_vertically(26);
    title_area
        .draw(&Text::new(
            figure.along.strip_title(),
            (i32::try_from(Y_LABELS + MARGIN_LEFT).unwrap_or(0), 6),
            ("sans-serif", 14).into_font().color(&NOMINAL),
        ))
        .map_err(drawing)?;
    let mut chart = ChartBuilder::on(&chart_area)
        .margin_left(MARGIN_LEFT)
        .margin_right(MARGIN_RIGHT)
        .margin_bottom(6)
        .x_label_area_size(X_LABELS)
        .y_label_area_size(Y_LABELS)
        .build_cartesian_2d(first..last, -limit..limit)
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .x_desc(figure.along.axis())
        .y_desc("µm")
        .y_labels(5)
        .light_line_style(GREY.mix(0.12))
        .bold_line_style(GREY.mix(0.35))
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 14))
        .draw()
        .map_err(drawing)?;
    chart.draw_series(LineSeries::new([(first, 0.0), (last, 0.0)], NOMINAL.stroke_width(1))).map_err(drawing)?;
    for series in &figure.series {
        for run in series.runs.iter().filter(|r| r.len() > 1) {
            let points = run.iter().map(|d| (d.along_mm, d.mm * 1000.0));
            chart.draw_series(LineSeries::new(points, series.colour.stroke_width(1))).map_err(drawing)?;
        }
    }
    Ok(())
}

/// A legend entry: a sample of the line and its label.
pub(crate) struct Entry {
    pub label: String,
    pub colour: RGBColor,
    pub dashed: bool,
    pub width: u32,
}

/// A title and lines under it.
pub(crate) fn header_text(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    title: &str,
    lines: &[String],
) -> Result<(), PlotError> {
    area.draw(&Text::new(title.to_string(), (14, 10), ("sans-serif", 20).into_font().color(&NOMINAL)))
        .map_err(drawing)?;
    for (k, line) in lines.iter().enumerate() {
        let y = i32::try_from(TITLE + LINE * k as u32).unwrap_or(0);
        area.draw(&Text::new(line.clone(), (14, y), ("sans-serif", 14).into_font().color(&NOMINAL)))
            .map_err(drawing)?;
    }
    Ok(())
}

/// The legend as one row, left to right.
fn legend_row(area: &DrawingArea<SVGBackend<'_>, Shift>, entries: &[Entry]) -> Result<(), PlotError> {
    let mut x = i32::try_from(Y_LABELS + MARGIN_LEFT).unwrap_or(0);
    let y = i32::try_from(LEGEND / 2).unwrap_or(0);
    for entry in entries {
        sample_line(area, entry, (x, y))?;
        let label = Text::new(entry.label.clone(), (x + 34, y), label_style(14, HPos::Left));
        area.draw(&label).map_err(drawing)?;
        x += 34 + text_width(&entry.label, 14) + 22;
    }
    Ok(())
}

/// A 28-pixel sample of an entry's line starting at `at`.
pub(crate) fn sample_line(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    entry: &Entry,
    (x, y): (i32, i32),
) -> Result<(), PlotError> {
    let style = entry.colour.stroke_width(entry.width);
    if entry.dashed {
        area.draw(&DashedPathElement::new(vec![(x, y), (x + 28, y)], 6, 4, style)).map_err(drawing)?;
    } else {
        area.draw(&PathElement::new(vec![(x, y), (x + 28, y)], style)).map_err(drawing)?;
    }
    Ok(())
}

/// The scale bar's micrometres and its length in pixels.
fn scale_bar_length(pixels_per_um: f64) -> (f64, i32) {
    let um = scale_bar_um(pixels_per_um, 50.0);
    (um, (um * pixels_per_um).round() as i32)
}

fn scale_text(um: f64, magnify: f64) -> String {
    format!("scale: {} µm of deviation (×{})", micrometres(um), micrometres(magnify))
}

/// The micrometre scale bar, at the right of the legend's last row.
fn scale_bar(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    pixels_per_um: f64,
    magnify: f64,
    row: u32,
) -> Result<(), PlotError> {
    let (um, length) = scale_bar_length(pixels_per_um);
    let right = i32::try_from(WIDTH - MARGIN_RIGHT).unwrap_or(0);
    let left = right - length;
    let y = i32::try_from(LEGEND * (row - 1) + LEGEND / 2).unwrap_or(0);
    let style = NOMINAL.stroke_width(2);
    area.draw(&PathElement::new(vec![(left, y), (right, y)], style)).map_err(drawing)?;
    for x in [left, right] {
        area.draw(&PathElement::new(vec![(x, y - 6), (x, y + 6)], style)).map_err(drawing)?;
    }
    let text = scale_text(um, magnify);
    area.draw(&Text::new(text, (left - 10, y), label_style(14, HPos::Right))).map_err(drawing)?;
    Ok(())
}

/// Black sans-serif text of `size`, anchored at its vertical middle and `h`.
pub(crate) fn label_style(size: u32, h: HPos) -> TextStyle<'static> {
    ("sans-serif", size).into_font().color(&NOMINAL).pos(Pos::new(h, VPos::Center))
}

/// About how wide `text` is in a sans-serif font of `size` pixels.
pub(crate) fn text_width(text: &str, size: u32) -> i32 {
    (text.chars().count() as f64 * f64::from(size) * 0.56).ceil() as i32
}

/// The part of the segment `a`–`b` inside `view` (Liang–Barsky).
fn clip(a: (f64, f64), b: (f64, f64), view: &View) -> Option<((f64, f64), (f64, f64))> {
    let (dz, dx) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [(-dz, a.0 - view.z.0), (dz, view.z.1 - a.0), (-dx, a.1 - view.x.0), (dx, view.x.1 - a.1)] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 < t1).then_some(((a.0 + t0 * dz, a.1 + t0 * dx), (a.0 + t1 * dz, a.1 + t1 * dx)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_keeps_the_part_inside() {
        let view = View { z: (0.0, 10.0), x: (0.0, 10.0) };
        assert_eq!(clip((-5.0, 5.0), (5.0, 5.0), &view), Some(((0.0, 5.0), (5.0, 5.0))));
        assert_eq!(clip((-5.0, 20.0), (5.0, 20.0), &view), None);
        assert_eq!(clip((1.0, 1.0), (2.0, 2.0), &view), Some(((1.0, 1.0), (2.0, 2.0))));
    }
}
