//! Gauss–Seidel and Jacobi: who steps when, and which values and slopes each input receives.
//!
//! A source steps a ramp `y = 2·t` (output 1); a target echoes its input 10. On the grid
//! 0, 0.25, …, 1 the ramp's samples tell exactly which communication point a value came from.

use fmu_import::value::VariableType;

use super::mock::{calls_of, inputs_set, slopes_set, Call, Failure, Journal, Law, Mock};
use crate::algorithm::{algorithm, AlgorithmKind, Wiring};
use crate::execution::Execution;
use crate::simulator::Simulator;
use crate::time::TimeGrid;

const RAMP: Law = Law::Ramp { vr: 1, slope: 2.0 };
const ECHO: Law = Law::Echo { input: 10, output: 11 };

/// Runs source and target to t = 1 in the given order (`source_first`), returns the journal.
fn run(kind: AlgorithmKind, interpolate: bool, source_first: bool) -> Journal {
    run_with(kind, interpolate, false, source_first)
}

/// [`run`], the target also extrapolating its inputs under Jacobi (`extrapolate`).
fn run_with(kind: AlgorithmKind, interpolate: bool, extrapolate: bool, source_first: bool) -> Journal {
    let journal = Journal::default();
    let source = Box::new(Mock::new("source", RAMP, &journal)) as Box<dyn Simulator>;
    let target = Box::new(Mock::new("target", ECHO, &journal)) as Box<dyn Simulator>;
    let (order, (s, t)) = if source_first { ([source, target], (0, 1)) } else { ([target, source], (1, 0)) };
    let mut wiring = Wiring::new(2);
    wiring.connect((s, 1, "y"), t, 10, VariableType::Real);
    wiring.set_interpolate(t, interpolate);
    wiring.set_extrapolate(t, extrapolate);
    let grid = TimeGrid::new(0.0, 1.0, 0.25).expect("grid");
    let mut execution = Execution::new(grid, 1.0, algorithm(kind, wiring));
    for simulator in order {
        execution.add_simulator(simulator, Vec::new());
    }
    execution.run().expect("the mocks never fail");
    execution.terminate().expect("terminate");
    journal
}

#[test]
fn gauss_seidel_feeds_outputs_of_earlier_instances_at_the_end_of_the_step() {
    let journal = run(AlgorithmKind::GaussSeidel, false, true);
    assert_eq!(inputs_set(&journal, "target", 10), [0.0, 0.5, 1.0, 1.5, 2.0]);
    assert!(slopes_set(&journal, "target", 10).is_empty());
}

#[test]
fn jacobi_feeds_every_output_from_the_start_of_the_step() {
    let journal = run(AlgorithmKind::Jacobi, false, true);
    assert_eq!(inputs_set(&journal, "target", 10), [0.0, 0.0, 0.5, 1.0, 1.5]);
}

#[test]
fn gauss_seidel_holds_inputs_from_later_instances() {
    let journal = run(AlgorithmKind::GaussSeidel, true, false);
    assert_eq!(inputs_set(&journal, "target", 10), [0.0, 0.0, 0.5, 1.0, 1.5]);
    assert!(slopes_set(&journal, "target", 10).is_empty(), "a held input has no slope to pass");
}

#[test]
fn interpolated_inputs_start_at_the_old_value_with_the_slope_to_the_new_one() {
    let journal = run(AlgorithmKind::GaussSeidel, true, true);
    // Value at t_k, slope (y(t_{k+1}) − y(t_k)) / h = 2: the ramp itself, not a jump.
    assert_eq!(inputs_set(&journal, "target", 10), [0.0, 0.0, 0.5, 1.0, 1.5]);
    assert_eq!(slopes_set(&journal, "target", 10), [2.0; 4]);
}

#[test]
fn jacobi_passes_no_slopes_unless_it_extrapolates() {
    let journal = run(AlgorithmKind::Jacobi, true, true);
    assert!(slopes_set(&journal, "target", 10).is_empty(), "input derivatives alone are Gauss-Seidel's");
}

#[test]
fn gauss_seidel_ignores_extrapolation() {
    for source_first in [true, false] {
        let plain = run(AlgorithmKind::GaussSeidel, true, source_first);
        let extrapolating = run_with(AlgorithmKind::GaussSeidel, true, true, source_first);
        assert_eq!(inputs_set(&extrapolating, "target", 10), inputs_set(&plain, "target", 10));
        assert_eq!(slopes_set(&extrapolating, "target", 10), slopes_set(&plain, "target", 10));
    }
}

