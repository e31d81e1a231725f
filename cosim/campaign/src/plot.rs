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
/// The widest legend right of the plots (pixels, all its columns); a wider one goes below them.
const LEGEND_RIGHT_MAX: u32 = 560;
/// Height of one panel's plot (pixels).
const PANEL_HEIGHT: u32 = 330;
/// The legend's first line (pixels from the top of its area) and its line height.
const LEGEND_TOP: u32 = 20;
const LEGEND_LINE: u32 = 22;
/// Height of the figure's title (pixels).
const TITLE_HEIGHT: u32 = 40;
/// PNGs are drawn at this multiple of their size and averaged down, which antialiases the lines
/// (plotters' bitmap backend draws them aliased).
pub const SUPERSAMPLE: u32 = 2;

/// Where a figure's legends sit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LegendPlacement {
    /// In columns right of each panel's plot.
    Right,
    /// In rows under each panel's plot, across its width.
    Below,
}

/// The legend's columns and rows (the same in every panel, sized for the panel with the most
/// curves) and the figure's size that follows from them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    pub placement: LegendPlacement,
    pub columns: u32,
    pub rows: u32,
    /// Width of one legend column (pixels).
    pub column_width: u32,
    /// Height of one panel, its legend below included (pixels).
    pub panel_height: u32,
    /// The whole image (pixels).
    pub size: (u32, u32),
}

impl Layout {
    /// Entries fill the rows of the legend column right of the plot; when they do not fit, the
    /// legend takes more columns, and when those would be wider than `LEGEND_RIGHT_MAX` it moves
    /// below the plot, with as many columns as fit across it.
    pub fn of(figure: &Figure) -> Layout {
        let longest = figure.panels.iter().flat_map(|p| &p.series).map(|s| s.label.chars().count()).max().unwrap_or(0);
        let entries = figure.panels.iter().map(|p| p.series.len()).max().unwrap_or(0) as u32;
        Layout::for_legend(entries, longest as u32, figure.panels.len().max(1) as u32)
    }

    fn for_legend(entries: u32, longest: u32, panels: u32) -> Layout {
        // About 8 pixels a character at 14 px, after the 36 px line sample.
        let column_width = (longest * 8 + 45).clamp(*LEGEND_WIDTH.start(), *LEGEND_WIDTH.end());
        let fit = (PANEL_HEIGHT - LEGEND_TOP) / LEGEND_LINE;
        let columns = entries.div_ceil(fit).max(1);
        let (placement, columns, panel_height, width) = if columns * column_width <= LEGEND_RIGHT_MAX {
            (LegendPlacement::Right, columns, PANEL_HEIGHT, PLOT_WIDTH + columns * column_width)
        } else {
            let across = (PLOT_WIDTH / column_width).max(1);
            let rows = entries.div_ceil(across);
            (LegendPlacement::Below, across, PANEL_HEIGHT + rows * LEGEND_LINE + LEGEND_TOP / 2, PLOT_WIDTH)
        };
        let rows = entries.div_ceil(columns);
        Layout {
            placement,
            columns,
            rows,
            column_width,
            panel_height,
            size: (width, panel_height * panels + TITLE_HEIGHT),
        }
    }

    /// The top left corner of the `index`-th entry's line sample within the legend's area (column
    /// by column right of the plot, row by row below it).
    fn entry(&self, index: u32) -> (u32, u32) {
        let (column, row) = match self.placement {
            LegendPlacement::Right => (index / self.rows, index % self.rows),
            LegendPlacement::Below => (index % self.columns, index / self.columns),
        };
        let top = if self.placement == LegendPlacement::Right { LEGEND_TOP } else { LEGEND_TOP / 2 };
        (column * self.column_width + 5, top + row * LEGEND_LINE)
    }
}

