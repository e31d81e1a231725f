//! One FMU instance: the state machine, argument checks and FMU-state snapshots, in safe Rust.
//! The raw C entry points of both versions ([`crate::fmi2::api`], [`crate::fmi3::api`]) only
//! convert pointers and call these methods.

use crate::image;
use crate::logging::{c_string, Logger, Short, LOG_CATEGORIES};
use crate::lookup::{settable_in, Lookup, RealSlot, Slot};
use crate::model::{Environment, Model};
use crate::state::{Mask, Standard, State};
use crate::status::Status;
use crate::variables::{Causality, Value, ValueType, Variable};
use fmu_model::time_tolerance;
use serde::{Deserialize, Serialize};
use std::ffi::{c_char, CString};

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

/// Reads one Real variable of a model.
type RealGetter<M> = fn(&M) -> f64;

/// The bits of `x` shifted left by one, dropping the sign: ordered as unsigned integers, the
/// finite numbers come before the infinities and NaNs (an exponent of all ones).
#[inline]
fn shifted_bits(x: f64) -> u64 {
    x.to_bits() << 1
}

/// Whether `shifted_bits` of a value are those of a finite number.
#[inline]
fn finite_when_shifted(bits: u64) -> bool {
    bits < shifted_bits(f64::INFINITY)
}

pub struct Instance<M: Model> {
    /// The API the instance was created through (see [`Standard`]).
    pub(crate) standard: Standard,
    pub(crate) name: CString,
    pub(crate) logger: Logger,
    logging_on: bool,
    guid: String,
    env: Environment,
    pub(crate) core: Core<M>,
    lookup: Lookup<M>,
    /// The getter of every Real output, in table order, checked for non-finite values after each
    /// model computation (a compact array: the check runs after every step).
    output_getters: Box<[RealGetter<M>]>,
    /// Keeps strings returned by `fmi2GetString` / `fmi3GetString` alive until the next call,
    /// as the standards require.
    strings: Vec<CString>,
    /// FMI 3.0's independent variable `time` (a Float64 every FMI 3.0 FMU declares, read-only):
    /// its value reference, or `None` for FMI 2.0, which has none.
    time_vr: Option<u32>,
    /// Whether a step longer than the model's largest sensible one was reported already (once is
    /// enough: the host chose its step for the whole run).
    warned_long_step: bool,
}

/// How an instance is created: the API, the host's logger and logging flag, and the GUID or
/// instantiation token of the description the host read.
pub struct Creation {
    pub standard: Standard,
    pub logger: Logger,
    pub logging_on: bool,
    pub guid: String,
    /// The value reference of FMI 3.0's independent variable `time`, `None` for FMI 2.0.
    pub time_vr: Option<u32>,
}

/// The `apply` of [`Instance::set_all`] for the variables of one [`Value`] variant: calls the
/// variable's setter (the slot check has made sure it has one).
macro_rules! setter {
    ($variant:ident) => {
        |model, v, value| {
            if let Value::$variant { set: Some(set), .. } = v.value {
                set(model, value);
            }
        }
    };
}

/// The value check of the types whose every value is valid (Boolean, String).
fn any_value<M, T>(_: &Variable<M>, _: u32, _: T) -> Outcome {
    Ok(())
}

impl<M: Model> Instance<M> {
    pub fn new(env: Environment, creation: Creation) -> Outcome<Self> {
        let table = M::variables();
        let core = fresh_core::<M>(&env)?;
        let Creation { standard, logger, logging_on, guid, time_vr } = creation;
        Ok(Instance {
            standard,
            name: c_string(&env.instance_name),
            logger,
            logging_on,
            guid,
            env,
            core,
            lookup: Lookup::new(table),
            output_getters: real_outputs(table).map(|(_, get)| get).collect(),
            strings: Vec::new(),
            time_vr,
            warned_long_step: false,
        })
    }

    pub fn state(&self) -> State {
        self.core.state
    }

    pub fn log_error(&self, status: Status, message: &str) {
        self.logger.log(&self.name, status, "logStatusError", message);
    }

