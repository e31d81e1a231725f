//! FMI 2.0 Co-Simulation import: everything needed to open an `.fmu` and drive one instance.
//!
//! Modules, bottom up (each uses only modules above it in this list):
//! * [`value`], [`names`], [`chain`], [`file`]: typed values, name suggestions, error chains,
//!   defensive reads of user-named files;
//! * [`fmi`]: the raw C ABI, library loading and the host callbacks (logger);
//! * [`fmu`]: opening `.fmu` archives and reading their model description;
//! * [`slave`]: a safe FMU instance ([`slave::Slave`]) with the FMI 2.0 call sequence;
//! * [`describe`]: a model description as text (`crane-cosim info`).

pub mod chain;
pub mod describe;
pub mod file;
pub mod fmi;
pub mod fmu;
pub mod names;
pub mod slave;
pub mod value;
pub mod watch;

pub use chain::error_chain;
