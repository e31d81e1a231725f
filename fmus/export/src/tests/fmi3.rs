//! The FMI 3.0 entry points of `Toy` (the `fmi3*` symbols `export_fmu!` generates beside the
//! `fmi2*` ones), driven as an FMI 3.0 host drives them: the description, a whole run against
//! the same run through FMI 2.0, the state machine under FMI 3.0's names, the arguments FMI 3.0
//! adds (nValues, the `fmi3DoStep` outputs, eventModeUsed), and the separation of the two APIs.

use super::host::{Fmu, Log as Log2};
use super::toy::{self, inert_model, vr, Toy};
use crate::ffi::{fmi2Error, fmi2OK, fmi2True};
use crate::ffi3::*;
use crate::fmi3::xml::TIME_VR;
use crate::variables::{Causality, Value, Variability, Variable};
use crate::ModelInfo;
use std::ffi::{c_char, c_void, CStr, CString};
use std::ptr::{null, null_mut};
use std::sync::Mutex;

/// What an FMI 3.0 logger received: (status, category, message).
#[derive(Default)]
struct Log(Mutex<Vec<(fmi3Status, String, String)>>);

impl Log {
    fn take(&self) -> Vec<(fmi3Status, String, String)> {
        std::mem::take(&mut *self.0.lock().unwrap_or_else(|e| e.into_inner()))
    }

    /// Whether some message contains every one of `parts`.
    fn has(&self, parts: &[&str]) -> bool {
        let messages = self.take();
        let found = messages.iter().any(|(_, _, text)| parts.iter().all(|p| text.contains(p)));
        assert!(found, "no message with {parts:?} in {messages:?}");
        found
    }
}

unsafe extern "C" fn capture(env: *mut c_void, status: fmi3Status, category: fmi3String, message: fmi3String) {
    // SAFETY: the exporter passes NUL-terminated strings valid for the call.
    let text = |p: *const c_char| unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned();
    // SAFETY: every instance of these tests gets a `Log` that outlives it as environment.
    if let Some(log) = unsafe { (env as *const Log).as_ref() } {
        log.0.lock().unwrap_or_else(|e| e.into_inner()).push((status, text(category), text(message)));
    }
}

/// The description `Toy`'s `fmi3rs_model_description` writes.
fn description() -> String {
    // SAFETY: a null buffer asks for the size; then the buffer has exactly that size.
    let mut buffer = vec![0u8; unsafe { toy::fmi3rs_model_description(null_mut(), 0) }];
    // SAFETY: as above.
    unsafe { toy::fmi3rs_model_description(buffer.as_mut_ptr() as *mut c_char, buffer.len()) };
    CStr::from_bytes_with_nul(&buffer).expect("one NUL, at the end").to_string_lossy().into_owned()
}

fn token() -> CString {
    let xml = description();
    let start = xml.find("instantiationToken=\"").expect("a token") + "instantiationToken=\"".len();
    CString::new(&xml[start..start + xml[start..].find('"').expect("closed")]).expect("no NUL")
}

/// One FMI 3.0 `Toy` instance with its own log; freed on drop.
struct Fmu3 {
    c: fmi3Instance,
    log: Box<Log>,
}

impl Fmu3 {
    fn instantiate(token: &CStr, event_mode_used: bool) -> (fmi3Instance, Box<Log>) {
        let log = Box::<Log>::default();
        // SAFETY: every pointer is valid for the call; `log` outlives the instance.
        let c = unsafe {
            toy::fmi3InstantiateCoSimulation(
                c"toy3".as_ptr(),
                token.as_ptr(),
                null(),
                false,
                false,
                event_mode_used,
                false,
                null(),
                0,
                &*log as *const Log as *mut c_void,
                Some(capture),
                None,
            )
        };
        (c, log)
    }

    fn new() -> Fmu3 {
        let (c, log) = Fmu3::instantiate(&token(), false);
        assert!(!c.is_null(), "fmi3InstantiateCoSimulation failed: {:?}", log.take());
        Fmu3 { c, log }
    }

