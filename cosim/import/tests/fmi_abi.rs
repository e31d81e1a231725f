//! C-ABI conformance of the pendulum FMU, called raw through `fmu_import::fmi`.
//!
//! Every misuse must return `fmi2Error` (or NULL from `fmi2Instantiate`), log
//! a message when there is an instance to log for, and never crash; after an
//! error the instance must recover where the standard allows it (`fmi2Reset`,
//! or `fmi2SetFMUstate` to a state saved before the error).
//!
//! Needs `target/fmu/pendulum.fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use std::ffi::{c_char, CStr, CString};
use std::ptr;
use std::sync::{Arc, Barrier};

use fmu_import::fmi::ffi::{self, fmi2Component, fmi2Status};
use fmu_import::fmi::{Functions, Library, LogContext, LogEcho, Status};
use fmu_import::fmu::{ExtractLimits, Fmu, ModelDescription};
use fmu_import::slave::{InstantiateOptions, Slave};

const H: f64 = 0.01;

/// The pendulum FMU, opened and loaded.
struct Pendulum {
    fmu: Fmu,
    library: Arc<Library>,
}

impl Pendulum {
    fn open() -> Self {
        let fmu = Fmu::open(&common::pendulum_fmu(), &ExtractLimits::default()).expect("the pendulum FMU opens");
        let library = fmu.library().expect("the pendulum library loads");
        Self { fmu, library }
    }

    fn f(&self) -> &Functions {
        self.library.functions()
    }

    fn md(&self) -> &ModelDescription {
        self.fmu.model_description()
    }

    fn vr(&self, name: &str) -> u32 {
        self.md().variable(name).unwrap_or_else(|| panic!("variable {name}")).value_reference
    }

    fn instantiate(&self, name: &str) -> Raw {
        let log = LogContext::new(name, LogEcho::Off);
        let callbacks = Box::new(log.callbacks());
        let c_name = CString::new(name).expect("name");
        let guid = CString::new(self.md().guid.clone()).expect("guid");
        let uri = CString::new(self.fmu.resource_uri()).expect("uri");
        // SAFETY: every argument is NULL or points to a live local (C strings, callbacks) for the call.
        let component = unsafe {
            (self.f().fmi2Instantiate)(
                c_name.as_ptr(),
                ffi::fmi2CoSimulation,
                guid.as_ptr(),
                uri.as_ptr(),
                &*callbacks,
                ffi::fmi2False,
                ffi::fmi2True,
            )
        };
        assert!(!component.is_null(), "fmi2Instantiate failed: {:?}", log.messages());
        Raw { f: *self.f(), c: component, log, _callbacks: callbacks }
    }
}

/// A Model Exchange function the pendulum exports (they are optional for a Co-Simulation FMU).
fn exported<F>(function: Option<F>) -> F {
    function.expect("the pendulum exports the Model Exchange functions")
}

/// A raw instance, freed on drop.
struct Raw {
    f: Functions,
    c: fmi2Component,
    log: Box<LogContext>,
    _callbacks: Box<ffi::fmi2CallbackFunctions>,
}

impl Drop for Raw {
    fn drop(&mut self) {
        // SAFETY: `self.c` came from fmi2Instantiate and is freed exactly once, here.
        unsafe { (self.f.fmi2FreeInstance)(self.c) };
    }
}

impl Raw {
    /// Runs `call`, asserts it returned fmi2Error and logged an error message.
    fn expect_error(&self, what: &str, call: impl FnOnce(&Functions, fmi2Component) -> fmi2Status) {
        let mark = self.log.mark();
        let status = Status::from_raw(call(&self.f, self.c));
        assert_eq!(status, Status::Error, "{what}: expected fmi2Error");
        let logged = self.log.since(mark);
        assert!(
            logged.iter().any(|m| m.status == Status::Error && !m.message.is_empty()),
            "{what}: no error message was logged ({logged:?})"
        );
    }

    fn ok(&self, what: &str, status: fmi2Status) {
        let status = Status::from_raw(status);
        assert!(status.is_success(), "{what}: {status}; log: {:?}", self.log.last_message());
    }

    fn setup_and_initialize(&self) {
        // SAFETY: `self.c` is a live instance of this test, and the call takes no other pointer.
        unsafe {
            self.ok("fmi2SetupExperiment", (self.f.fmi2SetupExperiment)(self.c, 0, 0.0, 0.0, 0, 0.0));
            self.ok("fmi2EnterInitializationMode", (self.f.fmi2EnterInitializationMode)(self.c));
            self.ok("fmi2ExitInitializationMode", (self.f.fmi2ExitInitializationMode)(self.c));
        }
    }

