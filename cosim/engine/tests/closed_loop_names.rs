//! Every name of [`ClosedLoopNames::TEST_SCALE`] resolves in `systems/closed_loop.json`: the
//! instance exists and its FMU's model description has the variable.
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use cosim_engine::closed_loop::{split, ClosedLoopNames};
use cosim_engine::system::{Overrides, System, SystemFiles};

#[test]
fn every_test_scale_name_resolves_in_the_closed_loop_system() {
    let file = common::workspace_root().join("systems/closed_loop.json");
    let system = System::load(&file, &Overrides::default(), &SystemFiles::default())
        .unwrap_or_else(|e| panic!("{}: {e} (run `cargo xtask package` first)", file.display()));
    let names = ClosedLoopNames::TEST_SCALE;
    assert!(system.instance_index(names.controller).is_some(), "no instance {}", names.controller);
    let unresolved: Vec<&str> = names
        .all()
        .into_iter()
        .filter(|name| {
            let Some((instance, variable)) = split(name) else { return true };
            let found = system.instance_index(instance).map(|i| &system.instances[i]);
            found.is_none_or(|i| i.fmu.model_description().variable(variable).is_none())
        })
        .collect();
    assert!(unresolved.is_empty(), "not in {}: {unresolved:?}", file.display());
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
