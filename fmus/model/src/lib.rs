//! Co-simulation models as the FMUs export them, independent of the FMI version.
//!
//! A model is a [`Model`] (its physics: initialize, step, state checks) and one static variable
//! table ([`Variable`] rows built with [`builder`], a row of one place of the model with
//! [`field!`], vector components with [`xyz!`], sections joined with [`table`], the rows several
//! models share with macros such as [`ship_inputs!`], [`load_outputs!`], [`sample_period!`] and
//! [`noise_parameters!`]). The table says what each variable is: causality, variability, type,
//! unit, start, range and description. How an FMI version spells that (FMI 2.0's `causality`,
//! `variability` and `initial` attributes, its status codes and C functions) is the business of
//! an export layer such as the `fmi2` crate, so that a second layer (FMI 3.0) exports the same
//! tables; this crate knows no FMI names. The model crates depend on this crate for what they
//! define and on the export layer only for the one line that exports them
//! (`fmu_export::export_fmu!(MyModel)`), so that adding an export layer adds a line, not a rewrite of
//! their imports.
//!
//! Sampled models (controllers) count their sample times with [`SampleClock`]. An enumeration
//! shown as an Integer parameter gets its codes, both directions and its range, from [`codes!`].
//!
//! The split follows the Reference-FMUs' separation of a model (its variables and equations)
//! from the FMI 2 and FMI 3 code around it.

pub mod builder;
pub mod codes;
mod load;
pub mod model;
pub mod sampling;
mod settings;
mod ship;
mod triple;
pub mod variables;

#[cfg(test)]
mod tests;

pub use builder::{Boolean, Integer, Real, Text};
pub use model::{Environment, Model, ModelInfo};
pub use sampling::{time_tolerance, SampleClock};
pub use variables::{check_table, table, table_len, Causality, Value, ValueType, Variability, Variable};