/// Draws `figure` into `out`: an SVG for a `.svg` file, a PNG for `.png`. Each panel's legend
/// sits beside or under its plot (see [`Layout::of`]), so it never covers a curve.
pub fn draw(out: &Path, figure: &Figure) -> Result<(), String> {
    let extension = out.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    let layout = Layout::of(figure);
    let drawn = match extension.as_deref() {
        Some("png") => write_png(out, layout.size, |root, scale| draw_on(root, figure, &layout, scale)),
        Some("svg") => draw_on(SVGBackend::new(out, layout.size).into_drawing_area(), figure, &layout, 1),
        _ => return Err(format!("{}: unknown image format: the file name must end in .png or .svg", out.display())),
    };
    drawn.map_err(|e| format!("{}: {e}", out.display()))
}

pub type DrawResult = Result<(), Box<dyn std::error::Error>>;

/// Writes a PNG of `size` that `paint` draws at [`SUPERSAMPLE`] times the size (it gets the
/// factor to scale its pixel sizes by), each pixel the mean of its block: antialiased, and the
/// same bytes for the same drawing.
pub fn write_png(
    out: &Path,
    size: (u32, u32),
    paint: impl FnOnce(DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>, u32) -> DrawResult,
) -> DrawResult {
    let scale = SUPERSAMPLE;
    let (width, height) = (size.0 * scale, size.1 * scale);
    let mut large = vec![0u8; width as usize * height as usize * 3];
    paint(BitMapBackend::with_buffer(&mut large, (width, height)).into_drawing_area(), scale)?;
    let small = downsample(&large, (width, height), scale);
    let mut png = BitMapBackend::new(out, size);
    png.blit_bitmap((0, 0), size, &small).map_err(|e| e.to_string())?;
    png.present().map_err(|e| e.to_string())?;
    Ok(())
}

/// An RGB image of `size` reduced by `factor` in each direction, each pixel the rounded mean of
/// its `factor` × `factor` block.
fn downsample(rgb: &[u8], (width, height): (u32, u32), factor: u32) -> Vec<u8> {
    let (w, f) = (width as usize, factor as usize);
    let (small_w, small_h) = (w / f, height as usize / f);
    let mut small = vec![0u8; small_w * small_h * 3];
    let n = (f * f) as u32;
    for y in 0..small_h {
        for x in 0..small_w {
            for c in 0..3 {
                let mut sum = 0u32;
                for dy in 0..f {
                    let row = (y * f + dy) * w;
                    for dx in 0..f {
                        sum += u32::from(rgb[(row + x * f + dx) * 3 + c]);
                    }
                }
                small[(y * small_w + x) * 3 + c] = ((sum + n / 2) / n) as u8;
            }
        }
    }
    small
}

fn draw_on<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    figure: &Figure,
    layout: &Layout,
    scale: u32,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let text = register_font();
    root.fill(&WHITE)?;
    let root = if text { root.titled(&figure.title, ("sans-serif", 22 * scale))? } else { root };
    let panels = root.split_evenly((figure.panels.len().max(1), 1));
    for (panel, area) in figure.panels.iter().zip(&panels) {
        let (plot_area, legend_area) = match layout.placement {
            LegendPlacement::Right => area.split_horizontally(PLOT_WIDTH * scale),
            LegendPlacement::Below => area.split_vertically(PANEL_HEIGHT * scale),
        };
        draw_panel(&plot_area, panel, &figure.x_label, text, scale)?;
        if text {
            draw_legend(&legend_area, &panel.series, layout, scale)?;
        }
    }
    root.present()?;
    Ok(())
}

/// The (t, y) ranges of a panel's points, y padded by 5 % (see [`y_range`]); an error if there
/// is no time span.
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
    Ok((t0..t1, y_range(y0, y1)))
}

/// Relative span below which values count as constant (round-off of one value).
const CONSTANT: f64 = 1e-12;

/// The y axis' range for values from `low` to `high`: padded by 5 %; a constant (or nearly
/// constant) signal gets ±10 % of its value (±1 around 0), so that its ticks differ.
pub fn y_range(low: f64, high: f64) -> std::ops::Range<f64> {
    if high - low <= CONSTANT * low.abs().max(high.abs()) {
        let middle = low + (high - low) / 2.0;
        let half = if middle == 0.0 { 1.0 } else { middle.abs() * 0.1 };
        return (middle - half)..(middle + half);
    }
    let pad = (high - low) * 0.05;
    (low - pad)..(high + pad)
}

