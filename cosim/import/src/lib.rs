//! FMI 2.0 and FMI 3.0 Co-Simulation import: everything needed to open an `.fmu` of either
//! version and drive one instance.
//!
//! The two versions side by side: each has its own module where the versions differ, the
//! C ABI in [`fmi::fmi2`] and [`fmi::fmi3`] and the model description's spelling in `fmu`'s
//! `description::{fmi2, fmi3}`; the rest is shared. An FMI 3.0 FMU is read into the same rows
//! ([`fmu::ScalarVariable`]) and driven through the same FMI 2.0 function table by an adapter,
//! so everything above (the [`slave::Slave`], the engine) handles both alike.
//!
//! Modules, bottom up (each uses only modules above it in this list):
//! * [`value`], [`names`], [`chain`], [`mod@file`], [`watch`]: typed values, name suggestions,
//!   error chains, defensive reads of user-named files, the FMU call in progress;
//! * [`fmi`]: the raw C ABI of both versions, library loading and the host callbacks (logger);
//! * [`fmu`]: opening `.fmu` archives and reading their model description (either version);
//! * [`slave`]: a safe FMU instance ([`slave::Slave`]) with the FMI 2.0 call sequence (an
//!   FMI 3.0 FMU's calls translated by the adapter);
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
