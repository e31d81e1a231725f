//! An execution: instances, an algorithm and observers on a time grid.
//!
//! Sequence (FMI 2.0 Co-Simulation):
//! `fmi2Instantiate` → `fmi2SetupExperiment(t0, stop)` → start values →
//! `fmi2EnterInitializationMode` → inputs at `t0` → `fmi2ExitInitializationMode`
//! → observe `t0` → for each `k`: inputs at `t_k`, `fmi2DoStep(t_k, t_{k+1} − t_k)`,
//! observe `t_{k+1}` → `fmi2Terminate` → `fmi2FreeInstance` (on drop).

use std::cell::RefCell;
use std::rc::Rc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use serde::Serialize;

use fmu_import::slave::{InstantiateOptions, Slave};
use fmu_import::value::Value;

use crate::algorithm::{algorithm, Algorithm, Wiring};
use crate::interrupt::{signal_name, Interrupt};
use crate::observer::{Observer, ObserverError, TableRecorder};
use crate::simulator::{timed, CallTimes, Simulator, SimulatorError, Wrapped, Wrapper};
use crate::system::System;
use crate::table::SignalTable;
use crate::text::Decimal;
use crate::time::TimeGrid;

/// Why an execution stopped.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    #[error("instantiation failed")]
    Instantiate(#[source] SimulatorError),
    #[error("initialization failed at t = {} s", Decimal(*time))]
    Initialize {
        time: f64,
        #[source]
        source: SimulatorError,
    },
    #[error("simulation stopped at t = {} s (step {step} of {steps})", Decimal(*time))]
    Step {
        time: f64,
        step: u64,
        steps: u64,
        #[source]
        source: SimulatorError,
    },
    /// `fmi2DoStep` returned `fmi2Discard` and the instance did not ask to end the simulation
    /// (`fmi2Terminated` false, or not available).
    #[error("instance {instance:?} discarded the step from t = {} s (step {step} of {steps}) {why}", Decimal(*time))]
    Discarded {
        instance: String,
        time: f64,
        step: u64,
        steps: u64,
        /// What its `fmi2Terminated` status said.
        why: String,
        #[source]
        source: SimulatorError,
    },
    /// Stopped between steps on request ([`Execution::interrupt_on`]).
    #[error("interrupted by {signal} at t = {} s", Decimal(*time))]
    Interrupted { time: f64, signal: String },
    #[error("recording failed at t = {} s", Decimal(*time))]
    Observer {
        time: f64,
        #[source]
        source: ObserverError,
    },
    #[error("termination failed")]
    Terminate(#[source] SimulatorError),
    /// [`Execution::save`] or [`Execution::restore`] failed.
    #[error("cannot {action} the state of instance {instance:?} at t = {} s", Decimal(*time))]
    State {
        /// `"save"` or `"restore"`.
        action: &'static str,
        instance: String,
        time: f64,
        #[source]
        source: SimulatorError,
    },
    /// [`Execution::save`] before initialization, or [`Execution::restore`] of a snapshot of
    /// another system.
    #[error("{0}")]
    Snapshot(String),
}

/// The whole state of an initialized execution at a communication point ([`Execution::save`]):
/// each instance's serialized FMU state, what the algorithm carries between steps, the steps
/// completed and whether an instance had ended the run. Plain data: it can be kept, cloned and
/// restored into this execution or another one of the same system, any number of times.
#[derive(Debug, Clone)]
pub struct Snapshot {
    completed: u64,
    termination: Option<Termination>,
    states: Vec<Vec<u8>>,
    wiring: Wiring,
}

impl Snapshot {
    /// The steps completed when it was taken.
    pub fn completed_steps(&self) -> u64 {
        self.completed
    }

    /// Each instance's serialized state, in stepping order.
    pub fn states(&self) -> &[Vec<u8>] {
        &self.states
    }
}

/// How far an instance that ended the run got in its last step ([`Execution::step`]).
enum StepEnd {
    /// To the step's end: the step counts and its row is kept.
    Completed,
    /// Part of the way: the run ends at the step's start.
    Short,
}

/// How close (relative to the time, at least 1 s) `fmi2LastSuccessfulTime` must be to `t_{k+1}`
/// for the step to count as completed: the FMU sums its own times, which may differ from the
/// grid's `t0 + (k+1)·h` in the last bits.
const FULL_STEP_TOLERANCE: f64 = 1e-9;

/// An instance that ended the run early: `fmi2DoStep` returned `fmi2Discard` and
/// `fmi2GetBooleanStatus(fmi2Terminated)` said true, which FMI 2.0 defines as a request to end
/// the simulation. The run stops at the last communication point every instance completed, which
/// is the discarded step's end when the instance reached it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Termination {
    /// The instance name.
    pub instance: String,
    /// The time (s) it reached in the discarded step (`fmi2LastSuccessfulTime`); null if it
    /// could not tell.
    pub time: Option<f64>,
}

