//! What feeds each instance's inputs: input files and connections.
//!
//! Connections are grouped as they are made, so a macro step costs one get call per source
//! instance and type and one set call per type for each target, and no allocation: per target
//! and ABI type, the target's inputs are kept in connection order (the order of the one set
//! call), and per source the outputs to read with one get call, with the place each value takes
//! among the target's inputs. Every buffer is sized here, once.

use fmu_import::value::VariableType;

use crate::input::InputBinding;
use crate::simulator::{Simulator, SimulatorError};

/// A value type exchanged through connections, with the simulator calls that read and write it.
trait Exchanged: Clone + Default + std::fmt::Debug {
    fn get(source: &dyn Simulator, vrs: &[u32], values: &mut [Self]) -> Result<(), SimulatorError>;
    fn set(target: &mut dyn Simulator, vrs: &[u32], values: &[Self]) -> Result<(), SimulatorError>;
    /// False for a value no input should be given (a non-finite Real).
    fn is_usable(&self) -> bool {
        true
    }
    /// Whether every value of `values` [`is_usable`](Self::is_usable): the check of every
    /// gathered batch, so each type may answer it in one pass.
    fn all_usable(values: &[Self]) -> bool {
        values.iter().all(Self::is_usable)
    }
}

impl Exchanged for f64 {
    fn get(source: &dyn Simulator, vrs: &[u32], values: &mut [Self]) -> Result<(), SimulatorError> {
        source.get_real(vrs, values)
    }
    fn set(target: &mut dyn Simulator, vrs: &[u32], values: &[Self]) -> Result<(), SimulatorError> {
        target.set_real(vrs, values)
    }
    fn is_usable(&self) -> bool {
        self.is_finite()
    }
    /// `x - x` is 0 for a finite x and NaN otherwise, so the sum is NaN exactly when some value
    /// is not finite: one pass without a branch per value (as the FMUs check their outputs).
    fn all_usable(values: &[Self]) -> bool {
        #[allow(clippy::eq_op)]
        let residue: f64 = values.iter().map(|x| x - x).sum();
        !residue.is_nan()
    }
}

/// A connected output that an instance returned non-finite with `fmi2OK`: the error is the
/// producer's, not that of the instance the value was meant for.
#[derive(Debug, thiserror::Error)]
#[error("instance {instance:?}: output {output} = {value} is not finite (returned with fmi2OK)")]
pub struct NonFiniteOutput {
    /// The instance that returned the value.
    pub instance: String,
    /// The output's name.
    pub output: String,
    /// The value as printed (`NaN`, `inf`, `-inf`).
    pub value: String,
}

impl Exchanged for i32 {
    fn get(source: &dyn Simulator, vrs: &[u32], values: &mut [Self]) -> Result<(), SimulatorError> {
        source.get_integer(vrs, values)
    }
    fn set(target: &mut dyn Simulator, vrs: &[u32], values: &[Self]) -> Result<(), SimulatorError> {
        target.set_integer(vrs, values)
    }
}

impl Exchanged for bool {
    fn get(source: &dyn Simulator, vrs: &[u32], values: &mut [Self]) -> Result<(), SimulatorError> {
        source.get_boolean(vrs, values)
    }
    fn set(target: &mut dyn Simulator, vrs: &[u32], values: &[Self]) -> Result<(), SimulatorError> {
        target.set_boolean(vrs, values)
    }
}

// Strings are owned by the simulator API, so they are the one type that allocates per step.
impl Exchanged for String {
    fn get(source: &dyn Simulator, vrs: &[u32], values: &mut [Self]) -> Result<(), SimulatorError> {
        for (value, read) in values.iter_mut().zip(source.get_string(vrs)?) {
            *value = read;
        }
        Ok(())
    }
    fn set(target: &mut dyn Simulator, vrs: &[u32], values: &[Self]) -> Result<(), SimulatorError> {
        let values: Vec<&str> = values.iter().map(String::as_str).collect();
        target.set_string(vrs, &values)
    }
}

