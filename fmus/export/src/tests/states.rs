//! The state machine: every Co-Simulation function called in every state an instance can be in,
//! against the table of FMI 2.0 §4.2.4 (written out here from the standard, not taken from
//! `crate::state`, so a wrong mask there makes these tests fail).

use super::host::Fmu;
use super::toy::{self, vr};
use crate::ffi::*;
use crate::state::State::{self, *};
use std::ffi::CStr;
use std::ptr::{null, null_mut};

/// FMI 2.0 §4.2.4, Co-Simulation, restricted to the states of this exporter (no
/// `stepInProgress` / `stepCanceled`: steps are synchronous). `fmi2FreeInstance` and the
/// functions without instance are checked separately.
const ALL_BUT_FATAL: &[State] = &[Instantiated, InitializationMode, StepComplete, StepFailed, Terminated, Error];
const GET: &[State] = &[InitializationMode, StepComplete, StepFailed, Terminated, Error];
const SET: &[State] = &[Instantiated, InitializationMode, StepComplete];
const STATUS: &[State] = &[StepComplete, StepFailed, Terminated];

/// One row of the table: a call with valid arguments, the states that allow it, and the state a
/// successful call leaves the instance in (`None`: unchanged).
struct Case {
    function: &'static str,
    allowed: &'static [State],
    after: Option<State>,
    call: fn(&Fmu, &Donor) -> fmi2Status,
}

