//! `modelDescription.xml` and the GUID, rendered from the variable table.

use crate::model::Model;
use crate::variables::{Causality, Value, Variability, Variable};
use std::fmt::Write;
use std::sync::OnceLock;

/// The rendered model description and the GUID it carries.
pub struct Description {
    pub xml: String,
    pub guid: String,
}

/// SI decomposition of every unit the FMUs use: (name, base-unit attributes).
/// A unit missing here is a programming error reported by [`render`].
const UNITS: &[(&str, &str)] = &[
    ("m", r#"m="1""#),
    ("m/s", r#"m="1" s="-1""#),
    ("m/s2", r#"m="1" s="-2""#),
    ("s", r#"s="1""#),
    ("1/s", r#"s="-1""#),
    ("rad", r#"rad="1""#),
    ("rad/s", r#"rad="1" s="-1""#),
    ("rad/s2", r#"rad="1" s="-2""#),
    ("deg", r#"rad="1" factor="0.017453292519943295""#),
    ("kg", r#"kg="1""#),
    ("N", r#"kg="1" m="1" s="-2""#),
    ("V", r#"kg="1" m="2" s="-3" A="-1""#),
    ("T", r#"kg="1" s="-2" A="-1""#),
    ("Hz", r#"s="-1""#),
    ("m/rad", r#"m="1" rad="-1""#),
    ("V/m", r#"kg="1" m="1" s="-3" A="-1""#),
    ("V/(m.s)", r#"kg="1" m="1" s="-4" A="-1""#),
    ("V.s/m", r#"kg="1" m="1" s="-2" A="-1""#),
    ("1/deg", r#"rad="-1" factor="57.29577951308232""#),
    ("1/(deg.s)", r#"rad="-1" s="-1" factor="57.29577951308232""#),
    ("s/deg", r#"rad="-1" s="1" factor="57.29577951308232""#),
    ("deg/s2", r#"rad="1" s="-2" factor="0.017453292519943295""#),
    ("mm/(V.s2)", r#"kg="-1" m="-1" s="1" A="1" factor="0.001""#),
    ("Pa", r#"kg="1" m="-1" s="-2""#),
    ("m3/s", r#"m="3" s="-1""#),
    ("W", r#"kg="1" m="2" s="-3""#),
    ("N.m", r#"kg="1" m="2" s="-2""#),
    ("kg.m2", r#"kg="1" m="2""#),
    ("1/m2", r#"m="-2""#),
    ("s2/m2", r#"m="-2" s="2""#),
    ("1", ""),
];

/// Renders the model description of `M` (with its GUID) or says which unit is undeclared.
pub fn render<M: Model>() -> Result<Description, String> {
    let body = render_with_guid::<M>("@GUID@")?;
    let guid = guid_of(&body);
    Ok(Description { xml: body.replace("@GUID@", guid.as_str()), guid: guid.as_str().to_owned() })
}

/// A GUID as its 38 ASCII characters `{xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx}`, held inline: an
/// FMU library caches it in a static, and a static that owned heap memory would leak that
/// memory at every unload of the library (Rust runs no destructors of statics at `dlclose`).
#[derive(Clone, Copy)]
pub struct Guid([u8; uuid::fmt::Braced::LENGTH]);

impl Guid {
    pub fn as_str(&self) -> &str {
        // The bytes were written by `Braced::encode_lower`, which writes ASCII only.
        std::str::from_utf8(&self.0).unwrap_or_default()
    }
}

/// The GUID is a name-based UUID of the whole rendered description, so any change of the table
/// (a renamed port, a new start value) changes it and a stale XML fails at `fmi2Instantiate`.
fn guid_of(text: &str) -> Guid {
    let namespace = uuid::Uuid::NAMESPACE_OID;
    let mut bytes = [0; uuid::fmt::Braced::LENGTH];
    uuid::Uuid::new_v5(&namespace, text.as_bytes()).braced().encode_lower(&mut bytes);
    Guid(bytes)
}

/// The GUID of `M`, rendered at the first call and then kept in `cache` (no heap memory, see
/// [`Guid`]); an error says why the description cannot be rendered.
pub fn cached_guid<M: Model>(cache: &'static OnceLock<Guid>) -> Result<&'static str, String> {
    if let Some(guid) = cache.get() {
        return Ok(guid.as_str());
    }
    let guid = guid_of(&render_with_guid::<M>("@GUID@")?);
    Ok(cache.get_or_init(|| guid).as_str())
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
    x.push_str("  <LogCategories>\n");
    for (name, what) in crate::instance::LOG_CATEGORIES {
        let _ = writeln!(x, r#"    <Category name="{name}" description="{what}"/>"#);
    }
    x.push_str("  </LogCategories>\n");
    let _ = writeln!(
        x,
        r#"  <DefaultExperiment startTime="0" stopTime="{:?}" stepSize="{:?}"/>"#,
        info.default_stop_time, info.default_step_size
    );
    x.push_str("  <ModelVariables>\n");
    for (i, v) in vars.iter().enumerate() {
        render_variable(&mut x, i + 1, v);
    }
    x.push_str("  </ModelVariables>\n");
    render_structure(&mut x, vars);
    x.push_str("</fmiModelDescription>\n");
    Ok(x)
}

fn render_units<M>(x: &mut String, vars: &[Variable<M>]) -> Result<(), String> {
    let mut used: Vec<&str> = vars
        .iter()
        .filter_map(|v| match v.value {
            Value::Real { unit, .. } if !unit.is_empty() => Some(unit),
            _ => None,
        })
        .collect();
    used.sort_unstable();
    used.dedup();
    if used.is_empty() {
        return Ok(());
    }
    x.push_str("  <UnitDefinitions>\n");
    for unit in used {
        let (_, base) = UNITS
            .iter()
            .find(|(n, _)| *n == unit)
            .ok_or_else(|| format!("unit '{unit}' has no SI decomposition in fmi2::xml::UNITS"))?;
        if base.is_empty() {
            let _ = writeln!(x, r#"    <Unit name="{unit}"/>"#);
        } else {
            let _ = writeln!(x, r#"    <Unit name="{unit}"><BaseUnit {base}/></Unit>"#);
        }
    }
    x.push_str("  </UnitDefinitions>\n");
    Ok(())
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
    let start = v.has_start();
    match &v.value {
        Value::Real { unit, start: s, min, max, .. } => {
            x.push_str("<Real");
            if !unit.is_empty() {
                let _ = write!(x, r#" unit="{unit}""#);
            }
            if let Some(m) = min {
                let _ = write!(x, r#" min="{m:?}""#);
            }
            if let Some(m) = max {
                let _ = write!(x, r#" max="{m:?}""#);
            }
            if start {
                let _ = write!(x, r#" start="{s:?}""#);
            }
        }
        Value::Integer { start: s, min, max, .. } => {
            x.push_str("<Integer");
            if let Some(m) = min {
                let _ = write!(x, r#" min="{m}""#);
            }
            if let Some(m) = max {
                let _ = write!(x, r#" max="{m}""#);
            }
            if start {
                let _ = write!(x, r#" start="{s}""#);
            }
        }
        Value::Boolean { start: s, .. } => {
            x.push_str("<Boolean");
            if start {
                let _ = write!(x, r#" start="{s}""#);
            }
        }
        Value::String { start: s, .. } => {
            x.push_str("<String");
            if start {
                let _ = write!(x, r#" start="{}""#, escape(s));
            }
        }
    }
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

fn positions<M>(vars: &[Variable<M>], keep: impl Fn(&Variable<M>) -> bool) -> Vec<usize> {
    vars.iter().enumerate().filter(|(_, v)| keep(v)).map(|(i, _)| i + 1).collect()
}

fn causality_name(c: Causality) -> &'static str {
    match c {
        Causality::Parameter => "parameter",
        Causality::CalculatedParameter => "calculatedParameter",
        Causality::Input => "input",
        Causality::Output => "output",
        Causality::Local => "local",
    }
}

/// FMI 2.0 `initial`, derived from the causality (never written by hand, so the combinations
/// the standard forbids cannot occur); `None`: the attribute is omitted, as for inputs.
fn initial_name(c: Causality) -> Option<&'static str> {
    match c {
        Causality::Parameter => Some("exact"),
        Causality::Input => None,
        Causality::Output | Causality::CalculatedParameter | Causality::Local => Some("calculated"),
    }
}

fn variability_name(v: Variability) -> &'static str {
    match v {
        Variability::Constant => "constant",
        Variability::Fixed => "fixed",
        Variability::Tunable => "tunable",
        Variability::Discrete => "discrete",
        Variability::Continuous => "continuous",
    }
}

/// The tables' own text, escaped by the one escaper both sides share.
fn escape(s: &str) -> std::borrow::Cow<'_, str> {
    common::markup::escape_own(s)
}
