//! The FMI 2.0 layer: the C entry points ([`api`], expanded by `export`'s half of
//! [`crate::export_fmu!`]) and the model description ([`xml`]), over the instance core, state
//! machine and variable tables FMI 3.0 shares (see [`crate::fmi3`] for what that version adds).

pub mod api;
mod export;
pub mod xml;
