//! Grouped bar charts (PNG): one group per test case, one bar per series in each group, like
//! the thesis' Figs. 7.16–7.20, 7.22, 7.23 and 7.25.

use std::ops::Range;
use std::path::Path;

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{drawn, DrawResult, Root, FONT};

/// Series colours, in order (Tableau 10); series beyond the palette reuse it.
const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
];
/// Image height (px), and widths for few and for many groups.
const HEIGHT: u32 = 600;
const NARROW: u32 = 1000;
const WIDE: u32 = 1600;
/// More groups than this get the wide image.
const MANY_GROUPS: usize = 12;
/// Share of a group's width its bars take; the rest separates the groups.
const GROUP_FILL: f64 = 0.8;
/// Height (px) of the strip above the plot holding the title and the legend.
const HEADER: u32 = 70;
/// Width (px) of the y-axis label area.
const Y_AREA: u32 = 80;
/// Margin (px) around the plot.
const MARGIN: u32 = 15;
/// Font size (px) of the group labels and the legend.
const LABEL_SIZE: f64 = 14.0;

/// One bar series: its legend label and one value per group (`None`: no bar).
pub type BarSeries = (String, Vec<Option<f64>>);

/// Pixel size (width, height) of a bar chart over `groups` groups.
pub fn chart_size(groups: usize) -> (u32, u32) {
    (if groups > MANY_GROUPS { WIDE } else { NARROW }, HEIGHT)
}

/// Draws a grouped bar chart into the PNG at `path`: one group per entry of `groups` (labels on
/// the x axis, rotated when crowded), one bar per series in each group, in the unit named by
/// `y_label`. Missing values, and with `log_y` (a logarithmic y axis) non-positive ones, leave
/// their bar out. Returns false, writing nothing, when not a single bar can be drawn.
pub fn bar_chart(
    path: &Path,
    title: &str,
    y_label: &str,
    groups: &[String],
    series: &[BarSeries],
    log_y: bool,
) -> Result<bool, String> {
    Bars { title, y_label, groups, series, log_y }.draw(path, cosim_plot::register_font())
}

/// The content of a bar chart (see [`bar_chart`]).
pub(super) struct Bars<'a> {
    /// Drawn above the chart.
    pub title: &'a str,
    /// The y axis' label, with the unit.
    pub y_label: &'a str,
    /// The x axis' group labels, one group of bars each.
    pub groups: &'a [String],
    /// One bar per group each.
    pub series: &'a [BarSeries],
    /// A logarithmic y axis.
    pub log_y: bool,
}

