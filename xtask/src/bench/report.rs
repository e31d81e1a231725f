//! What the bench measured (target/bench/report.json) and its Markdown rendering
//! (target/bench/report.md).

use super::budget::Verdict;
use super::compare::Difference;
use serde::Serialize;

/// Everything one bench run measured. Sections the run did not measure (`--check`) are empty.
#[derive(Debug, Serialize)]
pub struct Report {
    /// Where and on what the numbers were taken.
    pub machine: Machine,
    /// Each instruction budget against its measure.
    pub budgets: Vec<Verdict>,
    /// Callgrind counts, one per case.
    pub instructions: Vec<Instructions>,
    /// Wall times of the importers, one per case.
    pub wall: Vec<WallTimes>,
    /// Time inside the FMUs per macro step, one per case.
    pub fmu_timing: Vec<FmuTiming>,
    /// The full campaign's wall time, when measured.
    pub campaign: Option<CampaignTime>,
}

/// Report header: where and on what the numbers were taken.
#[derive(Debug, Serialize)]
pub struct Machine {
    /// The CPU's model name.
    pub cpu: String,
    /// Logical cores.
    pub cores: usize,
    /// UTC, ISO 8601.
    pub date: String,
    /// `rustc --version`.
    pub rustc: String,
    /// Short hash, with "-dirty" when the work tree has uncommitted changes.
    pub commit: String,
}

/// Callgrind counts of one case.
#[derive(Debug, Clone, Serialize)]
pub struct Instructions {
    /// The case's name.
    pub case: String,
    /// Its scenario file, relative to the workspace root.
    pub scenario: String,
    /// The two stop times (s) whose runs are subtracted.
    pub window_s: [f64; 2],
    /// (Ir(t2) − Ir(t1)) / steps in the window: start-up and exit cancel.
    pub per_step: u64,
    /// Ir of a whole run of one macro step: process start, load, instantiate, initialize, the
    /// step, recording and exit.
    pub start_up: u64,
    /// Per FMU library, the inclusive cost of its `fmi2*` entry points per step (same window).
    pub libraries: Vec<LibraryInstructions>,
}

/// The instructions of one FMU library's entry points.
#[derive(Debug, Clone, Serialize)]
pub struct LibraryInstructions {
    /// The FMU whose library it is.
    pub fmu: String,
    /// Instances sharing the library (their costs are counted together).
    pub instances: Vec<String>,
    /// Ir per macro step of its `fmi2*` entry points.
    pub per_step: u64,
}

/// Wall times of the importers on one scenario (best of `repeats`, pinned to one core).
#[derive(Debug, Serialize)]
pub struct WallTimes {
    /// The case's name.
    pub case: String,
    /// The scenario's stop time (s).
    pub stop_time: f64,
    /// Runs per importer, the best kept.
    pub repeats: usize,
    /// One per importer.
    pub masters: Vec<MasterTime>,
    /// Max abs difference of the recorded variables between the Jacobi importers.
    pub jacobi_cross_check: Vec<CrossCheck>,
}

/// One importer's wall time on a scenario.
#[derive(Debug, Clone, Serialize)]
pub struct MasterTime {
    /// The importer (e.g. [`CRANE_COSIM`]).
    pub master: String,
    /// Best wall time of a run (s).
    pub wall_s: f64,
    /// Simulated seconds per wall-clock second.
    pub real_time_factor: f64,
}

/// How far two importers' results are apart.
#[derive(Debug, Serialize)]
pub struct CrossCheck {
    /// The first importer compared.
    pub a: String,
    /// The second importer compared.
    pub b: String,
    /// Their largest difference over the recorded variables.
    #[serde(flatten)]
    pub difference: Difference,
}

/// `crane-cosim run --timing` of one case: per instance, µs per macro step.
#[derive(Debug, Serialize)]
pub struct FmuTiming {
    /// The case's name.
    pub case: String,
    /// None when the importer has no `--timing` (the report says "not available").
    pub instances: Option<Vec<InstanceTiming>>,
}

/// Where one instance's time went.
#[derive(Debug, Clone, Serialize)]
pub struct InstanceTiming {
    /// The instance's name.
    pub name: String,
    /// Inside `fmi2DoStep`, µs per macro step.
    pub do_step_us: f64,
    /// Inside `fmi2Get*` and `fmi2Set*`, µs per macro step.
    pub get_set_us: f64,
}

