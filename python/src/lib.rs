//! `crane_cosim._native`: the extension module under the `crane_cosim` Python package
//! (python/crane_cosim/__init__.py builds the DataFrame and holds the documented API). It is an
//! adapter onto the front door `crane-app`: each function reads its options into a request,
//! calls the use case with the interpreter's lock released, and words errors in the package's
//! keyword arguments ([`wording::Keywords`]).

use std::path::PathBuf;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

mod campaign;
mod names;
mod options;
mod simulation;
mod wording;

create_exception!(
    _native,
    SimulationError,
    PyException,
    "A run that could not be loaded or did not complete; the message is the one `crane-cosim run` prints, its settings named by the keyword arguments that set them."
);

/// The recorded run: (names, units, times, columns, warnings), the times and each column as
/// little-endian `f64` bytes (numpy reads them without a copy of the text in between).
pub(crate) type Native<'py> =
    (Vec<String>, Vec<Option<String>>, Bound<'py, PyBytes>, Vec<Bound<'py, PyBytes>>, Vec<String>);

pub(crate) fn le_bytes<'py>(py: Python<'py>, values: &[f64]) -> Bound<'py, PyBytes> {
    let bytes: Vec<u8> = values.iter().flat_map(|value| value.to_le_bytes()).collect();
    PyBytes::new(py, &bytes)
}

/// The recording and the notices shown before it as the extension returns them.
pub(crate) fn native<'py>(py: Python<'py>, recording: crane_app::run::Recording, notices: Vec<String>) -> Native<'py> {
    let columns = recording.columns.iter().map(|column| le_bytes(py, column)).collect();
    (recording.names, recording.units, le_bytes(py, &recording.times), columns, notices)
}

/// Runs a system, scenario, SSP archive, OSP structure or one FMU with `run`'s options
/// ([`options::RunOptions`]). The interpreter's lock is released while the file is loaded and run.
#[pyfunction]
fn run<'py>(py: Python<'py>, system: PathBuf, options: options::RunOptions) -> PyResult<Native<'py>> {
    let request = options.request(system)?;
    let (recording, notices) = py
        .detach(|| {
            let loaded = crane_app::run::load(&request);
            let notices: Vec<String> = loaded.notices().iter().map(ToString::to_string).collect();
            loaded.to_table().map(|recording| (recording, notices))
        })
        .map_err(|e| wording::chained(&e))?;
    Ok(native(py, recording, notices))
}

#[pymodule]
fn _native(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add("SimulationError", module.py().get_type::<SimulationError>())?;
    module.add_function(wrap_pyfunction!(run, module)?)?;
    module.add_class::<simulation::Simulation>()?;
    module.add_class::<simulation::SavedState>()?;
    module.add_function(wrap_pyfunction!(campaign::campaign_run, module)?)?;
    module.add_function(wrap_pyfunction!(campaign::campaign, module)?)?;
    module.add_function(wrap_pyfunction!(campaign::sweep, module)?)?;
    module.add_function(wrap_pyfunction!(campaign::tune, module)?)?;
    module.add_function(wrap_pyfunction!(names::crane_names, module)?)?;
    Ok(())
}
