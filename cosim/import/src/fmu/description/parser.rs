//! What reading either version's `modelDescription.xml` shares: the [`Parser`] over the
//! document with its attribute helpers (each error at the offending node's position), the
//! frame of the description (root, version, `<CoSimulation>`, `<DefaultExperiment>`,
//! `<ModelVariables>`) that hands the version's own elements to `fmi2` or `fmi3`, and start
//! literals.

use std::collections::HashMap;
use std::str::FromStr;

use roxmltree::{Document, Node};

use super::{DefaultExperiment, ModelDescription, ModelDescriptionError};
use crate::value::{Value, VariableType};

pub(super) struct Parser<'a, 'input> {
    pub(super) document: &'a Document<'input>,
}

impl<'a, 'input> Parser<'a, 'input> {
    pub(super) fn error(&self, node: Node, message: impl Into<String>) -> ModelDescriptionError {
        let position = self.document.text_pos_at(node.range().start);
        ModelDescriptionError { position: Some((position.row, position.col)), message: message.into() }
    }

    pub(super) fn required<'n>(
        &self,
        node: Node<'n, 'input>,
        attribute: &str,
    ) -> Result<&'n str, ModelDescriptionError> {
        node.attribute(attribute)
            .ok_or_else(|| self.error(node, format!("<{}> has no {attribute:?} attribute", node.tag_name().name())))
    }

    pub(super) fn parsed<T: FromStr>(
        &self,
        node: Node,
        attribute: &str,
        what: &str,
    ) -> Result<Option<T>, ModelDescriptionError> {
        match node.attribute(attribute) {
            None => Ok(None),
            Some(text) => text.trim().parse().map(Some).map_err(|_| {
                self.error(node, format!("<{}> attribute {attribute}={text:?} is not {what}", node.tag_name().name()))
            }),
        }
    }

    pub(super) fn real(&self, node: Node, attribute: &str) -> Result<Option<f64>, ModelDescriptionError> {
        self.parsed(node, attribute, "a number")
    }

    pub(super) fn boolean(&self, node: Node, attribute: &str) -> Result<bool, ModelDescriptionError> {
        match node.attribute(attribute).map(str::trim) {
            None => Ok(false),
            Some("true" | "1") => Ok(true),
            Some("false" | "0") => Ok(false),
            Some(text) => Err(self
                .error(node, format!("<{}> attribute {attribute}={text:?} is not a boolean", node.tag_name().name()))),
        }
    }

    pub(super) fn keyword<T: FromStr>(
        &self,
        node: Node,
        attribute: &str,
        keywords: &[&str],
    ) -> Result<Option<T>, ModelDescriptionError> {
        match node.attribute(attribute) {
            None => Ok(None),
            Some(text) => text.parse().map(Some).map_err(|_| {
                self.error(
                    node,
                    format!("{} {attribute}={text:?} is not one of {}", describe(node), keywords.join(", ")),
                )
            }),
        }
    }

    pub(super) fn child<'n>(
        &self,
        node: Node<'n, 'input>,
        tag: &str,
    ) -> Result<Option<Node<'n, 'input>>, ModelDescriptionError> {
        let mut found = node.children().filter(|c| c.is_element() && c.tag_name().name() == tag);
        let first = found.next();
        if let Some(second) = found.next() {
            return Err(self.error(second, format!("more than one <{tag}> element")));
        }
        Ok(first)
    }

    pub(super) fn model_description(&self) -> Result<ModelDescription, ModelDescriptionError> {
        let root = self.document.root_element();
        if root.tag_name().name() != "fmiModelDescription" {
            return Err(self.error(
                root,
                format!("the root element is <{}>, expected <fmiModelDescription>", root.tag_name().name()),
            ));
        }
        let fmi_version = self.required(root, "fmiVersion")?.to_string();
        let fmi3 = match fmi_version.as_str() {
            "2.0" => false,
            version if version.starts_with("3.") => true,
            _ => {
                return Err(
                    self.error(root, format!("fmiVersion is {fmi_version:?}; FMI \"2.0\" and \"3.0\" are supported"))
                )
            }
        };
        let model_name = self.required(root, "modelName")?.to_string();
        let guid = self.required(root, if fmi3 { "instantiationToken" } else { "guid" })?.to_string();

        let has_model_exchange = self.child(root, "ModelExchange")?.is_some();
        let Some(cs) = self.child(root, "CoSimulation")? else {
            let what = if has_model_exchange {
                "a Model Exchange FMU: this importer runs Co-Simulation FMUs only (FMI 2.0 and 3.0)"
            } else {
                "no <CoSimulation> element: this FMU does not support Co-Simulation"
            };
            return Err(self.error(root, what));
        };
        let co_simulation = if fmi3 { self.co_simulation_3(cs)? } else { self.co_simulation_2(cs)? };

        let default_experiment = match self.child(root, "DefaultExperiment")? {
            None => None,
            Some(node) => Some(DefaultExperiment {
                start_time: self.real(node, "startTime")?,
                stop_time: self.real(node, "stopTime")?,
                tolerance: self.real(node, "tolerance")?,
                step_size: self.real(node, "stepSize")?,
            }),
        };

        let units = if fmi3 { self.type_units_3(root)? } else { self.type_units_2(root)? };
        let Some(model_variables) = self.child(root, "ModelVariables")? else {
            return Err(self.error(root, "no <ModelVariables> element"));
        };
        let (variables, fmi3_elements) = if fmi3 {
            self.variables_3(model_variables, &units)?
        } else {
            (self.variables_2(model_variables, &units)?, Vec::new())
        };
        // Names are unique: checked in `variables_2` (FMI 2.0) and `variables_3` (FMI 3.0).
        let by_name = variables.iter().enumerate().map(|(index, v)| (v.name.clone(), index)).collect();

        Ok(ModelDescription {
            fmi_version,
            model_name,
            guid,
            description: root.attribute("description").map(String::from),
            generation_tool: root.attribute("generationTool").map(String::from),
            co_simulation,
            has_model_exchange,
            default_experiment,
            variables,
            fmi3_elements,
            by_name,
        })
    }
}

