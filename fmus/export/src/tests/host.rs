//! A minimal FMI host for the tests: a logger callback that records every message per instance,
//! and [`Fmu`], one `Toy` instance created and freed through the exported entry points, with a
//! way to bring it into each state of the Co-Simulation state machine.

use super::toy::{self, vr, Toy};
use crate::ffi::*;
use crate::fmi2::api;
use crate::instance::Instance;
use crate::state::State;
use crate::Model;
use std::ffi::{c_char, c_void, CStr, CString};
use std::sync::Mutex;

/// One call of the logger callback.
#[derive(Debug, Clone)]
pub struct Message {
    pub instance: String,
    pub status: fmi2Status,
    pub category: String,
    pub format: String,
    pub text: String,
}

/// What the logger received for one instance (its `componentEnvironment`).
#[derive(Default)]
pub struct Log(Mutex<Vec<Message>>);

impl Log {
    /// Every message so far, emptying the log.
    pub fn take(&self) -> Vec<Message> {
        std::mem::take(&mut *self.0.lock().unwrap_or_else(|e| e.into_inner()))
    }
}

fn text(ptr: *const c_char) -> String {
    if ptr.is_null() {
        "(null)".into()
    } else {
        // SAFETY: the FMU passes NUL-terminated strings valid for the duration of the call.
        unsafe { CStr::from_ptr(ptr) }.to_string_lossy().into_owned()
    }
}

/// The logger with its one variadic argument spelled out. The exporter always calls the logger
/// with the format `"%s"` and the message as the single variadic argument (asserted by the
/// tests through [`Message::format`]), and stable Rust cannot define a variadic function.
type Capture =
    unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, fmi2String);
type Variadic = unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...);

unsafe extern "C" fn capture(
    env: fmi2ComponentEnvironment,
    instance: fmi2String,
    status: fmi2Status,
    category: fmi2String,
    format: fmi2String,
    message: fmi2String,
) {
    let message = Message {
        instance: text(instance),
        status,
        category: text(category),
        format: text(format),
        text: text(message),
    };
    // SAFETY: every instance of these tests gets a `Log` that outlives it as environment.
    if let Some(log) = unsafe { (env as *const Log).as_ref() } {
        log.0.lock().unwrap_or_else(|e| e.into_inner()).push(message);
    }
}

/// Callbacks whose logger records into `log`.
pub fn callbacks(log: &Log) -> fmi2CallbackFunctions {
    // SAFETY: on the targets this module is compiled for (see `tests/mod.rs`), integer and
    // pointer arguments of a variadic call travel exactly as those of a non-variadic one, so
    // `capture` receives the format and the one string argument the exporter passes.
    let logger = unsafe { std::mem::transmute::<Capture, Variadic>(capture) };
    fmi2CallbackFunctions {
        logger: Some(logger),
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: log as *const Log as *mut c_void,
    }
}

/// The text `Toy`'s exported `fmi2rs_model_description(buffer, size)` writes, asked for the
/// size first as a host would.
pub fn toy_description() -> String {
    // SAFETY: a null buffer asks for the size only; then the buffer has exactly that size.
    let mut buffer = vec![0u8; unsafe { toy::fmi2rs_model_description(std::ptr::null_mut(), 0) }];
    // SAFETY: `c` is a live instance of this test; each array or slot is a live local of at least the announced length.
    unsafe { toy::fmi2rs_model_description(buffer.as_mut_ptr() as *mut c_char, buffer.len()) };
    CStr::from_bytes_with_nul(&buffer).expect("one NUL, at the end").to_string_lossy().into_owned()
}

/// The GUID `Toy`'s exported description declares.
pub fn toy_guid() -> CString {
    let xml = toy_description();
    let start = xml.find("guid=\"").expect("the description declares a guid") + "guid=\"".len();
    let end = start + xml[start..].find('"').expect("the guid attribute is closed");
    CString::new(&xml[start..end]).expect("no NUL in a GUID")
}

/// `fmi2Instantiate` of a model other than `Toy` through [`crate::fmi2::api`] (the `#[no_mangle]`
/// symbols are `Toy`'s), logging into `log`, with logging of calls off.
pub fn instantiate_through_api<M: Model>(log: &Log, name: &CStr) -> fmi2Component {
    let guid = CString::new(crate::fmi2::xml::render::<M>().expect("renders").guid).expect("no NUL in a GUID");
    instantiate_as_host(log, name, &guid, api_instantiate::<M>)
}