/// The outputs of one source that feed one target (one type), read with one get call.
#[derive(Debug, Clone)]
struct Batch<T> {
    source: usize,
    /// Source value references.
    vrs: Vec<u32>,
    /// Where each value goes among the target's inputs.
    positions: Vec<usize>,
    /// The first position if the positions follow each other (the connections of this source
    /// are listed together): then the values are read straight into place.
    contiguous: Option<usize>,
    /// The values read, when they are scattered.
    values: Vec<T>,
    /// Source variable names, for errors.
    names: Vec<Box<str>>,
}

impl<T: Exchanged> Batch<T> {
    /// Fails naming the first unusable value of `values` (this batch's, in its order).
    fn check(&self, source: &dyn Simulator, values: &[T]) -> Result<(), SimulatorError> {
        if T::all_usable(values) {
            return Ok(());
        }
        match values.iter().position(|value| !value.is_usable()) {
            None => Ok(()),
            Some(i) => Err(SimulatorError::failed(NonFiniteOutput {
                instance: source.name().to_string(),
                output: self.names[i].to_string(),
                value: format!("{:?}", values[i]),
            })),
        }
    }
}

/// The connected inputs of one target, of one type.
#[derive(Debug, Clone)]
struct Inputs<T> {
    /// Target value references, in connection order.
    vrs: Vec<u32>,
    /// The values to set, in connection order.
    values: Vec<T>,
    batches: Vec<Batch<T>>,
}

impl<T> Default for Inputs<T> {
    fn default() -> Self {
        Self { vrs: Vec::new(), values: Vec::new(), batches: Vec::new() }
    }
}

impl<T: Exchanged> Inputs<T> {
    /// Adds input `to_vr`, fed by output `from_vr` (named `from_name`) of instance `from`;
    /// returns its position.
    fn connect(&mut self, from: usize, from_vr: u32, from_name: &str, to_vr: u32) -> usize {
        let position = self.vrs.len();
        self.vrs.push(to_vr);
        self.values.push(T::default());
        let index = match self.batches.iter().position(|batch| batch.source == from) {
            Some(index) => index,
            None => {
                let batch = Batch {
                    source: from,
                    vrs: Vec::new(),
                    positions: Vec::new(),
                    contiguous: Some(position),
                    values: vec![],
                    names: vec![],
                };
                self.batches.push(batch);
                self.batches.len() - 1
            }
        };
        let batch = &mut self.batches[index];
        if batch.positions.last().is_some_and(|&last| last + 1 != position) {
            batch.contiguous = None;
        }
        batch.vrs.push(from_vr);
        batch.names.push(from_name.into());
        batch.positions.push(position);
        batch.values.push(T::default());
        position
    }

    /// Reads every source's current outputs into [`Inputs::values`].
    fn gather(&mut self, slaves: &[Box<dyn Simulator>]) -> Result<(), SimulatorError> {
        for batch in &mut self.batches {
            let source = slaves[batch.source].as_ref();
            if let Some(start) = batch.contiguous {
                let values = &mut self.values[start..start + batch.vrs.len()];
                T::get(source, &batch.vrs, values)?;
                batch.check(source, values)?;
                continue;
            }
            T::get(source, &batch.vrs, &mut batch.values)?;
            batch.check(source, &batch.values)?;
            for (&position, value) in batch.positions.iter().zip(&batch.values) {
                self.values[position] = value.clone();
            }
        }
        Ok(())
    }

    fn set(&self, target: &mut dyn Simulator) -> Result<(), SimulatorError> {
        if self.vrs.is_empty() {
            Ok(())
        } else {
            T::set(target, &self.vrs, &self.values)
        }
    }
}

/// The Real inputs of one target whose sources step before it (Gauss–Seidel), passed as their
/// value at `t_k` plus the slope to their value at `t_{k+1}` when the target interpolates.
#[derive(Debug, Clone, Default)]
struct Interpolation {
    /// System `input_derivatives` (Gauss–Seidel) or `extrapolate_inputs` (Jacobi) and the
    /// target's `canInterpolateInputs`.
    enabled: bool,
    /// Positions among the target's Real inputs.
    positions: Vec<usize>,
    /// Their target value references.
    vrs: Vec<u32>,
    /// Their values at `t_k` (gathered the step before).
    previous: Vec<f64>,
    /// Slopes over the coming step (unit of the input per second).
    slopes: Vec<f64>,
    /// For Jacobi: the communication point of [`Interpolation::previous`], once there is one.
    previous_time: Option<f64>,
}

