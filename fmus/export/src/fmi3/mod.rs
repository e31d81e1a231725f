//! The FMI 3.0 layer: the C entry points ([`api`], expanded by `export`'s half of
//! [`crate::export_fmu!`], the refusals one line each through `entry`'s macros) and the model
//! description ([`xml`]), over the same instance core, state machine and variable tables as
//! FMI 2.0 ([`crate::fmi2`]).
//!
//! What FMI 3.0 adds that these FMUs use, and what they leave out:
//! - Variables keep their FMI 2.0 names and value references (unique across types in every
//!   table, which FMI 3.0 requires and [`xml::render`] checks): Real is Float64, Integer Int32.
//!   Vectors (positions, quaternions) stay scalars: the names map 1:1 to the FMI 2.0 ones and
//!   to the recorded CSV columns, and importers without array support read them unchanged.
//! - The independent variable `time` ([`xml::TIME_VR`]), readable with `fmi3GetFloat64`.
//! - No Event Mode, no clocks, no intermediate update, no early return: a step always completes
//!   (`fmi3DoStep` reports no event, no termination and no early return), as in FMI 2.0.
//! - Input interpolation: FMI 3.0 has no `fmi2SetRealInputDerivatives`. Its replacements are
//!   intermediate update (the FMU calls the importer back at internal points, where the
//!   importer sets inputs) and output derivatives of the upstream FMU; neither FMPy's
//!   `simulate_fmu` nor the usual FMI 3.0 importers drive inputs through intermediate update,
//!   so the FMI 3.0 FMUs hold their inputs over each step (`providesIntermediateUpdate`
//!   false), which is what the FMI 2.0 FMUs do when no derivative is set.
//! - Model Exchange and Scheduled Execution instantiation return NULL with a message.

pub mod api;
mod entry;
mod export;
pub mod xml;
