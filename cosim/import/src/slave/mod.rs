//! A safe FMI 2.0 Co-Simulation instance.
//!
//! [`Slave`] owns everything the C side may point to (the library, the
//! callback table and the logging context) and frees the instance on drop.
//! Every status becomes a `Result`; a [`SlaveError`] names the instance, the
//! `fmi2*` call, the simulation time where relevant, the status and the
//! FMU's own log message.

mod error;
mod state;
mod values;

use std::cell::Cell;
use std::ffi::CString;
use std::ptr;
use std::sync::Arc;

pub use error::{CallFailure, SlaveError};
pub use state::FmuState;

use crate::fmi::{ffi, Functions, Library, LogContext, LogEcho, Status};
use crate::fmu::{Fmu, ModelDescription, ScalarVariable};
use crate::names;
use crate::watch::{self, Call};

/// Options for [`Slave::instantiate`].
#[derive(Debug, Clone, Copy, Default)]
pub struct InstantiateOptions {
    /// `visible` argument of `fmi2Instantiate`.
    pub visible: bool,
    /// `loggingOn` argument (FMU debug logging).
    pub logging_on: bool,
    /// Which FMU messages are echoed to standard error.
    pub echo: LogEcho,
}

/// Where an instance is in the FMI 2.0 Co-Simulation state machine, as far
/// as this wrapper knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    Instantiated,
    InitializationMode,
    StepMode,
    /// `fmi2DoStep` returned `fmi2Discard` (FMI 2.0 "slave initialized, step failed"): the
    /// status queries, the getters and `fmi2Terminate` are allowed, stepping is not.
    StepDiscarded,
    Terminated,
    /// A call returned `fmi2Error` (or `fmi2Discard` outside `fmi2DoStep`); only reset, free or
    /// restoring a state are allowed.
    Failed,
    /// A call returned `fmi2Fatal`; no further call is allowed (not even free).
    Fatal,
}

/// One FMU instance (`fmi2Component`) in Co-Simulation mode.
pub struct Slave {
    name: String,
    /// The number the current call is published under ([`watch`]).
    id: u32,
    component: ffi::fmi2Component,
    functions: Functions,
    phase: Cell<Phase>,
    /// Last communication point reached (s): the start time, then `t + h` after each step.
    time: Cell<f64>,
    model: Arc<ModelDescription>,
    // The C side holds pointers into these two until fmi2FreeInstance (in Drop).
    _callbacks: Box<ffi::fmi2CallbackFunctions>,
    log: Box<LogContext>,
    library: Arc<Library>,
    fmu: Fmu,
}

// SAFETY: FMI 2.0 instances may be used from any thread as long as calls on
// one instance are not concurrent; `Slave` is not `Sync`, so they cannot be.
// The owned boxes and Arcs are themselves `Send`.
unsafe impl Send for Slave {}

impl std::fmt::Debug for Slave {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Slave")
            .field("name", &self.name)
            .field("model", &self.model.model_name)
            .field("phase", &self.phase.get())
            .field("time", &self.time.get())
            .finish_non_exhaustive()
    }
}

fn to_c_string(instance: &str, call: &'static str, what: &str, text: &str) -> Result<CString, SlaveError> {
    CString::new(text).map_err(|_| SlaveError::InvalidArgument {
        instance: instance.to_string(),
        call,
        message: format!("{what} {text:?} contains a NUL character"),
    })
}

