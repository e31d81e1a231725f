//! One built FMU library, loaded through the importer's loader for its FMI 2.0 entry points and
//! opened for its FMI 3.0 ones ([`crate::fmi3`]), with what each version's model description
//! says a host needs: the GUID and the value references of each type (FMI 2.0), the
//! instantiation token, the variables with their causality, variability and initial, and the
//! log categories (FMI 3.0).

use crate::fmi3::{self, Library3};
use crate::table::{Causality, Initial, Kind, Variability};
use fmu_import::fmi::Library;
use fmu_import::fmu::ModelDescription;
use fmu_import::value::VariableType;
use std::collections::HashMap;
use std::ffi::{c_char, CStr, CString};
use std::path::{Path, PathBuf};

/// The workspace's `target/` (this crate is `cosim/fmu-fuzz`).
fn target_dir() -> PathBuf {
    let manifest_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest_dir.ancestors().nth(2).unwrap_or(manifest_dir).join("target")
}

/// `target/release/lib<model>.so`, which `cargo xtask package` (and so `cargo xtask test`, before
/// the integration tests) builds.
pub fn library_path(model: &str) -> PathBuf {
    target_dir().join(format!("release/lib{model}.so"))
}

/// The model identifiers of the project's FMUs, as `cargo xtask package` lists them in
/// `target/fmu/index.json` (so that no list of them is kept here).
pub fn models() -> Result<Vec<String>, String> {
    let path = target_dir().join("fmu/index.json");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| format!("{}: {e} (run `cargo xtask package` first)", path.display()))?;
    models_in_index(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// The `model_identifier` of every entry of an index.json's `fmus`.
fn models_in_index(text: &str) -> Result<Vec<String>, String> {
    let index: serde_json::Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
    let entries = index.get("fmus").and_then(|f| f.as_array()).ok_or("no \"fmus\" list")?;
    let models = entries.iter().map(|entry| {
        let name = entry.get("model_identifier").and_then(|m| m.as_str());
        name.map(str::to_string).ok_or_else(|| format!("an entry without a model_identifier: {entry}"))
    });
    let models = models.collect::<Result<Vec<_>, _>>()?;
    if models.is_empty() {
        return Err("no FMU listed".into());
    }
    Ok(models)
}

/// The API a host drives a library through.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Api {
    Fmi2,
    Fmi3,
}

impl Api {
    pub const BOTH: [Api; 2] = [Api::Fmi2, Api::Fmi3];

    pub fn name(self) -> &'static str {
        match self {
            Api::Fmi2 => "FMI 2.0",
            Api::Fmi3 => "FMI 3.0",
        }
    }

    /// The prefix of the API's names (`fmi2`, `fmi3`).
    pub fn prefix(self) -> &'static str {
        match self {
            Api::Fmi2 => "fmi2",
            Api::Fmi3 => "fmi3",
        }
    }
}

/// The value references of one FMU, by type (FMI 3.0: Float64, Int32, Boolean, String).
#[derive(Debug, Clone, Default)]
pub struct References {
    pub real: Vec<u32>,
    pub integer: Vec<u32>,
    pub boolean: Vec<u32>,
    pub string: Vec<u32>,
}

impl References {
    /// Every value reference, Reals first.
    pub fn all(&self) -> Vec<u32> {
        [&self.real, &self.integer, &self.boolean, &self.string].into_iter().flatten().copied().collect()
    }
}

/// What the FMI 3.0 model description says of the variables: the value references of each type
/// (unique across types in FMI 3.0; `time` is a Float64), the kind of each, and the log
/// categories.
#[derive(Debug, Clone, Default)]
pub struct Variables3 {
    /// The value references of each type (`real` the Float64 ones, `integer` the Int32 ones).
    pub by_type: References,
    pub kinds: HashMap<u32, Kind>,
    pub categories: Vec<CString>,
}

pub struct Fmu {
    pub model: String,
    /// The FMI 2.0 entry points.
    pub library: Library,
    pub guid: CString,
    pub references: References,
    /// The FMI 3.0 entry points (the same library).
    pub library3: Library3,
    pub token: CString,
    pub variables3: Variables3,
}

