//! `crane-cosim run`: a system file, scenario file, SSP archive or one FMU.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{anyhow, Result};
use clap::Args;
use cosim_engine::observer::FlushPolicy;
use cosim_engine::summary::RunSummary;
use cosim_engine::system::AlgorithmKind;
use cosim_engine::text::{counted, Decimal};
use crane_app::run::{self, default_output, summary_path, to_stdout, FileOutput, Grid, RunRequest};
use fmu_import::fmu::ExtractLimits;

/// Arguments of `crane-cosim run`.
// The field comments are the help text, which writes placeholders as <name>, not HTML.
#[allow(rustdoc::invalid_html_tags)]
#[derive(Debug, Args)]
#[command(after_help = "Examples:\n  \
    crane-cosim run systems/pendulum_free_decay.json -o out/decay.csv\n  \
    crane-cosim run scenarios/demo_still_off.json --start pendulum.theta_x0=-0.2\n  \
    crane-cosim run out/still_osp --stop-time 20   (a folder written by export --osp)\n  \
    crane-cosim run target/fmu/pendulum.fmu --start theta_x0=-0.4 --stop-time 60 --record 'theta_*' --record 'load.*'")]
pub struct RunArgs {
    /// The system file or scenario file (JSON), an SSP archive (.ssp), an OSP system structure (a
    /// folder holding OspSystemStructure.xml, or that file; it has no stop time: give
    /// --stop-time), or one FMU (.fmu) to run alone with its default experiment (its instance is named after the file: pendulum.fmu
    /// gives columns pendulum.theta_x, ...).
    pub system: PathBuf,
    /// Results CSV (Parquet when the name ends in .parquet), or - for standard output (then messages go to standard error and no summary
    /// is written unless --summary names one) [default: out/SYSTEM.csv, SYSTEM being the file name
    /// without extension].
    #[arg(short, long, value_name = "CSV")]
    pub output: Option<PathBuf>,
    /// Run summary JSON, with the recorded columns and their units [default: the output path with
    /// .summary.json].
    #[arg(long, value_name = "JSON")]
    pub summary: Option<PathBuf>,
    /// Set a start value, replacing the file's: instance.variable=VALUE for systems, scenarios and
    /// archives, variable=VALUE (or instance.variable=VALUE, as its columns are named) for an .fmu.
    /// VALUE is read as JSON when it is a number, true,
    /// false or a "quoted string", else taken as a string; {"path":"x.csv"} is a path relative to
    /// the working directory, passed to the FMU as an absolute path. Repeatable.
    #[arg(long, value_name = "NAME=VALUE", value_parser = parse_start)]
    pub start: Vec<(String, serde_json::Value)>,
    #[command(flatten)]
    pub grid: GridArgs,
    /// Feed inputs from a CSV with header time,<input>,... (for an .fmu) or
    /// time,<instance>.<input>,... (for a system, scenario or archive: inputs that no connection
    /// or inputs file of the file feeds); values are interpolated linearly and their slopes passed
    /// as input derivatives (unless --no-input-derivatives; for a file, where its
    /// input_derivatives says so); after its last row, its last values are held. Repeatable.
    #[arg(long, value_name = "CSV")]
    pub input: Vec<PathBuf>,
    /// Pass no input derivatives (slopes of the inputs files), also where the file asks for them:
    /// how the FMUs' reference results (target/fmu/<model>_ref.csv) are made.
    #[arg(long)]
    pub no_input_derivatives: bool,
    /// Record the variable of this name, or the outputs and locals matching this pattern (* any
    /// characters, ? one character): variable names for an .fmu (replacing its default, every
    /// output), instance.variable for a file (added after the file's recorded columns).
    /// Repeatable.
    #[arg(long, value_name = "PATTERN")]
    pub record: Vec<String>,
    /// Switch FMU debug logging on and print every FMU log message.
    #[arg(long)]
    pub fmu_log: bool,
    /// Measure wall time inside each instance's fmi2DoStep and get/set calls and in recording,
    /// and write it to the summary as "timing": {"steps", "total_s", "recording_s", "instances":
    /// [{"name", "do_step_s", "get_set_s"}]} (seconds).
    #[arg(long)]
    pub timing: bool,
    /// Write recorded rows to the CSV at least every N rows (and at the end).
    #[arg(long, value_name = "N", default_value_t = FlushPolicy::default().rows)]
    pub flush_rows: u64,
    /// Write recorded rows to the CSV at least every S seconds of wall time.
    #[arg(long, value_name = "S", default_value_t = FlushPolicy::default().interval.as_secs_f64())]
    pub flush_interval: f64,
    /// End the run (exit status 1, computed rows and summary written) when one FMU call
    /// (fmi2DoStep, initialization, ...) does not return within S seconds of wall time.
    #[arg(long, value_name = "S")]
    pub step_timeout: Option<f64>,
    /// Run even if the time grid has more than 10^9 steps or the CSV would exceed 16 GiB.
    #[arg(long)]
    pub force: bool,
    /// Print nothing on success.
    #[arg(short, long)]
    pub quiet: bool,
    #[command(flatten)]
    pub limits: super::limits::LimitArgs,
}

