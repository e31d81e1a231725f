//! Who may set which variable when (FMI 2.0 §4.2.4 with the variable rules of §2.2.7), ranges,
//! and the promise that a refused vector set leaves every element of the vector unchanged.

use super::host::Fmu;
use super::toy::{self, vr};
use crate::ffi::*;
use crate::state::State::{self, *};
use std::ptr::{null, null_mut};

/// Every state in which the `fmi2Set*` functions themselves are allowed.
const SETTABLE: [State; 3] = [Instantiated, InitializationMode, StepComplete];

/// Moves an instance from `Instantiated` on to `state`.
fn advance(fmu: &Fmu, state: State) {
    if fmu.state() == Instantiated && state != Instantiated {
        // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
        fmu.ok(unsafe { toy::fmi2SetupExperiment(fmu.c, fmi2False, 0.0, 0.0, fmi2False, 0.0) });
        // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
        fmu.ok(unsafe { toy::fmi2EnterInitializationMode(fmu.c) });
    }
    if fmu.state() == InitializationMode && state == StepComplete {
        // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
        fmu.ok(unsafe { toy::fmi2ExitInitializationMode(fmu.c) });
    }
    assert_eq!(fmu.state(), state);
}

#[test]
fn fixed_parameters_are_settable_until_initialization_ends() {
    let fmu = Fmu::new();
    fmu.ok(fmu.set_real(&[vr::GAIN], &[2.0]));
    fmu.ok(fmu.set_integer(&[vr::ORDER], &[3]));
    fmu.ok(fmu.set_boolean(&[vr::ENABLED], &[false]));
    fmu.ok(fmu.set_string(&[vr::LABEL], &[Some("first")]));
    advance(&fmu, InitializationMode);
    assert_eq!(fmu.reals(&[vr::GAIN]), [2.0]);
    fmu.ok(fmu.set_real(&[vr::GAIN], &[3.0]));
    fmu.ok(fmu.set_integer(&[vr::ORDER], &[4]));
    fmu.ok(fmu.set_boolean(&[vr::ENABLED], &[true]));
    fmu.ok(fmu.set_string(&[vr::LABEL], &[Some("second")]));
    advance(&fmu, StepComplete);

    fmu.refused(fmu.set_real(&[vr::GAIN], &[4.0]), "fmi2SetReal", &["'gain'", "StepComplete"]);
    fmu.refused(fmu.set_integer(&[vr::ORDER], &[5]), "fmi2SetInteger", &["'order'", "StepComplete"]);
    fmu.refused(fmu.set_boolean(&[vr::ENABLED], &[false]), "fmi2SetBoolean", &["'enabled'", "StepComplete"]);
    fmu.refused(fmu.set_string(&[vr::LABEL], &[Some("third")]), "fmi2SetString", &["'label'", "StepComplete"]);
    assert_eq!(fmu.reals(&[vr::GAIN]), [3.0]);
    assert_eq!(fmu.integers(&[vr::ORDER]), [4]);
    assert_eq!(fmu.booleans(&[vr::ENABLED]), [true]);
    assert_eq!(fmu.strings(&[vr::LABEL]), ["second"]);
}

/// Outputs here are `initial="calculated"` and constants never change, so the standard lets a
/// host set neither, in any state.
#[test]
fn outputs_and_constants_are_never_settable() {
    for state in SETTABLE {
        let fmu = Fmu::new();
        advance(&fmu, state);
        fmu.refused(fmu.set_real(&[vr::Y], &[1.0]), "fmi2SetReal", &["'y'", "cannot be set"]);
        fmu.refused(fmu.set_real(&[vr::TWO], &[3.0]), "fmi2SetReal", &["'two'", "cannot be set"]);
        fmu.refused(fmu.set_boolean(&[vr::POSITIVE], &[true]), "fmi2SetBoolean", &["'positive'", "cannot be set"]);
        if state != Instantiated {
            assert_eq!(fmu.reals(&[vr::Y, vr::TWO]), [0.0, 2.0]);
            assert_eq!(fmu.booleans(&[vr::POSITIVE]), [false]);
        }
    }
}

#[test]
fn a_tunable_parameter_is_settable_between_steps_and_takes_effect() {
    for state in SETTABLE {
        let fmu = Fmu::new();
        advance(&fmu, state);
        fmu.ok(fmu.set_real(&[vr::RATE], &[2.0]));
        advance(&fmu, StepComplete);
        fmu.ok(fmu.do_step(0.0, 0.5));
        assert_eq!(fmu.reals(&[vr::RATE, vr::Y]), [2.0, 1.0], "set in {state:?}");
        fmu.ok(fmu.set_real(&[vr::RATE], &[-4.0]));
        fmu.ok(fmu.do_step(0.5, 0.5));
        assert_eq!(fmu.reals(&[vr::RATE, vr::Y]), [-4.0, -1.0]);
    }
}

