//! What feeds each instance's inputs: input files and connections.

use fmu_import::value::VariableType;

use crate::input::InputBinding;
use crate::simulator::{Simulator, SimulatorError};

/// One connection, as value references.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Transfer {
    from: usize,
    from_vr: u32,
    to_vr: u32,
    kind: VariableType,
}

/// Values read from sources, to be set on one target instance.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Gathered {
    pub(super) real: (Vec<u32>, Vec<f64>),
    integer: (Vec<u32>, Vec<i32>),
    boolean: (Vec<u32>, Vec<bool>),
    string: (Vec<u32>, Vec<String>),
}

/// Inputs files and connections, indexed by target instance.
#[derive(Debug, Clone, Default)]
pub struct Wiring {
    files: Vec<Vec<InputBinding>>,
    transfers: Vec<Vec<Transfer>>,
    /// Per target: whether connected Real inputs from sources stepped earlier in the order are
    /// interpolated over the step (system `input_derivatives` and `canInterpolateInputs`).
    interpolate: Vec<bool>,
}

impl Wiring {
    /// No inputs for `instances` instances.
    pub fn new(instances: usize) -> Self {
        Self {
            files: vec![Vec::new(); instances],
            transfers: vec![Vec::new(); instances],
            interpolate: vec![false; instances],
        }
    }

    /// Feeds inputs of instance `target` from an input file.
    pub fn add_file(&mut self, target: usize, binding: InputBinding) {
        self.files[target].push(binding);
    }

    /// Connects output `from_vr` of instance `from` to input `to_vr` of instance `to`; both
    /// variables have the ABI type `kind`.
    pub fn connect(&mut self, from: usize, from_vr: u32, to: usize, to_vr: u32, kind: VariableType) {
        self.transfers[to].push(Transfer { from, from_vr, to_vr, kind });
    }

    /// Whether `target` gets its connected Real inputs from earlier sources interpolated over
    /// the step (Gauss–Seidel with input derivatives, for FMUs that can interpolate inputs).
    pub fn set_interpolate(&mut self, target: usize, interpolate: bool) {
        self.interpolate[target] = interpolate;
    }

    /// Number of instances.
    pub fn len(&self) -> usize {
        self.files.len()
    }

    /// True if there are no instances.
    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
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
        for binding in &self.files[index] {
            binding.apply(slave, time, next)?;
        }
        Ok(())
    }

    /// Reads the current source outputs of every connection into `target`.
    pub fn gather(&self, target: usize, slaves: &[Box<dyn Simulator>]) -> Result<Gathered, SimulatorError> {
        let mut gathered = Gathered::default();
        for transfer in &self.transfers[target] {
            let source = &slaves[transfer.from];
            let vr = [transfer.from_vr];
            match transfer.kind {
                VariableType::Real => {
                    let mut value = [0.0];
                    source.get_real(&vr, &mut value)?;
                    gathered.real.0.push(transfer.to_vr);
                    gathered.real.1.push(value[0]);
                }
                VariableType::Boolean => {
                    let mut value = [false];
                    source.get_boolean(&vr, &mut value)?;
                    gathered.boolean.0.push(transfer.to_vr);
                    gathered.boolean.1.push(value[0]);
                }
                VariableType::String => {
                    let value = source.get_string(&vr)?;
                    gathered.string.0.push(transfer.to_vr);
                    gathered.string.1.push(value.into_iter().next().unwrap_or_default());
                }
                VariableType::Integer | VariableType::Enumeration => {
                    let mut value = [0];
                    source.get_integer(&vr, &mut value)?;
                    gathered.integer.0.push(transfer.to_vr);
                    gathered.integer.1.push(value[0]);
                }
            }
        }
        Ok(gathered)
    }

    /// For Gauss–Seidel: the connected Real inputs of `target` whose sources were already
    /// stepped to t_{k+1} in this macro step, as (vr, index in the gathered Reals); with
    /// `previous` values at t_k these are passed as value at t_k plus the slope over the step,
    /// so the target sees its input move linearly across the step instead of jumping.
    pub fn interpolated(&self, target: usize) -> Vec<usize> {
        if !self.interpolate[target] {
            return Vec::new();
        }
        self.transfers[target]
            .iter()
            .filter(|t| t.kind == VariableType::Real)
            .enumerate()
            .filter(|(_, t)| t.from < target)
            .map(|(i, _)| i)
            .collect()
    }

    /// Sets gathered values on their target.
    pub fn set(gathered: &Gathered, slave: &mut dyn Simulator) -> Result<(), SimulatorError> {
        if !gathered.real.0.is_empty() {
            slave.set_real(&gathered.real.0, &gathered.real.1)?;
        }
        if !gathered.integer.0.is_empty() {
            slave.set_integer(&gathered.integer.0, &gathered.integer.1)?;
        }
        if !gathered.boolean.0.is_empty() {
            slave.set_boolean(&gathered.boolean.0, &gathered.boolean.1)?;
        }
        if !gathered.string.0.is_empty() {
            let values: Vec<&str> = gathered.string.1.iter().map(String::as_str).collect();
            slave.set_string(&gathered.string.0, &values)?;
        }
        Ok(())
    }
}