/// An instance of a model other than `Toy`, driven through [`crate::fmi2::api`] (its C symbols
/// would clash with `Toy`'s), with its own log; freed on drop.
pub struct ApiFmu<M: Model> {
    pub c: fmi2Component,
    pub log: Box<Log>,
    model: std::marker::PhantomData<M>,
}

impl<M: Model> ApiFmu<M> {
    /// A new instance named `name`, set up from t = 0 s without stop time, in initialization
    /// mode.
    pub fn initializing(name: &CStr) -> ApiFmu<M> {
        let log = Box::<Log>::default();
        let c = instantiate_through_api::<M>(&log, name);
        // SAFETY: `c` is a live instance of this test, and the calls take no other pointer.
        unsafe {
            assert_eq!(api::setup_experiment::<M>(c, fmi2False, 0.0, 0.0, fmi2False, 0.0), fmi2OK);
            assert_eq!(api::enter_initialization_mode::<M>(c), fmi2OK);
        }
        ApiFmu { c, log, model: std::marker::PhantomData }
    }
}

impl<M: Model> Drop for ApiFmu<M> {
    fn drop(&mut self) {
        // SAFETY: `self.c` is a live instance of this test, and the call takes no other pointer.
        unsafe { api::free_instance::<M>(self.c) }
    }
}

/// [`api::instantiate`] of `M` under the C signature of `fmi2Instantiate`, with `M`'s own GUID
/// as the one the FMU expects: what `export_fmu!(M)` would export.
unsafe extern "C" fn api_instantiate<M: Model>(
    name: fmi2String,
    kind: fmi2Type,
    guid: fmi2String,
    resources: fmi2String,
    functions: *const fmi2CallbackFunctions,
    visible: fmi2Boolean,
    logging_on: fmi2Boolean,
) -> fmi2Component {
    let Ok(ours) = crate::fmi2::xml::render::<M>() else { return std::ptr::null_mut() };
    // SAFETY: the caller's arguments, passed on.
    unsafe { api::instantiate::<M>(&ours.guid, name, kind, guid, resources, functions, visible, logging_on) }
}

/// `instantiate` called as every test host calls `fmi2Instantiate`: for Co-Simulation with
/// `guid`, no resource location, `log`'s callbacks, not visible, logging of calls off; it must
/// succeed.
fn instantiate_as_host(log: &Log, name: &CStr, guid: &CStr, instantiate: fmi2InstantiateTYPE) -> fmi2Component {
    let functions = callbacks(log);
    // SAFETY: every pointer is valid for the call; the caller keeps `log` alive.
    let c = unsafe {
        instantiate(name.as_ptr(), fmi2CoSimulation, guid.as_ptr(), std::ptr::null(), &functions, fmi2False, fmi2False)
    };
    assert!(!c.is_null(), "fmi2Instantiate failed: {:?}", log.take());
    c
}

/// An exported FMI 2.0 getter (`fmi2GetReal`, …) of values of type `T`.
pub type Getter<T> = unsafe extern "C" fn(fmi2Component, *const fmi2ValueReference, usize, *mut T) -> fmi2Status;
/// An exported FMI 2.0 setter (`fmi2SetReal`, …) of values of type `T`.
pub type Setter<T> = unsafe extern "C" fn(fmi2Component, *const fmi2ValueReference, usize, *const T) -> fmi2Status;

/// One `Toy` instance with its own log; freed on drop.
pub struct Fmu {
    pub c: fmi2Component,
    log: Box<Log>,
}

impl Fmu {
    /// `fmi2Instantiate` for Co-Simulation with the right GUID, logging of calls off.
    pub fn new() -> Fmu {
        let log = Box::<Log>::default();
        // `log` outlives the instance.
        let c = instantiate_as_host(&log, c"toy1", &toy_guid(), toy::fmi2Instantiate);
        Fmu { c, log }
    }

    /// No instance at all (a NULL component), for calls that must refuse it.
    pub fn null() -> Fmu {
        Fmu { c: std::ptr::null_mut(), log: Box::default() }
    }