const CASES: &[Case] = &[
    Case {
        function: "fmi2SetDebugLogging",
        allowed: ALL_BUT_FATAL,
        after: None,
        // SAFETY: `f.c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
        // other pointer is to a live local.
        call: |f, _| unsafe { toy::fmi2SetDebugLogging(f.c, fmi2False, 0, null()) },
    },
    Case {
        function: "fmi2SetupExperiment",
        allowed: &[Instantiated],
        after: None,
        // SAFETY: `f.c` is a live instance of this test, and the call takes no other pointer.
        call: |f, _| unsafe { toy::fmi2SetupExperiment(f.c, fmi2False, 0.0, 0.0, fmi2True, 5.0) },
    },
    Case {
        function: "fmi2EnterInitializationMode",
        allowed: &[Instantiated],
        after: Some(InitializationMode),
        // SAFETY: `f.c` is a live instance of this test, and the call takes no other pointer.
        call: |f, _| unsafe { toy::fmi2EnterInitializationMode(f.c) },
    },
    Case {
        function: "fmi2ExitInitializationMode",
        allowed: &[InitializationMode],
        after: Some(StepComplete),
        // SAFETY: `f.c` is a live instance of this test, and the call takes no other pointer.
        call: |f, _| unsafe { toy::fmi2ExitInitializationMode(f.c) },
    },
    Case {
        function: "fmi2Terminate",
        allowed: &[StepComplete, StepFailed],
        after: Some(Terminated),
        // SAFETY: `f.c` is a live instance of this test, and the call takes no other pointer.
        call: |f, _| unsafe { toy::fmi2Terminate(f.c) },
    },
    Case {
        function: "fmi2Reset",
        allowed: ALL_BUT_FATAL,
        after: Some(Instantiated),
        // SAFETY: `f.c` is a live instance of this test, and the call takes no other pointer.
        call: |f, _| unsafe { toy::fmi2Reset(f.c) },
    },
    // Not the output `y`: the host reaches state Error here through an infinite `y`, which no
    // getter hands out with fmi2OK.
    Case {
        function: "fmi2GetReal",
        allowed: GET,
        after: None,
        call: |f, _| f.get(toy::fmi2GetReal, &[vr::GAIN, vr::TWO], 0.0).0,
    },
    Case {
        function: "fmi2GetInteger",
        allowed: GET,
        after: None,
        call: |f, _| f.get(toy::fmi2GetInteger, &[vr::ORDER, vr::COMMAND], 0).0,
    },
    Case {
        function: "fmi2GetBoolean",
        allowed: GET,
        after: None,
        call: |f, _| f.get(toy::fmi2GetBoolean, &[vr::ENABLED, vr::POSITIVE], 0).0,
    },
    Case {
        function: "fmi2GetString",
        allowed: GET,
        after: None,
        call: |f, _| f.get(toy::fmi2GetString, &[vr::LABEL, vr::NOTE], null()).0,
    },
    // The setters use inputs, which the variable rules admit in every state the function is
    // allowed in; the per-variable rules are tested in `setters`.
    Case { function: "fmi2SetReal", allowed: SET, after: None, call: |f, _| f.set_real(&[vr::U], &[0.5]) },
    Case { function: "fmi2SetInteger", allowed: SET, after: None, call: |f, _| f.set_integer(&[vr::COMMAND], &[3]) },
    Case { function: "fmi2SetBoolean", allowed: SET, after: None, call: |f, _| f.set_boolean(&[vr::HOLD], &[true]) },
    Case { function: "fmi2SetString", allowed: SET, after: None, call: |f, _| f.set_string(&[vr::NOTE], &[Some("n")]) },
    Case {
        function: "fmi2SetRealInputDerivatives",
        allowed: SET,
        after: None,
        // SAFETY: `f.c` is a live instance of this test; each array or slot is a live local of at least the announced
        // length.
        call: |f, _| unsafe {
            toy::fmi2SetRealInputDerivatives(f.c, [vr::U].as_ptr(), 1, [1].as_ptr(), [0.5].as_ptr())
        },
    },
    Case {
        function: "fmi2GetFMUstate",
        allowed: ALL_BUT_FATAL,
        after: None,
        // SAFETY: `f.c` is a live instance of this test; `s` is a live local slot.
        call: |f, d| d.freeing(|s| unsafe { toy::fmi2GetFMUstate(f.c, s) }),
    },
    Case {
        function: "fmi2SetFMUstate",
        allowed: ALL_BUT_FATAL,
        after: Some(StepComplete),
        // SAFETY: `f.c` is a live instance of this test, and the call takes no other pointer.
        call: |f, d| unsafe { toy::fmi2SetFMUstate(f.c, d.state) },
    },
    Case {
        function: "fmi2FreeFMUstate",
        allowed: ALL_BUT_FATAL,
        after: None,
        call: |f, d| {
            let mut s = d.new_state();
            // SAFETY: `f.c` is a live instance of this test; each array or slot is a live local of at least the
            // announced length.
            let status = unsafe { toy::fmi2FreeFMUstate(f.c, &mut s) };
            assert!(status != fmi2OK || s.is_null(), "a freed state's slot is set to NULL");
            d.free(s);
            status
        },
    },
    Case {
        function: "fmi2SerializedFMUstateSize",
        allowed: ALL_BUT_FATAL,
        after: None,
        call: |f, d| {
            let mut size = 0;
            // SAFETY: `f.c` is a live instance of this test; each array or slot is a live local of at least the
            // announced length.
            let status = unsafe { toy::fmi2SerializedFMUstateSize(f.c, d.state, &mut size) };
            assert!(status != fmi2OK || size == d.bytes.len());
            status
        },
    },
    Case {
        function: "fmi2SerializeFMUstate",
        allowed: ALL_BUT_FATAL,
        after: None,
        call: |f, d| {
            let mut bytes = vec![0; d.bytes.len()];
            // SAFETY: `f.c` is a live instance of this test; each array or slot is a live local of at least the
            // announced length.
            unsafe { toy::fmi2SerializeFMUstate(f.c, d.state, bytes.as_mut_ptr(), bytes.len()) }
        },
    },
    Case {
        function: "fmi2DeSerializeFMUstate",
        allowed: ALL_BUT_FATAL,
        after: None,
        // SAFETY: `f.c` is a live instance of this test; the bytes and `s` are live locals of at least the announced
        // length.
        call: |f, d| d.freeing(|s| unsafe { toy::fmi2DeSerializeFMUstate(f.c, d.bytes.as_ptr(), d.bytes.len(), s) }),
    },
    Case { function: "fmi2DoStep", allowed: &[StepComplete], after: None, call: |f, _| f.do_step(0.0, 0.1) },
    Case {
        function: "fmi2GetRealStatus",
        allowed: STATUS,
        after: None,
        call: |f, _| {
            let mut v = f64::NAN;
            // SAFETY: `f.c` is a live instance of this test; each array or slot is a live local of at least the
            // announced length.
            unsafe { toy::fmi2GetRealStatus(f.c, fmi2LastSuccessfulTime, &mut v) }
        },
    },
    Case {
        function: "fmi2GetBooleanStatus",
        allowed: STATUS,
        after: None,
        call: |f, _| {
            let mut v = -1;
            // SAFETY: `f.c` is a live instance of this test; each array or slot is a live local of at least the
            // announced length.
            unsafe { toy::fmi2GetBooleanStatus(f.c, fmi2Terminated, &mut v) }
        },
    },
];

