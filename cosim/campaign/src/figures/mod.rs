//! The campaign's figures (PNG, plotters' bitmap backend): pendulum responses in the style of
//! Figs. 7.2/7.3 for the detailed runs, and bar charts like Figs. 7.16–7.20, 7.22, 7.23 and
//! 7.25 comparing each uncompensated test with its compensated twin in each feedback variant run.
//!
//! Only what the campaign has data for is drawn: a chart whose every value is missing is left
//! out, a missing run or metric leaves a gap. Without a TrueType font (see
//! [`cosim_plot::register_font`]) the figures are drawn without any text.

pub mod bars;
pub mod response;

use std::collections::HashMap;
use std::ops::RangeInclusive;
use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::{BitMapBackend, DrawingArea};

use crate::matrix::{self, Family, TestCase, Variant};
use crate::results::Campaign;
use crate::scale::{CampaignScale, Scale};
pub use bars::{bar_chart, BarSeries};
use crane_metrics::run::Metrics;
use crane_metrics::MetricId;

/// The font family registered by [`cosim_plot::register_font`].
const FONT: &str = "sans-serif";
/// The folder of the figures, inside the campaign's output folder.
const FOLDER: &str = "figures";

/// A whole PNG image being drawn.
type Root<'a> = DrawingArea<BitMapBackend<'a>, Shift>;
type DrawResult = Result<(), Box<dyn std::error::Error>>;

/// The outcome of drawing the figure at `path`: true when drawn, or the error naming the file.
fn drawn(path: &Path, result: DrawResult) -> Result<bool, String> {
    result.map(|()| true).map_err(|e| format!("{}: {e}", path.display()))
}

/// One figure of the thesis: its number and metric.
struct Chart {
    figure: &'static str,
    metric: MetricId,
}

impl Chart {
    /// The file name without ".png": the figure's number and the metric's name
    /// ("fig_7_16_tau_theta_x"), so that a figure drawing several metrics has a file for each.
    fn file(&self) -> String {
        format!("fig_{}_{}", self.figure.replace('.', "_"), self.metric.name())
    }
}

/// A set of bar charts: the uncompensated tests of the groups, each compared with its
/// compensated twin (the test whose [`matrix::reference_of`] it is).
struct Comparison {
    title: &'static str,
    references: RangeInclusive<u16>,
    charts: &'static [Chart],
}

const fn chart(figure: &'static str, metric: MetricId) -> Chart {
    Chart { figure, metric }
}

/// The charts of a figure under ship motion (Figs. 7.22, 7.23, 7.25): all three draw the same
/// metrics.
const fn ship_motion(figure: &'static str) -> [Chart; 3] {
    [chart(figure, MetricId::EllipsoidVolume), chart(figure, MetricId::Distance), chart(figure, MetricId::Rmse)]
}

const COMPARISONS: [Comparison; 4] = [
    Comparison {
        title: "energy dissipation, tests 001–040 vs 041–080 (l_p mm / θ0 deg)",
        references: 1..=40,
        charts: &[
            chart("7.16", MetricId::TauThetaX),
            chart("7.17", MetricId::TauThetaY),
            chart("7.18", MetricId::TauHeight),
            chart("7.19", MetricId::Distance),
            chart("7.20", MetricId::Rmse),
        ],
    },
    Comparison {
        title: "fixed set-point under ship motion, tests 081–083 vs 089–091",
        references: 81..=83,
        charts: &ship_motion("7.22"),
    },
    Comparison {
        title: "natural-frequency excitation, tests 084–088 vs 092–096",
        references: 84..=88,
        charts: &ship_motion("7.23"),
    },
    Comparison {
        title: "variable set-point, tests 097–100 vs 101–104",
        references: 97..=100,
        charts: &ship_motion("7.25"),
    },
];

/// Draws every figure the campaign has data for into `out/figures` and returns their paths
/// relative to `out` ("figures/response_020-1.png", "figures/fig_7_16_tau_theta_x.png", …).
pub fn draw_all(out: &Path, campaign: &Campaign) -> Result<Vec<String>, String> {
    draw_with(out, campaign, cosim_plot::register_font())
}

