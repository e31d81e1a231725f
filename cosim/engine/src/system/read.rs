//! Step 1 of loading a system: the file's bytes, as text, an extracted SSP archive or an opened
//! FMU. Nothing is interpreted yet, but a file or folder no system can be read from is refused
//! saying what it is ([`SystemError::Kind`]).

use std::io::Read;
use std::path::{Path, PathBuf};

use fmu_import::file::{open_regular, read_regular_text, MAX_TEXT_FILE_BYTES};
use fmu_import::fmu::Fmu;

use super::{osp, ssp, SystemError, SystemFiles};

/// What a system, scenario, SSP or OSP file holds before it is parsed.
#[derive(Debug)]
pub(super) enum Source {
    /// A system file or a scenario file (JSON), told apart when parsed.
    Json(String),
    /// An SSP archive extracted to this folder (deleted when dropped).
    Ssp(tempfile::TempDir),
    /// XML text (an OSP system structure, or XML of another kind refused when parsed) and the
    /// folder its paths are relative to.
    Xml { text: String, folder: PathBuf },
}

/// Reads `file`: an `.ssp` archive is extracted (within [`SystemFiles::limits`]), a folder is read
/// as an OSP system structure ([`osp::FILE`] in it), any other file as JSON or XML text.
pub(super) fn read(file: &Path, files: &SystemFiles) -> Result<Source, SystemError> {
    if ssp::is_ssp(file) {
        return ssp::extract(file, files.limits()).map(Source::Ssp);
    }
    if file.is_dir() {
        let structure = file.join(osp::FILE);
        if !structure.is_file() {
            let found = format!("a folder without {}", osp::FILE);
            return Err(SystemError::Kind { file: file.to_path_buf(), found });
        }
        let text = read_text(&structure)?;
        return Ok(Source::Xml { text, folder: file.to_path_buf() });
    }
    if let Some(found) = binary_kind(file) {
        return Err(SystemError::Kind { file: file.to_path_buf(), found });
    }
    let text = read_text(file)?;
    if osp::is_xml(&text) {
        let folder = file.parent().unwrap_or_else(|| Path::new("")).to_path_buf();
        return Ok(Source::Xml { text, folder });
    }
    Ok(Source::Json(text))
}

fn read_text(file: &Path) -> Result<String, SystemError> {
    read_system_text(file).map_err(|source| SystemError::Read { file: file.to_path_buf(), source })
}

/// What `file` is when it is no text: an FMU, an SSP archive not named `.ssp`, another zip
/// archive or binary data. `None` for text (and for files that cannot be opened: reading them
/// says why).
fn binary_kind(file: &Path) -> Option<String> {
    let mut head = Vec::new();
    open_regular(file).ok()?.take(4096).read_to_end(&mut head).ok()?;
    if head.starts_with(b"PK\x03\x04") || head.starts_with(b"PK\x05\x06") {
        return Some(zip_kind(file));
    }
    let invalid = match std::str::from_utf8(&head) {
        // A character cut at the end of the head is no sign of binary data.
        Err(error) => error.error_len().is_some(),
        Ok(_) => false,
    };
    (invalid || head.contains(&0)).then(|| "binary data, not text".to_string())
}

/// What a zip archive holds: an FMU (`modelDescription.xml`), an SSP archive (`SystemStructure.ssd`).
fn zip_kind(file: &Path) -> String {
    let names: Vec<String> = std::fs::File::open(file)
        .ok()
        .and_then(|f| zip::ZipArchive::new(f).ok())
        .map(|archive| archive.file_names().map(str::to_string).collect())
        .unwrap_or_default();
    if names.iter().any(|n| n == "modelDescription.xml") {
        "an FMU (a zip archive holding modelDescription.xml)".into()
    } else if names.iter().any(|n| n == ssp::SSD_FILE) {
        format!("an SSP archive (a zip archive holding {}) whose name does not end in .ssp", ssp::SSD_FILE)
    } else {
        "a zip archive".into()
    }
}

/// Opens the `.fmu` file of a single-FMU run (extraction and model description only).
pub(super) fn read_fmu(file: &Path, files: &SystemFiles) -> Result<Fmu, SystemError> {
    Ok(files.fmu(file)?)
}

/// A system or scenario file's text: a regular file of at most [`MAX_TEXT_FILE_BYTES`], in UTF-8.
pub(super) fn read_system_text(file: &Path) -> std::io::Result<String> {
    read_regular_text(file, MAX_TEXT_FILE_BYTES)
}
