//! Every name of [`ClosedLoopNames::TEST_SCALE`] resolves in `systems/closed_loop.json`: the
//! instance exists and its FMU's model description has the variable.
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use cosim_engine::closed_loop::{split, ClosedLoopNames, FullScaleNames};
use cosim_engine::system::{Overrides, System, SystemFiles};

/// The names of `names` that `systems/<file>` does not have.
fn unresolved(file: &str, names: Vec<&'static str>) -> Vec<&'static str> {
    let file = common::workspace_root().join("systems").join(file);
    let system = System::load(&file, &Overrides::default(), &SystemFiles::default())
        .unwrap_or_else(|e| panic!("{}: {e} (run `cargo xtask package` first)", file.display()));
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
fn every_test_scale_name_resolves_in_the_closed_loop_system() {
    // (The controller instance, `names.controller`, is the instance of `names.mode`.)
    let names = ClosedLoopNames::TEST_SCALE;
    assert_eq!(split(names.mode).map(|(instance, _)| instance), Some(names.controller));
    assert_eq!(unresolved("closed_loop.json", names.all()), Vec::<&str>::new());
}

#[test]
fn every_full_scale_name_resolves_in_the_full_scale_system() {
    assert_eq!(unresolved("full_scale_ahc.json", FullScaleNames::FULL_SCALE.all()), Vec::<&str>::new());
}

#[test]
fn a_misspelt_name_is_caught() {
    // The check above must be able to fail: a name the loop does not have is found unresolved.
    let file = common::workspace_root().join("systems/closed_loop.json");
    let system = System::load(&file, &Overrides::default(), &SystemFiles::default()).unwrap();
    let controller = system.instance_index("controller").unwrap();
    let description = system.instances[controller].fmu.model_description();
    assert!(description.variable("sp.load.x").is_some());
    assert!(description.variable("sp.load.w").is_none());
    assert!(system.instance_index("pendulum2").is_none());
}
