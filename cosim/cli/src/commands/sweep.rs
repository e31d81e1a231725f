//! `crane-cosim sweep`: parameter studies (plan, run, collect); see docs/sweeps.md.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{anyhow, Context, Result};
use clap::{Args, Subcommand, ValueEnum};
use crane_app::sweep::{self, collect, ImageFormat, Selection, SweepRequest, MAX_CASES};
use fmu_import::fmu::ExtractLimits;

/// Arguments of `crane-cosim sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    #[command(subcommand)]
    pub command: SweepCommand,
}

#[derive(Debug, Subcommand)]
pub enum SweepCommand {
    /// Print (or write) the numbered cases of a study: case id, seed, parameter values.
    Plan {
        /// The study file (JSON).
        study: PathBuf,
        /// Write the cases to this CSV file instead of printing them.
        #[arg(short, long, value_name = "FILE")]
        output: Option<PathBuf>,
        /// Refuse a study planning more cases than this.
        #[arg(long, value_name = "N", default_value_t = MAX_CASES)]
        max_cases: usize,
    },
    /// Run a study's cases not done yet: one (--case-index, or SLURM_ARRAY_TASK_ID or
    /// JOB_COMPLETION_INDEX when set), a shard (--shard i/N), or all of them.
    Run(RunArgs),
    /// Merge the case results of an output folder into DIR/results.csv and DIR/results.parquet,
    /// draw summary plots into DIR/plots/ and refresh DIR/manifest.json.
    Collect {
        /// The output folder of `sweep run`.
        dir: PathBuf,
        /// Format of the plots (each metric against each parameter, a histogram per metric).
        #[arg(long, value_enum, default_value_t = PlotFormat::Png)]
        plots: PlotFormat,
    },
}

/// `sweep collect --plots`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PlotFormat {
    Png,
    Svg,
    /// No plots.
    None,
}

/// Arguments of `crane-cosim sweep run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The study file (JSON).
    pub study: PathBuf,
    /// Output folder.
    #[arg(short, long = "output", visible_alias = "out", value_name = "DIR")]
    pub out: PathBuf,
    /// Run only the case with this index (0-based).
    #[arg(long, value_name = "I", conflicts_with = "shard")]
    pub case_index: Option<usize>,
    /// Run only the cases whose index is i modulo N (0 ≤ i < N).
    #[arg(long, value_name = "i/N", value_parser = parse_shard)]
    pub shard: Option<(usize, usize)>,
    /// Worker threads (0: one per core).
    #[arg(short, long, default_value_t = 0)]
    pub jobs: usize,
    /// Print nothing but errors.
    #[arg(short, long)]
    pub quiet: bool,
    /// Refuse a study planning more cases than this.
    #[arg(long, value_name = "N", default_value_t = MAX_CASES)]
    pub max_cases: usize,
    #[command(flatten)]
    pub limits: super::limits::LimitArgs,
}

/// The array-job index variables read when neither --case-index nor --shard is given.
const INDEX_VARIABLES: [&str; 2] = ["SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"];

pub fn sweep(args: &SweepArgs) -> Result<()> {
    match &args.command {
        SweepCommand::Plan { study, output, max_cases } => print_plan(study, output.as_deref(), *max_cases),
        SweepCommand::Run(args) => run(args, args.limits.extract_limits()),
        SweepCommand::Collect { dir, plots } => print_collect(dir, *plots),
    }
}

fn print_collect(dir: &Path, plots: PlotFormat) -> Result<()> {
    let format = match plots {
        PlotFormat::Png => Some(ImageFormat::Png),
        PlotFormat::Svg => Some(ImageFormat::Svg),
        PlotFormat::None => None,
    };
    let collection = collect(dir, format)?;
    println!("{}", collection.parquet.display());
    if format.is_some() {
        println!("{} plots in {}", collection.plots.len(), dir.join("plots").display());
    }
    let counts = collection.counts;
    println!(
        "{}: {} done, {} failed, {} pending",
        collection.csv.display(),
        counts.done,
        counts.failed,
        counts.pending
    );
    Ok(())
}

fn print_plan(study_file: &Path, output: Option<&Path>, max_cases: usize) -> Result<()> {
    let text = sweep::plan_csv(study_file, max_cases)?;
    match output {
        Some(file) => std::fs::write(file, text).with_context(|| format!("cannot write {}", file.display())),
        None => Ok(std::io::stdout().lock().write_all(text.as_bytes())?),
    }
}

fn run(args: &RunArgs, limits: ExtractLimits) -> Result<()> {
    let request = SweepRequest {
        selection: selection(args)?,
        jobs: args.jobs,
        max_cases: args.max_cases,
        progress: !args.quiet,
        interrupt: Some(crate::process::interrupt()),
        limits,
        ..SweepRequest::new(args.study.clone(), args.out.clone())
    };
    let prepared = sweep::prepare(&request)?;
    if !args.quiet {
        super::show(&prepared.notices());
    }
    let count = prepared.run()?;
    if !args.quiet {
        println!(
            "{} done, {} failed, {} already done; manifest: {}",
            count.done,
            count.failed,
            count.skipped,
            args.out.join("manifest.json").display()
        );
    }
    match count.failed {
        0 => Ok(()),
        n => Err(anyhow!("{n} of {} cases run failed (see {})", count.done + n, args.out.join("cases").display())),
    }
}

/// The options' selection, else an array job's index from the environment, else all cases.
fn selection(args: &RunArgs) -> Result<Selection> {
    if let Some(index) = args.case_index {
        return Ok(Selection::Index(index));
    }
    if let Some((index, count)) = args.shard {
        return Ok(Selection::Shard { index, count });
    }
    for variable in INDEX_VARIABLES {
        if let Ok(value) = std::env::var(variable) {
            let index = value.trim().parse().map_err(|_| anyhow!("{variable}={value:?} is not a case index"))?;
            return Ok(Selection::Index(index));
        }
    }
    Ok(Selection::All)
}

/// `i/N` → (i, N).
fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let parsed = text.split_once('/').and_then(|(i, n)| Some((i.trim().parse().ok()?, n.trim().parse().ok()?)));
    match parsed {
        Some((i, n)) if i < n => Ok((i, n)),
        _ => Err(format!("{text:?}: expected i/N with 0 ≤ i < N, e.g. 0/4")),
    }
}
