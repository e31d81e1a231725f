//! A safe FMI 2.0 Co-Simulation instance.
//!
//! [`Slave`] owns everything the C side may point to (the library, the
//! callback table and the logging context) and frees the instance on drop.
//! Every status becomes a `Result`; a [`SlaveError`] names the instance, the
//! `fmi2*` call, the simulation time where relevant, the status and the
//! FMU's own log message.

mod error;
mod state;

use std::cell::Cell;
use std::ffi::{CStr, CString};
use std::ptr;
use std::sync::Arc;

pub use error::{CallFailure, SlaveError};
pub use state::FmuState;

use crate::fmi::{ffi, Functions, Library, LogContext, LogEcho, Status};
use crate::fmu::{Fmu, ModelDescription, ScalarVariable};
use crate::names;
use crate::value::{Value, VariableType};

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
    Terminated,
    /// A call returned `fmi2Error` (or `fmi2Discard`); only reset, free or
    /// restoring a state are allowed.
    Failed,
    /// A call returned `fmi2Fatal`; no further call is allowed (not even free).
    Fatal,
}

/// One FMU instance (`fmi2Component`) in Co-Simulation mode.
pub struct Slave {
    name: String,
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

fn to_c_string(
    instance: &str,
    call: &'static str,
    what: &str,
    text: &str,
) -> Result<CString, SlaveError> {
    CString::new(text).map_err(|_| SlaveError::InvalidArgument {
        instance: instance.to_string(),
        call,
        message: format!("{what} {text:?} contains a NUL character"),
    })
}

impl Slave {
    /// `fmi2Instantiate` in Co-Simulation mode with the GUID from the model
    /// description and the `file:` URI of the extracted `resources/` folder.
    pub fn instantiate(
        fmu: &Fmu,
        name: &str,
        options: InstantiateOptions,
    ) -> Result<Self, SlaveError> {
        let library = fmu.library()?;
        let model = Arc::clone(fmu.model_description());
        let call = "fmi2Instantiate";
        let c_name = to_c_string(name, call, "instance name", name)?;
        let guid = to_c_string(name, call, "GUID", &model.guid)?;
        let resources = to_c_string(name, call, "resource location", &fmu.resource_uri())?;
        let log = LogContext::new(name, options.echo);
        let callbacks = Box::new(log.callbacks());
        let functions = *library.functions();
        // SAFETY: all pointers are valid NUL-terminated strings / a live callback
        // table; `callbacks` and `log` are kept alive until fmi2FreeInstance.
        let component = unsafe {
            (functions.fmi2Instantiate)(
                c_name.as_ptr(),
                ffi::fmi2CoSimulation,
                guid.as_ptr(),
                resources.as_ptr(),
                &*callbacks,
                ffi::fmi2Boolean::from(options.visible),
                ffi::fmi2Boolean::from(options.logging_on),
            )
        };
        if component.is_null() {
            return Err(SlaveError::InstantiateFailed {
                instance: name.to_string(),
                fmu: fmu.source().to_path_buf(),
                log: log.messages(),
            });
        }
        Ok(Self {
            name: name.to_string(),
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
        self.model
            .variable(name)
            .ok_or_else(|| SlaveError::UnknownVariable {
                instance: self.name.clone(),
                model: self.model.model_name.clone(),
                name: name.to_string(),
                suggestion: names::closest(
                    name,
                    self.model.variables.iter().map(|v| v.name.as_str()),
                ),
                available: self
                    .model
                    .variables
                    .iter()
                    .map(|v| v.name.clone())
                    .collect(),
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
            call,
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
        SlaveError::InvalidArgument {
            instance: self.name.clone(),
            call,
            message: message.into(),
        }
    }

    fn check_lengths(
        &self,
        call: &'static str,
        references: usize,
        values: usize,
    ) -> Result<(), SlaveError> {
        if references == values {
            Ok(())
        } else {
            Err(self.invalid(
                call,
                format!("{references} value references but {values} values"),
            ))
        }
    }

    /// `name = value, ...` for the variables of a failed set call.
    fn describe_values(&self, abi_type: VariableType, vrs: &[u32], values: &[String]) -> String {
        const SHOWN: usize = 12;
        let mut parts: Vec<String> = vrs
            .iter()
            .zip(values)
            .take(SHOWN)
            .map(
                |(&vr, value)| match self.model.variable_by_reference(vr, abi_type) {
                    Some(variable) => format!("{} = {value}", variable.name),
                    None => format!("unknown valueReference {vr} = {value}"),
                },
            )
            .collect();
        if vrs.len() > SHOWN {
            parts.push(format!("... {} more", vrs.len() - SHOWN));
        }
        parts.join(", ")
    }

    fn describe_references(&self, abi_type: VariableType, vrs: &[u32]) -> String {
        let names: Vec<String> = vrs
            .iter()
            .take(12)
            .map(|&vr| match self.model.variable_by_reference(vr, abi_type) {
                Some(variable) => variable.name.clone(),
                None => format!("unknown valueReference {vr}"),
            })
            .collect();
        let more = if vrs.len() > 12 {
            format!(", ... {} more", vrs.len() - 12)
        } else {
            String::new()
        };
        format!("{}{more}", names.join(", "))
    }

    /// `fmi2SetupExperiment` (times in seconds). Also sets the tracked time to `start`.
    pub fn setup_experiment(
        &mut self,
        tolerance: Option<f64>,
        start: f64,
        stop: Option<f64>,
    ) -> Result<(), SlaveError> {
        let mark = self.log.mark();
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
        self.check("fmi2SetupExperiment", Some(start), mark, raw, || {
            Some(format!(
                "startTime = {start:?}, stopTime = {}",
                stop.map_or("undefined".into(), |s| format!("{s:?}"))
            ))
        })?;
        self.time.set(start);
        Ok(())
    }

    /// `fmi2EnterInitializationMode`.
    pub fn enter_initialization_mode(&mut self) -> Result<(), SlaveError> {
        let mark = self.log.mark();
        // SAFETY: live component.
        let raw = unsafe { (self.functions.fmi2EnterInitializationMode)(self.component) };
        self.check(
            "fmi2EnterInitializationMode",
            Some(self.time.get()),
            mark,
            raw,
            || None,
        )?;
        self.phase.set(Phase::InitializationMode);
        Ok(())
    }

    /// `fmi2ExitInitializationMode`.
    pub fn exit_initialization_mode(&mut self) -> Result<(), SlaveError> {
        let mark = self.log.mark();
        // SAFETY: live component.
        let raw = unsafe { (self.functions.fmi2ExitInitializationMode)(self.component) };
        self.check(
            "fmi2ExitInitializationMode",
            Some(self.time.get()),
            mark,
            raw,
            || None,
        )?;
        self.phase.set(Phase::StepMode);
        Ok(())
    }

    /// `fmi2DoStep` from `current` (s) over `step` (s), with
    /// `noSetFMUStatePriorToCurrentPoint = fmi2True`.
    pub fn do_step(&mut self, current: f64, step: f64) -> Result<(), SlaveError> {
        let mark = self.log.mark();
        // SAFETY: live component.
        let raw =
            unsafe { (self.functions.fmi2DoStep)(self.component, current, step, ffi::fmi2True) };
        self.check("fmi2DoStep", Some(current), mark, raw, || {
            Some(format!(
                "currentCommunicationPoint = {current:?}, communicationStepSize = {step:?}"
            ))
        })?;
        self.time.set(current + step);
        Ok(())
    }

    /// `fmi2Terminate`.
    pub fn terminate(&mut self) -> Result<(), SlaveError> {
        let mark = self.log.mark();
        // SAFETY: live component.
        let raw = unsafe { (self.functions.fmi2Terminate)(self.component) };
        self.check("fmi2Terminate", Some(self.time.get()), mark, raw, || None)?;
        self.phase.set(Phase::Terminated);
        Ok(())
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
    pub fn set_debug_logging(
        &mut self,
        logging_on: bool,
        categories: &[&str],
    ) -> Result<(), SlaveError> {
        let call = "fmi2SetDebugLogging";
        let owned: Vec<CString> = categories
            .iter()
            .map(|c| to_c_string(&self.name, call, "category", c))
            .collect::<Result<_, _>>()?;
        let pointers: Vec<ffi::fmi2String> = owned.iter().map(|c| c.as_ptr()).collect();
        let mark = self.log.mark();
        // SAFETY: `pointers` holds `len` valid strings.
        let raw = unsafe {
            (self.functions.fmi2SetDebugLogging)(
                self.component,
                ffi::fmi2Boolean::from(logging_on),
                pointers.len(),
                if pointers.is_empty() {
                    ptr::null()
                } else {
                    pointers.as_ptr()
                },
            )
        };
        self.check(call, None, mark, raw, || None)
    }

    /// `fmi2GetReal`: `values[i]` receives the value of `vrs[i]`.
    pub fn get_real(&self, vrs: &[u32], values: &mut [f64]) -> Result<(), SlaveError> {
        let call = "fmi2GetReal";
        self.check_lengths(call, vrs.len(), values.len())?;
        let mark = self.log.mark();
        // SAFETY: both slices have `vrs.len()` elements.
        let raw = unsafe {
            (self.functions.fmi2GetReal)(
                self.component,
                vrs.as_ptr(),
                vrs.len(),
                values.as_mut_ptr(),
            )
        };
        self.check(call, Some(self.time.get()), mark, raw, || {
            Some(self.describe_references(VariableType::Real, vrs))
        })
    }

    /// `fmi2GetInteger` (also for enumerations).
    pub fn get_integer(&self, vrs: &[u32], values: &mut [i32]) -> Result<(), SlaveError> {
        let call = "fmi2GetInteger";
        self.check_lengths(call, vrs.len(), values.len())?;
        let mark = self.log.mark();
        // SAFETY: both slices have `vrs.len()` elements.
        let raw = unsafe {
            (self.functions.fmi2GetInteger)(
                self.component,
                vrs.as_ptr(),
                vrs.len(),
                values.as_mut_ptr(),
            )
        };
        self.check(call, Some(self.time.get()), mark, raw, || {
            Some(self.describe_references(VariableType::Integer, vrs))
        })
    }

    /// `fmi2GetBoolean` (any non-zero `fmi2Boolean` is `true`).
    pub fn get_boolean(&self, vrs: &[u32], values: &mut [bool]) -> Result<(), SlaveError> {
        let call = "fmi2GetBoolean";
        self.check_lengths(call, vrs.len(), values.len())?;
        let mut raw_values = vec![ffi::fmi2False; vrs.len()];
        let mark = self.log.mark();
        // SAFETY: both buffers have `vrs.len()` elements.
        let raw = unsafe {
            (self.functions.fmi2GetBoolean)(
                self.component,
                vrs.as_ptr(),
                vrs.len(),
                raw_values.as_mut_ptr(),
            )
        };
        self.check(call, Some(self.time.get()), mark, raw, || {
            Some(self.describe_references(VariableType::Boolean, vrs))
        })?;
        for (value, raw) in values.iter_mut().zip(raw_values) {
            *value = raw != ffi::fmi2False;
        }
        Ok(())
    }

    /// `fmi2GetString`, copied into owned strings (invalid UTF-8 is replaced).
    pub fn get_string(&self, vrs: &[u32]) -> Result<Vec<String>, SlaveError> {
        let call = "fmi2GetString";
        let mut pointers: Vec<ffi::fmi2String> = vec![ptr::null(); vrs.len()];
        let mark = self.log.mark();
        // SAFETY: both buffers have `vrs.len()` elements.
        let raw = unsafe {
            (self.functions.fmi2GetString)(
                self.component,
                vrs.as_ptr(),
                vrs.len(),
                pointers.as_mut_ptr(),
            )
        };
        self.check(call, Some(self.time.get()), mark, raw, || {
            Some(self.describe_references(VariableType::String, vrs))
        })?;
        pointers
            .into_iter()
            .zip(vrs)
            .map(|(pointer, vr)| {
                if pointer.is_null() {
                    Err(self.invalid(
                        call,
                        format!("the FMU returned NULL for valueReference {vr}"),
                    ))
                } else {
                    // SAFETY: the FMU returned a NUL-terminated string valid until its next call.
                    Ok(unsafe { CStr::from_ptr(pointer) }
                        .to_string_lossy()
                        .into_owned())
                }
            })
            .collect()
    }

    /// `fmi2SetReal`. On failure the error lists `name = value` of the variables.
    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Result<(), SlaveError> {
        let call = "fmi2SetReal";
        self.check_lengths(call, vrs.len(), values.len())?;
        let mark = self.log.mark();
        // SAFETY: both slices have `vrs.len()` elements.
        let raw = unsafe {
            (self.functions.fmi2SetReal)(self.component, vrs.as_ptr(), vrs.len(), values.as_ptr())
        };
        self.check(call, Some(self.time.get()), mark, raw, || {
            let shown: Vec<String> = values.iter().map(|v| format!("{v:?}")).collect();
            Some(self.describe_values(VariableType::Real, vrs, &shown))
        })
    }

    /// `fmi2SetInteger` (also for enumerations).
    pub fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Result<(), SlaveError> {
        let call = "fmi2SetInteger";
        self.check_lengths(call, vrs.len(), values.len())?;
        let mark = self.log.mark();
        // SAFETY: both slices have `vrs.len()` elements.
        let raw = unsafe {
            (self.functions.fmi2SetInteger)(
                self.component,
                vrs.as_ptr(),
                vrs.len(),
                values.as_ptr(),
            )
        };
        self.check(call, Some(self.time.get()), mark, raw, || {
            let shown: Vec<String> = values.iter().map(i32::to_string).collect();
            Some(self.describe_values(VariableType::Integer, vrs, &shown))
        })
    }

    /// `fmi2SetBoolean`.
    pub fn set_boolean(&mut self, vrs: &[u32], values: &[bool]) -> Result<(), SlaveError> {
        let call = "fmi2SetBoolean";
        self.check_lengths(call, vrs.len(), values.len())?;
        let raw_values: Vec<ffi::fmi2Boolean> =
            values.iter().map(|&v| ffi::fmi2Boolean::from(v)).collect();
        let mark = self.log.mark();
        // SAFETY: both buffers have `vrs.len()` elements.
        let raw = unsafe {
            (self.functions.fmi2SetBoolean)(
                self.component,
                vrs.as_ptr(),
                vrs.len(),
                raw_values.as_ptr(),
            )
        };
        self.check(call, Some(self.time.get()), mark, raw, || {
            let shown: Vec<String> = values.iter().map(bool::to_string).collect();
            Some(self.describe_values(VariableType::Boolean, vrs, &shown))
        })
    }

    /// `fmi2SetString`.
    pub fn set_string(&mut self, vrs: &[u32], values: &[&str]) -> Result<(), SlaveError> {
        let call = "fmi2SetString";
        self.check_lengths(call, vrs.len(), values.len())?;
        let owned: Vec<CString> = values
            .iter()
            .map(|v| to_c_string(&self.name, call, "value", v))
            .collect::<Result<_, _>>()?;
        let pointers: Vec<ffi::fmi2String> = owned.iter().map(|c| c.as_ptr()).collect();
        let mark = self.log.mark();
        // SAFETY: both buffers have `vrs.len()` elements; the strings outlive the call.
        let raw = unsafe {
            (self.functions.fmi2SetString)(
                self.component,
                vrs.as_ptr(),
                vrs.len(),
                pointers.as_ptr(),
            )
        };
        self.check(call, Some(self.time.get()), mark, raw, || {
            let shown: Vec<String> = values.iter().map(|v| format!("{v:?}")).collect();
            Some(self.describe_values(VariableType::String, vrs, &shown))
        })
    }

    /// Sets one value of any type on the variable `variable` (type-checked).
    pub fn set_value(
        &mut self,
        variable: &ScalarVariable,
        value: &Value,
    ) -> Result<(), SlaveError> {
        let vr = [variable.value_reference];
        match (variable.variable_type.abi_type(), value) {
            (VariableType::Real, Value::Real(v)) => self.set_real(&vr, &[*v]),
            (VariableType::Integer, Value::Integer(v)) => self.set_integer(&vr, &[*v]),
            (VariableType::Boolean, Value::Boolean(v)) => self.set_boolean(&vr, &[*v]),
            (VariableType::String, Value::String(v)) => self.set_string(&vr, &[v.as_str()]),
            (expected, value) => Err(SlaveError::TypeMismatch {
                instance: self.name.clone(),
                variable: variable.name.clone(),
                expected,
                actual: value.abi_type(),
            }),
        }
    }

    /// Reads one value of any type.
    pub fn get_value(&self, variable: &ScalarVariable) -> Result<Value, SlaveError> {
        let vr = [variable.value_reference];
        Ok(match variable.variable_type.abi_type() {
            VariableType::Real => {
                let mut v = [0.0];
                self.get_real(&vr, &mut v)?;
                Value::Real(v[0])
            }
            VariableType::Boolean => {
                let mut v = [false];
                self.get_boolean(&vr, &mut v)?;
                Value::Boolean(v[0])
            }
            VariableType::String => {
                Value::String(self.get_string(&vr)?.into_iter().next().unwrap_or_default())
            }
            _ => {
                let mut v = [0];
                self.get_integer(&vr, &mut v)?;
                Value::Integer(v[0])
            }
        })
    }

    /// `fmi2SetRealInputDerivatives`: `values[i]` is the `orders[i]`-th time
    /// derivative of input `vrs[i]` (SI unit per second^order), valid from the
    /// current communication point.
    pub fn set_real_input_derivatives(
        &mut self,
        vrs: &[u32],
        orders: &[i32],
        values: &[f64],
    ) -> Result<(), SlaveError> {
        let call = "fmi2SetRealInputDerivatives";
        self.check_lengths(call, vrs.len(), values.len())?;
        self.check_lengths(call, vrs.len(), orders.len())?;
        if !self.model.co_simulation.can_interpolate_inputs {
            return Err(SlaveError::Unsupported {
                instance: self.name.clone(),
                call,
                capability: "canInterpolateInputs",
            });
        }
        let mark = self.log.mark();
        // SAFETY: all slices have `vrs.len()` elements.
        let raw = unsafe {
            (self.functions.fmi2SetRealInputDerivatives)(
                self.component,
                vrs.as_ptr(),
                vrs.len(),
                orders.as_ptr(),
                values.as_ptr(),
            )
        };
        self.check(call, Some(self.time.get()), mark, raw, || {
            let shown: Vec<String> = orders
                .iter()
                .zip(values)
                .map(|(o, v)| format!("{v:?} (order {o})"))
                .collect();
            Some(self.describe_values(VariableType::Real, vrs, &shown))
        })
    }
}

impl Drop for Slave {
    /// Terminates the instance if it is initialized and running, then frees it.
    /// After `fmi2Fatal` nothing is called (the standard forbids it); the
    /// instance is leaked.
    fn drop(&mut self) {
        match self.phase.get() {
            Phase::Fatal => return,
            Phase::InitializationMode | Phase::StepMode => {
                let _ = self.terminate();
            }
            Phase::Instantiated | Phase::Terminated | Phase::Failed => {}
        }
        // SAFETY: the component is live and freed exactly once; the callbacks and
        // the log context it points to are still alive (fields drop afterwards).
        unsafe { (self.functions.fmi2FreeInstance)(self.component) };
    }
}