    /// Initialized at t = 0 with stop time 10, in Step Mode.
    fn stepping() -> Fmu3 {
        let fmu = Fmu3::new();
        // SAFETY: `fmu.c` is live; no other pointer.
        assert_eq!(unsafe { toy::fmi3EnterInitializationMode(fmu.c, false, 0.0, 0.0, true, 10.0) }, fmi3OK);
        // SAFETY: as above.
        assert_eq!(unsafe { toy::fmi3ExitInitializationMode(fmu.c) }, fmi3OK);
        fmu
    }

    fn set_f64(&self, vrs: &[u32], values: &[f64]) -> fmi3Status {
        // SAFETY: live instance; arrays of the announced lengths.
        unsafe { toy::fmi3SetFloat64(self.c, vrs.as_ptr(), vrs.len(), values.as_ptr(), values.len()) }
    }

    fn get_f64(&self, vrs: &[u32]) -> (fmi3Status, Vec<f64>) {
        let mut out = vec![f64::NAN; vrs.len()];
        // SAFETY: live instance; arrays of the announced lengths.
        let status = unsafe { toy::fmi3GetFloat64(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr(), out.len()) };
        (status, out)
    }

    /// `fmi3DoStep` and its four outputs.
    fn step(&self, t: f64, h: f64) -> (fmi3Status, [bool; 3], f64) {
        let (mut event, mut terminate, mut early, mut last) = (true, true, true, f64::NAN);
        // SAFETY: live instance; each output a live local.
        let status = unsafe { toy::fmi3DoStep(self.c, t, h, true, &mut event, &mut terminate, &mut early, &mut last) };
        (status, [event, terminate, early], last)
    }
}

impl Drop for Fmu3 {
    fn drop(&mut self) {
        // SAFETY: the instance is live (or NULL) and freed once.
        unsafe { toy::fmi3FreeInstance(self.c) }
    }
}

#[test]
fn the_description_is_fmi3_with_the_same_variables_and_a_token_instantiation_checks() {
    let xml = description();
    for part in [
        r#"fmiVersion="3.0""#,
        r#"<CoSimulation modelIdentifier="toy""#,
        r#"canHandleVariableCommunicationStepSize="true""#,
        r#"hasEventMode="false""#,
        r#"<Float64 name="time" valueReference="2147483647""#,
        r#"causality="independent""#,
        r#"<Float64 name="gain" valueReference="0""#,
        r#"<Int32 name="order" valueReference="10""#,
        r#"<Boolean name="positive" valueReference="21""#,
        r#"<Output valueReference="3"/>"#,
        r#"<Unit name="1"/>"#,
    ] {
        assert!(xml.contains(part), "{part} missing from\n{xml}");
    }
    assert_eq!(token().to_str().unwrap(), crate::fmi3::xml::render::<Toy>().unwrap().guid);
    assert_ne!(token(), super::host::toy_guid(), "FMI 2.0 and 3.0 descriptions differ, so do their GUIDs");
    // A token of another build is refused with a message.
    let (c, log) = Fmu3::instantiate(&super::host::toy_guid(), false);
    assert!(c.is_null());
    assert!(log.has(&["fmi3InstantiateCoSimulation", "instantiationToken", "does not match"]));
}

#[test]
fn a_table_that_reuses_a_value_reference_across_types_has_no_fmi3_description() {
    #[derive(Clone, serde::Serialize, serde::Deserialize)]
    struct Clash;
    inert_model!(Clash {
        info: ModelInfo {
            model_identifier: "clash",
            description: "Real 0 and Integer 0",
            default_stop_time: 1.0,
            default_step_size: 0.1,
            can_interpolate_inputs: false,
            max_step_size: 1.0,
        },
        variables: &CLASH_VARIABLES,
        new: Clash,
    });
    static CLASH_VARIABLES: [Variable<Clash>; 2] = [
        Variable {
            vr: 0,
            name: "x",
            description: "a Real",
            causality: Causality::Output,
            variability: Variability::Continuous,
            value: Value::Real {
                unit: "",
                start: 0.0,
                min: None,
                max: None,
                get: |_| 0.0,
                set: None,
                derivative: None,
            },
        },
        Variable {
            vr: 0,
            name: "n",
            description: "an Integer",
            causality: Causality::Output,
            variability: Variability::Discrete,
            value: Value::Integer { start: 0, min: None, max: None, get: |_| 0, set: None },
        },
    ];
    assert!(crate::fmi2::xml::render::<Clash>().is_ok(), "FMI 2.0 allows it");
    let refused = crate::fmi3::xml::render::<Clash>().err().expect("FMI 3.0 does not");
    assert!(refused.contains("value reference 0 is used by 'x' and 'n'"), "{refused}");
}

