//! Components and FMU states are used only while this library lists them as live objects of
//! the model they are read as (`crate::live`): freed, forged and foreign pointers are refused
//! with `fmi2Error` before any access. A tag inside the object, checked by reading it, would
//! read freed memory for the first and accept the other two.

use super::host::{instantiate_through_api, Fmu, Log};
use super::toy::{self, inert_model, Toy};
use crate::ffi::*;
use crate::fmi2::api;
use crate::model::ModelInfo;
use crate::state::State::StepComplete;
use serde::{Deserialize, Serialize};
use std::ptr::null_mut;

/// A model no other test instantiates, so that no live `Ghost` can take the address of a freed
/// one while a test uses the stale pointer.
#[derive(Clone, Serialize, Deserialize)]
struct Ghost;

inert_model!(Ghost { info: ModelInfo { model_identifier: "ghost", ..Toy::INFO }, variables: &[], new: Ghost });

/// The tags earlier builds checked (instance and FMU state), which forged memory can carry.
const INSTANCE_TAG: u64 = u64::from_le_bytes(crate::image::BINCODE_TAG);
const STATE_TAG: u64 = 0x464d_4932_5354_4154;

#[test]
fn a_freed_component_is_refused_unread() {
    let log = Box::<Log>::default();
    let c = instantiate_through_api::<Ghost>(&log, c"ghost");
    // SAFETY: `c` is a live instance, freed once here.
    unsafe { api::free_instance::<Ghost>(c) };
    // SAFETY: `c` is freed, and no Ghost lives at its address (see `Ghost`): that these calls
    // refuse it without reading it is what this tests; the second free must be a no-op.
    unsafe {
        assert_eq!(api::do_step::<Ghost>(c, 0.0, 0.1, fmi2True), fmi2Error);
        api::free_instance::<Ghost>(c);
        assert_eq!(api::reset::<Ghost>(c), fmi2Error);
    }
}

#[test]
fn forged_components_and_states_are_refused_unread() {
    let forged_instance = vec![INSTANCE_TAG; 256];
    let forged_state = vec![STATE_TAG; 256];
    let fmu = Fmu::in_state(StepComplete);
    let (c, s) = (forged_instance.as_ptr() as fmi2Component, forged_state.as_ptr() as fmi2FMUstate);
    // SAFETY: both forged pointers point to live vectors this test owns, so even a read would
    // not be undefined behaviour; `fmu.c` is a live instance of this test.
    unsafe {
        assert_eq!(toy::fmi2DoStep(c, 0.0, 0.1, fmi2True), fmi2Error);
        toy::fmi2FreeInstance(c);
        fmu.refused(toy::fmi2SetFMUstate(fmu.c, s), "fmi2SetFMUstate", &["not a state of this FMU"]);
        let mut slot = s;
        fmu.refused(toy::fmi2FreeFMUstate(fmu.c, &mut slot), "fmi2FreeFMUstate", &["not a state of this FMU"]);
    }
    assert!(forged_instance.iter().chain(&forged_state).all(|w| *w == INSTANCE_TAG || *w == STATE_TAG));
}

#[test]
fn a_component_or_state_of_another_model_is_refused() {
    let log = Box::<Log>::default();
    let ghost = instantiate_through_api::<Ghost>(&log, c"ghost");
    let fmu = Fmu::in_state(StepComplete);
    let mut s = null_mut();
    // SAFETY: `ghost` and `fmu.c` are live instances of this test, `s` a live local slot; each
    // call passes an object of one model to the entry points of the other.
    unsafe {
        fmu.ok(toy::fmi2GetFMUstate(fmu.c, &mut s));
        assert_eq!(toy::fmi2Reset(ghost), fmi2Error);
        assert_eq!(api::set_fmu_state::<Ghost>(ghost, s), fmi2Error);
        assert_eq!(api::free_fmu_state::<Ghost>(ghost, &mut s), fmi2Error);
        assert!(!s.is_null(), "the state was not freed by the other model");
        api::free_instance::<Ghost>(ghost);
        fmu.ok(toy::fmi2FreeFMUstate(fmu.c, &mut s));
    }
}
