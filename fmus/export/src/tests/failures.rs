//! Failures: a non-finite output or a model failure puts the instance in `Error` (the crate's
//! rule, so that no importer integrates garbage), a panic becomes `fmi2Fatal` without unwinding
//! into C, and bad step or instantiation arguments are errors with a message.

use super::host::{callbacks, toy_description, toy_guid, Fmu, Log, Message};
use super::toy::{self, vr};
use crate::ffi::*;
use crate::state::State::*;
use std::ffi::c_char;
use std::ptr::null;
use std::sync::atomic::{AtomicBool, Ordering::SeqCst};

#[test]
fn a_non_finite_output_after_a_step_puts_the_instance_in_error() {
    for rate in [1e308, -1e308] {
        let fmu = Fmu::in_state(StepComplete);
        fmu.ok(fmu.set_real(&[vr::RATE], &[rate]));
        fmu.refused(fmu.do_step(0.0, 10.0), "fmi2DoStep", &["output 'y'", "inf"]);
        assert_eq!(fmu.state(), Error);

        // Error allows reading (to diagnose: the value is written, with fmi2Error), resetting and
        // FMU states, nothing that goes on.
        let (status, y) = fmu.get_real(&[vr::Y]);
        assert!(status == fmi2Error && y[0].is_infinite(), "{status} {y:?}");
        fmu.refused(fmu.do_step(10.0, 0.1), "fmi2DoStep", &["not allowed in state Error"]);
        fmu.refused(fmu.set_real(&[vr::RATE], &[0.0]), "fmi2SetReal", &["not allowed in state Error"]);
        // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
        fmu.refused(unsafe { toy::fmi2Terminate(fmu.c) }, "fmi2Terminate", &["not allowed in state Error"]);
        assert_eq!(fmu.state(), Error);

        // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
        fmu.ok(unsafe { toy::fmi2Reset(fmu.c) });
        assert_eq!(fmu.state(), Instantiated);
        fmu.initialize(0.0, None);
        fmu.ok(fmu.do_step(0.0, 1.0));
        assert_eq!(fmu.reals(&[vr::Y, vr::RATE]), [0.0, 0.0], "a reset run starts from the start values");
    }
}

#[test]
fn a_non_finite_output_at_initialization_puts_the_instance_in_error() {
    let fmu = Fmu::in_state(InitializationMode);
    fmu.ok(fmu.set_real(&[vr::GAIN, vr::U], &[10.0, 1e308]));
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    let status = unsafe { toy::fmi2ExitInitializationMode(fmu.c) };
    fmu.refused(status, "fmi2ExitInitializationMode", &["output 'y'", "inf"]);
    assert_eq!(fmu.state(), Error);
    fmu.refused(fmu.do_step(0.0, 0.1), "fmi2DoStep", &["not allowed in state Error"]);
}

/// A getter never returns a non-finite value with `fmi2OK`: outputs that follow the inputs
/// directly (here in initialization mode) are checked as they are read, and the instance goes
/// to `Error`; finite values of the same call are still written.
#[test]
fn reading_a_non_finite_output_is_an_error_and_puts_the_instance_in_error() {
    let fmu = Fmu::in_state(InitializationMode);
    fmu.ok(fmu.set_real(&[vr::GAIN, vr::U], &[10.0, 1e308]));
    let (status, values) = fmu.get_real(&[vr::GAIN, vr::Y]);
    assert_eq!((status, values[0]), (fmi2Error, 10.0));
    assert!(values[1].is_infinite());
    let text = fmu.refused(status, "fmi2GetReal", &["'y' is inf"]);
    assert!(text.contains("state Error"), "{text}");
    assert_eq!(fmu.state(), Error);
}

/// Refused step arguments are the host's mistake, not the model's: the instance stays in step
/// mode at the same time, and a correct step still works.
#[test]
fn bad_step_arguments_are_refused_and_change_nothing() {
    let fmu = Fmu::in_state(StepComplete);
    fmu.ok(fmu.set_real(&[vr::RATE], &[1.0]));
    for h in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        fmu.refused(fmu.do_step(0.0, h), "fmi2DoStep", &[]);
    }
    let text = fmu.refused(fmu.do_step(0.0, 0.0), "fmi2DoStep", &["communicationStepSize must be > 0"]);
    assert_eq!(text.matches("fmi2DoStep").count(), 1, "the function is named once: {text}");
    fmu.refused(fmu.do_step(0.3, 0.1), "fmi2DoStep", &["currentCommunicationPoint 0.3", "current time 0"]);
    fmu.refused(fmu.do_step(f64::NAN, 0.1), "fmi2DoStep", &["non-finite"]);
    assert_eq!(fmu.state(), StepComplete);
    assert_eq!(fmu.time(), 0.0);
    assert_eq!(fmu.reals(&[vr::Y]), [0.0]);
    fmu.ok(fmu.do_step(0.0, 0.5));
    assert_eq!(fmu.reals(&[vr::Y]), [0.5]);
}