/// The same inputs through both APIs give the same bits, step for step, and `fmi3DoStep`
/// reports no event, no termination, no early return and the time reached.
#[test]
fn a_run_through_fmi3_equals_the_run_through_fmi2_bit_for_bit() {
    let fmu3 = Fmu3::new();
    let fmu2 = Fmu::new();
    assert_eq!(fmu3.set_f64(&[vr::GAIN], &[1.5]), fmi3OK);
    assert_eq!(fmu2.set_real(&[vr::GAIN], &[1.5]), fmi2OK);
    // SAFETY: live instances; no other pointer.
    unsafe {
        assert_eq!(toy::fmi3EnterInitializationMode(fmu3.c, true, 1e-6, 0.0, false, 0.0), fmi3OK);
        assert_eq!(toy::fmi3ExitInitializationMode(fmu3.c), fmi3OK);
        assert_eq!(toy::fmi2SetupExperiment(fmu2.c, 0, 0.0, 0.0, 0, 0.0), fmi2OK);
        assert_eq!(toy::fmi2EnterInitializationMode(fmu2.c), fmi2OK);
        assert_eq!(toy::fmi2ExitInitializationMode(fmu2.c), fmi2OK);
    }
    let h = 0.1;
    for k in 0..50 {
        let t = k as f64 * h;
        let u = (0.3 * t).sin();
        assert_eq!(fmu3.set_f64(&[vr::U, vr::RATE], &[u, 0.01 * k as f64]), fmi3OK);
        assert_eq!(fmu2.set_real(&[vr::U, vr::RATE], &[u, 0.01 * k as f64]), fmi2OK);
        let (status, flags, last) = fmu3.step(t, h);
        assert_eq!((status, flags, last), (fmi3OK, [false; 3], t + h));
        // SAFETY: live instance; no other pointer.
        assert_eq!(unsafe { toy::fmi2DoStep(fmu2.c, t, h, fmi2True) }, fmi2OK);
        let (status, y3) = fmu3.get_f64(&[vr::Y, TIME_VR]);
        assert_eq!(status, fmi3OK);
        assert_eq!(y3[0].to_bits(), fmu2.get_real(&[vr::Y]).1[0].to_bits(), "step {k}");
        assert_eq!(y3[1], t + h, "time is readable");
    }
    // SAFETY: live instances; no other pointer.
    unsafe {
        assert_eq!(toy::fmi3Terminate(fmu3.c), fmi3OK);
        assert_eq!(toy::fmi3Reset(fmu3.c), fmi3OK);
    }
}

#[test]
fn the_state_machine_refuses_calls_with_fmi3_state_names() {
    let fmu = Fmu3::new();
    let (status, ..) = fmu.step(0.0, 0.1);
    assert_eq!(status, fmi3Error);
    assert!(fmu.log.has(&["fmi3DoStep is not allowed in state Instantiated (allowed in: StepMode)"]));
    let stepping = Fmu3::stepping();
    // SAFETY: live instance.
    assert_eq!(unsafe { toy::fmi3EnterInitializationMode(stepping.c, false, 0.0, 0.0, false, 0.0) }, fmi3Error);
    assert!(stepping.log.has(&["fmi3EnterInitializationMode is not allowed in state StepMode"]));
    // Steps past the stop time given at fmi3EnterInitializationMode are refused.
    let (status, _, last) = stepping.step(0.0, 11.0);
    assert_eq!((status, last), (fmi3Error, 0.0), "the time before the refused step");
    assert!(stepping.log.has(&["goes past stopTime 10"]));
    // A stop time before the start is refused as a whole, and the instance stays Instantiated.
    let fresh = Fmu3::new();
    // SAFETY: live instance.
    assert_eq!(unsafe { toy::fmi3EnterInitializationMode(fresh.c, false, 0.0, 5.0, true, 1.0) }, fmi3Error);
    // SAFETY: live instance.
    assert_eq!(unsafe { toy::fmi3EnterInitializationMode(fresh.c, false, 0.0, 0.0, false, 0.0) }, fmi3OK);
}

