//! `crane_cosim._native`: the extension module under the `crane_cosim` Python package
//! (python/crane_cosim/__init__.py builds the DataFrame and holds the documented API).

use std::path::PathBuf;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

// The command line's own translation of the libraries' setting names into its options
// (`Overrides::start["x"]` → `--start x`), so that an error reads as `crane-cosim run` prints it.
mod campaign;
#[path = "../../cosim/cli/src/flags.rs"]
mod flags;
mod simulate;
mod simulation;

create_exception!(
    _native,
    SimulationError,
    PyException,
    "A run that could not be loaded or did not complete; the message is the one `crane-cosim run` prints."
);

/// The recorded run: (names, units, times, columns, warnings), the times and each column as
/// little-endian `f64` bytes (numpy reads them without a copy of the text in between).
pub(crate) type Native<'py> =
    (Vec<String>, Vec<Option<String>>, Bound<'py, PyBytes>, Vec<Bound<'py, PyBytes>>, Vec<String>);

pub(crate) fn le_bytes<'py>(py: Python<'py>, values: &[f64]) -> Bound<'py, PyBytes> {
    let bytes: Vec<u8> = values.iter().flat_map(|value| value.to_le_bytes()).collect();
    PyBytes::new(py, &bytes)
}

/// Runs a system, scenario, SSP archive, OSP structure or one FMU with the options of `run`
/// ([`Options`]). The interpreter's lock is released while the file is loaded and run.
#[pyfunction]
fn run<'py>(py: Python<'py>, system: PathBuf, options: Options) -> PyResult<Native<'py>> {
    let request = options.request(system)?;
    let results = py
        .detach(|| simulate::run(&request))
        .map_err(|message| SimulationError::new_err(flags::name_flags(&message)))?;
    let columns = results.columns.iter().map(|column| le_bytes(py, column)).collect();
    Ok((results.names, results.units, le_bytes(py, &results.times), columns, results.warnings))
}

/// The options `run` and `Simulation` take after the system, as the package's `_options` packs
/// them into one tuple: start values as `(name, JSON text)`, stop time, step size, recording
/// interval, algorithm, record patterns, input files, force.
#[derive(FromPyObject)]
pub(crate) struct Options(
    Vec<(String, String)>,
    Option<f64>,
    Option<f64>,
    Option<f64>,
    Option<String>,
    Vec<String>,
    Vec<PathBuf>,
    bool,
);

impl Options {
    /// The run these options ask for on `system`, its start values parsed.
    pub(crate) fn request(self, system: PathBuf) -> PyResult<simulate::Request> {
        let Self(start, stop_time, step_size, record_interval, algorithm, record, inputs, force) = self;
        let start = start_values(start)?;
        Ok(simulate::Request { system, start, stop_time, step_size, record_interval, algorithm, record, inputs, force })
    }
}

/// Start values given as `(name, JSON text)`, parsed.
pub(crate) fn start_values(start: Vec<(String, String)>) -> PyResult<Vec<(String, serde_json::Value)>> {
    start
        .into_iter()
        .map(|(name, json)| {
            serde_json::from_str(&json)
                .map(|value| (name.clone(), value))
                .map_err(|e| SimulationError::new_err(format!("start value of {name}: {e}")))
        })
        .collect()
}

#[pymodule]
fn _native(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add("SimulationError", module.py().get_type::<SimulationError>())?;
    module.add_function(wrap_pyfunction!(run, module)?)?;
    module.add_class::<simulation::Simulation>()?;
    module.add_function(wrap_pyfunction!(campaign::campaign_run, module)?)?;
    module.add_function(wrap_pyfunction!(campaign::campaign, module)?)?;
    module.add_function(wrap_pyfunction!(campaign::sweep, module)?)?;
    module.add_class::<simulation::SavedState>()?;
    Ok(())
}
