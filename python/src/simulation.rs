//! `crane_cosim._native.Simulation`: a co-simulation stepped from Python, its variables read and
//! written between steps by name, its whole state saved and restored
//! (python/crane_cosim/__init__.py wraps it as `crane_cosim.Simulation`).

use std::collections::HashMap;

use cosim_engine::execution::{Execution, Snapshot};
use cosim_engine::observer::{Observer, TableRecorder};
use cosim_engine::system::System;
use cosim_engine::text::Decimal;
use fmu_import::fmu::ScalarVariable;
use fmu_import::value::{Value, VariableType};
use pyo3::prelude::*;
use pyo3::types::PyBytes;

use crane_app::run::{self, recording, table_recorder, IN_MEMORY};
use crane_app::Source;

use crate::wording::{chained, error};
use crate::{native, Native, SimulationError};

/// What `Python::detach` may take along: the closure runs on this very thread while the
/// interpreter's lock is released, so a value that is not `Send` (an execution holds its
/// observers as plain trait objects) is never touched by another thread.
struct OnThisThread<T>(T);

// SAFETY: `OnThisThread` only wraps values handed to `Python::detach`, which runs its closure
// on the calling thread and returns before the caller goes on; `Simulation` is `unsendable`, so
// PyO3 also refuses every access to it from another thread.
unsafe impl<T> Send for OnThisThread<T> {}

impl<T> OnThisThread<T> {
    /// The value (a method, so that a closure captures the whole wrapper, not its fields).
    fn into_inner(self) -> T {
        self.0
    }
}

/// How much of a step a requested time may fall short of a communication point and still be it:
/// times are sums of steps, so `advance_to(12.3)` must land on the grid's 12.299999… too.
const TIME_TOLERANCE: f64 = 1e-9;

/// A variable by its qualified name: the instance's index in stepping order and the variable.
type Resolved = (usize, ScalarVariable);

/// The whole co-simulation state at a communication point, for `Simulation.restore`.
#[pyclass(frozen, module = "crane_cosim._native")]
pub struct SavedState {
    snapshot: Snapshot,
    time: f64,
}

#[pymethods]
impl SavedState {
    /// The communication point (s) it was saved at.
    #[getter]
    fn time(&self) -> f64 {
        self.time
    }

    /// The steps completed when it was saved.
    #[getter]
    fn steps_completed(&self) -> u64 {
        self.snapshot.completed_steps()
    }

    /// Each instance's serialized FMU state, in stepping order (`fmi2SerializeFMUstate`).
    fn instance_states<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyBytes>> {
        self.snapshot.states().iter().map(|state| PyBytes::new(py, state)).collect()
    }

    fn __repr__(&self) -> String {
        format!("SavedState(time={}, steps_completed={})", Decimal(self.time), self.snapshot.completed_steps())
    }
}

/// The error of a call on a closed simulation.
fn closed(system: &System) -> PyErr {
    SimulationError::new_err(format!("{}: the simulation is closed", system.file.display()))
}

/// A loaded, instantiated and initialized system, stepped on request.
#[pyclass(unsendable, module = "crane_cosim._native")]
pub struct Simulation {
    system: System,
    /// `None` once closed.
    execution: Option<Execution>,
    recorder: TableRecorder,
    warnings: Vec<String>,
    /// What was loaded: a lone FMU's names may leave out its instance.
    source: Source,
    resolved: HashMap<String, Resolved>,
}

impl Simulation {
    fn execution(&mut self) -> PyResult<&mut Execution> {
        self.execution.as_mut().ok_or_else(|| closed(&self.system))
    }

    /// Resolves `name` (`instance.variable`, or for a lone FMU also `variable`).
    fn resolve(&mut self, name: &str) -> PyResult<Resolved> {
        if let Some(found) = self.resolved.get(name) {
            return Ok(found.clone());
        }
        let found = self.lookup(name).map_err(error)?;
        self.resolved.insert(name.to_string(), found.clone());
        Ok(found)
    }

    fn lookup(&self, name: &str) -> Result<Resolved, String> {
        let qualified = self.source.qualified(name);
        let instances = || self.system.instances.iter().map(|i| i.name.as_str()).collect::<Vec<_>>().join(", ");
        let Some((instance, variable)) = qualified.split_once('.') else {
            return Err(format!("{name}: expected instance.variable (instances: {})", instances()));
        };
        let index = self
            .system
            .instance_index(instance)
            .ok_or_else(|| format!("{name}: unknown instance '{instance}' (instances: {})", instances()))?;
        let description = self.system.instances[index].fmu.model_description();
        let variable = description
            .variable(variable)
            .ok_or_else(|| format!("{name}: instance '{instance}' has no variable '{variable}'"))?;
        Ok((index, variable.clone()))
    }