#[test]
fn fmi3_arguments_are_checked() {
    let fmu = Fmu3::stepping();
    // nValues must equal nValueReferences: every variable is a scalar.
    let mut out = [0.0; 2];
    // SAFETY: live instance; arrays of at least the announced lengths.
    let status = unsafe { toy::fmi3GetFloat64(fmu.c, [vr::Y].as_ptr(), 1, out.as_mut_ptr(), 2) };
    assert_eq!(status, fmi3Error);
    assert!(fmu.log.has(&["nValues = 2 differs from nValueReferences = 1"]));
    // A type the FMU has no variable of: empty calls succeed, any value reference is unknown.
    let mut f32s = [0.0f32; 1];
    // SAFETY: as above.
    assert_eq!(unsafe { toy::fmi3GetFloat32(fmu.c, null(), 0, f32s.as_mut_ptr(), 0) }, fmi3OK);
    // SAFETY: as above.
    assert_eq!(unsafe { toy::fmi3GetFloat32(fmu.c, [vr::Y].as_ptr(), 1, f32s.as_mut_ptr(), 1) }, fmi3Error);
    assert!(fmu.log.has(&["fmi3GetFloat32", "unknown Float32 value reference 3"]));
    // nValues counts the values of the variables referenced: none for none.
    // SAFETY: as above.
    assert_eq!(unsafe { toy::fmi3GetFloat32(fmu.c, null(), 0, f32s.as_mut_ptr(), 1) }, fmi3Error);
    assert!(fmu.log.has(&["nValues = 1 differs from nValueReferences = 0"]));
    // `time` is read-only, and the Float64 of another type's value reference is unknown.
    assert_eq!(fmu.set_f64(&[TIME_VR], &[1.0]), fmi3Error);
    assert_eq!(fmu.get_f64(&[vr::ORDER]).0, fmi3Error);
    // Int32, Boolean and String go to the table's Integer, Boolean and String variables.
    let mut order = [0i32; 1];
    // SAFETY: as above.
    assert_eq!(unsafe { toy::fmi3GetInt32(fmu.c, [vr::ORDER].as_ptr(), 1, order.as_mut_ptr(), 1) }, fmi3OK);
    assert_eq!(order, [2]);
    // A C bool other than 0 or 1 is read as true, never as an invalid Rust bool.
    let odd_true = [2u8];
    // SAFETY: as above; one byte per C bool.
    let status = unsafe { toy::fmi3SetBoolean(fmu.c, [vr::HOLD].as_ptr(), 1, odd_true.as_ptr() as *const bool, 1) };
    assert_eq!(status, fmi3OK);
    let mut hold = [false; 1];
    // SAFETY: as above.
    assert_eq!(unsafe { toy::fmi3GetBoolean(fmu.c, [vr::HOLD].as_ptr(), 1, hold.as_mut_ptr(), 1) }, fmi3OK);
    assert_eq!(hold, [true]);
    // A NULL output of fmi3DoStep is refused before the step.
    let (mut a, mut b, mut last) = (false, false, 0.0);
    // SAFETY: live instance; NULL is what is tested.
    let status = unsafe { toy::fmi3DoStep(fmu.c, 0.0, 0.1, true, &mut a, &mut b, null_mut(), &mut last) };
    assert_eq!(status, fmi3Error);
    assert!(fmu.log.has(&["earlyReturn", "is NULL"]));
    assert_eq!(fmu.step(0.0, 0.1).0, fmi3OK, "nothing stepped before");
}

