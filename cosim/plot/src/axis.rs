//! Axes: the y range of the values, ticks at round steps with their labels, and the mesh's
//! fonts and lines.

use plotters::prelude::*;

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
    /// The axis' range.
    pub range: std::ops::Range<f64>,
    /// Where the ticks go, in the range.
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

/// A chart on `area` with a `margin` and label areas `labels` (x, y) wide when `text` is drawn,
/// else 5 wide (room for the tick marks only), all in pixels × `scale`.
pub fn chart_builder<'a, 'b, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, plotters::coord::Shift>,
    margin: u32,
    labels: (u32, u32),
    text: bool,
    scale: u32,
) -> ChartBuilder<'a, 'b, DB> {
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(margin * scale)
        .x_label_area_size(if text { labels.0 } else { 5 } * scale)
        .y_label_area_size(if text { labels.1 } else { 5 } * scale);
    builder
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
