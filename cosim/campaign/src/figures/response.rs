//! One run's response after the release, in the style of the thesis' Figs. 7.2/7.3: four
//! stacked panels over the test — (a) the load's height above the set-point, (b) θx, (c) θy,
//! each with its detected peaks and fitted exponential decay, and (d) the distance travelled
//! with the frame-to-frame speed against the noise threshold.

use std::ops::Range;
use std::path::Path;

use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::{drawn, DrawResult, Root, FONT};
use crane_metrics::decay::DecayFit;
use crane_metrics::run::Evaluation;
use crane_metrics::{Trace, CAPTURE_RATE, DISTANCE_THRESHOLD};

/// Image size (px): four panels of 350 px.
pub const SIZE: (u32, u32) = (1000, 1400);
/// Points of a drawn exponential fit.
const FIT_SAMPLES: usize = 400;
/// Width (px) of the label areas left and right of every panel (kept equal so the time axes
/// line up).
const Y_AREA: u32 = 75;

/// One decay panel: a signal with its peaks and fit.
struct DecayPanel<'a> {
    /// Panel title, e.g. "(b) θx".
    caption: &'a str,
    y_label: &'a str,
    values: &'a [f64],
    /// Factor from the signal's unit (m, rad) to the plotted one (mm, deg).
    scale: f64,
    fit: Option<&'a DecayFit>,
}

/// Draws the response of run `id` into the PNG at `path`, with text only if `text`. Returns
/// false, writing nothing, when the evaluation has fewer than two samples.
pub fn draw(path: &Path, id: &str, evaluation: &Evaluation, text: bool) -> Result<bool, String> {
    let signals = &evaluation.signals;
    if signals.times.len() < 2 {
        return Ok(false);
    }
    let degrees = 180.0 / std::f64::consts::PI;
    let panels = [
        DecayPanel {
            caption: "(a) height above the set-point",
            y_label: "height (mm)",
            values: &signals.height,
            scale: 1e3,
            fit: evaluation.fit_height.as_ref(),
        },
        DecayPanel {
            caption: "(b) θx",
            y_label: "θx (deg)",
            values: &signals.theta_x,
            scale: degrees,
            fit: evaluation.fit_theta_x.as_ref(),
        },
        DecayPanel {
            caption: "(c) θy",
            y_label: "θy (deg)",
            values: &signals.theta_y,
            scale: degrees,
            fit: evaluation.fit_theta_y.as_ref(),
        },
    ];
    let root = BitMapBackend::new(path, SIZE).into_drawing_area();
    let draw = || -> DrawResult {
        root.fill(&WHITE)?;
        let body = if text {
            root.titled(&format!("Run {id}: response after the release"), (FONT, 22))?
        } else {
            root.clone()
        };
        let areas = body.split_evenly((4, 1));
        for (panel, area) in panels.iter().zip(&areas) {
            draw_decay(area, &signals.times, panel, text)?;
        }
        draw_distance(&areas[3], &signals.times, &signals.load, text)?;
        root.present()?;
        Ok(())
    };
    drawn(path, draw())
}

/// The chart frame shared by the panels: caption, label areas and time axis; a secondary axis
/// gets a right label area, the others a margin as wide, so that all time axes line up.
fn panel_builder<'a, 'b>(
    area: &'a Root<'b>,
    caption: &str,
    secondary: bool,
    text: bool,
) -> ChartBuilder<'a, 'b, BitMapBackend<'b>> {
    let mut builder = ChartBuilder::on(area);
    let side = if text { Y_AREA } else { 5 };
    builder.margin(10).x_label_area_size(if text { 35 } else { 5 }).y_label_area_size(side);
    if secondary {
        builder.right_y_label_area_size(side);
    } else {
        builder.margin_right(10 + side);
    }
    if text {
        builder.caption(caption, (FONT, 18));
    }
    builder
}

/// Draws the mesh, with the time and `y_label` axes if `text`.
fn draw_mesh<Y>(
    chart: &mut ChartContext<'_, BitMapBackend<'_>, Cartesian2d<RangedCoordf64, Y>>,
    y_label: &str,
    text: bool,
) -> DrawResult
where
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let mut mesh = chart.configure_mesh();
    if text {
        mesh.x_desc("time since release (s)").y_desc(y_label);
    } else {
        mesh.disable_x_axis().disable_y_axis();
    }
    mesh.draw()?;
    Ok(())
}