/// At most this many intervals between ticks.
const MAX_TICK_INTERVALS: f64 = 10.0;

/// The ticks of an axis over `range`: multiples of a step of 1, 2 or 5 × 10ᵏ, at most
/// `MAX_TICK_INTERVALS` apart, and the decimals that step needs.
pub fn ticks(range: &std::ops::Range<f64>) -> (Vec<f64>, usize) {
    let span = range.end - range.start;
    if !(span > 0.0 && span.is_finite()) {
        return (vec![range.start], 0);
    }
    let magnitude = 10f64.powf((span / MAX_TICK_INTERVALS).log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * magnitude)
        .find(|step| span / step <= MAX_TICK_INTERVALS * (1.0 + 1e-9))
        .unwrap_or(10.0 * magnitude);
    let decimals = (-(step.log10() + 1e-9).floor()).max(0.0) as usize;
    let (first, last) = ((range.start / step - 1e-9).ceil() as i64, (range.end / step + 1e-9).floor() as i64);
    // k × step, rounded to the step's decimals: no round-off in the ticks' values.
    let round = |v: f64| format!("{v:.decimals$}").parse::<f64>().unwrap_or(v);
    ((first..=last).map(|k| round(k as f64 * step)).collect(), decimals)
}

/// An f64 axis with the given ticks (plotters' own pick steps such as 0.25 and label them with
/// at most five decimals), labelled by the mesh's formatter, e.g. [`tick_label`].
pub struct Ticked {
    pub range: std::ops::Range<f64>,
    pub ticks: Vec<f64>,
}

impl plotters::coord::ranged1d::Ranged for Ticked {
    type FormatOption = plotters::coord::ranged1d::DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let (start, end) = (self.range.start, self.range.end);
        let fraction = (value - start) / (end - start);
        limit.0 + (f64::from(limit.1 - limit.0) * fraction).round() as i32
    }

    fn key_points<Hint: plotters::coord::ranged1d::KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            Vec::new()
        } else {
            self.ticks.clone()
        }
    }

    fn range(&self) -> std::ops::Range<f64> {
        self.range.clone()
    }
}

/// A tick's label with `decimals` decimals ("0", not "-0").
pub fn tick_label(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$}");
    if text.starts_with('-') && text[1..].chars().all(|c| c == '0' || c == '.') {
        text[1..].to_string()
    } else {
        text
    }
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    panel: &Panel,
    x_label: &str,
    text: bool,
    scale: u32,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let (t, y) = ranges(panel)?;
    let (y_ticks, decimals) = ticks(&y);
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(10 * scale)
        .x_label_area_size(if text { 40 } else { 5 } * scale)
        .y_label_area_size(if text { 80 } else { 5 } * scale);
    let mut chart = builder.build_cartesian_2d(t, Ticked { range: y, ticks: y_ticks })?;
    let y_format = |v: &f64| tick_label(*v, decimals);
    let mut mesh = chart.configure_mesh();
    style_mesh(&mut mesh, scale);
    if text {
        mesh.x_desc(x_label).y_desc(panel.y_label.as_str()).y_label_formatter(&y_format);
    } else {
        mesh.disable_x_axis().disable_y_axis();
    }
    mesh.draw()?;
    for (i, s) in panel.series.iter().enumerate() {
        let style = series_color(i).stroke_width(2 * scale);
        let points = s.points.iter().copied();
        match series_dash(i) {
            None => chart.draw_series(LineSeries::new(points, style))?,
            Some((dash, gap)) => chart.draw_series(DashedLineSeries::new(points, dash * scale, gap * scale, style))?,
        };
    }
    Ok(())
}