#[test]
fn what_the_fmu_does_not_offer_is_refused_with_a_reason() {
    let (c, log) = Fmu3::instantiate(&token(), true);
    assert!(c.is_null());
    assert!(log.has(&["eventModeUsed is true", "hasEventMode"]));
    let log = Log::default();
    // SAFETY: every pointer valid for the call.
    let c = unsafe {
        toy::fmi3InstantiateModelExchange(
            c"me".as_ptr(),
            token().as_ptr(),
            null(),
            false,
            false,
            &log as *const Log as *mut c_void,
            Some(capture),
        )
    };
    assert!(c.is_null());
    assert!(log.has(&["fmi3InstantiateModelExchange", "Co-Simulation FMU only"]));
    let fmu = Fmu3::stepping();
    // SAFETY: live instance.
    assert_eq!(unsafe { toy::fmi3EnterEventMode(fmu.c) }, fmi3Error);
    assert!(fmu.log.has(&["fmi3EnterEventMode is not supported by toy"]));
    let mut n = 0usize;
    // SAFETY: live instance; a live slot.
    assert_eq!(unsafe { toy::fmi3GetNumberOfContinuousStates(fmu.c, &mut n) }, fmi3Error);
    // Clocks are read and set in Event Mode only (FMI 3.0 §2.3.5), which these FMUs never
    // enter: even an empty call is refused, in every state.
    // SAFETY: live instance; no value reference, no value.
    assert_eq!(unsafe { toy::fmi3GetClock(fmu.c, null(), 0, null_mut()) }, fmi3Error);
    assert!(fmu.log.has(&["fmi3GetClock is not supported by toy"]));
    // SAFETY: as above.
    assert_eq!(unsafe { toy::fmi3SetClock(Fmu3::new().c, null(), 0, null()) }, fmi3Error);
    // NULL instances are refused unread.
    // SAFETY: NULL is what is tested.
    assert_eq!(unsafe { toy::fmi3Terminate(null_mut()) }, fmi3Error);
}

/// An instance answers only the API that created it: the other version's calls are refused
/// without touching it (as a foreign pointer is).
#[test]
fn an_instance_is_driven_only_through_the_api_that_created_it() {
    let fmu3 = Fmu3::stepping();
    // SAFETY: a live instance, but of the other API: refused unread.
    assert_eq!(unsafe { toy::fmi2DoStep(fmu3.c, 0.0, 0.1, fmi2True) }, fmi2Error);
    // SAFETY: as above; an FMI 2.0 free of an FMI 3.0 instance frees nothing.
    unsafe { toy::fmi2FreeInstance(fmu3.c) };
    assert_eq!(fmu3.step(0.0, 0.1).0, fmi3OK, "still live");
    let fmu2 = Fmu::in_state(crate::state::State::StepComplete);
    let (mut a, mut b, mut e, mut last) = (false, false, false, 0.0);
    // SAFETY: as above.
    assert_eq!(unsafe { toy::fmi3DoStep(fmu2.c, 0.0, 0.1, true, &mut a, &mut b, &mut e, &mut last) }, fmi3Error);
    let _ = Log2::default();
}

#[test]
fn fmu_states_round_trip_through_fmi3_serialization() {
    let fmu = Fmu3::stepping();
    assert_eq!(fmu.set_f64(&[vr::U], &[0.5]), fmi3OK);
    assert_eq!(fmu.step(0.0, 0.1).0, fmi3OK);
    let mut state: fmi3FMUState = null_mut();
    let mut size = 0usize;
    // SAFETY: live instance; live slots and a buffer of the announced size.
    unsafe {
        assert_eq!(toy::fmi3GetFMUState(fmu.c, &mut state), fmi3OK);
        assert_eq!(toy::fmi3SerializedFMUStateSize(fmu.c, state, &mut size), fmi3OK);
    }
    let mut bytes = vec![0u8; size];
    // SAFETY: as above.
    unsafe {
        assert_eq!(toy::fmi3SerializeFMUState(fmu.c, state, bytes.as_mut_ptr(), size), fmi3OK);
        assert_eq!(toy::fmi3FreeFMUState(fmu.c, &mut state), fmi3OK);
    }
    assert!(state.is_null());
    let before = fmu.get_f64(&[vr::Y]).1;
    assert_eq!(fmu.step(0.1, 0.1).0, fmi3OK);
    let after = fmu.get_f64(&[vr::Y]).1;
    let mut restored: fmi3FMUState = null_mut();
    // SAFETY: as above.
    unsafe {
        assert_eq!(toy::fmi3DeserializeFMUState(fmu.c, bytes.as_ptr(), size, &mut restored), fmi3OK);
        assert_eq!(toy::fmi3SetFMUState(fmu.c, restored), fmi3OK);
    }
    assert_eq!(fmu.get_f64(&[vr::Y]).1, before);
    assert_eq!(fmu.step(0.1, 0.1).0, fmi3OK);
    assert_eq!(fmu.get_f64(&[vr::Y]).1[0].to_bits(), after[0].to_bits(), "continues bit for bit");
    assert_eq!(crate::calls::unfreed_states::<Toy>(fmu.c), 1, "freed with the instance");
}