    /// Steps until `steps` steps are completed (or an instance ends the run), recording each row,
    /// with the interpreter's lock released.
    fn step_until(&mut self, py: Python<'_>, steps: u64) -> PyResult<f64> {
        let Self { execution, recorder, system, .. } = self;
        let execution = execution.as_mut().ok_or_else(|| closed(system))?;
        let work = OnThisThread((execution, recorder));
        let outcome = py.detach(move || {
            let (execution, recorder) = work.into_inner();
            while execution.completed_steps() < steps && !execution.is_done() {
                execution.step()?;
                let (k, time) = (execution.completed_steps(), execution.time());
                recorder.observe(k, time, execution.simulators())?;
            }
            Ok::<f64, cosim_engine::error::Error>(execution.time())
        });
        outcome.map_err(|e| chained(&e))
    }

    fn set_one(&mut self, name: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let (instance, variable) = self.resolve(name)?;
        let value = match variable.variable_type.abi_type() {
            VariableType::Real => Value::Real(value.extract()?),
            VariableType::Integer | VariableType::Enumeration => Value::Integer(value.extract()?),
            VariableType::Boolean => Value::Boolean(value.extract()?),
            VariableType::String => Value::String(value.extract()?),
        };
        let execution = self.execution()?;
        execution.simulators_mut()[instance]
            .set_value(variable.value_reference, &value)
            .map_err(|e| SimulationError::new_err(format!("cannot set {name}: {}", chain_of(&e))))
    }

    fn get_one(&mut self, py: Python<'_>, name: &str) -> PyResult<Py<PyAny>> {
        let (instance, variable) = self.resolve(name)?;
        let vr = [variable.value_reference];
        let execution = self.execution()?;
        let simulator = &execution.simulators()[instance];
        let failed = |e: cosim_engine::simulator::SimulatorError| {
            SimulationError::new_err(format!("cannot get {name}: {}", chain_of(&e)))
        };
        Ok(match variable.variable_type.abi_type() {
            VariableType::Real => {
                let mut value = [0.0];
                simulator.get_real(&vr, &mut value).map_err(failed)?;
                value[0].into_pyobject(py)?.into_any().unbind()
            }
            VariableType::Integer | VariableType::Enumeration => {
                let mut value = [0];
                simulator.get_integer(&vr, &mut value).map_err(failed)?;
                value[0].into_pyobject(py)?.into_any().unbind()
            }
            VariableType::Boolean => {
                let mut value = [false];
                simulator.get_boolean(&vr, &mut value).map_err(failed)?;
                pyo3::types::PyBool::new(py, value[0]).to_owned().into_any().unbind()
            }
            VariableType::String => {
                let value = simulator.get_string(&vr).map_err(failed)?;
                value.into_iter().next().unwrap_or_default().into_pyobject(py)?.into_any().unbind()
            }
        })
    }
}