impl std::fmt::Display for Termination {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "terminated by instance {:?}", self.instance)?;
        match self.time {
            Some(time) => write!(f, " at t = {} s", Decimal(time)),
            None => write!(f, " (time reached unknown)"),
        }
    }
}

/// Instances stepped by an [`Algorithm`] on a [`TimeGrid`], watched by [`Observer`]s.
pub struct Execution {
    slaves: Vec<Box<dyn Simulator>>,
    /// Per simulator, (value reference, value) to set before initialization.
    start_values: Vec<Vec<(u32, Value)>>,
    algorithm: Box<dyn Algorithm>,
    observers: Vec<Box<dyn Observer>>,
    grid: TimeGrid,
    stop_time: f64,
    completed: u64,
    initialized: bool,
    interrupt: Option<Interrupt>,
    termination: Option<Termination>,
    /// `completed`, for another thread to read ([`Execution::publish_progress`]).
    progress: Option<Arc<AtomicU64>>,
}

impl std::fmt::Debug for Execution {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Execution")
            .field("simulators", &self.slaves.iter().map(|s| s.name()).collect::<Vec<_>>())
            .field("algorithm", &self.algorithm.name())
            .field("grid", &self.grid)
            .field("completed", &self.completed)
            .finish_non_exhaustive()
    }
}

impl Execution {
    /// An execution of already instantiated slaves. `stop_time` (s) is passed
    /// to `fmi2SetupExperiment`.
    pub fn new(grid: TimeGrid, stop_time: f64, algorithm: Box<dyn Algorithm>) -> Self {
        Self {
            slaves: Vec::new(),
            start_values: Vec::new(),
            algorithm,
            observers: Vec::new(),
            grid,
            stop_time,
            completed: 0,
            initialized: false,
            interrupt: None,
            termination: None,
            progress: None,
        }
    }

    /// Instantiates every instance of a validated system, in order.
    pub fn from_system(system: &System, options: InstantiateOptions) -> Result<Self, RunError> {
        let mut execution =
            Self::new(system.grid, system.spec.stop_time, algorithm(system.spec.algorithm, wiring(system)));
        for instance in &system.instances {
            let slave = Slave::instantiate(&instance.fmu, &instance.name, options)
                .map_err(|e| RunError::Instantiate(e.into()))?;
            let start = instance.start.iter().map(|(variable, value)| (variable.value_reference, value.clone()));
            execution.add_simulator(Box::new(slave), start.collect());
        }
        Ok(execution)
    }

    /// Adds a simulator (stepping order is insertion order) with the start values (value
    /// reference, value) to set before initialization. Returns its index.
    pub fn add_simulator(&mut self, simulator: Box<dyn Simulator>, start_values: Vec<(u32, Value)>) -> usize {
        self.slaves.push(simulator);
        self.start_values.push(start_values);
        self.slaves.len() - 1
    }