#[test]
fn jacobi_extrapolates_from_the_last_two_communication_points() {
    for source_first in [true, false] {
        let journal = run_with(AlgorithmKind::Jacobi, false, true, source_first);
        // Value at t_k, slope (y(t_k) − y(t_{k−1})) / h = 2 from the second step on: at the
        // first there is no earlier point and the input is held.
        assert_eq!(inputs_set(&journal, "target", 10), [0.0, 0.0, 0.5, 1.0, 1.5]);
        assert_eq!(slopes_set(&journal, "target", 10), [2.0; 3], "source first: {source_first}");
    }
}

#[test]
fn instances_step_in_order_on_the_grid() {
    for kind in [AlgorithmKind::GaussSeidel, AlgorithmKind::Jacobi] {
        let journal = run(kind, false, true);
        let steps: Vec<(&str, f64)> = journal
            .lock()
            .expect("journal")
            .iter()
            .filter_map(|(who, call)| match call {
                Call::DoStep { current, step } => {
                    assert_eq!(*step, 0.25);
                    Some((*who, *current))
                }
                _ => None,
            })
            .collect();
        let expected: Vec<(&str, f64)> =
            [0.0, 0.25, 0.5, 0.75].iter().flat_map(|&t| [("source", t), ("target", t)]).collect();
        assert_eq!(steps, expected, "{kind:?}");
    }
}

#[test]
fn an_instance_ending_the_run_at_a_step_end_lets_the_others_take_that_step() {
    for kind in [AlgorithmKind::GaussSeidel, AlgorithmKind::Jacobi] {
        let journal = Journal::default();
        let source = Mock::new("source", RAMP, &journal).failing_at(1, Failure::Terminate { reached: 1.0 });
        let target = Mock::new("target", ECHO, &journal);
        let mut wiring = Wiring::new(2);
        wiring.connect((0, 1, "y"), 1, 10, VariableType::Real);
        let grid = TimeGrid::new(0.0, 1.0, 0.25).expect("grid");
        let mut execution = Execution::new(grid, 1.0, algorithm(kind, wiring));
        execution.add_simulator(Box::new(source), Vec::new());
        execution.add_simulator(Box::new(target), Vec::new());
        execution.run().expect("a termination is a normal end");
        // Both took the step 0.25 → 0.5 that the source ended the run with, and no other.
        assert_eq!(execution.time(), 0.5, "{kind:?}");
        for who in ["source", "target"] {
            let steps: Vec<f64> = calls_of(&journal, who)
                .iter()
                .filter_map(|call| match call {
                    Call::DoStep { current, .. } => Some(*current),
                    _ => None,
                })
                .collect();
            assert_eq!(steps, [0.0, 0.25], "{kind:?} {who}");
        }
    }
}

#[test]
fn the_fmi_call_sequence_is_kept() {
    let journal = run(AlgorithmKind::GaussSeidel, false, true);
    let target = calls_of(&journal, "target");
    assert_eq!(target[0], Call::Setup { start: 0.0, stop: Some(1.0) });
    assert_eq!(target[1], Call::EnterInitialization);
    assert!(matches!(target[2], Call::SetReal { .. }), "inputs at t0 are set in initialization mode");
    assert_eq!(target[3], Call::ExitInitialization);
    assert_eq!(target.last(), Some(&Call::Terminate));
    // Every instance enters initialization mode before any input is set.
    let all = journal.lock().expect("journal").clone();
    let last_enter = all.iter().rposition(|(_, c)| *c == Call::EnterInitialization).expect("enter");
    let first_set = all.iter().position(|(_, c)| matches!(c, Call::SetReal { .. })).expect("set");
    assert!(last_enter < first_set);
}

#[test]
fn a_non_finite_connected_output_is_blamed_on_the_instance_that_returned_it() {
    for kind in [AlgorithmKind::GaussSeidel, AlgorithmKind::Jacobi] {
        let journal = Journal::default();
        let mut wiring = Wiring::new(2);
        wiring.connect((0, 1, "y"), 1, 10, VariableType::Real);
        let grid = TimeGrid::new(0.0, 1.0, 0.25).expect("grid");
        let mut execution = Execution::new(grid, 1.0, algorithm(kind, wiring));
        execution.add_simulator(Box::new(Mock::new("source", Law::Ramp { vr: 1, slope: f64::NAN }, &journal)), vec![]);
        execution.add_simulator(Box::new(Mock::new("target", ECHO, &journal)), vec![]);
        let error = execution.run().expect_err("NaN must not reach the target");
        let message = fmu_import::error_chain(&error);
        assert!(message.contains(r#"instance "source": output y = NaN is not finite"#), "{kind:?}: {message}");
        assert!(!message.contains("target"), "{kind:?}: the consumer is not to blame: {message}");
        assert!(inputs_set(&journal, "target", 10).iter().all(|v| v.is_finite()), "{kind:?}");
    }
}
