//! The report as a person sees it: headless Chromium opens the page of the bundled ball bar
//! example (compensated, then reported) from a folder of its own, with the network left
//! out, and must show a page that is not blank, with the plots drawn in their colours and
//! the verdict; its DOM must hold the three figures' SVG (the path, the finished part, the
//! polar plot) and name no address.

use std::path::Path;
use std::process::Command;

use crate::support::{external, repo};

const WIDTH: u32 = 1280;
const HEIGHT: u32 = 4200;

/// Chromium with the flags a sandboxed, offline, throwaway run needs (run as root in CI).
fn chromium(program: &Path, profile: &Path) -> Command {
    let mut command = Command::new(program);
    command.args([
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--hide-scrollbars",
    ]);
    command.arg(format!("--user-data-dir={}", profile.display()));
    command
}

fn turnpass(args: &[&str]) {
    let output = Command::new(env!("CARGO_BIN_EXE_turnpass")).args(args).current_dir(repo()).output().unwrap();
    assert!(output.status.success(), "turnpass {args:?}: {}", String::from_utf8_lossy(&output.stderr));
}

/// How many pixels of `image` (RGBA rows) are within 24 of `colour` in every channel (the
/// palette's colours are further apart; an anti-aliased edge between two of them is not).
fn pixels_near(image: &[u8], colour: [u8; 3]) -> usize {
    image.chunks_exact(4).filter(|p| (0..3).all(|c| p[c].abs_diff(colour[c]) <= 24)).count()
}

#[test]
fn the_report_renders_in_headless_chromium() {
    let Some(program) = external::program("chromium", "chromium") else { return };
    let tmp = tempfile::tempdir().unwrap();
    let (compensated, page, shot) =
        (tmp.path().join("c.nc"), tmp.path().join("report.html"), tmp.path().join("shot.png"));
    let model = "examples/machines/thesis-several-effects.toml";
    let original = "examples/programs/ballbar-r100.nc";
    turnpass(&["compensate", original, "--model", model, "-o", &compensated.to_string_lossy()]);
    turnpass(&["report", original, &compensated.to_string_lossy(), "--model", model, "-o", &page.to_string_lossy()]);
    let url = format!("file://{}", page.display());

    let profile = tempfile::tempdir().unwrap();
    let output = chromium(&program, profile.path()).args(["--dump-dom", &url]).output().unwrap();
    assert!(output.status.success(), "chromium --dump-dom: {}", String::from_utf8_lossy(&output.stderr));
    let dom = String::from_utf8_lossy(&output.stdout);
    for wanted in
        ["id=\"plot-path\"", "id=\"plot-part\"", "id=\"plot-polar\"", "verify: ok", "id=\"diff\"", "id=\"figures\""]
    {
        assert!(dom.contains(wanted), "the page as Chromium reads it has no `{wanted}`");
    }
    assert_eq!(dom.matches("<svg").count(), 3, "three inline plots");
    assert!(!dom.contains("http://") && !dom.contains("https://"), "the page names an address");

    let profile = tempfile::tempdir().unwrap();
    let output = chromium(&program, profile.path())
        .arg(format!("--window-size={WIDTH},{HEIGHT}"))
        .arg(format!("--screenshot={}", shot.display()))
        .arg(&url)
        .output()
        .unwrap();
    assert!(output.status.success(), "chromium --screenshot: {}", String::from_utf8_lossy(&output.stderr));
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&shot).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut image = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut image).unwrap();
    assert_eq!((info.width, info.height), (WIDTH, HEIGHT), "the screenshot's size");
    let image = match info.color_type {
        png::ColorType::Rgba => image,
        png::ColorType::Rgb => image.chunks_exact(3).flat_map(|p| [p[0], p[1], p[2], 255]).collect(),
        other => panic!("a screenshot in {other:?}"),
    };
    let pixels = image.len() / 4;
    let drawn = pixels - pixels_near(&image, [255, 255, 255]);
    assert!(drawn * 50 > pixels, "the page is nearly blank: {drawn} of {pixels} pixels drawn");
    // Each plot in its colours: the path plot and the polar plot both draw vermillion and
    // blue (as programmed, compensated); only the polar plot draws orange and sky blue (the
    // second direction); the verdict box is green.
    for (what, colour) in [
        ("vermillion (as programmed)", [213, 94, 0]),
        ("blue (compensated)", [0, 114, 178]),
        ("orange (counter-clockwise, as programmed: the polar plot)", [230, 159, 0]),
        ("sky blue (counter-clockwise, compensated: the polar plot)", [86, 180, 233]),
        ("the verdict's green", [216, 240, 230]),
    ] {
        let found = pixels_near(&image, colour);
        assert!(found > 300, "{what}: {found} pixels");
    }
    // Both plots, one above the other: the path plot's vermillion above the first row of the
    // polar plot's orange.
    let rows: Vec<&[u8]> = image.chunks_exact(WIDTH as usize * 4).collect();
    let polar_top = rows.iter().position(|row| pixels_near(row, [230, 159, 0]) > 0).unwrap();
    let above: usize = rows[..polar_top].iter().map(|row| pixels_near(row, [213, 94, 0])).sum();
    assert!(above > 300, "the path plot above the polar plot (row {polar_top}): {above} vermillion pixels");
}