#[test]
fn inputs_are_settable_in_every_state_that_allows_setting() {
    for state in SETTABLE {
        let fmu = Fmu::new();
        advance(&fmu, state);
        fmu.ok(fmu.set_real(&[vr::U, vr::W], &[0.25, -0.5]));
        fmu.ok(fmu.set_integer(&[vr::COMMAND], &[7]));
        fmu.ok(fmu.set_boolean(&[vr::HOLD], &[true]));
        fmu.ok(fmu.set_string(&[vr::NOTE], &[Some("hello")]));
        advance(&fmu, if state == Instantiated { InitializationMode } else { state });
        assert_eq!(fmu.reals(&[vr::U, vr::W]), [0.25, -0.5], "set in {state:?}");
        assert_eq!(fmu.integers(&[vr::COMMAND]), [7]);
        assert_eq!(fmu.booleans(&[vr::HOLD]), [true]);
        assert_eq!(fmu.strings(&[vr::NOTE]), ["hello"]);
    }
}

#[test]
fn values_outside_min_max_are_refused_and_not_stored() {
    let fmu = Fmu::new();
    advance(&fmu, InitializationMode);
    for bad in [10.5, -0.1, 1e300] {
        fmu.refused(fmu.set_real(&[vr::GAIN], &[bad]), "fmi2SetReal", &["'gain'", "outside its range [0, 10]"]);
        assert_eq!(fmu.reals(&[vr::GAIN]), [1.0]);
    }
    for bad in [0, 6, i32::MIN] {
        fmu.refused(fmu.set_integer(&[vr::ORDER], &[bad]), "fmi2SetInteger", &["'order'", "outside its range [1, 5]"]);
        assert_eq!(fmu.integers(&[vr::ORDER]), [2]);
    }
    // The bounds themselves belong to the range.
    fmu.ok(fmu.set_real(&[vr::GAIN], &[0.0]));
    fmu.ok(fmu.set_real(&[vr::GAIN], &[10.0]));
    fmu.ok(fmu.set_integer(&[vr::ORDER], &[1]));
    fmu.ok(fmu.set_integer(&[vr::ORDER], &[5]));
    assert_eq!(fmu.reals(&[vr::GAIN]), [10.0]);
    assert_eq!(fmu.integers(&[vr::ORDER]), [5]);

    // Inputs are checked in step mode too.
    advance(&fmu, StepComplete);
    fmu.refused(fmu.set_real(&[vr::W], &[1.5]), "fmi2SetReal", &["'w'", "outside"]);
    fmu.refused(fmu.set_integer(&[vr::COMMAND], &[100]), "fmi2SetInteger", &["'command'", "outside"]);
    fmu.refused(fmu.set_integer(&[vr::COMMAND], &[-1]), "fmi2SetInteger", &["'command'", "outside"]);
    assert_eq!(fmu.reals(&[vr::W]), [0.0]);
    assert_eq!(fmu.integers(&[vr::COMMAND]), [0]);
}

#[test]
fn non_finite_reals_are_refused_and_not_stored() {
    let fmu = Fmu::new();
    advance(&fmu, InitializationMode);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for (r, name) in [(vr::U, "'u'"), (vr::RATE, "'rate'"), (vr::GAIN, "'gain'")] {
            fmu.refused(fmu.set_real(&[r], &[bad]), "fmi2SetReal", &[name, "non-finite"]);
        }
        assert_eq!(fmu.reals(&[vr::U, vr::RATE, vr::GAIN]), [0.0, 0.0, 1.0]);
    }
}

/// A vector with one bad element, at the end (after elements a naive loop would already have
/// stored) and in the middle.
fn with_bad<T: Copy>(good: &[(u32, T)], bad: (u32, T)) -> [(Vec<u32>, Vec<T>); 2] {
    let mut last: Vec<(u32, T)> = good.to_vec();
    last.push(bad);
    let mut middle: Vec<(u32, T)> = good.to_vec();
    middle.insert(good.len() / 2 + 1, bad);
    [last, middle].map(|v| v.into_iter().unzip())
}

