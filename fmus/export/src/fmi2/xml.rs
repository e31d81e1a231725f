//! FMI 2.0 `modelDescription.xml` and its GUID, rendered from the variable table (the parts both
//! versions share are in [`crate::description`]).

use crate::description::{self, write_variable_attributes, Description, Dialect};
use crate::model::{Model, ModelInfo};
use crate::variables::{Causality, Value, Variable};
use std::fmt::Write;

/// What the FMI 2.0 description spells its own way.
pub struct Fmi2;

/// Renders the FMI 2.0 model description of `M` (with its GUID) or says which unit is
/// undeclared.
pub fn render<M: Model>() -> Result<Description, String> {
    description::render::<Fmi2, M>()
}

impl Dialect for Fmi2 {
    fn write_head(x: &mut String, info: &ModelInfo, guid: &str) {
        let _ = writeln!(
            x,
            concat!(
                r#"<fmiModelDescription fmiVersion="2.0" modelName="{id}" guid="{guid}" description="{desc}" "#,
                r#"generationTool="fmi2-rs {ver}" version="{ver}" variableNamingConvention="structured" "#,
                r#"numberOfEventIndicators="0">"#,
            ),
            id = info.model_identifier,
            guid = guid,
            desc = description::escape(info.description),
            ver = env!("CARGO_PKG_VERSION"),
        );
        let _ = writeln!(
            x,
            concat!(
                r#"  <CoSimulation modelIdentifier="{}" needsExecutionTool="false" "#,
                r#"canHandleVariableCommunicationStepSize="true" canInterpolateInputs="{}" "#,
                r#"maxOutputDerivativeOrder="0" canRunAsynchronuously="false" "#,
                r#"canBeInstantiatedOnlyOncePerProcess="false" canNotUseMemoryManagementFunctions="true" "#,
                r#"canGetAndSetFMUstate="true" canSerializeFMUstate="true" providesDirectionalDerivative="false"/>"#,
            ),
            info.model_identifier, info.can_interpolate_inputs
        );
    }

    /// Each variable as a `<ScalarVariable>` with its 1-based index (which the model structure
    /// refers to) in a comment, and its type as a child element.
    fn write_variables<M>(x: &mut String, vars: &[Variable<M>]) {
        for (i, v) in vars.iter().enumerate() {
            let _ = write!(x, "    <!-- index {} -->\n    <ScalarVariable", i + 1);
            write_variable_attributes(x, v);
            x.push_str(">\n      ");
            let element = match v.value {
                Value::Real { .. } => "Real",
                Value::Integer { .. } => "Integer",
                Value::Boolean { .. } => "Boolean",
                Value::String { .. } => "String",
            };
            let _ = write!(x, "<{element}");
            description::write_value_attributes(x, v, true);
            x.push_str("/>\n    </ScalarVariable>\n");
        }
    }

    /// Outputs and initial unknowns by index: every output (all have `initial="calculated"`) and
    /// calculated parameter; dependencies are omitted, which FMI 2.0 reads as "depends on all
    /// knowns". An empty list is left out.
    fn write_structure<M>(x: &mut String, vars: &[Variable<M>]) {
        let outputs = description::positions(vars, |v| v.causality == Causality::Output);
        let unknowns =
            description::positions(vars, |v| matches!(v.causality, Causality::Output | Causality::CalculatedParameter));
        for (list, indices) in [("Outputs", outputs), ("InitialUnknowns", unknowns)] {
            if indices.is_empty() {
                continue;
            }
            let _ = writeln!(x, "    <{list}>");
            for i in indices {
                let _ = writeln!(x, r#"      <Unknown index="{i}"/>"#);
            }
            let _ = writeln!(x, "    </{list}>");
        }
    }
}
