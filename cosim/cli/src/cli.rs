//! The `crane-cosim` command line.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{Args, Parser, Subcommand};

use anyhow::{anyhow, Result};
use cosim_engine::export;
use cosim_engine::input::InputTable;
use cosim_engine::observer::FlushPolicy;
use cosim_engine::run::{run_system_file, RunOptions};
use cosim_engine::system::{AlgorithmKind, Overrides, System};
use crane_campaign::{figures, matrix, metrics, plot, report, run_campaign, CampaignOptions};
use fmu_import::fmi::LogEcho;
use fmu_import::fmu::{ExtractLimits, Fmu};
use fmu_import::slave::InstantiateOptions;

/// FMI 2.0 co-simulation master.
#[derive(Debug, Parser)]
#[command(name = "crane-cosim", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
    #[command(flatten)]
    pub limits: LimitArgs,
}

/// Limits on what opening one `.fmu` may unpack (against "zip bombs").
#[derive(Debug, Args)]
pub struct LimitArgs {
    /// Largest total size an FMU archive may unpack to, in bytes or with a K, M or G suffix
    /// (powers of 1024).
    #[arg(long, global = true, value_name = "SIZE", default_value = "2G", value_parser = parse_size)]
    pub max_unpacked_size: u64,
    /// Most entries an FMU archive may have.
    #[arg(long, global = true, value_name = "N", default_value_t = 10_000)]
    pub max_archive_entries: u64,
    /// Highest compression ratio (unpacked : packed) of any archive entry over 1 MiB.
    #[arg(long, global = true, value_name = "R", default_value_t = 200)]
    pub max_compression_ratio: u64,
}

impl LimitArgs {
    /// The extraction limits these options stand for.
    pub fn extract_limits(&self) -> ExtractLimits {
        ExtractLimits {
            max_unpacked_bytes: self.max_unpacked_size,
            max_entries: self.max_archive_entries,
            max_ratio: self.max_compression_ratio,
        }
    }
}

/// `123`, `64K`, `512M`, `2G` (binary multiples) as bytes.
fn parse_size(text: &str) -> Result<u64, String> {
    let text = text.trim();
    let (digits, shift) = match text.char_indices().last() {
        Some((at, 'K' | 'k')) => (&text[..at], 10),
        Some((at, 'M' | 'm')) => (&text[..at], 20),
        Some((at, 'G' | 'g')) => (&text[..at], 30),
        _ => (text, 0),
    };
    let number: u64 = digits.parse().map_err(|_| format!("{text:?} is not a size such as 4096, 512M or 4G"))?;
    number.checked_mul(1 << shift).ok_or_else(|| format!("{text:?} is too large"))
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run a system file, scenario file or SSP archive (.ssp) and record the results to CSV.
    Run(RunArgs),
    /// Write a system or scenario file (with its overrides applied) for other masters: an SSP 1.0
    /// archive (OMSimulator, libcosim, FMPy, crane-cosim) and/or a folder with the FMUs and an
    /// OspSystemStructure.xml (libcosim, cosim-cli).
    Export(ExportArgs),
    /// Print an FMU's model description and its variables.
    Info {
        /// The .fmu file.
        fmu: PathBuf,
    },
    /// Compare closed-loop results CSVs: settling, distance travelled, set-point RMSE.
    Compare {
        /// Metrics cover the time from here on (s), e.g. the release of the load.
        #[arg(long, default_value_t = 0.0)]
        from: f64,
        /// Results CSVs of systems/closed_loop.json or its scenarios.
        #[arg(required = true)]
        results: Vec<PathBuf>,
    },
    /// Run the thesis' test campaign (tests 001-104, truth and sensor feedback) in parallel and
    /// write per-run metrics, a report beside Tables 7.1-7.3 and figures.
    Campaign(CampaignArgs),
    /// Plot one column of one or more results CSVs against time (PNG).
    Plot {
        /// Column name, e.g. pendulum.theta_x.
        #[arg(long)]
        column: String,
        /// Multiply the values (e.g. 57.29578 for degrees).
        #[arg(long, default_value_t = 1.0)]
        scale: f64,
        /// Y-axis label.
        #[arg(long, default_value = "")]
        label: String,
        /// Output PNG.
        #[arg(short, long)]
        output: PathBuf,
        /// Results CSVs; each becomes a curve labelled by its file name.
        #[arg(required = true)]
        results: Vec<PathBuf>,
    },
}

