//! Batched wiring: one get call per source and type and one set call per type still deliver
//! exactly the values, value references and slopes of reading every connection on its own.
//!
//! Sources `a` and `b` step before the target, `c` after it; their outputs are ramps
//! `y = vr · t` ([`Law::Ramps`]). The connections of the three are listed interleaved (values
//! scattered among the target's inputs) and grouped by source (values read straight into
//! place). The expected calls come from [`per_connection`], the rules applied one connection at
//! a time as the importer did before batching.

use fmu_import::value::VariableType;

use super::mock::{calls_of, gets_of, Call, Journal, Law, Mock};
use crate::algorithm::{algorithm, AlgorithmKind, Wiring};
use crate::execution::Execution;
use crate::simulator::Simulator;
use crate::time::TimeGrid;

/// Stepping order.
const NAMES: [&str; 4] = ["a", "b", "target", "c"];
const TARGET: usize = 2;
const OUTPUTS: [&[u32]; 4] = [&[1, 3], &[2, 4], &[], &[5, 6]];
/// (source instance, source vr, target vr), interleaved across sources: every source's values
/// are scattered among the target's inputs.
const INTERLEAVED: [(usize, u32, u32); 6] = [(0, 1, 10), (3, 5, 11), (1, 2, 12), (0, 3, 13), (3, 6, 14), (1, 4, 15)];
/// The same outputs listed source by source: each source's values are read straight into place.
const GROUPED: [(usize, u32, u32); 6] = [(0, 1, 10), (0, 3, 11), (1, 2, 12), (1, 4, 13), (3, 5, 14), (3, 6, 15)];
const STEP: f64 = 0.25;
const STEPS: u32 = 4;

fn run(connections: &[(usize, u32, u32)], kind: AlgorithmKind, interpolate: bool) -> Journal {
    let journal = Journal::default();
    let mut wiring = Wiring::new(NAMES.len());
    for &(from, from_vr, to_vr) in connections {
        wiring.connect((from, from_vr, "y"), TARGET, to_vr, VariableType::Real);
    }
    wiring.set_interpolate(TARGET, interpolate);
    let stop = STEP * f64::from(STEPS);
    let grid = TimeGrid::new(0.0, stop, STEP).expect("grid");
    let mut execution = Execution::new(grid, stop, algorithm(kind, wiring));
    for (name, outputs) in NAMES.into_iter().zip(OUTPUTS) {
        execution.add_simulator(Box::new(Mock::new(name, Law::Ramps(outputs), &journal)) as Box<dyn Simulator>, vec![]);
    }
    execution.run().expect("the mocks never fail");
    journal
}

/// The target's set calls of step `k` (`t_k = k · STEP`) computed one connection at a time:
/// (inputs set, slopes set). A source before the target in Gauss–Seidel has stepped to
/// `t_{k+1}`; interpolated, its input is its value at `t_k` with the slope to `t_{k+1}`.
fn per_connection(
    connections: &[(usize, u32, u32)],
    kind: AlgorithmKind,
    interpolate: bool,
    k: u32,
) -> (Call, Option<Call>) {
    let (now, next) = (f64::from(k) * STEP, f64::from(k + 1) * STEP);
    let (mut values, mut slopes, mut slope_vrs) = (Vec::new(), Vec::new(), Vec::new());
    for &(from, from_vr, to_vr) in connections {
        let stepped = kind == AlgorithmKind::GaussSeidel && from < TARGET;
        let at = |t: f64| f64::from(from_vr) * t;
        if stepped && interpolate {
            values.push(at(now));
            slope_vrs.push(to_vr);
            slopes.push((at(next) - at(now)) / STEP);
        } else {
            values.push(if stepped { at(next) } else { at(now) });
        }
    }
    let vrs = connections.iter().map(|c| c.2).collect();
    let derivatives = (!slopes.is_empty()).then_some(Call::Derivatives { vrs: slope_vrs, values: slopes });
    (Call::SetReal { vrs, values }, derivatives)
}

/// The target's value and derivative calls of every step (after initialization).
fn step_calls(journal: &Journal) -> Vec<Call> {
    let calls = calls_of(journal, "target");
    let start = calls.iter().position(|c| *c == Call::ExitInitialization).expect("initialized");
    calls[start..].iter().filter(|c| matches!(c, Call::SetReal { .. } | Call::Derivatives { .. })).cloned().collect()
}

fn check(kind: AlgorithmKind, interpolate: bool) {
    for connections in [INTERLEAVED, GROUPED] {
        check_with(&connections, kind, interpolate);
    }
}

fn check_with(connections: &[(usize, u32, u32)], kind: AlgorithmKind, interpolate: bool) {
    let journal = run(connections, kind, interpolate);
    let expected: Vec<Call> = (0..STEPS)
        .flat_map(|k| {
            let (set, derivatives) = per_connection(connections, kind, interpolate, k);
            std::iter::once(set).chain(derivatives)
        })
        .collect();
    assert_eq!(step_calls(&journal), expected, "{kind:?}, interpolate {interpolate}, {connections:?}");

    // One get call per source and step (plus those while initializing), each for all of the
    // source's connected outputs in connection order.
    let initializing = if kind == AlgorithmKind::GaussSeidel && interpolate { 2 } else { 1 };
    for (source, outputs) in [(0, [1, 3]), (1, [2, 4]), (3, [5, 6])] {
        let gets = gets_of(&journal, NAMES[source]);
        assert_eq!(gets, vec![outputs.to_vec(); initializing + STEPS as usize], "{}", NAMES[source]);
    }
}

#[test]
fn gauss_seidel_with_interpolation_gets_the_per_connection_values_and_slopes() {
    check(AlgorithmKind::GaussSeidel, true);
}

#[test]
fn gauss_seidel_without_interpolation_gets_the_per_connection_values() {
    check(AlgorithmKind::GaussSeidel, false);
}

#[test]
fn jacobi_gets_the_per_connection_values() {
    check(AlgorithmKind::Jacobi, true);
}

#[test]
fn initial_inputs_are_set_once_in_connection_order() {
    let journal = run(&INTERLEAVED, AlgorithmKind::GaussSeidel, true);
    let calls = calls_of(&journal, "target");
    let enter = calls.iter().position(|c| *c == Call::EnterInitialization).expect("enter");
    let exit = calls.iter().position(|c| *c == Call::ExitInitialization).expect("exit");
    let vrs = INTERLEAVED.iter().map(|c| c.2).collect();
    assert_eq!(calls[enter + 1..exit], [Call::SetReal { vrs, values: vec![0.0; 6] }]);
}
