//! The cost of one 10 ms communication step of the full-scale crane
//! (physics::hydraulic_crane::plant::CraneParams::advance: 10 RK4 substeps, 40 right-hand sides).
//!
//! ```text
//! cargo run --release -p physics --example crane_step_cost -- 20000
//! valgrind --tool=callgrind target/release/examples/crane_step_cost 1000
//! ```
//!
//! The crane holds 10 t at the default joints with the boom spool at 0.5 (every drive's rates
//! and the load coupling are exercised). Prints the wall time per step and a checksum of the
//! final state (the same number before and after a change that keeps the results).

use physics::hydraulic_crane::plant::{CraneParams, Loads, Spools, DEFAULT_JOINTS};
use physics::math::{Vec3, STANDARD_GRAVITY};
use std::time::Instant;

fn main() -> Result<(), String> {
    let steps: usize = match std::env::args().nth(1) {
        Some(arg) => arg.parse().map_err(|e| format!("step count {arg:?}: {e}"))?,
        None => 20_000,
    };
    let params = CraneParams::DEFAULT;
    let mass = 10_000.0;
    let loads = Loads { cable: Vec3::new(0.0, 0.0, mass * STANDARD_GRAVITY), load_mass: mass, ..Loads::default() };
    let mut state = params.initial_state(DEFAULT_JOINTS, &loads)?;
    let spools = Spools([0.2, 0.5, -0.3, 0.0]);
    let start = Instant::now();
    for _ in 0..steps {
        state = params.advance(&state, &spools, &loads, 0.01);
    }
    let elapsed = start.elapsed();
    let checksum: f64 = state.q.iter().chain(&state.qd).sum::<f64>() + state.drum;
    println!(
        "{steps} steps of 10 ms: {:.0} ns per step; q {:?}, checksum {checksum:.17e}",
        elapsed.as_nanos() as f64 / steps as f64,
        state.q
    );
    Ok(())
}
