//! Scalar values and types of FMI 2.0 variables.

use std::fmt;

/// The base type of a `ScalarVariable`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum VariableType {
    /// `fmi2Real` (double).
    Real,
    /// `fmi2Integer` (32-bit signed).
    Integer,
    /// `fmi2Boolean` (0 / 1 on the ABI).
    Boolean,
    /// `fmi2String` (UTF-8).
    String,
    /// An enumeration; exchanged as `fmi2Integer`.
    Enumeration,
}

impl VariableType {
    /// The type actually used on the C ABI (enumerations are integers).
    pub fn abi_type(self) -> VariableType {
        match self {
            VariableType::Enumeration => VariableType::Integer,
            other => other,
        }
    }
}

impl fmt::Display for VariableType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            VariableType::Real => "Real",
            VariableType::Integer => "Integer",
            VariableType::Boolean => "Boolean",
            VariableType::String => "String",
            VariableType::Enumeration => "Enumeration",
        })
    }
}

/// A value of one variable.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    Real(f64),
    /// Also used for enumerations.
    Integer(i32),
    Boolean(bool),
    String(String),
}

impl Value {
    /// The ABI type of this value.
    pub fn abi_type(&self) -> VariableType {
        match self {
            Value::Real(_) => VariableType::Real,
            Value::Integer(_) => VariableType::Integer,
            Value::Boolean(_) => VariableType::Boolean,
            Value::String(_) => VariableType::String,
        }
    }
}

impl fmt::Display for Value {
    /// Reals use Rust's shortest round-trip representation (`{:?}`).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Real(v) => write!(f, "{v:?}"),
            Value::Integer(v) => write!(f, "{v}"),
            Value::Boolean(v) => write!(f, "{v}"),
            Value::String(v) => write!(f, "{v:?}"),
        }
    }
}
