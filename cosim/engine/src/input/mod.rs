//! External input signals from CSV files, applied to an instance at each
//! communication point the way FMPy's `Input.apply` does.

mod interpolate;

use std::sync::Arc;

pub use interpolate::{discrete_index, locate, Segment};

use fmu_import::fmu::{ScalarVariable, Variability};
use fmu_import::value::VariableType;

use crate::simulator::{Simulator, SimulatorError};
use crate::table::SignalTable;

/// The inputs of one instance that are fed from one table.
///
/// Real inputs with continuous variability are interpolated linearly (and
/// their slopes optionally passed as first-order input derivatives); all
/// other inputs are discrete (held). Integer and Boolean columns are
/// converted like NumPy's cast to `int` (truncation toward zero; non-zero is
/// `true`). Variables are set in model-description order, Reals first, as
/// FMPy does.
#[derive(Debug, Clone)]
pub struct InputBinding {
    table: Arc<SignalTable>,
    continuous: Channel,
    discrete_real: Channel,
    integer: Channel,
    boolean: Channel,
    derivatives: bool,
}

/// Value references and the table columns they read.
#[derive(Debug, Clone, Default)]
struct Channel {
    vrs: Vec<u32>,
    columns: Vec<usize>,
}

impl Channel {
    fn push(&mut self, vr: u32, column: usize) {
        self.vrs.push(vr);
        self.columns.push(column);
    }
}

impl InputBinding {
    /// Binds `columns` (column index, variable) of `table`; `derivatives`
    /// enables `fmi2SetRealInputDerivatives` (order 1) for continuous Reals.
    ///
    /// The caller has checked that the variables are inputs of a settable
    /// type; string inputs are ignored here.
    pub fn new(table: Arc<SignalTable>, mut columns: Vec<(usize, usize, &ScalarVariable)>, derivatives: bool) -> Self {
        // (model-description index, column, variable): FMPy's order.
        columns.sort_by_key(|(index, _, _)| *index);
        let mut binding = Self {
            table,
            continuous: Channel::default(),
            discrete_real: Channel::default(),
            integer: Channel::default(),
            boolean: Channel::default(),
            derivatives,
        };
        for (_, column, variable) in columns {
            let vr = variable.value_reference;
            match variable.variable_type.abi_type() {
                VariableType::Real if variable.variability == Variability::Continuous => {
                    binding.continuous.push(vr, column)
                }
                VariableType::Real => binding.discrete_real.push(vr, column),
                VariableType::Integer => binding.integer.push(vr, column),
                VariableType::Boolean => binding.boolean.push(vr, column),
                _ => {}
            }
        }
        binding
    }

    /// The table.
    pub fn table(&self) -> &SignalTable {
        &self.table
    }

    /// Values of the continuous Real inputs at `time` (before or after an
    /// event at exactly that time).
    pub fn continuous_at(&self, time: f64, after_event: bool) -> Vec<f64> {
        let table = &self.table;
        let segment = locate(&table.times, time, after_event);
        self.continuous.columns.iter().map(|&c| segment.value(&table.columns[c])).collect()
    }

    /// Sets all bound inputs of `slave` to their values at `time` (seconds).
    ///
    /// `next` is the end of the coming step (None during initialization).
    /// With derivatives on, the slope passed for a continuous input is the
    /// secant of the interpolated signal over `[time, next]`, so an FMU that
    /// interpolates inputs sees exactly the piecewise-linear signal through
    /// the samples when they lie on the grid. (FMPy 0.3.x instead passes the
    /// slope of the segment that *ends* at a sample, which extrapolates the
    /// previous segment over the coming step.)
    pub fn apply(&self, slave: &mut dyn Simulator, time: f64, next: Option<f64>) -> Result<(), SimulatorError> {
        let table = &self.table;
        let after_event = next.is_some();
        if !self.continuous.vrs.is_empty() {
            let values = self.continuous_at(time, after_event);
            slave.set_real(&self.continuous.vrs, &values)?;
            if let (true, Some(next)) = (self.derivatives, next) {
                let ahead = self.continuous_at(next, false);
                let slopes: Vec<f64> = ahead.iter().zip(&values).map(|(a, v)| (a - v) / (next - time)).collect();
                slave.set_real_input_derivatives(&self.continuous.vrs, &slopes)?;
            }
        }
        let row = discrete_index(&table.times, time, after_event);
        let at = |column: usize| table.columns[column][row];
        if !self.discrete_real.vrs.is_empty() {
            let values: Vec<f64> = self.discrete_real.columns.iter().map(|&c| at(c)).collect();
            slave.set_real(&self.discrete_real.vrs, &values)?;
        }
        if !self.integer.vrs.is_empty() {
            let values: Vec<i32> = self.integer.columns.iter().map(|&c| at(c) as i32).collect();
            slave.set_integer(&self.integer.vrs, &values)?;
        }
        if !self.boolean.vrs.is_empty() {
            let values: Vec<bool> = self.boolean.columns.iter().map(|&c| at(c) as i32 != 0).collect();
            slave.set_boolean(&self.boolean.vrs, &values)?;
        }
        Ok(())
    }
}