/// A decay panel: the signal, its peaks (black before the largest, red from it on, where the
/// fit starts) and the fitted exponential (dashed); the caption gives τ or "no fit".
fn draw_decay(area: &Root, times: &[f64], panel: &DecayPanel, text: bool) -> DrawResult {
    let signal = scaled(times, panel.values, panel.scale);
    let peaks: Vec<(f64, f64)> =
        panel.fit.map_or(Vec::new(), |f| f.peaks.iter().map(|&(t, v)| (t, v * panel.scale)).collect());
    let fit = panel.fit.map_or(Vec::new(), |f| fit_curve(f, time_span(times).end, panel.scale));
    let y = padded(signal.iter().chain(&peaks).chain(&fit).map(|p| p.1));
    let caption = match panel.fit {
        Some(f) => format!("{}: τ = {:.1} s", panel.caption, f.fit.tau),
        None => format!("{}: no fit", panel.caption),
    };
    let mut chart = panel_builder(area, &caption, false, text).build_cartesian_2d(time_span(times), y)?;
    draw_mesh(&mut chart, panel.y_label, text)?;
    for run in finite_runs(&signal) {
        chart.draw_series(LineSeries::new(run, BLUE.stroke_width(1)))?;
    }
    let first = panel.fit.map_or(0, |f| f.first_fitted);
    chart.draw_series(peaks.iter().enumerate().map(|(k, &p)| {
        let color = if k < first { BLACK } else { RED };
        Circle::new(p, 4, color.stroke_width(2))
    }))?;
    chart.draw_series(DashedLineSeries::new(fit, 8, 5, RED.stroke_width(2)))?;
    Ok(())
}

/// The distance panel: cumulative distance (m, solid), the frame-to-frame speed (mm/s, thin,
/// secondary axis) and the threshold speed (dashed).
fn draw_distance(area: &Root, times: &[f64], load: &Trace, text: bool) -> DrawResult {
    let moves = frame_moves(load);
    let cumulative = cumulative_distance(&moves);
    let total = cumulative.last().copied().unwrap_or(0.0);
    let to_speed = CAPTURE_RATE * 1e3;
    let threshold = DISTANCE_THRESHOLD * to_speed;
    let distance: Vec<(f64, f64)> = times.iter().copied().zip(cumulative).collect();
    let speed: Vec<(f64, f64)> = times.iter().skip(1).zip(&moves).map(|(&t, m)| (t, m * to_speed)).collect();
    let top_speed = speed.iter().map(|p| p.1).filter(|v| v.is_finite()).fold(threshold, f64::max);
    let caption =
        format!("(d) distance travelled: {total:.3} m (moves above {:.0} mm per frame)", DISTANCE_THRESHOLD * 1e3);
    let span = time_span(times);
    let chart =
        panel_builder(area, &caption, true, text).build_cartesian_2d(span.clone(), 0.0..total.max(1e-3) * 1.1)?;
    let mut chart = chart.set_secondary_coord(span.clone(), 0.0..top_speed * 1.1);
    draw_mesh(&mut chart, "distance (m)", text)?;
    if text {
        chart.configure_secondary_axes().y_desc("speed (mm/s)").draw()?;
    }
    let speed_color = RGBColor(120, 120, 120);
    for run in finite_runs(&speed) {
        chart.draw_secondary_series(LineSeries::new(run, speed_color.stroke_width(1)))?;
    }
    let line = [(span.start, threshold), (span.end, threshold)];
    chart.draw_secondary_series(DashedLineSeries::new(line, 8, 5, RED.stroke_width(2)))?;
    for run in finite_runs(&distance) {
        chart.draw_series(LineSeries::new(run, BLUE.stroke_width(2)))?;
    }
    if text {
        let entries = [
            ("distance".to_string(), BLUE),
            ("speed".into(), speed_color),
            (format!("threshold {threshold:.0} mm/s"), RED),
        ];
        for (label, color) in entries {
            chart
                .draw_series(LineSeries::new(std::iter::empty::<(f64, f64)>(), color))?
                .label(label)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2)));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()?;
    }
    Ok(())
}

