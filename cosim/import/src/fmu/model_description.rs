//! `modelDescription.xml` of an FMI 2.0 Co-Simulation FMU.

use std::collections::HashMap;
use std::fmt;
use std::str::FromStr;

use roxmltree::{Document, Node};

use crate::value::{Value, VariableType};

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

/// `causality` of a variable (FMI 2.0 default: `local`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Causality {
    Parameter,
    CalculatedParameter,
    Input,
    Output,
    #[default]
    Local,
    Independent,
}

/// `variability` of a variable (FMI 2.0 default: `continuous`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Variability {
    Constant,
    Fixed,
    Tunable,
    Discrete,
    #[default]
    Continuous,
}

/// `initial` of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Initial {
    Exact,
    Approx,
    Calculated,
}

macro_rules! keyword_enum {
    ($type:ident { $($variant:ident = $text:literal),* $(,)? }) => {
        impl $type {
            /// All keywords, as written in the XML.
            pub const KEYWORDS: &'static [&'static str] = &[$($text),*];
            /// The keyword as written in the XML.
            pub fn as_str(self) -> &'static str {
                match self { $($type::$variant => $text),* }
            }
        }
        impl FromStr for $type {
            type Err = ();
            fn from_str(text: &str) -> Result<Self, ()> {
                match text { $($text => Ok($type::$variant),)* _ => Err(()) }
            }
        }
        impl fmt::Display for $type {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.as_str())
            }
        }
    };
}

keyword_enum!(Causality {
    Parameter = "parameter",
    CalculatedParameter = "calculatedParameter",
    Input = "input",
    Output = "output",
    Local = "local",
    Independent = "independent",
});
keyword_enum!(Variability {
    Constant = "constant",
    Fixed = "fixed",
    Tunable = "tunable",
    Discrete = "discrete",
    Continuous = "continuous",
});
keyword_enum!(Initial { Exact = "exact", Approx = "approx", Calculated = "calculated" });

/// One `ScalarVariable`.
#[derive(Debug, Clone, PartialEq)]
pub struct ScalarVariable {
    pub name: String,
    pub value_reference: u32,
    pub description: Option<String>,
    pub causality: Causality,
    pub variability: Variability,
    pub initial: Option<Initial>,
    pub variable_type: VariableType,
    /// `start` attribute of the type element, parsed to the variable's type
    /// (enumerations as [`Value::Integer`]).
    pub start: Option<Value>,
    /// Unit of a Real: the `unit` attribute, else the unit of its `declaredType`.
    pub unit: Option<String>,
    pub declared_type: Option<String>,
    /// The `min` and `max` attributes of the type element as written (shown, not enforced: the
    /// FMU checks what it is given).
    pub range: (Option<String>, Option<String>),
}

impl ScalarVariable {
    /// The `initial` attribute or, when it is absent, the FMI 2.0 default for the
    /// variable's causality and variability: exact for parameters and constants,
    /// calculated for calculated parameters and for other outputs and locals, none
    /// for inputs and the independent variable.
    pub fn initial_or_default(&self) -> Option<Initial> {
        self.initial.or(match (self.causality, self.variability) {
            (Causality::Input | Causality::Independent, _) => None,
            (Causality::Parameter, _) | (_, Variability::Constant) => Some(Initial::Exact),
            (Causality::CalculatedParameter | Causality::Output | Causality::Local, _) => Some(Initial::Calculated),
        })
    }