impl Fmu {
    /// Loads `target/release/lib<model>.so` and reads its model description.
    pub fn load(model: &str) -> Result<Fmu, String> {
        let path = library_path(model);
        // SAFETY: one of this project's FMU libraries.
        let library = unsafe { Library::load(&path) }.map_err(|e| format!("{e} (run `cargo xtask package` first)"))?;
        // Opened again while loaded, the library is not read a second time.
        let xml = rendered(&path, "fmi2rs_model_description")?;
        let description = ModelDescription::parse(&xml).map_err(|e| format!("{model}: {e}"))?;
        let mut references = References::default();
        for v in &description.variables {
            let list = match v.variable_type {
                VariableType::Real => &mut references.real,
                VariableType::Integer | VariableType::Enumeration => &mut references.integer,
                VariableType::Boolean => &mut references.boolean,
                VariableType::String => &mut references.string,
            };
            list.push(v.value_reference);
        }
        let guid = CString::new(description.guid).map_err(|e| e.to_string())?;
        // SAFETY: as above.
        let library3 = unsafe { Library3::load(&path) }?;
        let (token, variables3) =
            fmi3_description(&rendered(&path, "fmi3rs_model_description")?).map_err(|e| format!("{model}: {e}"))?;
        Ok(Fmu { model: model.to_string(), library, guid, references, library3, token, variables3 })
    }

    /// The FMI 3.0 entry points.
    pub fn f3(&self) -> &fmi3::Functions {
        self.library3.functions()
    }
}

/// The model description the library at `path` (already loaded) renders with `symbol`
/// (`fmi2rs_model_description` or `fmi3rs_model_description`), as the packager reads it.
fn rendered(path: &Path, symbol: &str) -> Result<String, String> {
    let symbol = CString::new(symbol).map_err(|e| e.to_string())?;
    // SAFETY: one of this project's FMU libraries; the function writes at most `size` bytes.
    unsafe {
        let library = libloading::Library::new(path)
            .map_err(|e| format!("{}: {e} (run `cargo xtask package` first)", path.display()))?;
        let describe: libloading::Symbol<unsafe extern "C" fn(*mut c_char, usize) -> usize> =
            library.get(symbol.as_bytes_with_nul()).map_err(|e| e.to_string())?;
        let mut buffer = vec![0u8; describe(std::ptr::null_mut(), 0)];
        describe(buffer.as_mut_ptr() as *mut c_char, buffer.len());
        let text = CStr::from_bytes_until_nul(&buffer).map_err(|e| e.to_string())?;
        Ok(text.to_string_lossy().into_owned())
    }
}

/// The instantiation token and the variables of an FMI 3.0 model description.
fn fmi3_description(xml: &str) -> Result<(CString, Variables3), String> {
    let document = roxmltree::Document::parse(xml).map_err(|e| e.to_string())?;
    let root = document.root_element();
    let token = root.attribute("instantiationToken").ok_or("no instantiationToken")?;
    let token = CString::new(token).map_err(|e| e.to_string())?;
    let mut variables = Variables3::default();
    let elements =
        |name: &'static str| root.children().filter(move |n| n.has_tag_name(name)).flat_map(|n| n.children());
    for category in elements("LogCategories").filter(|n| n.has_tag_name("Category")) {
        let name = category.attribute("name").ok_or("a Category without a name")?;
        variables.categories.push(CString::new(name).map_err(|e| e.to_string())?);
    }
    for v in elements("ModelVariables").filter(|n| n.is_element()) {
        let name = v.attribute("name").unwrap_or("?");
        let vr: u32 = v
            .attribute("valueReference")
            .and_then(|vr| vr.parse().ok())
            .ok_or_else(|| format!("variable '{name}' has no valueReference"))?;
        let list = match v.tag_name().name() {
            "Float64" => &mut variables.by_type.real,
            "Int32" => &mut variables.by_type.integer,
            "Boolean" => &mut variables.by_type.boolean,
            "String" => &mut variables.by_type.string,
            other => return Err(format!("variable '{name}' is a {other}, which the fuzzer does not know")),
        };
        list.push(vr);
        let kind =
            kind(v.tag_name().name(), v.attribute("causality"), v.attribute("variability"), v.attribute("initial"))
                .map_err(|e| format!("variable '{name}': {e}"))?;
        variables.kinds.insert(vr, kind);
    }
    Ok((token, variables))
}

