//! Python's words for the settings the libraries' messages name: each setting is the keyword
//! argument that sets it (`Setting::Start("x")` → `start={"x": …}`), and errors are raised as
//! `SimulationError` in those words.

use crane_app::{Setting, Wording};
use pyo3::PyErr;

use crate::SimulationError;

/// The package's wording of settings: its keyword arguments.
pub struct Keywords;

impl Wording for Keywords {
    fn word(&self, setting: &Setting) -> String {
        match setting {
            Setting::Start(name) => format!("start={{\"{name}\": …}}"),
            Setting::Record(pattern) => format!("record=[\"{pattern}\"]"),
            Setting::Input(file) => format!("inputs=[\"{file}\"]"),
            Setting::Tests(selection) => format!("tests=\"{selection}\""),
            Setting::StopTime => "stop_time".into(),
            Setting::StepSize => "step_size".into(),
            Setting::RecordInterval => "record_interval".into(),
            Setting::Force => "force=True".into(),
            // The package opens archives within the default limits; only the command line
            // raises them.
            Setting::MaxUnpackedBytes => "crane-cosim's --max-unpacked-size".into(),
            Setting::MaxEntries => "crane-cosim's --max-archive-entries".into(),
            Setting::MaxRatio => "crane-cosim's --max-compression-ratio".into(),
            Setting::MaxCases => "max_cases".into(),
            Setting::CampaignSystem => "system".into(),
            Setting::StartFile => "start_file".into(),
            Setting::Check => "check".into(),
            Setting::Crane => "crane".into(),
            Setting::FullScale => "full_scale=True".into(),
        }
    }
}

/// A `SimulationError` of a library message, its settings in the package's words.
pub fn error(message: impl AsRef<str>) -> PyErr {
    SimulationError::new_err(crane_app::reword(message.as_ref(), &Keywords))
}

/// A `SimulationError` of a library error with its whole chain on one line.
pub fn chained(error: &(dyn std::error::Error + 'static)) -> PyErr {
    self::error(fmu_import::error_chain(error))
}