    /// Puts `wrapper` around simulator `index` (stepping order) from now on, e.g. to set its
    /// inputs before every step. Panics if there is no simulator `index`, as indexing does.
    pub fn wrap(&mut self, index: usize, wrapper: impl Wrapper + 'static) {
        let inner = self.slaves.remove(index);
        self.slaves.insert(index, Box::new(Wrapped::new(inner, wrapper)));
    }

    /// Times every simulator's `do_step` and get/set calls from now on (wall time); returns
    /// the totals, in stepping order.
    pub fn time_calls(&mut self) -> Vec<Arc<CallTimes>> {
        let (slaves, times) = std::mem::take(&mut self.slaves)
            .into_iter()
            .map(|slave| {
                let (slave, times) = timed(slave);
                (Box::new(slave) as Box<dyn Simulator>, times)
            })
            .unzip();
        self.slaves = slaves;
        times
    }

    /// Adds an observer.
    pub fn add_observer(&mut self, observer: Box<dyn Observer>) {
        self.observers.push(observer);
    }

    /// The simulators, in stepping order.
    pub fn simulators(&self) -> &[Box<dyn Simulator>] {
        &self.slaves
    }

    /// The time grid.
    pub fn grid(&self) -> &TimeGrid {
        &self.grid
    }

    /// Steps completed so far.
    pub fn completed_steps(&self) -> u64 {
        self.completed
    }

    /// The communication point reached (s).
    pub fn time(&self) -> f64 {
        self.grid.time(self.completed)
    }

