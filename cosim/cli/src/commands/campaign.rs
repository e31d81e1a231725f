//! `crane-cosim campaign`: the thesis' test campaign.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{anyhow, Result};
use clap::{Args, ValueEnum};
use cosim_engine::text::counted;
use crane_app::campaign::{self, AttitudeFilter, CampaignRequest, Init, Scale};
use fmu_import::fmu::ExtractLimits;

/// Arguments of `crane-cosim campaign`.
#[derive(Debug, Args)]
pub struct CampaignArgs {
    /// The crane: the thesis' test-scale rig, or the full-scale hydraulic offshore crane with the
    /// matrix mapped to it (docs/full-scale.md; tests 1-104, variants 1 and 2).
    #[arg(long, value_enum, default_value_t = ScaleArg::Test)]
    pub scale: ScaleArg,
    /// The closed-loop system file the scenarios start from [default: systems/closed_loop.json,
    /// or systems/full_scale_ahc.json with --scale full, of the working directory if it has one,
    /// else of the source tree this binary was built in, else of share/crane-cosim/ beside its
    /// bin/ folder]. The file and its FMUs are printed before the runs start.
    #[arg(long, value_name = "FILE")]
    pub system: Option<PathBuf>,
    /// Tests to run, e.g. "1-104" or "20,60,84,92" [default: 1-104].
    #[arg(long)]
    pub tests: Option<String>,
    /// Feedback variants: 1 truth, 2 sensors with noise, 3 sensors with noise and the ship's
    /// surge/sway/heave from the controller's EKF instead of truth (e.g. "1,2,3").
    #[arg(long, value_delimiter = ',', default_values_t = [1u8, 2])]
    pub variants: Vec<u8>,
    /// Attitude estimator of the sensor variants (2, 3): the thesis' complementary filter or
    /// Madgwick's gradient-descent filter.
    #[arg(long, value_enum, default_value_t = AttitudeFilterArg::Complementary)]
    pub attitude_filter: AttitudeFilterArg,
    /// Give every run this start value on top of the system file's (instance.variable=VALUE,
    /// VALUE as for `run --start`), e.g. controller.encoder.relative=false; values the test matrix
    /// sets itself are refused. Repeatable.
    #[arg(long, value_name = "NAME=VALUE", value_parser = super::run::parse_start)]
    pub start: Vec<(String, serde_json::Value)>,
    /// The full-scale crane's description (docs/crane-description.md): a catalogue name
    /// (osp_derived, osp_test_crane, ahc_10t) or a JSON file; the crane and its controller both
    /// get it. Needs --scale full.
    #[arg(long, value_name = "NAME|FILE")]
    pub crane: Option<String>,
    /// Give every run the start values of this scenario file's "start" (e.g. the best.json of
    /// `crane-cosim tune`), before those of --start.
    #[arg(long, value_name = "FILE")]
    pub start_file: Option<PathBuf>,
    /// Worker threads (0: one per core).
    #[arg(short, long, default_value_t = 0)]
    pub jobs: usize,
    /// Output folder: new, empty, or one a campaign wrote (its campaign-files.json lists what it
    /// wrote; only those files are replaced, and a folder holding any other file is refused).
    #[arg(short, long = "output", visible_alias = "out", value_name = "DIR", default_value = "out/campaign")]
    pub out: PathBuf,
    /// Keep every run's results CSV (by default only the runs drawn in the response figures).
    #[arg(long)]
    pub keep_results: bool,
    /// Start as the thesis' simulations did: filters at the identity (cf_init = 0) and no
    /// 10 s hold, so the tests include the initial estimation transient.
    #[arg(long)]
    pub thesis_init: bool,
    /// Exit with an error when a band of docs/acceptance.md is not met (bands the selection has
    /// no test pair for are not judged), or when no band could be judged at all; the report is
    /// written either way.
    #[arg(long)]
    pub check: bool,
    /// Print nothing but errors.
    #[arg(short, long)]
    pub quiet: bool,
    #[command(flatten)]
    pub limits: super::limits::LimitArgs,
}

/// `--scale`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ScaleArg {
    Test,
    Full,
}

impl From<ScaleArg> for Scale {
    fn from(arg: ScaleArg) -> Self {
        match arg {
            ScaleArg::Test => Scale::Test,
            ScaleArg::Full => Scale::Full,
        }
    }
}

/// `--attitude-filter`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AttitudeFilterArg {
    Complementary,
    Madgwick,
}

impl From<AttitudeFilterArg> for AttitudeFilter {
    fn from(arg: AttitudeFilterArg) -> Self {
        match arg {
            AttitudeFilterArg::Complementary => AttitudeFilter::Complementary,
            AttitudeFilterArg::Madgwick => AttitudeFilter::Madgwick,
        }
    }
}

impl CampaignArgs {
    /// The campaign these arguments ask for.
    pub fn request(&self, limits: ExtractLimits) -> CampaignRequest {
        CampaignRequest {
            scale: self.scale.into(),
            system: self.system.clone(),
            tests: self.tests.clone().unwrap_or_else(|| "1-104".into()),
            variants: self.variants.clone(),
            attitude_filter: self.attitude_filter.into(),
            init: if self.thesis_init { Init::Thesis } else { Init::Held },
            start: self.start.clone(),
            start_file: self.start_file.clone(),
            crane: self.crane.clone(),
            jobs: self.jobs,
            output: self.out.clone(),
            keep_results: self.keep_results,
            progress: !self.quiet,
            interrupt: Some(crate::process::interrupt()),
            limits,
        }
    }
}

pub fn campaign(args: &CampaignArgs, limits: ExtractLimits) -> Result<()> {
    let request = args.request(limits);
    let prepared = campaign::prepare(&request)?;
    if !args.quiet {
        super::show(&prepared.notices());
    }
    let outcome = prepared.run()?;
    for failure in outcome.campaign.failures() {
        eprintln!("error: {}", crate::flags::name_flags(failure.error.as_deref().unwrap_or_default()));
    }
    let campaign = &outcome.campaign;
    if !args.quiet {
        writeln!(
            std::io::stdout().lock(),
            "{} in {:.1} s on {} ({:.0}x real time overall); report: {}",
            counted(campaign.results.len() as u64, "run"),
            campaign.wall_time,
            counted(campaign.jobs as u64, "thread"),
            campaign.real_time_factor(),
            outcome.report.display()
        )?;
    }
    outcome.all_completed().map_err(|e| anyhow!(e))?;
    if args.check {
        outcome.check().map_err(|e| anyhow!(e))?;
    }
    Ok(())
}