/// The full campaign on all cores.
#[derive(Debug, Serialize)]
pub struct CampaignTime {
    /// Wall time of the whole campaign (s).
    pub wall_s: f64,
    /// Logical cores it ran on.
    pub cores: usize,
}

/// Names of the importers, as the report and its ratios refer to them.
pub const CRANE_COSIM: &str = "crane-cosim (Gauss-Seidel)";
pub const CRANE_COSIM_JACOBI: &str = "crane-cosim (Jacobi)";
pub const PYTHON: &str = "Python over FMPy (Jacobi)";
pub const LIBCOSIM: &str = "libcosim (Jacobi)";

impl Report {
    pub fn markdown(&self) -> String {
        let m = &self.machine;
        let mut out = format!(
            "# Closed-loop benchmark\n\n{} ({} cores), {}, {}, commit {}\n",
            m.cpu, m.cores, m.date, m.rustc, m.commit
        );
        out.push_str("\n## Instruction budgets\n\n");
        out.push_str(&table(
            &["case", "measure", "measured", "ceiling (checked)", "verdict", "goal", "goal met"],
            self.budgets.iter().map(|v| {
                vec![
                    v.budget.case.to_string(),
                    v.budget.measure.label().to_string(),
                    thousands(v.measured),
                    thousands(v.budget.limit),
                    if v.within { "ok" } else { "OVER" }.to_string(),
                    thousands(v.budget.goal),
                    if v.measured <= v.budget.goal { "yes" } else { "no" }.to_string(),
                ]
            }),
        ));
        out.push_str("\n## Instructions (callgrind)\n\n");
        out.push_str(&table(
            &["case", "window (s)", "per macro step", "start-up (1-step run)"],
            self.instructions.iter().map(|i| {
                vec![
                    i.case.clone(),
                    format!("{}-{}", i.window_s[0], i.window_s[1]),
                    thousands(i.per_step),
                    thousands(i.start_up),
                ]
            }),
        ));
        out.push_str(&self.library_section());
        out.push_str(&self.wall_section());
        out.push_str(&self.timing_section());
        if let Some(c) = &self.campaign {
            out.push_str(&format!("\n## Campaign\n\n208 runs on {} cores: {:.2} s wall\n", c.cores, c.wall_s));
        }
        out
    }

    fn library_section(&self) -> String {
        let mut out =
            String::from("\n### Per FMU: inclusive instructions of its fmi2* entry points per macro step\n\n");
        for case in &self.instructions {
            out.push_str(&format!("{}:\n\n", case.case));
            out.push_str(&table(
                &["FMU", "instances", "per macro step"],
                case.libraries.iter().map(|l| vec![l.fmu.clone(), l.instances.join(", "), thousands(l.per_step)]),
            ));
            out.push('\n');
        }
        out
    }

    fn wall_section(&self) -> String {
        let mut out = String::new();
        for w in &self.wall {
            out.push_str(&format!(
                "\n## Wall time: {} to {} s (best of {}, one core)\n\n",
                w.case, w.stop_time, w.repeats
            ));
            out.push_str(&table(
                &["master", "wall (s)", "real-time factor"],
                w.masters
                    .iter()
                    .map(|t| vec![t.master.clone(), format!("{:.3}", t.wall_s), format!("{:.0}", t.real_time_factor)]),
            ));
            for other in [PYTHON, LIBCOSIM] {
                if let Some(ratio) = w.speedup(other) {
                    out.push_str(&format!("\n{CRANE_COSIM} is {ratio:.1}x as fast as {other}"));
                }
            }
            out.push_str("\n\nJacobi cross-check, max abs difference of the recorded variables:\n\n");
            out.push_str(&table(
                &["", "", "max abs difference", "values compared"],
                w.jacobi_cross_check.iter().map(|c| {
                    vec![c.a.clone(), c.b.clone(), difference(c.difference.max_abs), c.difference.values.to_string()]
                }),
            ));
        }
        out
    }

