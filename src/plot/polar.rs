//! The polar figure of a circular test, as a ball bar's software draws it: the radial
//! deviation against the angle about the circle's centre, around a base circle (0 µm, the
//! nominal radius) with rings one division apart and labelled in micrometres, spokes every
//! 30° labelled with the angle from +Z toward +X, the directions +Z and +X, and beside the
//! drawing, clear of the trace, the legend, the test (radius, feed, direction) and the
//! ISO 230-4 figures.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::HPos;

use super::palette::{GREY, NOMINAL};
use super::path::{Entry, header_text, label_style, sample_line, text_width};
use super::scale::{micrometres, nice_at_least};
use super::{PlotError, drawing};

/// One trace: (angle from +Z toward +X in radians, radial deviation in µm) points.
pub(crate) struct PolarSeries {
    pub label: String,
    pub colour: RGBColor,
    pub dashed: bool,
    pub points: Vec<(f64, f64)>,
}

pub(crate) struct PolarFigure<'a> {
    pub title: &'a str,
    /// What the deviations are, before the division the figure chooses.
    pub what: &'a str,
    pub series: Vec<PolarSeries>,
    /// The legend's words for the 0 µm circle.
    pub zero_label: String,
    /// Lines about the test, under the legend.
    pub notes: Vec<String>,
    /// A table under the notes (its first row the heading), and its title.
    pub table_title: String,
    pub table: Vec<Vec<String>>,
}

const HEADER: u32 = 62;
/// The square the polar drawing fills, pixels.
const SQUARE: u32 = 800;
const PANEL: u32 = 460;

/// Draw the figure; the rings are `division` µm apart where that division is the round
/// one that holds the largest deviation within two rings of the base circle.
pub(crate) fn draw(figure: &PolarFigure<'_>) -> Result<String, PlotError> {
    let largest = figure.series.iter().flat_map(|s| &s.points).map(|&(_, d)| d.abs()).fold(0.0, f64::max);
    let division = nice_at_least(largest / 2.0, 0.1);
    let base = 4.0 * division;
    let extent = base + 3.2 * division;
    let (width, height) = (SQUARE + PANEL, HEADER + SQUARE);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        let (header, rest) = root.split_vertically(HEADER);
        let (square, panel) = rest.split_horizontally(SQUARE);
        header_text(&header, figure.title, &[format!("{}, {} µm per ring", figure.what, micrometres(division))])?;
        // A square plotting area and equal ranges: the circle is drawn round.
        let mut chart = ChartBuilder::on(&square)
            .margin(10)
            .build_cartesian_2d(-extent..extent, -extent..extent)
            .map_err(drawing)?;
        let ring = |r: f64| (0..=720).map(move |d| polar(r, (f64::from(d) / 2.0).to_radians()));
        for k in -2..=2 {
            let style = if k == 0 { NOMINAL.stroke_width(2) } else { GREY.mix(0.45).stroke_width(1) };
            chart.draw_series(LineSeries::new(ring(base + f64::from(k) * division), style)).map_err(drawing)?;
        }
        for degrees in (0..360).step_by(30) {
            let a = f64::from(degrees).to_radians();
            let spoke = [polar(base - 2.0 * division, a), polar(base + 2.25 * division, a)];
            chart.draw_series(LineSeries::new(spoke, GREY.mix(0.3).stroke_width(1))).map_err(drawing)?;
            let text = match degrees {
                0 => "0° +Z".to_string(),
                90 => "90° +X".to_string(),
                _ => format!("{degrees}°"),
            };
            let (z, x) = polar(base + 2.75 * division, a);
            let anchor = if a.cos() > 0.3 {
                HPos::Left
            } else if a.cos() < -0.3 {
                HPos::Right
            } else {
                HPos::Center
            };
            chart.draw_series(std::iter::once(Text::new(text, (z, x), label_style(14, anchor)))).map_err(drawing)?;
        }
        for s in &figure.series {
            let mut line: Vec<(f64, f64)> = s.points.iter().map(|&(angle, d)| polar(base + d, angle)).collect();
            line.dedup();
            if line.len() < 2 {
                continue;
            }
            let style = s.colour.stroke_width(2);
            if s.dashed {
                chart.draw_series(DashedLineSeries::new(line, 7, 4, style)).map_err(drawing)?;
            } else {
                chart.draw_series(LineSeries::new(line, style)).map_err(drawing)?;
            }
        }
        // The rings' values beside the +X spoke, on white so that a trace under them does
        // not hide them.
        for k in -2..=2 {
            let value = f64::from(k) * division;
            let text = if k == 0 {
                "0 µm".to_string()
            } else {
                format!("{}{} µm", if value > 0.0 { "+" } else { "" }, micrometres(value))
            };
            let w = text_width(&text, 13);
            let label = EmptyElement::at((0.0, base + value))
                + Rectangle::new([(3, -8), (7 + w, 8)], WHITE.mix(0.85).filled())
                + Text::new(text, (5, 0), label_style(13, HPos::Left));
            chart.draw_series(std::iter::once(label)).map_err(drawing)?;
        }
        directions(&square)?;
        side_panel(&panel, figure)?;
        root.present().map_err(drawing)?;
    }
    Ok(svg)
}