    fn step(&self, t: f64) {
        // SAFETY: `self.c` is a live instance of this test, and the call takes no other pointer.
        self.ok("fmi2DoStep", unsafe { (self.f.fmi2DoStep)(self.c, t, H, ffi::fmi2True) });
    }

    fn get(&self, vrs: &[u32]) -> Vec<f64> {
        let mut values = vec![0.0; vrs.len()];
        // SAFETY: `self.c` is a live instance of this test; each array or slot is a live local of at least the
        // announced length.
        self.ok("fmi2GetReal", unsafe { (self.f.fmi2GetReal)(self.c, vrs.as_ptr(), vrs.len(), values.as_mut_ptr()) });
        values
    }

    fn set(&self, vrs: &[u32], values: &[f64]) {
        // SAFETY: `self.c` is a live instance of this test; each array or slot is a live local of at least the
        // announced length.
        self.ok("fmi2SetReal", unsafe { (self.f.fmi2SetReal)(self.c, vrs.as_ptr(), vrs.len(), values.as_ptr()) });
    }

    /// After an error: `fmi2Reset`, then a complete valid sequence must work.
    fn recover_with_reset(&self, p: &Pendulum, after: &str) {
        // SAFETY: `self.c` is a live instance of this test, and the call takes no other pointer.
        self.ok(&format!("fmi2Reset after {after}"), unsafe { (self.f.fmi2Reset)(self.c) });
        self.valid_sequence(p, after);
    }

    /// setup → init → a few steps with an input, outputs finite.
    fn valid_sequence(&self, p: &Pendulum, after: &str) {
        self.setup_and_initialize();
        let theta = p.vr("theta_x");
        for k in 0..5 {
            self.set(&[p.vr("tip.x")], &[0.001 * k as f64]);
            // SAFETY: `self.c` is a live instance of this test, and the call takes no other pointer.
            let status = unsafe { (self.f.fmi2DoStep)(self.c, k as f64 * H, H, ffi::fmi2True) };
            assert!(
                Status::from_raw(status).is_success(),
                "valid step {k} after {after}: {:?}",
                self.log.last_message()
            );
        }
        assert!(self.get(&[theta])[0].is_finite(), "after {after}");
    }
}

#[test]
fn platform_and_version() {
    let p = Pendulum::open();
    // SAFETY: the function returns a pointer to a static NUL-terminated string.
    unsafe {
        assert_eq!(CStr::from_ptr((p.f().fmi2GetTypesPlatform)()).to_str(), Ok("default"));
        assert_eq!(CStr::from_ptr((p.f().fmi2GetVersion)()).to_str(), Ok("2.0"));
    }
}

#[test]
fn do_step_before_initialization() {
    let p = Pendulum::open();
    let raw = p.instantiate("early_step");
    // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
    raw.expect_error("fmi2DoStep before initialization", |f, c| unsafe { (f.fmi2DoStep)(c, 0.0, H, 1) });
    raw.recover_with_reset(&p, "fmi2DoStep before initialization");
}

#[test]
fn exit_initialization_before_enter() {
    let p = Pendulum::open();
    let raw = p.instantiate("early_exit");
    // SAFETY: `raw.c` is a live instance of this test, and the call takes no other pointer.
    unsafe { raw.ok("setup", (raw.f.fmi2SetupExperiment)(raw.c, 0, 0.0, 0.0, 0, 0.0)) };
    // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
    raw.expect_error("fmi2ExitInitializationMode before Enter", |f, c| unsafe { (f.fmi2ExitInitializationMode)(c) });
    raw.recover_with_reset(&p, "fmi2ExitInitializationMode before Enter");
}

#[test]
fn unknown_value_references() {
    let p = Pendulum::open();
    let raw = p.instantiate("unknown_vr");
    raw.setup_and_initialize();
    let highest = p.md().variables.iter().map(|v| v.value_reference).max().unwrap_or(0);
    for vr in [highest + 1000, u32::MAX] {
        let vrs = [vr];
        // SAFETY: `c` is a live instance of this test; each array or slot is a live local of at least the announced
        // length.
        raw.expect_error("fmi2SetReal unknown vr", |f, c| unsafe {
            (f.fmi2SetReal)(c, vrs.as_ptr(), 1, [1.0].as_ptr())
        });
        raw.recover_with_reset(&p, "fmi2SetReal with an unknown value reference");
        let mut out = [0.0];
        // SAFETY: `c` is a live instance of this test; each array or slot is a live local of at least the announced
        // length.
        raw.expect_error("fmi2GetReal unknown vr", |f, c| unsafe {
            (f.fmi2GetReal)(c, vrs.as_ptr(), 1, out.as_mut_ptr())
        });
        raw.recover_with_reset(&p, "fmi2GetReal with an unknown value reference");
    }
}

