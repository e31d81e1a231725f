//! `crane-cosim plot`: columns of results CSVs against time, in one figure or stacked panels.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Result};
use clap::Args;
use cosim_engine::summary::ColumnSummary;
use cosim_engine::system::single::glob_matches;
use cosim_engine::table::SignalTable;
use cosim_engine::text::counted;
use cosim_plot::{self as plot, Figure, Panel, Series};
use fmu_import::names::{closest, did_you_mean};

use super::{read_results, stem};
use crane_app::run::summary_path;

/// Arguments of `crane-cosim plot`.
#[derive(Debug, Args)]
#[command(after_help = "Units come from the run summary next to each CSV (x.summary.json for x.csv, as \
    `crane-cosim run` writes it). With --scale, give the unit of the scaled values with --unit.\n\n\
    Examples:\n  \
    crane-cosim plot -c pendulum.theta_x -c pendulum.theta_y --scale 57.29578 --unit deg -o out/angles.svg out/a.csv\n  \
    crane-cosim plot -c 'pendulum.load.*' --panels --from 10 --to 40 -o out/load.png out/a.csv out/b.csv")]
pub struct PlotArgs {
    /// Columns to plot: names or patterns (* any characters, ? one character), e.g.
    /// pendulum.theta_x or 'pendulum.load.*'. Repeatable.
    #[arg(short, long = "column", value_name = "NAME|PATTERN", required = true)]
    pub columns: Vec<String>,
    /// One panel per column, stacked, each with its own y axis (default: every curve in one).
    #[arg(long)]
    pub panels: bool,
    /// Multiply the values (e.g. 57.29578 for radians to degrees).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub scale: f64,
    /// Unit of the values after --scale, shown on the y axis (e.g. deg) [default: the column's
    /// unit, marked "× SCALE" when scaled].
    #[arg(long)]
    pub unit: Option<String>,
    /// Y-axis label, replacing "COLUMN (UNIT)".
    #[arg(long)]
    pub label: Option<String>,
    /// Figure title [default: the files' names].
    #[arg(long)]
    pub title: Option<String>,
    /// Plot from this time on (s).
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub from: Option<f64>,
    /// Plot up to this time (s).
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub to: Option<f64>,
    /// Output image: .png or .svg.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Results CSVs; curves are labelled by column, by file name, or both when a panel has several
    /// of each.
    #[arg(required = true)]
    pub results: Vec<PathBuf>,
}

/// One results file: its name, table and column units.
struct Results {
    name: String,
    table: SignalTable,
    units: BTreeMap<String, String>,
}

/// Draws the figure.
pub fn plot(args: &PlotArgs) -> Result<()> {
    let (from, to) = (args.from.unwrap_or(f64::NEG_INFINITY), args.to.unwrap_or(f64::INFINITY));
    if !(from < to) {
        bail!("--from {from} is not before --to {to}");
    }
    let files = args.results.iter().map(|path| load(path)).collect::<Result<Vec<_>>>()?;
    let columns = selected_columns(&args.columns, &files)?;
    let groups: Vec<Vec<&str>> = if args.panels {
        columns.iter().map(|c| vec![c.as_str()]).collect()
    } else {
        vec![columns.iter().map(String::as_str).collect()]
    };
    let mut panels = Vec::new();
    for group in groups {
        let series = group
            .iter()
            .flat_map(|column| files.iter().map(move |file| (*column, file)))
            .filter_map(|(column, file)| {
                let label = match (group.len(), files.len()) {
                    (1, 1) => column.to_string(),
                    (1, _) => file.name.clone(),
                    (_, 1) => column.to_string(),
                    _ => format!("{}: {column}", file.name),
                };
                series(file, column, label, args.scale, (from, to))
            })
            .collect::<Vec<_>>();
        if series.iter().all(|s| s.points.len() < 2) {
            bail!("no data between --from and --to for {}", group.join(", "));
        }
        panels.push(Panel { y_label: y_label(args, &group, &files), series });
    }
    let title =
        args.title.clone().unwrap_or_else(|| files.iter().map(|f| f.name.as_str()).collect::<Vec<_>>().join(", "));
    let curves = panels.iter().map(|p| p.series.len() as u64).sum::<u64>();
    let panel_count = panels.len() as u64;
    plot::draw(&args.output, &Figure { title, panels, x_label: "time (s)".into() }).map_err(|e| anyhow!(e))?;
    let panels = if panel_count > 1 { format!(" in {}", counted(panel_count, "panel")) } else { String::new() };
    println!("wrote {} ({}{panels})", args.output.display(), counted(curves, "curve"));
    Ok(())
}

/// The results file and the units its summary gives (none if it has no summary).
fn load(path: &Path) -> Result<Results> {
    let table = read_results(path)?;
    let units = match std::fs::read_to_string(summary_path(path)) {
        Ok(text) => units(&text).map_err(|e| anyhow!("{}: {e}", summary_path(path).display()))?,
        Err(_) => BTreeMap::new(),
    };
    Ok(Results { name: stem(path), table, units })
}

