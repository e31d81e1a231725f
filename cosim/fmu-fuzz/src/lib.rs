//! Hostile testing of the FMU libraries as built (`target/release/lib<model>.so`), through the C
//! ABI a host uses:
//!
//! * [`fuzz`]: seeded random FMI call sequences (wrong call order, null pointers, unknown value
//!   references, non-finite values, any step size and start time, garbage and truncated
//!   serialized states), checking that no call crashes, panics, hangs or returns `fmi2OK` with a
//!   non-finite value, and that calls bad by construction are refused;
//! * [`cycles`]: instantiate/step/free cycles (leaving FMU states unfreed) and load/unload
//!   cycles of each library, run under valgrind by `cargo xtask test` (`fmu-leak`).

//!
//! The FMUs are those `cargo xtask package` listed in `target/fmu/index.json` ([`fmu::models`]).

pub mod cycles;
pub mod fmu;
pub mod fuzz;
mod rng;
