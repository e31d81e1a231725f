//! Input files fed through the wiring: linear interpolation at communication points and the
//! secant slope over each step, also across a kink of the signal.

use std::path::Path;
use std::sync::Arc;

use fmu_import::fmu::{Causality, ScalarVariable, Variability};
use fmu_import::value::VariableType;

use super::mock::{inputs_set, slopes_set, Journal, Law, Mock};
use crate::algorithm::{algorithm, AlgorithmKind, Wiring};
use crate::execution::Execution;
use crate::input::InputBinding;
use crate::table::SignalTable;
use crate::time::TimeGrid;

/// A continuous Real input with value reference `vr`.
pub fn real_input(name: &str, vr: u32) -> ScalarVariable {
    ScalarVariable {
        name: name.into(),
        value_reference: vr,
        description: None,
        causality: Causality::Input,
        variability: Variability::Continuous,
        initial: None,
        variable_type: VariableType::Real,
        start: Some(fmu_import::value::Value::Real(0.0)),
        unit: None,
        declared_type: None,
        range: (None, None),
    }
}

/// `u` rises from 0 to 5 until t = 0.5, then stays at 5; sampled off the 0.25 s grid.
const SIGNAL: &str = "time,u\n0,0\n0.5,5\n2,5\n";

fn run_with_file(derivatives: bool) -> Journal {
    let journal = Journal::default();
    let table = Arc::new(SignalTable::parse(SIGNAL, Path::new("u.csv")).expect("table"));
    let u = real_input("u", 10);
    let binding = InputBinding::new(table, vec![(0, 0, &u)], derivatives);
    let mut wiring = Wiring::new(1);
    wiring.add_file(0, binding);
    let grid = TimeGrid::new(0.0, 1.0, 0.25).expect("grid");
    let mut execution = Execution::new(grid, 1.0, algorithm(AlgorithmKind::GaussSeidel, wiring));
    execution.add_simulator(Box::new(Mock::new("target", Law::Echo { input: 10, output: 11 }, &journal)), vec![]);
    execution.run().expect("run");
    journal
}

#[test]
fn file_inputs_are_interpolated_at_each_communication_point() {
    let journal = run_with_file(false);
    assert_eq!(inputs_set(&journal, "target", 10), [0.0, 0.0, 2.5, 5.0, 5.0]);
    assert!(slopes_set(&journal, "target", 10).is_empty());
}

#[test]
fn file_input_slopes_are_secants_over_the_coming_step() {
    let journal = run_with_file(true);
    // 10/s on the rise, 0 after the kink at t = 0.5 (which lies on the grid here).
    assert_eq!(slopes_set(&journal, "target", 10), [10.0, 10.0, 0.0, 0.0]);
}

#[test]
fn a_step_across_a_kink_gets_the_secant_not_either_segment_slope() {
    let table = Arc::new(SignalTable::parse(SIGNAL, Path::new("u.csv")).expect("table"));
    let u = real_input("u", 10);
    let binding = InputBinding::new(table, vec![(0, 0, &u)], true);
    let journal = Journal::default();
    let mut mock = Mock::new("target", Law::Echo { input: 10, output: 11 }, &journal);
    // [0.375, 0.625]: 3.75 → 5, i.e. 5/s, where the segments have 10/s and 0/s.
    binding.apply(&mut mock, 0.375, Some(0.625)).expect("apply");
    assert_eq!(inputs_set(&journal, "target", 10), [3.75]);
    assert_eq!(slopes_set(&journal, "target", 10), [5.0]);
}