impl Bars<'_> {
    /// Draws into `path`, with titles, labels and legend only if `text` (a font is registered).
    pub fn draw(&self, path: &Path, text: bool) -> Result<bool, String> {
        let Some(range) = self.y_range() else { return Ok(false) };
        let root = BitMapBackend::new(path, chart_size(self.groups.len())).into_drawing_area();
        let draw = || -> DrawResult {
            root.fill(&WHITE)?;
            if self.log_y {
                let base = range.start;
                self.draw_plot(&root, range.clone().log_scale(), base, text)?;
            } else {
                self.draw_plot(&root, range.clone(), 0.0, text)?;
            }
            root.present()?;
            Ok(())
        };
        drawn(path, draw())
    }

    /// Whether a value gets a bar.
    fn drawable(&self, value: f64) -> bool {
        value.is_finite() && (!self.log_y || value > 0.0)
    }

    fn values(&self) -> impl Iterator<Item = f64> + '_ {
        self.series.iter().flat_map(|(_, values)| values.iter().flatten().copied()).filter(|&v| self.drawable(v))
    }

    /// The y axis: from 0 (or whole decades on a log axis) to past the largest value; `None`
    /// without a group or a drawable value.
    fn y_range(&self) -> Option<Range<f64>> {
        if self.groups.is_empty() {
            return None;
        }
        let (lo, hi) = self
            .values()
            .fold(None, |acc: Option<(f64, f64)>, v| Some(acc.map_or((v, v), |(lo, hi)| (lo.min(v), hi.max(v)))))?;
        if self.log_y {
            let (lo, hi) = (10f64.powf(lo.log10().floor()), 10f64.powf(hi.log10().ceil()));
            return Some(lo..if hi > lo { hi } else { lo * 10.0 });
        }
        let (lo, hi) = (lo.min(0.0), hi.max(0.0));
        let pad = if hi > lo { 0.05 * (hi - lo) } else { 1.0 };
        Some(if lo < 0.0 { lo - pad } else { lo }..hi + pad)
    }

    /// The plot below the header: axes, bars from `base` (0, or the bottom of a log axis) to
    /// each value, group labels, and the header (title and legend).
    fn draw_plot<Y>(&self, root: &Root, y: Y, base: f64, text: bool) -> DrawResult
    where
        Y: AsRangedCoord<Value = f64>,
        Y::CoordDescType: ValueFormatter<f64>,
    {
        let n = self.groups.len();
        let rotate = text && self.crowded(root)?;
        let mut builder = ChartBuilder::on(root);
        builder.margin(MARGIN).margin_top(if text { HEADER } else { MARGIN });
        builder.x_label_area_size(if text { self.x_area(root, rotate)? } else { 5 });
        builder.y_label_area_size(if text { Y_AREA } else { 5 });
        let mut chart = builder.build_cartesian_2d(-0.5..n as f64 - 0.5, y)?;
        let mut mesh = chart.configure_mesh();
        mesh.disable_x_mesh().x_labels(0);
        if text {
            mesh.y_desc(self.y_label);
        } else {
            mesh.disable_x_axis().disable_y_axis();
        }
        mesh.draw()?;
        let width = GROUP_FILL / self.series.len().max(1) as f64;
        for (j, (_, values)) in self.series.iter().enumerate() {
            let color = PALETTE[j % PALETTE.len()];
            let left = |i: usize| i as f64 - GROUP_FILL / 2.0 + j as f64 * width;
            let bars = values.iter().enumerate().filter_map(|(i, v)| v.filter(|&v| self.drawable(v)).map(|v| (i, v)));
            chart.draw_series(bars.map(|(i, v)| {
                Rectangle::new([(left(i) + 0.05 * width, base), (left(i) + 0.95 * width, v)], color.filled())
            }))?;
        }
        if text {
            let bottom = chart.y_range().start;
            let anchors: Vec<(i32, i32)> = (0..n).map(|i| chart.backend_coord(&(i as f64, bottom))).collect();
            self.draw_group_labels(root, &anchors, rotate)?;
            self.draw_header(root)?;
        }
        Ok(())
    }

    fn label_style(rotate: bool) -> TextStyle<'static> {
        let style = TextStyle::from((FONT, LABEL_SIZE).into_font());
        if rotate {
            style.transform(FontTransform::Rotate270).pos(Pos::new(HPos::Right, VPos::Center))
        } else {
            style.pos(Pos::new(HPos::Center, VPos::Top))
        }
    }

    /// Pixel width of the widest group label.
    fn widest_label(&self, root: &Root) -> Result<u32, Box<dyn std::error::Error>> {
        let style = Self::label_style(false);
        let mut widest = 0;
        for g in self.groups {
            widest = widest.max(root.estimate_text_size(g, &style)?.0);
        }
        Ok(widest)
    }

    /// Whether the group labels are too wide to stand side by side.
    fn crowded(&self, root: &Root) -> Result<bool, Box<dyn std::error::Error>> {
        let plot_width = root.dim_in_pixel().0.saturating_sub(Y_AREA + 2 * MARGIN);
        let per_group = plot_width / self.groups.len().max(1) as u32;
        Ok(self.widest_label(root)? + 4 > per_group)
    }

    /// Height (px) of the x label area.
    fn x_area(&self, root: &Root, rotate: bool) -> Result<u32, Box<dyn std::error::Error>> {
        Ok(if rotate { self.widest_label(root)? + 15 } else { LABEL_SIZE as u32 + 15 })
    }

    /// Group labels hanging below the x axis at the group centres `anchors` (px).
    fn draw_group_labels(&self, root: &Root, anchors: &[(i32, i32)], rotate: bool) -> DrawResult {
        let style = Self::label_style(rotate);
        for (label, &(x, y)) in self.groups.iter().zip(anchors) {
            root.draw(&Text::new(label.as_str(), (x, y + 6), style.clone()))?;
        }
        Ok(())
    }

    /// The title, centred at the top, and one legend entry per series below it.
    fn draw_header(&self, root: &Root) -> DrawResult {
        let width = root.dim_in_pixel().0 as i32;
        let title = (FONT, 20).into_text_style(root).pos(Pos::new(HPos::Center, VPos::Top));
        root.draw(&Text::new(self.title, (width / 2, 10), title))?;
        let style = (FONT, LABEL_SIZE).into_text_style(root).pos(Pos::new(HPos::Left, VPos::Center));
        let mut x = (Y_AREA + MARGIN) as i32;
        let y = 48;
        for (j, (label, _)) in self.series.iter().enumerate() {
            let color = PALETTE[j % PALETTE.len()];
            root.draw(&Rectangle::new([(x, y - 7), (x + 14, y + 7)], color.filled()))?;
            root.draw(&Text::new(label.as_str(), (x + 20, y), style.clone()))?;
            x += 20 + root.estimate_text_size(label, &style)?.0 as i32 + 30;
        }
        Ok(())
    }
}