/// [`draw_all`], with text only if `text`.
fn draw_with(out: &Path, campaign: &Campaign, text: bool) -> Result<Vec<String>, String> {
    let folder = out.join(FOLDER);
    std::fs::create_dir_all(&folder).map_err(|e| format!("cannot create {}: {e}", folder.display()))?;
    let mut written = Vec::new();
    let mut keep = |name: String, drawn: bool| {
        if drawn {
            written.push(format!("{FOLDER}/{name}"));
        }
    };
    for (id, evaluation) in &campaign.detailed {
        let name = format!("response_{id}.png");
        keep(name.clone(), response::draw(&folder.join(&name), id, evaluation, text)?);
    }
    let metrics = metrics_by_run(campaign);
    let variants = variants_run(campaign);
    let tests = matrix::tests();
    let scale = campaign.results.first().map(|r| r.run.scale).unwrap_or_default();
    for comparison in &COMPARISONS {
        let pairs = pairs(&tests, &comparison.references);
        let groups: Vec<String> = pairs.iter().map(|(reference, _)| group_label(reference, scale)).collect();
        for chart in comparison.charts {
            let series = series(&pairs, &metrics, &variants, chart.metric);
            let info = chart.metric.info();
            let title = format!("Fig. {} equivalent — {}: {}", chart.figure, info.chart_title, comparison.title);
            let y_label = chart.metric.axis_label();
            let bars =
                bars::Bars { title: &title, y_label: &y_label, groups: &groups, series: &series, log_y: info.log_axis };
            let name = format!("{}.png", chart.file());
            keep(name.clone(), bars.draw(&folder.join(&name), text)?);
        }
    }
    Ok(written)
}

/// The metrics of every run that has them, by (test number, variant).
fn metrics_by_run(campaign: &Campaign) -> HashMap<(u16, Variant), Metrics> {
    campaign.results.iter().filter_map(|r| r.metrics.map(|m| ((r.run.test.number, r.run.variant), m))).collect()
}

/// The variants the campaign ran, at least the thesis' two (so that a one-variant campaign keeps
/// the charts' four series, one pair empty).
fn variants_run(campaign: &Campaign) -> Vec<Variant> {
    let mut variants: Vec<Variant> =
        Variant::BOTH.into_iter().chain(campaign.results.iter().map(|r| r.run.variant)).collect();
    variants.sort_unstable();
    variants.dedup();
    variants
}

/// Each uncompensated test numbered in `references` with its compensated twin, if it has one.
fn pairs<'a>(tests: &'a [TestCase], references: &RangeInclusive<u16>) -> Vec<(&'a TestCase, Option<&'a TestCase>)> {
    tests
        .iter()
        .filter(|t| references.contains(&t.number))
        .map(|reference| (reference, tests.iter().find(|t| matrix::reference_of(t) == Some(reference.number))))
        .collect()
}

/// "400 / -8.5" (length mm at `scale` / the initial angle, deg) for the energy-dissipation
/// tests, else the excitation: "profile 1", "wn(0.70 m)", "no motion".
fn group_label(test: &TestCase, scale: Scale) -> String {
    if test.family == Family::EnergyDissipation {
        let [x, y] = test.theta0_deg;
        format!("{:.0} / {}", scale.length(test.lp) * 1e3, if x != 0.0 { x } else { y })
    } else {
        test.motion.label_at(scale)
    }
}

/// The series "No compensation (v)" for each of `variants`, then "Compensation (v)" (with the
/// thesis' two: (1), (2), (1), (2)): `metric` of each pair's uncompensated and compensated test
/// in each variant, `None` where the run or the metric is missing.
fn series(
    pairs: &[(&TestCase, Option<&TestCase>)],
    metrics: &HashMap<(u16, Variant), Metrics>,
    variants: &[Variant],
    metric: MetricId,
) -> Vec<BarSeries> {
    let value = |test: Option<&TestCase>, variant: Variant| {
        let plotted = |m: &Metrics| m.get(metric).map(|v| metric.info().display.scaled(v));
        test.and_then(|t| metrics.get(&(t.number, variant))).and_then(plotted)
    };
    let mut all = Vec::new();
    for (name, compensated) in [("No compensation", false), ("Compensation", true)] {
        for &variant in variants {
            let values = pairs
                .iter()
                .map(|&(reference, twin)| value(if compensated { twin } else { Some(reference) }, variant))
                .collect();
            all.push((format!("{name} ({})", variant.number()), values));
        }
    }
    all
}

#[cfg(test)]
mod tests;
