//! The campaign's files: per-run metrics (CSV and JSON) and the Markdown report that sets the
//! mean reductions beside the thesis' simulation columns of Tables 7.1–7.3.

use std::fmt::Write as _;
use std::path::Path;

use cosim_engine::text::counted;

use crate::matrix::{AttitudeFilter, Family, RunSpec, Variant, TEST_TIME};
use crate::results::{Campaign, RunResult};
use crate::scale::{Scale, LENGTH_SCALE};
use crate::summary::{bands, changes, mean_reduction, verdicts, Change};
use crane_metrics::MetricId;

/// Writes `metrics.csv`, `metrics.json`, `changes.json` and `report.md` into `out`.
pub fn write_files(out: &Path, campaign: &Campaign, figures: &[String]) -> Result<(), String> {
    let changes = changes(&campaign.results);
    write(&out.join("metrics.csv"), &metrics_csv(&campaign.results))?;
    write(&out.join("metrics.json"), &json(&campaign.results)?)?;
    write(&out.join("changes.json"), &json(&changes)?)?;
    write(&out.join("report.md"), &markdown(campaign, &changes, figures))
}

fn write(path: &Path, text: &str) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

fn json<T: serde::Serialize>(value: &T) -> Result<String, String> {
    serde_json::to_string_pretty(value).map_err(|e| e.to_string())
}

/// One row per run: identification, then the catalogue's metrics in SI units (s, m, m³, rad),
/// empty where none.
pub fn metrics_csv(results: &[RunResult]) -> String {
    let metrics: Vec<String> = MetricId::ALL.iter().map(|id| id.csv_column()).collect();
    let mut text = format!(
        "id,test,variant,family,control,lp_m,theta_x0_deg,theta_y0_deg,motion,{},wall_time_s,error\n",
        metrics.join(",")
    );
    for r in results {
        let t = &r.run.test;
        let values: Vec<String> = MetricId::ALL
            .iter()
            .map(|&id| r.metrics.and_then(|m| m.get(id)).map_or(String::new(), |v| format!("{v:e}")))
            .collect();
        let _ = writeln!(
            text,
            "{},{},{},{},{},{},{},{},{},{},{:.3},{}",
            r.id,
            t.number,
            r.run.variant.number(),
            kebab(&t.family),
            kebab(&t.control),
            r.run.lp(),
            t.theta0_deg[0],
            t.theta0_deg[1],
            r.run.excitation(),
            values.join(","),
            r.wall_time,
            r.error.as_deref().unwrap_or("").replace([',', '\n'], ";"),
        );
    }
    text
}

/// An enum's serde name ("energy-dissipation"), as in metrics.json.
fn kebab<T: serde::Serialize>(value: &T) -> String {
    serde_json::to_value(value).ok().and_then(|v| v.as_str().map(String::from)).unwrap_or_default()
}

fn percent(v: Option<f64>) -> String {
    v.map_or("—".into(), |v| if v < 0.0 { format!("({:.1} % ↑)", -v) } else { format!("{v:.1} %") })
}

/// The system file as the report names it: `systems/<file>` for a file of a `systems` folder
/// (the shipped ones, wherever the tree is), else its file name; never a machine's path.
fn system_name(system: &std::path::Path) -> String {
    let name = |p: &std::path::Path| p.file_name().map(|n| n.to_string_lossy().into_owned());
    let file = name(system).unwrap_or_else(|| "the system file".into());
    match system.parent().and_then(name) {
        Some(folder) if folder == "systems" => format!("systems/{file}"),
        _ => file,
    }
}

