//! FMI 2.0 co-simulation master.
//!
//! Layers, bottom up:
//! * [`fmi`]: the raw C ABI, library loading and host callbacks;
//! * [`fmu`]: opening `.fmu` archives and their model description;
//! * [`slave`]: a safe FMU instance ([`slave::Slave`]);
//! * [`system`]: JSON system files, validated before anything is instantiated;
//! * [`algorithm`], [`observer`], [`execution`]: libcosim-style stepping
//!   (slaves + an algorithm + read-only observers on an integer time grid);
//! * [`run`]: a complete run of a system file with CSV output and summary;
//! * [`metrics`], [`campaign`]: the thesis' §7.2.2 metrics and its test campaign (Chapter 7);
//! * [`cli`]: the `crane-cosim` command line.

pub mod algorithm;
pub mod campaign;
pub mod cli;
pub mod error;
pub mod execution;
pub mod fmi;
pub mod fmu;
pub mod info;
pub mod input;
pub mod metrics;
pub mod names;
pub mod observer;
pub mod plot;
pub mod run;
pub mod slave;
pub mod summary;
pub mod system;
pub mod time;
pub mod value;

pub use error::{error_chain, Error};