type Call = fn(fmi2Component) -> fmi2Status;

/// Functions this exporter does not support (Model Exchange; asynchronous steps; directional
/// and output derivatives, which the XML says are not provided): `fmi2Error` in every state.
const UNSUPPORTED: &[(&str, Call)] = &[
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2GetDirectionalDerivative", |c| unsafe {
        toy::fmi2GetDirectionalDerivative(c, null(), 0, null(), 0, null(), null_mut())
    }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2EnterEventMode", |c| unsafe { toy::fmi2EnterEventMode(c) }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2NewDiscreteStates", |c| unsafe { toy::fmi2NewDiscreteStates(c, &mut fmi2EventInfo::default()) }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2EnterContinuousTimeMode", |c| unsafe { toy::fmi2EnterContinuousTimeMode(c) }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2CompletedIntegratorStep", |c| unsafe { toy::fmi2CompletedIntegratorStep(c, fmi2True, &mut 0, &mut 0) }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2SetTime", |c| unsafe { toy::fmi2SetTime(c, 0.0) }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2SetContinuousStates", |c| unsafe { toy::fmi2SetContinuousStates(c, null(), 0) }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2GetDerivatives", |c| unsafe { toy::fmi2GetDerivatives(c, null_mut(), 0) }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2GetEventIndicators", |c| unsafe { toy::fmi2GetEventIndicators(c, null_mut(), 0) }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2GetContinuousStates", |c| unsafe { toy::fmi2GetContinuousStates(c, null_mut(), 0) }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2GetNominalsOfContinuousStates", |c| unsafe { toy::fmi2GetNominalsOfContinuousStates(c, null_mut(), 0) }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2GetRealOutputDerivatives", |c| unsafe {
        toy::fmi2GetRealOutputDerivatives(c, null(), 0, null(), null_mut())
    }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2CancelStep", |c| unsafe { toy::fmi2CancelStep(c) }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2GetStatus", |c| unsafe { toy::fmi2GetStatus(c, fmi2DoStepStatus, &mut 0) }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2GetIntegerStatus", |c| unsafe { toy::fmi2GetIntegerStatus(c, fmi2DoStepStatus, &mut 0) }),
    // SAFETY: an unsupported function reads none of its pointers; `c` is a test instance or NULL.
    ("fmi2GetStringStatus", |c| unsafe { toy::fmi2GetStringStatus(c, fmi2PendingStatus, &mut null()) }),
];

/// An instance in `StepComplete` lending FMU states (and their serialized bytes) to the calls
/// under test, so that the state functions can be tried in states where `fmi2GetFMUstate` is
/// itself refused.
struct Donor {
    fmu: Fmu,
    state: fmi2FMUstate,
    bytes: Vec<fmi2Byte>,
}

impl Donor {
    fn new() -> Donor {
        let fmu = Fmu::in_state(StepComplete);
        let mut state = null_mut();
        // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
        // length.
        fmu.ok(unsafe { toy::fmi2GetFMUstate(fmu.c, &mut state) });
        let mut size = 0;
        // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
        // length.
        fmu.ok(unsafe { toy::fmi2SerializedFMUstateSize(fmu.c, state, &mut size) });
        let mut bytes = vec![0; size];
        // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
        // length.
        fmu.ok(unsafe { toy::fmi2SerializeFMUstate(fmu.c, state, bytes.as_mut_ptr(), size) });
        Donor { fmu, state, bytes }
    }

    fn new_state(&self) -> fmi2FMUstate {
        let mut s = null_mut();
        // SAFETY: `self.fmu.c` is a live instance of this test; each array or slot is a live local of at least the
        // announced length.
        self.fmu.ok(unsafe { toy::fmi2GetFMUstate(self.fmu.c, &mut s) });
        s
    }

    /// `call` with a NULL state slot to fill; the state it may leave there is freed.
    fn freeing(&self, call: impl FnOnce(&mut fmi2FMUstate) -> fmi2Status) -> fmi2Status {
        let mut s = null_mut();
        let status = call(&mut s);
        self.free(s);
        status
    }