#[test]
fn null_component_to_every_function() {
    let p = Pendulum::open();
    let f = p.f();
    let null: fmi2Component = ptr::null_mut();
    let vr = [p.vr("tip.x")];
    let mut real = [0.0];
    let mut integer = [0];
    let mut string: [ffi::fmi2String; 1] = [ptr::null()];
    let text = [c"x".as_ptr()];
    let order = [1];
    let mut state: ffi::fmi2FMUstate = ptr::null_mut();
    let mut size = 0usize;
    let mut bytes = [0 as c_char; 8];
    let mut info = ffi::fmi2EventInfo::default();
    let (mut flag_a, mut flag_b) = (0, 0);
    let mut status_out = 0;
    let mut string_out: ffi::fmi2String = ptr::null();
    // SAFETY: `null` is the NULL component each call must refuse before it touches any other
    // argument (what this tests); every other pointer is to a live local above.
    let calls: Vec<(&str, fmi2Status)> = unsafe {
        vec![
            ("fmi2SetDebugLogging", (f.fmi2SetDebugLogging)(null, 1, 0, ptr::null())),
            ("fmi2SetupExperiment", (f.fmi2SetupExperiment)(null, 0, 0.0, 0.0, 0, 0.0)),
            ("fmi2EnterInitializationMode", (f.fmi2EnterInitializationMode)(null)),
            ("fmi2ExitInitializationMode", (f.fmi2ExitInitializationMode)(null)),
            ("fmi2Terminate", (f.fmi2Terminate)(null)),
            ("fmi2Reset", (f.fmi2Reset)(null)),
            ("fmi2GetReal", (f.fmi2GetReal)(null, vr.as_ptr(), 1, real.as_mut_ptr())),
            ("fmi2GetInteger", (f.fmi2GetInteger)(null, vr.as_ptr(), 1, integer.as_mut_ptr())),
            ("fmi2GetBoolean", (f.fmi2GetBoolean)(null, vr.as_ptr(), 1, integer.as_mut_ptr())),
            ("fmi2GetString", (f.fmi2GetString)(null, vr.as_ptr(), 1, string.as_mut_ptr())),
            ("fmi2SetReal", (f.fmi2SetReal)(null, vr.as_ptr(), 1, real.as_ptr())),
            ("fmi2SetInteger", (f.fmi2SetInteger)(null, vr.as_ptr(), 1, integer.as_ptr())),
            ("fmi2SetBoolean", (f.fmi2SetBoolean)(null, vr.as_ptr(), 1, integer.as_ptr())),
            ("fmi2SetString", (f.fmi2SetString)(null, vr.as_ptr(), 1, text.as_ptr())),
            ("fmi2GetFMUstate", (f.fmi2GetFMUstate)(null, &mut state)),
            ("fmi2SetFMUstate", (f.fmi2SetFMUstate)(null, state)),
            ("fmi2FreeFMUstate", (f.fmi2FreeFMUstate)(null, &mut state)),
            ("fmi2SerializedFMUstateSize", (f.fmi2SerializedFMUstateSize)(null, state, &mut size)),
            ("fmi2SerializeFMUstate", (f.fmi2SerializeFMUstate)(null, state, bytes.as_mut_ptr(), bytes.len())),
            ("fmi2DeSerializeFMUstate", (f.fmi2DeSerializeFMUstate)(null, bytes.as_ptr(), bytes.len(), &mut state)),
            (
                "fmi2GetDirectionalDerivative",
                (f.fmi2GetDirectionalDerivative)(
                    null,
                    vr.as_ptr(),
                    1,
                    vr.as_ptr(),
                    1,
                    real.as_ptr(),
                    real.as_mut_ptr(),
                ),
            ),
            ("fmi2EnterEventMode", exported(f.fmi2EnterEventMode)(null)),
            ("fmi2NewDiscreteStates", exported(f.fmi2NewDiscreteStates)(null, &mut info)),
            ("fmi2EnterContinuousTimeMode", exported(f.fmi2EnterContinuousTimeMode)(null)),
            ("fmi2CompletedIntegratorStep", exported(f.fmi2CompletedIntegratorStep)(null, 1, &mut flag_a, &mut flag_b)),
            ("fmi2SetTime", exported(f.fmi2SetTime)(null, 0.0)),
            ("fmi2SetContinuousStates", exported(f.fmi2SetContinuousStates)(null, real.as_ptr(), 1)),
            ("fmi2GetDerivatives", exported(f.fmi2GetDerivatives)(null, real.as_mut_ptr(), 1)),
            ("fmi2GetEventIndicators", exported(f.fmi2GetEventIndicators)(null, real.as_mut_ptr(), 1)),
            ("fmi2GetContinuousStates", exported(f.fmi2GetContinuousStates)(null, real.as_mut_ptr(), 1)),
            (
                "fmi2GetNominalsOfContinuousStates",
                exported(f.fmi2GetNominalsOfContinuousStates)(null, real.as_mut_ptr(), 1),
            ),
            (
                "fmi2SetRealInputDerivatives",
                (f.fmi2SetRealInputDerivatives)(null, vr.as_ptr(), 1, order.as_ptr(), real.as_ptr()),
            ),
            (
                "fmi2GetRealOutputDerivatives",
                (f.fmi2GetRealOutputDerivatives)(null, vr.as_ptr(), 1, order.as_ptr(), real.as_mut_ptr()),
            ),
            ("fmi2DoStep", (f.fmi2DoStep)(null, 0.0, H, 1)),
            ("fmi2CancelStep", (f.fmi2CancelStep)(null)),
            ("fmi2GetStatus", (f.fmi2GetStatus)(null, ffi::fmi2DoStepStatus, &mut status_out)),
            ("fmi2GetRealStatus", (f.fmi2GetRealStatus)(null, ffi::fmi2LastSuccessfulTime, &mut real[0])),
            ("fmi2GetIntegerStatus", (f.fmi2GetIntegerStatus)(null, ffi::fmi2DoStepStatus, &mut integer[0])),
            ("fmi2GetBooleanStatus", (f.fmi2GetBooleanStatus)(null, ffi::fmi2Terminated, &mut flag_a)),
            ("fmi2GetStringStatus", (f.fmi2GetStringStatus)(null, ffi::fmi2PendingStatus, &mut string_out)),
        ]
    };
    // Every function of fmi2Functions.h except the three without a component
    // (fmi2GetTypesPlatform, fmi2GetVersion, fmi2Instantiate) and fmi2FreeInstance.
    assert_eq!(calls.len(), fmu_import::fmi::SYMBOLS.len() - 4);
    for (name, status) in calls {
        assert_eq!(Status::from_raw(status), Status::Error, "{name}(NULL, ...)");
    }
    // SAFETY: freeing a NULL component must be a no-op that reads nothing (what this tests).
    unsafe { (f.fmi2FreeInstance)(null) };

    // The library still works afterwards.
    let raw = p.instantiate("after_null");
    raw.valid_sequence(&p, "NULL component calls");
}