impl Slave {
    /// `fmi2Instantiate` in Co-Simulation mode with the GUID from the model
    /// description and the `file:` URI of the extracted `resources/` folder.
    pub fn instantiate(fmu: &Fmu, name: &str, options: InstantiateOptions) -> Result<Self, SlaveError> {
        let library = fmu.library()?;
        let model = Arc::clone(fmu.model_description());
        let call = "fmi2Instantiate";
        let c_name = to_c_string(name, call, "instance name", name)?;
        let guid = to_c_string(name, call, "GUID", &model.guid)?;
        let resources = to_c_string(name, call, "resource location", &fmu.resource_uri())?;
        let log = LogContext::new(name, options.echo);
        let callbacks = Box::new(log.callbacks());
        let functions = *library.functions();
        let id = watch::register_instance(name, library.fmi3().is_some());
        watch::enter(id, Call::Instantiate, f64::NAN, f64::NAN);
        let component = match library.fmi3() {
            // SAFETY: valid strings, and the log context behind the callbacks lives until the
            // instance is freed (in Drop).
            Some(fmi3) => unsafe {
                crate::fmi::fmi3::instantiate(
                    fmi3,
                    &c_name,
                    &guid,
                    fmu.resource_dir(),
                    &callbacks,
                    options.visible,
                    options.logging_on,
                    &model.fmi3_elements,
                )
            },
            // SAFETY: all pointers are valid NUL-terminated strings / a live callback
            // table; `callbacks` and `log` are kept alive until fmi2FreeInstance.
            None => unsafe {
                (functions.fmi2Instantiate)(
                    c_name.as_ptr(),
                    ffi::fmi2CoSimulation,
                    guid.as_ptr(),
                    resources.as_ptr(),
                    &*callbacks,
                    ffi::fmi2Boolean::from(options.visible),
                    ffi::fmi2Boolean::from(options.logging_on),
                )
            },
        };
        watch::leave();
        if component.is_null() {
            watch::forget_instance(id);
            let call = if library.fmi3().is_some() { "fmi3InstantiateCoSimulation" } else { "fmi2Instantiate" };
            return Err(SlaveError::InstantiateFailed {
                instance: name.to_string(),
                call,
                fmu: fmu.source().to_path_buf(),
                log: log.messages(),
            });
        }
        Ok(Self {
            name: name.to_string(),
            id,
            component,
            functions,
            phase: Cell::new(Phase::Instantiated),
            time: Cell::new(0.0),
            model,
            _callbacks: callbacks,
            log,
            library,
            fmu: fmu.clone(),
        })
    }

    /// Instance name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The FMU this instance was created from.
    pub fn fmu(&self) -> &Fmu {
        &self.fmu
    }

    /// Its model description.
    pub fn model_description(&self) -> &ModelDescription {
        &self.model
    }

    /// Its shared library.
    pub fn library(&self) -> &Arc<Library> {
        &self.library
    }

    /// Messages the FMU logged for this instance.
    pub fn log(&self) -> &LogContext {
        &self.log
    }

    /// State-machine phase as tracked by this wrapper.
    pub fn phase(&self) -> Phase {
        self.phase.get()
    }

    /// Last communication point reached, in seconds.
    pub fn time(&self) -> f64 {
        self.time.get()
    }

    /// The raw component pointer (for ABI-level tests; do not free it).
    pub fn raw_component(&self) -> ffi::fmi2Component {
        self.component
    }

    /// Looks a variable up by name; the error suggests close names and lists
    /// all variables.
    pub fn variable(&self, name: &str) -> Result<&ScalarVariable, SlaveError> {
        self.model.variable(name).ok_or_else(|| SlaveError::UnknownVariable {
            instance: self.name.clone(),
            model: self.model.model_name.clone(),
            name: name.to_string(),
            suggestion: names::closest(name, self.model.variables.iter().map(|v| v.name.as_str())),
            available: self.model.variables.iter().map(|v| v.name.clone()).collect(),
        })
    }

    /// Turns a raw status into a result, updating the tracked phase.
    fn check(
        &self,
        call: &'static str,
        time: Option<f64>,
        mark: u64,
        raw: ffi::fmi2Status,
        detail: impl FnOnce() -> Option<String>,
    ) -> Result<(), SlaveError> {
        let status = Status::from_raw(raw);
        if status.is_success() {
            return Ok(());
        }
        let failure = CallFailure {
            instance: self.name.clone(),
            call: self.call_name(call),
            time,
            status,
            detail: detail(),
            log: self.log.since(mark),
        };
        match status {
            Status::Discard => {
                self.phase.set(Phase::Failed);
                Err(SlaveError::Discard(failure))
            }
            Status::Fatal => {
                self.phase.set(Phase::Fatal);
                Err(SlaveError::Failed(failure))
            }
            _ => {
                self.phase.set(Phase::Failed);
                Err(SlaveError::Failed(failure))
            }
        }
    }

    fn invalid(&self, call: &'static str, message: impl Into<String>) -> SlaveError {
        SlaveError::InvalidArgument { instance: self.name.clone(), call: self.call_name(call), message: message.into() }
    }

