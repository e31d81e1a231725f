//! Every name of each scale's [`CraneNames`] resolves in that scale's system file: the instance
//! exists and its FMU's model description has the variable; the rigging's hook in the closed
//! loop with the rigging.
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use cosim_engine::system::{Overrides, System, SystemFiles};
use crane_names::{split, Scale, RIGGING_HOOK};

fn load(file: &str) -> System {
    let file = common::workspace_root().join("systems").join(file);
    System::load(&file, &Overrides::default(), &SystemFiles::default())
        .unwrap_or_else(|e| panic!("{}: {e} (run `cargo xtask package` first)", file.display()))
}

/// The names of `names` that `system` does not have.
fn unresolved(system: &System, names: Vec<&'static str>) -> Vec<&'static str> {
    names
        .into_iter()
        .filter(|name| {
            let Some((instance, variable)) = split(name) else { return true };
            let found = system.instance_index(instance).map(|i| &system.instances[i]);
            found.is_none_or(|i| i.fmu.model_description().variable(variable).is_none())
        })
        .collect()
}

#[test]
fn every_name_of_each_scale_resolves_in_its_system_file() {
    for scale in Scale::ALL {
        let (names, system) = (scale.names(), load(scale.system_file()));
        assert_eq!(unresolved(&system, names.all()), Vec::<&str>::new(), "{scale:?}");
        let missing: Vec<_> = names.instances().into_iter().filter(|i| system.instance_index(i).is_none()).collect();
        assert_eq!(missing, Vec::<&str>::new(), "{scale:?}");
        // The controller is the instance of its mode.
        assert_eq!(split(names.mode).map(|(instance, _)| instance), Some(names.controller.0));
    }
}

#[test]
fn each_scale_has_its_own_controls_and_all_lists_them() {
    let (test, full) = (Scale::Test.names(), Scale::Full.names());
    assert!(test.test.is_some() && test.full.is_none() && full.full.is_some() && full.test.is_none());
    // all() is generated from the fields: the scale-specific ones are in it.
    assert!(test.all().contains(&"controller.feedback"));
    assert!(full.all().contains(&"knuckle_boom_controller.heave"));
    assert!(!test.all().contains(&"knuckle_boom_controller.heave"));
}

#[test]
fn the_rigging_hook_resolves_in_the_rigging_loop() {
    let system = load("closed_loop_rigging.json");
    assert_eq!(unresolved(&system, RIGGING_HOOK.axes.to_vec()), Vec::<&str>::new());
}

#[test]
fn a_misspelt_name_is_caught() {
    // The check above must be able to fail: a name the loop does not have is found unresolved.
    let system = load("closed_loop.json");
    assert_eq!(unresolved(&system, vec!["controller.sp.load.x", "controller.sp.load.w"]), ["controller.sp.load.w"]);
    assert_eq!(unresolved(&system, vec!["pendulum2.theta_x", "nodot"]), ["pendulum2.theta_x", "nodot"]);
}

#[test]
fn the_names_reach_python_as_json() {
    // The Python package reads the names as JSON: triples with their axes, instances as strings,
    // what a scale lacks as null.
    let json: serde_json::Value = serde_json::to_value(Scale::Full.names()).unwrap();
    assert_eq!(json["controller"], "knuckle_boom_controller");
    assert_eq!(json["tip"]["axes"][2], "knuckle_boom.tip.z");
    assert_eq!(json["test"], serde_json::Value::Null);
}