/// The Markdown report.
pub fn markdown(campaign: &Campaign, changes: &[Change], figures: &[String]) -> String {
    let scale = campaign.results.first().map(|r| r.run.scale).unwrap_or_default();
    let mut md = match scale {
        Scale::Test => format!("# Simulation campaign: {} against the thesis\n\n", selection(&campaign.results)),
        Scale::Full => format!(
            "# Simulation campaign at full scale: {}\n\nThe thesis' test matrix on the full-scale hydraulic crane \
             ({}; docs/full-scale.md): rope lengths and the sine's amplitude ×{LENGTH_SCALE} \
             (Froude similarity), angles and the ship motion profiles as they are, the vessel's motion unscaled. \
             The thesis has no full-scale figures: its columns are empty.\n\n",
            selection(&campaign.results),
            system_name(&campaign.system),
        ),
    };
    let runs = campaign.results.len();
    let failed = campaign.failures().count();
    let _ = writeln!(
        md,
        "{} ({failed} failed) in {:.1} s wall time on {}; {:.0} s simulated per wall-clock second overall.\n",
        counted(runs as u64, "run"),
        campaign.wall_time,
        counted(campaign.jobs as u64, "worker thread"),
        campaign.real_time_factor()
    );
    let init = match campaign.results.first().map(|r| r.run.init) {
        Some(crate::matrix::Init::Thesis) => {
            "as the thesis' simulations: filters started at the identity, no hold, everything from t = 0"
        }
        _ if scale == Scale::Full && campaign.results.iter().any(|r| r.run.test_time() != TEST_TIME) => {
            "10 s with the load held and the crane's control inactive (it latches its references at release), then \
             the 120 s test; the pick-and-place tests 097–104 run their Froude-scaled profile, 600 s"
        }
        _ if scale == Scale::Full => {
            "10 s with the load held and the crane's control inactive (it latches its references at release), then \
             the 120 s test"
        }
        _ => "10 s with the load held and the filters aligned on their first sample, then the 120 s test",
    };
    let _ = writeln!(md, "Estimator initialisation: {init}.\n");
    if campaign.results.iter().any(|r| r.run.attitude == AttitudeFilter::Madgwick) {
        md.push_str("Attitude filter of the sensor variants: Madgwick's gradient-descent filter (not the thesis' complementary filter).\n\n");
    }
    if !campaign.start.is_empty() {
        let values: Vec<String> = campaign.start.iter().map(|(name, value)| format!("`{name}` = {value}")).collect();
        let _ = writeln!(md, "Start values of every run beyond the system file's: {}.\n", values.join(", "));
    }
    md.push_str(
        "Mean percentage reductions (−eq. 7.1, compensated against uncompensated; an increase is shown as (x % ↑)) beside \
         the thesis' simulation columns: (1) truth feedback, (2) sensor feedback with noise. `n` is the number of test \
         pairs averaged; angle time constants are averaged on the axis of the initial angle. The acceptance \
         figures are those of docs/acceptance.md in the source repository.\n\n",
    );
    let estimated = campaign.results.iter().any(|r| r.run.variant == Variant::Estimated);
    if estimated {
        md.push_str(
            "Ours (3): sensor feedback with noise and the ship's surge, sway and heave from the controller's EKF \
             (§5.1.3) instead of truth; the thesis has no such column.\n\n",
        );
    }
    let verdicts = verdicts(changes, scale);
    let mut group = None;
    for &row in bands(scale) {
        if group != Some(row.group) {
            group = Some(row.group);
            let _ = writeln!(md, "\n### {}\n", row.group.title());
            md.push_str("| Metric | Thesis exp. | Thesis sim. (1) | Ours (1) | n | Thesis sim. (2) | Ours (2) | n |");
            md.push_str(if estimated { " Ours (3) | n | Acceptance |\n" } else { " Acceptance |\n" });
            md.push_str(if estimated {
                "|---|---|---|---|---|---|---|---|---|---|---|\n"
            } else {
                "|---|---|---|---|---|---|---|---|---|\n"
            });
        }
        let ours = Variant::BOTH.map(|v| mean_reduction(changes, row.group, v, row.metric));
        let verdict = verdicts
            .iter()
            .filter(|v| v.row == row)
            .map(|v| {
                let met = match v.met() {
                    None => "no data",
                    Some(true) => "met",
                    Some(false) => "NOT met",
                };
                format!("({}) {} {met}", v.variant.number(), v.acceptance.describe())
            })
            .collect::<Vec<_>>()
            .join("; ");
        let count = |o: Option<(f64, usize)>| o.map_or("0".into(), |(_, n)| n.to_string());
        let third = if estimated {
            let ours = mean_reduction(changes, row.group, Variant::Estimated, row.metric);
            format!(" {} | {} |", percent(ours.map(|(r, _)| r)), count(ours))
        } else {
            String::new()
        };
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} |{third} {} |",
            row.metric.info().title,
            percent(row.experimental),
            percent(row.simulation[0]),
            percent(ours[0].map(|(r, _)| r)),
            count(ours[0]),
            percent(row.simulation[1]),
            percent(ours[1].map(|(r, _)| r)),
            count(ours[1]),
            verdict,
        );
    }
    md.push_str("\n## Per-run metrics\n\n");
    md.push_str(&per_run_header());
    for r in &campaign.results {
        md.push_str(&per_run_row(r));
    }
    md.push_str(NO_TIME_CONSTANT);
    if !figures.is_empty() {
        md.push_str("\n## Figures\n\n");
        for f in figures {
            let _ = writeln!(md, "![{f}]({f})\n");
        }
    }
    md
}