/// Fonts, lines and tick marks of a mesh, in pixels × `scale`.
pub fn style_mesh<DB: DrawingBackend, X: plotters::coord::ranged1d::Ranged, Y: plotters::coord::ranged1d::Ranged>(
    mesh: &mut plotters::chart::MeshStyle<'_, '_, X, Y, DB>,
    scale: u32,
) {
    let s = scale;
    mesh.label_style(("sans-serif", 12 * s))
        .axis_desc_style(("sans-serif", 12 * s))
        .axis_style(BLACK.stroke_width(s))
        .bold_line_style(BLACK.mix(0.2).stroke_width(s))
        .light_line_style(BLACK.mix(0.08).stroke_width(s))
        .set_all_tick_mark_size(5 * s);
}

/// The Okabe–Ito colours (Okabe and Ito, "Color Universal Design", 2008), distinct for the
/// colour-blind, without their yellow, which is unreadable on white.
const PALETTE: [RGBColor; 7] = [
    RGBColor(0x00, 0x72, 0xB2), // blue
    RGBColor(0xD5, 0x5E, 0x00), // vermillion
    RGBColor(0x00, 0x9E, 0x73), // bluish green
    RGBColor(0xCC, 0x79, 0xA7), // reddish purple
    RGBColor(0xE6, 0x9F, 0x00), // orange
    RGBColor(0x56, 0xB4, 0xE9), // sky blue
    RGBColor(0x00, 0x00, 0x00), // black
];

/// The colour of a panel's `index`-th curve: the same in every panel, so that stacked panels of
/// the same files match. After the palette's seven colours they repeat, dashed, dotted, then
/// long-dashed.
pub fn series_color(index: usize) -> RGBColor {
    PALETTE[index % PALETTE.len()]
}

/// The dash and gap lengths (pixels) of the `index`-th curve; `None` for a solid line.
pub fn series_dash(index: usize) -> Option<(u32, u32)> {
    match (index / PALETTE.len()) % 4 {
        0 => None,
        1 => Some((10, 6)),
        2 => Some((2, 4)),
        _ => Some((20, 5)),
    }
}

