//! The `crane-cosim` command line.

use std::path::PathBuf;

use clap::{Args, CommandFactory, Parser, Subcommand};

use anyhow::Result;
use cosim_engine::export;
use cosim_engine::system::single::SingleFmu;
use cosim_engine::system::{System, SystemFiles};
use crane_app::Source;
use fmu_import::fmu::ExtractLimits;

use crate::commands::campaign::CampaignArgs;
use crate::commands::compare::CompareArgs;
use crate::commands::limits::LimitArgs;
use crate::commands::live::LiveArgs;
use crate::commands::plot::PlotArgs;
use crate::commands::run::{GridArgs, RunArgs};
use crate::commands::shell::{CompletionsArgs, ManArgs};
use crate::commands::sweep::SweepArgs;
use crate::commands::tune::TuneArgs;
use crate::commands::view::ViewArgs;

/// FMI 2.0 and 3.0 co-simulation master.
#[derive(Debug, Parser)]
#[command(name = "crane-cosim", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run a system file, scenario file, SSP archive (.ssp), OSP system structure (folder) or one
    /// FMU (.fmu) and record the results to CSV.
    Run(RunArgs),
    /// Write a system (with its overrides applied) for other importers: an SSP 1.0
    /// archive (OMSimulator, libcosim, FMPy, crane-cosim) and/or a folder with the FMUs and an
    /// OspSystemStructure.xml (libcosim, cosim-cli).
    Export(ExportArgs),
    /// Print an FMU's model description and its variables.
    Info(crate::commands::info::InfoArgs),
    /// Compare results CSVs: settling of a swing, distance travelled, set-point RMSE.
    Compare(CompareArgs),
    /// Run the thesis' test campaign (tests 001-104, truth and sensor feedback) in parallel and
    /// write per-run metrics, a report beside Tables 7.1-7.3 and figures.
    Campaign(CampaignArgs),
    /// Plot columns of results CSVs against time (PNG or SVG), in one figure or stacked panels.
    Plot(PlotArgs),
    /// Parameter studies over a scenario: plan the cases, run them (by index, shard or all),
    /// collect their metrics into one CSV.
    Sweep(SweepArgs),
    /// Tune controller parameters with CMA-ES over campaign tests (a tuning file names the
    /// parameters, bounds, objective and the training and held-out runs); resumable.
    Tune(TuneArgs),
    /// Write a run as one self-contained HTML page: the deck, crane, cable and load in 3D with
    /// the estimated load and set-point, a time slider and plots of the swing.
    View(ViewArgs),
    /// Run the closed loop at real time and show it live in the browser (127.0.0.1): the
    /// operator moves the load set-point, switches compensation, pauses, resets, records.
    Live(LiveArgs),
    /// Print a shell completion script (bash, zsh, fish, elvish, PowerShell).
    Completions(CompletionsArgs),
    /// Print the manual page, or write one per command into a folder (`-o DIR`).
    Man(ManArgs),
}

/// Arguments of `crane-cosim export`.
#[derive(Debug, Args)]
#[command(group = clap::ArgGroup::new("format").required(true).multiple(true))]
pub struct ExportArgs {
    /// The system file or scenario file (JSON), an SSP archive (.ssp), an OSP system structure
    /// (a folder holding OspSystemStructure.xml, or that file), or one FMU (.fmu) alone.
    pub system: PathBuf,
    /// Write an SSP 1.0 archive: SystemStructure.ssd and the FMUs under resources/.
    #[arg(long, value_name = "FILE.ssp", group = "format")]
    pub ssp: Option<PathBuf>,
    /// Write OspSystemStructure.xml and copies of the FMUs into this folder.
    #[arg(long, value_name = "DIR", group = "format")]
    pub osp: Option<PathBuf>,
    #[command(flatten)]
    pub grid: GridArgs,
    #[command(flatten)]
    pub limits: LimitArgs,
}

/// Executes a parsed command line.
pub fn execute(cli: &Cli) -> Result<()> {
    match &cli.command {
        Command::Info(args) => crate::commands::info::info(args, &args.limits.extract_limits()),
        Command::Compare(args) => crate::commands::compare::compare(args),
        Command::Plot(args) => crate::commands::plot::plot(args),
        Command::Campaign(args) => crate::commands::campaign::campaign(args, args.limits.extract_limits()),
        Command::Export(args) => export(args, args.limits.extract_limits()),
        Command::Run(args) => crate::commands::run::run(args, args.limits.extract_limits()),
        Command::Sweep(args) => crate::commands::sweep::sweep(args),
        Command::Tune(args) => crate::commands::tune::tune(args, args.limits.extract_limits()),
        Command::View(args) => crate::commands::view::view(args, args.limits.extract_limits()),
        Command::Live(args) => crate::commands::live::live(args, args.limits.extract_limits()),
        Command::Completions(args) => crate::commands::shell::completions(args, Cli::command()),
        Command::Man(args) => crate::commands::shell::man(args, Cli::command()),
    }
}

fn export(args: &ExportArgs, limits: ExtractLimits) -> Result<()> {
    let overrides = args.grid.grid().overrides();
    // An archive being exported again provides its FMUs from its extraction folder.
    let files = SystemFiles::new(limits);
    let (system, _archive) = if matches!(Source::of(&args.system), Source::Fmu(_)) {
        // One FMU alone, as `run` runs it.
        (System::load_fmu(&args.system, &SingleFmu::default(), &overrides, &files)?, None)
    } else {
        System::load_keeping_archive(&args.system, &overrides, &files)?
    };
    if let Some(path) = &args.ssp {
        export::ssp::write(&system, path)?;
        println!("wrote {}", path.display());
    }
    if let Some(dir) = &args.osp {
        println!("wrote {}", export::osp::write(&system, dir)?.display());
    }
    Ok(())
}