/// The work of one `fmi2DoStep` is bounded: a step longer than the model's declared maximum is
/// refused with a message naming the limit, and the instance can go on with shorter steps.
#[test]
fn a_step_longer_than_the_models_maximum_is_refused_naming_the_limit() {
    let fmu = Fmu::in_state(StepComplete);
    for h in [toy::MAX_STEP_SIZE * 1.5, 1e9, 1e300] {
        fmu.refused(fmu.do_step(0.0, h), "fmi2DoStep", &["exceeds the largest step", "100 s per fmi2DoStep"]);
    }
    assert_eq!((fmu.state(), fmu.time()), (StepComplete, 0.0));
    fmu.ok(fmu.do_step(0.0, toy::MAX_STEP_SIZE));
    assert_eq!(fmu.time(), toy::MAX_STEP_SIZE);
}

/// At a large time the communication point must still match to a microsecond (a relative
/// tolerance of 1e-9 would accept 1 ms at t = 1e7 s), and a step too short to change t is
/// refused rather than taken without time advancing, as is one that would overflow t.
#[test]
fn at_large_times_communication_points_are_exact_and_steps_must_advance_time() {
    let fmu = Fmu::new();
    fmu.initialize(1e7, None);
    fmu.refused(fmu.do_step(1e7 + 1e-3, 0.1), "fmi2DoStep", &["currentCommunicationPoint 10000000.001"]);
    fmu.ok(fmu.do_step(1e7 + 1e-7, 0.1));
    let late = Fmu::new();
    late.initialize(1e300, None);
    // Very large and very small numbers read in exponent form, not as hundreds of digits.
    let message = late.refused(late.do_step(1e300, 1.0), "fmi2DoStep", &["does not advance time", "t = 1e300 s"]);
    assert!(message.len() < 200, "{message}");
    let message = late.refused(late.do_step(1e300, 5e-324), "fmi2DoStep", &["a step of 5e-324 s from t = 1e300 s"]);
    assert!(message.len() < 200, "{message}");
    late.refused(late.do_step(1e300, f64::MAX), "fmi2DoStep", &["past the largest representable time"]);
    assert_eq!(late.state(), StepComplete);
}

#[test]
fn steps_past_the_stop_time_are_refused() {
    let fmu = Fmu::new();
    fmu.initialize(0.0, Some(1.0));
    fmu.refused(fmu.do_step(0.0, 1.5), "fmi2DoStep", &["past stopTime 1"]);
    fmu.ok(fmu.do_step(0.0, 1.0));
    assert_eq!(fmu.time(), 1.0);
}

#[test]
fn an_inconsistent_experiment_is_refused() {
    let fmu = Fmu::new();
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    let status = unsafe { toy::fmi2SetupExperiment(fmu.c, fmi2False, 0.0, 2.0, fmi2True, 1.0) };
    fmu.refused(status, "fmi2SetupExperiment", &["stopTime 1 is before startTime 2"]);
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    let status = unsafe { toy::fmi2SetupExperiment(fmu.c, fmi2False, 0.0, f64::NAN, fmi2False, 0.0) };
    fmu.refused(status, "fmi2SetupExperiment", &["not finite"]);
    assert_eq!(fmu.state(), Instantiated);
}

/// A saved state must always be serializable, so nothing non-finite enters through the
/// experiment: an infinite stop time (defined) and an unusable tolerance are refused, naming
/// the argument and its value; an infinite stop time that is not defined is ignored.
#[test]
fn a_non_finite_experiment_is_refused_by_name() {
    let fmu = Fmu::new();
    let refusals = [
        (
            fmi2False,
            0.0,
            0.0,
            fmi2True,
            f64::INFINITY,
            "stopTime inf is not finite (leave stopTimeDefined false for no stop time)",
        ),
        (fmi2False, 0.0, 0.0, fmi2True, f64::NAN, "stopTime NaN is not finite"),
        (fmi2False, 0.0, f64::NEG_INFINITY, fmi2False, 0.0, "startTime -inf is not finite"),
        (fmi2True, f64::NAN, 0.0, fmi2False, 0.0, "tolerance NaN is not a finite positive number"),
        (fmi2True, f64::INFINITY, 0.0, fmi2False, 0.0, "tolerance inf is not a finite positive number"),
        (fmi2True, 0.0, 0.0, fmi2False, 0.0, "tolerance 0 is not a finite positive number"),
        (fmi2True, -1e-6, 0.0, fmi2False, 0.0, "tolerance -0.000001 is not a finite positive number"),
    ];
    for (tolerance_defined, tolerance, start, stop_defined, stop, message) in refusals {
        // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
        let status =
            unsafe { toy::fmi2SetupExperiment(fmu.c, tolerance_defined, tolerance, start, stop_defined, stop) };
        fmu.refused(status, "fmi2SetupExperiment", &[message]);
    }
    // SAFETY: as above.
    fmu.ok(unsafe { toy::fmi2SetupExperiment(fmu.c, fmi2False, f64::NAN, 0.0, fmi2False, f64::INFINITY) });
    // SAFETY: as above.
    fmu.ok(unsafe { toy::fmi2SetupExperiment(fmu.c, fmi2True, 1e-6, 0.0, fmi2True, 10.0) });
    assert_eq!(fmu.state(), Instantiated);
}

