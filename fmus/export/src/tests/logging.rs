//! Logging of calls: with `logCalls` on, every call reaches the host's logger once, successful
//! or not; with it off, successful calls log nothing.

use super::host::{Fmu, Message};
use super::toy::{self, vr};
use crate::ffi::*;
use crate::state::State::*;
use std::ptr::null;

/// The texts of the `logCalls` messages, after checking how each was sent.
fn calls(messages: &[Message]) -> Vec<&str> {
    let calls: Vec<&Message> = messages.iter().filter(|m| m.category == "logCalls").collect();
    for m in &calls {
        assert_eq!((m.status, m.format.as_str(), m.instance.as_str()), (fmi2OK, "%s", "toy1"), "{m:?}");
    }
    calls.iter().map(|m| m.text.as_str()).collect()
}

/// Makes one call of each function of a macro step (sets, derivatives, step, gets), one of
/// them refused; returns the statuses.
fn macro_step(fmu: &Fmu, t: f64) -> Vec<fmi2Status> {
    let (u, command, hold) = ([vr::U], [vr::COMMAND], [vr::HOLD]);
    let (mut real, mut int, mut boolean) = ([0.0], [0], [0]);
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    unsafe {
        vec![
            toy::fmi2SetReal(fmu.c, u.as_ptr(), 1, [1.0].as_ptr()),
            toy::fmi2SetRealInputDerivatives(fmu.c, u.as_ptr(), 1, [1].as_ptr(), [0.5].as_ptr()),
            toy::fmi2SetInteger(fmu.c, command.as_ptr(), 1, [3].as_ptr()),
            toy::fmi2SetBoolean(fmu.c, hold.as_ptr(), 1, [fmi2False].as_ptr()),
            toy::fmi2DoStep(fmu.c, t, 0.1, fmi2True),
            toy::fmi2GetReal(fmu.c, [vr::Y].as_ptr(), 1, real.as_mut_ptr()),
            toy::fmi2GetInteger(fmu.c, command.as_ptr(), 1, int.as_mut_ptr()),
            toy::fmi2GetBoolean(fmu.c, hold.as_ptr(), 1, boolean.as_mut_ptr()),
            toy::fmi2GetReal(fmu.c, [vr::UNKNOWN].as_ptr(), 1, real.as_mut_ptr()),
        ]
    }
}

const MACRO_STEP_CALLS: [&str; 9] = [
    "fmi2SetReal",
    "fmi2SetRealInputDerivatives",
    "fmi2SetInteger",
    "fmi2SetBoolean",
    "fmi2DoStep",
    "fmi2GetReal",
    "fmi2GetInteger",
    "fmi2GetBoolean",
    "fmi2GetReal",
];

#[test]
fn with_logging_on_every_call_reaches_the_logger_once() {
    let fmu = Fmu::in_state(StepComplete);
    // SAFETY: `fmu.c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
    // other pointer is to a live local.
    fmu.ok(unsafe { toy::fmi2SetDebugLogging(fmu.c, fmi2True, 0, null()) });

    let statuses = macro_step(&fmu, 0.0);
    assert_eq!(statuses, [fmi2OK, fmi2OK, fmi2OK, fmi2OK, fmi2OK, fmi2OK, fmi2OK, fmi2OK, fmi2Error]);
    let messages = fmu.messages();
    assert_eq!(calls(&messages), MACRO_STEP_CALLS);
    let errors: Vec<&str> = messages.iter().filter(|m| m.status == fmi2Error).map(|m| m.text.as_str()).collect();
    assert_eq!(errors, ["fmi2GetReal: unknown Real value reference 77"]);

    // Switching off is itself the last call logged; then only the refused call's error remains.
    // SAFETY: `fmu.c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
    // other pointer is to a live local.
    assert_eq!(unsafe { toy::fmi2SetDebugLogging(fmu.c, fmi2False, 0, null()) }, fmi2OK);
    assert_eq!(calls(&fmu.messages()), ["fmi2SetDebugLogging"]);
    macro_step(&fmu, 0.1);
    let messages = fmu.messages();
    assert!(calls(&messages).is_empty(), "{messages:?}");
    assert_eq!(messages.len(), 1, "{messages:?}");
}
