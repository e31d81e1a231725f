//! The adapter on a fake FMI 3.0 FMU: how a step's outputs become FMI 2.0 statuses, and array
//! elements set and read through their whole array.

use super::adapter::Adapter;
use super::elements::Elements;
use super::step::{do_step, get_boolean_status, get_real_status};
use super::types::{Fmi3Element, Fmi3Type, Start};
use super::values::{get_real, set_real};
use super::Functions;
use crate::fmi::ffi;
use crate::fmi::{LogContext, LogEcho};
use fmi3_sys as f3;
use std::cell::Cell;

/// What the fake `fmi3DoStep` returns: its status and its output arguments
/// (eventHandlingNeeded, terminateSimulation, earlyReturn, lastSuccessfulTime).
#[derive(Clone, Copy)]
struct Step {
    status: f3::fmi3Status,
    event: bool,
    terminate: bool,
    early: bool,
    last: f64,
}

thread_local! {
    static STEP: Cell<Step> =
        const { Cell::new(Step { status: f3::fmi3OK, event: false, terminate: false, early: false, last: 0.0 }) };
}

unsafe extern "C" fn fake_do_step(
    _instance: f3::fmi3Instance,
    _t: f64,
    _h: f64,
    _no_set_prior: bool,
    event: *mut bool,
    terminate: *mut bool,
    early: *mut bool,
    last: *mut f64,
) -> f3::fmi3Status {
    let step = STEP.get();
    // SAFETY: the adapter passes four writable locals.
    unsafe { (*event, *terminate, *early, *last) = (step.event, step.terminate, step.early, step.last) };
    step.status
}

unsafe extern "C" fn never_instantiated(
    _name: f3::fmi3String,
    _token: f3::fmi3String,
    _resources: f3::fmi3String,
    _visible: bool,
    _logging_on: bool,
    _event_mode: bool,
    _early_return: bool,
    _required: *const f3::fmi3ValueReference,
    _n_required: usize,
    _environment: f3::fmi3InstanceEnvironment,
    _log: f3::fmi3LogMessageCallback,
    _intermediate: f3::fmi3IntermediateUpdateCallback,
) -> f3::fmi3Instance {
    std::ptr::null_mut()
}
unsafe extern "C" fn unused_free(_instance: f3::fmi3Instance) {}
unsafe extern "C" fn unused_logging(
    _instance: f3::fmi3Instance,
    _on: bool,
    _n: usize,
    _categories: *const f3::fmi3String,
) -> f3::fmi3Status {
    f3::fmi3Error
}
unsafe extern "C" fn unused_enter(
    _instance: f3::fmi3Instance,
    _tolerance_defined: bool,
    _tolerance: f64,
    _start: f64,
    _stop_defined: bool,
    _stop: f64,
) -> f3::fmi3Status {
    f3::fmi3Error
}
unsafe extern "C" fn unused_call(_instance: f3::fmi3Instance) -> f3::fmi3Status {
    f3::fmi3Error
}
macro_rules! unused_values {
    ($get:ident, $set:ident, $type:ty) => {
        unsafe extern "C" fn $get(
            _i: f3::fmi3Instance,
            _vr: *const u32,
            _n: usize,
            _v: *mut $type,
            _nv: usize,
        ) -> f3::fmi3Status {
            f3::fmi3Error
        }
        unsafe extern "C" fn $set(
            _i: f3::fmi3Instance,
            _vr: *const u32,
            _n: usize,
            _v: *const $type,
            _nv: usize,
        ) -> f3::fmi3Status {
            f3::fmi3Error
        }
    };
}
unused_values!(unused_get_f64, unused_set_f64, f64);
unused_values!(unused_get_i32, unused_set_i32, i32);
unused_values!(unused_get_bool, unused_set_bool, bool);
unused_values!(unused_get_string, unused_set_string, f3::fmi3String);