/// The time grid and algorithm options shared by the commands that run or export a system.
#[derive(Debug, Args)]
pub struct GridArgs {
    /// Replace the stop time (s) of the file or of the FMU's default experiment (required for an
    /// OSP system structure, which has none).
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub stop_time: Option<f64>,
    /// Replace the communication step size (s) of the file or of the FMU's default experiment.
    #[arg(long, value_name = "H", allow_negative_numbers = true, value_parser = positive_seconds)]
    pub step_size: Option<f64>,
    /// Replace the algorithm: gauss-seidel or jacobi (libcosim always steps Jacobi).
    #[arg(long, value_name = "NAME")]
    pub algorithm: Option<AlgorithmKind>,
    /// Under Jacobi, pass FMUs that can interpolate inputs the slope of each connected input from
    /// the last two communication points (`extrapolate_inputs`; libcosim passes none).
    #[arg(long)]
    pub extrapolate_inputs: bool,
    /// Replace the recording interval (s) of the file, a whole multiple of the step size
    /// [default: the file's, else every step].
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true, value_parser = positive_seconds)]
    pub record_interval: Option<f64>,
}

/// A duration option's value: a finite number of seconds > 0, refused in the option's own name
/// (clap puts it in front) rather than as a field of the system file it replaces.
fn positive_seconds(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(seconds) if seconds > 0.0 && seconds.is_finite() => Ok(seconds),
        Ok(_) => Err("expected a finite number of seconds > 0".into()),
        Err(_) => Err("expected a number of seconds, e.g. 0.01".into()),
    }
}

impl GridArgs {
    /// The replacements these options stand for.
    pub fn grid(&self) -> Grid {
        Grid {
            stop_time: self.stop_time,
            step_size: self.step_size,
            algorithm: self.algorithm,
            extrapolate_inputs: self.extrapolate_inputs,
            record_interval: self.record_interval,
        }
    }
}

/// `NAME=VALUE` with VALUE as JSON if it parses as JSON, else as a string.
pub(crate) fn parse_start(text: &str) -> Result<(String, serde_json::Value), String> {
    let (name, value) = text.split_once('=').ok_or_else(|| format!("{text:?}: expected NAME=VALUE"))?;
    if name.is_empty() {
        return Err(format!("{text:?}: the name before '=' is empty"));
    }
    let value = serde_json::from_str(value).unwrap_or_else(|_| serde_json::Value::String(value.to_string()));
    Ok((name.to_string(), value))
}

impl RunArgs {
    /// The run these arguments ask for, archives opened within `limits`.
    pub fn request(&self, limits: ExtractLimits) -> RunRequest {
        RunRequest {
            start: self.start.clone(),
            grid: self.grid.grid(),
            record: self.record.clone(),
            inputs: self.input.clone(),
            no_input_derivatives: self.no_input_derivatives,
            force: self.force,
            limits,
            ..RunRequest::new(&self.system)
        }
    }

    /// Where the results go and what the run shows while it runs.
    pub fn file_output(&self) -> Result<FileOutput> {
        let output = self.output.clone().unwrap_or_else(|| default_output(&self.system));
        let summary = self.summary.clone().or_else(|| (!to_stdout(&output)).then(|| summary_path(&output)));
        let interval = std::time::Duration::try_from_secs_f64(self.flush_interval)
            .map_err(|_| anyhow!("--flush-interval {}: expected a number of seconds >= 0", self.flush_interval))?;
        if let Some(limit) = self.step_timeout {
            let limit = std::time::Duration::try_from_secs_f64(limit)
                .ok()
                .filter(|limit| !limit.is_zero())
                .ok_or_else(|| anyhow!("--step-timeout {limit}: expected a number of seconds > 0"))?;
            crate::process::set_step_timeout(limit);
        }
        Ok(FileOutput {
            output,
            summary,
            progress: !self.quiet,
            timing: self.timing,
            fmu_log: self.fmu_log,
            flush: FlushPolicy { rows: self.flush_rows.max(1), interval },
            interrupt: Some(crate::process::interrupt()),
        })
    }
}

/// Runs the file and prints what was done.
pub fn run(args: &RunArgs, limits: ExtractLimits) -> Result<()> {
    let output = args.file_output()?;
    let loaded = run::load(&args.request(limits));
    super::show(&loaded.notices());
    let summary = loaded.to_file(&output)?;
    if !args.quiet {
        print_done(&summary, &output.output)?;
    }
    Ok(())
}

/// What the run did, on standard output, or on standard error when the results went there.
fn print_done(summary: &RunSummary, output: &Path) -> Result<()> {
    let mut message = String::new();
    if let Some(termination) = &summary.termination {
        message.push_str(&format!("{termination}\n"));
    }
    let factor = summary.real_time_factor.map_or(String::new(), |f| format!(", {f:.1}x real time"));
    // 2 − 2·0.7 s reads 0.6 s, not 0.6000000000000001 s.
    let shortened = summary
        .shortened_last_step
        .map_or(String::new(), |last| format!(" (last step shortened to {} s)", Decimal(last)));
    let written_to = if to_stdout(output) { "standard output".to_string() } else { output.display().to_string() };
    message.push_str(&format!(
        "completed {} to t = {} s{shortened} in {:.3} s{factor}; {} written to {written_to}\n",
        counted(summary.steps_completed, "step"),
        Decimal(summary.end_time.unwrap_or_default()),
        summary.wall_time,
        counted(summary.rows_recorded, "row"),
    ));
    if to_stdout(output) {
        std::io::stderr().lock().write_all(message.as_bytes())?;
    } else {
        std::io::stdout().lock().write_all(message.as_bytes())?;
    }
    Ok(())
}
