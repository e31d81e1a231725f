//! The controller's setting for the hook–load mode (docs/rigging.md, "A controller setting for
//! the second mode"): the thesis rig with a 0.2 m sling between hook and load and the load IMU on
//! the load (systems/closed_loop_rigging.json, whose controller knows the sling).
//!
//! Test 059 (a 23° θx release on 1 m of hoist rope, compensated, sensor feedback) against its
//! crane-off twin 019: with the notch the compensation damps the swing as on the single pendulum;
//! without it (ζ = 0) the delta law feeds the hook–load mode back until the hoist rope's angle runs
//! away and the run ends in an error.
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

mod pairs;

use crane_campaign::matrix::{runs, tests, Init, Variant};
use crane_campaign::RunResult;
use std::collections::BTreeMap;

fn run_pair(start: BTreeMap<String, serde_json::Value>) -> Vec<RunResult> {
    let selected: Vec<_> = tests().into_iter().filter(|t| [19, 59].contains(&t.number)).collect();
    let runs = runs(&selected, &[Variant::Sensors], Init::Held);
    pairs::run(&common::workspace_root().join("systems/closed_loop_rigging.json"), &runs, start)
}

#[test]
fn the_hook_load_notch_keeps_the_compensated_release_stable_and_damped() {
    let notched = run_pair(BTreeMap::new());
    // The single pendulum's pair reduces τθx by 87 % (docs/rigging.md); the Table 7.1 band is 85 %.
    pairs::assert_damped(&notched, "019-2 / 059-2 with the notch", 0.85);

    let unnotched = run_pair(BTreeMap::from([("controller.sling.notch_damping".to_string(), 0.0.into())]));
    let failure = unnotched[1].error.as_deref().expect("without the notch 059-2 fails");
    assert!(failure.contains("singularity") || failure.contains("slack"), "{failure}");
}