    /// Reports a call under `logCalls` if logging is on; with logging off this is one test.
    #[inline]
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
            self.not_allowed(function, mask)
        }
    }

    #[cold]
    #[inline(never)]
    fn not_allowed(&self, function: &str, mask: Mask) -> Outcome {
        let (state, standard) = (self.core.state, self.standard);
        error(format!(
            "{function} is not allowed in state {} (allowed in: {})",
            state.name(standard),
            mask.describe(standard)
        ))
    }

    pub fn set_debug_logging(&mut self, on: bool, categories: &[&str]) -> Outcome {
        if let Some(unknown) = categories.iter().find(|c| !LOG_CATEGORIES.iter().any(|(n, _)| n == *c)) {
            let known: Vec<&str> = LOG_CATEGORIES.iter().map(|(n, _)| *n).collect();
            return error(format!("unknown log category '{unknown}' (known: {})", known.join(", ")));
        }
        self.logging_on = on;
        Ok(())
    }

    /// Refuses what a state image could not hold (a non-finite time) and a tolerance no solver
    /// could use; the tolerance itself is not used (the models step with fixed rules).
    pub fn setup_experiment(&mut self, tolerance: Option<f64>, start: f64, stop: Option<f64>) -> Outcome {
        if let Some(tolerance) = tolerance {
            if !(tolerance > 0.0 && tolerance.is_finite()) {
                return error(format!("tolerance {tolerance} is not a finite positive number"));
            }
        }
        if !start.is_finite() {
            return error(format!("startTime {start} is not finite"));
        }
        if let Some(stop) = stop {
            if !stop.is_finite() {
                return error(format!("stopTime {stop} is not finite (leave stopTimeDefined false for no stop time)"));
            }
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
        self.model_call(|m| m.initialize(t0), || "initialization".to_owned())?;
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
            return error(format!("non-finite arguments (t = {}, h = {})", Short(tc), Short(h)));
        }
        if h <= 0.0 {
            return error(format!("communicationStepSize must be > 0, got {}", Short(h)));
        }
        if !(tc + h).is_finite() {
            return error(format!(
                "a step of {} s from t = {} s ends past the largest representable time",
                Short(h),
                Short(tc)
            ));
        }
        let max = M::INFO.max_step_size;
        if h > max {
            return error(format!(
                "communicationStepSize {} s exceeds the largest step of this FMU, {max} s per fmi2DoStep \
                 (a bound on the work of one call): split the step",
                Short(h)
            ));
        }
        if (tc - now).abs() > time_tolerance(now) {
            return error(format!(
                "currentCommunicationPoint {} is not the current time {} of this instance",
                Short(tc),
                Short(now)
            ));
        }
        if tc + h == tc {
            return error(format!(
                "a step of {} s from t = {} s does not advance time (below the resolution of t)",
                Short(h),
                Short(tc)
            ));
        }

        if let Some(stop) = self.core.stop_time {
            if tc + h > stop + time_tolerance(stop) {
                return error(format!("step to {} goes past stopTime {}", Short(tc + h), Short(stop)));
            }
        }
        self.warn_long_step(h);
        self.model_call(|m| m.do_step(tc, h), || format!("step from t = {} s", Short(tc)))?;
        self.core.time = tc + h;
        for message in self.core.model.take_warnings() {
            self.logger.log(&self.name, Status::Warning, "logStatusWarning", &message);
        }
        Ok(())
    }

    /// Logs a warning, once, when `h` is longer than the model's largest sensible step
    /// ([`Model::largest_sensible_step`]), naming both; the step still runs.
    fn warn_long_step(&mut self, h: f64) {
        if self.warned_long_step {
            return;
        }
        let Some(limit) = self.core.model.largest_sensible_step() else { return };
        if h <= limit + time_tolerance(limit) {
            return;
        }
        self.warned_long_step = true;
        let message = format!(
            "communicationStepSize {} s is longer than this FMU's largest sensible step, {} s (its sample \
             period): the samples between two communication points run on inputs held since the first, \
             so the results are not what a step of {} s or less gives",
            Short(h),
            Short(limit),
            Short(limit)
        );
        self.logger.log(&self.name, Status::Warning, "logStatusWarning", &message);
    }

    /// Runs a model computation; a failure or a non-finite output puts the instance in `Error`.
    /// `what` names the computation in the message, and is only called if it failed.
    fn model_call(&mut self, f: impl FnOnce(&mut M) -> Result<(), String>, what: impl FnOnce() -> String) -> Outcome {
        let result = f(&mut self.core.model).and_then(|()| self.first_non_finite_output());
        result.map_err(|message| {
            self.core.state = State::Error;
            Failure { status: Status::Error, message: format!("{} failed: {message}", what()) }
        })
    }

    fn first_non_finite_output(&self) -> Result<(), String> {
        let model = &self.core.model;
        // One pass without a branch per output; only a failure looks for the name. Shifted left
        // by one (dropping the sign), the bits of an infinity or NaN are at least those of an
        // exponent of all ones, and of every finite number below: so the largest shifted pattern
        // tells whether all are finite. The maximum stays in an integer register across the
        // getter calls, where an `f64` accumulator is saved and reloaded around each call. Two
        // getters per iteration share the loop's own instructions (the maximum is associative).
        let shifted = |get: &RealGetter<M>| shifted_bits(get(model));
        let mut pairs = self.output_getters.chunks_exact(2);
        let mut largest = 0;
        for pair in &mut pairs {
            largest = largest.max(shifted(&pair[0])).max(shifted(&pair[1]));
        }
        largest = pairs.remainder().iter().map(shifted).fold(largest, u64::max);
        if finite_when_shifted(largest) {
            return Ok(());
        }
        match real_outputs(M::variables()).find(|(_, get)| !get(model).is_finite()) {
            None => Ok(()),
            Some((name, get)) => Err(format!("output '{name}' became {}", get(model))),
        }
    }

    /// Outputs read during initialization mode reflect the parameters and inputs set so far.
    #[inline]
    fn refresh_if_initializing(&mut self) -> Outcome {
        if self.core.state == State::InitializationMode {
            self.refresh()
        } else {
            Ok(())
        }
    }

    /// The work of [`Self::refresh_if_initializing`], out of line: only initialization needs it,
    /// and every getter call tests for it.
    #[cold]
    #[inline(never)]
    fn refresh(&mut self) -> Outcome {
        let t0 = self.core.start_time;
        self.core.model.initialize(t0).or_else(|message| error(format!("initialization failed: {message}")))
    }

    fn variable(&self, ty: ValueType, vr: u32) -> Outcome<&'static Variable<M>> {
        match self.lookup.row(ty, vr) {
            Some(row) => Ok(&M::variables()[row]),
            None => unknown(ty, vr),
        }
    }

    /// Who may set a variable in which state (FMI 2.0 §3.2.3 / §4.2.4).
    fn check_settable(&self, v: &Variable<M>) -> Outcome {
        let Some(mask) = settable_in(v) else {
            return error(format!("variable '{}' ({:?}) cannot be set", v.name, v.causality));
        };
        if mask.allows(self.core.state) {
            Ok(())
        } else {
            error(format!(
                "variable '{}' cannot be set in state {} (allowed in: {})",
                v.name,
                self.core.state.name(self.standard),
                mask.describe(self.standard)
            ))
        }
    }

    pub fn get_real(&mut self, vrs: &[u32], out: &mut [f64]) -> Outcome {
        self.refresh_if_initializing()?;
        let model = &self.core.model;
        // Whether every value is finite, tracked as they are read (see
        // `first_non_finite_output`): no second pass over the values.
        let mut largest = 0;
        let read = |real: &RealSlot<M>, slot: &mut f64| {
            let value = (real.get)(model);
            *slot = value;
            largest = largest.max(shifted_bits(value));
            true
        };
        match self.lookup.reals().first_refused(vrs.iter().copied().zip(out.iter_mut()), read) {
            None if finite_when_shifted(largest) => Ok(()),
            None => self.refuse_non_finite(vrs, out),
            Some(i) if self.time_vr.is_some() => self.get_real_with_time(vrs, out, i),
            Some(i) => unknown(ValueType::Real, vrs[i]),
        }
    }

    /// [`Self::get_real`] where the value reference at `first_unknown` is not a table variable:
    /// FMI 3.0's `time` is read here, off the hot path (hosts rarely read it), every other
    /// unknown one is refused.
    #[cold]
    #[inline(never)]
    fn get_real_with_time(&mut self, vrs: &[u32], out: &mut [f64], first_unknown: usize) -> Outcome {
        for (vr, slot) in vrs.iter().zip(out.iter_mut()).skip(first_unknown) {
            *slot = match self.lookup.reals().get(*vr) {
                _ if Some(*vr) == self.time_vr => self.core.time,
                Some(real) if real.present() => (real.get)(&self.core.model),
                _ => return unknown(ValueType::Real, *vr),
            };
        }
        match out.iter().position(|x| !x.is_finite()) {
            None => Ok(()),
            Some(_) => self.refuse_non_finite(vrs, out),
        }
    }

    /// No value leaves the FMU non-finite with `fmi2OK`: outputs that follow inputs directly (set
    /// since the last step) or a failed computation can be NaN, and then the call fails and the
    /// instance goes to `Error`. Called when some value of `values` is not finite.
    #[cold]
    #[inline(never)]
    fn refuse_non_finite(&mut self, vrs: &[u32], values: &[f64]) -> Outcome {
        let i = values.iter().position(|x| !x.is_finite()).unwrap_or_default();
        let name = self.variable(ValueType::Real, vrs[i]).map_or("?", |v| v.name);
        self.core.state = State::Error;
        error(format!("'{name}' is {}: the instance is now in state Error", values[i]))
    }

    pub fn get_integer(&mut self, vrs: &[u32], out: &mut [i32]) -> Outcome {
        self.refresh_if_initializing()?;
        for (vr, slot) in vrs.iter().zip(out) {
            if let Value::Integer { get, .. } = self.variable(ValueType::Integer, *vr)?.value {
                *slot = get(&self.core.model);
            }
        }
        Ok(())
    }

    /// Writes the host's booleans (`fmi2Boolean` or `fmi3Boolean`, made by `to_c`) straight
    /// into its array.
    pub fn get_boolean<B>(&mut self, vrs: &[u32], out: &mut [B], to_c: impl Fn(bool) -> B) -> Outcome {
        self.refresh_if_initializing()?;
        for (vr, slot) in vrs.iter().zip(out) {
            if let Value::Boolean { get, .. } = self.variable(ValueType::Boolean, *vr)?.value {
                *slot = to_c(get(&self.core.model));
            }
        }
        Ok(())
    }

    /// Writes pointers valid until the next string get on this instance into `out`.
    pub fn get_string(&mut self, vrs: &[u32], out: &mut [*const c_char]) -> Outcome {
        self.refresh_if_initializing()?;
        let mut strings = Vec::with_capacity(vrs.len());
        for vr in vrs {
            if let Value::String { get, .. } = self.variable(ValueType::String, *vr)?.value {
                strings.push(c_string(get(&self.core.model)));
            }
        }
        self.strings = strings;
        for (slot, string) in out.iter_mut().zip(&self.strings) {
            *slot = string.as_ptr();
        }
        Ok(())
    }

    /// Sets Reals, all or none: a refused element leaves the instance unchanged. Setting an
    /// input clears its derivative (the input is held until a derivative is set again).
    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Outcome {
        let state = self.core.state;
        let reals = self.lookup.reals();
        let elements = || vrs.iter().copied().zip(values.iter().copied());
        if let Some(i) = reals.first_refused_by(elements(), |real, value| real.accepts(state, value)) {
            return self.refusal(ValueType::Real, vrs[i], values[i], check_real);
        }
        let model = &mut self.core.model;
        if self.lookup.has_derivatives() {
            reals.for_each_accepted(elements(), |real, value| {
                (real.set)(model, value);
                if let Some(derivative) = real.derivative {
                    derivative(model, None);
                }
            });
        } else {
            // No derivative to clear: the loop is the setter calls alone.
            reals.for_each_accepted(elements(), |real, value| (real.set)(model, value));
        }
        Ok(())
    }

    /// Sets Integers, all or none.
    pub fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Outcome {
        let elements = vrs.iter().copied().zip(values.iter().copied());
        self.set_all(ValueType::Integer, elements, check_integer, setter!(Integer))
    }

    /// Sets Booleans from the host's booleans (`is_true` reads one), all or none.
    pub fn set_boolean<B: Copy>(&mut self, vrs: &[u32], values: &[B], is_true: impl Fn(B) -> bool) -> Outcome {
        let elements = vrs.iter().copied().zip(values.iter().map(|b| is_true(*b)));
        self.set_all(ValueType::Boolean, elements, any_value, setter!(Boolean))
    }

    /// Sets Strings, all or none.
    pub fn set_string(&mut self, vrs: &[u32], values: &[&str]) -> Outcome {
        let elements = vrs.iter().copied().zip(values.iter().copied());
        self.set_all(ValueType::String, elements, any_value, setter!(String))
    }

    /// First-order derivatives of Real inputs, used by the next `fmi2DoStep` to interpolate;
    /// all or none.
    pub fn set_real_input_derivatives(&mut self, vrs: &[u32], orders: &[i32], values: &[f64]) -> Outcome {
        let state = self.core.state;
        let reals = self.lookup.reals();
        let elements = vrs.iter().copied().zip(orders.iter().copied().zip(values.iter().copied()));
        let accepts = |real: &RealSlot<M>, (order, value)| real.accepts_derivative(state, order, value);
        if let Some(i) = reals.first_refused_by(elements, accepts) {
            return self.refusal(ValueType::Real, vrs[i], (orders[i], values[i]), check_derivative);
        }
        let model = &mut self.core.model;
        reals.for_each_accepted(vrs.iter().copied().zip(values.iter().copied()), |real, value| {
            if let Some(derivative) = real.derivative {
                derivative(model, Some(value));
            }
        });
        Ok(())
    }

    /// The all-or-nothing set of the non-Real types (parameters, set a few times per run): the
    /// first pass checks every element, the second applies them all and runs only if the first
    /// refused none.
    fn set_all<T: Copy>(
        &mut self,
        ty: ValueType,
        elements: impl Iterator<Item = (u32, T)> + Clone,
        check: impl Fn(&Variable<M>, u32, T) -> Outcome,
        apply: impl Fn(&mut M, &Variable<M>, T),
    ) -> Outcome {
        elements.clone().try_for_each(|(vr, value)| self.check_element(ty, vr, value, &check))?;
        for (vr, value) in elements {
            if let Some(row) = self.lookup.row(ty, vr) {
                apply(&mut self.core.model, &M::variables()[row], value);
            }
        }
        Ok(())
    }

    /// Why an element may not be set: unknown, not settable now, or a refused value (in that
    /// order, the first that applies).
    fn check_element<T>(
        &self,
        ty: ValueType,
        vr: u32,
        value: T,
        check: impl Fn(&Variable<M>, u32, T) -> Outcome,
    ) -> Outcome {
        let v = self.variable(ty, vr)?;
        self.check_settable(v)?;
        check(v, vr, value)
    }

    /// The failure of an element the slot check refused, explained by the descriptive check, so
    /// that messages are built only when a call fails. The two checks must agree (a test holds
    /// them to it); if they did not, the panic becomes `fmi2Fatal` rather than a silent set.
    fn refusal<T>(&self, ty: ValueType, vr: u32, value: T, check: impl Fn(&Variable<M>, u32, T) -> Outcome) -> Outcome {
        Err(self.check_element(ty, vr, value, check).expect_err("the slot check and the descriptive check disagree"))
    }

    pub fn snapshot(&self) -> Core<M> {
        self.core.clone()
    }

    pub fn restore(&mut self, core: &Core<M>) {
        self.core = core.clone();
    }

    /// The bytes of a state, if [`Instance::deserialize`] would accept them back: a state whose
    /// model holds a NaN (a computation that went wrong without reaching an output) is refused
    /// here rather than written into bytes that no instance can read.
    pub fn serialize(&self, core: &Core<M>) -> Outcome<Vec<u8>> {
        validate_decoded(core).or_else(|message| error(format!("the FMU state cannot be serialized: {message}")))?;
        image::encode(self.identity(), core).or_else(|e| error(format!("cannot serialize FMU state: {e}")))
    }

    /// The state in `bytes`, if they are an image this build wrote (see `crate::image`) and
    /// hold values the setters would have accepted.
    pub fn deserialize(&self, bytes: &[u8]) -> Outcome<Core<M>> {
        let core = image::decode(self.identity(), bytes)
            .or_else(|message| error(format!("refused serialized state: {message}")))?;
        validate_decoded(&core).or_else(|message| error(format!("corrupted serialized state: {message}")))?;
        Ok(core)
    }

    /// What an image of this instance's states carries to tell its FMU build.
    fn identity(&self) -> image::Identity<'_> {
        image::Identity { model_identifier: M::INFO.model_identifier, guid: &self.guid }
    }
}

