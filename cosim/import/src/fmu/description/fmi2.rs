//! FMI 2.0 model descriptions: `<CoSimulation>` under its FMI 2.0 attribute names, units of
//! `<SimpleType>`s, and `<ScalarVariable>` rows with their type element (Real, Integer,
//! Boolean, String, Enumeration).

use std::collections::HashMap;

use roxmltree::Node;

use super::parser::{parse_start, real_unit, Parser};
use super::{Causality, CoSimulation, Initial, ModelDescriptionError, ScalarVariable, Variability};
use crate::value::VariableType;

impl<'a, 'input> Parser<'a, 'input> {
    /// FMI 2.0 `<CoSimulation>` (FMI 3.0 reads the attributes both versions share here too).
    pub(super) fn co_simulation_2(&self, node: Node) -> Result<CoSimulation, ModelDescriptionError> {
        let model_identifier = self.required(node, "modelIdentifier")?.to_string();
        let mut chars = model_identifier.chars();
        let valid = chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && chars.all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !valid {
            return Err(self.error(node, format!("modelIdentifier {model_identifier:?} is not a valid C identifier")));
        }
        Ok(CoSimulation {
            model_identifier,
            needs_execution_tool: self.boolean(node, "needsExecutionTool")?,
            can_handle_variable_communication_step_size: self
                .boolean(node, "canHandleVariableCommunicationStepSize")?,
            can_interpolate_inputs: self.boolean(node, "canInterpolateInputs")?,
            max_output_derivative_order: self
                .parsed(node, "maxOutputDerivativeOrder", "an unsigned integer")?
                .unwrap_or(0),
            can_run_asynchronuously: self.boolean(node, "canRunAsynchronuously")?,
            can_be_instantiated_only_once_per_process: self.boolean(node, "canBeInstantiatedOnlyOncePerProcess")?,
            can_not_use_memory_management_functions: self.boolean(node, "canNotUseMemoryManagementFunctions")?,
            can_get_and_set_fmu_state: self.boolean(node, "canGetAndSetFMUstate")?,
            can_serialize_fmu_state: self.boolean(node, "canSerializeFMUstate")?,
            provides_directional_derivative: self.boolean(node, "providesDirectionalDerivative")?,
        })
    }

    /// Units of `<TypeDefinitions>/<SimpleType>/<Real unit=...>`, by type name.
    pub(super) fn type_units_2(&self, root: Node) -> Result<HashMap<String, String>, ModelDescriptionError> {
        let mut units = HashMap::new();
        if let Some(definitions) = self.child(root, "TypeDefinitions")? {
            for simple in definitions.children().filter(|c| c.has_tag_name("SimpleType")) {
                let name = self.required(simple, "name")?;
                if let Some(unit) = simple.children().find(|c| c.has_tag_name("Real")).and_then(|r| r.attribute("unit"))
                {
                    units.insert(name.to_string(), unit.to_string());
                }
            }
        }
        Ok(units)
    }

    /// The rows of `<ModelVariables>`: one per `<ScalarVariable>`, names unique.
    pub(super) fn variables_2(
        &self,
        model_variables: Node,
        units: &HashMap<String, String>,
    ) -> Result<Vec<ScalarVariable>, ModelDescriptionError> {
        let mut variables = Vec::new();
        let mut names = std::collections::HashSet::new();
        for node in model_variables.children().filter(|c| c.is_element()) {
            if node.tag_name().name() != "ScalarVariable" {
                let tag = node.tag_name().name();
                return Err(self.error(node, format!("unexpected <{tag}> in <ModelVariables>")));
            }
            let variable = self.scalar_variable(node, units)?;
            if !names.insert(variable.name.clone()) {
                return Err(self.error(node, format!("variable name {:?} is declared twice", variable.name)));
            }
            variables.push(variable);
        }
        Ok(variables)
    }

    fn scalar_variable(
        &self,
        node: Node,
        units: &HashMap<String, String>,
    ) -> Result<ScalarVariable, ModelDescriptionError> {
        let name = self.required(node, "name")?.to_string();
        let value_reference = match self.parsed::<u32>(node, "valueReference", "an unsigned 32-bit integer")? {
            Some(vr) => vr,
            None => return Err(self.error(node, format!("variable {name:?} has no valueReference"))),
        };
        let causality = self.keyword(node, "causality", Causality::KEYWORDS)?.unwrap_or_default();
        let variability = self.keyword(node, "variability", Variability::KEYWORDS)?.unwrap_or_default();
        let initial = self.keyword(node, "initial", Initial::KEYWORDS)?;

        let mut type_nodes = node.children().filter(|c| {
            c.is_element() && matches!(c.tag_name().name(), "Real" | "Integer" | "Boolean" | "String" | "Enumeration")
        });
        let Some(type_node) = type_nodes.next() else {
            return Err(self.error(
                node,
                format!("variable {name:?} has no type element (Real, Integer, Boolean, String or Enumeration)"),
            ));
        };
        if type_nodes.next().is_some() {
            return Err(self.error(node, format!("variable {name:?} has more than one type element")));
        }
        let variable_type = match type_node.tag_name().name() {
            "Real" => VariableType::Real,
            "Integer" => VariableType::Integer,
            "Boolean" => VariableType::Boolean,
            "String" => VariableType::String,
            _ => VariableType::Enumeration,
        };
        let declared_type = type_node.attribute("declaredType").map(String::from);
        if variable_type == VariableType::Enumeration && declared_type.is_none() {
            return Err(self.error(type_node, format!("Enumeration variable {name:?} has no declaredType")));
        }
        let start = match type_node.attribute("start") {
            None => None,
            Some(text) => Some(parse_start(variable_type, text).ok_or_else(|| {
                self.error(type_node, format!("variable {name:?}: start={text:?} is not a valid {variable_type}"))
            })?),
        };
        let unit = real_unit(variable_type, type_node, declared_type.as_ref(), units);
        Ok(ScalarVariable {
            name,
            value_reference,
            description: node.attribute("description").map(String::from),
            causality,
            variability,
            initial,
            variable_type,
            start,
            unit,
            declared_type,
            range: (type_node.attribute("min").map(String::from), type_node.attribute("max").map(String::from)),
        })
    }
}