    fn timing_section(&self) -> String {
        let mut out = String::new();
        for t in &self.fmu_timing {
            out.push_str(&format!("\n## Per instance, µs per macro step (crane-cosim --timing): {}\n\n", t.case));
            match &t.instances {
                None => out.push_str("not available\n"),
                Some(instances) => out.push_str(&table(
                    &["instance", "fmi2DoStep (µs)", "get/set (µs)"],
                    instances
                        .iter()
                        .map(|i| vec![i.name.clone(), format!("{:.2}", i.do_step_us), format!("{:.2}", i.get_set_us)]),
                )),
            }
        }
        out
    }
}

impl WallTimes {
    /// How many times faster crane-cosim (Gauss–Seidel) ran than `other`.
    pub fn speedup(&self, other: &str) -> Option<f64> {
        let wall = |name: &str| self.masters.iter().find(|m| m.master == name).map(|m| m.wall_s);
        Some(wall(other)? / wall(CRANE_COSIM)?)
    }
}

/// A Markdown table; columns are padded to their widest cell, numbers (cells starting with a
/// digit) right-aligned.
pub fn table(header: &[&str], rows: impl IntoIterator<Item = Vec<String>>) -> String {
    let rows: Vec<Vec<String>> = rows.into_iter().collect();
    let widths: Vec<usize> = (0..header.len())
        .map(|c| rows.iter().map(|r| r[c].chars().count()).chain([header[c].chars().count(), 3]).max().unwrap_or(3))
        .collect();
    let numeric: Vec<bool> = (0..header.len())
        .map(|c| !rows.is_empty() && rows.iter().all(|r| r[c].starts_with(|ch: char| ch.is_ascii_digit())))
        .collect();
    let line = |cells: Vec<String>| {
        let padded: Vec<String> = cells
            .iter()
            .enumerate()
            .map(
                |(c, s)| if numeric[c] { format!("{s:>w$}", w = widths[c]) } else { format!("{s:<w$}", w = widths[c]) },
            )
            .collect();
        format!("| {} |\n", padded.join(" | "))
    };
    let mut out = line(header.iter().map(|h| h.to_string()).collect());
    let rule: Vec<String> = widths
        .iter()
        .zip(&numeric)
        .map(|(&w, &n)| if n { format!("{}:", "-".repeat(w - 1)) } else { "-".repeat(w) })
        .collect();
    out.push_str(&format!("| {} |\n", rule.join(" | ")));
    for row in rows {
        out.push_str(&line(row));
    }
    out
}

/// "0" when the results are bit-identical, else e.g. "5.0e-14".
pub fn difference(max_abs: f64) -> String {
    if max_abs == 0.0 {
        "0".into()
    } else {
        format!("{max_abs:.1e}")
    }
}

/// 286123 → "286,123".
pub fn thousands(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, ch) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(ch);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thousands_are_grouped_by_three() {
        assert_eq!(thousands(0), "0");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(1000), "1,000");
        assert_eq!(thousands(2_300_000_123), "2,300,000,123");
    }

    #[test]
    fn differences_show_bit_identical_results_as_zero() {
        assert_eq!(difference(0.0), "0");
        assert_eq!(difference(5.02e-14), "5.0e-14");
        assert_eq!(difference(f64::INFINITY), "inf");
    }

    #[test]
    fn tables_pad_columns_and_right_align_numbers() {
        let rows = vec![vec!["still".to_string(), "286,000".to_string()], vec!["profile 1".into(), "9".into()]];
        let text = table(&["case", "per step"], rows);
        assert_eq!(
            text,
            "| case      | per step |\n\
             | --------- | -------: |\n\
             | still     |  286,000 |\n\
             | profile 1 |        9 |\n"
        );
    }

    #[test]
    fn speedups_divide_the_other_masters_wall_time_by_crane_cosims() {
        let time = |master: &str, wall_s| MasterTime { master: master.into(), wall_s, real_time_factor: 0.0 };
        let wall = WallTimes {
            case: "c".into(),
            stop_time: 70.0,
            repeats: 3,
            masters: vec![time(CRANE_COSIM, 0.5), time(PYTHON, 20.0)],
            jacobi_cross_check: Vec::new(),
        };
        assert_eq!(wall.speedup(PYTHON), Some(40.0));
        assert_eq!(wall.speedup(LIBCOSIM), None, "not measured");
    }
}