#[test]
fn null_arrays_with_values_announced() {
    let p = Pendulum::open();
    let raw = p.instantiate("null_arrays");
    raw.setup_and_initialize();
    let vr = [p.vr("tip.x")];
    let out_vr = [p.vr("theta_x")];
    let real = [0.0];
    let mut real_out = [0.0];
    let integer = [0];
    let mut integer_out = [0];
    let order = [1];
    let text = [c"x".as_ptr()];
    let mut string_out: [ffi::fmi2String; 1] = [ptr::null()];
    let (real_out, integer_out, string_out) =
        (real_out.as_mut_ptr(), integer_out.as_mut_ptr(), string_out.as_mut_ptr());
    type Call<'a> = Box<dyn Fn(&Functions, fmi2Component) -> fmi2Status + 'a>;
    let calls: Vec<(&str, Call)> = vec![
        // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
        // other pointer is to a live local.
        ("fmi2GetReal(vr=NULL)", Box::new(|f, c| unsafe { (f.fmi2GetReal)(c, ptr::null(), 1, real_out) })),
        (
            "fmi2GetReal(value=NULL)",
            // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
            // other pointer is to a live local.
            Box::new(|f, c| unsafe { (f.fmi2GetReal)(c, out_vr.as_ptr(), 1, ptr::null_mut()) }),
        ),
        // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
        // other pointer is to a live local.
        ("fmi2SetReal(vr=NULL)", Box::new(|f, c| unsafe { (f.fmi2SetReal)(c, ptr::null(), 1, real.as_ptr()) })),
        // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
        // other pointer is to a live local.
        ("fmi2SetReal(value=NULL)", Box::new(|f, c| unsafe { (f.fmi2SetReal)(c, vr.as_ptr(), 1, ptr::null()) })),
        // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
        // other pointer is to a live local.
        ("fmi2GetInteger(vr=NULL)", Box::new(|f, c| unsafe { (f.fmi2GetInteger)(c, ptr::null(), 1, integer_out) })),
        (
            "fmi2GetInteger(value=NULL)",
            // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
            // other pointer is to a live local.
            Box::new(|f, c| unsafe { (f.fmi2GetInteger)(c, vr.as_ptr(), 1, ptr::null_mut()) }),
        ),
        (
            "fmi2SetInteger(vr=NULL)",
            // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
            // other pointer is to a live local.
            Box::new(|f, c| unsafe { (f.fmi2SetInteger)(c, ptr::null(), 1, integer.as_ptr()) }),
        ),
        // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
        // other pointer is to a live local.
        ("fmi2SetInteger(value=NULL)", Box::new(|f, c| unsafe { (f.fmi2SetInteger)(c, vr.as_ptr(), 1, ptr::null()) })),
        // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
        // other pointer is to a live local.
        ("fmi2GetBoolean(vr=NULL)", Box::new(|f, c| unsafe { (f.fmi2GetBoolean)(c, ptr::null(), 1, integer_out) })),
        (
            "fmi2GetBoolean(value=NULL)",
            // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
            // other pointer is to a live local.
            Box::new(|f, c| unsafe { (f.fmi2GetBoolean)(c, vr.as_ptr(), 1, ptr::null_mut()) }),
        ),
        (
            "fmi2SetBoolean(vr=NULL)",
            // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
            // other pointer is to a live local.
            Box::new(|f, c| unsafe { (f.fmi2SetBoolean)(c, ptr::null(), 1, integer.as_ptr()) }),
        ),
        // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
        // other pointer is to a live local.
        ("fmi2SetBoolean(value=NULL)", Box::new(|f, c| unsafe { (f.fmi2SetBoolean)(c, vr.as_ptr(), 1, ptr::null()) })),
        // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
        // other pointer is to a live local.
        ("fmi2GetString(vr=NULL)", Box::new(|f, c| unsafe { (f.fmi2GetString)(c, ptr::null(), 1, string_out) })),
        (
            "fmi2GetString(value=NULL)",
            // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
            // other pointer is to a live local.
            Box::new(|f, c| unsafe { (f.fmi2GetString)(c, vr.as_ptr(), 1, ptr::null_mut()) }),
        ),
        // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
        // other pointer is to a live local.
        ("fmi2SetString(vr=NULL)", Box::new(|f, c| unsafe { (f.fmi2SetString)(c, ptr::null(), 1, text.as_ptr()) })),
        // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
        // other pointer is to a live local.
        ("fmi2SetString(value=NULL)", Box::new(|f, c| unsafe { (f.fmi2SetString)(c, vr.as_ptr(), 1, ptr::null()) })),
        (
            "fmi2SetRealInputDerivatives(vr=NULL)",
            // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
            // other pointer is to a live local.
            Box::new(|f, c| unsafe {
                (f.fmi2SetRealInputDerivatives)(c, ptr::null(), 1, order.as_ptr(), real.as_ptr())
            }),
        ),
        (
            "fmi2SetRealInputDerivatives(order=NULL)",
            // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
            // other pointer is to a live local.
            Box::new(|f, c| unsafe { (f.fmi2SetRealInputDerivatives)(c, vr.as_ptr(), 1, ptr::null(), real.as_ptr()) }),
        ),
        (
            "fmi2SetRealInputDerivatives(value=NULL)",
            // SAFETY: `c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
            // other pointer is to a live local.
            Box::new(|f, c| unsafe { (f.fmi2SetRealInputDerivatives)(c, vr.as_ptr(), 1, order.as_ptr(), ptr::null()) }),
        ),
    ];
    for (name, call) in calls {
        raw.expect_error(name, |f, c| call(f, c));
        raw.recover_with_reset(&p, name);
    }
}

