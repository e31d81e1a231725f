//! FMI 2.0 `modelDescription.xml` and its GUID, rendered from the variable table (the parts both
//! versions share are in [`crate::description`]).

use crate::description::{
    self, causality_name, escape, initial_name, positions, render_units, variability_name, Description, Guid,
};
use crate::model::Model;
use crate::variables::{Causality, Value, Variable};
use std::fmt::Write;
use std::sync::OnceLock;

/// Renders the FMI 2.0 model description of `M` (with its GUID) or says which unit is
/// undeclared.
pub fn render<M: Model>() -> Result<Description, String> {
    description::with_guid(render_with_guid::<M>)
}

/// The GUID of `M`'s FMI 2.0 description, rendered once and kept in `cache`.
pub fn cached_guid<M: Model>(cache: &'static OnceLock<Guid>) -> Result<&'static str, String> {
    description::cached_guid(cache, render_with_guid::<M>)
}

fn render_with_guid<M: Model>(guid: &str) -> Result<String, String> {
    let info = &M::INFO;
    let vars = M::variables();
    let mut x = String::new();
    let _ = writeln!(x, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        x,
        concat!(
            r#"<fmiModelDescription fmiVersion="2.0" modelName="{id}" guid="{guid}" description="{desc}" "#,
            r#"generationTool="fmi2-rs {ver}" version="{ver}" variableNamingConvention="structured" "#,
            r#"numberOfEventIndicators="0">"#,
        ),
        id = info.model_identifier,
        guid = guid,
        desc = escape(info.description),
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
    render_units(&mut x, vars)?;
    description::write_log_categories_and_experiment(&mut x, crate::instance::LOG_CATEGORIES, info);
    x.push_str("  <ModelVariables>\n");
    for (i, v) in vars.iter().enumerate() {
        render_variable(&mut x, i + 1, v);
    }
    x.push_str("  </ModelVariables>\n");
    render_structure(&mut x, vars);
    x.push_str("</fmiModelDescription>\n");
    Ok(x)
}

fn render_variable<M>(x: &mut String, index: usize, v: &Variable<M>) {
    let _ = write!(
        x,
        r#"    <!-- index {index} -->
    <ScalarVariable name="{}" valueReference="{}" description="{}" causality="{}" variability="{}""#,
        escape(v.name),
        v.vr,
        escape(v.description),
        causality_name(v.causality),
        variability_name(v.variability)
    );
    if let Some(initial) = initial_name(v.causality) {
        let _ = write!(x, r#" initial="{initial}""#);
    }
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

/// Outputs and initial unknowns: every output (all have `initial="calculated"`) and calculated
/// parameter; dependencies are omitted, which FMI 2.0 reads as "depends on all knowns".
fn render_structure<M>(x: &mut String, vars: &[Variable<M>]) {
    let outputs: Vec<usize> = positions(vars, |v| v.causality == Causality::Output);
    let unknowns: Vec<usize> =
        positions(vars, |v| matches!(v.causality, Causality::Output | Causality::CalculatedParameter));
    x.push_str("  <ModelStructure>\n");
    if !outputs.is_empty() {
        x.push_str("    <Outputs>\n");
        for i in &outputs {
            let _ = writeln!(x, r#"      <Unknown index="{i}"/>"#);
        }
        x.push_str("    </Outputs>\n");
    }
    if !unknowns.is_empty() {
        x.push_str("    <InitialUnknowns>\n");
        for i in &unknowns {
            let _ = writeln!(x, r#"      <Unknown index="{i}"/>"#);
        }
        x.push_str("    </InitialUnknowns>\n");
    }
    x.push_str("  </ModelStructure>\n");
}