/// An adapter onto the fake FMU (only `fmi3DoStep` answers), logging into `log`.
fn adapter_on(log: &LogContext) -> Box<Adapter> {
    let functions = Functions {
        fmi3InstantiateCoSimulation: never_instantiated,
        fmi3FreeInstance: unused_free,
        fmi3SetDebugLogging: unused_logging,
        fmi3EnterInitializationMode: unused_enter,
        fmi3ExitInitializationMode: unused_call,
        fmi3Terminate: unused_call,
        fmi3Reset: unused_call,
        fmi3GetFloat64: unused_get_f64,
        fmi3GetInt32: unused_get_i32,
        fmi3GetBoolean: unused_get_bool,
        fmi3GetString: unused_get_string,
        fmi3SetFloat64: unused_set_f64,
        fmi3SetInt32: unused_set_i32,
        fmi3SetBoolean: unused_set_bool,
        fmi3SetString: unused_set_string,
        fmi3DoStep: fake_do_step,
        fmi3GetFloat32: None,
        fmi3GetInt8: None,
        fmi3GetUInt8: None,
        fmi3GetInt16: None,
        fmi3GetUInt16: None,
        fmi3GetUInt32: None,
        fmi3GetInt64: None,
        fmi3GetUInt64: None,
        fmi3SetFloat32: None,
        fmi3SetInt8: None,
        fmi3SetUInt8: None,
        fmi3SetInt16: None,
        fmi3SetUInt16: None,
        fmi3SetUInt32: None,
        fmi3SetInt64: None,
        fmi3SetUInt64: None,
        fmi3GetFMUState: None,
        fmi3SetFMUState: None,
        fmi3FreeFMUState: None,
        fmi3SerializedFMUStateSize: None,
        fmi3SerializeFMUState: None,
        fmi3DeserializeFMUState: None,
    };
    Box::new(Adapter {
        instance: std::ptr::null_mut(),
        functions,
        log: log.callbacks().componentEnvironment,
        tolerance: None,
        start: 0.0,
        stop: None,
        terminate_requested: false,
        last_successful_time: 0.0,
        elements: Elements::new(&[]),
    })
}

/// `fmi2DoStep` from t = 2.4 by 0.2 on the adapter when `fmi3DoStep` answers `step`: the
/// FMI 2.0 status, `fmi2Terminated` and `fmi2LastSuccessfulTime`, and what was logged.
fn step_with(step: Step) -> (ffi::fmi2Status, bool, f64, Vec<String>) {
    STEP.set(step);
    let log = LogContext::new("x", LogEcho::Off);
    let mut adapter = adapter_on(&log);
    let c = &mut *adapter as *mut Adapter as ffi::fmi2Component;
    let (mut terminated, mut last) = (-1, f64::NAN);
    // SAFETY: `c` is a live adapter, used by one call at a time.
    let status = unsafe { do_step(c, 2.4, 0.2, 1) };
    // SAFETY: as above; two writable slots.
    let statuses = unsafe {
        (
            get_boolean_status(c, ffi::fmi2Terminated, &mut terminated),
            get_real_status(c, ffi::fmi2LastSuccessfulTime, &mut last),
        )
    };
    assert_eq!(statuses, (ffi::fmi2OK, ffi::fmi2OK));
    (status, terminated != 0, last, log.messages().into_iter().map(|m| m.message).collect())
}

const OK: Step = Step { status: f3::fmi3OK, event: false, terminate: false, early: false, last: 2.6 };

#[test]
fn a_step_asking_to_end_the_simulation_is_a_terminating_discard_at_the_step_end_or_the_early_return() {
    assert_eq!(step_with(OK), (ffi::fmi2OK, false, 2.4 + 0.2, vec![]));
    let (status, terminated, last, log) = step_with(Step { terminate: true, ..OK });
    assert_eq!((status, terminated, last), (ffi::fmi2Discard, true, 2.4 + 0.2));
    assert!(log[0].starts_with("fmi3DoStep set terminateSimulation"), "{log:?}");
    let (status, terminated, last, _) = step_with(Step { terminate: true, early: true, last: 2.5, ..OK });
    assert_eq!((status, terminated, last), (ffi::fmi2Discard, true, 2.5));
}

#[test]
fn early_returns_and_event_requests_end_the_step_as_a_discard_saying_why() {
    let (status, terminated, last, log) = step_with(Step { early: true, last: 2.5, ..OK });
    assert_eq!((status, terminated, last), (ffi::fmi2Discard, false, 2.5));
    assert!(log[0].starts_with("fmi3DoStep returned early (earlyReturn)"), "{log:?}");
    let (status, terminated, _, log) = step_with(Step { event: true, ..OK });
    assert_eq!((status, terminated), (ffi::fmi2Discard, false));
    assert!(log[0].starts_with("fmi3DoStep set eventHandlingNeeded"), "{log:?}");
}

