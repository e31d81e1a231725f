//! The raw FMI C ABI as seen by an importer, one folder per version and the parts both share.
//!
//! - Shared: shared-library loading of either version ([`Library`]), the check of a library's
//!   headers before it is loaded ([`check_file`]), status codes ([`Status`]) and the host
//!   callbacks ([`LogContext`]).
//! - [`fmi2`]: the FMI 2.0 function table ([`Functions`]), through which the importer calls
//!   every FMU; its C declarations are [`ffi`].
//! - [`fmi3`]: FMI 3.0 FMUs behind that same table, an adapter translating each FMI 2.0 call into
//!   its FMI 3.0 counterpart, and how the adapter reaches FMI 3.0 variables that are not direct
//!   scalars.
//!
//! Everything here is `unsafe`-adjacent plumbing; simulation code should use
//! [`crate::slave::Slave`] instead.

pub mod fmi2;
pub mod fmi3;
mod header;
mod library;
mod logger;
mod status;

/// The raw FMI 2.0 C declarations, shared with the FMU side: the `fmi2-sys` crate.
pub use fmi2_sys as ffi;

pub use fmi2::{Functions, SYMBOLS};
pub use library::{check_file, Library, LibraryError};
pub use logger::{LogContext, LogEcho, LogMessage, LOG_CAPACITY};
pub use status::Status;