#[test]
fn zero_values_with_null_arrays_are_accepted() {
    // FMI 2.0 allows nvr = 0; the arrays are then never read, so NULL is as good as any pointer.
    let p = Pendulum::open();
    let raw = p.instantiate("zero_values");
    raw.setup_and_initialize();
    let (f, c) = (&raw.f, raw.c);
    // SAFETY: `c` is a live instance of this test; with zero elements announced the NULL arrays
    // are never read (FMI 2.0 allows nvr = 0), which is what this tests.
    let calls = unsafe {
        [
            ("fmi2GetReal", (f.fmi2GetReal)(c, ptr::null(), 0, ptr::null_mut())),
            ("fmi2GetInteger", (f.fmi2GetInteger)(c, ptr::null(), 0, ptr::null_mut())),
            ("fmi2GetBoolean", (f.fmi2GetBoolean)(c, ptr::null(), 0, ptr::null_mut())),
            ("fmi2GetString", (f.fmi2GetString)(c, ptr::null(), 0, ptr::null_mut())),
            ("fmi2SetReal", (f.fmi2SetReal)(c, ptr::null(), 0, ptr::null())),
            ("fmi2SetInteger", (f.fmi2SetInteger)(c, ptr::null(), 0, ptr::null())),
            ("fmi2SetBoolean", (f.fmi2SetBoolean)(c, ptr::null(), 0, ptr::null())),
            ("fmi2SetString", (f.fmi2SetString)(c, ptr::null(), 0, ptr::null())),
            (
                "fmi2SetRealInputDerivatives",
                (f.fmi2SetRealInputDerivatives)(c, ptr::null(), 0, ptr::null(), ptr::null()),
            ),
        ]
    };
    for (call, status) in calls {
        assert_eq!(Status::from_raw(status), Status::Ok, "{call} with no values");
    }
    raw.step(0.0);
}

