//! One built FMU library, loaded through the importer's loader, with what its model description
//! says a host needs: the GUID and the value references of each type.

use fmu_import::fmi::Library;
use fmu_import::fmu::ModelDescription;
use fmu_import::value::VariableType;
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

/// The value references of one FMU, by type.
#[derive(Debug, Clone, Default)]
pub struct References {
    pub real: Vec<u32>,
    pub integer: Vec<u32>,
    pub boolean: Vec<u32>,
    pub string: Vec<u32>,
}

pub struct Fmu {
    pub model: String,
    pub library: Library,
    pub guid: CString,
    pub references: References,
}

impl Fmu {
    /// Loads `target/release/lib<model>.so` and reads its model description.
    pub fn load(model: &str) -> Result<Fmu, String> {
        let path = library_path(model);
        // SAFETY: one of this project's FMU libraries.
        let library = unsafe { Library::load(&path) }.map_err(|e| format!("{e} (run `cargo xtask package` first)"))?;
        // Opened again while loaded, the library is not read a second time.
        let xml = description(&path)?;
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
        Ok(Fmu { model: model.to_string(), library, guid, references })
    }
}

/// The model description the library at `path` (already loaded) renders
/// (`fmi2rs_model_description`), as the packager reads it.
fn description(path: &Path) -> Result<String, String> {
    // SAFETY: one of this project's FMU libraries; the function writes at most `size` bytes.
    unsafe {
        let library = libloading::Library::new(path)
            .map_err(|e| format!("{}: {e} (run `cargo xtask package` first)", path.display()))?;
        let describe: libloading::Symbol<unsafe extern "C" fn(*mut c_char, usize) -> usize> =
            library.get(b"fmi2rs_model_description").map_err(|e| e.to_string())?;
        let mut buffer = vec![0u8; describe(std::ptr::null_mut(), 0)];
        describe(buffer.as_mut_ptr() as *mut c_char, buffer.len());
        let text = CStr::from_bytes_until_nul(&buffer).map_err(|e| e.to_string())?;
        Ok(text.to_string_lossy().into_owned())
    }
}

#[cfg(test)]
mod tests {
    use super::models_in_index;

    #[test]
    fn the_models_are_the_index_entries_and_an_empty_or_broken_index_is_refused() {
        let index = r#"{ "fmus": [ { "model_identifier": "crane", "archive": "crane.fmu" },
                                   { "model_identifier": "imu" } ] }"#;
        assert_eq!(models_in_index(index).unwrap(), ["crane", "imu"]);
        assert_eq!(models_in_index(r#"{ "fmus": [] }"#).unwrap_err(), "no FMU listed");
        assert!(models_in_index(r#"{ "fmus": [ { "archive": "x.fmu" } ] }"#).unwrap_err().contains("model_identifier"));
        assert!(models_in_index("[]").unwrap_err().contains("\"fmus\""));
    }
}