    /// True for variables the importer may set before initialization from a
    /// system file: FMI 2.0 allows it on inputs and on any variable that is not
    /// constant and whose `initial` is exact or approx (parameters, and outputs or
    /// locals whose start value the FMU takes as given or as a guess).
    pub fn is_settable_start(&self) -> bool {
        self.variability != Variability::Constant
            && (self.causality == Causality::Input
                || matches!(self.initial_or_default(), Some(Initial::Exact | Initial::Approx)))
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
/// [`ModelDescription::parse`] only accepts FMI 2.0 descriptions with a
/// `<CoSimulation>` element.
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
    /// Parses and checks an FMI 2.0 Co-Simulation model description.
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

#[path = "fmi3_description.rs"]
mod fmi3;
pub use fmi3::{Fmi3Element, Fmi3Type, Start as Fmi3Start};

struct Parser<'a, 'input> {
    document: &'a Document<'input>,
}

impl<'a, 'input> Parser<'a, 'input> {
    fn error(&self, node: Node, message: impl Into<String>) -> ModelDescriptionError {
        let position = self.document.text_pos_at(node.range().start);
        ModelDescriptionError { position: Some((position.row, position.col)), message: message.into() }
    }

    fn required<'n>(&self, node: Node<'n, 'input>, attribute: &str) -> Result<&'n str, ModelDescriptionError> {
        node.attribute(attribute)
            .ok_or_else(|| self.error(node, format!("<{}> has no {attribute:?} attribute", node.tag_name().name())))
    }

    fn parsed<T: FromStr>(&self, node: Node, attribute: &str, what: &str) -> Result<Option<T>, ModelDescriptionError> {
        match node.attribute(attribute) {
            None => Ok(None),
            Some(text) => text.trim().parse().map(Some).map_err(|_| {
                self.error(node, format!("<{}> attribute {attribute}={text:?} is not {what}", node.tag_name().name()))
            }),
        }
    }

    fn real(&self, node: Node, attribute: &str) -> Result<Option<f64>, ModelDescriptionError> {
        self.parsed(node, attribute, "a number")
    }

    fn boolean(&self, node: Node, attribute: &str) -> Result<bool, ModelDescriptionError> {
        match node.attribute(attribute).map(str::trim) {
            None => Ok(false),
            Some("true" | "1") => Ok(true),
            Some("false" | "0") => Ok(false),
            Some(text) => Err(self
                .error(node, format!("<{}> attribute {attribute}={text:?} is not a boolean", node.tag_name().name()))),
        }
    }

    fn keyword<T: FromStr>(
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

    fn child<'n>(&self, node: Node<'n, 'input>, tag: &str) -> Result<Option<Node<'n, 'input>>, ModelDescriptionError> {
        let mut found = node.children().filter(|c| c.is_element() && c.tag_name().name() == tag);
        let first = found.next();
        if let Some(second) = found.next() {
            return Err(self.error(second, format!("more than one <{tag}> element")));
        }
        Ok(first)
    }

    fn model_description(&self) -> Result<ModelDescription, ModelDescriptionError> {
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
        let co_simulation = if fmi3 { self.co_simulation_3(cs)? } else { self.co_simulation(cs)? };

        let default_experiment = match self.child(root, "DefaultExperiment")? {
            None => None,
            Some(node) => Some(DefaultExperiment {
                start_time: self.real(node, "startTime")?,
                stop_time: self.real(node, "stopTime")?,
                tolerance: self.real(node, "tolerance")?,
                step_size: self.real(node, "stepSize")?,
            }),
        };

        let units = if fmi3 { self.type_units_3(root)? } else { self.type_units(root)? };
        let Some(model_variables) = self.child(root, "ModelVariables")? else {
            return Err(self.error(root, "no <ModelVariables> element"));
        };
        let mut variables = Vec::new();
        let mut fmi3_elements = Vec::new();
        if fmi3 {
            (variables, fmi3_elements) = self.variables_3(model_variables, &units)?;
        } else {
            let mut names = std::collections::HashSet::new();
            for node in model_variables.children().filter(|c| c.is_element()) {
                if node.tag_name().name() != "ScalarVariable" {
                    let tag = node.tag_name().name();
                    return Err(self.error(node, format!("unexpected <{tag}> in <ModelVariables>")));
                }
                let variable = self.scalar_variable(node, &units)?;
                if !names.insert(variable.name.clone()) {
                    return Err(self.error(node, format!("variable name {:?} is declared twice", variable.name)));
                }
                variables.push(variable);
            }
        }
        // Names are unique: checked per node above (FMI 2.0) and in `variables_3` (FMI 3.0).
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

    fn co_simulation(&self, node: Node) -> Result<CoSimulation, ModelDescriptionError> {
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
    fn type_units(&self, root: Node) -> Result<HashMap<String, String>, ModelDescriptionError> {
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
        let unit = match variable_type {
            VariableType::Real => type_node
                .attribute("unit")
                .map(String::from)
                .or_else(|| declared_type.as_ref().and_then(|t| units.get(t).cloned())),
            _ => None,
        };
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

fn describe(node: Node) -> String {
    match node.attribute("name") {
        Some(name) => format!("<{} name={name:?}>", node.tag_name().name()),
        None => format!("<{}>", node.tag_name().name()),
    }
}

/// Parses an XML `start` literal (xs:double, xs:int, xs:boolean or string).
fn parse_start(variable_type: VariableType, text: &str) -> Option<Value> {
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

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="pendulum" guid="{abc}" generationTool="test">
  <CoSimulation modelIdentifier="pendulum" canHandleVariableCommunicationStepSize="true"
      canInterpolateInputs="true" maxOutputDerivativeOrder="0" canGetAndSetFMUstate="true"
      canSerializeFMUstate="true"/>
  <UnitDefinitions><Unit name="m"/><Unit name="rad"/></UnitDefinitions>
  <TypeDefinitions><SimpleType name="Angle"><Real quantity="Angle" unit="rad"/></SimpleType></TypeDefinitions>
  <DefaultExperiment startTime="0" stopTime="60" stepSize="0.01"/>
  <ModelVariables>
    <ScalarVariable name="tip.x" valueReference="1" causality="input" description="tip x in W">
      <Real start="0" unit="m"/>
    </ScalarVariable>
    <ScalarVariable name="theta_x0" valueReference="100" causality="parameter" variability="fixed" initial="exact">
      <Real declaredType="Angle" start="-0.349"/>
    </ScalarVariable>
    <ScalarVariable name="theta_x" valueReference="200" causality="output" initial="calculated">
      <Real unit="rad"/>
    </ScalarVariable>
    <ScalarVariable name="count" valueReference="300" causality="output" variability="discrete">
      <Integer/>
    </ScalarVariable>
    <ScalarVariable name="held" valueReference="301" causality="parameter" variability="fixed">
      <Boolean start="true"/>
    </ScalarVariable>
    <ScalarVariable name="label" valueReference="302" causality="parameter" variability="fixed">
      <String start="a b"/>
    </ScalarVariable>
    <ScalarVariable name="mode" valueReference="303" causality="parameter" variability="fixed">
      <Enumeration declaredType="Mode" start="2"/>
    </ScalarVariable>
    <ScalarVariable name="time" valueReference="0" causality="independent"><Real/></ScalarVariable>
  </ModelVariables>
  <ModelStructure/>
</fmiModelDescription>"#;

    #[test]
    fn absent_initial_takes_the_fmi_default_and_decides_settable_starts() {
        let md = ModelDescription::parse(GOOD).expect("valid");
        let variable = |name: &str| md.variable(name).expect(name);
        let defaults = ["tip.x", "held", "count", "time"].map(|name| variable(name).initial_or_default());
        assert_eq!(defaults, [None, Some(Initial::Exact), Some(Initial::Calculated), None]);
        let settable =
            ["tip.x", "theta_x0", "held", "theta_x", "count", "time"].map(|name| variable(name).is_settable_start());
        assert_eq!(settable, [true, true, true, false, false, false]);
    }

    #[test]
    fn parses_a_complete_description() {
        let md = ModelDescription::parse(GOOD).expect("valid");
        assert_eq!(md.fmi_version, "2.0");
        assert_eq!(md.model_name, "pendulum");
        assert_eq!(md.guid, "{abc}");
        assert_eq!(md.co_simulation.model_identifier, "pendulum");
        assert!(md.co_simulation.can_interpolate_inputs);
        assert!(md.co_simulation.can_handle_variable_communication_step_size);
        assert!(md.co_simulation.can_get_and_set_fmu_state && md.co_simulation.can_serialize_fmu_state);
        assert_eq!(md.co_simulation.max_output_derivative_order, 0);
        assert_eq!(md.default_experiment.and_then(|d| d.step_size), Some(0.01));
        assert_eq!(md.default_experiment.and_then(|d| d.stop_time), Some(60.0));
        assert_eq!(md.variables.len(), 8);

        let tip = md.variable("tip.x").expect("tip.x");
        assert_eq!(tip.value_reference, 1);
        assert_eq!(tip.causality, Causality::Input);
        assert_eq!(tip.variability, Variability::Continuous);
        assert_eq!(tip.initial, None);
        assert_eq!(tip.unit.as_deref(), Some("m"));
        assert_eq!(tip.description.as_deref(), Some("tip x in W"));
        assert_eq!(tip.start, Some(Value::Real(0.0)));

        let theta = md.variable("theta_x0").expect("theta_x0");
        assert_eq!(theta.unit.as_deref(), Some("rad"), "unit from the declared type");
        assert_eq!(theta.start, Some(Value::Real(-0.349)));
        assert_eq!(theta.initial, Some(Initial::Exact));
        assert_eq!(theta.variability, Variability::Fixed);

        assert_eq!(md.variable("count").map(|v| v.variable_type), Some(VariableType::Integer));
        assert_eq!(md.variable("held").and_then(|v| v.start.clone()), Some(Value::Boolean(true)));
        assert_eq!(md.variable("label").and_then(|v| v.start.clone()), Some(Value::String("a b".into())));
        assert_eq!(md.variable("mode").and_then(|v| v.start.clone()), Some(Value::Integer(2)));
        assert_eq!(md.variable("time").map(|v| v.causality), Some(Causality::Independent));
        assert_eq!(md.variable("time").map(|v| v.causality), Some(Causality::Independent));
        assert_eq!(md.variables_with(Causality::Output).count(), 2);
        assert_eq!(md.variable_by_reference(200, VariableType::Real).map(|v| v.name.as_str()), Some("theta_x"));
        assert!(md.variable("nope").is_none());
    }

    fn error_of(xml: &str) -> String {
        ModelDescription::parse(xml).expect_err("must be refused").to_string()
    }

    #[test]
    fn malformed_xml_reports_the_position() {
        let message = error_of("<fmiModelDescription fmiVersion=\"2.0\">\n  <CoSimulation>\n</fmiModelDescription>");
        assert!(message.contains("not well-formed XML") && message.contains("line 3"), "{message}");
    }

    #[test]
    fn wrong_root_version_and_missing_parts_are_refused() {
        assert!(error_of("<model/>").contains("expected <fmiModelDescription>"));
        let v1 = error_of(r#"<fmiModelDescription fmiVersion="1.0" modelName="m" guid="g"/>"#);
        assert!(v1.contains("\"1.0\"") && v1.contains("FMI \"2.0\" and \"3.0\""), "{v1}");
        let v3 = error_of(r#"<fmiModelDescription fmiVersion="3.0" modelName="m" instantiationToken="g"/>"#);
        assert!(v3.contains("no <CoSimulation>"), "an FMI 3.0 description is read as such: {v3}");
        let no_guid = error_of(r#"<fmiModelDescription fmiVersion="2.0" modelName="m"/>"#);
        assert!(no_guid.contains("\"guid\""), "{no_guid}");
        let me_only = error_of(
            r#"<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g"><ModelExchange modelIdentifier="m"/><ModelVariables/></fmiModelDescription>"#,
        );
        assert!(me_only.contains("a Model Exchange FMU"), "{me_only}");
        let no_vars = error_of(
            r#"<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g"><CoSimulation modelIdentifier="m"/></fmiModelDescription>"#,
        );
        assert!(no_vars.contains("<ModelVariables>"), "{no_vars}");
    }

    fn with_variable(variable: &str) -> String {
        format!(
            r#"<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g">
<CoSimulation modelIdentifier="m"/>
<ModelVariables>{variable}</ModelVariables></fmiModelDescription>"#
        )
    }

    #[test]
    fn bad_variables_are_named() {
        let cases = [
            (r#"<ScalarVariable name="a" valueReference="x"><Real/></ScalarVariable>"#, "valueReference=\"x\""),
            (r#"<ScalarVariable name="a" valueReference="-1"><Real/></ScalarVariable>"#, "valueReference=\"-1\""),
            (r#"<ScalarVariable name="a"><Real/></ScalarVariable>"#, "\"a\" has no valueReference"),
            (r#"<ScalarVariable valueReference="1"><Real/></ScalarVariable>"#, "no \"name\" attribute"),
            (r#"<ScalarVariable name="a" valueReference="1"/>"#, "\"a\" has no type element"),
            (
                r#"<ScalarVariable name="a" valueReference="1" causality="out"><Real/></ScalarVariable>"#,
                "causality=\"out\" is not one of",
            ),
            (
                r#"<ScalarVariable name="a" valueReference="1" variability="sometimes"><Real/></ScalarVariable>"#,
                "name=\"a\"",
            ),
            (
                r#"<ScalarVariable name="a" valueReference="1"><Real start="abc"/></ScalarVariable>"#,
                "start=\"abc\" is not a valid Real",
            ),
            (
                r#"<ScalarVariable name="a" valueReference="1"><Integer start="1.5"/></ScalarVariable>"#,
                "not a valid Integer",
            ),
            (
                r#"<ScalarVariable name="a" valueReference="1"><Boolean start="yes"/></ScalarVariable>"#,
                "not a valid Boolean",
            ),
            (
                r#"<ScalarVariable name="a" valueReference="1"><Enumeration start="1"/></ScalarVariable>"#,
                "no declaredType",
            ),
            (r#"<ScalarVariable name="a" valueReference="1"><Real/><Integer/></ScalarVariable>"#, "more than one type"),
            (
                r#"<ScalarVariable name="a" valueReference="1"><Real/></ScalarVariable><ScalarVariable name="a" valueReference="2"><Real/></ScalarVariable>"#,
                "declared twice",
            ),
            (r#"<Variable name="a"/>"#, "unexpected <Variable>"),
        ];
        for (variable, expected) in cases {
            let message = error_of(&with_variable(variable));
            assert!(message.contains(expected), "{variable}: {message}");
            assert!(message.starts_with("line 3"), "{variable}: {message}");
        }
    }

    #[test]
    fn bad_capabilities_are_named() {
        let bad_bool = error_of(
            r#"<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g"><CoSimulation modelIdentifier="m" canInterpolateInputs="yes"/><ModelVariables/></fmiModelDescription>"#,
        );
        assert!(bad_bool.contains("canInterpolateInputs=\"yes\""), "{bad_bool}");
        let bad_identifier = error_of(
            r#"<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g"><CoSimulation modelIdentifier="../evil"/><ModelVariables/></fmiModelDescription>"#,
        );
        assert!(bad_identifier.contains("not a valid C identifier"), "{bad_identifier}");
    }

    #[test]
    fn real_start_literals() {
        assert_eq!(parse_start(VariableType::Real, " 1e-3 "), Some(Value::Real(1e-3)));
        assert_eq!(parse_start(VariableType::Real, "-INF"), Some(Value::Real(f64::NEG_INFINITY)));
        assert_eq!(parse_start(VariableType::Real, "inf"), None);
        assert!(matches!(parse_start(VariableType::Real, "NaN"), Some(Value::Real(v)) if v.is_nan()));
    }

    const FMI3: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="3.0" modelName="m3" instantiationToken="{tok}">
  <CoSimulation modelIdentifier="m3" canHandleVariableCommunicationStepSize="true"
      canGetAndSetFMUState="true" canSerializeFMUState="true" hasEventMode="false"/>
  <TypeDefinitions><Float64Type name="Angle" unit="rad"/></TypeDefinitions>
  <ModelVariables>
    <Float64 name="time" valueReference="0" causality="independent" variability="continuous"/>
    <Float64 name="x" valueReference="1" causality="input" start="0.5" unit="m"/>
    <Float64 name="phi" valueReference="2" causality="output" declaredType="Angle"/>
    <Int32 name="n" valueReference="3" causality="parameter" variability="fixed" start="4"/>
    <Boolean name="on" valueReference="4" causality="parameter" variability="fixed" start="true"/>
    <String name="label" valueReference="5" causality="parameter" variability="fixed"><Start value="a b"/></String>
  </ModelVariables>
  <ModelStructure><Output valueReference="2"/></ModelStructure>
</fmiModelDescription>"#;

    #[test]
    fn an_fmi3_description_reads_into_the_same_rows() {
        let md = ModelDescription::parse(FMI3).expect("parses");
        assert!(md.is_fmi3());
        assert_eq!((md.guid.as_str(), md.co_simulation.model_identifier.as_str()), ("{tok}", "m3"));
        let cs = &md.co_simulation;
        assert!(cs.can_get_and_set_fmu_state && cs.can_serialize_fmu_state && !cs.can_interpolate_inputs);
        let x = md.variable("x").expect("x");
        assert_eq!(
            (x.variable_type, x.start.clone(), x.unit.as_deref()),
            (VariableType::Real, Some(Value::Real(0.5)), Some("m"))
        );
        assert_eq!(md.variable("phi").and_then(|v| v.unit.as_deref()), Some("rad"), "unit of the declared type");
        let n = md.variable("n").expect("n");
        assert_eq!((n.variable_type, n.start.clone()), (VariableType::Integer, Some(Value::Integer(4))));
        assert_eq!(md.variable("on").and_then(|v| v.start.clone()), Some(Value::Boolean(true)));
        assert_eq!(md.variable("label").and_then(|v| v.start.clone()), Some(Value::String("a b".into())));
        assert_eq!(md.variable("time").map(|v| v.causality), Some(Causality::Independent));
        assert_eq!(md.variable("n").map(|v| v.variability), Some(Variability::Fixed));
    }

    #[test]
    fn fmi3_arrays_become_elements_and_other_types_convert() {
        let xml = FMI3.replace(
            "  </ModelVariables>",
            r#"    <Float32 name="gain" valueReference="10" causality="parameter" variability="fixed" start="0.5"/>
    <Int8 name="small" valueReference="11" causality="output"/>
    <UInt64 name="big" valueReference="12" causality="parameter" variability="fixed" start="5000000000"/>
    <Float64 name="u" valueReference="13" causality="input" start="1 2 3"><Dimension start="3"/></Float64>
    <Float64 name="m" valueReference="14" causality="output"><Dimension start="2"/><Dimension start="2"/></Float64>
    <UInt64 name="size" valueReference="9" causality="structuralParameter" variability="fixed" start="3"/>
  </ModelVariables>"#,
        );
        let md = ModelDescription::parse(&xml).expect("parses");
        let gain = md.variable("gain").expect("gain");
        assert_eq!((gain.variable_type, gain.start.clone()), (VariableType::Real, Some(Value::Real(0.5))));
        assert_eq!(md.variable("small").map(|v| v.variable_type), Some(VariableType::Integer));
        assert_eq!(
            md.variable("big").map(|v| v.start.clone()),
            Some(None),
            "a start outside 32 bits is not a row start"
        );
        let elements: Vec<(&str, Option<Value>)> =
            ["u[1]", "u[2]", "u[3]"].iter().map(|n| (*n, md.variable(n).and_then(|v| v.start.clone()))).collect();
        assert_eq!(
            elements,
            [("u[1]", Some(Value::Real(1.0))), ("u[2]", Some(Value::Real(2.0))), ("u[3]", Some(Value::Real(3.0)))]
        );
        assert!(["m[1,1]", "m[1,2]", "m[2,1]", "m[2,2]"].iter().all(|n| md.variable(n).is_some()));
        assert!(md.variable("u").is_none(), "an array is its elements");
        // Element value references come after the largest the FMU uses, and are unique.
        let mut references: Vec<u32> = md.variables.iter().map(|v| v.value_reference).collect();
        assert_eq!(md.variable("u[1]").map(|v| v.value_reference), Some(15));
        references.sort_unstable();
        references.dedup();
        assert_eq!(references.len(), md.variables.len());
        // Every converted row and element is listed with how it is reached.
        let m12 = md.fmi3_elements.iter().find(|e| e.name == "m[1,2]").expect("m[1,2]");
        assert_eq!((m12.fmi3_value_reference, m12.fmi3_type, m12.index, m12.size), (14, Fmi3Type::Float64, 1, 4));
        let gain = md.fmi3_elements.iter().find(|e| e.name == "gain").expect("gain");
        assert_eq!((gain.fmi3_type, gain.size), (Fmi3Type::Float32, 1));
        assert!(md.fmi3_elements.iter().all(|e| e.name != "x" && e.name != "n"), "direct scalars need no element");
        // A structural parameter is read, never set (only Configuration Mode may set it).
        assert_eq!(md.variable("size").map(|v| v.causality), Some(Causality::CalculatedParameter));
    }

    #[test]
    fn fmi3_variables_no_row_can_carry_are_refused_by_name() {
        let with =
            |variable: &str| FMI3.replace("  </ModelVariables>", &format!("    {variable}\n  </ModelVariables>"));
        let refused = [
            (
                r#"<Binary name="blob" valueReference="20" causality="output"/>"#,
                r#"variable "blob" is an FMI 3.0 Binary"#,
            ),
            (r#"<Clock name="tick" valueReference="20" causality="input"/>"#, r#"variable "tick" is an FMI 3.0 Clock"#),
            (
                r#"<String name="words" valueReference="20" causality="output"><Dimension start="2"/></String>"#,
                r#"variable "words" is a String array"#,
            ),
            (
                r#"<Float64 name="v" valueReference="20" causality="output"><Dimension valueReference="3"/></Float64>"#,
                r#"array "v" is sized by a structural parameter"#,
            ),
            (
                r#"<Float64 name="w" valueReference="20" causality="input" start="1 2"><Dimension start="3"/></Float64>"#,
                r#"array "w" has 3 elements but 2 start values"#,
            ),
        ];
        for (variable, expected) in refused {
            let message = ModelDescription::parse(&with(variable)).expect_err(variable).to_string();
            assert!(message.contains(expected), "{message}");
        }
    }

    #[test]
    fn model_exchange_fmus_of_either_version_are_refused_saying_so() {
        for xml in [GOOD.replace("<CoSimulation", "<ModelExchange"), FMI3.replace("<CoSimulation", "<ModelExchange")] {
            let message = ModelDescription::parse(&xml).expect_err("Model Exchange").to_string();
            assert!(message.contains("a Model Exchange FMU: this importer runs Co-Simulation FMUs only"), "{message}");
        }
        let message = ModelDescription::parse(&FMI3.replace(r#"fmiVersion="3.0""#, r#"fmiVersion="1.0""#))
            .expect_err("FMI 1.0")
            .to_string();
        assert!(message.contains(r#"FMI "2.0" and "3.0" are supported"#), "{message}");
    }
}