    /// A new instance brought into `state` by the calls a host makes (`StepFailed`, which no
    /// call of this exporter leads to, is set directly), with an empty log.
    pub fn in_state(state: State) -> Fmu {
        let fmu = Fmu::new();
        if state != State::Instantiated {
            // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
            fmu.ok(unsafe { toy::fmi2SetupExperiment(fmu.c, fmi2False, 0.0, 0.0, fmi2False, 0.0) });
            // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
            fmu.ok(unsafe { toy::fmi2EnterInitializationMode(fmu.c) });
        }
        if !matches!(state, State::Instantiated | State::InitializationMode) {
            // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
            fmu.ok(unsafe { toy::fmi2ExitInitializationMode(fmu.c) });
        }
        match state {
            // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
            State::Terminated => fmu.ok(unsafe { toy::fmi2Terminate(fmu.c) }),
            State::StepFailed => fmu.force_state(State::StepFailed),
            State::Error => {
                fmu.ok(fmu.set_real(&[vr::RATE], &[1e308]));
                // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
                assert_eq!(unsafe { toy::fmi2DoStep(fmu.c, 0.0, 10.0, fmi2True) }, fmi2Error);
            }
            State::Fatal => {
                fmu.ok(fmu.set_integer(&[vr::COMMAND], &[toy::PANIC_COMMAND]));
                // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
                assert_eq!(unsafe { toy::fmi2DoStep(fmu.c, 0.0, 0.1, fmi2True) }, fmi2Fatal);
            }
            _ => {}
        }
        assert_eq!(fmu.state(), state, "setting up state {state:?}");
        fmu.log.take();
        fmu
    }

    /// Sets up an experiment from `start_time` (until `stop_time`, if given) and goes through
    /// initialization mode to step mode, as a host does; every call must succeed.
    pub fn initialize(&self, start_time: f64, stop_time: Option<f64>) {
        let (stop_defined, stop) = match stop_time {
            Some(stop) => (fmi2True, stop),
            None => (fmi2False, 0.0),
        };
        // SAFETY: `self.c` is a live instance of this test, and the calls take no other pointer.
        unsafe {
            self.ok(toy::fmi2SetupExperiment(self.c, fmi2False, 0.0, start_time, stop_defined, stop));
            self.ok(toy::fmi2EnterInitializationMode(self.c));
            self.ok(toy::fmi2ExitInitializationMode(self.c));
        }
    }

    /// The state the calls so far led to (read from the instance behind the component).
    pub fn state(&self) -> State {
        // SAFETY: `c` is a live instance of `Toy` created by `fmi2Instantiate`.
        unsafe { &*(self.c as *const Instance<Toy>) }.state()
    }

    /// How many FMU states this instance created that are not freed yet (it frees them with
    /// itself).
    pub fn unfreed_states(&self) -> usize {
        crate::calls::unfreed_states::<Toy>(self.c)
    }

    /// Puts the instance in `state` without a call (for states no call leads to).
    fn force_state(&self, state: State) {
        // SAFETY: as in `state`; no other reference to the instance is alive.
        unsafe { &mut *(self.c as *mut Instance<Toy>) }.core.state = state;
    }

    /// Every message logged since the last call.
    pub fn messages(&self) -> Vec<Message> {
        self.log.take()
    }

    /// Asserts `status` is `fmi2OK` and nothing was logged as an error.
    #[track_caller]
    pub fn ok(&self, status: fmi2Status) {
        let messages = self.messages();
        assert_eq!(status, fmi2OK, "messages: {messages:?}");
        assert!(messages.iter().all(|m| m.status == fmi2OK), "errors logged on success: {messages:?}");
    }

    /// Asserts `status` is `fmi2Error` and that an error message naming `function` and
    /// containing each of `words` reached the logger; returns that message's text.
    #[track_caller]
    pub fn refused(&self, status: fmi2Status, function: &str, words: &[&str]) -> String {
        let messages = self.messages();
        assert_eq!(status, fmi2Error, "{function} should be refused; messages: {messages:?}");
        let found = messages
            .iter()
            .find(|m| m.status == fmi2Error && m.text.contains(function) && words.iter().all(|w| m.text.contains(w)));
        let Some(message) = found else {
            panic!("no error message naming {function} and {words:?} was logged: {messages:?}")
        };
        assert_eq!(message.format, "%s", "messages go through a literal format");
        assert_eq!(message.category, "logStatusError");
        assert_eq!(message.instance, "toy1");
        message.text.clone()
    }

