//! Runs a few campaign runs into a temporary folder, for the tests that compare a test with its
//! crane-off twin on one system file.

use crane_campaign::matrix::RunSpec;
use crane_campaign::{run_campaign, CampaignOptions, RunResult};
use std::collections::BTreeMap;
use std::path::Path;

/// The results of `runs` on `system` with the extra start values `start`, in the runs' order.
pub fn run(system: &Path, runs: &[RunSpec], start: BTreeMap<String, serde_json::Value>) -> Vec<RunResult> {
    let dir = tempfile::tempdir().expect("tempdir");
    let options = CampaignOptions {
        system: system.to_path_buf(),
        out: dir.path().join("campaign"),
        jobs: 2,
        keep_results: false,
        progress: false,
        interrupt: None,
        start,
        limits: Default::default(),
    };
    run_campaign(runs, &options).expect("campaign").results
}