/// Arguments of `crane-cosim run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The system file or scenario file (JSON), or an SSP archive (.ssp).
    pub system: PathBuf,
    /// Results CSV [default: out/SYSTEM.csv, SYSTEM being the system file name without extension].
    #[arg(short, long, value_name = "CSV")]
    pub output: Option<PathBuf>,
    /// Run summary JSON [default: the output path with .summary.json].
    #[arg(long, value_name = "JSON")]
    pub summary: Option<PathBuf>,
    /// Replace the system file's stop_time (s).
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub stop_time: Option<f64>,
    /// Replace the system file's step_size (s).
    #[arg(long, value_name = "H", allow_negative_numbers = true)]
    pub step_size: Option<f64>,
    /// Replace the system or scenario file's algorithm: gauss-seidel or jacobi.
    #[arg(long, value_name = "NAME")]
    pub algorithm: Option<AlgorithmKind>,
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
    /// Run even if the time grid has more than 10^9 steps or the CSV would exceed 16 GiB.
    #[arg(long)]
    pub force: bool,
    /// Print nothing on success.
    #[arg(short, long)]
    pub quiet: bool,
}

impl RunArgs {
    /// The options these arguments stand for.
    pub fn options(&self) -> Result<RunOptions> {
        let output = self.output.clone().unwrap_or_else(|| default_output(&self.system));
        let summary = self.summary.clone().unwrap_or_else(|| summary_path(&output));
        let interval = std::time::Duration::try_from_secs_f64(self.flush_interval)
            .map_err(|_| anyhow!("--flush-interval {}: expected a number of seconds >= 0", self.flush_interval))?;
        Ok(RunOptions {
            output,
            summary: Some(summary),
            overrides: Overrides { stop_time: self.stop_time, step_size: self.step_size, algorithm: self.algorithm },
            progress: !self.quiet,
            timing: self.timing,
            instantiate: InstantiateOptions {
                visible: false,
                logging_on: self.fmu_log,
                echo: if self.fmu_log { LogEcho::All } else { LogEcho::Warnings },
            },
            flush: FlushPolicy { rows: self.flush_rows.max(1), interval },
            interrupt: Some(crate::process::interrupt()),
            force: self.force,
        })
    }
}

/// Arguments of `crane-cosim export`.
#[derive(Debug, Args)]
#[command(group = clap::ArgGroup::new("format").required(true).multiple(true))]
pub struct ExportArgs {
    /// The system file or scenario file (JSON), or an SSP archive.
    pub system: PathBuf,
    /// Write an SSP 1.0 archive: SystemStructure.ssd and the FMUs under resources/.
    #[arg(long, value_name = "FILE.ssp", group = "format")]
    pub ssp: Option<PathBuf>,
    /// Write OspSystemStructure.xml and copies of the FMUs into this folder.
    #[arg(long, value_name = "DIR", group = "format")]
    pub osp: Option<PathBuf>,
    /// Replace the stop_time (s).
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub stop_time: Option<f64>,
    /// Replace the step_size (s).
    #[arg(long, value_name = "H", allow_negative_numbers = true)]
    pub step_size: Option<f64>,
    /// Replace the algorithm: gauss-seidel or jacobi (libcosim always steps Jacobi).
    #[arg(long, value_name = "NAME")]
    pub algorithm: Option<AlgorithmKind>,
}

/// Arguments of `crane-cosim campaign`.
#[derive(Debug, Args)]
pub struct CampaignArgs {
    /// The closed-loop system file the scenarios start from.
    #[arg(long, default_value = "systems/closed_loop.json")]
    pub system: PathBuf,
    /// Tests to run, e.g. "1-104" or "20,60,84,92".
    #[arg(long, default_value = "1-104")]
    pub tests: String,
    /// Feedback variants: 1 truth, 2 sensors with noise.
    #[arg(long, value_delimiter = ',', default_values_t = [1u8, 2])]
    pub variants: Vec<u8>,
    /// Worker threads (0: one per core).
    #[arg(short, long, default_value_t = 0)]
    pub jobs: usize,
    /// Output folder.
    #[arg(short, long, default_value = "out/campaign")]
    pub out: PathBuf,
    /// Keep every run's results CSV (by default only the runs drawn in the response figures).
    #[arg(long)]
    pub keep_results: bool,
    /// Start as the thesis' simulations did: filters at the identity (cf_init = 0) and no
    /// 10 s hold, so the tests include the initial estimation transient.
    #[arg(long)]
    pub thesis_init: bool,
    /// Print nothing but errors.
    #[arg(short, long)]
    pub quiet: bool,
}

/// `out/<system file stem>.csv`.
pub fn default_output(system: &Path) -> PathBuf {
    let stem = system.file_stem().map_or_else(|| "results".into(), |s| s.to_string_lossy().into_owned());
    Path::new("out").join(format!("{stem}.csv"))
}

/// `<output without extension>.summary.json`.
pub fn summary_path(output: &Path) -> PathBuf {
    output.with_extension("summary.json")
}