    /// Frees a state a call under test may have left (NULL is fine).
    fn free(&self, mut s: fmi2FMUstate) {
        // SAFETY: `self.fmu.c` is a live instance of this test; each array or slot is a live local of at least the
        // announced length.
        self.fmu.ok(unsafe { toy::fmi2FreeFMUstate(self.fmu.c, &mut s) });
    }
}

impl Drop for Donor {
    fn drop(&mut self) {
        self.free(self.state);
    }
}

#[test]
fn every_function_is_allowed_exactly_in_the_states_of_the_standard() {
    let donor = Donor::new();
    for case in CASES {
        for state in State::ALL {
            let fmu = Fmu::in_state(state);
            let status = (case.call)(&fmu, &donor);
            if case.allowed.contains(&state) {
                let context = format!("{} in {state:?}", case.function);
                assert_eq!(status, fmi2OK, "{context}: {:?}", fmu.messages());
                fmu.ok(status);
                assert_eq!(fmu.state(), case.after.unwrap_or(state), "state after {context}");
            } else {
                let text = fmu.refused(status, case.function, &["not allowed in state", &format!("{state:?}")]);
                assert_eq!(fmu.state(), state, "a refused call changes nothing: {text}");
            }
        }
    }
}

#[test]
fn unsupported_functions_fail_with_a_message_in_every_state() {
    for (function, call) in UNSUPPORTED {
        for state in State::ALL {
            let fmu = Fmu::in_state(state);
            fmu.refused(call(fmu.c), function, &["not supported"]);
            assert_eq!(fmu.state(), state, "{function} in {state:?} changes nothing");
        }
    }
}

/// Without an instance there is no logger to report to: the status is the whole answer, and it
/// must be an error, not a crash.
#[test]
fn a_null_component_is_an_error_for_every_function() {
    let donor = Donor::new();
    let fmu = Fmu::null();
    for case in CASES {
        assert_eq!((case.call)(&fmu, &donor), fmi2Error, "{} with a NULL component", case.function);
    }
    for (function, call) in UNSUPPORTED {
        assert_eq!(call(null_mut()), fmi2Error, "{function} with a NULL component");
    }
}

#[test]
fn a_whole_run_follows_the_standard_sequence() {
    let fmu = Fmu::new();
    fmu.ok(fmu.set_real(&[vr::GAIN, vr::U], &[2.0, 1.0]));
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    fmu.ok(unsafe { toy::fmi2SetupExperiment(fmu.c, fmi2False, 0.0, 1.0, fmi2True, 2.0) });
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    fmu.ok(unsafe { toy::fmi2EnterInitializationMode(fmu.c) });
    assert_eq!(fmu.reals(&[vr::Y]), [2.0], "outputs in initialization mode reflect the parameters set");
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    fmu.ok(unsafe { toy::fmi2ExitInitializationMode(fmu.c) });
    fmu.ok(fmu.do_step(1.0, 0.5));
    fmu.ok(fmu.do_step(1.5, 0.5));
    assert_eq!(fmu.time(), 2.0);
    assert_eq!(fmu.reals(&[vr::Y]), [4.0]);
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    fmu.ok(unsafe { toy::fmi2Terminate(fmu.c) });
    assert_eq!(fmu.state(), Terminated);
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    fmu.ok(unsafe { toy::fmi2Reset(fmu.c) });
    assert_eq!(fmu.state(), Instantiated);
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    fmu.ok(unsafe { toy::fmi2EnterInitializationMode(fmu.c) });
    assert_eq!(fmu.reals(&[vr::GAIN, vr::Y]), [1.0, 0.0], "a reset restores the start values");
}

#[test]
fn the_platform_functions_answer_without_an_instance() {
    // SAFETY: both return static NUL-terminated strings.
    let platform = unsafe { CStr::from_ptr(toy::fmi2GetTypesPlatform()) };
    // SAFETY: the function returns a pointer to a static NUL-terminated string.
    let version = unsafe { CStr::from_ptr(toy::fmi2GetVersion()) };
    assert_eq!(platform.to_str(), Ok(fmi2TypesPlatform));
    assert_eq!(version.to_str(), Ok(fmi2Version));
}
