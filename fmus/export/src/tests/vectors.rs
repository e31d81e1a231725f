//! Vector gets and sets: every element resolves to its own variable whatever the order of the
//! value references, repeated references are served (a repeated set applies in order, so the
//! last value stays), and value references far apart resolve as well as compact ones.

use super::host::{ApiFmu, Fmu};
use super::toy::{self, sparse_vr, vr, Sparse};
use crate::ffi::*;
use crate::fmi2::api;
use crate::state::State::*;

#[test]
fn getters_serve_shuffled_and_repeated_value_references() {
    let fmu = Fmu::in_state(InitializationMode);
    fmu.ok(fmu.set_real(&[vr::GAIN, vr::U, vr::RATE, vr::W], &[3.0, 0.5, -2.0, 0.25]));
    fmu.ok(fmu.set_integer(&[vr::ORDER, vr::COMMAND], &[4, 9]));
    fmu.ok(fmu.set_boolean(&[vr::ENABLED, vr::HOLD], &[false, true]));
    fmu.ok(fmu.set_string(&[vr::LABEL, vr::NOTE], &[Some("first"), Some("second")]));
    // In initialization mode y = gain·u = 1.5, so `positive` is true; `two` is the constant 2.
    let reals = [vr::W, vr::Y, vr::GAIN, vr::TWO, vr::U, vr::W, vr::RATE, vr::GAIN];
    assert_eq!(fmu.reals(&reals), [0.25, 1.5, 3.0, 2.0, 0.5, 0.25, -2.0, 3.0]);
    assert_eq!(fmu.integers(&[vr::COMMAND, vr::ORDER, vr::COMMAND, vr::ORDER]), [9, 4, 9, 4]);
    assert_eq!(fmu.booleans(&[vr::HOLD, vr::POSITIVE, vr::ENABLED, vr::HOLD]), [true, true, false, true]);
    assert_eq!(fmu.strings(&[vr::NOTE, vr::LABEL, vr::NOTE]), ["second", "first", "second"]);
}

#[test]
fn setters_apply_shuffled_and_repeated_value_references_in_order() {
    let fmu = Fmu::in_state(InitializationMode);
    fmu.ok(fmu.set_real(&[vr::W, vr::GAIN, vr::U, vr::RATE, vr::W], &[0.5, 4.0, 5.0, 6.0, -0.75]));
    assert_eq!(fmu.reals(&[vr::U, vr::RATE, vr::GAIN, vr::W]), [5.0, 6.0, 4.0, -0.75]);
    fmu.ok(fmu.set_integer(&[vr::COMMAND, vr::ORDER, vr::COMMAND], &[1, 5, 42]));
    assert_eq!(fmu.integers(&[vr::ORDER, vr::COMMAND]), [5, 42]);
    fmu.ok(fmu.set_boolean(&[vr::HOLD, vr::ENABLED, vr::HOLD], &[false, false, true]));
    assert_eq!(fmu.booleans(&[vr::ENABLED, vr::HOLD]), [false, true]);
    fmu.ok(fmu.set_string(&[vr::NOTE, vr::LABEL, vr::NOTE], &[Some("x"), Some("y"), Some("z")]));
    assert_eq!(fmu.strings(&[vr::LABEL, vr::NOTE]), ["y", "z"]);
}

/// The elements a refused set had already resolved must not be applied by the next set.
#[test]
fn a_refused_set_leaves_nothing_behind_for_the_next_one() {
    let fmu = Fmu::in_state(InitializationMode);
    let vrs = [vr::U, vr::RATE, vr::GAIN, vr::UNKNOWN, vr::W];
    fmu.refused(fmu.set_real(&vrs, &[4.0, 3.0, 2.0, 1.0, 0.5]), "fmi2SetReal", &["unknown Real value reference 77"]);
    fmu.ok(fmu.set_real(&[vr::W], &[-0.5]));
    assert_eq!(fmu.reals(&[vr::U, vr::RATE, vr::GAIN, vr::W]), [0.0, 0.0, 1.0, -0.5]);

    fmu.refused(fmu.set_integer(&[vr::ORDER, vr::UNKNOWN], &[3, 1]), "fmi2SetInteger", &["reference 77"]);
    fmu.ok(fmu.set_integer(&[vr::COMMAND], &[8]));
    assert_eq!(fmu.integers(&[vr::ORDER, vr::COMMAND]), [2, 8]);
}

