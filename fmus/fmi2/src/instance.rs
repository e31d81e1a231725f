//! One FMU instance: the state machine, argument checks and FMU-state snapshots, in safe Rust.
//! The raw C entry points in [`crate::api`] only convert pointers and call these methods.

use crate::logging::{c_string, Logger};
use crate::model::{Environment, Model};
use crate::state::{self, Mask, State};
use crate::status::Status;
use crate::variables::{Causality, Value, Variability, Variable};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::ffi::CString;

/// Log categories declared in the model description.
pub const LOG_CATEGORIES: &[(&str, &str)] = &[
    ("logStatusError", "Errors (always reported)"),
    ("logStatusWarning", "Warnings"),
    ("logCalls", "Every fmi2 function call"),
];

/// Marks a live instance so that stale or foreign component pointers are recognised.
pub(crate) const MAGIC: u64 = 0x464d_4932_5253_0001;

/// Why a call failed: the status to return and the message for the logger.
#[derive(Debug)]
pub struct Failure {
    pub status: Status,
    pub message: String,
}

pub type Outcome<T = ()> = Result<T, Failure>;

pub fn error<T>(message: impl Into<String>) -> Outcome<T> {
    Err(Failure { status: Status::Error, message: message.into() })
}

/// The part of an instance that an FMU state captures.
#[derive(Clone, Serialize, Deserialize)]
pub struct Core<M> {
    pub state: State,
    pub start_time: f64,
    pub stop_time: Option<f64>,
    /// Current communication point (s): the start time, then `tc + h` of each accepted step.
    pub time: f64,
    pub model: M,
}

/// Serialized FMU states begin with this tag and the GUID, so a state from another model or
/// build is refused instead of misread.
#[derive(Serialize, Deserialize)]
struct SerializedState<M> {
    tag: u64,
    guid: String,
    core: Core<M>,
}

pub struct Instance<M: Model> {
    pub(crate) magic: u64,
    pub(crate) name: CString,
    logger: Logger,
    logging_on: bool,
    guid: String,
    env: Environment,
    pub(crate) core: Core<M>,
    lookup: HashMap<(&'static str, u32), usize>,
    /// Keeps strings returned by `fmi2GetString` alive until the next call, as FMI 2.0 requires.
    strings: Vec<CString>,
}

impl<M: Model> Instance<M> {
    pub fn new(env: Environment, logger: Logger, logging_on: bool, guid: String) -> Outcome<Self> {
        let lookup = M::variables().iter().enumerate().map(|(i, v)| ((v.type_name(), v.vr), i)).collect();
        let core = fresh_core::<M>(&env)?;
        Ok(Instance {
            magic: MAGIC,
            name: c_string(&env.instance_name),
            logger,
            logging_on,
            guid,
            env,
            core,
            lookup,
            strings: Vec::new(),
        })
    }

    pub fn state(&self) -> State {
        self.core.state
    }

    pub fn log_error(&self, status: Status, message: &str) {
        self.logger.log(&self.name, status, "logStatusError", message);
    }

    pub fn log_call(&self, message: &str) {
        if self.logging_on {
            self.logger.log(&self.name, Status::Ok, "logCalls", message);
        }
    }

    /// Refuses a call the state machine does not allow in the current state.
    pub fn check_state(&self, function: &str, mask: Mask) -> Outcome {
        if mask.allows(self.core.state) {
            Ok(())
        } else {
            error(format!("{function} is not allowed in state {:?} (allowed in: {})", self.core.state, mask.describe()))
        }
    }

    pub fn set_debug_logging(&mut self, on: bool, categories: &[String]) -> Outcome {
        if let Some(unknown) = categories.iter().find(|c| !LOG_CATEGORIES.iter().any(|(n, _)| n == c)) {
            let known: Vec<&str> = LOG_CATEGORIES.iter().map(|(n, _)| *n).collect();
            return error(format!("unknown log category '{unknown}' (known: {})", known.join(", ")));
        }
        self.logging_on = on;
        Ok(())
    }

