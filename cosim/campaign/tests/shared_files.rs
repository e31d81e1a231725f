//! A campaign opens every FMU once and runs all its runs, on several threads, on the one loaded
//! library of each FMU: its metrics must be exactly those of runs that each open and load their
//! FMUs on their own (as every run did before the FMUs were shared).
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use crane_campaign::matrix::{runs, tests, Init, Variant};
use crane_campaign::{run_campaign, CampaignOptions};

#[test]
fn shared_fmus_give_the_metrics_of_fresh_loads() {
    // Compensated 700 mm release in still water, fixed set-point under ship profile 2 and
    // variable set-point under profile 1, all with noisy sensor feedback.
    let selected: Vec<_> = tests().into_iter().filter(|t| [60, 90, 102].contains(&t.number)).collect();
    let runs = runs(&selected, &[Variant::Sensors], Init::Held);
    assert_eq!(runs.len(), 3);
    let dir = tempfile::tempdir().expect("tempdir");
    let options = |folder: &str| CampaignOptions {
        system: common::workspace_root().join("systems/closed_loop.json"),
        out: dir.path().join(folder),
        jobs: 2,
        keep_results: false,
        progress: false,
        interrupt: None,
        start: Default::default(),
        limits: Default::default(),
    };

    let shared = run_campaign(&runs, &options("shared")).expect("campaign");
    for (run, shared) in runs.iter().zip(&shared.results) {
        let fresh = run_campaign(std::slice::from_ref(run), &options("fresh")).expect("campaign");
        assert_eq!(shared.id, fresh.results[0].id);
        assert!(shared.error.is_none(), "{:?}", shared.error);
        assert_eq!(shared.metrics, fresh.results[0].metrics, "{}", shared.id);
    }
}