#[test]
fn a_refused_real_vector_changes_none_of_its_elements() {
    let good = [(vr::U, 4.0), (vr::RATE, 3.0), (vr::GAIN, 2.0)];
    let bad = [
        ((vr::UNKNOWN, 1.0), "unknown Real value reference 77"),
        ((vr::W, 5.0), "outside its range"),
        ((vr::W, f64::NAN), "non-finite"),
        ((vr::Y, 1.0), "cannot be set"),
        ((vr::TWO, 2.0), "cannot be set"),
    ];
    for (element, words) in bad {
        for (vrs, values) in with_bad(&good, element) {
            let fmu = Fmu::new();
            advance(&fmu, InitializationMode);
            fmu.refused(fmu.set_real(&vrs, &values), "fmi2SetReal", &[words]);
            assert_eq!(fmu.reals(&[vr::U, vr::RATE, vr::GAIN, vr::W]), [0.0, 0.0, 1.0, 0.0], "after {vrs:?}");
        }
    }
    // In step mode a fixed parameter spoils a vector of otherwise settable variables.
    let fmu = Fmu::new();
    advance(&fmu, StepComplete);
    fmu.refused(fmu.set_real(&[vr::RATE, vr::U, vr::GAIN], &[3.0, 4.0, 2.0]), "fmi2SetReal", &["'gain'"]);
    assert_eq!(fmu.reals(&[vr::RATE, vr::U, vr::GAIN]), [0.0, 0.0, 1.0]);
}

#[test]
fn a_refused_integer_vector_changes_none_of_its_elements() {
    let cases = [
        (&[(vr::ORDER, 3)][..], (vr::UNKNOWN, 1), "unknown Integer value reference 77"),
        (&[(vr::ORDER, 3)], (vr::COMMAND, 100), "outside its range"),
        (&[(vr::COMMAND, 5)], (vr::ORDER, 6), "outside its range"),
        // Real 3 is `y`; Integer 3 does not exist.
        (&[(vr::ORDER, 3), (vr::COMMAND, 5)], (vr::Y, 1), "unknown Integer value reference 3"),
    ];
    for (good, element, words) in cases {
        for (vrs, values) in with_bad(good, element) {
            let fmu = Fmu::new();
            advance(&fmu, InitializationMode);
            fmu.refused(fmu.set_integer(&vrs, &values), "fmi2SetInteger", &[words]);
            assert_eq!(fmu.integers(&[vr::ORDER, vr::COMMAND]), [2, 0], "after {vrs:?}");
        }
    }
}

#[test]
fn a_refused_boolean_vector_changes_none_of_its_elements() {
    let good = [(vr::ENABLED, false), (vr::HOLD, true)];
    let bad = [((vr::UNKNOWN, true), "unknown Boolean value reference 77"), ((vr::POSITIVE, true), "cannot be set")];
    for (element, words) in bad {
        for (vrs, values) in with_bad(&good, element) {
            let fmu = Fmu::new();
            advance(&fmu, InitializationMode);
            fmu.refused(fmu.set_boolean(&vrs, &values), "fmi2SetBoolean", &[words]);
            assert_eq!(fmu.booleans(&[vr::ENABLED, vr::HOLD]), [true, false], "after {vrs:?}");
        }
    }
}

#[test]
fn a_refused_string_vector_changes_none_of_its_elements() {
    let cases = [
        (&[(vr::LABEL, Some("new"))][..], (vr::UNKNOWN, Some("x")), "unknown String value reference 77"),
        (&[(vr::LABEL, Some("new"))], (vr::NOTE, None), "value is NULL"),
        (&[(vr::NOTE, Some("new"))], (vr::LABEL, None), "value is NULL"),
    ];
    for (good, element, words) in cases {
        for (vrs, values) in with_bad(good, element) {
            let fmu = Fmu::new();
            advance(&fmu, InitializationMode);
            fmu.refused(fmu.set_string(&vrs, &values), "fmi2SetString", &[words]);
            assert_eq!(fmu.strings(&[vr::LABEL, vr::NOTE]), ["toy", ""], "after {vrs:?}");
        }
    }
}

