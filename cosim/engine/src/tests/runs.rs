//! Observation and failures: decimated recording, and a simulator that fails mid-run leaves
//! every row recorded before the failure in the CSV.

use fmu_import::fmu::Causality;

use super::inputs::real_input;
use super::mock::{Failure, Journal, Law, Mock};
use crate::algorithm::{algorithm, AlgorithmKind, Wiring};
use crate::execution::{Execution, RunError};
use crate::observer::CsvRecorder;
use crate::time::TimeGrid;
use crate::variable::VariableRef;

/// Runs a ramp `y = 2·t` on 0, 0.1, …, 1 recording `y` every `every` points into a CSV;
/// returns the run's outcome and the file's lines.
fn record(every: u64, failure: Option<(u64, Failure)>) -> (Result<(), RunError>, Vec<String>) {
    let journal = Journal::default();
    let mut ramp = Mock::new("ramp", Law::Ramp { vr: 1, slope: 2.0 }, &journal);
    if let Some((step, failure)) = failure {
        ramp = ramp.failing_at(step, failure);
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("out.csv");
    let y = VariableRef {
        instance: 0,
        qualified_name: "ramp.y".into(),
        variable: fmu_import::fmu::ScalarVariable { causality: Causality::Output, ..real_input("y", 1) },
    };
    let recorder = CsvRecorder::create(&file, &[y], every).expect("recorder");
    let grid = TimeGrid::new(0.0, 1.0, 0.1).expect("grid");
    let mut execution = Execution::new(grid, 1.0, algorithm(AlgorithmKind::GaussSeidel, Wiring::new(1)));
    execution.add_simulator(Box::new(ramp), Vec::new());
    execution.add_observer(Box::new(recorder));
    let outcome = execution.run();
    execution.finish_observers().expect("flush");
    let text = std::fs::read_to_string(&file).expect("csv");
    (outcome, text.lines().map(str::to_string).collect())
}

#[test]
fn every_nth_point_is_recorded_from_the_first() {
    let (outcome, lines) = record(4, None);
    outcome.expect("run");
    assert_eq!(lines, ["time,ramp.y", "0.0,0.0", "0.4,0.8", "0.8,1.6"]);
}

#[test]
fn every_point_is_recorded_by_default() {
    let (_, lines) = record(1, None);
    assert_eq!(lines.len(), 1 + 11);
    assert_eq!(lines[11], "1.0,2.0");
}

#[test]
fn an_error_at_step_n_keeps_every_row_before_it() {
    let (outcome, lines) = record(1, Some((5, Failure::Error)));
    match outcome {
        Err(RunError::Step { time, step: 5, steps: 10, .. }) => assert_eq!(time, 0.5),
        other => panic!("expected a step error at step 5, got {other:?}"),
    }
    // t = 0 … 0.5: the rows of k = 0..=5, the last one the state the failing step started from.
    assert_eq!(lines.len(), 1 + 6);
    assert_eq!(lines[6], "0.5,1.0");
}

#[test]
fn a_discard_ends_the_run_early_as_a_discard() {
    let (outcome, lines) = record(1, Some((3, Failure::Discard)));
    let error = outcome.expect_err("the step is discarded");
    assert!(error.is_discard(), "{error}");
    assert!(matches!(error, RunError::Discarded { step: 3, .. }));
    assert_eq!(lines.len(), 1 + 4);
}

#[test]
fn the_failure_names_the_simulator_message() {
    let (outcome, _) = record(1, Some((2, Failure::Error)));
    let message = fmu_import::error_chain(&outcome.expect_err("fails"));
    assert!(message.contains("step 2 at t = 0.2") && message.contains("ramp"), "{message}");
}

/// Requests the interrupt when it sees communication point `at`, as a signal would mid-run.
struct InterruptAt {
    at: u64,
    interrupt: crate::interrupt::Interrupt,
}

impl crate::observer::Observer for InterruptAt {
    fn observe(
        &mut self,
        k: u64,
        _: f64,
        _: &[Box<dyn crate::simulator::Simulator>],
    ) -> Result<(), crate::observer::ObserverError> {
        if k == self.at {
            self.interrupt.request(15);
        }
        Ok(())
    }

    fn finish(&mut self) -> Result<(), crate::observer::ObserverError> {
        Ok(())
    }
}

#[test]
fn an_interrupt_stops_the_run_between_steps_naming_the_signal_and_time() {
    let journal = Journal::default();
    let grid = TimeGrid::new(0.0, 1.0, 0.1).expect("grid");
    let mut execution = Execution::new(grid, 1.0, algorithm(AlgorithmKind::GaussSeidel, Wiring::new(1)));
    execution.add_simulator(Box::new(Mock::new("ramp", Law::Ramp { vr: 1, slope: 2.0 }, &journal)), Vec::new());
    let interrupt = crate::interrupt::Interrupt::new();
    execution.interrupt_on(interrupt.clone());
    execution.add_observer(Box::new(InterruptAt { at: 3, interrupt }));
    let error = execution.run().expect_err("interrupted");
    assert!(matches!(error, RunError::Interrupted { .. }), "{error:?}");
    assert_eq!(error.to_string(), "interrupted by SIGTERM at t = 0.30000000000000004 s");
    assert_eq!(execution.completed_steps(), 3, "the step under way when the signal came is completed, no other");
}