    /// The algorithm's name.
    pub fn algorithm_name(&self) -> &'static str {
        self.algorithm.name()
    }

    fn observe(&mut self) -> Result<(), RunError> {
        let (k, time) = (self.completed, self.time());
        for observer in &mut self.observers {
            observer.observe(k, time, &self.slaves).map_err(|source| RunError::Observer { time, source })?;
        }
        Ok(())
    }

    /// Setup, start values, initialization mode with inputs at `t0`, then
    /// the first observation.
    pub fn initialize(&mut self) -> Result<(), RunError> {
        let time = self.grid.start();
        let failed = |source| RunError::Initialize { time, source };
        for (slave, start_values) in self.slaves.iter_mut().zip(&self.start_values) {
            slave.setup_experiment(time, Some(self.stop_time)).map_err(failed)?;
            for (vr, value) in start_values {
                slave.set_value(*vr, value).map_err(failed)?;
            }
        }
        for slave in &mut self.slaves {
            slave.enter_initialization_mode().map_err(failed)?;
        }
        self.algorithm.initialize(&mut self.slaves, time).map_err(failed)?;
        for slave in &mut self.slaves {
            slave.exit_initialization_mode().map_err(failed)?;
        }
        self.initialized = true;
        self.observe()
    }

    /// True when every step of the grid is done or an instance ended the run ([`Execution::termination`]).
    pub fn is_done(&self) -> bool {
        self.completed >= self.grid.steps() || self.termination.is_some()
    }

    /// The instance that ended the run early, if one did.
    pub fn termination(&self) -> Option<&Termination> {
        self.termination.as_ref()
    }

    /// One macro step `t_k → t_{k+1}`, then observation of `t_{k+1}`. A step discarded by an
    /// instance that asks to terminate ends the run at `t_k` instead ([`Execution::termination`]).
    pub fn step(&mut self) -> Result<(), RunError> {
        let (step, steps) = (self.completed, self.grid.steps());
        let time = self.grid.time(step);
        match self.algorithm.step(&mut self.slaves, time, self.grid.step_size(step)) {
            Ok(()) => self.complete_step(),
            Err(source) => match source.discarded_by().map(str::to_string) {
                Some(instance) => match self.end_on_discard(instance, time, step, source)? {
                    StepEnd::Completed => self.complete_step(),
                    StepEnd::Short => Ok(()),
                },
                None => Err(RunError::Step { time, step, steps, source }),
            },
        }
    }

    /// Counts the macro step just taken and observes `t_{k+1}`.
    fn complete_step(&mut self) -> Result<(), RunError> {
        self.completed += 1;
        if let Some(progress) = &self.progress {
            progress.store(self.completed, Ordering::Relaxed);
        }
        self.observe()
    }

    /// FMI 2.0 after `fmi2DoStep` returned `fmi2Discard`: the instance asks to end the simulation
    /// if its `fmi2Terminated` status is true; otherwise the discard is an error. An instance
    /// that ends the run at the end of the full step (`fmi2LastSuccessfulTime` = t_{k+1}) has
    /// completed it, as every other instance has ([`crate::algorithm`]), so that step counts and
    /// its row is kept, as FMPy, fmusim and the FMU Compliance Checker keep it.
    fn end_on_discard(
        &mut self,
        instance: String,
        time: f64,
        step: u64,
        source: SimulatorError,
    ) -> Result<StepEnd, RunError> {
        let slave = self.slaves.iter().find(|slave| slave.name() == instance);
        let why = match slave.map(|slave| slave.terminated()) {
            Some(Ok(true)) => {
                let reached = slave.and_then(|slave| slave.last_successful_time().ok());
                let next = self.grid.time(step + 1);
                let full =
                    reached.is_some_and(|reached| (reached - next).abs() <= FULL_STEP_TOLERANCE * next.abs().max(1.0));
                self.termination = Some(Termination { instance, time: reached });
                return Ok(if full { StepEnd::Completed } else { StepEnd::Short });
            }
            Some(Ok(false)) => "without asking to end the simulation (fmi2Terminated is false)".to_string(),
            Some(Err(error)) => format!("and its fmi2Terminated status is unavailable ({error})"),
            None => "but is not in this execution".to_string(),
        };
        Err(RunError::Discarded { instance, time, step, steps: self.grid.steps(), why, source })
    }

    /// The whole co-simulation state at the communication point reached ([`Snapshot`]), taken
    /// after initialization.
    pub fn save(&mut self) -> Result<Snapshot, RunError> {
        if !self.initialized {
            return Err(RunError::Snapshot("cannot save the state before initialization".into()));
        }
        let time = self.time();
        let states = self
            .slaves
            .iter_mut()
            .map(|slave| {
                slave.save_state().map_err(|source| RunError::State {
                    action: "save",
                    instance: slave.name().to_string(),
                    time,
                    source,
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(Snapshot {
            completed: self.completed,
            termination: self.termination.clone(),
            states,
            wiring: self.algorithm.wiring().clone(),
        })
    }

    /// Puts every instance and the algorithm back to `snapshot` (of this execution or another
    /// one of the same system, after its initialization): the next step continues from there
    /// exactly as the saved execution did. The observers see nothing of it: a recorder keeps
    /// its rows and goes on from the restored step.
    pub fn restore(&mut self, snapshot: &Snapshot) -> Result<(), RunError> {
        if !self.initialized {
            return Err(RunError::Snapshot("cannot restore a state before initialization".into()));
        }
        if snapshot.states.len() != self.slaves.len() || snapshot.completed > self.grid.steps() {
            return Err(RunError::Snapshot(format!(
                "the state is of a system with {} instances at step {}, not of this one ({} instances, {} steps)",
                snapshot.states.len(),
                snapshot.completed,
                self.slaves.len(),
                self.grid.steps()
            )));
        }
        let time = self.grid.time(snapshot.completed);
        for (slave, state) in self.slaves.iter_mut().zip(&snapshot.states) {
            slave.restore_state(state).map_err(|source| RunError::State {
                action: "restore",
                instance: slave.name().to_string(),
                time,
                source,
            })?;
            slave.set_time_hint(time);
        }
        self.algorithm.set_wiring(snapshot.wiring.clone());
        self.completed = snapshot.completed;
        self.termination = snapshot.termination.clone();
        if let Some(progress) = &self.progress {
            progress.store(self.completed, Ordering::Relaxed);
        }
        Ok(())
    }

    /// The simulators, in stepping order, to set values between steps.
    pub fn simulators_mut(&mut self) -> &mut [Box<dyn Simulator>] {
        &mut self.slaves
    }

    /// True once [`Execution::initialize`] succeeded.
    pub fn is_initialized(&self) -> bool {
        self.initialized
    }

    /// The steps completed, kept up to date from now on for a thread that ends the process
    /// while this one is inside an FMU call ([`crate::emergency`]).
    pub fn publish_progress(&mut self) -> Arc<AtomicU64> {
        let progress = Arc::new(AtomicU64::new(self.completed));
        self.progress = Some(Arc::clone(&progress));
        progress
    }

    /// Makes [`Execution::run`] stop with [`RunError::Interrupted`] before the next step once
    /// `interrupt` is requested.
    pub fn interrupt_on(&mut self, interrupt: Interrupt) {
        self.interrupt = Some(interrupt);
    }

    /// Initializes (if not done yet) and steps to the end of the grid.
    pub fn run(&mut self) -> Result<(), RunError> {
        if !self.initialized {
            self.initialize()?;
        }
        while !self.is_done() {
            if let Some(signal) = self.interrupt.as_ref().and_then(Interrupt::requested) {
                return Err(RunError::Interrupted { time: self.time(), signal: signal_name(signal) });
            }
            self.step()?;
        }
        Ok(())
    }

    /// `fmi2Terminate` on every instance.
    pub fn terminate(&mut self) -> Result<(), RunError> {
        for slave in &mut self.slaves {
            slave.terminate().map_err(RunError::Terminate)?;
        }
        Ok(())
    }

    /// Runs to the end and terminates with `recorder` observing besides the other observers, and
    /// returns what it recorded. The observers are flushed whatever the outcome; the run's error
    /// comes first, then a flush's.
    pub fn run_into_table(mut self, recorder: TableRecorder) -> Result<SignalTable, RunError> {
        let table = Rc::new(RefCell::new(recorder));
        self.add_observer(Box::new(Rc::clone(&table)));
        let outcome = self.run().and_then(|()| self.terminate());
        outcome.and(self.finish_observers())?;
        // The execution, the recorder's other owner, goes first.
        drop(self);
        let table = Rc::into_inner(table).expect("the recorder's only other owner was the execution");
        Ok(table.into_inner().into_table())
    }

    /// Flushes every observer (all of them, even if one fails; the first
    /// error is returned).
    pub fn finish_observers(&mut self) -> Result<(), RunError> {
        let time = self.time();
        let mut first = None;
        for observer in &mut self.observers {
            if let Err(source) = observer.finish() {
                first.get_or_insert(RunError::Observer { time, source });
            }
        }
        first.map_or(Ok(()), Err)
    }
}

/// The wiring of a validated system: its input files and connections, and which targets
/// interpolate their connected inputs (`input_derivatives` and `canInterpolateInputs`) and which
/// extrapolate them under Jacobi (`extrapolate_inputs` and `canInterpolateInputs`).
pub fn wiring(system: &System) -> Wiring {
    let mut wiring = Wiring::new(system.instances.len());
    for input in &system.inputs {
        wiring.add_file(input.instance, input.binding.clone());
    }
    for (index, instance) in system.instances.iter().enumerate() {
        let can_interpolate = instance.fmu.model_description().co_simulation.can_interpolate_inputs;
        wiring.set_interpolate(index, system.spec.input_derivatives && can_interpolate);
        wiring.set_extrapolate(index, system.spec.extrapolate_inputs && can_interpolate);
    }
    for connection in &system.connections {
        let (from, to) = (&connection.from, &connection.to);
        let kind = to.variable.variable_type.abi_type();
        let source = (from.instance, from.variable.value_reference, from.variable.name.as_str());
        wiring.connect(source, to.instance, to.variable.value_reference, kind);
    }
    wiring
}