    /// The name of the C function behind the FMI 2.0 call `call`: itself, or its FMI 3.0
    /// counterpart for an FMI 3.0 FMU (see [`crate::fmi::fmi3`]).
    fn call_name(&self, call: &'static str) -> &'static str {
        if self.library.fmi3().is_some() {
            crate::fmi::fmi3::call_name(call)
        } else {
            call
        }
    }

    fn check_lengths(&self, call: &'static str, references: usize, values: usize) -> Result<(), SlaveError> {
        if references == values {
            Ok(())
        } else {
            Err(self.invalid(call, format!("{references} value references but {values} values")))
        }
    }

    /// `fmi2SetupExperiment` (times in seconds). Also sets the tracked time to `start`.
    pub fn setup_experiment(
        &mut self,
        tolerance: Option<f64>,
        start: f64,
        stop: Option<f64>,
    ) -> Result<(), SlaveError> {
        let mark = self.log.mark();
        watch::enter(self.id, Call::SetupExperiment, start, f64::NAN);
        // SAFETY: live component; plain values.
        let raw = unsafe {
            (self.functions.fmi2SetupExperiment)(
                self.component,
                ffi::fmi2Boolean::from(tolerance.is_some()),
                tolerance.unwrap_or(0.0),
                start,
                ffi::fmi2Boolean::from(stop.is_some()),
                stop.unwrap_or(0.0),
            )
        };
        watch::leave();
        self.check("fmi2SetupExperiment", Some(start), mark, raw, || {
            Some(format!("startTime = {start:?}, stopTime = {}", stop.map_or("undefined".into(), |s| format!("{s:?}"))))
        })?;
        self.time.set(start);
        Ok(())
    }

    /// `fmi2EnterInitializationMode`.
    pub fn enter_initialization_mode(&mut self) -> Result<(), SlaveError> {
        let enter = self.functions.fmi2EnterInitializationMode;
        self.transition("fmi2EnterInitializationMode", Call::EnterInitializationMode, enter, Phase::InitializationMode)
    }

    /// `fmi2ExitInitializationMode`.
    pub fn exit_initialization_mode(&mut self) -> Result<(), SlaveError> {
        let exit = self.functions.fmi2ExitInitializationMode;
        self.transition("fmi2ExitInitializationMode", Call::ExitInitializationMode, exit, Phase::StepMode)
    }

    /// A call that takes the component alone and moves the instance to `phase` (`call`, the
    /// table's `function`), watched as `watched`.
    fn transition(
        &mut self,
        call: &'static str,
        watched: Call,
        function: unsafe extern "C" fn(ffi::fmi2Component) -> ffi::fmi2Status,
        phase: Phase,
    ) -> Result<(), SlaveError> {
        let mark = self.log.mark();
        watch::enter(self.id, watched, self.time.get(), f64::NAN);
        // SAFETY: live component.
        let raw = unsafe { function(self.component) };
        watch::leave();
        self.check(call, Some(self.time.get()), mark, raw, || None)?;
        self.phase.set(phase);
        Ok(())
    }

    /// `fmi2DoStep` from `current` (s) over `step` (s), with
    /// `noSetFMUStatePriorToCurrentPoint = fmi2True`.
    pub fn do_step(&mut self, current: f64, step: f64) -> Result<(), SlaveError> {
        let mark = self.log.mark();
        watch::enter(self.id, Call::DoStep, current, step);
        // SAFETY: live component.
        let raw = unsafe { (self.functions.fmi2DoStep)(self.component, current, step, ffi::fmi2True) };
        watch::leave();
        self.check("fmi2DoStep", Some(current), mark, raw, || {
            Some(format!("currentCommunicationPoint = {current:?}, communicationStepSize = {step:?}"))
        })
        .inspect_err(|error| {
            if error.is_discard() {
                self.phase.set(Phase::StepDiscarded);
            }
        })?;
        self.time.set(current + step);
        Ok(())
    }

    /// `fmi2GetBooleanStatus(fmi2Terminated)`: after `fmi2DoStep` returned `fmi2Discard`,
    /// true if the FMU asks the importer to end the simulation.
    pub fn terminated(&self) -> Result<bool, SlaveError> {
        let get = self.functions.fmi2GetBooleanStatus;
        let value =
            self.status_query("fmi2GetBooleanStatus", "fmi2Terminated", get, ffi::fmi2Terminated, ffi::fmi2False)?;
        Ok(value != ffi::fmi2False)
    }

    /// `fmi2GetRealStatus(fmi2LastSuccessfulTime)`: after `fmi2DoStep` returned `fmi2Discard`,
    /// the time (s) up to which the FMU computed the step.
    pub fn last_successful_time(&self) -> Result<f64, SlaveError> {
        let get = self.functions.fmi2GetRealStatus;
        self.status_query("fmi2GetRealStatus", "fmi2LastSuccessfulTime", get, ffi::fmi2LastSuccessfulTime, 0.0)
    }

    /// Runs one `fmi2Get*Status` call (`call`, the table's `get`) for the status kind `kind`
    /// (named `kind_name`), its value written over `initial`. Such a call returns `fmi2Discard`
    /// when the FMU cannot tell; that is an error for the caller but leaves the instance's state
    /// as it was.
    fn status_query<T>(
        &self,
        call: &'static str,
        kind_name: &'static str,
        get: unsafe extern "C" fn(ffi::fmi2Component, ffi::fmi2StatusKind, *mut T) -> ffi::fmi2Status,
        kind: ffi::fmi2StatusKind,
        initial: T,
    ) -> Result<T, SlaveError> {
        let mut value = initial;
        let (phase, mark) = (self.phase.get(), self.log.mark());
        // SAFETY: live component; `value` is a valid out-parameter.
        let raw = unsafe { get(self.component, kind, &mut value) };
        self.check(call, Some(self.time.get()), mark, raw, || Some(format!("s = {kind_name}"))).inspect_err(
            |error| {
                if error.is_discard() {
                    self.phase.set(phase);
                }
            },
        )?;
        Ok(value)
    }

    /// `fmi2Terminate`.
    pub fn terminate(&mut self) -> Result<(), SlaveError> {
        self.transition("fmi2Terminate", Call::Terminate, self.functions.fmi2Terminate, Phase::Terminated)
    }

    /// `fmi2Reset`: back to the state right after instantiation.
    pub fn reset(&mut self) -> Result<(), SlaveError> {
        let mark = self.log.mark();
        // SAFETY: live component.
        let raw = unsafe { (self.functions.fmi2Reset)(self.component) };
        self.check("fmi2Reset", None, mark, raw, || None)?;
        self.phase.set(Phase::Instantiated);
        self.time.set(0.0);
        Ok(())
    }

    /// `fmi2SetDebugLogging` for the given categories (all if empty).
    pub fn set_debug_logging(&mut self, logging_on: bool, categories: &[&str]) -> Result<(), SlaveError> {
        let call = "fmi2SetDebugLogging";
        let owned: Vec<CString> =
            categories.iter().map(|c| to_c_string(&self.name, call, "category", c)).collect::<Result<_, _>>()?;
        let pointers: Vec<ffi::fmi2String> = owned.iter().map(|c| c.as_ptr()).collect();
        let mark = self.log.mark();
        // SAFETY: `pointers` holds `len` valid strings.
        let raw = unsafe {
            (self.functions.fmi2SetDebugLogging)(
                self.component,
                ffi::fmi2Boolean::from(logging_on),
                pointers.len(),
                if pointers.is_empty() { ptr::null() } else { pointers.as_ptr() },
            )
        };
        self.check(call, None, mark, raw, || None)
    }
}

impl Drop for Slave {
    /// Terminates the instance if it is initialized and stepping, then frees it.
    ///
    /// FMI 2.0 allows `fmi2Terminate` only once initialization is done (slave
    /// initialized: step complete, failed (discarded) or canceled); an instance dropped while
    /// instantiated or in initialization mode (another instance failed to
    /// initialize) or after `fmi2Error` is only freed. After `fmi2Fatal` nothing
    /// is called (the standard forbids it); the instance is leaked.
    fn drop(&mut self) {
        match self.phase.get() {
            Phase::Fatal => {
                watch::forget_instance(self.id);
                return;
            }
            Phase::StepMode | Phase::StepDiscarded => {
                let _ = self.terminate();
            }
            Phase::Instantiated | Phase::InitializationMode | Phase::Terminated | Phase::Failed => {}
        }
        watch::enter(self.id, Call::FreeInstance, self.time.get(), f64::NAN);
        // SAFETY: the component is live and freed exactly once; the callbacks and
        // the log context it points to are still alive (fields drop afterwards).
        unsafe { (self.functions.fmi2FreeInstance)(self.component) };
        watch::leave();
        watch::forget_instance(self.id);
    }
}
