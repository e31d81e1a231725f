//! What a campaign produced: one result per run and the detailed evaluations kept for figures.

use serde::Serialize;

use crate::matrix::RunSpec;
use crane_metrics::run::{Evaluation, Metrics};

/// Runs whose full evaluation (signals and fits) is kept for the response figures, in the
/// style of Figs. 7.2/7.3 (7.7–7.9): the 700 mm, −23° free and compensated responses.
pub const DETAILED: [&str; 4] = ["020-1", "060-1", "060-2", "092-2"];

/// The outcome of one run.
#[derive(Debug, Clone, Serialize)]
pub struct RunResult {
    /// The thesis' simulation label, e.g. `"020-1"` (test, variant).
    pub id: String,
    /// The test and variant it ran.
    pub run: RunSpec,
    /// None when the run or its evaluation failed (see `error`).
    pub metrics: Option<Metrics>,
    /// The error chain, when the run or its evaluation failed.
    pub error: Option<String>,
    /// Simulated time (s) and wall time of the simulation (s).
    pub simulated_time: f64,
    /// Wall-clock time of the simulation (s).
    pub wall_time: f64,
}

/// Everything a campaign produced.
#[derive(Debug)]
pub struct Campaign {
    /// In matrix order.
    pub results: Vec<RunResult>,
    /// Full evaluations of the [`DETAILED`] runs that ran.
    pub detailed: Vec<(String, Evaluation)>,
    /// Wall time of the whole campaign (s) and the worker threads used.
    pub wall_time: f64,
    /// Worker threads used.
    pub jobs: usize,
    /// The extra start values every run had ([`crate::CampaignOptions::start`]).
    pub start: std::collections::BTreeMap<String, serde_json::Value>,
    /// The closed-loop system file the runs started from ([`crate::CampaignOptions::system`]).
    pub system: std::path::PathBuf,
}

impl Campaign {
    /// Simulated seconds per wall-clock second over the whole campaign.
    pub fn real_time_factor(&self) -> f64 {
        self.results.iter().map(|r| r.simulated_time).sum::<f64>() / self.wall_time
    }

    pub fn failures(&self) -> impl Iterator<Item = &RunResult> {
        self.results.iter().filter(|r| r.error.is_some())
    }
}