/// Distance (m) between consecutive load positions, one per frame after the first.
fn frame_moves(load: &Trace) -> Vec<f64> {
    let norm = |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|k| (b[k] - a[k]).powi(2)).sum::<f64>().sqrt();
    load.points.windows(2).map(|w| norm(&w[0], &w[1])).collect()
}

/// Distance travelled (m) up to each frame, counting only moves above
/// [`DISTANCE_THRESHOLD`] (as `distance_travelled`); one more entry than `moves`, from 0.
fn cumulative_distance(moves: &[f64]) -> Vec<f64> {
    let counted = moves.iter().map(|&m| if m > DISTANCE_THRESHOLD { m } else { 0.0 });
    std::iter::once(0.0)
        .chain(counted.scan(0.0, |sum, m| {
            *sum += m;
            Some(*sum)
        }))
        .collect()
}

/// The fitted exponential y = ±A·e^(−(t − t_first)/τ), scaled by `scale`, from the first fitted
/// peak to `end` (s), on the side (sign) of the peaks.
fn fit_curve(decay: &DecayFit, end: f64, scale: f64) -> Vec<(f64, f64)> {
    let Some(&(t_first, value)) = decay.peaks.get(decay.first_fitted) else { return Vec::new() };
    let sign = if value < 0.0 { -1.0 } else { 1.0 };
    let step = (end - t_first).max(0.0) / FIT_SAMPLES as f64;
    (0..=FIT_SAMPLES).map(|k| k as f64 * step).map(|dt| (t_first + dt, sign * scale * decay.fit.at(dt))).collect()
}

/// (t, value × scale) pairs.
fn scaled(times: &[f64], values: &[f64], scale: f64) -> Vec<(f64, f64)> {
    times.iter().zip(values).map(|(&t, &v)| (t, v * scale)).collect()
}

/// The stretches of consecutive finite points: a non-finite value leaves a gap.
fn finite_runs(points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    points
        .split(|p| !(p.0.is_finite() && p.1.is_finite()))
        .filter(|run| !run.is_empty())
        .map(<[(f64, f64)]>::to_vec)
        .collect()
}

/// From the first to the last time (s).
fn time_span(times: &[f64]) -> Range<f64> {
    let first = times.first().copied().unwrap_or(0.0);
    let last = times.last().copied().unwrap_or(1.0);
    if last > first {
        first..last
    } else {
        first..first + 1.0
    }
}

/// The range of the finite `values` with 5 % margins (−1..1 without any).
fn padded(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (lo, hi) =
        values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !(hi >= lo) {
        return -1.0..1.0;
    }
    let pad = if hi > lo { 0.05 * (hi - lo) } else { 0.1 * lo.abs().max(1.0) };
    lo - pad..hi + pad
}

#[cfg(test)]
mod tests {
    use super::*;
    use crane_metrics::distance_travelled;

    #[test]
    fn the_cumulative_distance_ends_at_the_distance_travelled() {
        // Moves of 1, 4, 2, 5 mm: only the 4 and 5 mm ones exceed the 3 mm threshold.
        let xs = [0.0, 0.001, 0.005, 0.007, 0.012];
        let load = Trace {
            times: (0..5).map(|k| k as f64 / CAPTURE_RATE).collect(),
            points: xs.map(|x| [x, 0.0, 0.0]).to_vec(),
        };
        let cumulative = cumulative_distance(&frame_moves(&load));
        assert_eq!(cumulative.len(), 5);
        assert!((cumulative[4] - 0.009).abs() < 1e-12, "{cumulative:?}");
        assert!((cumulative[4] - distance_travelled(&load, DISTANCE_THRESHOLD)).abs() < 1e-15);
        assert_eq!(cumulative[1], 0.0);
    }

    #[test]
    fn non_finite_values_split_a_line() {
        let points = [(0.0, 1.0), (1.0, f64::NAN), (2.0, 2.0), (3.0, 3.0), (4.0, f64::INFINITY)];
        assert_eq!(finite_runs(&points), vec![vec![(0.0, 1.0)], vec![(2.0, 2.0), (3.0, 3.0)]]);
        assert_eq!(padded([f64::NAN].into_iter()), -1.0..1.0);
    }
}