/// Column name → unit from a run summary's `"columns"`.
fn units(summary: &str) -> Result<BTreeMap<String, String>, serde_json::Error> {
    #[derive(serde::Deserialize)]
    struct Summary {
        #[serde(default)]
        columns: Vec<ColumnSummary>,
    }
    let summary: Summary = serde_json::from_str(summary)?;
    Ok(summary.columns.into_iter().filter_map(|c| Some((c.name, c.unit?))).collect())
}

/// The columns matching any pattern, in the order of the patterns then of the first file's
/// header; a pattern that matches nothing in some file is an error suggesting the closest
/// column, or naming that file's columns when none is close.
fn selected_columns(patterns: &[String], files: &[Results]) -> Result<Vec<String>> {
    let mut columns: Vec<String> = Vec::new();
    for pattern in patterns {
        for file in files {
            let matching: Vec<&String> = file.table.names.iter().filter(|n| glob_matches(pattern, n)).collect();
            if matching.is_empty() {
                let names = file.table.names.iter().map(String::as_str);
                if let Some(closest) = closest(pattern, names).filter(|_| !pattern.contains(['*', '?'])) {
                    bail!("{}: no column matches {pattern:?}{}", file.name, did_you_mean(&Some(closest)));
                }
                bail!("{}: no column matches {pattern:?} (columns: {})", file.name, file.table.names.join(", "));
            }
            for name in matching {
                if !columns.contains(name) {
                    columns.push(name.clone());
                }
            }
        }
    }
    Ok(columns)
}

/// The scaled samples of `column` in `file` within the window; None if the file lacks it.
fn series(file: &Results, column: &str, label: String, scale: f64, (from, to): (f64, f64)) -> Option<Series> {
    let values = &file.table.columns[file.table.column(column)?];
    let points = file
        .table
        .times
        .iter()
        .zip(values)
        .filter(|(t, _)| (from..=to).contains(*t))
        .map(|(t, v)| (*t, v * scale))
        .collect();
    Some(Series { label, points })
}

/// `--label`, else "COLUMN (UNIT)" for one column or "UNIT" for several; units from `--unit`
/// or the summaries (marked "× SCALE" when scaled without `--unit`).
fn y_label(args: &PlotArgs, columns: &[&str], files: &[Results]) -> String {
    if let Some(label) = &args.label {
        return label.clone();
    }
    let unit = args.unit.clone().or_else(|| {
        let mut units: Vec<&str> = Vec::new();
        for unit in columns.iter().filter_map(|c| files.iter().find_map(|f| f.units.get(*c))) {
            if !units.contains(&unit.as_str()) {
                units.push(unit);
            }
        }
        let unit = (!units.is_empty()).then(|| units.join(", "));
        match unit {
            _ if args.scale == 1.0 => unit,
            Some(unit) => Some(format!("{unit} × {}", args.scale)),
            None => Some(format!("× {}", args.scale)),
        }
    });
    let name = if columns.len() == 1 { columns[0] } else { "" };
    match unit {
        Some(unit) if name.is_empty() => unit,
        Some(unit) => format!("{name} ({unit})"),
        None => name.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(scale: f64, unit: Option<&str>) -> PlotArgs {
        PlotArgs {
            columns: Vec::new(),
            panels: false,
            scale,
            unit: unit.map(String::from),
            label: None,
            title: None,
            from: None,
            to: None,
            output: PathBuf::new(),
            results: Vec::new(),
        }
    }

    fn results(summary: &str) -> Results {
        let table = SignalTable { file: PathBuf::new(), names: Vec::new(), times: Vec::new(), columns: Vec::new() };
        Results { name: "a".into(), table, units: units(summary).expect("summary") }
    }

    #[test]
    fn y_labels_carry_the_units_of_the_run_summary() {
        let summary = r#"{"status": "completed", "columns": [{"name": "p.theta_x", "unit": "rad"},
            {"name": "p.theta_y", "unit": "rad"}, {"name": "p.load.z", "unit": "m"}, {"name": "p.mode", "unit": null}]}"#;
        let files = [results(summary)];
        assert_eq!(y_label(&args(1.0, None), &["p.theta_x"], &files), "p.theta_x (rad)");
        assert_eq!(y_label(&args(1.0, None), &["p.theta_x", "p.theta_y"], &files), "rad");
        assert_eq!(y_label(&args(1.0, None), &["p.theta_x", "p.load.z"], &files), "rad, m");
        assert_eq!(y_label(&args(57.3, Some("deg")), &["p.theta_x"], &files), "p.theta_x (deg)");
        assert_eq!(y_label(&args(1000.0, None), &["p.load.z"], &files), "p.load.z (m × 1000)");
        assert_eq!(y_label(&args(1.0, None), &["p.mode"], &files), "p.mode");
        assert_eq!(y_label(&args(1.0, None), &["p.theta_x"], &[results("{}")]), "p.theta_x");
    }
}