#[test]
fn non_finite_inputs_are_refused() {
    let p = Pendulum::open();
    let raw = p.instantiate("non_finite");
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for input in ["tip.x", "lp", "tip.az"] {
            raw.setup_and_initialize();
            raw.step(0.0);
            let vr = [p.vr(input)];
            let what = format!("fmi2SetReal({input} = {bad:?})");
            // SAFETY: `c` is a live instance of this test; each array or slot is a live local of at least the announced
            // length.
            raw.expect_error(&what, |f, c| unsafe { (f.fmi2SetReal)(c, vr.as_ptr(), 1, [bad].as_ptr()) });
            raw.recover_with_reset(&p, &what);
            // SAFETY: `raw.c` is a live instance of this test, and the call takes no other pointer.
            unsafe { raw.ok("reset", (raw.f.fmi2Reset)(raw.c)) };
        }
    }
}

#[test]
fn non_positive_and_invalid_step_sizes_are_refused() {
    let p = Pendulum::open();
    let raw = p.instantiate("bad_step");
    for step in [0.0, -H, f64::NAN, f64::INFINITY] {
        raw.setup_and_initialize();
        let what = format!("fmi2DoStep(communicationStepSize = {step:?})");
        // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
        raw.expect_error(&what, |f, c| unsafe { (f.fmi2DoStep)(c, 0.0, step, 1) });
        raw.recover_with_reset(&p, &what);
        // SAFETY: `raw.c` is a live instance of this test, and the call takes no other pointer.
        unsafe { raw.ok("reset", (raw.f.fmi2Reset)(raw.c)) };
    }
}

#[test]
fn communication_point_must_be_the_current_time() {
    let p = Pendulum::open();
    let raw = p.instantiate("bad_time");
    for current in [H / 2.0, 5.0 * H, -H, f64::NAN] {
        raw.setup_and_initialize();
        raw.step(0.0);
        raw.step(H);
        // The instance is at 2h now.
        let what = format!("fmi2DoStep(currentCommunicationPoint = {current:?}) at t = 2h");
        // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
        raw.expect_error(&what, |f, c| unsafe { (f.fmi2DoStep)(c, current, H, 1) });
        raw.recover_with_reset(&p, &what);
        // SAFETY: `raw.c` is a live instance of this test, and the call takes no other pointer.
        unsafe { raw.ok("reset", (raw.f.fmi2Reset)(raw.c)) };
    }
}

#[test]
fn instantiate_refuses_bad_arguments() {
    let p = Pendulum::open();
    let f = p.f();
    let uri = CString::new(p.fmu.resource_uri()).expect("uri");
    let guid = CString::new(p.md().guid.clone()).expect("guid");
    let log = LogContext::new("instantiate", LogEcho::Off);
    let callbacks = log.callbacks();

    // Wrong GUID: NULL and a message.
    // SAFETY: every argument is NULL or points to a live local (C strings, callbacks) for the call.
    let component = unsafe {
        (f.fmi2Instantiate)(
            c"wrong_guid".as_ptr(),
            ffi::fmi2CoSimulation,
            c"{00000000-0000-0000-0000-000000000000}".as_ptr(),
            uri.as_ptr(),
            &callbacks,
            0,
            0,
        )
    };
    assert!(component.is_null(), "a wrong GUID must be refused");
    assert!(!log.is_empty(), "the GUID mismatch must be logged");

    // Model Exchange: NULL and a message.
    let mark = log.mark();
    // SAFETY: every argument is NULL or points to a live local (C strings, callbacks) for the call.
    let component = unsafe {
        (f.fmi2Instantiate)(c"me".as_ptr(), ffi::fmi2ModelExchange, guid.as_ptr(), uri.as_ptr(), &callbacks, 0, 0)
    };
    assert!(component.is_null(), "fmi2ModelExchange must be refused");
    assert!(!log.since(mark).is_empty(), "the refusal of Model Exchange must be logged");

    // NULL logger: NULL (nothing to log to).
    let mut no_logger = callbacks;
    no_logger.logger = None;
    // SAFETY: every argument is NULL or points to a live local (C strings, callbacks) for the call.
    let component = unsafe {
        (f.fmi2Instantiate)(c"no_logger".as_ptr(), ffi::fmi2CoSimulation, guid.as_ptr(), uri.as_ptr(), &no_logger, 0, 0)
    };
    assert!(component.is_null(), "a NULL logger must be refused");

    // NULL callback table: NULL.
    // SAFETY: every argument is NULL or points to a live local (C strings, callbacks) for the call.
    let component = unsafe {
        (f.fmi2Instantiate)(
            c"no_callbacks".as_ptr(),
            ffi::fmi2CoSimulation,
            guid.as_ptr(),
            uri.as_ptr(),
            ptr::null(),
            0,
            0,
        )
    };
    assert!(component.is_null(), "a NULL callback table must be refused");

    // Valid arguments still work.
    let raw = p.instantiate("valid_after_refusals");
    raw.valid_sequence(&p, "refused instantiations");
}

