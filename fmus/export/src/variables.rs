//! The variable table, from the version-neutral `fmu-model` crate; this crate maps it to FMI 2.0
//! (its C getters and setters in [`crate::instance`], its XML in [`crate::xml`]).

pub use fmu_model::variables::*;