impl Interpolation {
    fn add(&mut self, position: usize, vr: u32) {
        self.positions.push(position);
        self.vrs.push(vr);
        self.previous.push(0.0);
        self.slopes.push(0.0);
    }

    fn is_active(&self) -> bool {
        self.enabled && !self.positions.is_empty()
    }
}

/// Everything that feeds one instance.
#[derive(Debug, Clone, Default)]
struct Target {
    files: Vec<InputBinding>,
    real: Inputs<f64>,
    integer: Inputs<i32>,
    boolean: Inputs<bool>,
    string: Inputs<String>,
    interpolation: Interpolation,
    /// Every connected Real input (Jacobi: all sources are at `t_k`), extrapolated from the last
    /// two communication points when the target interpolates.
    extrapolation: Interpolation,
}

/// Input files and connections, indexed by target instance, with the buffers a macro step
/// moves values through.
#[derive(Debug, Clone, Default)]
pub struct Wiring {
    targets: Vec<Target>,
}

impl Wiring {
    /// No inputs for `instances` instances.
    pub fn new(instances: usize) -> Self {
        Self { targets: vec![Target::default(); instances] }
    }

    /// Feeds inputs of instance `target` from an input file.
    pub fn add_file(&mut self, target: usize, binding: InputBinding) {
        self.targets[target].files.push(binding);
    }

    /// Connects output `from.1` (named `from.2` in errors) of instance `from.0` to input `to_vr`
    /// of instance `to`; both variables have the ABI type `kind`. A non-finite Real read from
    /// the output is an error (`NonFiniteOutput`).
    pub fn connect(&mut self, from: (usize, u32, &str), to: usize, to_vr: u32, kind: VariableType) {
        let (from, from_vr, from_name) = from;
        let target = &mut self.targets[to];
        match kind {
            VariableType::Real => {
                let position = target.real.connect(from, from_vr, from_name, to_vr);
                target.extrapolation.add(position, to_vr);
                if from < to {
                    target.interpolation.add(position, to_vr);
                }
            }
            VariableType::Boolean => {
                target.boolean.connect(from, from_vr, from_name, to_vr);
            }
            VariableType::String => {
                target.string.connect(from, from_vr, from_name, to_vr);
            }
            VariableType::Integer | VariableType::Enumeration => {
                target.integer.connect(from, from_vr, from_name, to_vr);
            }
        }
    }

    /// Whether `target` gets its connected Real inputs from earlier sources interpolated over
    /// the step (Gauss–Seidel with input derivatives, for FMUs that can interpolate inputs).
    pub fn set_interpolate(&mut self, target: usize, interpolate: bool) {
        self.targets[target].interpolation.enabled = interpolate;
    }

    /// Whether `target` gets its connected Real inputs extrapolated over the step (Jacobi with
    /// `extrapolate_inputs`, for FMUs that can interpolate inputs; see [`Wiring::extrapolate`]).
    pub fn set_extrapolate(&mut self, target: usize, extrapolate: bool) {
        self.targets[target].extrapolation.enabled = extrapolate;
    }

    /// Number of instances.
    pub fn len(&self) -> usize {
        self.targets.len()
    }

    /// True if there are no instances.
    pub fn is_empty(&self) -> bool {
        self.targets.is_empty()
    }

    /// Sets the inputs of `slave` (instance `index`) that come from files, at
    /// `time`; `next` is the end of the coming step (None while initializing).
    pub fn apply_files(
        &self,
        index: usize,
        slave: &mut dyn Simulator,
        time: f64,
        next: Option<f64>,
    ) -> Result<(), SimulatorError> {
        for binding in &self.targets[index].files {
            binding.apply(slave, time, next)?;
        }
        Ok(())
    }

