//! The status of an FMI call on the Rust side of the exporter.

use crate::ffi;

/// An `fmi2Status` as the exporter's logic produces it. The C entry points return the C type
/// [`ffi::fmi2Status`] (a `c_int`); [`Status::to_c`] converts at that boundary (in
/// [`crate::fmi2::api`], [`crate::fmi3::api`] and [`crate::logging`]), so nothing here depends on how C passes enums.
#[repr(i32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Status {
    Ok = ffi::fmi2OK,
    Warning = ffi::fmi2Warning,
    Discard = ffi::fmi2Discard,
    Error = ffi::fmi2Error,
    Fatal = ffi::fmi2Fatal,
    Pending = ffi::fmi2Pending,
}

impl Status {
    /// The C value, as returned by the `fmi2*` functions and passed to the logger callback.
    pub const fn to_c(self) -> ffi::fmi2Status {
        self as ffi::fmi2Status
    }
}

impl From<Status> for ffi::fmi2Status {
    fn from(status: Status) -> Self {
        status.to_c()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn c_values_are_those_of_the_header() {
        let all = [Status::Ok, Status::Warning, Status::Discard, Status::Error, Status::Fatal, Status::Pending];
        let c: Vec<ffi::fmi2Status> = all.iter().map(|s| s.to_c()).collect();
        assert_eq!(c, [0, 1, 2, 3, 4, 5]);
    }
}
