//! A wrapped simulator passes every call through and lets its wrapper act before each step and
//! around the step and the get/set calls (the timing and the live operator are wrappers).

use std::sync::atomic::{AtomicUsize, Ordering};

use super::mock::{Call, Journal, Law, Mock};
use crate::algorithm::{algorithm, AlgorithmKind, Wiring};
use crate::execution::Execution;
use crate::simulator::{timed, Simulator, SimulatorError, Wrapped, Wrapper};
use crate::time::TimeGrid;

/// Sets input 1 to `value` before every step, counts the steps and get/set calls it sees, and
/// can refuse to step.
#[derive(Default)]
struct Writer {
    value: f64,
    refuse: bool,
    steps: AtomicUsize,
    get_set: AtomicUsize,
}

impl Wrapper for Writer {
    fn before_step(&mut self, inner: &mut dyn Simulator) -> Result<(), SimulatorError> {
        if self.refuse {
            return Err(SimulatorError::failed("the wrapper refuses"));
        }
        inner.set_real(&[1], &[self.value])
    }

    fn around_step(&self, call: &mut dyn FnMut() -> Result<(), SimulatorError>) -> Result<(), SimulatorError> {
        self.steps.fetch_add(1, Ordering::Relaxed);
        call()
    }

    fn around_get_set(&self, call: &mut dyn FnMut() -> Result<(), SimulatorError>) -> Result<(), SimulatorError> {
        self.get_set.fetch_add(1, Ordering::Relaxed);
        call()
    }
}

fn echo(journal: &Journal) -> Box<dyn Simulator> {
    Box::new(Mock::new("echo", Law::Echo { input: 1, output: 2 }, journal))
}

#[test]
fn the_wrapper_writes_before_each_step_and_sees_every_get_set() {
    let journal = Journal::default();
    let mut wrapped = Wrapped::new(echo(&journal), Writer { value: 7.5, ..Writer::default() });
    wrapped.setup_experiment(0.0, Some(1.0)).unwrap();
    wrapped.enter_initialization_mode().unwrap();
    wrapped.set_real(&[1], &[3.0]).unwrap();
    wrapped.exit_initialization_mode().unwrap();
    wrapped.do_step(0.0, 0.5).unwrap();
    let mut output = [0.0];
    wrapped.get_real(&[2], &mut output).unwrap();
    wrapped.terminate().unwrap();

    // The step saw the wrapper's value, not the one set before it.
    assert_eq!(output, [7.5]);
    assert_eq!(wrapped.name(), "echo");
    let calls: Vec<Call> = journal.lock().unwrap().iter().map(|(_, call)| call.clone()).collect();
    assert_eq!(
        calls,
        [
            Call::Setup { start: 0.0, stop: Some(1.0) },
            Call::EnterInitialization,
            Call::SetReal { vrs: vec![1], values: vec![3.0] },
            Call::ExitInitialization,
            Call::SetReal { vrs: vec![1], values: vec![7.5] },
            Call::DoStep { current: 0.0, step: 0.5 },
            Call::GetReal { vrs: vec![2] },
            Call::Terminate,
        ]
    );
    // The wrapper's own set goes to the inner simulator directly; the host's two calls pass it.
    assert_eq!(wrapped.wrapper().steps.load(Ordering::Relaxed), 1);
    assert_eq!(wrapped.wrapper().get_set.load(Ordering::Relaxed), 2);
    // Errors of the inner simulator come back unchanged.
    let error = wrapped.get_string(&[1]).unwrap_err();
    assert!(error.to_string().contains("only Reals"), "{error}");
    assert_eq!(wrapped.wrapper().get_set.load(Ordering::Relaxed), 3);
}

#[test]
fn a_failing_wrapper_stops_the_step_before_the_inner_simulator_is_called() {
    let journal = Journal::default();
    let mut wrapped = Wrapped::new(echo(&journal), Writer { refuse: true, ..Writer::default() });
    let error = wrapped.do_step(0.0, 0.5).unwrap_err();
    assert!(error.to_string().contains("the wrapper refuses"), "{error}");
    assert!(journal.lock().unwrap().is_empty());
    assert_eq!(wrapped.wrapper().steps.load(Ordering::Relaxed), 0);
}

#[test]
fn timing_adds_up_the_inner_calls_only() {
    let journal = Journal::default();
    let (mut wrapped, times) = timed(echo(&journal));
    assert_eq!((times.do_step(), times.get_set()), (Default::default(), Default::default()));
    wrapped.set_real(&[1], &[2.0]).unwrap();
    let after_set = times.get_set();
    assert!(after_set > Default::default() && times.do_step() == Default::default());
    wrapped.do_step(0.0, 0.5).unwrap();
    assert!(times.do_step() > Default::default() && times.get_set() == after_set);
    let mut output = [0.0];
    wrapped.get_real(&[2], &mut output).unwrap();
    assert_eq!(output, [2.0]);
    assert!(times.get_set() > after_set);
}

#[test]
fn an_execution_wraps_the_simulator_it_is_told_and_keeps_the_order() {
    let journal = Journal::default();
    let grid = TimeGrid::new(0.0, 0.2, 0.1).unwrap();
    let mut execution = Execution::new(grid, 0.2, algorithm(AlgorithmKind::GaussSeidel, Wiring::new(2)));
    execution.add_simulator(Box::new(Mock::new("first", Law::Echo { input: 1, output: 2 }, &journal)), Vec::new());
    execution.add_simulator(Box::new(Mock::new("second", Law::Echo { input: 1, output: 2 }, &journal)), Vec::new());
    execution.wrap(1, Writer { value: 4.0, ..Writer::default() });
    execution.initialize().unwrap();
    execution.step().unwrap();
    let names: Vec<&str> = execution.simulators().iter().map(|s| s.name()).collect();
    assert_eq!(names, ["first", "second"]);
    let output = |index: usize| {
        let mut value = [0.0];
        execution.simulators()[index].get_real(&[2], &mut value).unwrap();
        value[0]
    };
    // Only the wrapped one had its input written before the step.
    assert_eq!((output(0), output(1)), (0.0, 4.0));
}