    pub fn setup_experiment(&mut self, start: f64, stop: Option<f64>) -> Outcome {
        if !start.is_finite() {
            return error(format!("startTime {start} is not finite"));
        }
        if let Some(stop) = stop {
            if !(stop >= start) {
                return error(format!("stopTime {stop} is before startTime {start}"));
            }
        }
        self.core.start_time = start;
        self.core.stop_time = stop;
        self.core.time = start;
        Ok(())
    }

    pub fn enter_initialization(&mut self) -> Outcome {
        self.core.state = State::InitializationMode;
        Ok(())
    }

    pub fn exit_initialization(&mut self) -> Outcome {
        let t0 = self.core.start_time;
        self.model_call(|m| m.initialize(t0), "initialization")?;
        self.core.state = State::StepComplete;
        Ok(())
    }

    pub fn terminate(&mut self) -> Outcome {
        self.core.state = State::Terminated;
        Ok(())
    }

    pub fn reset(&mut self) -> Outcome {
        self.core = fresh_core::<M>(&self.env)?;
        Ok(())
    }

    pub fn do_step(&mut self, tc: f64, h: f64) -> Outcome {
        let now = self.core.time;
        if !tc.is_finite() || !h.is_finite() {
            return error(format!("non-finite arguments (t = {tc}, h = {h})"));
        }
        if h <= 0.0 {
            return error(format!("communicationStepSize must be > 0, got {h}"));
        }
        if (tc - now).abs() > 1e-9 * now.abs().max(1.0) {
            return error(format!("currentCommunicationPoint {tc} is not the current time {now} of this instance"));
        }
        if let Some(stop) = self.core.stop_time {
            if tc + h > stop + 1e-9 * stop.abs().max(1.0) {
                return error(format!("step to {} goes past stopTime {stop}", tc + h));
            }
        }
        self.model_call(|m| m.do_step(tc, h), &format!("step from t = {tc} s"))?;
        self.core.time = tc + h;
        Ok(())
    }

    /// Runs a model computation; a failure or a non-finite output puts the instance in `Error`.
    fn model_call(&mut self, f: impl FnOnce(&mut M) -> Result<(), String>, what: &str) -> Outcome {
        let result = f(&mut self.core.model).and_then(|()| first_non_finite_output(&self.core.model));
        result.map_err(|message| {
            self.core.state = State::Error;
            Failure { status: Status::Error, message: format!("{what} failed: {message}") }
        })
    }

    /// Outputs read during initialization mode reflect the parameters and inputs set so far.
    fn refresh_if_initializing(&mut self) -> Outcome {
        if self.core.state == State::InitializationMode {
            let t0 = self.core.start_time;
            if let Err(message) = self.core.model.initialize(t0) {
                return error(format!("initialization failed: {message}"));
            }
        }
        Ok(())
    }

