//! Observation and failures: decimated recording, a simulator that fails mid-run leaves every
//! row recorded before the failure in the CSV, and a discarded step ends the run normally only
//! when the simulator asks to terminate.

use fmu_import::fmu::Causality;

use super::inputs::real_input;
use super::mock::{calls_of, Call, Failure, Journal, Law, Mock};
use crate::algorithm::{algorithm, AlgorithmKind, Wiring};
use crate::execution::{Execution, RunError, Termination};
use crate::observer::CsvRecorder;
use crate::time::TimeGrid;
use crate::variable::VariableRef;

/// Runs a ramp `y = 2·t` on 0, 0.1, …, 1 recording `y` every `every` points into a CSV;
/// returns the run's outcome and the file's lines.
fn record(every: u64, failure: Option<(u64, Failure)>) -> (Result<(), RunError>, Vec<String>) {
    let (outcome, lines, _) = record_ending(every, failure, &Journal::default());
    (outcome, lines)
}

/// [`record`], also returning the instance that terminated the run, if one did; `fmi2Terminate`
/// is called after a successful run, as a run does.
fn record_ending(
    every: u64,
    failure: Option<(u64, Failure)>,
    journal: &Journal,
) -> (Result<(), RunError>, Vec<String>, Option<Termination>) {
    let mut ramp = Mock::new("ramp", Law::Ramp { vr: 1, slope: 2.0 }, journal);
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
    let outcome = execution.run().and_then(|()| execution.terminate());
    execution.finish_observers().expect("flush");
    let text = std::fs::read_to_string(&file).expect("csv");
    (outcome, text.lines().map(str::to_string).collect(), execution.termination().cloned())
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
fn a_discard_with_terminated_ends_the_run_normally_at_the_last_communication_point() {
    let journal = Journal::default();
    let (outcome, lines, termination) = record_ending(1, Some((3, Failure::Terminate { reached: 0.5 })), &journal);
    outcome.expect("a termination is a normal end");
    // The FMU got half-way through the step from t_3 = 3 · 0.1.
    assert_eq!(termination, Some(Termination { instance: "ramp".into(), time: Some(3.0 * 0.1 + 0.5 * 0.1) }));
    // Rows of t = 0 … 0.3, the last completed communication point.
    assert_eq!(lines.len(), 1 + 4);
    assert_eq!(lines[4], "0.30000000000000004,0.6000000000000001");
    let calls = calls_of(&journal, "ramp");
    let after_step = &calls[calls.len() - 3..];
    assert_eq!(after_step, [Call::Terminated, Call::LastSuccessfulTime, Call::Terminate]);
}

#[test]
fn a_termination_at_the_end_of_a_full_step_keeps_that_row() {
    let journal = Journal::default();
    let (outcome, lines, termination) = record_ending(1, Some((3, Failure::Terminate { reached: 1.0 })), &journal);
    outcome.expect("a termination is a normal end");
    assert_eq!(termination, Some(Termination { instance: "ramp".into(), time: Some(3.0 * 0.1 + 0.1) }));
    // Rows of t = 0 … 0.4: the FMU computed the step from t_3 to its end, as FMPy records it.
    assert_eq!(lines.len(), 1 + 5);
    assert_eq!(lines[5], "0.4,0.8");
}

#[test]
fn a_discard_without_terminated_is_an_error_naming_the_instance() {
    let journal = Journal::default();
    let (outcome, lines, termination) = record_ending(1, Some((3, Failure::Discard)), &journal);
    let error = outcome.expect_err("the FMU does not ask to terminate");
    assert!(matches!(&error, RunError::Discarded { step: 3, steps: 10, .. }), "{error:?}");
    assert_eq!(
        error.to_string(),
        "instance \"ramp\" discarded the step from t = 0.3 s (step 3 of 10) without asking to end \
         the simulation (fmi2Terminated is false)"
    );
    assert_eq!(termination, None);
    assert_eq!(lines.len(), 1 + 4);
    assert!(calls_of(&journal, "ramp").contains(&Call::Terminated));
}

#[test]
fn a_discard_whose_terminated_status_is_unavailable_is_an_error() {
    let (outcome, _, termination) = record_ending(1, Some((3, Failure::DiscardWithoutStatus)), &Journal::default());
    let message = fmu_import::error_chain(&outcome.expect_err("no status"));
    assert!(message.contains("instance \"ramp\" discarded the step"), "{message}");
    assert!(
        message.contains("its fmi2Terminated status is unavailable (fmi2Terminated is not available)"),
        "{message}"
    );
    assert!(message.contains("ramp: step 3 at t = 0.30000000000000004 fails"), "{message}");
    assert_eq!(termination, None);
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
    assert_eq!(error.to_string(), "interrupted by SIGTERM at t = 0.3 s");
    assert_eq!(execution.completed_steps(), 3, "the step under way when the signal came is completed, no other");
}
