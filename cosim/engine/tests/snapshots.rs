//! Saving and restoring a whole co-simulation ([`Execution::save`], [`Execution::restore`]):
//! the closed loop under ship profile 1 with compensation and sensor noise (every instance's
//! state matters: the wave phases, the noise counters, the estimators, the PIDs, the pendulum)
//! continues from a restored snapshot bit for bit as the run that never stopped, in the same
//! execution after running on past the snapshot and in a second execution of the same system.
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use cosim_engine::execution::{Execution, RunError};
use cosim_engine::observer::{Observer, TableRecorder};
use cosim_engine::system::{AlgorithmKind, Overrides, System, SystemFiles};
use cosim_engine::table::SignalTable;
use fmu_import::fmi::LogEcho;
use fmu_import::slave::InstantiateOptions;

const OPTIONS: InstantiateOptions = InstantiateOptions { visible: false, logging_on: false, echo: LogEcho::Warnings };

fn system(algorithm: AlgorithmKind) -> System {
    let file = common::workspace_root().join("scenarios/demo_profile1_compensated.json");
    let overrides = Overrides { stop_time: Some(12.5), algorithm: Some(algorithm), ..Overrides::default() };
    System::load(&file, &overrides, &SystemFiles::default())
        .unwrap_or_else(|e| panic!("{}: {e} (run `cargo xtask package` first)", file.display()))
}

/// An initialized execution of `system` and a recorder of its recorded variables, every step.
fn start(system: &System) -> (Execution, TableRecorder) {
    let mut execution = Execution::from_system(system, OPTIONS).expect("instantiates");
    execution.initialize().expect("initializes");
    let mut recorder = TableRecorder::new(&system.file, &system.record.variables, 1).expect("numbers");
    recorder.observe(0, execution.time(), execution.simulators()).expect("records");
    (execution, recorder)
}

/// Steps until `steps` steps are completed, recording each.
fn step_to(execution: &mut Execution, recorder: &mut TableRecorder, steps: u64) {
    while execution.completed_steps() < steps {
        execution.step().expect("steps");
        let (k, time) = (execution.completed_steps(), execution.time());
        recorder.observe(k, time, execution.simulators()).expect("records");
    }
}

/// The rows of `table` from index `from` on, as (time bits, value bits).
fn rows_from(table: &SignalTable, from: usize) -> Vec<Vec<u64>> {
    (from..table.times.len())
        .map(|i| std::iter::once(table.times[i]).chain(table.columns.iter().map(|c| c[i])).map(f64::to_bits).collect())
        .collect()
}

fn continues_bit_for_bit(algorithm: AlgorithmKind) {
    let system = system(algorithm);
    let (saved_at, end) = (1_150, system.grid.steps());
    let (mut straight, mut reference) = start(&system);
    step_to(&mut straight, &mut reference, end);

    let (mut execution, mut recorder) = start(&system);
    step_to(&mut execution, &mut recorder, saved_at);
    let snapshot = execution.save().expect("saves");
    assert_eq!(snapshot.completed_steps(), saved_at);
    // Run on past the snapshot, so that every instance and the wiring hold later values.
    step_to(&mut execution, &mut recorder, end);
    execution.restore(&snapshot).expect("restores");
    assert_eq!(execution.completed_steps(), saved_at);
    recorder.rewind(saved_at);
    assert_eq!(recorder.table().times.len(), saved_at as usize + 1);
    step_to(&mut execution, &mut recorder, end);
    assert_eq!(rows_from(recorder.table(), 0), rows_from(reference.table(), 0));

    // A second execution of the same system, restored to the snapshot right after its
    // initialization, continues the same way.
    let (mut other, mut other_rows) = start(&system);
    other.restore(&snapshot).expect("restores into another execution");
    other_rows.rewind(0);
    step_to(&mut other, &mut other_rows, end);
    let from = saved_at as usize + 1;
    assert_eq!(rows_from(other_rows.table(), 1), rows_from(reference.table(), from));
}

#[test]
fn a_restored_closed_loop_continues_bit_for_bit_under_gauss_seidel() {
    continues_bit_for_bit(AlgorithmKind::GaussSeidel);
}

#[test]
fn a_restored_closed_loop_continues_bit_for_bit_under_jacobi() {
    // (Gauss–Seidel interpolates the pendulum's and the crane's inputs across each step from
    // the values the wiring kept of the step before: without them restored, that test fails.)
    continues_bit_for_bit(AlgorithmKind::Jacobi);
}

#[test]
fn a_snapshot_needs_an_initialized_execution_of_the_same_system() {
    let system = system(AlgorithmKind::GaussSeidel);
    let mut fresh = Execution::from_system(&system, OPTIONS).expect("instantiates");
    assert!(matches!(fresh.save(), Err(RunError::Snapshot(_))));
    let (mut execution, _) = start(&system);
    let snapshot = execution.save().expect("saves");
    assert!(matches!(fresh.restore(&snapshot), Err(RunError::Snapshot(_))));

    let lone = common::pendulum_fmu();
    let single = cosim_engine::system::single::SingleFmu::default();
    let pendulum = System::load_fmu(&lone, &single, &Overrides::default(), &SystemFiles::default()).expect("loads");
    let (mut other, _) = start(&pendulum);
    let error = other.restore(&snapshot).expect_err("six instances into one").to_string();
    assert!(error.contains("6 instances") && error.contains("1 instances"), "{error}");
}
