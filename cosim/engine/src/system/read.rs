//! Step 1 of loading a system: the file's bytes, as text, an extracted SSP archive or an opened
//! FMU. Nothing is interpreted yet.

use std::path::Path;

use fmu_import::file::{read_regular_text, MAX_TEXT_FILE_BYTES};
use fmu_import::fmu::Fmu;

use super::{ssp, SystemError, SystemFiles};

/// What a system, scenario or SSP file holds before it is parsed.
#[derive(Debug)]
pub(super) enum Source {
    /// A system file or a scenario file (JSON), told apart when parsed.
    Json(String),
    /// An SSP archive extracted to this folder (deleted when dropped).
    Ssp(tempfile::TempDir),
}

/// Reads `file`: an `.ssp` archive is extracted (within [`SystemFiles::limits`]), any other file
/// is read as JSON text.
pub(super) fn read(file: &Path, files: &SystemFiles) -> Result<Source, SystemError> {
    if ssp::is_ssp(file) {
        return ssp::extract(file, files.limits()).map(Source::Ssp);
    }
    let text = read_system_text(file).map_err(|source| SystemError::Read { file: file.to_path_buf(), source })?;
    Ok(Source::Json(text))
}

/// Opens the `.fmu` file of a single-FMU run (extraction and model description only).
pub(super) fn read_fmu(file: &Path, files: &SystemFiles) -> Result<Fmu, SystemError> {
    Ok(files.fmu(file)?)
}

/// A system or scenario file's text: a regular file of at most [`MAX_TEXT_FILE_BYTES`], in UTF-8.
pub(super) fn read_system_text(file: &Path) -> std::io::Result<String> {
    read_regular_text(file, MAX_TEXT_FILE_BYTES)
}
