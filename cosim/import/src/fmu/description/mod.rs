//! `modelDescription.xml` of an FMI 2.0 or FMI 3.0 Co-Simulation FMU, read into one
//! [`ModelDescription`] whatever the version, so that everything above the importer handles
//! both alike.
//!
//! What both versions share is here and in `variable` (the rows, [`ScalarVariable`]) and
//! `parser` (attribute helpers, the document's frame); what each version spells its own way
//! (capabilities, type definitions, variables) is in [`fmi2`] and [`fmi3`].

mod fmi2;
mod fmi3;
mod parser;
#[cfg(test)]
mod tests;
mod variable;

use std::collections::HashMap;
use std::fmt;

use roxmltree::Document;

pub use crate::fmi::fmi3::{Fmi3Element, Fmi3Type, Start as Fmi3Start};
use crate::value::VariableType;
use parser::Parser;
pub use variable::{Causality, Initial, ScalarVariable, Variability};

/// A problem in a `modelDescription.xml`, with its position when known.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub struct ModelDescriptionError {
    /// 1-based line and column of the offending element or attribute.
    pub position: Option<(u32, u32)>,
    pub message: String,
}

impl fmt::Display for ModelDescriptionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.position {
            Some((line, column)) => write!(f, "line {line}, column {column}: {}", self.message),
            None => f.write_str(&self.message),
        }
    }
}

/// `<CoSimulation>` capabilities.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct CoSimulation {
    pub model_identifier: String,
    pub needs_execution_tool: bool,
    pub can_handle_variable_communication_step_size: bool,
    pub can_interpolate_inputs: bool,
    pub max_output_derivative_order: u32,
    pub can_run_asynchronuously: bool,
    pub can_be_instantiated_only_once_per_process: bool,
    pub can_not_use_memory_management_functions: bool,
    pub can_get_and_set_fmu_state: bool,
    pub can_serialize_fmu_state: bool,
    pub provides_directional_derivative: bool,
}

/// `<DefaultExperiment>` (seconds).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DefaultExperiment {
    pub start_time: Option<f64>,
    pub stop_time: Option<f64>,
    pub tolerance: Option<f64>,
    pub step_size: Option<f64>,
}

/// The parts of `modelDescription.xml` a co-simulation importer needs.
///
/// [`ModelDescription::parse`] accepts FMI 2.0 and FMI 3.0 descriptions with a
/// `<CoSimulation>` element; an FMI 3.0 one is read into the same rows.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelDescription {
    pub fmi_version: String,
    pub model_name: String,
    pub guid: String,
    pub description: Option<String>,
    pub generation_tool: Option<String>,
    pub co_simulation: CoSimulation,
    /// True if the FMU also declares `<ModelExchange>` (not used by this importer).
    pub has_model_exchange: bool,
    pub default_experiment: Option<DefaultExperiment>,
    /// In document order (an FMI 3.0 array as its elements, see [`Fmi3Element`]).
    pub variables: Vec<ScalarVariable>,
    /// FMI 3.0: the variables reached through a conversion or as array elements (every one that
    /// is not a Float64, Int32, Boolean or String scalar), by their value reference in
    /// `variables`; empty for FMI 2.0.
    pub fmi3_elements: Vec<Fmi3Element>,
    by_name: HashMap<String, usize>,
}

impl ModelDescription {
    /// Parses and checks an FMI 2.0 or FMI 3.0 Co-Simulation model description.
    pub fn parse(xml: &str) -> Result<Self, ModelDescriptionError> {
        let document = Document::parse(xml).map_err(|error| {
            let position = error.pos();
            ModelDescriptionError {
                position: Some((position.row, position.col)),
                message: format!("not well-formed XML: {error}"),
            }
        })?;
        Parser { document: &document }.model_description()
    }

    /// Whether this is an FMI 3.0 description (else FMI 2.0).
    pub fn is_fmi3(&self) -> bool {
        self.fmi_version.starts_with("3.")
    }

    /// Looks a variable up by its exact name.
    pub fn variable(&self, name: &str) -> Option<&ScalarVariable> {
        self.by_name.get(name).map(|&index| &self.variables[index])
    }

    /// Variables with the given causality, in document order.
    pub fn variables_with(&self, causality: Causality) -> impl Iterator<Item = &ScalarVariable> {
        self.variables.iter().filter(move |v| v.causality == causality)
    }

    /// The first variable with this value reference and ABI type.
    pub fn variable_by_reference(&self, vr: u32, abi_type: VariableType) -> Option<&ScalarVariable> {
        self.variables.iter().find(|v| v.value_reference == vr && v.variable_type.abi_type() == abi_type)
    }
}