/// Executes a parsed command line.
pub fn execute(cli: &Cli) -> Result<()> {
    cli.limits.extract_limits().install();
    match &cli.command {
        Command::Info { fmu } => {
            let fmu = Fmu::open(fmu)?;
            write!(std::io::stdout().lock(), "{}", fmu_import::describe::describe(&fmu))?;
            Ok(())
        }
        Command::Compare { from, results } => compare(*from, results),
        Command::Plot { column, scale, label, output, results } => plot(column, *scale, label, output, results),
        Command::Campaign(args) => campaign(args),
        Command::Export(args) => export(args),
        Command::Run(args) => {
            let options = args.options()?;
            let summary = run_system_file(&args.system, &options)?;
            if !args.quiet {
                if let Some(termination) = &summary.termination {
                    println!("{termination}");
                }
                let factor = summary.real_time_factor.map_or(String::new(), |f| format!(", {f:.1}x real time"));
                writeln!(
                    std::io::stdout().lock(),
                    "completed {} steps to t = {:?} s in {:.3} s{factor}; {} rows written to {}",
                    summary.steps_completed,
                    summary.end_time.unwrap_or_default(),
                    summary.wall_time,
                    summary.rows_recorded,
                    options.output.display()
                )?;
            }
            Ok(())
        }
    }
}

fn export(args: &ExportArgs) -> Result<()> {
    let overrides = Overrides { stop_time: args.stop_time, step_size: args.step_size, algorithm: args.algorithm };
    // An archive being exported again provides its FMUs from its extraction folder.
    let (system, _archive) = System::load_keeping_archive(&args.system, &overrides)?;
    if let Some(path) = &args.ssp {
        export::ssp::write(&system, path)?;
        println!("wrote {}", path.display());
    }
    if let Some(dir) = &args.osp {
        println!("wrote {}", export::osp::write(&system, dir)?.display());
    }
    Ok(())
}

fn stem(path: &Path) -> String {
    path.file_stem().map_or_else(|| path.display().to_string(), |s| s.to_string_lossy().into_owned())
}

fn read_results(path: &Path) -> Result<InputTable> {
    InputTable::read(path).map_err(|e| anyhow!(e.to_string()))
}

fn compare(from: f64, results: &[PathBuf]) -> Result<()> {
    let mut out = std::io::stdout().lock();
    writeln!(
        out,
        "{:<28} {:>12} {:>14} {:>10} {:>16}",
        "run", "settling (s)", "distance (m)", "RMSE (mm)", "last 10 s (deg)"
    )?;
    for path in results {
        let metrics =
            metrics::run_metrics(&read_results(path)?, from).map_err(|e| anyhow!("{}: {e}", path.display()))?;
        let settling = metrics.settling.map_or("never".to_string(), |s| format!("{s:.1}"));
        writeln!(
            out,
            "{:<28} {:>12} {:>14.3} {:>10.1} {:>16.2}",
            stem(path),
            settling,
            metrics.distance,
            metrics.rmse * 1e3,
            metrics.final_swing.to_degrees()
        )?;
    }
    Ok(())
}

fn plot(column: &str, scale: f64, label: &str, output: &Path, results: &[PathBuf]) -> Result<()> {
    let mut series = Vec::new();
    for path in results {
        let table = read_results(path)?;
        let c = table.column(column).ok_or_else(|| anyhow!("{}: no column '{column}'", path.display()))?;
        let points = table.times.iter().zip(&table.columns[c]).map(|(t, v)| (*t, v * scale)).collect();
        series.push(plot::Series { label: stem(path), points });
    }
    plot::line_plot(output, column, label, &series).map_err(|e| anyhow!(e))
}

fn campaign(args: &CampaignArgs) -> Result<()> {
    let numbers = matrix::parse_selection(&args.tests).map_err(|e| anyhow!(e))?;
    let variants = args
        .variants
        .iter()
        .map(|&n| {
            matrix::Variant::from_number(n).ok_or_else(|| anyhow!("variant {n}: expected 1 (truth) or 2 (sensors)"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let tests: Vec<_> = matrix::tests().into_iter().filter(|t| numbers.contains(&t.number)).collect();
    let init = if args.thesis_init { matrix::Init::Thesis } else { matrix::Init::Held };
    let runs = matrix::runs(&tests, &variants, init);
    let options = CampaignOptions {
        system: args.system.clone(),
        out: args.out.clone(),
        jobs: args.jobs,
        keep_results: args.keep_results,
        progress: !args.quiet,
        interrupt: Some(crate::process::interrupt()),
    };
    let campaign = run_campaign(&runs, &options)?;
    let drawn = figures::draw_all(&args.out, &campaign).map_err(|e| anyhow!(e))?;
    report::write_files(&args.out, &campaign, &drawn).map_err(|e| anyhow!(e))?;
    for failure in campaign.failures() {
        eprintln!("error: {}", failure.error.as_deref().unwrap_or_default());
    }
    if !args.quiet {
        writeln!(
            std::io::stdout().lock(),
            "{} runs in {:.1} s on {} threads ({:.0}x real time overall); report: {}",
            campaign.results.len(),
            campaign.wall_time,
            campaign.jobs,
            campaign.real_time_factor(),
            args.out.join("report.md").display()
        )?;
    }
    match campaign.failures().count() {
        0 => Ok(()),
        n => Err(anyhow!(
            "{n} of {} runs failed (see above and {})",
            campaign.results.len(),
            args.out.join("report.md").display()
        )),
    }
}
