//! Summary plots of a collected study: each metric against each varied parameter (one point a
//! case) and a histogram of each metric, PNG or SVG (plotters; text in the font of
//! [`cosim_plot::register_font`]).
//!
//! Files: `<metric>-vs-<parameter>.<ext>` and `<metric>-histogram.<ext>`, names with any
//! character other than letters, digits, `.`, `_` and `-` replaced by `_`; a plot with no value
//! to show (no case done) is not drawn.

use std::ops::Range;
use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use super::table::Table;
use crate::StudyError;
use cosim_plot::{chart_builder, register_font, series_color, style_mesh, tick_label, write_png, Ticked};
use crane_metrics::catalogue::MetricId;

/// The image format of the plots.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    Png,
    Svg,
}

impl ImageFormat {
    fn extension(self) -> &'static str {
        match self {
            ImageFormat::Png => "png",
            ImageFormat::Svg => "svg",
        }
    }
}

/// Width and height of every plot (pixels).
const SIZE: (u32, u32) = (800, 560);
/// The histograms' bins: about √n, within these bounds.
const BINS: std::ops::RangeInclusive<usize> = 5..=40;

/// Equal-width bins over the values' range: the first bin's left edge, the width and the count
/// of each bin (a value on an inner edge counts in the bin to its right; the largest value in
/// the last bin).
#[derive(Debug, Clone, PartialEq)]
pub struct Histogram {
    /// The first bin's left edge.
    pub start: f64,
    /// Each bin's width.
    pub width: f64,
    /// Values in each bin.
    pub counts: Vec<usize>,
}

/// The (parameter, metric) points of the cases with both values, in plan order.
pub fn scatter_points(table: &Table, metric: usize, parameter: usize) -> Vec<(f64, f64)> {
    table.rows.iter().filter_map(|row| Some((row.parameters[parameter]?, row.metrics[metric]?))).collect()
}

/// The histogram of the finite `values`; `None` if there is none. Identical values get one bin
/// of width 1 around them.
pub fn histogram(values: &[f64]) -> Option<Histogram> {
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    let (low, high) = finite.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| (l.min(v), h.max(v)));
    if finite.is_empty() {
        return None;
    }
    if high == low {
        return Some(Histogram { start: low - 0.5, width: 1.0, counts: vec![finite.len()] });
    }
    let bins = ((finite.len() as f64).sqrt().ceil() as usize).clamp(*BINS.start(), *BINS.end());
    let width = (high - low) / bins as f64;
    let mut counts = vec![0; bins];
    for v in finite {
        counts[(((v - low) / width) as usize).min(bins - 1)] += 1;
    }
    Some(Histogram { start: low, width, counts })
}

/// One summary plot.
enum Plot<'a> {
    /// A metric (y) against a parameter (x).
    Scatter {
        points: &'a [(f64, f64)],
        parameter: &'a str,
        metric: &'a str,
    },
    Histogram {
        histogram: &'a Histogram,
        metric: &'a str,
    },
}

impl Plot<'_> {
    /// E.g. "rmse against crane.lp0 (64 cases)".
    fn title(&self) -> String {
        match self {
            Plot::Scatter { points, parameter, metric } => {
                format!("{metric} against {parameter} ({} cases)", points.len())
            }
            Plot::Histogram { histogram, metric } => {
                format!("{metric} ({} cases)", histogram.counts.iter().sum::<usize>())
            }
        }
    }
}

/// Draws every plot of `table` into `dir` (created if missing); returns the files written.
pub fn write_plots(dir: &Path, table: &Table, format: ImageFormat) -> Result<Vec<PathBuf>, StudyError> {
    std::fs::create_dir_all(dir).map_err(|source| StudyError::Write { file: dir.to_path_buf(), source })?;
    let mut written = Vec::new();
    for (m, metric) in table.metrics.iter().enumerate() {
        for (p, parameter) in table.parameters.iter().enumerate() {
            let points = scatter_points(table, m, p);
            let file = dir.join(format!("{}-vs-{}.{}", file_name(metric), file_name(parameter), format.extension()));
            if !points.is_empty() {
                draw(&file, format, &Plot::Scatter { points: &points, parameter, metric })?;
                written.push(file);
            }
        }
        let values: Vec<f64> = table.rows.iter().filter_map(|row| row.metrics[m]).collect();
        if let Some(histogram) = histogram(&values) {
            let file = dir.join(format!("{}-histogram.{}", file_name(metric), format.extension()));
            draw(&file, format, &Plot::Histogram { histogram: &histogram, metric })?;
            written.push(file);
        }
    }
    Ok(written)
}

