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
//! The 10 t AHC crane of the catalogue (cranes/ahc_10t.json) on profile 2's pick and place, the
//! pair 099/103 (docs/crane-description.md, "The full-scale campaign per crane"): on the rigid
//! hoist rope of systems/full_scale_ahc.json 103 loses its rope when the arm, saturated by the
//! roll at the far end of the move, reverses at full flow; on the elastic steel rope of
//! systems/full_scale_ahc_elastic_rope.json the rope goes slack and snaps taut again, the run
//! completes, and the set-point RMSE falls by 68 %.
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

fn profile_2_pick_and_place(system: &str) -> Vec<RunResult> {
    let runs: Vec<RunSpec> = tests()
        .into_iter()
        .filter(|t| [99, 103].contains(&t.number))
        .map(|t| RunSpec { scale: Scale::Full, ..RunSpec::new(t, Variant::Truth) })
        .collect();
    let crane = |instance: &str| (format!("{instance}.crane"), serde_json::Value::from("ahc_10t"));
    let start = BTreeMap::from([crane("knuckle_boom"), crane("knuckle_boom_controller")]);
    pairs::run(&common::workspace_root().join(system), &runs, start)
}

fn rmse(run: &RunResult) -> f64 {
    assert!(run.error.is_none(), "{}: {:?}", run.id, run.error);
    run.metrics.as_ref().map(|m| m.rmse).expect("a set-point RMSE")
}

#[test]
fn the_ahc_crane_completes_profile_2s_pick_and_place_on_an_elastic_rope_and_not_on_a_rigid_one() {
    let elastic = profile_2_pick_and_place("systems/full_scale_ahc_elastic_rope.json");
    let (off, on) = (rmse(&elastic[0]), rmse(&elastic[1]));
    let reduction = 1.0 - on / off;
    println!(
        "099-1 / 103-1 on ahc_10t, elastic rope: RMSE {:.1} mm → {:.1} mm, {:.1} %",
        off * 1e3,
        on * 1e3,
        100.0 * reduction
    );
    assert!(reduction > 0.6, "reduced by only {:.1} %", 100.0 * reduction);
    let rigid = profile_2_pick_and_place("systems/full_scale_ahc.json");
    let failure = rigid[1].error.clone().expect("on the rigid rope 103-1 loses its rope");
    assert!(failure.contains("slack"), "{failure}");
}
