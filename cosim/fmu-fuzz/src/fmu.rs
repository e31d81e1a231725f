//! One built FMU library, loaded through the importer's loader, with what its model description
//! says a host needs: the GUID and the value references of each type.

use fmu_import::fmi::Library;
use fmu_import::fmu::ModelDescription;
use fmu_import::value::VariableType;
use std::ffi::{c_char, CStr, CString};
use std::path::{Path, PathBuf};

/// `target/release/lib<model>.so`, which `cargo xtask package` (and so `cargo xtask test`, before
/// the integration tests) builds.
pub fn library_path(model: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../../target/release/lib{model}.so"))
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
    pub model: &'static str,
    pub library: Library,
    pub guid: CString,
    pub references: References,
}

impl Fmu {
    /// Loads `target/release/lib<model>.so` and reads its model description.
    pub fn load(model: &'static str) -> Result<Fmu, String> {
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
        Ok(Fmu { model, library, guid, references })
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