/// A panic in the model must not unwind into the host: the call returns `fmi2Fatal` with a
/// message, and the instance accepts nothing afterwards but being freed.
#[test]
fn a_panic_in_the_model_is_fatal_and_reported() {
    let fmu = Fmu::in_state(StepComplete);
    fmu.ok(fmu.set_integer(&[vr::COMMAND], &[toy::PANIC_COMMAND]));
    let status = fmu.do_step(0.0, 0.1);
    let messages = fmu.messages();
    assert_eq!(status, fmi2Fatal, "{messages:?}");
    assert!(
        messages.iter().any(|m| m.status == fmi2Fatal
            && m.text.contains("fmi2DoStep")
            && m.text.contains("internal error")
            && m.text.contains("reached a model bug")),
        "{messages:?}"
    );
    assert_eq!(fmu.state(), Fatal);
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    fmu.refused(unsafe { toy::fmi2Reset(fmu.c) }, "fmi2Reset", &["not allowed in state Fatal"]);
}

/// The panic hook sends the panic's message and location to the instance's logger (instead of
/// the host's stderr, where Rust's default hook writes).
#[test]
fn the_panic_hook_reports_the_location_to_the_logger_of_the_instance() {
    let fmu = Fmu::in_state(StepComplete);
    fmu.ok(fmu.set_integer(&[vr::COMMAND], &[toy::PANIC_COMMAND]));
    fmu.do_step(0.0, 0.1);
    let messages = fmu.messages();
    assert!(
        messages.iter().any(|m| m.status == fmi2Fatal
            && m.category == "logStatusError"
            && m.text.contains("panicked at fmus/export/src/tests/toy.rs:")
            && m.text.contains("reached a model bug")),
        "{messages:?}"
    );
}

/// Each panic's report reaches the logger of the instance whose call panicked, once, also while
/// another thread keeps calling another instance (whose logger gets none of them).
#[test]
fn panic_reports_go_to_the_panicking_instance_only_while_other_threads_call() {
    let stop = AtomicBool::new(false);
    std::thread::scope(|scope| {
        let busy = scope.spawn(|| {
            let fmu = Fmu::in_state(StepComplete);
            let mut steps = 0;
            while steps < 100 || !stop.load(SeqCst) {
                fmu.ok(fmu.do_step(fmu.time(), 1e-3));
                steps += 1;
            }
            fmu.messages()
        });
        // Asserted after the busy thread stopped: a failed assertion here would leave it running.
        let panicked: Vec<(fmi2Status, Vec<Message>)> = (0..20)
            .map(|_| {
                let fmu = Fmu::in_state(StepComplete);
                fmu.ok(fmu.set_integer(&[vr::COMMAND], &[toy::PANIC_COMMAND]));
                (fmu.do_step(0.0, 0.1), fmu.messages())
            })
            .collect();
        stop.store(true, SeqCst);
        let busy = busy.join().expect("the busy thread's calls succeed");
        assert!(busy.iter().all(|m| !m.text.contains("panicked at")), "{busy:?}");
        for (status, messages) in panicked {
            let reports = messages.iter().filter(|m| m.text.contains("panicked at")).count();
            assert_eq!((status, reports), (fmi2Fatal, 1), "{messages:?}");
        }
    });
}

/// `fmi2Instantiate` with the given arguments; the component (if any) is freed.
fn instantiate(
    name: fmi2String,
    kind: fmi2Type,
    guid: fmi2String,
    functions: *const fmi2CallbackFunctions,
) -> fmi2Component {
    // SAFETY: every argument is NULL or points to a live local (C strings, callbacks) for the call.
    let c = unsafe { toy::fmi2Instantiate(name, kind, guid, null(), functions, fmi2False, fmi2False) };
    // SAFETY: `c` is what fmi2Instantiate just returned, NULL or a live instance, freed once
    // here (freeing NULL is a no-op).
    unsafe { toy::fmi2FreeInstance(c) };
    c
}

