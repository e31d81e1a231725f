//! FMI 3.0 Co-Simulation FMUs behind the FMI 2.0 calling convention the rest of the importer
//! speaks: an adapter per instance holds the FMI 3.0 instance and functions, and
//! [`functions`] is an FMI 2.0 function table whose entries are this module's `extern "C"`
//! functions, each translating one FMI 2.0 call into its FMI 3.0 counterpart on the adapter
//! behind the component pointer. So [`crate::slave::Slave`] (state tracking, errors, logs,
//! the call watch) is the same code for both versions.
//!
//! The translation, call by call (FMI 3.0.2):
//! - `fmi2Instantiate` → `fmi3InstantiateCoSimulation` (done by [`instantiate`], which has the
//!   FMI 3.0 table): no Event Mode, no early return, no intermediate update; the resource
//!   folder as a path with a trailing separator; the logger is the same log context, called
//!   through a non-variadic FMI 3.0 callback.
//! - `fmi2SetupExperiment` keeps the times; `fmi2EnterInitializationMode` passes them to
//!   `fmi3EnterInitializationMode`, which takes them.
//! - Real ↔ Float64, Integer ↔ Int32, Boolean ↔ Boolean (C `bool`, converted element-wise),
//!   String ↔ String, with `nValues = nValueReferences` (scalars only: arrays are refused when
//!   the description is read).
//! - `fmi2DoStep` → `fmi3DoStep`. A step that returns OK but asks to end the simulation
//!   (`terminateSimulation`), returns early (`earlyReturn`) or needs event handling
//!   (`eventHandlingNeeded`, which an FMU without Event Mode must not set) becomes
//!   `fmi2Discard` with a log message saying which; `fmi2GetBooleanStatus(fmi2Terminated)` and
//!   `fmi2GetRealStatus(fmi2LastSuccessfulTime)` then answer from what `fmi3DoStep` reported, so
//!   a run ends cleanly and says why, as for an FMI 2.0 discard. A step that returns
//!   `fmi3Discard` (or worse) stays what it is, and its output arguments, which FMI 3.0 leaves
//!   undefined then, are not read: no request to end the simulation, nothing completed after the
//!   step's start.
//! - `fmi2SetRealInputDerivatives`: FMI 3.0 has none; refused (the description says
//!   `canInterpolateInputs = false`, so the engine never calls it).
//! - FMU states: the same six functions under FMI 3.0 names (optional: resolved if exported).
//!
//! One file per concept: the FMI 3.0 functions the adapter calls ([`Functions`]), the adapter
//! and its instantiation, the lifecycle calls, values (with the rows of `elements`, reached
//! through a conversion or as array elements, described by [`Fmi3Element`]), the step, FMU states, and the FMI 2.0 table
//! that points at all of them ([`functions`]).

mod adapter;
mod elements;
mod functions;
mod lifecycle;
mod states;
mod step;
mod table;
#[cfg(test)]
mod tests;
mod types;
mod values;

pub use adapter::instantiate;
pub use functions::Functions;
pub use table::{call_name, functions};
pub use types::{Fmi3Element, Fmi3Type, Start};