    /// Reads the current source outputs of every connection into `target`'s buffers.
    pub fn gather(&mut self, target: usize, slaves: &[Box<dyn Simulator>]) -> Result<(), SimulatorError> {
        let target = &mut self.targets[target];
        target.real.gather(slaves)?;
        target.integer.gather(slaves)?;
        target.boolean.gather(slaves)?;
        target.string.gather(slaves)
    }

    /// Sets the gathered values on instance `index`: Reals, Integers, Booleans, Strings, one
    /// call each, in connection order.
    pub fn set(&self, index: usize, slave: &mut dyn Simulator) -> Result<(), SimulatorError> {
        let target = &self.targets[index];
        target.real.set(slave)?;
        target.integer.set(slave)?;
        target.boolean.set(slave)?;
        target.string.set(slave)
    }

    /// True if `target` is passed interpolated inputs (see [`Wiring::set_interpolate`]).
    pub fn interpolates(&self, target: usize) -> bool {
        self.targets[target].interpolation.is_active()
    }

    /// Keeps the gathered values of `target`'s interpolated inputs as those at `t_k` of the
    /// first step (after initialization).
    pub fn remember(&mut self, target: usize) {
        let Target { real, interpolation, .. } = &mut self.targets[target];
        for (previous, &position) in interpolation.previous.iter_mut().zip(&interpolation.positions) {
            *previous = real.values[position];
        }
    }

    /// For Gauss–Seidel, after [`Wiring::gather`] at `t_{k+1}` of the earlier sources: each
    /// interpolated input of `target` goes back to its value at `t_k` and gets the slope
    /// `(y(t_{k+1}) − y(t_k)) / step`, so the target sees it move linearly across the step
    /// instead of jumping; the value at `t_{k+1}` is kept for the next step.
    pub fn interpolate(&mut self, target: usize, step: f64) {
        let Target { real, interpolation, .. } = &mut self.targets[target];
        if !interpolation.is_active() {
            return;
        }
        let Interpolation { positions, previous, slopes, .. } = interpolation;
        for ((&position, previous), slope) in positions.iter().zip(previous.iter_mut()).zip(slopes.iter_mut()) {
            let now = real.values[position];
            *slope = (now - *previous) / step;
            real.values[position] = std::mem::replace(previous, now);
        }
    }

    /// Passes the slopes computed by [`Wiring::interpolate`] to instance `index` as first
    /// derivatives of its inputs (nothing if it does not interpolate).
    pub fn set_slopes(&self, index: usize, slave: &mut dyn Simulator) -> Result<(), SimulatorError> {
        let interpolation = &self.targets[index].interpolation;
        if !interpolation.is_active() {
            return Ok(());
        }
        slave.set_real_input_derivatives(&interpolation.vrs, &interpolation.slopes)
    }

    /// For Jacobi, after [`Wiring::gather`] at `t_k` (`time`): each connected Real input of
    /// `target` keeps its value at `t_k` and gets the slope `(u(t_k) − u(t_{k−1})) / (t_k − t_{k−1})`
    /// from the last two communication points, the one slope known before any instance steps;
    /// at the first step there is none. Returns whether there are slopes to pass.
    pub fn extrapolate(&mut self, target: usize, time: f64) -> bool {
        let Target { real, extrapolation, .. } = &mut self.targets[target];
        if !extrapolation.is_active() {
            return false;
        }
        let Interpolation { positions, previous, slopes, previous_time, .. } = extrapolation;
        let span = previous_time.map(|before| time - before);
        for ((&position, previous), slope) in positions.iter().zip(previous.iter_mut()).zip(slopes.iter_mut()) {
            let now = real.values[position];
            if let Some(span) = span {
                *slope = (now - *previous) / span;
            }
            *previous = now;
        }
        *previous_time = Some(time);
        span.is_some()
    }

    /// Passes the slopes computed by [`Wiring::extrapolate`] to instance `index` as first
    /// derivatives of its inputs.
    pub fn set_extrapolated_slopes(&self, index: usize, slave: &mut dyn Simulator) -> Result<(), SimulatorError> {
        let extrapolation = &self.targets[index].extrapolation;
        slave.set_real_input_derivatives(&extrapolation.vrs, &extrapolation.slopes)
    }
}