#[test]
fn instantiation_refuses_wrong_arguments_with_a_message() {
    let guid = toy_guid();
    let wrong = c"{00000000-0000-0000-0000-000000000000}";
    let cases: [(&str, fmi2String, fmi2Type, fmi2String, &[&str]); 6] = [
        ("a foreign GUID", c"x".as_ptr(), fmi2CoSimulation, wrong.as_ptr(), &["GUID {00000000-", "does not match"]),
        ("Model Exchange", c"x".as_ptr(), fmi2ModelExchange, guid.as_ptr(), &["Co-Simulation only"]),
        ("no GUID", c"x".as_ptr(), fmi2CoSimulation, null(), &["fmuGUID is NULL"]),
        ("no instance name", null(), fmi2CoSimulation, guid.as_ptr(), &["instanceName is NULL"]),
        ("an empty instance name", c"".as_ptr(), fmi2CoSimulation, guid.as_ptr(), &["instanceName is empty"]),
        ("a blank instance name", c" \t".as_ptr(), fmi2CoSimulation, guid.as_ptr(), &["instanceName is empty"]),
    ];
    for (what, name, kind, guid, words) in cases {
        let log = Log::default();
        assert!(instantiate(name, kind, guid, &callbacks(&log)).is_null(), "{what}");
        let messages = log.take();
        assert!(
            messages.iter().any(|m| m.status == fmi2Error
                && m.text.contains("fmi2Instantiate")
                && words.iter().all(|w| m.text.contains(w))),
            "{what}: {messages:?}"
        );
    }
    // A foreign token of a megabyte is quoted by its start and length, not echoed whole.
    let long = std::ffi::CString::new("{".repeat(1 << 20)).unwrap();
    let log = Log::default();
    assert!(instantiate(c"x".as_ptr(), fmi2CoSimulation, long.as_ptr(), &callbacks(&log)).is_null());
    let messages = log.take();
    let refusal = messages.iter().find(|m| m.text.contains("does not match")).expect("a refusal");
    assert!(refusal.text.contains("… (1048576 characters)") && refusal.text.len() < 300, "{}", refusal.text);
    // Without callbacks or without a logger there is nobody to tell why.
    assert!(instantiate(c"x".as_ptr(), fmi2CoSimulation, guid.as_ptr(), null()).is_null());
    let log = Log::default();
    let silent = fmi2CallbackFunctions { logger: None, ..callbacks(&log) };
    assert!(instantiate(c"x".as_ptr(), fmi2CoSimulation, guid.as_ptr(), &silent).is_null());
}

#[test]
fn the_exported_description_carries_the_guid_instantiate_checks() {
    let xml = toy_description();
    assert_eq!(toy_guid().to_str().unwrap(), crate::fmi2::xml::render::<toy::Toy>().unwrap().guid);
    assert!(xml.contains(r#"<CoSimulation modelIdentifier="toy""#));
    assert!(xml.contains(r#"name="gain""#) && xml.contains(r#"min="0.0" max="10.0""#));
}

#[test]
fn a_short_buffer_gets_a_truncated_nul_terminated_description_and_the_size_it_needs() {
    let needed = toy_description().len() + 1;
    let mut buffer = [0x55u8; 8];
    // SAFETY: the buffer has the 8 bytes announced.
    let size = unsafe { toy::fmi2rs_model_description(buffer.as_mut_ptr() as *mut c_char, buffer.len()) };
    assert_eq!(size, needed);
    assert_eq!(&buffer, b"<?xml v\0");
}

#[test]
fn a_step_longer_than_the_models_sample_period_is_reported_once_and_still_runs() {
    let fmu = Fmu::new();
    fmu.initialize(0.0, None);
    // A model without a largest sensible step says nothing of a long step.
    fmu.ok(fmu.do_step(0.0, 50.0));
    fmu.ok(fmu.set_integer(&[vr::COMMAND], &[toy::SAMPLED_COMMAND]));
    // A step of the period itself is what a sampled model is made for.
    fmu.ok(fmu.do_step(50.0, toy::SAMPLE_PERIOD));
    assert_eq!(fmu.do_step(50.25, 1.0), fmi2OK);
    let messages = fmu.messages();
    let warnings: Vec<&Message> = messages.iter().filter(|m| m.status == fmi2Warning).collect();
    assert_eq!(warnings.len(), 1, "{messages:?}");
    let text = &warnings[0].text;
    assert!(text.contains("communicationStepSize 1 s") && text.contains("largest sensible step, 0.25 s"), "{text}");
    assert_eq!(warnings[0].category, "logStatusWarning");
    // Once per instance: the host chose its step for the whole run.
    assert_eq!(fmu.do_step(51.25, 1.0), fmi2OK);
    assert!(fmu.messages().iter().all(|m| m.status != fmi2Warning));
}
