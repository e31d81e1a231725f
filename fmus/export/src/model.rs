//! The model trait, from the version-neutral `fmu-model` crate: this crate exports any
//! [`Model`] as an FMI 2.0 and an FMI 3.0 Co-Simulation FMU.

pub use fmu_model::{Environment, Model, ModelInfo};
