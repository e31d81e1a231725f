//! Variables of a system's instances, resolved against their model descriptions.

use fmu_import::fmu::ScalarVariable;

/// A variable of an instance, resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct VariableRef {
    /// Index of the instance in the system's stepping order.
    pub instance: usize,
    /// `"<instance>.<variable>"`.
    pub qualified_name: String,
    pub variable: ScalarVariable,
}