/// A column name made safe as (part of) a file name.
fn file_name(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || "._-".contains(c) { c } else { '_' }).collect()
}

fn draw(file: &Path, format: ImageFormat, plot: &Plot) -> Result<(), StudyError> {
    let drawn = match format {
        ImageFormat::Png => write_png(file, SIZE, |root, scale| paint(root, plot, scale)),
        ImageFormat::Svg => paint(SVGBackend::new(file, SIZE).into_drawing_area(), plot, 1),
    };
    drawn.map_err(|e| StudyError::Write { file: file.to_path_buf(), source: std::io::Error::other(e.to_string()) })
}

type DrawResult = Result<(), Box<dyn std::error::Error>>;

fn paint<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, plot: &Plot, scale: u32) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let text = register_font();
    root.fill(&WHITE)?;
    let root = if text { root.titled(&plot.title(), ("sans-serif", 20 * scale))? } else { root };
    let (x, y, x_label, y_label) = match plot {
        Plot::Scatter { points, parameter, metric } => {
            (padded(points.iter().map(|p| p.0)), padded(points.iter().map(|p| p.1)), *parameter, *metric)
        }
        Plot::Histogram { histogram, metric } => {
            let end = histogram.start + histogram.width * histogram.counts.len() as f64;
            (histogram.start..end, count_range(histogram), *metric, "cases")
        }
    };
    let (y_ticks, decimals) = match plot {
        Plot::Scatter { .. } => cosim_plot::ticks(&y),
        Plot::Histogram { .. } => (count_ticks(&y), 0),
    };
    let mut chart =
        chart_builder(&root, 15, (45, 85), text, scale).build_cartesian_2d(x, Ticked { range: y, ticks: y_ticks })?;
    let y_format = |v: &f64| tick_label(*v, decimals);
    let (x_label, y_label) = (axis_label(x_label), axis_label(y_label));
    let mut mesh = chart.configure_mesh();
    style_mesh(&mut mesh, scale);
    mesh.y_label_formatter(&y_format);
    if text {
        mesh.x_desc(x_label).y_desc(y_label);
    } else {
        mesh.disable_x_axis().disable_y_axis();
    }
    mesh.draw()?;
    let color = series_color(0);
    match plot {
        Plot::Scatter { points, .. } => {
            chart.draw_series(points.iter().map(|&p| Circle::new(p, 3 * scale, color.filled())))?;
        }
        Plot::Histogram { histogram, .. } => {
            let bar = |(k, &count): (usize, &usize)| {
                let left = histogram.start + histogram.width * k as f64;
                Rectangle::new([(left, 0.0), (left + histogram.width, count as f64)], color.filled())
            };
            chart.draw_series(histogram.counts.iter().enumerate().map(bar))?;
        }
    }
    root.present()?;
    Ok(())
}

/// A histogram's count axis: from 0 to a little above the highest count.
fn count_range(histogram: &Histogram) -> Range<f64> {
    let highest = histogram.counts.iter().copied().max().unwrap_or(0) as f64;
    0.0..highest * 1.05 + 0.5
}

/// The ticks of a count axis: whole numbers only, every one up to 10, else round steps of 2 or
/// more.
fn count_ticks(range: &Range<f64>) -> Vec<f64> {
    let (ticks, _) = cosim_plot::ticks(range);
    if ticks.iter().all(|t| t.fract() == 0.0) {
        ticks
    } else {
        (0..=range.end.floor() as u64).map(|count| count as f64).collect()
    }
}

/// An axis' label: a column's name with its unit where the name tells it ("rmse (m)",
/// "rmse.change (%)"); the units of variables' statistics and of parameters are not known here.
pub fn axis_label(name: &str) -> String {
    let unit = if name.ends_with(".change") {
        Some("%")
    } else {
        MetricId::from_name(name.strip_suffix(".baseline").unwrap_or(name)).map(|id| id.info().unit.symbol())
    };
    match unit {
        Some(unit) => format!("{name} ({unit})"),
        None => name.to_string(),
    }
}

