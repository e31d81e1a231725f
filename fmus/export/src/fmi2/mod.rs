//! The FMI 2.0 layer: the C entry points ([`api`]) and the model description ([`xml`]).

pub mod api;
pub mod xml;