#[test]
fn model_exchange_functions_are_refused() {
    let p = Pendulum::open();
    let raw = p.instantiate("model_exchange");
    let mut values = [0.0; 4];
    let mut info = ffi::fmi2EventInfo::default();
    let (mut enter, mut terminate) = (0, 0);
    type Call<'a> = Box<dyn Fn(&Functions, fmi2Component) -> fmi2Status + 'a>;
    let out = values.as_mut_ptr();
    let info_ptr: *mut ffi::fmi2EventInfo = &mut info;
    let (enter_ptr, terminate_ptr): (*mut i32, *mut i32) = (&mut enter, &mut terminate);
    let calls: Vec<(&str, Call)> = vec![
        // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
        ("fmi2EnterEventMode", Box::new(|f, c| unsafe { exported(f.fmi2EnterEventMode)(c) })),
        // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
        ("fmi2NewDiscreteStates", Box::new(move |f, c| unsafe { exported(f.fmi2NewDiscreteStates)(c, info_ptr) })),
        // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
        ("fmi2EnterContinuousTimeMode", Box::new(|f, c| unsafe { exported(f.fmi2EnterContinuousTimeMode)(c) })),
        (
            "fmi2CompletedIntegratorStep",
            // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
            Box::new(move |f, c| unsafe { exported(f.fmi2CompletedIntegratorStep)(c, 1, enter_ptr, terminate_ptr) }),
        ),
        // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
        ("fmi2SetTime", Box::new(|f, c| unsafe { exported(f.fmi2SetTime)(c, 0.0) })),
        // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
        ("fmi2SetContinuousStates", Box::new(move |f, c| unsafe { exported(f.fmi2SetContinuousStates)(c, out, 4) })),
        // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
        ("fmi2GetDerivatives", Box::new(move |f, c| unsafe { exported(f.fmi2GetDerivatives)(c, out, 4) })),
        // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
        ("fmi2GetEventIndicators", Box::new(move |f, c| unsafe { exported(f.fmi2GetEventIndicators)(c, out, 1) })),
        // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
        ("fmi2GetContinuousStates", Box::new(move |f, c| unsafe { exported(f.fmi2GetContinuousStates)(c, out, 4) })),
        (
            "fmi2GetNominalsOfContinuousStates",
            // SAFETY: `c` is a live instance of this test, and the call takes no other pointer.
            Box::new(move |f, c| unsafe { exported(f.fmi2GetNominalsOfContinuousStates)(c, out, 4) }),
        ),
    ];
    for (name, call) in calls {
        raw.setup_and_initialize();
        raw.expect_error(name, |f, c| call(f, c));
        raw.recover_with_reset(&p, name);
        // SAFETY: `raw.c` is a live instance of this test, and the call takes no other pointer.
        unsafe { raw.ok("reset", (raw.f.fmi2Reset)(raw.c)) };
    }
}

/// Tip motion used to drive the pendulum in the state and thread tests.
fn drive(p: &Pendulum, k: u64) -> (Vec<u32>, Vec<f64>) {
    let t = k as f64 * H;
    let vrs = vec![p.vr("tip.x"), p.vr("tip.vx"), p.vr("tip.ax")];
    let w = 2.0;
    (vrs, vec![0.05 * (w * t).sin(), 0.05 * w * (w * t).cos(), -0.05 * w * w * (w * t).sin()])
}

fn outputs(p: &Pendulum) -> Vec<u32> {
    p.md()
        .variables
        .iter()
        .filter(|v| v.causality == fmu_import::fmu::Causality::Output)
        .map(|v| v.value_reference)
        .collect()
}

