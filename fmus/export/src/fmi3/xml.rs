//! FMI 3.0 `modelDescription.xml` and its instantiation token, rendered from the same variable
//! table as the FMI 2.0 description (the shared parts are in [`crate::description`]).

use crate::description::{self, escape, write_value_attributes, write_variable_attributes, Description, Dialect};
use crate::model::{Model, ModelInfo};
use crate::variables::{Causality, Value, Variable};
use std::collections::BTreeMap;
use std::fmt::Write;

/// The value reference of the independent variable `time` that every FMI 3.0 description
/// declares: outside the blocks the tables number their variables in (the largest `int32`, so
/// importers that hold value references in signed integers read it too).
pub const TIME_VR: u32 = i32::MAX as u32;

/// What the FMI 3.0 description spells its own way.
pub struct Fmi3;

/// Renders the FMI 3.0 model description of `M` (with its instantiation token) or says why it
/// cannot be rendered (an undeclared unit, a value reference used twice).
pub fn render<M: Model>() -> Result<Description, String> {
    description::render::<Fmi3, M>()
}

impl Dialect for Fmi3 {
    fn render<M: Model>(token: &str) -> Result<String, String> {
        check_unique_value_references(M::variables())?;
        description::render_document::<Self, M>(token)
    }

    fn write_head(x: &mut String, info: &ModelInfo, token: &str) {
        let _ = writeln!(
            x,
            concat!(
                r#"<fmiModelDescription fmiVersion="3.0" modelName="{id}" instantiationToken="{token}" "#,
                r#"description="{desc}" generationTool="fmu-export {ver}" version="{ver}" "#,
                r#"variableNamingConvention="structured">"#,
            ),
            id = info.model_identifier,
            token = token,
            desc = escape(info.description),
            ver = env!("CARGO_PKG_VERSION"),
        );
        let _ = writeln!(
            x,
            concat!(
                r#"  <CoSimulation modelIdentifier="{}" needsExecutionTool="false" "#,
                r#"canBeInstantiatedOnlyOncePerProcess="false" canGetAndSetFMUState="true" "#,
                r#"canSerializeFMUState="true" providesDirectionalDerivatives="false" "#,
                r#"providesAdjointDerivatives="false" providesPerElementDependencies="false" "#,
                r#"canHandleVariableCommunicationStepSize="true" maxOutputDerivativeOrder="0" "#,
                r#"providesIntermediateUpdate="false" mightReturnEarlyFromDoStep="false" "#,
                r#"canReturnEarlyAfterIntermediateUpdate="false" hasEventMode="false" "#,
                r#"providesEvaluateDiscreteStates="false"/>"#,
            ),
            info.model_identifier
        );
    }

    /// The independent variable `time` first, then each variable as the element of its type.
    fn write_variables<M>(x: &mut String, vars: &[Variable<M>]) {
        let _ = writeln!(
            x,
            r#"    <Float64 name="time" valueReference="{TIME_VR}" description="Simulation time" causality="independent" variability="continuous"/>"#
        );
        for v in vars {
            render_variable(x, v);
        }
    }

    /// Outputs and initial unknowns by value reference: every output (all have
    /// `initial="calculated"`) and calculated parameter; dependencies are omitted, which FMI 3.0
    /// reads as "depends on all knowns".
    fn write_structure<M>(x: &mut String, vars: &[Variable<M>]) {
        for v in vars.iter().filter(|v| v.causality == Causality::Output) {
            let _ = writeln!(x, r#"    <Output valueReference="{}"/>"#, v.vr);
        }
        for v in vars.iter().filter(|v| matches!(v.causality, Causality::Output | Causality::CalculatedParameter)) {
            let _ = writeln!(x, r#"    <InitialUnknown valueReference="{}"/>"#, v.vr);
        }
    }
}

/// FMI 3.0 value references are unique across all types (FMI 2.0's are unique per type), and
/// `time` takes [`TIME_VR`].
fn check_unique_value_references<M>(vars: &[Variable<M>]) -> Result<(), String> {
    // A BTreeMap, not a HashMap: a HashMap seeds its hasher from the OS, which on Windows makes the
    // DLL import bcryptprimitives.dll (missing from older Wine and some embedded Windows).
    let mut seen: BTreeMap<u32, &str> = BTreeMap::from([(TIME_VR, "time")]);
    for v in vars {
        if let Some(other) = seen.insert(v.vr, v.name) {
            return Err(format!(
                "value reference {} is used by '{other}' and '{}': FMI 3.0 needs one value reference per variable",
                v.vr, v.name
            ));
        }
    }
    Ok(())
}

/// The FMI 3.0 element name of a variable's type.
pub fn type_name<M>(v: &Variable<M>) -> &'static str {
    match v.value {
        Value::Real { .. } => "Float64",
        Value::Integer { .. } => "Int32",
        Value::Boolean { .. } => "Boolean",
        Value::String { .. } => "String",
    }
}

fn render_variable<M>(x: &mut String, v: &Variable<M>) {
    let element = type_name(v);
    let _ = write!(x, "    <{element}");
    write_variable_attributes(x, v);
    write_value_attributes(x, v, false);
    match v.value {
        Value::String { start, .. } if v.has_start() => {
            let _ = writeln!(x, ">\n      <Start value=\"{}\"/>\n    </{element}>", escape(start));
        }
        _ => x.push_str("/>\n"),
    }
}