/// A variable's kind from its attributes, with FMI 3.0's defaults (causality local, variability
/// continuous for Float64 and discrete for the other types).
fn kind(
    element: &str,
    causality: Option<&str>,
    variability: Option<&str>,
    initial: Option<&str>,
) -> Result<Kind, String> {
    let causality = match causality.unwrap_or("local") {
        "parameter" => Causality::Parameter,
        "calculatedParameter" => Causality::CalculatedParameter,
        "structuralParameter" => Causality::StructuralParameter,
        "input" => Causality::Input,
        "output" => Causality::Output,
        "local" => Causality::Local,
        "independent" => Causality::Independent,
        other => return Err(format!("causality {other}")),
    };
    let variability = variability.unwrap_or(if element == "Float64" { "continuous" } else { "discrete" });
    let variability = variability.parse::<Variability>().map_err(|()| format!("variability {variability}"))?;
    let initial = match initial {
        None => None,
        Some(text) => Some(text.parse::<Initial>().map_err(|()| format!("initial {text}"))?),
    };
    Ok(Kind { causality, variability, initial })
}

#[cfg(test)]
mod tests {
    use super::{fmi3_description, models_in_index};
    use crate::table::{Causality, Initial, Variability};

    #[test]
    fn the_models_are_the_index_entries_and_an_empty_or_broken_index_is_refused() {
        let index = r#"{ "fmus": [ { "model_identifier": "crane", "archive": "crane.fmu" },
                                   { "model_identifier": "imu" } ] }"#;
        assert_eq!(models_in_index(index).unwrap(), ["crane", "imu"]);
        assert_eq!(models_in_index(r#"{ "fmus": [] }"#).unwrap_err(), "no FMU listed");
        assert!(models_in_index(r#"{ "fmus": [ { "archive": "x.fmu" } ] }"#).unwrap_err().contains("model_identifier"));
        assert!(models_in_index("[]").unwrap_err().contains("\"fmus\""));
    }

    #[test]
    fn an_fmi3_description_gives_the_token_the_variables_by_type_and_their_kinds() {
        let xml = r#"<fmiModelDescription fmiVersion="3.0" instantiationToken="{abc}">
            <LogCategories><Category name="logCalls"/><Category name="logStatusError"/></LogCategories>
            <ModelVariables>
              <Float64 name="time" valueReference="2147483647" causality="independent" variability="continuous"/>
              <Float64 name="m" valueReference="1" causality="parameter" variability="fixed" initial="exact"/>
              <Int32 name="n" valueReference="2" causality="input"/>
              <Boolean name="b" valueReference="3" causality="output" initial="calculated"/>
              <String name="s" valueReference="4" causality="parameter" variability="tunable"><Start value="x"/></String>
            </ModelVariables></fmiModelDescription>"#;
        let (token, v) = fmi3_description(xml).unwrap();
        assert_eq!(token.to_str().unwrap(), "{abc}");
        let types = &v.by_type;
        assert_eq!((types.real.as_slice(), types.integer.as_slice()), (&[2147483647, 1][..], &[2][..]));
        assert_eq!((types.boolean.as_slice(), types.string.as_slice()), (&[3][..], &[4][..]));
        assert_eq!(v.kinds[&2147483647].causality, Causality::Independent);
        assert_eq!(v.kinds[&1].initial, Some(Initial::Exact));
        assert_eq!(v.kinds[&2].variability, Variability::Discrete, "the default of an Int32");
        assert_eq!(v.kinds[&4].variability, Variability::Tunable);
        assert_eq!(v.categories.len(), 2);
        assert!(fmi3_description(&xml.replace("Int32", "UInt8")).unwrap_err().contains("UInt8"));
    }
}