/// The range of `values` padded by 5 % each side (by 0.5 if they are all equal), so that no
/// point sits on the frame.
fn padded(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (low, high) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    let pad = if high > low { (high - low) * 0.05 } else { 0.5 };
    (low - pad)..(high + pad)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::execute::Status;
    use crate::sweep::table::Row;

    /// Two parameters with different values in each case, two metrics, the last case pending.
    fn table() -> Table {
        let row = |index: usize, a: f64, b: f64, m: Option<f64>| Row {
            id: format!("{index:04}"),
            index,
            seed: index as u64,
            status: if m.is_some() { Status::Done } else { Status::Pending },
            parameters: if m.is_some() { vec![Some(a), Some(b)] } else { vec![None, None] },
            metrics: vec![m, m.map(|m| -m)],
            wall_time: m.map(|_| 0.1),
        };
        Table {
            parameters: vec!["crane.lp0".into(), "imu/noise scale".into()],
            metrics: vec!["pendulum.theta_x.rms".into(), "rmse".into()],
            rows: vec![row(0, 0.4, 10.0, Some(1.0)), row(1, 0.7, 30.0, Some(2.0)), row(2, 0.0, 0.0, None)],
        }
    }

    #[test]
    fn a_scatter_pairs_each_metric_with_the_named_parameter_of_the_same_case() {
        let table = table();
        assert_eq!(scatter_points(&table, 0, 0), [(0.4, 1.0), (0.7, 2.0)]);
        assert_eq!(scatter_points(&table, 0, 1), [(10.0, 1.0), (30.0, 2.0)]);
        assert_eq!(scatter_points(&table, 1, 1), [(10.0, -1.0), (30.0, -2.0)]);
    }

    #[test]
    fn a_histogram_counts_values_in_equal_bins_with_the_largest_in_the_last() {
        let values: Vec<f64> = (0..10).map(f64::from).chain([f64::NAN]).collect();
        let histogram = histogram(&values).unwrap();
        assert_eq!((histogram.start, histogram.width), (0.0, 9.0 / 5.0));
        assert_eq!(histogram.counts, [2, 2, 2, 2, 2]);
        let single = super::histogram(&[3.0, 3.0]).unwrap();
        assert_eq!((single.start, single.width, single.counts), (2.5, 1.0, vec![2]));
        assert_eq!(super::histogram(&[f64::NAN]), None);
    }

    #[test]
    fn histogram_counts_get_whole_ticks() {
        for counts in [vec![1], vec![2, 3], vec![7, 0, 1], vec![12, 30, 1], vec![400, 3]] {
            let histogram = Histogram { start: 0.0, width: 1.0, counts: counts.clone() };
            let range = count_range(&histogram);
            let ticks = count_ticks(&range);
            let highest = *counts.iter().max().unwrap() as f64;
            assert!(ticks.iter().all(|t| t.fract() == 0.0 && range.contains(t)), "{counts:?}: {ticks:?}");
            assert!(ticks.len() >= 2 && ticks.len() <= 11 && highest <= range.end, "{counts:?}: {ticks:?}");
        }
        let single = Histogram { start: 0.0, width: 1.0, counts: vec![1] };
        assert_eq!(count_ticks(&count_range(&single)), [0.0, 1.0]);
    }

    #[test]
    fn axes_carry_the_units_the_names_tell() {
        assert_eq!(axis_label("rmse"), "rmse (m)");
        assert_eq!(axis_label("rmse.baseline"), "rmse.baseline (m)");
        assert_eq!(axis_label("rmse.change"), "rmse.change (%)");
        assert_eq!(axis_label("pendulum.theta_x.rms.change"), "pendulum.theta_x.rms.change (%)");
        assert_eq!(axis_label("crane.lp0"), "crane.lp0");
    }

    #[test]
    fn every_metric_gets_a_scatter_per_parameter_and_a_histogram() {
        let dir = tempfile::tempdir().unwrap();
        let written = write_plots(dir.path(), &table(), ImageFormat::Svg).unwrap();
        let names: Vec<String> = written.iter().map(|f| f.file_name().unwrap().to_string_lossy().into()).collect();
        let expected = [
            "pendulum.theta_x.rms-vs-crane.lp0.svg",
            "pendulum.theta_x.rms-vs-imu_noise_scale.svg",
            "pendulum.theta_x.rms-histogram.svg",
            "rmse-vs-crane.lp0.svg",
            "rmse-vs-imu_noise_scale.svg",
            "rmse-histogram.svg",
        ];
        assert_eq!(names, expected);
        assert!(written.iter().all(|f| std::fs::metadata(f).is_ok_and(|m| m.len() > 1000)), "{written:?}");
    }
}
