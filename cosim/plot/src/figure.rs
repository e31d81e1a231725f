//! Figures of stacked panels of line series against a shared x axis, each panel's legend beside
//! or under its plot, drawn as PNG or SVG.

use std::path::Path;

use plotters::prelude::*;

use crate::axis::{chart_builder, style_mesh, tick_label, ticks, y_range, Ticked};
use crate::font::register_font;
use crate::png::{write_png, DrawResult};
use crate::style::{series_color, series_dash};

/// One curve: a label and (t, value) samples.
pub struct Series {
    /// The legend's text.
    pub label: String,
    /// Its (t, value) samples.
    pub points: Vec<(f64, f64)>,
}

/// A figure: panels stacked top to bottom, sharing the time axis.
pub struct Figure {
    /// Drawn above the panels.
    pub title: String,
    /// Top to bottom.
    pub panels: Vec<Panel>,
    /// The shared x axis' label, with its unit (`"time (s)"` for results against time).
    pub x_label: String,
}

/// One panel: its curves and the label of its y axis (with the unit, e.g. `"θx (deg)"`).
pub struct Panel {
    /// The y axis' label, with the unit.
    pub y_label: String,
    /// Its curves, drawn in order.
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
    /// Right of the plots or below them.
    pub placement: LegendPlacement,
    /// Legend columns.
    pub columns: u32,
    /// Legend rows.
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
    let mut chart =
        chart_builder(area, 10, (40, 80), text, scale).build_cartesian_2d(t, Ticked { range: y, ticks: y_ticks })?;
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

    #[test]
    fn pngs_are_the_same_bytes_on_every_run() {
        let dir = tempfile::tempdir().unwrap();
        let figure = figure(2, "curve");
        let (a, b) = (dir.path().join("a.png"), dir.path().join("b.png"));
        draw(&a, &figure).unwrap();
        draw(&b, &figure).unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    }
}
