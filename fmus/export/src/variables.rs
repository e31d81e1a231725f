//! The variable table, from the version-neutral `fmu-model` crate; this crate maps it to FMI 2.0
//! and FMI 3.0 (its getters and setters in [`crate::instance`], its XML in [`crate::fmi2::xml`]
//! and [`crate::fmi3::xml`]).

pub use fmu_model::variables::*;