    /// `setter` (`toy::fmi2SetReal`, …) of `vrs` to `values`, as is.
    pub fn set<T>(&self, setter: Setter<T>, vrs: &[u32], values: &[T]) -> fmi2Status {
        assert_eq!(vrs.len(), values.len());
        // SAFETY: `self.c` is a live instance of this test; each array or slot is a live local of at least the
        // announced length.
        unsafe { setter(self.c, vrs.as_ptr(), vrs.len(), values.as_ptr()) }
    }

    pub fn set_real(&self, vrs: &[u32], values: &[f64]) -> fmi2Status {
        self.set(toy::fmi2SetReal, vrs, values)
    }

    pub fn set_integer(&self, vrs: &[u32], values: &[i32]) -> fmi2Status {
        self.set(toy::fmi2SetInteger, vrs, values)
    }

    pub fn set_boolean(&self, vrs: &[u32], values: &[bool]) -> fmi2Status {
        let values: Vec<fmi2Boolean> = values.iter().map(|b| if *b { fmi2True } else { fmi2False }).collect();
        self.set(toy::fmi2SetBoolean, vrs, &values)
    }

    /// `None` passes a NULL string.
    pub fn set_string(&self, vrs: &[u32], values: &[Option<&str>]) -> fmi2Status {
        let owned: Vec<Option<CString>> = values.iter().map(|v| v.map(|s| CString::new(s).unwrap())).collect();
        let pointers: Vec<fmi2String> =
            owned.iter().map(|v| v.as_ref().map_or(std::ptr::null(), |s| s.as_ptr())).collect();
        self.set(toy::fmi2SetString, vrs, &pointers)
    }

    /// `getter` (`toy::fmi2GetReal`, …) of `vrs` as is: the status and the values written over
    /// `fill`.
    pub fn get<T: Clone>(&self, getter: Getter<T>, vrs: &[u32], fill: T) -> (fmi2Status, Vec<T>) {
        let mut out = vec![fill; vrs.len()];
        // SAFETY: `self.c` is a live instance of this test; each array or slot is a live local of at least the
        // announced length.
        let status = unsafe { getter(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr()) };
        (status, out)
    }

    /// As [`Fmu::get`], which must succeed: the values.
    #[track_caller]
    fn values<T: Clone>(&self, getter: Getter<T>, vrs: &[u32], fill: T) -> Vec<T> {
        let (status, out) = self.get(getter, vrs, fill);
        self.ok(status);
        out
    }

    /// The values of Real variables, which must be readable.
    #[track_caller]
    pub fn reals(&self, vrs: &[u32]) -> Vec<f64> {
        self.values(toy::fmi2GetReal, vrs, f64::NAN)
    }

    /// `fmi2GetReal` as is: the status and the values written.
    pub fn get_real(&self, vrs: &[u32]) -> (fmi2Status, Vec<f64>) {
        self.get(toy::fmi2GetReal, vrs, 0.0)
    }

    #[track_caller]
    pub fn integers(&self, vrs: &[u32]) -> Vec<i32> {
        self.values(toy::fmi2GetInteger, vrs, -1)
    }

    #[track_caller]
    pub fn booleans(&self, vrs: &[u32]) -> Vec<bool> {
        let out = self.values(toy::fmi2GetBoolean, vrs, -1);
        for b in &out {
            assert!(*b == fmi2True || *b == fmi2False, "fmi2GetBoolean wrote {b}");
        }
        out.iter().map(|b| *b == fmi2True).collect()
    }

    #[track_caller]
    pub fn strings(&self, vrs: &[u32]) -> Vec<String> {
        self.values(toy::fmi2GetString, vrs, std::ptr::null()).iter().map(|p| text(*p)).collect()
    }

    /// The time of the last accepted step (`fmi2LastSuccessfulTime`).
    #[track_caller]
    pub fn time(&self) -> f64 {
        let mut t = f64::NAN;
        // SAFETY: `self.c` is a live instance of this test; each array or slot is a live local of at least the
        // announced length.
        self.ok(unsafe { toy::fmi2GetRealStatus(self.c, fmi2LastSuccessfulTime, &mut t) });
        t
    }

    pub fn do_step(&self, t: f64, h: f64) -> fmi2Status {
        // SAFETY: `self.c` is a live instance of this test, and the call takes no other pointer.
        unsafe { toy::fmi2DoStep(self.c, t, h, fmi2True) }
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        // SAFETY: `c` came from fmi2Instantiate and is freed once; the log outlives the call.
        unsafe { toy::fmi2FreeInstance(self.c) }
    }
}
