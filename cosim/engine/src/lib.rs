//! Co-simulation engine: simulators stepped by an algorithm on an integer time grid and watched
//! by read-only observers (libcosim's design), fed by input signals and built from validated
//! system files.
//!
//! Modules, bottom up (each uses only modules above it in this list):
//! * [`time`], [`variable`], [`text`]: the communication grid, resolved variable references, and
//!   how times and counts read in messages;
//! * [`simulator`]: the [`Simulator`](simulator::Simulator) trait between the engine and FMU
//!   instances (implemented by [`fmu_import::slave::Slave`] and by test mocks);
//! * [`table`]: a [`SignalTable`](table::SignalTable) of sampled signals by name, read from a CSV
//!   file (an input or a results file) or recorded in memory;
//! * [`input`]: input signals from such tables, interpolated like FMPy;
//! * [`algorithm`]: Gauss–Seidel and Jacobi stepping over a [`Wiring`](algorithm::Wiring);
//! * [`observer`]: CSV and in-memory table recorders and progress bar;
//! * [`system`]: system and scenario files turned into a validated [`System`](system::System);
//! * [`execution`]: simulators + an algorithm + observers on a grid;
//! * [`export`]: a system as an SSP archive or an OSP system structure, for other importers;
//! * [`summary`], [`error`], [`run`]: a complete run of a system file with its summary.
//!
//! The engine names no crane instance or variable: the crane systems' vocabulary is the crate
//! crane-names.

pub mod algorithm;
pub mod emergency;
pub mod error;
pub mod execution;
pub mod export;
pub mod input;
pub mod interrupt;
pub mod observer;
pub mod partial;
pub mod run;
pub mod simulator;
pub mod summary;
pub mod system;
pub mod table;
pub mod text;
pub mod time;
pub mod variable;
pub mod workload;

pub use error::Error;
pub use fmu_import::error_chain;

#[cfg(test)]
mod tests;