/// `w` is a held input (no derivative setter): it spoils the derivative of `u` in the same call.
#[test]
fn a_refused_input_derivative_vector_changes_none_of_its_elements() {
    let fmu = Fmu::new();
    advance(&fmu, StepComplete);
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    let status = unsafe {
        toy::fmi2SetRealInputDerivatives(fmu.c, [vr::U, vr::W].as_ptr(), 2, [1, 1].as_ptr(), [2.0, 1.0].as_ptr())
    };
    fmu.refused(status, "fmi2SetRealInputDerivatives", &["'w'", "not an input that can be interpolated"]);
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    let status = unsafe { toy::fmi2SetRealInputDerivatives(fmu.c, [vr::U].as_ptr(), 1, [2].as_ptr(), [2.0].as_ptr()) };
    fmu.refused(status, "fmi2SetRealInputDerivatives", &["'u'", "order 2"]);
    // With the derivative of u stored, y would grow by gain·du·h²/2 = 1.
    fmu.ok(fmu.do_step(0.0, 1.0));
    assert_eq!(fmu.reals(&[vr::Y]), [0.0]);

    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    fmu.ok(unsafe { toy::fmi2SetRealInputDerivatives(fmu.c, [vr::U].as_ptr(), 1, [1].as_ptr(), [2.0].as_ptr()) });
    fmu.ok(fmu.do_step(1.0, 1.0));
    assert_eq!(fmu.reals(&[vr::Y]), [1.0], "the accepted derivative is used");
}

#[test]
fn unknown_value_references_are_refused_by_the_getters() {
    let fmu = Fmu::new();
    advance(&fmu, StepComplete);
    let mut real = [0.0; 2];
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    let status = unsafe { toy::fmi2GetReal(fmu.c, [vr::Y, vr::UNKNOWN].as_ptr(), 2, real.as_mut_ptr()) };
    fmu.refused(status, "fmi2GetReal", &["unknown Real value reference 77"]);
    let mut int = [0; 1];
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    let status = unsafe { toy::fmi2GetInteger(fmu.c, [vr::Y].as_ptr(), 1, int.as_mut_ptr()) };
    fmu.refused(status, "fmi2GetInteger", &["unknown Integer value reference 3"]);
    let mut boolean = [0; 1];
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    let status = unsafe { toy::fmi2GetBoolean(fmu.c, [vr::UNKNOWN].as_ptr(), 1, boolean.as_mut_ptr()) };
    fmu.refused(status, "fmi2GetBoolean", &["unknown Boolean value reference 77"]);
    let mut string = [null(); 1];
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    let status = unsafe { toy::fmi2GetString(fmu.c, [vr::NOTE + 1].as_ptr(), 1, string.as_mut_ptr()) };
    fmu.refused(status, "fmi2GetString", &["unknown String value reference 32"]);
}

/// A NULL array with a nonzero count is an error with a message, never a dereference; with a
/// count of zero it is a valid empty call.
#[test]
fn null_arrays_with_nonzero_counts_are_refused() {
    let fmu = Fmu::new();
    advance(&fmu, StepComplete);
    let r = [vr::U];
    let mut real = [0.0];
    let mut int = [0];
    let mut string = [null()];
    // SAFETY: `fmu.c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
    // other pointer is to a live local.
    unsafe {
        fmu.refused(toy::fmi2GetReal(fmu.c, null(), 1, real.as_mut_ptr()), "fmi2GetReal", &["vr is NULL"]);
        fmu.refused(toy::fmi2GetReal(fmu.c, r.as_ptr(), 1, null_mut()), "fmi2GetReal", &["value is NULL"]);
        fmu.refused(toy::fmi2GetInteger(fmu.c, null(), 1, int.as_mut_ptr()), "fmi2GetInteger", &["vr is NULL"]);
        fmu.refused(toy::fmi2GetInteger(fmu.c, r.as_ptr(), 1, null_mut()), "fmi2GetInteger", &["value is NULL"]);
        fmu.refused(toy::fmi2GetBoolean(fmu.c, null(), 1, int.as_mut_ptr()), "fmi2GetBoolean", &["vr is NULL"]);
        fmu.refused(toy::fmi2GetBoolean(fmu.c, r.as_ptr(), 1, null_mut()), "fmi2GetBoolean", &["value is NULL"]);
        fmu.refused(toy::fmi2GetString(fmu.c, null(), 1, string.as_mut_ptr()), "fmi2GetString", &["vr is NULL"]);
        fmu.refused(toy::fmi2GetString(fmu.c, r.as_ptr(), 1, null_mut()), "fmi2GetString", &["value is NULL"]);
        fmu.refused(toy::fmi2SetReal(fmu.c, null(), 1, [1.0].as_ptr()), "fmi2SetReal", &["vr is NULL"]);
        fmu.refused(toy::fmi2SetReal(fmu.c, r.as_ptr(), 1, null()), "fmi2SetReal", &["value is NULL"]);
        fmu.refused(toy::fmi2SetInteger(fmu.c, null(), 1, [1].as_ptr()), "fmi2SetInteger", &["vr is NULL"]);
        fmu.refused(toy::fmi2SetInteger(fmu.c, r.as_ptr(), 1, null()), "fmi2SetInteger", &["value is NULL"]);
        fmu.refused(toy::fmi2SetBoolean(fmu.c, null(), 1, [1].as_ptr()), "fmi2SetBoolean", &["vr is NULL"]);
        fmu.refused(toy::fmi2SetBoolean(fmu.c, r.as_ptr(), 1, null()), "fmi2SetBoolean", &["value is NULL"]);
        fmu.refused(toy::fmi2SetString(fmu.c, null(), 1, [c"x".as_ptr()].as_ptr()), "fmi2SetString", &["vr is NULL"]);
        fmu.refused(toy::fmi2SetString(fmu.c, r.as_ptr(), 1, null()), "fmi2SetString", &["value is NULL"]);
        let status = toy::fmi2SetRealInputDerivatives(fmu.c, r.as_ptr(), 1, null(), [1.0].as_ptr());
        fmu.refused(status, "fmi2SetRealInputDerivatives", &["order is NULL"]);
        let status = toy::fmi2SetDebugLogging(fmu.c, fmi2True, 1, null());
        fmu.refused(status, "fmi2SetDebugLogging", &["categories is NULL"]);
        let status = toy::fmi2SetDebugLogging(fmu.c, fmi2True, 1, [null()].as_ptr());
        fmu.refused(status, "fmi2SetDebugLogging", &["category is NULL"]);
        fmu.refused(toy::fmi2GetRealStatus(fmu.c, fmi2LastSuccessfulTime, null_mut()), "fmi2GetRealStatus", &["NULL"]);
        fmu.refused(toy::fmi2GetBooleanStatus(fmu.c, fmi2Terminated, null_mut()), "fmi2GetBooleanStatus", &["NULL"]);

        fmu.ok(toy::fmi2GetReal(fmu.c, null(), 0, null_mut()));
        fmu.ok(toy::fmi2SetReal(fmu.c, null(), 0, null()));
        fmu.ok(toy::fmi2SetString(fmu.c, null(), 0, null()));
        fmu.ok(toy::fmi2GetString(fmu.c, null(), 0, null_mut()));
    }
    assert_eq!(fmu.state(), StepComplete, "argument errors leave the instance usable");
}