/// Steps `slave` from step `from` to `to`, returning all outputs after each step.
fn run_slave(p: &Pendulum, slave: &mut Slave, from: u64, to: u64) -> Vec<Vec<f64>> {
    let out = outputs(p);
    (from..to)
        .map(|k| {
            let (vrs, values) = drive(p, k);
            slave.set_real(&vrs, &values).expect("inputs");
            slave.do_step(k as f64 * H, H).expect("step");
            let mut values = vec![0.0; out.len()];
            slave.get_real(&out, &mut values).expect("outputs");
            values
        })
        .collect()
}

fn initialized_slave(p: &Pendulum, name: &str, theta_x0: f64) -> Slave {
    let mut slave = Slave::instantiate(&p.fmu, name, InstantiateOptions::default()).expect("instantiate");
    slave.setup_experiment(None, 0.0, None).expect("setup");
    slave.set_real(&[p.vr("theta_x0"), p.vr("lp")], &[theta_x0, 0.8]).expect("parameters");
    slave.enter_initialization_mode().expect("enter");
    slave.exit_initialization_mode().expect("exit");
    slave
}

fn assert_identical(a: &[Vec<f64>], b: &[Vec<f64>], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}");
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        let same = x.iter().zip(y).all(|(u, v)| u.to_bits() == v.to_bits());
        assert!(same, "{what}: outputs differ after step {k}: {x:?} vs {y:?}");
    }
}

#[test]
fn fmu_state_round_trip_reproduces_outputs() {
    let p = Pendulum::open();
    let mut slave = initialized_slave(&p, "state", -0.2);
    run_slave(&p, &mut slave, 0, 50);
    let state = slave.get_fmu_state().expect("get state");
    let first = run_slave(&p, &mut slave, 50, 150);

    slave.set_fmu_state(&state).expect("set state");
    let again = run_slave(&p, &mut slave, 50, 150);
    assert_identical(&first, &again, "after fmi2SetFMUstate");

    // Serialize, then restore into a fresh instance.
    let bytes = slave.serialize_fmu_state(&state).expect("serialize");
    assert!(!bytes.is_empty());
    slave.free_fmu_state(state).expect("free state");
    let mut fresh = initialized_slave(&p, "fresh", 0.0);
    let restored = fresh.deserialize_fmu_state(&bytes).expect("deserialize");
    fresh.set_fmu_state(&restored).expect("set deserialized state");
    fresh.free_fmu_state(restored).expect("free");
    let replayed = run_slave(&p, &mut fresh, 50, 150);
    assert_identical(&first, &replayed, "after deserializing into a fresh instance");

    // Truncated bytes are refused cleanly.
    assert!(fresh.deserialize_fmu_state(&bytes[..bytes.len() / 2]).is_err());
}

#[test]
fn set_fmu_state_recovers_after_an_error() {
    let p = Pendulum::open();
    let mut reference = initialized_slave(&p, "reference", 0.1);
    let expected = run_slave(&p, &mut reference, 0, 60);

    let mut slave = initialized_slave(&p, "recovering", 0.1);
    run_slave(&p, &mut slave, 0, 30);
    let state = slave.get_fmu_state().expect("get state");
    let error = slave.set_real(&[p.vr("tip.x")], &[f64::NAN]).expect_err("NaN is refused");
    assert!(error.to_string().contains("tip.x = NaN"), "{error}");
    slave.set_fmu_state(&state).expect("restore after the error");
    let resumed = run_slave(&p, &mut slave, 30, 60);
    assert_identical(&expected[30..], &resumed, "resumed from the saved state");
}

#[test]
fn two_instances_in_two_threads_match_sequential_runs() {
    let p = Pendulum::open();
    const STEPS: u64 = 2000;
    let sequential: Vec<Vec<Vec<f64>>> = [-0.3, 0.25]
        .iter()
        .enumerate()
        .map(|(i, &theta)| {
            let mut slave = initialized_slave(&p, &format!("seq{i}"), theta);
            run_slave(&p, &mut slave, 0, STEPS)
        })
        .collect();

    let barrier = Barrier::new(2);
    let parallel: Vec<Vec<Vec<f64>>> = std::thread::scope(|scope| {
        let handles: Vec<_> = [-0.3, 0.25]
            .iter()
            .enumerate()
            .map(|(i, &theta)| {
                let mut slave = initialized_slave(&p, &format!("par{i}"), theta);
                let (p, barrier) = (&p, &barrier);
                scope.spawn(move || {
                    barrier.wait();
                    run_slave(p, &mut slave, 0, STEPS)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().expect("thread")).collect()
    });
    for i in 0..2 {
        assert_identical(&sequential[i], &parallel[i], &format!("instance {i}"));
    }
    assert_ne!(sequential[0].last(), sequential[1].last(), "the two instances really differ");
}
