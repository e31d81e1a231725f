//! Line plots of results CSVs against time, PNG or SVG (plotters).
//!
//! Text needs a TrueType font: `CRANE_PLOT_FONT=<file.ttf>`, else the first DejaVu/Liberation
//! sans font (or any `.ttf`) under /usr/share/fonts. Without one, plots are drawn without text.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::prelude::*;
use plotters::style::FontStyle;

/// One curve: a label and (t, value) samples.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

/// Registers a sans-serif font once per process; false if none could be found.
pub fn register_font() -> bool {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    *REGISTERED.get_or_init(|| {
        let Some(bytes) = font_candidates().iter().find_map(|p| std::fs::read(p).ok()) else {
            return false;
        };
        // plotters keeps fonts for the whole run, hence the leak.
        let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
        plotters::style::register_font("sans-serif", FontStyle::Normal, bytes).is_ok()
    })
}

fn font_candidates() -> Vec<PathBuf> {
    let mut candidates: Vec<PathBuf> = std::env::var_os("CRANE_PLOT_FONT").map(PathBuf::from).into_iter().collect();
    for name in ["dejavu/DejaVuSans.ttf", "liberation/LiberationSans-Regular.ttf", "freefont/FreeSans.ttf"] {
        candidates.push(Path::new("/usr/share/fonts/truetype").join(name));
    }
    candidates.extend(find_ttf(Path::new("/usr/share/fonts"), 4));
    candidates
}

fn find_ttf(dir: &Path, depth: usize) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else { return Vec::new() };
    let mut found = Vec::new();
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() && depth > 0 {
            found.extend(find_ttf(&path, depth - 1));
        } else if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("ttf")) {
            found.push(path);
        }
    }
    found.sort();
    found
}

/// A figure: panels stacked top to bottom, sharing the time axis.
pub struct Figure {
    pub title: String,
    pub panels: Vec<Panel>,
    /// The shared x axis' label, with its unit (`"time (s)"` for results against time).
    pub x_label: String,
}

/// One panel: its curves and the label of its y axis (with the unit, e.g. `"θx (deg)"`).
pub struct Panel {
    pub y_label: String,
    pub series: Vec<Series>,
}

/// Width of the plots and the legend column's bounds (pixels); the column is as wide as the
/// longest label needs.
const PLOT_WIDTH: u32 = 860;
const LEGEND_WIDTH: std::ops::RangeInclusive<u32> = 120..=520;
/// Height of one panel (pixels).
const PANEL_HEIGHT: u32 = 330;

/// Draws `figure` into `out`: an SVG for a `.svg` file, a PNG for `.png`. Each panel's legend
/// sits in a column right of its plot, so it never covers a curve.
pub fn draw(out: &Path, figure: &Figure) -> Result<(), String> {
    let extension = out.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    let longest = figure.panels.iter().flat_map(|p| &p.series).map(|s| s.label.chars().count()).max().unwrap_or(0);
    // About 8 pixels a character at 14 px, after the 36 px line sample.
    let legend = (longest as u32 * 8 + 45).clamp(*LEGEND_WIDTH.start(), *LEGEND_WIDTH.end());
    let size = (PLOT_WIDTH + legend, PANEL_HEIGHT * figure.panels.len().max(1) as u32 + 40);
    let drawn = match extension.as_deref() {
        Some("png") => draw_on(BitMapBackend::new(out, size).into_drawing_area(), figure),
        Some("svg") => draw_on(SVGBackend::new(out, size).into_drawing_area(), figure),
        _ => return Err(format!("{}: unknown image format: the file name must end in .png or .svg", out.display())),
    };
    drawn.map_err(|e| format!("{}: {e}", out.display()))
}

type DrawResult = Result<(), Box<dyn std::error::Error>>;

fn draw_on<DB: DrawingBackend>(root: DrawingArea<DB, plotters::coord::Shift>, figure: &Figure) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let text = register_font();
    root.fill(&WHITE)?;
    let root = if text { root.titled(&figure.title, ("sans-serif", 22))? } else { root };
    let panels = root.split_evenly((figure.panels.len().max(1), 1));
    for (panel, area) in figure.panels.iter().zip(&panels) {
        let (plot_area, legend_area) = area.split_horizontally(PLOT_WIDTH);
        draw_panel(&plot_area, panel, &figure.x_label, text)?;
        if text {
            draw_legend(&legend_area, &panel.series)?;
        }
    }
    root.present()?;
    Ok(())
}

/// The (t, y) ranges of a panel's points, y padded by 5 %; an error if there is no time span.
fn ranges(panel: &Panel) -> Result<(std::ops::Range<f64>, std::ops::Range<f64>), String> {
    let (mut t0, mut t1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for &(t, y) in panel.series.iter().flat_map(|s| s.points.iter()) {
        (t0, t1) = (t0.min(t), t1.max(t));
        if y.is_finite() {
            (y0, y1) = (y0.min(y), y1.max(y));
        }
    }
    if !(t1 > t0) || !(y1 >= y0) {
        return Err(format!("{}: nothing to plot (fewer than two samples)", panel.y_label));
    }
    let pad = ((y1 - y0) * 0.05).max(1e-9);
    Ok((t0..t1, (y0 - pad)..(y1 + pad)))
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    panel: &Panel,
    x_label: &str,
    text: bool,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let (t, y) = ranges(panel)?;
    let mut builder = ChartBuilder::on(area);
    builder.margin(10).x_label_area_size(if text { 40 } else { 5 }).y_label_area_size(if text { 80 } else { 5 });
    let mut chart = builder.build_cartesian_2d(t, y)?;
    let mut mesh = chart.configure_mesh();
    if text {
        mesh.x_desc(x_label).y_desc(panel.y_label.as_str());
    } else {
        mesh.disable_x_axis().disable_y_axis();
    }
    mesh.draw()?;
    for (i, s) in panel.series.iter().enumerate() {
        let color = series_color(i);
        chart.draw_series(LineSeries::new(s.points.iter().copied(), color.stroke_width(2)))?;
    }
    Ok(())
}

/// The colour of a panel's `index`-th curve: the same in every panel, so that stacked panels of
/// the same files match.
fn series_color(index: usize) -> RGBAColor {
    Palette99::pick(index).to_rgba()
}

/// A line sample and the label of each series, top down, in the legend column.
fn draw_legend<DB: DrawingBackend>(area: &DrawingArea<DB, plotters::coord::Shift>, series: &[Series]) -> DrawResult
where
    DB::ErrorType: 'static,
{
    for (i, s) in series.iter().enumerate() {
        let color = series_color(i);
        let y = 20 + 22 * i as i32;
        area.draw(&PathElement::new(vec![(5, y), (30, y)], color.stroke_width(2)))?;
        area.draw(&Text::new(s.label.clone(), (36, y - 7), ("sans-serif", 14)))?;
    }
    Ok(())
}
