//! The campaign's files: per-run metrics (CSV and JSON) and the Markdown report that sets the
//! mean reductions beside the thesis' simulation columns of Tables 7.1–7.3.

use std::fmt::Write as _;
use std::path::Path;

use crate::matrix::Variant;
use crate::results::{Campaign, RunResult};
use crate::summary::{changes, mean_reduction, Change, THESIS};

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

/// One row per run: identification, then the metrics in SI units (s, m, m³), empty where none.
pub fn metrics_csv(results: &[RunResult]) -> String {
    let mut text = String::from(
        "id,test,variant,family,control,lp_m,theta_x0_deg,theta_y0_deg,motion,tau_theta_x_s,tau_theta_y_s,tau_height_s,distance_m,ellipsoid_volume_m3,rmse_m,peak_height_m,peak_theta_x_rad,peak_theta_y_rad,wall_time_s,error\n",
    );
    let opt = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:e}"));
    for r in results {
        let t = &r.run.test;
        let m = r.metrics.unwrap_or_default();
        let have = r.metrics.is_some();
        let num = |v: f64| if have { format!("{v:e}") } else { String::new() };
        let _ = writeln!(
            text,
            "{},{},{},{:?},{:?},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.3},{}",
            r.id,
            t.number,
            r.run.variant.number(),
            t.family,
            t.control,
            t.lp,
            t.theta0_deg[0],
            t.theta0_deg[1],
            t.motion.label(),
            opt(m.tau_theta_x),
            opt(m.tau_theta_y),
            opt(m.tau_height),
            num(m.distance),
            opt(m.ellipsoid_volume),
            num(m.rmse),
            num(m.peak_height),
            num(m.peak_theta_x),
            num(m.peak_theta_y),
            r.wall_time,
            r.error.as_deref().unwrap_or("").replace([',', '\n'], ";"),
        );
    }
    text
}

fn percent(v: Option<f64>) -> String {
    v.map_or("—".into(), |v| if v < 0.0 { format!("({:.1} % ↑)", -v) } else { format!("{v:.1} %") })
}

/// The Markdown report.
pub fn markdown(campaign: &Campaign, changes: &[Change], figures: &[String]) -> String {
    let mut md = String::from("# Simulation campaign: tests 001–104 against the thesis\n\n");
    let runs = campaign.results.len();
    let failed = campaign.failures().count();
    let _ = writeln!(
        md,
        "{runs} runs ({failed} failed) in {:.1} s wall time on {} worker threads; {:.0} s simulated per wall-clock second overall.\n",
        campaign.wall_time,
        campaign.jobs,
        campaign.real_time_factor()
    );
    let init = match campaign.results.first().map(|r| r.run.init) {
        Some(crate::matrix::Init::Thesis) => {
            "as the thesis' simulations: filters started at the identity, no hold, everything from t = 0"
        }
        _ => "10 s with the load held and the filters aligned on their first sample, then the 120 s test",
    };
    let _ = writeln!(md, "Estimator initialisation: {init}.\n");
    md.push_str(
        "Mean percentage reductions (−eq. 7.1, compensated against uncompensated; an increase is shown as (x % ↑)) beside \
         the thesis' simulation columns: (1) truth feedback, (2) sensor feedback with noise. `n` is the number of test \
         pairs averaged; angle time constants are averaged on the axis of the initial angle. SPEC §7 gives the \
         acceptance figures.\n\n",
    );
    let mut group = None;
    for row in THESIS {
        if group != Some(row.group) {
            group = Some(row.group);
            let _ = writeln!(md, "\n### {}\n", row.group.title());
            md.push_str("| Metric | Thesis exp. | Thesis sim. (1) | Ours (1) | n | Thesis sim. (2) | Ours (2) | n | SPEC §7 |\n");
            md.push_str("|---|---|---|---|---|---|---|---|---|\n");
        }
        let ours = Variant::BOTH.map(|v| mean_reduction(changes, row.group, v, row.metric));
        let verdict = Variant::BOTH
            .iter()
            .zip(row.acceptance)
            .filter_map(|(v, a)| a.map(|a| (v, a)))
            .map(|(v, a)| {
                let verdict = match ours[*v as usize - 1] {
                    None => "no data",
                    Some((r, _)) if a.holds(r) => "met",
                    Some(_) => "NOT met",
                };
                format!("({}) {} {verdict}", v.number(), a.describe())
            })
            .collect::<Vec<_>>()
            .join("; ");
        let count = |o: Option<(f64, usize)>| o.map_or("0".into(), |(_, n)| n.to_string());
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            row.metric.name(),
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
    md.push_str("| Run | l_p (mm) | θ0 (deg) | Excitation | Control | τθx (s) | τθy (s) | τh (s) | Distance (m) | Ellipsoid (cm³) | RMSE (mm) |\n");
    md.push_str("|---|---|---|---|---|---|---|---|---|---|---|\n");
    let opt =
        |v: Option<f64>, scale: f64, digits: usize| v.map_or("—".into(), |v| format!("{:.*}", digits, v * scale));
    for r in &campaign.results {
        let t = &r.run.test;
        let Some(m) = r.metrics else {
            let _ =
                writeln!(md, "| {} | failed: {} |||||||||| ", r.id, r.error.as_deref().unwrap_or("").replace('|', "/"));
            continue;
        };
        let _ = writeln!(
            md,
            "| {} | {:.0} | {}, {} | {} | {:?} | {} | {} | {} | {:.3} | {} | {:.1} |",
            r.id,
            t.lp * 1e3,
            t.theta0_deg[0],
            t.theta0_deg[1],
            t.motion.label(),
            t.control,
            opt(m.tau_theta_x, 1.0, 1),
            opt(m.tau_theta_y, 1.0, 1),
            opt(m.tau_height, 1.0, 1),
            m.distance,
            opt(m.ellipsoid_volume, 1e6, 3),
            m.rmse * 1e3,
        );
    }
    if !figures.is_empty() {
        md.push_str("\n## Figures\n\n");
        for f in figures {
            let _ = writeln!(md, "![{f}]({f})\n");
        }
    }
    md
}
