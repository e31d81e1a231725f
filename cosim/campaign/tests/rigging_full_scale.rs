//! The full-scale crane with a hook block and a sling (docs/rigging.md, "At full scale"): a
//! 300 kg hook and the 5 t load on a rigid 3 m sling below 17.5 m of hoist rope
//! (systems/full_scale_ahc_rigging.json, whose controller knows the sling).
//!
//! Test 060 (a 23° θx release, world-frame compensation with the winch's heave compensation,
//! truth feedback) against its crane-off twin 020:
//! - with the controller's setting for the sling (a notch at the hook–load mode before the
//!   anti-sway law, and the spool ramp over about that mode's period) the release is damped;
//! - with the controller as it is (no notch, the default 0.4 s ramp) the anti-sway law drives the
//!   hook–load mode until the rigid hoist rope's tension turns negative and the run ends in an
//!   error.
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

mod pairs;

use crane_campaign::matrix::{tests, RunSpec, Variant};
use crane_campaign::scale::Scale;
use crane_campaign::RunResult;
use std::collections::BTreeMap;

fn run_pair(start: BTreeMap<String, serde_json::Value>) -> Vec<RunResult> {
    let runs: Vec<RunSpec> = tests()
        .into_iter()
        .filter(|t| [20, 60].contains(&t.number))
        .map(|t| RunSpec { scale: Scale::Full, ..RunSpec::new(t, Variant::Truth) })
        .collect();
    pairs::run(&common::workspace_root().join("systems/full_scale_ahc_rigging.json"), &runs, start)
}

#[test]
fn the_sling_setting_damps_the_full_scale_release_that_the_single_pendulum_law_loses() {
    let set = run_pair(BTreeMap::new());
    // The single pendulum's pair: 72.7 s → 28.2 s (61 %) with the same ramp, 25.7 s (65 %) with the
    // default one (docs/rigging.md).
    pairs::assert_damped(&set, "020-1 / 060-1 with the sling setting", 0.5);

    let as_is = BTreeMap::from([
        ("knuckle_boom_controller.sling.length".to_string(), 0.0.into()),
        ("knuckle_boom_controller.spool_rate".to_string(), 5.0.into()),
    ]);
    let failure = run_pair(as_is)[1].error.clone().expect("with the controller as it is 060-1 fails");
    assert!(failure.contains("slack"), "{failure}");
}