/// Arrows for +Z (right) and +X (up) in the lower left corner.
fn directions(area: &DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), PlotError> {
    let (ox, oy) = (40, i32::try_from(SQUARE).unwrap_or(0) - 40);
    let style = NOMINAL.stroke_width(2);
    for (end, head) in [
        ((ox + 60, oy), [(ox + 52, oy - 5), (ox + 52, oy + 5)]),
        ((ox, oy - 60), [(ox - 5, oy - 52), (ox + 5, oy - 52)]),
    ] {
        area.draw(&PathElement::new(vec![(ox, oy), end], style)).map_err(drawing)?;
        area.draw(&Polygon::new(vec![end, head[0], head[1]], NOMINAL.filled())).map_err(drawing)?;
    }
    area.draw(&Text::new("+Z", (ox + 66, oy), label_style(15, HPos::Left))).map_err(drawing)?;
    area.draw(&Text::new("+X", (ox, oy - 72), label_style(15, HPos::Center))).map_err(drawing)?;
    Ok(())
}

/// The legend, the notes and the table, top to bottom.
fn side_panel(area: &DrawingArea<SVGBackend<'_>, Shift>, figure: &PolarFigure<'_>) -> Result<(), PlotError> {
    let x = 10;
    let mut y = 24;
    area.draw(&Text::new("Legend", (x, y), label_style(16, HPos::Left))).map_err(drawing)?;
    y += 26;
    let zero = Entry { label: figure.zero_label.clone(), colour: NOMINAL, dashed: false, width: 2 };
    let entries = std::iter::once(zero).chain(figure.series.iter().map(|s| Entry {
        label: s.label.clone(),
        colour: s.colour,
        dashed: s.dashed,
        width: 2,
    }));
    for entry in entries {
        sample_line(area, &entry, (x, y))?;
        area.draw(&Text::new(entry.label.clone(), (x + 36, y), label_style(14, HPos::Left))).map_err(drawing)?;
        y += 22;
    }
    y += 14;
    for note in &figure.notes {
        area.draw(&Text::new(note.clone(), (x, y), label_style(14, HPos::Left))).map_err(drawing)?;
        y += 20;
    }
    if figure.table.is_empty() {
        return Ok(());
    }
    y += 14;
    area.draw(&Text::new(figure.table_title.clone(), (x, y), label_style(16, HPos::Left))).map_err(drawing)?;
    y += 24;
    // The first column from the left, the figures right-aligned at these.
    let columns = [x, x + 250, x + 430];
    for row in &figure.table {
        for (k, (cell, &column)) in row.iter().zip(&columns).enumerate() {
            let anchor = if k == 0 { HPos::Left } else { HPos::Right };
            area.draw(&Text::new(cell.clone(), (column, y), label_style(14, anchor))).map_err(drawing)?;
        }
        y += 20;
    }
    Ok(())
}

/// A point at radius `r` and angle `a` (from +Z toward +X) in the plot's (Z, X) axes.
fn polar(r: f64, a: f64) -> (f64, f64) {
    (r * a.cos(), r * a.sin())
}