/// The per-run table's header and rule: the run, then the compared metrics in their displayed
/// units.
fn per_run_header() -> String {
    let metrics: String = MetricId::compared().map(|id| format!(" {} |", id.column_label())).collect();
    let rule = "---|".repeat(5 + MetricId::compared().count());
    format!("| Run | l_p (mm) | θ0 (deg) | Excitation | Control |{metrics}\n|{rule}\n")
}

/// One run's row of the per-run table, or its error.
fn per_run_row(r: &RunResult) -> String {
    let t = &r.run.test;
    let Some(m) = r.metrics else {
        let cells = "|".repeat(4 + MetricId::compared().count());
        return format!("| {} | failed: {} {cells} \n", r.id, r.error.as_deref().unwrap_or("").replace('|', "/"));
    };
    let cell = |id: MetricId| match m.get(id) {
        _ if id.is_time_constant() => time_constant(&r.run, m.get(id)),
        None => "—".into(),
        Some(v) => id.info().display.format(v),
    };
    let metrics: String = MetricId::compared().map(|id| format!(" {} |", cell(id))).collect();
    format!(
        "| {} | {:.0} | {}, {} | {} | {} |{metrics}\n",
        r.id,
        r.run.lp() * 1e3,
        t.theta0_deg[0],
        t.theta0_deg[1],
        r.run.excitation(),
        t.control.label(),
    )
}

/// "tests 020, 024, 060–064 (variants 1, 2)": the runs a campaign made, test numbers in ranges.
pub fn selection(results: &[RunResult]) -> String {
    let mut numbers: Vec<u16> = results.iter().map(|r| r.run.test.number).collect();
    numbers.sort_unstable();
    numbers.dedup();
    let mut variants: Vec<u8> = results.iter().map(|r| r.run.variant.number()).collect();
    variants.sort_unstable();
    variants.dedup();
    let mut ranges: Vec<(u16, u16)> = Vec::new();
    for n in numbers {
        match ranges.last_mut() {
            Some((_, last)) if *last + 1 == n => *last = n,
            _ => ranges.push((n, n)),
        }
    }
    let tests: Vec<String> =
        ranges.iter().map(|&(a, b)| if a == b { format!("{a:03}") } else { format!("{a:03}–{b:03}") }).collect();
    let noun = if tests.len() == 1 && ranges[0].0 == ranges[0].1 { "test" } else { "tests" };
    let variants: Vec<String> = variants.iter().map(u8::to_string).collect();
    let variant_noun = if variants.len() == 1 { "variant" } else { "variants" };
    format!("{noun} {} ({variant_noun} {})", tests.join(", "), variants.join(", "))
}

/// A fitted time constant over this many test lengths is no decay worth the name.
const MEANINGFUL_TAU_TESTS: f64 = 10.0;

/// The per-run table's cell for a time constant (s): the value, or "—" with a mark whose reason
/// [`NO_TIME_CONSTANT`] gives. Only runs released from an initial angle (tests 001–080) decay
/// freely; a fit to the set-point tests' swing is not a time constant (metrics.csv keeps it).
fn time_constant(run: &RunSpec, tau: Option<f64>) -> String {
    match tau {
        _ if run.test.family != Family::EnergyDissipation => "—ᵃ".into(),
        None => "—ᵇ".into(),
        Some(t) if t > MEANINGFUL_TAU_TESTS * run.test_time() => "—ᶜ".into(),
        Some(t) => format!("{t:.1}"),
    }
}