pub(super) fn describe(node: Node) -> String {
    match node.attribute("name") {
        Some(name) => format!("<{} name={name:?}>", node.tag_name().name()),
        None => format!("<{}>", node.tag_name().name()),
    }
}

/// The unit of a row: for a Real, the `unit` attribute of `element`, else the unit of its
/// `declaredType` in `units`; none for other types.
pub(super) fn real_unit(
    variable_type: VariableType,
    element: Node,
    declared_type: Option<&String>,
    units: &HashMap<String, String>,
) -> Option<String> {
    match variable_type {
        VariableType::Real => {
            element.attribute("unit").map(String::from).or_else(|| declared_type.and_then(|t| units.get(t).cloned()))
        }
        _ => None,
    }
}

/// Parses an XML `start` literal (xs:double, xs:int, xs:boolean or string).
pub(super) fn parse_start(variable_type: VariableType, text: &str) -> Option<Value> {
    let trimmed = text.trim();
    match variable_type {
        VariableType::Real => match trimmed {
            "INF" => Some(f64::INFINITY),
            "-INF" => Some(f64::NEG_INFINITY),
            "NaN" => Some(f64::NAN),
            _ if trimmed.chars().all(|c| c.is_ascii_digit() || matches!(c, '+' | '-' | '.' | 'e' | 'E')) => {
                trimmed.parse().ok()
            }
            _ => None,
        }
        .map(Value::Real),
        VariableType::Integer | VariableType::Enumeration => trimmed.parse().ok().map(Value::Integer),
        VariableType::Boolean => match trimmed {
            "true" | "1" => Some(Value::Boolean(true)),
            "false" | "0" => Some(Value::Boolean(false)),
            _ => None,
        },
        VariableType::String => Some(Value::String(text.to_string())),
    }
}