/// A simulator error with its causes, on one line.
fn chain_of(error: &(dyn std::error::Error + 'static)) -> String {
    fmu_import::error_chain(error)
}

#[pymethods]
impl Simulation {
    /// Loads, instantiates and initializes; the options are those of `run`.
    #[new]
    fn new(py: Python<'_>, system: std::path::PathBuf, options: crate::options::RunOptions) -> PyResult<Self> {
        let request = options.request(system)?;
        let loaded = py.detach(|| {
            let loaded = run::load(&request);
            let warnings: Vec<String> = loaded.notices().iter().map(ToString::to_string).collect();
            let system = loaded.into_system()?;
            let recorder = table_recorder(&system)?;
            let mut execution = Execution::from_system(&system, IN_MEMORY).map_err(cosim_engine::error::Error::from)?;
            execution.initialize().map_err(cosim_engine::error::Error::from)?;
            Ok::<_, run::TableError>(OnThisThread((system, recorder, execution, warnings)))
        });
        let (system, mut recorder, execution, warnings) = loaded.map_err(|e| chained(&e))?.into_inner();
        recorder.observe(0, execution.time(), execution.simulators()).map_err(|e| chained(&e))?;
        let source = request.source;
        Ok(Self { system, execution: Some(execution), recorder, warnings, source, resolved: HashMap::new() })
    }

    /// The communication point reached (s).
    #[getter]
    fn time(&self) -> f64 {
        self.execution.as_ref().map_or(f64::NAN, Execution::time)
    }

    /// Macro steps completed.
    #[getter]
    fn steps_completed(&self) -> u64 {
        self.execution.as_ref().map_or(0, Execution::completed_steps)
    }

    /// Macro steps from the start to the stop time.
    #[getter]
    fn steps(&self) -> u64 {
        self.system.grid.steps()
    }

    /// The macro step size (s) of the coming step.
    #[getter]
    fn step_size(&self) -> f64 {
        self.system.grid.step_size(self.steps_completed())
    }

    /// The stop time (s).
    #[getter]
    fn stop_time(&self) -> f64 {
        self.system.grid.time(self.system.grid.steps())
    }

    /// True when the stop time is reached or an instance ended the run.
    #[getter]
    fn done(&self) -> bool {
        self.execution.as_ref().is_none_or(Execution::is_done)
    }

    /// The instance names, in stepping order.
    #[getter]
    fn instances(&self) -> Vec<String> {
        self.system.instances.iter().map(|i| i.name.clone()).collect()
    }

    /// The notes and warnings the command line prints before the run.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// Every variable as (qualified name, causality, type, unit).
    fn variables(&self) -> Vec<(String, String, String, Option<String>)> {
        let mut all = Vec::new();
        for instance in &self.system.instances {
            for variable in &instance.fmu.model_description().variables {
                all.push((
                    format!("{}.{}", instance.name, variable.name),
                    format!("{:?}", variable.causality).to_lowercase(),
                    format!("{:?}", variable.variable_type.abi_type()).to_lowercase(),
                    variable.unit.clone(),
                ));
            }
        }
        all
    }

    /// Takes `count` macro steps (fewer if the run ends first); returns the time reached.
    fn step(&mut self, py: Python<'_>, count: u64) -> PyResult<f64> {
        let completed = self.execution()?.completed_steps();
        if self.done() && count > 0 {
            return Err(SimulationError::new_err(format!(
                "{}: the run ended at t = {} s; nothing left to step",
                self.system.file.display(),
                Decimal(self.time())
            )));
        }
        self.step_until(py, completed.saturating_add(count))
    }

    /// Steps until the communication point at `time` (s) or the first one after it.
    fn advance_to(&mut self, py: Python<'_>, time: f64) -> PyResult<f64> {
        let grid = self.system.grid;
        if !time.is_finite() || time > grid.time(grid.steps()) * (1.0 + TIME_TOLERANCE) + TIME_TOLERANCE {
            return Err(SimulationError::new_err(format!(
                "advance_to({}): beyond the stop time {} s",
                Decimal(time),
                Decimal(grid.time(grid.steps()))
            )));
        }
        let mut steps = self.steps_completed();
        while steps < grid.steps() && grid.time(steps) < time - TIME_TOLERANCE * time.abs().max(1.0) {
            steps += 1;
        }
        self.step_until(py, steps)
    }

    /// Steps to the stop time.
    fn run(&mut self, py: Python<'_>) -> PyResult<f64> {
        let steps = self.system.grid.steps();
        self.step_until(py, steps)
    }

    /// The current values of `names`, each as its type (float, int, bool, str).
    fn get(&mut self, py: Python<'_>, names: Vec<String>) -> PyResult<Vec<Py<PyAny>>> {
        names.iter().map(|name| self.get_one(py, name)).collect()
    }

    /// The current values of Real variables, as floats (one `fmi2GetReal` per instance and name).
    fn get_reals(&mut self, names: Vec<String>) -> PyResult<Vec<f64>> {
        let mut values = Vec::with_capacity(names.len());
        for name in &names {
            let (instance, variable) = self.resolve(name)?;
            if variable.variable_type.abi_type() != VariableType::Real {
                return Err(SimulationError::new_err(format!("{name} is not a Real variable")));
            }
            let mut value = [0.0];
            let execution = self.execution()?;
            execution.simulators()[instance]
                .get_real(&[variable.value_reference], &mut value)
                .map_err(|e| SimulationError::new_err(format!("cannot get {name}: {}", chain_of(&e))))?;
            values.push(value[0]);
        }
        Ok(values)
    }

    /// Sets each (name, value) before the next step: parameters the FMU lets change, and inputs
    /// (a connected input is overwritten by its connection at the next step).
    fn set(&mut self, values: Vec<(String, Bound<'_, PyAny>)>) -> PyResult<()> {
        for (name, value) in &values {
            self.set_one(name, value)?;
        }
        Ok(())
    }

    /// The whole co-simulation state now: every instance's FMU state and what the master
    /// carries between steps.
    fn save(&mut self) -> PyResult<SavedState> {
        let time = self.time();
        let snapshot = self.execution()?.save().map_err(|e| chained(&e))?;
        Ok(SavedState { snapshot, time })
    }

    /// Goes back (or forward) to a saved state of this system; the recorded rows after it are
    /// dropped and recorded again as the run goes on.
    fn restore(&mut self, state: &SavedState) -> PyResult<()> {
        self.execution()?.restore(&state.snapshot).map_err(|e| chained(&e))?;
        self.recorder.rewind(state.snapshot.completed_steps());
        Ok(())
    }

    /// The rows recorded so far: (names, units, times, columns), as `run` gives them.
    fn results<'py>(&self, py: Python<'py>) -> Native<'py> {
        native(py, recording(&self.system, self.recorder.table().clone()), Vec::new())
    }

    /// Terminates and frees the instances (`fmi2Terminate`, `fmi2FreeInstance`); idempotent.
    fn close(&mut self) -> PyResult<()> {
        if let Some(mut execution) = self.execution.take() {
            execution.terminate().map_err(|e| chained(&e))?;
        }
        Ok(())
    }
}