    fn variable(&self, type_name: &'static str, vr: u32) -> Outcome<&'static Variable<M>> {
        match self.lookup.get(&(type_name, vr)) {
            Some(&i) => Ok(&M::variables()[i]),
            None => error(format!("unknown {type_name} value reference {vr}")),
        }
    }

    /// Who may set a variable in which state (FMI 2.0 §3.2.3 / §4.2.4).
    fn check_settable(&self, v: &Variable<M>) -> Outcome {
        let mask = match (v.causality, v.variability) {
            (Causality::Input, _) | (Causality::Parameter, Variability::Tunable) => state::SET_INPUTS,
            (Causality::Parameter, Variability::Fixed) => state::SET_BEFORE_STEPPING,
            _ => return error(format!("variable '{}' ({:?}) cannot be set", v.name, v.causality)),
        };
        if mask.allows(self.core.state) {
            Ok(())
        } else {
            error(format!(
                "variable '{}' cannot be set in state {:?} (allowed in: {})",
                v.name,
                self.core.state,
                mask.describe()
            ))
        }
    }

    pub fn get_real(&mut self, vrs: &[u32], out: &mut [f64]) -> Outcome {
        self.refresh_if_initializing()?;
        for (vr, slot) in vrs.iter().zip(out.iter_mut()) {
            match self.variable("Real", *vr)?.value {
                Value::Real { get, .. } => *slot = get(&self.core.model),
                _ => unreachable!("lookup is keyed by type"),
            }
        }
        Ok(())
    }

    pub fn get_integer(&mut self, vrs: &[u32], out: &mut [i32]) -> Outcome {
        self.refresh_if_initializing()?;
        for (vr, slot) in vrs.iter().zip(out.iter_mut()) {
            if let Value::Integer { get, .. } = self.variable("Integer", *vr)?.value {
                *slot = get(&self.core.model);
            }
        }
        Ok(())
    }

    pub fn get_boolean(&mut self, vrs: &[u32], out: &mut [bool]) -> Outcome {
        self.refresh_if_initializing()?;
        for (vr, slot) in vrs.iter().zip(out.iter_mut()) {
            if let Value::Boolean { get, .. } = self.variable("Boolean", *vr)?.value {
                *slot = get(&self.core.model);
            }
        }
        Ok(())
    }

    /// Returns pointers valid until the next `fmi2GetString` on this instance.
    pub fn get_string(&mut self, vrs: &[u32]) -> Outcome<Vec<*const std::ffi::c_char>> {
        self.refresh_if_initializing()?;
        let mut strings = Vec::with_capacity(vrs.len());
        for vr in vrs {
            if let Value::String { get, .. } = self.variable("String", *vr)?.value {
                strings.push(c_string(get(&self.core.model)));
            }
        }
        self.strings = strings;
        Ok(self.strings.iter().map(|s| s.as_ptr()).collect())
    }

    /// Checks every value first and applies none if one is refused, so a failed call leaves the
    /// instance unchanged. Setting an input clears its derivative (held until set again).
    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Outcome {
        for (vr, value) in vrs.iter().zip(values) {
            let v = self.variable("Real", *vr)?;
            self.check_settable(v)?;
            if let Value::Real { min, max, .. } = v.value {
                if !value.is_finite() {
                    return error(format!("'{}' (vr {vr}) set to non-finite value {value}", v.name));
                }
                if min.is_some_and(|m| *value < m) || max.is_some_and(|m| *value > m) {
                    return error(format!(
                        "'{}' = {value} is outside its range [{}, {}]",
                        v.name,
                        min.unwrap_or(f64::NEG_INFINITY),
                        max.unwrap_or(f64::INFINITY)
                    ));
                }
            }
        }
        for (vr, value) in vrs.iter().zip(values) {
            if let Value::Real { set: Some(set), derivative, .. } = self.variable("Real", *vr)?.value {
                set(&mut self.core.model, *value);
                if let Some(derivative) = derivative {
                    derivative(&mut self.core.model, None);
                }
            }
        }
        Ok(())
    }

    pub fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Outcome {
        for (vr, value) in vrs.iter().zip(values) {
            let v = self.variable("Integer", *vr)?;
            self.check_settable(v)?;
            if let Value::Integer { min, max, .. } = v.value {
                if min.is_some_and(|m| *value < m) || max.is_some_and(|m| *value > m) {
                    return error(format!(
                        "'{}' = {value} is outside its range [{}, {}]",
                        v.name,
                        min.unwrap_or(i32::MIN),
                        max.unwrap_or(i32::MAX)
                    ));
                }
            }
        }
        for (vr, value) in vrs.iter().zip(values) {
            if let Value::Integer { set: Some(set), .. } = self.variable("Integer", *vr)?.value {
                set(&mut self.core.model, *value);
            }
        }
        Ok(())
    }

    pub fn set_boolean(&mut self, vrs: &[u32], values: &[bool]) -> Outcome {
        for vr in vrs {
            let v = self.variable("Boolean", *vr)?;
            self.check_settable(v)?;
        }
        for (vr, value) in vrs.iter().zip(values) {
            if let Value::Boolean { set: Some(set), .. } = self.variable("Boolean", *vr)?.value {
                set(&mut self.core.model, *value);
            }
        }
        Ok(())
    }

    pub fn set_string(&mut self, vrs: &[u32], values: &[String]) -> Outcome {
        for vr in vrs {
            let v = self.variable("String", *vr)?;
            self.check_settable(v)?;
        }
        for (vr, value) in vrs.iter().zip(values) {
            if let Value::String { set: Some(set), .. } = self.variable("String", *vr)?.value {
                set(&mut self.core.model, value);
            }
        }
        Ok(())
    }

    /// First-order derivatives of Real inputs, used by the next `fmi2DoStep` to interpolate.
    pub fn set_real_input_derivatives(&mut self, vrs: &[u32], orders: &[i32], values: &[f64]) -> Outcome {
        for ((vr, order), value) in vrs.iter().zip(orders).zip(values) {
            let v = self.variable("Real", *vr)?;
            self.check_settable(v)?;
            if *order != 1 {
                return error(format!("'{}': derivative order {order} not supported (only 1)", v.name));
            }
            if !value.is_finite() {
                return error(format!("'{}': non-finite derivative {value}", v.name));
            }
            if !matches!(v.value, Value::Real { derivative: Some(_), .. }) {
                return error(format!("'{}' is not an input that can be interpolated", v.name));
            }
        }
        for (vr, value) in vrs.iter().zip(values) {
            if let Value::Real { derivative: Some(derivative), .. } = self.variable("Real", *vr)?.value {
                derivative(&mut self.core.model, Some(*value));
            }
        }
        Ok(())
    }

    pub fn snapshot(&self) -> Core<M> {
        self.core.clone()
    }

    pub fn restore(&mut self, core: &Core<M>) {
        self.core = core.clone();
    }

    pub fn serialize(&self, core: &Core<M>) -> Outcome<Vec<u8>> {
        let image = SerializedState { tag: MAGIC, guid: self.guid.clone(), core: core.clone() };
        bincode::serialize(&image).or_else(|e| error(format!("cannot serialize FMU state: {e}")))
    }

    pub fn deserialize(&self, bytes: &[u8]) -> Outcome<Core<M>> {
        let image: SerializedState<M> =
            bincode::deserialize(bytes).or_else(|e| error(format!("not a serialized state of this FMU: {e}")))?;
        if image.tag != MAGIC || image.guid != self.guid {
            return error(format!("serialized state belongs to FMU {}, this is {}", image.guid, self.guid));
        }
        Ok(image.core)
    }
}

/// A model with every table start value applied, in state `Instantiated`.
fn fresh_core<M: Model>(env: &Environment) -> Outcome<Core<M>> {
    let model = with_start_values::<M>(env).or_else(error)?;
    Ok(Core { state: State::Instantiated, start_time: 0.0, stop_time: None, time: 0.0, model })
}

/// `M::new` followed by every start value of the table, which is what `fmi2Instantiate` hands
/// the host (so the table's starts are the model's defaults, stated once).
pub fn with_start_values<M: Model>(env: &Environment) -> Result<M, String> {
    let mut model = M::new(env);
    for v in M::variables().iter().filter(|v| v.has_start()) {
        match v.value {
            Value::Real { start, set: Some(set), .. } => set(&mut model, start),
            Value::Integer { start, set: Some(set), .. } => set(&mut model, start),
            Value::Boolean { start, set: Some(set), .. } => set(&mut model, start),
            Value::String { start, set: Some(set), .. } => set(&mut model, start),
            _ => return Err(format!("variable '{}' has a start value but no setter", v.name)),
        }
    }
    Ok(model)
}

fn first_non_finite_output<M: Model>(model: &M) -> Result<(), String> {
    for v in M::variables().iter().filter(|v| v.causality == Causality::Output) {
        if let Value::Real { get, .. } = v.value {
            let value = get(model);
            if !value.is_finite() {
                return Err(format!("output '{}' became {value}", v.name));
            }
        }
    }
    Ok(())
}
