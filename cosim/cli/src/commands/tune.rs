//! `crane-cosim tune`: CMA-ES over controller parameters, scored by the campaign (docs/tuning.md).

use std::io::Write;
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use crane_campaign::scale::Scale;
use crane_tune::{tune as run_tuning, Step, StepResult, TuneOptions};
use fmu_import::fmu::ExtractLimits;

/// Arguments of `crane-cosim tune`.
#[derive(Debug, Args)]
pub struct TuneArgs {
    /// The tuning file (JSON, docs/tuning.md).
    pub tuning: PathBuf,
    /// Output folder: new, empty, or one this tuning wrote (the run resumes where it stopped).
    #[arg(short, long, value_name = "DIR", default_value = "out/tune")]
    pub output: PathBuf,
    /// Worker threads (0: one per core).
    #[arg(short, long, default_value_t = 0)]
    pub jobs: usize,
    /// Only run the references if missing and print the next generation's candidates not yet
    /// evaluated as JSON ({"generation": G, "candidates": [...]}, or {"finished": true}), for
    /// an external scheduler (tools/ray/tune_ray.py).
    #[arg(long, conflicts_with = "candidate")]
    pub ask: bool,
    /// Evaluate only this candidate of the current generation (an id printed by --ask, e.g.
    /// g003-k05) and write its file.
    #[arg(long, value_name = "ID")]
    pub candidate: Option<String>,
    /// Print nothing but errors.
    #[arg(short, long)]
    pub quiet: bool,
    #[command(flatten)]
    pub limits: super::limits::LimitArgs,
}

pub fn tune(args: &TuneArgs, limits: ExtractLimits) -> Result<()> {
    let default_system = super::campaign::default_system(Scale::Test.system_file())?;
    let options = TuneOptions {
        tuning_file: args.tuning.clone(),
        default_system,
        out: args.output.clone(),
        jobs: args.jobs,
        progress: !args.quiet && !args.ask && args.candidate.is_none(),
        interrupt: Some(crate::process::interrupt()),
        limits,
    };
    let step = match (&args.candidate, args.ask) {
        (Some(id), _) => Step::Candidate(id.clone()),
        (None, true) => Step::Ask,
        (None, false) => Step::All,
    };
    let mut out = std::io::stdout().lock();
    match run_tuning(&options, &step)? {
        StepResult::Asked { generation, candidates } => {
            writeln!(out, "{}", serde_json::json!({ "generation": generation, "candidates": candidates }))?;
        }
        StepResult::Finished => writeln!(out, "{}", serde_json::json!({ "finished": true }))?,
        StepResult::Evaluated(candidate) if !args.quiet => {
            writeln!(out, "{}: objective {:.6}", candidate.id, candidate.objective)?;
        }
        StepResult::Evaluated(_) => {}
        StepResult::Done(summary) if !args.quiet => {
            writeln!(
                out,
                "{} candidates in {} generations ({:.1} s); best {}: objective {:.4} -> {:.4} on the training runs \
                 ({:+.1} %), {:.4} -> {:.4} held out ({:+.1} %)",
                summary.evaluations,
                summary.generations,
                summary.wall_time,
                summary.best,
                summary.training[0].objective,
                summary.training[1].objective,
                -summary.improvement[0],
                summary.held_out[0].objective,
                summary.held_out[1].objective,
                -summary.improvement[1],
            )?;
            for (name, start, best) in &summary.parameters {
                writeln!(out, "  {name}: {start} -> {best}")?;
            }
            writeln!(out, "report: {}", args.output.join("report.md").display())?;
        }
        StepResult::Done(_) => {}
    }
    Ok(())
}