/// Checks a state decoded from the host's bytes before it can be used: every number finite, the
/// experiment's times consistent, every parameter and input within its declared range (what the
/// setters would have refused), then the model's own invariants.
fn validate_decoded<M: Model>(core: &Core<M>) -> Result<(), String> {
    crate::finite::check(core)?;
    if core.stop_time.is_some_and(|stop| !(stop >= core.start_time)) {
        return Err(format!("stopTime {:?} is before startTime {}", core.stop_time, core.start_time));
    }
    for v in M::variables() {
        let checked = match v.value {
            Value::Real { get, set: Some(_), .. } => check_real(v, v.vr, get(&core.model)),
            Value::Integer { get, set: Some(_), .. } => check_integer(v, v.vr, get(&core.model)),
            _ => Ok(()),
        };
        checked.map_err(|failure| failure.message)?;
    }
    core.model.validate_state()
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

/// The name and getter of each Real output of a table, in table order.
fn real_outputs<M>(table: &'static [Variable<M>]) -> impl Iterator<Item = (&'static str, RealGetter<M>)> {
    table.iter().filter_map(|v| match v.value {
        Value::Real { get, .. } if v.causality == Causality::Output => Some((v.name, get)),
        _ => None,
    })
}

/// The failure for a value reference no variable of type `ty` has.
#[cold]
#[inline(never)]
fn unknown<T>(ty: ValueType, vr: u32) -> Outcome<T> {
    error(format!("unknown {} value reference {vr}", ty.name()))
}

/// A Real value must be finite and within the variable's range.
pub(crate) fn check_real<M>(v: &Variable<M>, vr: u32, value: f64) -> Outcome {
    let Value::Real { min, max, .. } = v.value else { return Ok(()) };
    if !value.is_finite() {
        return error(format!("'{}' (vr {vr}) set to non-finite value {value}", v.name));
    }
    if min.is_some_and(|m| value < m) || max.is_some_and(|m| value > m) {
        return error(format!(
            "'{}' = {} is outside its range [{}, {}]",
            v.name,
            Short(value),
            Short(min.unwrap_or(f64::NEG_INFINITY)),
            Short(max.unwrap_or(f64::INFINITY))
        ));
    }
    Ok(())
}

/// An Integer value must be within the variable's range.
fn check_integer<M>(v: &Variable<M>, _vr: u32, value: i32) -> Outcome {
    let Value::Integer { min, max, .. } = v.value else { return Ok(()) };
    if min.is_some_and(|m| value < m) || max.is_some_and(|m| value > m) {
        return error(format!(
            "'{}' = {value} is outside its range [{}, {}]",
            v.name,
            min.unwrap_or(i32::MIN),
            max.unwrap_or(i32::MAX)
        ));
    }
    Ok(())
}

/// A derivative must be of order 1, finite, and of an input that accepts one.
pub(crate) fn check_derivative<M>(v: &Variable<M>, _vr: u32, (order, value): (i32, f64)) -> Outcome {
    if order != 1 {
        return error(format!("'{}': derivative order {order} not supported (only 1)", v.name));
    }
    if !value.is_finite() {
        return error(format!("'{}': non-finite derivative {value}", v.name));
    }
    if !matches!(v.value, Value::Real { derivative: Some(_), .. }) {
        return error(format!("'{}' is not an input that can be interpolated", v.name));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The output check after a step compares shifted bits rather than floats.
    #[test]
    fn shifted_bits_tell_finite_from_non_finite_numbers() {
        let finite = [0.0, -0.0, f64::MAX, f64::MIN, f64::MIN_POSITIVE, -f64::MIN_POSITIVE / 2.0, 1.0, -1e300];
        for x in finite {
            assert!(finite_when_shifted(shifted_bits(x)), "{x}");
        }
        for x in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN, -f64::NAN, f64::from_bits(0x7FF0_0000_0000_0001)] {
            assert!(!finite_when_shifted(shifted_bits(x)), "{x}");
        }
    }
}
