//! What both model descriptions (FMI 2.0 and FMI 3.0) share: the unit table, the GUID or
//! instantiation token (a name-based UUID of the rendered text, cached without heap memory),
//! the spelling of causality, variability and `initial`, and the escaping of the tables' text.

use crate::variables::{Causality, Value, Variability, Variable};
use std::fmt::Write;
use std::sync::OnceLock;

/// The rendered model description and the GUID it carries.
pub struct Description {
    pub xml: String,
    pub guid: String,
}

/// SI decomposition of every unit the FMUs use: (name, base-unit attributes).
/// A unit missing here is a programming error reported by the renderers.
pub const UNITS: &[(&str, &str)] = &[
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
    ("m3/rad", r#"m="3" rad="-1""#),
    ("W", r#"kg="1" m="2" s="-3""#),
    ("N.m", r#"kg="1" m="2" s="-2""#),
    ("kg.m2", r#"kg="1" m="2""#),
    ("1/m2", r#"m="-2""#),
    ("s2/m2", r#"m="-2" s="2""#),
    ("1", ""),
];

/// Where the GUID goes in the text it is the hash of.
const PLACEHOLDER: &str = "@GUID@";

/// Renders a description with `render_with_guid` (the text with the given placeholder where the
/// GUID goes), then puts the GUID of that text in.
pub fn with_guid(render_with_guid: impl Fn(&str) -> Result<String, String>) -> Result<Description, String> {
    let body = render_with_guid(PLACEHOLDER)?;
    let guid = guid_of(&body);
    Ok(Description { xml: body.replace(PLACEHOLDER, guid.as_str()), guid: guid.as_str().to_owned() })
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
/// (a renamed port, a new start value) changes it and a stale XML fails at instantiation.
fn guid_of(text: &str) -> Guid {
    let namespace = uuid::Uuid::NAMESPACE_OID;
    let mut bytes = [0; uuid::fmt::Braced::LENGTH];
    uuid::Uuid::new_v5(&namespace, text.as_bytes()).braced().encode_lower(&mut bytes);
    Guid(bytes)
}

/// The GUID of the description `render_with_guid` renders, rendered at the first call and then
/// kept in `cache` (no heap memory, see [`Guid`]); an error says why the description cannot be
/// rendered.
pub fn cached_guid(
    cache: &'static OnceLock<Guid>,
    render_with_guid: impl Fn(&str) -> Result<String, String>,
) -> Result<&'static str, String> {
    if let Some(guid) = cache.get() {
        return Ok(guid.as_str());
    }
    let guid = guid_of(&render_with_guid(PLACEHOLDER)?);
    Ok(cache.get_or_init(|| guid).as_str())
}

/// The parts in which the FMI 2.0 and FMI 3.0 model descriptions differ; [`render_document`]
/// puts them into the frame both share, so that the order of the sections (which both schemas
/// prescribe alike) is written once.
pub trait Dialect {
    /// Renders the description of `M` with `guid` (the GUID or instantiation token) in it, or
    /// says why it cannot be rendered; what a version checks before rendering goes here.
    fn render<M: crate::model::Model>(guid: &str) -> Result<String, String> {
        render_document::<Self, M>(guid)
    }

    /// `<fmiModelDescription …>` and `<CoSimulation …/>`, each on its own line.
    fn write_head(x: &mut String, info: &crate::model::ModelInfo, guid: &str);

    /// The children of `<ModelVariables>`.
    fn write_variables<M>(x: &mut String, vars: &[Variable<M>]);

    /// The children of `<ModelStructure>`.
    fn write_structure<M>(x: &mut String, vars: &[Variable<M>]);
}

/// Renders the model description of `M` in dialect `D` (with its GUID), or says why it cannot
/// be rendered.
pub fn render<D: Dialect, M: crate::model::Model>() -> Result<Description, String> {
    with_guid(D::render::<M>)
}

/// The GUID of `M`'s description in dialect `D`, rendered once and kept in `cache`.
pub fn cached<D: Dialect, M: crate::model::Model>(cache: &'static OnceLock<Guid>) -> Result<&'static str, String> {
    cached_guid(cache, D::render::<M>)
}

/// The whole description of `M` in dialect `D`: the XML declaration, the head, the units, log
/// categories and default experiment, the variables and the model structure.
pub fn render_document<D: Dialect + ?Sized, M: crate::model::Model>(guid: &str) -> Result<String, String> {
    let info = &M::INFO;
    let vars = M::variables();
    let mut x = String::new();
    let _ = writeln!(x, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    D::write_head(&mut x, info, guid);
    render_units(&mut x, vars)?;
    write_log_categories_and_experiment(&mut x, crate::logging::LOG_CATEGORIES, info);
    x.push_str("  <ModelVariables>\n");
    D::write_variables(&mut x, vars);
    x.push_str("  </ModelVariables>\n");
    x.push_str("  <ModelStructure>\n");
    D::write_structure(&mut x, vars);
    x.push_str("  </ModelStructure>\n");
    x.push_str("</fmiModelDescription>\n");
    Ok(x)
}

/// The attributes every variable element opens with in both versions: name, value reference,
/// description, causality, variability and (derived from the causality) `initial`.
pub fn write_variable_attributes<M>(x: &mut String, v: &Variable<M>) {
    let _ = write!(
        x,
        r#" name="{}" valueReference="{}" description="{}" causality="{}" variability="{}""#,
        escape(v.name),
        v.vr,
        escape(v.description),
        causality_name(v.causality),
        variability_name(v.variability)
    );
    if let Some(initial) = initial_name(v.causality) {
        let _ = write!(x, r#" initial="{initial}""#);
    }
}

pub fn render_units<M>(x: &mut String, vars: &[Variable<M>]) -> Result<(), String> {
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
            .ok_or_else(|| format!("unit '{unit}' has no SI decomposition in fmu_export::description::UNITS"))?;
        if base.is_empty() {
            let _ = writeln!(x, r#"    <Unit name="{unit}"/>"#);
        } else {
            let _ = writeln!(x, r#"    <Unit name="{unit}"><BaseUnit {base}/></Unit>"#);
        }
    }
    x.push_str("  </UnitDefinitions>\n");
    Ok(())
}

pub fn positions<M>(vars: &[Variable<M>], keep: impl Fn(&Variable<M>) -> bool) -> Vec<usize> {
    vars.iter().enumerate().filter(|(_, v)| keep(v)).map(|(i, _)| i + 1).collect()
}

pub fn causality_name(c: Causality) -> &'static str {
    match c {
        Causality::Parameter => "parameter",
        Causality::CalculatedParameter => "calculatedParameter",
        Causality::Input => "input",
        Causality::Output => "output",
        Causality::Local => "local",
    }
}

/// `initial` (the same rule in FMI 2.0 and 3.0), derived from the causality (never written by hand, so the combinations
/// the standard forbids cannot occur); `None`: the attribute is omitted, as for inputs.
pub fn initial_name(c: Causality) -> Option<&'static str> {
    match c {
        Causality::Parameter => Some("exact"),
        Causality::Input => None,
        Causality::Output | Causality::CalculatedParameter | Causality::Local => Some("calculated"),
    }
}

pub fn variability_name(v: Variability) -> &'static str {
    match v {
        Variability::Constant => "constant",
        Variability::Fixed => "fixed",
        Variability::Tunable => "tunable",
        Variability::Discrete => "discrete",
        Variability::Continuous => "continuous",
    }
}

/// The tables' own text, escaped by the one escaper both sides share.
pub fn escape(s: &str) -> std::borrow::Cow<'_, str> {
    common::markup::escape_own(s)
}

/// The type attributes of `v` (unit, range, start), as FMI 2.0's type element and FMI 3.0's
/// variable element both spell them; a String's start only if `string_start_attribute` (FMI 3.0
/// gives it as a `<Start value=…/>` child instead).
pub fn write_value_attributes<M>(x: &mut String, v: &Variable<M>, string_start_attribute: bool) {
    let start = v.has_start();
    match &v.value {
        Value::Real { unit, start: s, min, max, .. } => {
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
            if start {
                let _ = write!(x, r#" start="{s}""#);
            }
        }
        Value::String { start: s, .. } => {
            if start && string_start_attribute {
                let _ = write!(x, r#" start="{}""#, escape(s));
            }
        }
    }
}

/// `<LogCategories>` (`categories`: name, description) and `<DefaultExperiment>`, spelled alike in
/// FMI 2.0 and 3.0.
pub fn write_log_categories_and_experiment(
    x: &mut String,
    categories: &[(&str, &str)],
    info: &crate::model::ModelInfo,
) {
    x.push_str("  <LogCategories>\n");
    for (name, what) in categories {
        let _ = writeln!(x, r#"    <Category name="{name}" description="{what}"/>"#);
    }
    x.push_str("  </LogCategories>\n");
    let _ = writeln!(
        x,
        r#"  <DefaultExperiment startTime="0" stopTime="{:?}" stepSize="{:?}"/>"#,
        info.default_stop_time, info.default_step_size
    );
}
