//! `crane-cosim campaign`: the thesis' test campaign.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{anyhow, Result};
use clap::{Args, ValueEnum};
use cosim_engine::text::counted;
use crane_campaign::results::Campaign;
use crane_campaign::scale::Scale;
use crane_campaign::{figures, matrix, output, report, run_campaign, summary, CampaignOptions};
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

impl From<AttitudeFilterArg> for matrix::AttitudeFilter {
    fn from(arg: AttitudeFilterArg) -> Self {
        match arg {
            AttitudeFilterArg::Complementary => matrix::AttitudeFilter::Complementary,
            AttitudeFilterArg::Madgwick => matrix::AttitudeFilter::Madgwick,
        }
    }
}

pub fn campaign(args: &CampaignArgs, limits: ExtractLimits) -> Result<()> {
    let scale = Scale::from(args.scale);
    let numbers = matrix::parse_selection(args.tests.as_deref().unwrap_or("1-104")).map_err(|e| anyhow!(e))?;
    let variants = args
        .variants
        .iter()
        .map(|&n| {
            matrix::Variant::from_number(n)
                .ok_or_else(|| anyhow!("variant {n}: expected 1 (truth), 2 (sensors) or 3 (sensors and the EKF)"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let tests: Vec<_> = matrix::tests().into_iter().filter(|t| numbers.contains(&t.number)).collect();
    let init = if args.thesis_init { matrix::Init::Thesis } else { matrix::Init::Held };
    // The attitude filter is the sensor variants' (the truth variant reads no filter).
    let attitude = args.attitude_filter.into();
    let runs: Vec<_> = matrix::runs(&tests, &variants, init)
        .into_iter()
        .map(|run| if run.variant.sensors() { matrix::RunSpec { attitude, ..run } } else { run })
        .map(|run| matrix::RunSpec { scale, ..run })
        .collect();
    for run in &runs {
        matrix::supported(run).map_err(|e| anyhow!(e))?;
    }
    let system = match &args.system {
        Some(file) => file.clone(),
        None => default_system(scale.system_file())?,
    };
    if !args.quiet {
        super::announce_system(&system, limits);
    }
    let options = CampaignOptions {
        system,
        out: args.out.clone(),
        jobs: args.jobs,
        keep_results: args.keep_results,
        progress: !args.quiet,
        interrupt: Some(crate::process::interrupt()),
        start: start_values(args)?,
        limits,
    };
    let campaign = run_campaign(&runs, &options)?;
    let written = figures::draw_all(&args.out, &campaign)
        .and_then(|drawn| report::write_files(&args.out, &campaign, &drawn))
        .map_err(|e| anyhow!(e));
    // Listed also when a figure or the report failed: the next campaign may then clear them.
    output::seal(&args.out)?;
    written?;
    for failure in campaign.failures() {
        eprintln!("error: {}", crate::flags::name_flags(failure.error.as_deref().unwrap_or_default()));
    }
    if !args.quiet {
        writeln!(
            std::io::stdout().lock(),
            "{} in {:.1} s on {} ({:.0}x real time overall); report: {}",
            counted(campaign.results.len() as u64, "run"),
            campaign.wall_time,
            counted(campaign.jobs as u64, "thread"),
            campaign.real_time_factor(),
            args.out.join("report.md").display()
        )?;
    }
    let failed = campaign.failures().count();
    if failed > 0 {
        return Err(anyhow!(
            "{failed} of {} runs failed (see above and {})",
            campaign.results.len(),
            args.out.join("report.md").display()
        ));
    }
    if args.check {
        check_bands(&campaign, scale, &args.out.join("report.md"))?;
    }
    Ok(())
}

/// The extra start values: the --start-file scenario's, then --start's.
fn start_values(args: &CampaignArgs) -> Result<std::collections::BTreeMap<String, serde_json::Value>> {
    let mut start = std::collections::BTreeMap::new();
    if let Some(file) = &args.start_file {
        let text = fmu_import::file::read_regular_text(file, super::SCENARIO_SIZE_LIMIT)
            .map_err(|e| anyhow!("cannot read --start-file {}: {e}", file.display()))?;
        let scenario: cosim_engine::system::scenario::ScenarioSpec =
            cosim_engine::system::json::parse(&text, cosim_engine::system::FileKind::Scenario)
                .map_err(|e| anyhow!("--start-file {}:{}:{}: {e}", file.display(), e.line, e.column))?;
        start.extend(scenario.start);
    }
    start.extend(args.start.iter().cloned());
    Ok(start)
}

/// One error listing every band of docs/acceptance.md the campaign misses, or saying that the
/// selection judged none (a check that holds nothing must not pass).
fn check_bands(campaign: &Campaign, scale: Scale, report: &Path) -> Result<()> {
    let verdicts = summary::verdicts(&summary::changes(&campaign.results), scale);
    if verdicts.iter().all(|v| v.met().is_none()) {
        return Err(anyhow!(
            "--check: no acceptance band of docs/acceptance.md had data: the selection has no test pair for any \
             (see {}); select both runs of a pair, e.g. --tests 20,60",
            report.display()
        ));
    }
    let missed: Vec<String> = verdicts
        .iter()
        .filter(|v| v.met() == Some(false))
        .map(|v| {
            let (reduction, pairs) = v.reduction.unwrap_or_default();
            format!(
                "{}, {} ({}): {reduction:.1} % over {pairs} pairs, band {}",
                v.row.group.title(),
                v.row.metric.info().title,
                v.variant.number(),
                v.acceptance.describe()
            )
        })
        .collect();
    if missed.is_empty() {
        return Ok(());
    }
    Err(anyhow!(
        "{} acceptance band(s) of docs/acceptance.md not met (see {}):\n  {}",
        missed.len(),
        report.display(),
        missed.join("\n  ")
    ))
}

/// The system file `name` of `systems/`, looked for in this order: the working directory's
/// `systems/` (a checkout or a copy of one, whose own FMUs its system files name), the source
/// tree the binary was built from (`cargo build`, `cargo install --path`), and
/// `share/crane-cosim/systems/` next to the binary's `bin/` folder (an installed package).
pub(crate) fn default_system(name: &str) -> Result<PathBuf> {
    let mut candidates = vec![Path::new("systems").join(name)];
    candidates.push(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../systems").join(name));
    if let Some(prefix) = std::env::current_exe().ok().and_then(|exe| Some(exe.parent()?.parent()?.to_path_buf())) {
        candidates.push(prefix.join("share/crane-cosim/systems").join(name));
    }
    candidates.iter().find(|c| c.is_file()).cloned().ok_or_else(|| {
        let looked: Vec<String> = candidates.iter().map(|c| c.display().to_string()).collect();
        anyhow!("no closed-loop system file in {}: give one with --system FILE", looked.join(" or "))
    })
}
