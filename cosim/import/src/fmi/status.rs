//! Safe view of `fmi2Status`.

use std::fmt;

use super::ffi;

/// An `fmi2Status` returned by an FMU (or passed to the logger).
///
/// Values outside the enumeration are kept as [`Status::Invalid`] instead of
/// being trusted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Status {
    Ok,
    Warning,
    Discard,
    Error,
    Fatal,
    Pending,
    /// A value that is not an `fmi2Status`.
    Invalid(i32),
}

impl Status {
    /// Interprets a raw status code.
    pub fn from_raw(raw: ffi::fmi2Status) -> Self {
        match raw {
            ffi::fmi2OK => Status::Ok,
            ffi::fmi2Warning => Status::Warning,
            ffi::fmi2Discard => Status::Discard,
            ffi::fmi2Error => Status::Error,
            ffi::fmi2Fatal => Status::Fatal,
            ffi::fmi2Pending => Status::Pending,
            other => Status::Invalid(other),
        }
    }

    /// The raw code.
    pub fn to_raw(self) -> ffi::fmi2Status {
        match self {
            Status::Ok => ffi::fmi2OK,
            Status::Warning => ffi::fmi2Warning,
            Status::Discard => ffi::fmi2Discard,
            Status::Error => ffi::fmi2Error,
            Status::Fatal => ffi::fmi2Fatal,
            Status::Pending => ffi::fmi2Pending,
            Status::Invalid(raw) => raw,
        }
    }

    /// `fmi2OK` or `fmi2Warning`: the call did what was asked.
    pub fn is_success(self) -> bool {
        matches!(self, Status::Ok | Status::Warning)
    }
}

impl Status {
    /// The status as the standard of `prefix` (`"fmi2"` or `"fmi3"`) spells it: `fmi3Error`.
    /// FMI 3.0 has no Pending; its codes 0–4 are FMI 2.0's.
    pub fn spelled(self, prefix: &str) -> String {
        let name = match self {
            Status::Ok => "OK",
            Status::Warning => "Warning",
            Status::Discard => "Discard",
            Status::Error => "Error",
            Status::Fatal => "Fatal",
            Status::Pending => "Pending",
            Status::Invalid(raw) => return format!("invalid {prefix}Status {raw}"),
        };
        format!("{prefix}{name}")
    }
}

/// FMI 2.0's spelling ([`Status::spelled`] gives either version's).
impl fmt::Display for Status {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.spelled("fmi2"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn raw_round_trip_and_unknown_codes() {
        for raw in -2..8 {
            assert_eq!(Status::from_raw(raw).to_raw(), raw);
        }
        assert_eq!(Status::from_raw(3), Status::Error);
        assert_eq!(Status::from_raw(42).to_string(), "invalid fmi2Status 42");
        assert!(Status::Warning.is_success() && !Status::Discard.is_success());
    }

    #[test]
    fn each_standard_spells_its_own_statuses() {
        assert_eq!(Status::Error.spelled("fmi3"), "fmi3Error");
        assert_eq!(Status::Ok.spelled("fmi3"), "fmi3OK");
        assert_eq!(Status::Invalid(9).spelled("fmi3"), "invalid fmi3Status 9");
        assert_eq!(Status::Discard.to_string(), "fmi2Discard");
    }
}
