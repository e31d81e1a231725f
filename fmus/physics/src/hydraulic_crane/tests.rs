//! Whole-crane verification against independent references: static equilibrium (the arm's
//! inverse dynamics and H7/H8 at rest), conservation of energy with closed, loss-free drives (the
//! arm's Lagrangian energy plus H11), the power balance H12 extended by the arm and the load, the
//! port reliefs at a cylinder's end stop, and a sanity run on a rolling, heaving deck.

mod deck;
mod energy;
mod holding;
mod power;
mod relief;

use super::plant::{CraneParams, Loads, PlantState, Spools, DEFAULT_JOINTS};
use crate::math::{Vec3, STANDARD_GRAVITY};
use crate::motion::ShipMotion;

/// The communication step of the runs (s): the FMU's usual 10 ms.
const STEP: f64 = 0.01;

/// A load of `tonnes` hanging straight below the tip on a still deck: F₀ = (0, 0, m g) in W
/// (z down), m the load's mass.
fn hanging(tonnes: f64) -> Loads {
    let mass = tonnes * 1000.0;
    Loads { ship: ShipMotion::default(), cable: Vec3::new(0.0, 0.0, mass * STANDARD_GRAVITY), load_mass: mass }
}

/// The crane at rest at [`DEFAULT_JOINTS`] under `loads`, or the test fails with the reason.
fn at_rest(params: &CraneParams, loads: &Loads) -> PlantState {
    match params.initial_state(DEFAULT_JOINTS, loads) {
        Ok(state) => state,
        Err(e) => panic!("no initial state: {e}"),
    }
}

/// Advances `state` over `duration` (s) in steps of [`STEP`], the spools and loads of each step
/// given by its start time; calls `observe(t, state)` after every step.
fn run(
    params: &CraneParams,
    mut state: PlantState,
    duration: f64,
    spools: impl Fn(f64) -> Spools,
    loads: impl Fn(f64) -> Loads,
    mut observe: impl FnMut(f64, &PlantState),
) -> PlantState {
    let steps = (duration / STEP).round() as usize;
    for k in 0..steps {
        let t = k as f64 * STEP;
        state = params.advance(&state, &spools(t), &loads(t), STEP);
        observe(t + STEP, &state);
    }
    state
}

/// The tip's position in W.
fn tip(params: &CraneParams, state: &PlantState, ship: &ShipMotion) -> Vec3 {
    params.arm.tip_in_world(ship, &state.q, &state.qd, &[0.0; 3]).pos
}
