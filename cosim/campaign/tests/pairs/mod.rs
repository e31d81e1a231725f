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

/// Asserts that both runs of `pair` (crane-off twin first) completed and that the compensated one
/// reduces the θx time constant by more than `at_least` (a fraction), printing both under `label`.
pub fn assert_damped(pair: &[RunResult], label: &str, at_least: f64) {
    let [off, on] = [0, 1].map(|i| {
        let r = &pair[i];
        assert!(r.error.is_none(), "{}: {:?}", r.id, r.error);
        r.metrics.as_ref().and_then(|m| m.tau_theta_x).expect("a θx time constant")
    });
    let reduction = 1.0 - on / off;
    println!("{label}: τθx {off:.1} s → {on:.1} s, {:.1} %", 100.0 * reduction);
    assert!(reduction > at_least, "τθx reduced by only {:.1} %", 100.0 * reduction);
}
