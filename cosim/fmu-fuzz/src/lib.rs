//! Hostile testing of the FMU libraries as built (`target/release/lib<model>.so`), through the C
//! ABIs a host uses, FMI 2.0's and FMI 3.0's (each library exports both):
//!
//! * [`fuzz`]: seeded random FMI call sequences through either API (wrong call order, null
//!   pointers, unknown value references, non-finite values, any step size and start time,
//!   garbage and truncated serialized states, the other version's API on an instance), checking
//!   that no call crashes, panics, hangs or returns OK with a non-finite value, that calls bad by
//!   construction are refused, and, for FMI 3.0, every status against the standard's state
//!   table ([`table`]);
//! * [`cycles`]: instantiate/step/free cycles (leaving FMU states unfreed) and load/unload
//!   cycles of each library through either API, and the refusal of another library's instances
//!   and states, run under valgrind by `cargo xtask test` (`fmu-leak`).
//!
//! The FMUs are those `cargo xtask package` listed in `target/fmu/index.json` ([`fmu::models`]).

pub mod cycles;
pub mod fmi3;
pub mod fmu;
pub mod fuzz;
mod rng;
pub mod table;