/// An unknown value reference among input derivatives stores none of them: with the derivative
/// of u stored, y would grow by gain·du·h²/2 = 1 over the step.
#[test]
fn an_unknown_value_reference_among_derivatives_stores_none() {
    let fmu = Fmu::in_state(StepComplete);
    let vrs = [vr::U, vr::UNKNOWN, vr::U];
    let status =
        // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
        // length.
        unsafe { toy::fmi2SetRealInputDerivatives(fmu.c, vrs.as_ptr(), 3, [1; 3].as_ptr(), [2.0; 3].as_ptr()) };
    fmu.refused(status, "fmi2SetRealInputDerivatives", &["unknown Real value reference 77"]);
    fmu.ok(fmu.do_step(0.0, 1.0));
    assert_eq!(fmu.reals(&[vr::Y]), [0.0]);
}

/// An instance of [`Sparse`] in initialization mode.
struct SparseFmu(ApiFmu<Sparse>);

impl SparseFmu {
    fn new() -> SparseFmu {
        SparseFmu(ApiFmu::initializing(c"sparse"))
    }

    fn reals(&self, vrs: &[u32]) -> Vec<f64> {
        let mut out = vec![f64::NAN; vrs.len()];
        // SAFETY: `self.0.c` is a live instance of this test; each array or slot is a live local of at least the
        // announced length.
        let status = unsafe {
            api::get_values::<Sparse, crate::calls::Real>(
                self.0.c,
                "fmi2GetReal",
                vrs.as_ptr(),
                vrs.len(),
                out.as_mut_ptr(),
            )
        };
        assert_eq!(status, fmi2OK, "{:?}", self.0.log.take());
        out
    }

    fn set_real(&self, vrs: &[u32], values: &[f64]) -> fmi2Status {
        // SAFETY: `self.0.c` is a live instance of this test; each array or slot is a live local of at least the
        // announced length.
        unsafe {
            api::set_values::<Sparse, crate::calls::Real>(
                self.0.c,
                "fmi2SetReal",
                vrs.as_ptr(),
                vrs.len(),
                values.as_ptr(),
            )
        }
    }
}

#[test]
fn sparse_value_references_resolve_like_compact_ones() {
    use sparse_vr::{A, B, C, S};
    let fmu = SparseFmu::new();
    // Start values a = 1, b = 2, c = 3, so s = 1 + 20 + 300.
    assert_eq!(fmu.reals(&[S, C, A, B, A]), [321.0, 3.0, 1.0, 2.0, 1.0]);
    assert_eq!(fmu.set_real(&[B, C, A, B], &[5.0, 6.0, 7.0, 8.0]), fmi2OK);
    assert_eq!(fmu.reals(&[A, B, C, S]), [7.0, 8.0, 6.0, 687.0]);

    // Neighbours of known value references are unknown, and refuse the whole vector.
    for unknown in [A - 1, A + 1, B + 1, C - 1, S - 1, 0] {
        assert_eq!(fmu.set_real(&[A, unknown, B], &[0.0, 0.0, 0.0]), fmi2Error);
        let expected = format!("fmi2SetReal: unknown Real value reference {unknown}");
        let messages = fmu.0.log.take();
        assert!(messages.iter().any(|m| m.text == expected), "{expected}: {messages:?}");
        assert_eq!(fmu.reals(&[A, B, C]), [7.0, 8.0, 6.0]);
    }
}