/// A line sample and the label of each series, in the legend's columns.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    series: &[Series],
    layout: &Layout,
    scale: u32,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let s = scale as i32;
    for (i, entry) in series.iter().enumerate() {
        let style = series_color(i).stroke_width(2 * scale);
        let (x, y) = layout.entry(i as u32);
        let (x, y) = (x as i32 * s, y as i32 * s);
        let pieces: Vec<(i32, i32)> = match series_dash(i) {
            None => vec![(0, 25)],
            Some((dash, gap)) => {
                let (dash, period) = (dash as i32, (dash + gap) as i32);
                (0..25).step_by(period as usize).map(|a| (a, (a + dash).min(25))).collect()
            }
        };
        for (a, b) in pieces {
            area.draw(&PathElement::new(vec![(x + a * s, y), (x + b * s, y)], style))?;
        }
        area.draw(&Text::new(entry.label.clone(), (x + 31 * s, y - 7 * s), ("sans-serif", 14 * scale)))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn figure(entries: usize, label: &str) -> Figure {
        let series = (0..entries)
            .map(|i| Series { label: format!("{label}{i:02}"), points: vec![(0.0, i as f64), (1.0, 1.0)] })
            .collect();
        Figure { title: "t".into(), panels: vec![Panel { y_label: "y".into(), series }], x_label: "time (s)".into() }
    }

    #[test]
    fn a_constant_signal_gets_distinct_tick_labels_around_its_value() {
        for value in [0.5, 0.5 + 1e-15, -3.0, 0.0, 1234.5] {
            let range = y_range(value, if value == 0.5 { 0.5 + 1e-15 } else { value });
            assert!(range.start < value && value < range.end, "{value}: {range:?}");
            let (ticks, decimals) = ticks(&range);
            let labels: Vec<String> = ticks.iter().map(|&t| tick_label(t, decimals)).collect();
            let mut distinct = labels.clone();
            distinct.dedup();
            assert!(labels.len() >= 3 && distinct.len() == labels.len(), "{value}: {labels:?}");
        }
        let (ticks, decimals) = ticks(&y_range(0.5, 0.5));
        assert_eq!((ticks.first(), ticks.last(), decimals), (Some(&0.45), Some(&0.55), 2));
        // A signal that varies keeps its span, padded by 5 %.
        assert_eq!(y_range(0.0, 10.0), -0.5..10.5);
    }

    #[test]
    fn ticks_are_round_multiples_of_a_step_with_its_decimals() {
        assert_eq!(ticks(&(-0.5..10.5)), (vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0], 0));
        assert_eq!(ticks(&(0.0..1.0)), ((0..=10).map(|k| k as f64 / 10.0).collect(), 1));
        let (tiny, decimals) = ticks(&(1.0..1.0 + 4e-9));
        assert_eq!((tiny.len(), decimals), (9, 10));
        assert_eq!(tick_label(-0.0001, 2), "0.00");
        assert_eq!(tick_label(-1.5, 1), "-1.5");
    }

    #[test]
    fn the_legend_takes_more_columns_then_moves_below_when_its_entries_do_not_fit() {
        let few = Layout::of(&figure(3, "pendulum.theta_"));
        assert_eq!((few.placement, few.columns, few.rows), (LegendPlacement::Right, 1, 3));
        // The 23 columns of a closed loop's results: two columns beside the plot.
        let many = Layout::of(&figure(23, "controller.est.ship.pit"));
        assert_eq!((many.placement, many.columns, many.rows), (LegendPlacement::Right, 2, 12));
        assert!(LEGEND_TOP + many.rows * LEGEND_LINE <= many.panel_height);
        assert_eq!(many.size.0, PLOT_WIDTH + 2 * many.column_width);
        // Too many for the side: under the plot, the panel taller by the legend's rows.
        let most = Layout::of(&figure(60, "controller.est.ship.pit"));
        assert_eq!(most.placement, LegendPlacement::Below);
        assert!(most.columns * most.column_width <= PLOT_WIDTH);
        assert_eq!(most.rows, 60u32.div_ceil(most.columns));
        assert!(most.panel_height >= PANEL_HEIGHT + most.rows * LEGEND_LINE);
        assert_eq!(most.size, (PLOT_WIDTH, most.panel_height + TITLE_HEIGHT));
        // Every entry within the legend's area.
        for layout in [few, many, most] {
            let (width, height) = match layout.placement {
                LegendPlacement::Right => (layout.size.0 - PLOT_WIDTH, layout.panel_height),
                LegendPlacement::Below => (PLOT_WIDTH, layout.panel_height - PANEL_HEIGHT),
            };
            let last = layout.entry(layout.columns * layout.rows - 1);
            assert!(last.0 + layout.column_width <= width + 5 && last.1 < height, "{layout:?}: {last:?}");
        }
    }

    /// WCAG's contrast ratio of a colour against white.
    fn contrast_on_white(color: RGBColor) -> f64 {
        let linear = |c: u8| {
            let c = f64::from(c) / 255.0;
            if c <= 0.03928 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        let luminance = 0.2126 * linear(color.0) + 0.7152 * linear(color.1) + 0.0722 * linear(color.2);
        1.05 / (luminance + 0.05)
    }

    #[test]
    fn every_curve_colour_reads_on_white_and_repeats_only_with_another_dash() {
        for i in 0..PALETTE.len() {
            assert!(contrast_on_white(series_color(i)) >= 2.0, "colour {i}: {:?}", series_color(i));
        }
        let styles: Vec<(RGBColor, Option<(u32, u32)>)> = (0..28).map(|i| (series_color(i), series_dash(i))).collect();
        for (i, a) in styles.iter().enumerate() {
            assert!(styles[..i].iter().all(|b| b != a), "curve {i} looks like an earlier one");
        }
    }

    #[test]
    fn pngs_are_antialiased_and_the_same_bytes_on_every_run() {
        let dir = tempfile::tempdir().unwrap();
        let figure = figure(2, "curve");
        let (a, b) = (dir.path().join("a.png"), dir.path().join("b.png"));
        draw(&a, &figure).unwrap();
        draw(&b, &figure).unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
        // A 2 × 2 block of one black and three white pixels averages to a grey.
        let block = [0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255];
        assert_eq!(downsample(&block, (2, 2), 2), [191, 191, 191]);
    }
}
