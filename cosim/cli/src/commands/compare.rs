//! `crane-cosim compare`: swing, travel and set-point metrics of results CSVs.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{anyhow, Result};
use clap::Args;
use cosim_engine::text::rounded;
use crane_metrics::{self as metrics, Angles, Comparison, RunMetrics, Target};
use serde::Serialize;

use super::{read_results, stem};

/// Arguments of `crane-cosim compare`.
#[derive(Debug, Args)]
#[command(
    long_about = "Compare results CSVs: how fast a swing settles, how far the load travels and how \
                  close it stays to a set-point, over the time from --from to the end of each file.",
    after_long_help = "Metrics (each over the window from --from to the last sample):\n  \
    settling (s)     time after --from until both angles stay within ±--band for good; \"never\" if\n                   \
    they are outside it at the last sample, or if the swing's last peak is outside it and the\n                   \
    next peak (half a swing later) is not in the file\n  \
    distance (m)     path length of the load position resampled at 30 Hz, counting only\n                   \
    frame-to-frame moves over 3 mm (the thesis' motion-capture threshold, §7.2.2)\n  \
    RMSE (mm)        root-mean-square distance of the load position from the target, at 30 Hz\n                   \
    (\"—\" with --target none)\n  \
    last 10 s (deg)  largest |angle| of the two over the last 10 s of the window\n\n\
    The defaults read the closed loop's columns (systems/closed_loop.json and its scenarios).\n\
    Other runs name theirs, e.g. the free pendulum of systems/pendulum_free_decay.json:\n  \
    crane-cosim compare --angles load.theta_x,load.theta_y --position load.load. --target none out/decay.csv\n\
    and the campaign's results CSVs (positions only):\n  \
    crane-cosim compare --angles tip:crane.tip. --from 10 out/campaign/runs/060-1.csv"
)]
pub struct CompareArgs {
    /// Metrics cover the time from here on (s), e.g. the release of the load; must lie before
    /// the last sample of every file.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub from: f64,
    /// The two swing-angle columns (rad), or "tip:PREFIX" for angles from the cable direction,
    /// crane tip PREFIXx, PREFIXy, PREFIXz to the load position (results that record positions
    /// only, such as the campaign's: tip:crane.tip.).
    #[arg(long, value_name = "X,Y|tip:PREFIX", default_value = "pendulum.theta_x,pendulum.theta_y")]
    pub angles: String,
    /// Prefix of the load position columns PREFIXx, PREFIXy, PREFIXz (m).
    #[arg(long, value_name = "PREFIX", default_value = metrics::LOAD_PREFIX)]
    pub position: String,
    /// The set-point of the RMSE: a column prefix (PREFIXx, PREFIXy, PREFIXz), a fixed point
    /// "x,y,z" in metres, or "none".
    #[arg(long, value_name = "PREFIX|X,Y,Z|none", default_value = metrics::SETPOINT_PREFIX)]
    pub target: String,
    /// Settling band (deg).
    #[arg(long, value_name = "DEG", default_value_t = 2.0)]
    pub band: f64,
    /// Print JSON (an array of {"run", "file", "from_s", "settling_s", "distance_m", "rmse_m",
    /// "final_swing_rad"}; null for "never" and "—") instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Results CSVs; each row is labelled by its file name.
    #[arg(required = true)]
    pub results: Vec<PathBuf>,
}

impl CompareArgs {
    fn comparison(&self) -> Result<Comparison> {
        let target = match self.target.as_str() {
            "none" => None,
            text => Some(parse_point(text).map_or_else(|| Target::Columns(text.to_string()), Target::Point)),
        };
        if !(self.band > 0.0) {
            return Err(anyhow!("--band {}: expected degrees > 0", self.band));
        }
        let angles = match self.angles.strip_prefix("tip:") {
            Some(prefix) => Angles::FromTip(prefix.to_string()),
            None => match self.angles.split_once(',') {
                Some((x, y)) if !x.is_empty() && !y.is_empty() && !y.contains(',') => {
                    Angles::Columns([x.to_string(), y.to_string()])
                }
                _ => return Err(anyhow!("--angles {}: expected two columns X,Y or tip:PREFIX", self.angles)),
            },
        };
        Ok(Comparison { angles, position: self.position.clone(), target, band: self.band.to_radians() })
    }
}

/// `"x,y,z"` as three numbers, else None (a column prefix).
fn parse_point(text: &str) -> Option<[f64; 3]> {
    let numbers: Vec<f64> = text.split(',').map(|n| n.trim().parse().ok()).collect::<Option<_>>()?;
    numbers.try_into().ok()
}

/// One row of the JSON output (SI units).
#[derive(Debug, Serialize)]
struct Row {
    run: String,
    file: String,
    from_s: f64,
    settling_s: Option<f64>,
    distance_m: f64,
    rmse_m: Option<f64>,
    final_swing_rad: f64,
}

/// Computes and prints the metrics of every file; any unreadable file or missing column fails
/// the command before anything is printed.
pub fn compare(args: &CompareArgs) -> Result<()> {
    let comparison = args.comparison()?;
    let mut rows = Vec::new();
    for path in &args.results {
        let table = read_results(path)?;
        let m = metrics::run_metrics(&table, args.from, &comparison).map_err(|e| {
            let hint =
                if e.starts_with("no column") { "; name the columns with --angles, --position, --target" } else { "" };
            anyhow!("{}: {e}{hint}", path.display())
        })?;
        rows.push(row(path, args.from, &m));
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&rows)?)?;
        return Ok(());
    }
    writeln!(
        out,
        "{:<28} {:>12} {:>14} {:>10} {:>16}",
        "run", "settling (s)", "distance (m)", "RMSE (mm)", "last 10 s (deg)"
    )?;
    for r in &rows {
        writeln!(
            out,
            "{:<28} {:>12} {:>14.3} {:>10} {:>16.2}",
            r.run,
            r.settling_s.map_or("never".to_string(), |s| format!("{s:.1}")),
            r.distance_m,
            r.rmse_m.map_or("—".to_string(), |e| format!("{:.1}", e * 1e3)),
            r.final_swing_rad.to_degrees()
        )?;
    }
    Ok(())
}

fn row(path: &std::path::Path, from: f64, m: &RunMetrics) -> Row {
    Row {
        run: stem(path),
        file: path.display().to_string(),
        from_s: from,
        // A difference of two sample times: without its round-off (10.07, not 10.069999999999999).
        settling_s: m.settling.map(rounded),
        distance_m: m.distance,
        rmse_m: m.rmse,
        final_swing_rad: m.final_swing,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settling_times_print_without_round_off() {
        let m = RunMetrics { settling: Some(10.37 - 0.3), distance: 1.0, rmse: None, final_swing: 0.0 };
        let json = serde_json::to_string(&row(std::path::Path::new("a.csv"), 0.3, &m)).unwrap();
        assert!(json.contains(r#""settling_s":10.07,"#), "{json}");
    }
}