#[test]
fn the_output_arguments_of_a_discarded_step_are_not_taken() {
    // FMI 3.0 leaves them undefined after fmi3Discard: terminateSimulation written true there
    // is no request to end the simulation (the run then fails on the discard, as in FMPy),
    // and the step completed nothing.
    let discard = Step { status: f3::fmi3Discard, terminate: true, early: true, last: 2.5, ..OK };
    let (status, terminated, last, log) = step_with(discard);
    assert_eq!((status, terminated, last), (ffi::fmi2Discard, false, 2.4));
    assert!(log[0].contains("the request to end the simulation is not taken"), "{log:?}");
    let (status, terminated, _, _) = step_with(Step { status: f3::fmi3Error, terminate: true, ..OK });
    assert_eq!((status, terminated), (ffi::fmi2Error, false));
    let (status, terminated, last, log) = step_with(Step { status: f3::fmi3Discard, ..OK });
    assert_eq!((status, terminated, last, log), (ffi::fmi2Discard, false, 2.4, vec![]));
}

thread_local! {
    /// The fake FMU's Float64 array (value reference 7) as last set.
    static ARRAY: std::cell::RefCell<Vec<f64>> = const { std::cell::RefCell::new(Vec::new()) };
}

unsafe extern "C" fn array_get(
    _instance: f3::fmi3Instance,
    vr: *const u32,
    _n: usize,
    values: *mut f64,
    n_values: usize,
) -> f3::fmi3Status {
    // SAFETY: one value reference and `n_values` writable values, as the adapter passes.
    let (vr, out) = unsafe { (*vr, std::slice::from_raw_parts_mut(values, n_values)) };
    assert_eq!(vr, 7, "elements are read through their array");
    ARRAY.with_borrow(|array| out.copy_from_slice(&array.iter().map(|v| v * 10.0).collect::<Vec<_>>()));
    f3::fmi3OK
}

unsafe extern "C" fn array_set(
    _instance: f3::fmi3Instance,
    vr: *const u32,
    _n: usize,
    values: *const f64,
    n_values: usize,
) -> f3::fmi3Status {
    // SAFETY: as above, readable.
    let (vr, given) = unsafe { (*vr, std::slice::from_raw_parts(values, n_values)) };
    assert_eq!(vr, 7, "elements are set through their array");
    ARRAY.set(given.to_vec());
    f3::fmi3OK
}

#[test]
fn array_elements_are_set_with_the_rest_of_their_array_and_read_from_it() {
    let element = |index: usize| Fmi3Element {
        value_reference: 100 + index as u32,
        name: format!("u[{}]", index + 1),
        fmi3_value_reference: 7,
        fmi3_type: Fmi3Type::Float64,
        index,
        size: 3,
        start: Some(Start::Float(index as f64 + 1.0)),
    };
    let float32 = Fmi3Element {
        value_reference: 200,
        name: "gain".into(),
        fmi3_value_reference: 8,
        fmi3_type: Fmi3Type::Float32,
        index: 0,
        size: 1,
        start: None,
    };
    let log = LogContext::new("x", LogEcho::Off);
    let mut adapter = adapter_on(&log);
    adapter.functions.fmi3GetFloat64 = array_get;
    adapter.functions.fmi3SetFloat64 = array_set;
    adapter.elements = Elements::new(&[element(0), element(1), element(2), float32]);
    let c = &mut *adapter as *mut Adapter as ffi::fmi2Component;
    // SAFETY: a live adapter; arrays of the announced lengths.
    assert_eq!(unsafe { set_real(c, [101].as_ptr(), 1, [5.0].as_ptr()) }, ffi::fmi2OK);
    assert_eq!(ARRAY.with_borrow(Clone::clone), [1.0, 5.0, 3.0], "the other elements keep their start");
    // SAFETY: as above.
    assert_eq!(unsafe { set_real(c, [102, 100].as_ptr(), 2, [6.0, 4.0].as_ptr()) }, ffi::fmi2OK);
    assert_eq!(ARRAY.with_borrow(Clone::clone), [4.0, 5.0, 6.0], "and then the values last set");
    let mut out = [0.0; 3];
    // SAFETY: as above.
    assert_eq!(unsafe { get_real(c, [102, 100, 101].as_ptr(), 3, out.as_mut_ptr()) }, ffi::fmi2OK);
    assert_eq!(out, [60.0, 40.0, 50.0]);
    // A Float32 takes only values that are exactly 32-bit floats (refused before any call).
    // SAFETY: as above.
    assert_eq!(unsafe { set_real(c, [200].as_ptr(), 1, [0.1].as_ptr()) }, ffi::fmi2Error);
    let message = log.messages().pop().expect("a message").message;
    // The nearest float32 is shown widened (as a float32, 0.1f32 would print as "0.1").
    let expected = "gain is an FMI 3.0 Float32: 0.1 is not exactly a 32-bit float (the nearest is 0.10000000149011612)";
    assert!(message.contains(expected), "{message}");
}
