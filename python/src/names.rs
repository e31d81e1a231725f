//! The crane systems' vocabulary for Python: each scale's instance and variable names, so that
//! the package's code names no `instance.variable` itself.

use ::crane_names::Scale;
use pyo3::prelude::*;

use crate::wording::error;

/// The names of `scale`'s closed loop ("test" or "full") as JSON: each field of
/// `CraneNames` of the crate crane-names, a triple as `{"prefix", "axes"}`, a name the scale lacks as null.
#[pyfunction]
pub fn crane_names(scale: &str) -> PyResult<String> {
    let scale = Scale::ALL
        .into_iter()
        .find(|s| s.key() == scale)
        .ok_or_else(|| error(format!("scale {scale:?}: expected \"test\" or \"full\"")))?;
    serde_json::to_string(scale.names()).map_err(|e| error(e.to_string()))
}