#[test]
fn unknown_log_categories_are_refused() {
    let fmu = Fmu::new();
    let categories = [c"logCalls".as_ptr(), c"logEverything".as_ptr()];
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    let status = unsafe { toy::fmi2SetDebugLogging(fmu.c, fmi2True, 2, categories.as_ptr()) };
    fmu.refused(status, "fmi2SetDebugLogging", &["'logEverything'"]);
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    fmu.ok(unsafe { toy::fmi2SetDebugLogging(fmu.c, fmi2True, 1, categories.as_ptr()) });
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    let _ = unsafe { toy::fmi2SetupExperiment(fmu.c, fmi2False, 0.0, 0.0, fmi2False, 0.0) };
    let calls = fmu.messages();
    assert!(
        calls.iter().any(|m| m.category == "logCalls" && m.text.contains("fmi2SetupExperiment")),
        "logCalls on reports calls: {calls:?}"
    );
}

/// `fmi2SetReal` and `fmi2SetRealInputDerivatives` decide with the precomputed slot of each
/// variable and ask the descriptive checks only for the message of a refusal; the two must agree
/// on every variable, state and value, or a refused value would be set (or a legal one refused
/// with an internal error).
#[test]
fn the_slot_checks_agree_with_the_descriptive_checks() {
    use crate::instance::{check_derivative, check_real};
    use crate::lookup::{settable_in, Lookup};
    use crate::Model;
    let table = toy::Toy::variables();
    let lookup = Lookup::new(table);
    let values =
        [0.0, 0.5, -1.0, 1.0, 10.0, -1.5, 10.5, 1e300, f64::MAX, f64::MIN, f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
    for v in table.iter().filter(|v| matches!(v.value, crate::Value::Real { .. })) {
        let slot = lookup.reals().get(v.vr).expect("every Real has a slot");
        for state in State::ALL {
            let settable = settable_in(v).is_some_and(|mask| mask.allows(state));
            for value in values {
                let descriptive = settable && check_real(v, v.vr, value).is_ok();
                assert_eq!(slot.accepts(state, value), descriptive, "'{}' = {value} in {state:?}", v.name);
                for order in [0, 1, 2] {
                    let descriptive = settable && check_derivative(v, v.vr, (order, value)).is_ok();
                    let fast = slot.accepts_derivative(state, order, value);
                    assert_eq!(fast, descriptive, "'{}' derivative {value} of order {order} in {state:?}", v.name);
                }
            }
        }
    }
}