const NO_TIME_CONSTANT: &str =
    "\nNo time constant: ᵃ not a release from an initial angle (tests 081–104 hold or move a \
set-point; their swing does not decay freely); ᵇ no significant decaying peaks to fit (e.g. θy after a release in θx); \
ᶜ the fit's time constant exceeds ten times the 120 s test, i.e. no decay within it. metrics.csv and metrics.json keep \
every fitted value.\n";

#[cfg(test)]
mod tests {
    use super::*;
    use crate::matrix::tests as all_tests;

    fn results(numbers: &[u16], variants: &[Variant]) -> Vec<RunResult> {
        let tests = all_tests().into_iter().filter(|t| numbers.contains(&t.number)).collect::<Vec<_>>();
        crate::matrix::runs(&tests, variants, crate::matrix::Init::Held)
            .into_iter()
            .map(|run| RunResult { id: run.id(), run, metrics: None, error: None, simulated_time: 0.0, wall_time: 0.0 })
            .collect()
    }

    #[test]
    fn the_title_names_the_selection_in_ranges() {
        let all: Vec<u16> = (1..=104).collect();
        assert_eq!(selection(&results(&all, &Variant::BOTH)), "tests 001–104 (variants 1, 2)");
        assert_eq!(
            selection(&results(&[20, 21, 22, 60, 92], &[Variant::Sensors])),
            "tests 020–022, 060, 092 (variant 2)"
        );
        assert_eq!(selection(&results(&[84], &[Variant::Truth])), "test 084 (variant 1)");
    }

    #[test]
    fn the_report_names_the_system_file_it_ran_without_a_machines_path() {
        let named = |p: &str| system_name(std::path::Path::new(p));
        assert_eq!(
            named("/home/u/crane/systems/full_scale_ahc_elastic_rope.json"),
            "systems/full_scale_ahc_elastic_rope.json"
        );
        assert_eq!(named("/tmp/study/my_loop.json"), "my_loop.json");
        assert_eq!(named(""), "the system file");
    }

    #[test]
    fn the_tables_get_variant_3_columns_only_when_it_ran() {
        let campaign = |variants: &[Variant]| Campaign {
            results: results(&[60], variants),
            detailed: Vec::new(),
            wall_time: 1.0,
            jobs: 1,
            start: Default::default(),
            system: Default::default(),
        };
        let header = "| Metric | Thesis exp. | Thesis sim. (1) | Ours (1) | n | Thesis sim. (2) | Ours (2) | n |";
        let two = markdown(&campaign(&Variant::BOTH), &[], &[]);
        assert!(two.contains(&format!("{header} Acceptance |\n")) && !two.contains("Ours (3)"), "{two}");
        let three = markdown(&campaign(&Variant::ALL), &[], &[]);
        assert!(
            three.contains(&format!(
                "{header} Ours (3) | n | Acceptance |\n|---|---|---|---|---|---|---|---|---|---|---|\n"
            )),
            "{three}"
        );
        // No pairs ran: every mean is missing, in every column.
        assert!(
            three
                .contains("| θx time constant | 88.7 % | 89.7 % | — | 0 | 95.0 % | — | 0 | — | 0 | (1) ≥ 85 % no data"),
            "{three}"
        );
    }

    #[test]
    fn time_constants_without_a_free_decay_are_dashes_with_a_reason() {
        let runs = results(&[20, 84], &[Variant::Truth]);
        let (free, setpoint) = (&runs[0].run, &runs[1].run);
        assert_eq!(time_constant(free, Some(73.31)), "73.3");
        assert_eq!(time_constant(free, None), "—ᵇ");
        assert_eq!(time_constant(free, Some(16_000.0)), "—ᶜ");
        assert_eq!(time_constant(setpoint, Some(1616.0)), "—ᵃ");
    }
}
