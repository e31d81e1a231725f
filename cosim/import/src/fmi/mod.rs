//! The raw FMI 2.0 C ABI as seen by an importer: types and function pointer
//! declarations ([`ffi`]), shared-library loading ([`Library`]), status codes
//! ([`Status`]) and the host callbacks ([`LogContext`]); FMI 3.0 FMUs are driven through the
//! same FMI 2.0 table by the adapter in [`fmi3`].
//!
//! Everything here is `unsafe`-adjacent plumbing; simulation code should use
//! [`crate::slave::Slave`] instead.

pub mod fmi3;
mod header;
mod library;
mod logger;
mod status;

/// The raw C declarations, shared with the FMU side: the `fmi2-sys` crate.
pub use fmi2_sys as ffi;

pub use library::{check_file, Functions, Library, LibraryError, SYMBOLS};
pub use logger::{LogContext, LogEcho, LogMessage, LOG_CAPACITY};
pub use status::Status;
