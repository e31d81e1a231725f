//! A study's files: the text of the study, scenario, manifest and case files read defensively,
//! and every output written atomically (a temporary file beside it, then a rename), so that
//! jobs sharing an output folder never see a half-written file.

use fmu_import::file::{read_regular_text, MAX_TEXT_FILE_BYTES};

use crate::StudyError;

/// The text of a study, scenario, manifest or case file: a regular file (a FIFO or a device such
/// as `/dev/zero` is refused from its metadata, before it could block or fill memory) of at most
/// [`MAX_TEXT_FILE_BYTES`], in UTF-8, as system files are read.
pub(crate) fn read_text(file: &std::path::Path) -> Result<String, StudyError> {
    read_regular_text(file, MAX_TEXT_FILE_BYTES).map_err(|source| StudyError::Read { file: file.to_path_buf(), source })
}

/// Writes `value` as pretty JSON and a newline to `file`, streamed through a buffer into a
/// temporary file renamed over `file` (as [`write_bytes_atomically`]), so that a manifest of
/// millions of cases is never held whole in memory.
pub(crate) fn write_json_atomically(file: &std::path::Path, value: &impl serde::Serialize) -> Result<(), StudyError> {
    use std::io::Write;
    let error = |source| StudyError::Write { file: file.to_path_buf(), source };
    let folder = file.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(std::path::Path::new("."));
    let temporary = tempfile::NamedTempFile::new_in(folder).map_err(error)?;
    let mut writer = std::io::BufWriter::new(temporary);
    serde_json::to_writer_pretty(&mut writer, value).map_err(|e| error(e.into()))?;
    writer.write_all(b"\n").map_err(error)?;
    let temporary = writer.into_inner().map_err(|e| error(e.into_error()))?;
    temporary.persist(file).map_err(|e| error(e.error))?;
    Ok(())
}

/// Writes `text` to `file` through [`write_bytes_atomically`].
pub(crate) fn write_atomically(file: &std::path::Path, text: &str) -> Result<(), StudyError> {
    write_bytes_atomically(file, text.as_bytes())
}

/// Writes `bytes` to `file` through a temporary file beside it and a rename, so that a reader
/// (another shard, a collect) never sees a half-written file. `tempfile` names the temporary
/// file at random and creates it exclusively, so jobs on different machines sharing the folder
/// (containers, where every job may have the same process id) never write the same one; one
/// that fails is deleted.
pub(crate) fn write_bytes_atomically(file: &std::path::Path, bytes: &[u8]) -> Result<(), StudyError> {
    persist_atomically(file, bytes).map_err(|source| StudyError::Write { file: file.to_path_buf(), source })
}

/// The I/O of `write_bytes_atomically`, also the tuning's output files'.
pub use cosim_engine::partial::persist_atomically;
